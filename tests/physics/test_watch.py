"""The throw's compiled loops change nothing: integrating chunk after chunk in one kernel call
(watch.integrate_watched; watch.roll_watched for the ball alone) and flying the approach's pieces
in one (approach.approach, and approach.approach_through_air through air) give,
bit for bit, the throws that decide after every chunk and fly every piece in Python; and the
rest window keeps what the rest test needs."""

from __future__ import annotations

import numpy as np
import pytest

from netgym.bench.throws import sample_throws
from netgym.physics.fast_path import approach
from netgym.physics.throw import recipe
from netgym.physics.plans import Integrate
from netgym.physics.simulator import Simulator
from netgym.physics.fast_path.watch import RestWindow, at_rest, remember
from netgym.physics.throw import throw


def _throw_all(sim: Simulator, launches) -> list[tuple]:
    """Every launch thrown in turn into ``sim`` (balls kept as the scene keeps them): each
    result's fields (the work done among them) and the state after it."""
    outcomes = []
    for position, velocity in launches:
        r = throw(sim, position, velocity)
        s = sim.state
        outcomes.append((r.captured, r.entered, r.reason, r.time, r.substeps, r.settle_substeps,
                         r.final_position.tobytes(), r.final_velocity.tobytes(), s.x.tobytes(), s.v.tobytes(),
                         s.time, sim.awake))
    return outcomes


SPECIAL = {  # throws decided on the net, on the ground, flying off the rim, landing on a ball, at rest on a roof
    "basket": [([5.0, 0.0, 1.8], [-5.0, 0.0, 6.1]), ([0.0, 5.0, 1.8], [0.0, -5.0, 6.1]),
               ([0.113, 3.237, 1.652], [0.02, -1.452, 8.234]), ([-3.81, -2.29, 1.78], [3.6, 1.1, 1.55])],
    "goal": [([0.43, -0.56, 2.3], [0.0, 0.0, 0.0])],
}


WINDY = {"air.density": 1.2, "air.wind": [1.5, -1.0, 0.0]}
TIME = 7   # where the approach kernels take the time they start from


@pytest.mark.parametrize(("scene", "overrides", "flight"),
                         [("basket", None, "approach"), ("goal", None, "approach"),
                          ("goal", {"capture_rule": "held"}, "approach"), ("basket", WINDY, "approach_through_air")])
def test_the_compiled_loops_give_the_python_loops_throws_bit_for_bit(scene: str, overrides, flight: str,
                                                                      monkeypatch) -> None:
    """Under ``held`` the goal's roof holds a ball that comes to rest there while the loop runs;
    through air, the pieces are flown by ``approach_through_air``."""
    launches = SPECIAL[scene] + sample_throws(scene, 16, seed=11)
    calls = {"watched": 0, "pieces": 0, "alone": 0}
    kernel, fly = recipe.Watched, getattr(approach, flight)

    def watched(integrator, dt, watch, alone=False):
        calls["watched"] += 1
        calls["alone"] += alone
        return kernel(integrator, dt, watch, alone)

    def pieces(*args):
        time = fly(*args)
        calls["pieces"] += time != args[TIME]
        return time

    monkeypatch.setattr(recipe, "Watched", watched)
    monkeypatch.setattr(approach, flight, pieces)
    compiled = _throw_all(Simulator(scene, overrides), launches)
    assert calls["watched"] > 0 and calls["pieces"] > 0 and calls["alone"] > 0  # every loop took part

    sim = Simulator(scene, overrides)

    def one_chunk(integrator, dt, watch, alone=False):  # what a throw asked for before the watched loop
        return Integrate(min(watch.chunk, round((watch.deadline - sim.state.time) / dt)), integrator, dt,
                         watch.row if alone else -1)

    monkeypatch.setattr(recipe, "Watched", one_chunk)
    monkeypatch.setattr(approach, flight, lambda *args: args[TIME])  # no piece flown in the kernel
    assert _throw_all(sim, launches) == compiled


def _window(n_bodies: int = 2) -> RestWindow:
    return RestWindow.sized(n_bodies, dt=0.01, window=0.1, epsilon=1e-9, near=1.0, bound=0.01)


def test_the_rest_window_keeps_the_latest_check_at_least_a_window_old() -> None:
    rest, x = _window(), np.zeros((2, 3))
    for k in range(15):
        remember(rest, 0.01 * k, x)
    first, count = rest.ring
    kept = [rest.times[(first + j) % rest.times.shape[0]] for j in range(count)]
    assert np.allclose(kept, 0.01 * np.arange(4, 15))  # 0.04 is the latest at least 0.1 s before 0.14
    remember(rest, 0.14, x + 1.0)  # the same instant again: replaced, not added
    assert rest.ring[1] == count and rest.positions[(first + count - 1) % rest.times.shape[0]][0, 0] == 1.0


def test_at_rest_needs_the_whole_window_and_every_check_within_bound() -> None:
    rest, x = _window(), np.zeros((2, 3))
    for k in range(10):
        remember(rest, 0.01 * k, x)
    assert not at_rest(rest, x, 1, 0.09)  # the window is not covered yet
    remember(rest, 0.1, x)
    assert at_rest(rest, x, 1, 0.1)
    moved = x.copy()
    moved[0, 2] = 0.02  # a body near the ball moved more than the bound since the checks
    remember(rest, 0.11, moved)
    assert not at_rest(rest, moved, 1, 0.11)


def test_a_rest_window_checked_more_often_than_once_a_step_says_so() -> None:
    rest, x = _window(), np.zeros((2, 3))
    with pytest.raises(RuntimeError, match="more than once a step"):
        for k in range(rest.times.shape[0] + 1):
            remember(rest, 1e-4 * k, x)


def test_a_check_a_rounding_error_after_the_last_is_the_same_instant() -> None:
    """At implicit Euler's 10 ms a ball is flown to the step grid from a rounding error off it
    and checked again 4e-16 s after the last check, every other chunk: the rest window takes
    that check for the same instant (it filled up otherwise, and the throw stopped)."""
    position, velocity = sample_throws("basket", 90, seed=99)[89]
    sim = Simulator("basket", {"simulation.integrator": "implicit_euler", "simulation.dt": 0.01}, check_stability=False)
    result = throw(sim, position, velocity)
    assert result.captured and result.reason == "cannot_leave"
    rest = _window()
    remember(rest, 0.14, np.zeros((2, 3)))
    remember(rest, 0.14 + 4.4e-16, np.ones((2, 3)))
    assert rest.ring[1] == 1 and rest.positions[rest.ring[0]][0, 0] == 1.0
