"""The plan driver (``netgym/physics/plans.py``): what :func:`drive` does with each request of a
plan, that it hands back the plan's result, and how it throws a divergence into the plan."""

from __future__ import annotations

import numpy as np
import pytest

from netgym.errors import SimulationDivergedError
from netgym.kinds import Integrator
from netgym.physics.plans import Integrate, Plan, Tick, drive
from netgym.physics.simulator import Simulator


def snapshot(sim: Simulator) -> tuple[float, np.ndarray, int]:
    """(time, positions, substeps so far) of ``sim``."""
    return sim.state.time, sim.state.x.copy(), sim.substeps


def single(request: Integrate) -> Plan:
    """A plan of one request."""
    yield request


def diverging(sim: Simulator) -> Integrate:
    """A request that diverges: explicit Euler at 60 times its stability limit on the net."""
    return Integrate(200, Integrator.EXPLICIT_EULER, 60 * sim.stable_dt)


def test_drive_integrates_each_integrate_request_observes_each_tick_and_returns_the_result(
        basket: Simulator) -> None:
    """Integrate(n) advances the state n steps of dt (one substep each: no balls); Tick
    integrates nothing; the observer sees the simulator after every request; the plan's return
    value is drive's."""
    dt, code = basket.dt, basket.integrator
    start = snapshot(basket)
    seen = []

    def plan() -> Plan:
        yield Integrate(5, code, dt)
        yield Tick()
        yield Integrate(3, code, dt)
        return "the plan's result"

    assert drive(basket, plan(), basket.workspace, observer=lambda s: seen.append(snapshot(s))) == "the plan's result"
    assert [time for time, _, _ in seen] == [start[0] + 5 * dt, start[0] + 5 * dt, start[0] + 5 * dt + 3 * dt]
    assert [substeps - start[2] for _, _, substeps in seen] == [5, 5, 8]
    assert np.array_equal(seen[0][1], seen[1][1])  # the tick moved nothing
    whole = Simulator("basket")
    drive(whole, single(Integrate(8, code, dt)), whole.workspace)
    assert np.array_equal(whole.state.x, basket.state.x)  # 5 + 3 steps are 8 steps
    assert not np.array_equal(whole.state.x, start[1])


def test_a_divergence_is_thrown_into_the_plan_with_the_state_restored(basket: Simulator) -> None:
    basket.launch_ball([0.0, 0.0, 2.0], [0.0, 0.0, 0.0])
    start = snapshot(basket)
    seen = []

    def plan() -> Plan:
        try:
            yield diverging(basket)
        except SimulationDivergedError as error:
            return error
        return None

    caught = drive(basket, plan(), basket.workspace, observer=lambda s: seen.append(snapshot(s)))
    assert isinstance(caught, SimulationDivergedError) and "explicit_euler" in str(caught)
    assert seen == []  # a failed request is not observed
    assert basket.state.time == start[0] and np.array_equal(basket.state.x, start[1])


def test_a_divergence_the_plan_does_not_catch_leaves_drive(basket: Simulator) -> None:
    basket.launch_ball([0.0, 0.0, 2.0], [0.0, 0.0, 0.0])
    with pytest.raises(SimulationDivergedError, match="explicit_euler at dt"):
        drive(basket, single(diverging(basket)), basket.workspace)
