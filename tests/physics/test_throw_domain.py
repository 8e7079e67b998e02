"""The simulator's whole input domain, as properties: launches from anywhere around each scene,
at any speed up to the documented limit, in both scenes, with every integrator and both
contact models. Each throw returns within its bounded number of pieces and of simulated
seconds, no ball passes through a net wall, and the fast path's outcome is the full
simulation's, unless that outcome is itself decided by a hair (it flips under a launch
velocity nudged by one part in a million).

The default (CI) run draws a few derandomized examples for each scene and configuration; the
long run, before a change to the fast path is called done (docs/CONTRIBUTING.md)::

    HYPOTHESIS_PROFILE=domain python -m pytest tests/physics/test_throw_domain.py --hypothesis-show-statistics

draws :data:`LONG_EXAMPLES` per scene and configuration (thousands in all). The goal's
compliant cases are marked as known defects (:data:`GOAL_COMPLIANT`) and not run.
"""

from __future__ import annotations

import math
import os

import numpy as np
import pytest
from hypothesis import HealthCheck, event, given, settings
from hypothesis import strategies as st

from netgym.physics.progress_guard import ProgressGuard
from netgym.physics.simulator import MAX_LAUNCH_SPEED, Simulator
from netgym.physics.throw import ThrowResult, throw

LONG_EXAMPLES = 200
LONG = os.environ.get("HYPOTHESIS_PROFILE") == "domain"
EXAMPLES = LONG_EXAMPLES if LONG else 2
NUDGE = 1e-6  # relative change of the launch velocity that shows a throw decided by a hair

# (contact model, integrator, dt or None for the scene's own): every integrator with each contact
# model that has a step for it (compliant contacts have none for implicit Euler), at a stable dt
CONFIGURATIONS = [
    ("impulse", "imex_euler", None),
    ("impulse", "implicit_euler", 2e-3),
    ("impulse", "symplectic_euler", 5e-4),
    ("impulse", "explicit_euler", 5e-4),
    ("impulse", "rk4", 5e-4),
    ("compliant", "imex_euler", 1e-3),
    ("compliant", "symplectic_euler", 5e-4),
    ("compliant", "explicit_euler", 5e-4),
    ("compliant", "rk4", 5e-4),
]
SCENES = ("basket", "goal")
GOAL_COMPLIANT = pytest.mark.xfail(reason=(
    "known defects this property found (2026-12-07): on the goal, whose bottom net lies on the ground, compliant "
    "contacts let a 15 m/s ball through the side net (IMEX Euler, 1 ms), and the explicit integrators diverge "
    "on the grounded net within their springs' stability limit (the contact's penalty and regularised friction "
    "are stiffer than the springs and are left out of that limit); not run: a minute or more an example"),
    strict=False, run=False)
CASES = [pytest.param(scene, configuration, id=f"{scene}-" + "-".join(str(p) for p in configuration if p),
                      marks=GOAL_COMPLIANT if (scene, configuration[0]) == ("goal", "compliant") else ())
         for scene in SCENES for configuration in CONFIGURATIONS]
_SIMS: dict[tuple, Simulator] = {}


def _sim(scene: str, configuration: tuple) -> Simulator:
    """One simulator per scene and configuration, reset before each use."""
    key = (scene, *configuration)
    if key not in _SIMS:
        contact_model, integrator, dt = configuration
        overrides = {"simulation.contact_model": contact_model, "simulation.integrator": integrator}
        _SIMS[key] = Simulator(scene, overrides if dt is None else {**overrides, "simulation.dt": dt})
    _SIMS[key].reset()
    return _SIMS[key]


@st.composite
def launches(draw: st.DrawFn, scene: str) -> tuple[np.ndarray, np.ndarray]:
    """A release 2-6 m from the z axis (through the basket's opening and the goal mouth's centre),
    at 0.5-3.5 m (anywhere around the basket; in front of the goal's mouth or beside it), aimed at a point of the net's box,
    at up to the documented launch speed limit."""
    distance = draw(st.floats(2.0, 6.0))
    bearing = draw(st.floats(0.0, 2.0 * math.pi) if scene == "basket" else st.floats(0.5 * math.pi, 1.5 * math.pi))
    height = draw(st.floats(0.5, 3.5))
    position = np.array([distance * math.cos(bearing), distance * math.sin(bearing), height])
    lower, upper = ((-1.0, -1.0, 0.5), (1.0, 1.0, 3.0)) if scene == "basket" else ((0.0, -1.5, 0.0), (1.0, 1.5, 2.0))
    target = np.array([draw(st.floats(lo, hi)) for lo, hi in zip(lower, upper)])
    speed = draw(st.floats(1.0, MAX_LAUNCH_SPEED))
    direction = target - position
    return position, speed * direction / np.linalg.norm(direction)


def _deep_inside(sim: Simulator, ball: np.ndarray) -> bool:
    """The ball's centre lies more than its radius inside the net's box, each wall taken where it
    is now (the mean of the four particles of that face nearest the ball across it), and more than
    its radius past the opening's plane: where only the opening leads."""
    m, x, r = sim.model, sim.state.x, sim.model.ball_radius
    lattice, top = m.geometry.lattice, m.geometry.lattice.max(axis=0)
    opening = sim.opening
    if opening.depth(ball) <= r:
        return False
    for axis in range(3):
        across = [a for a in range(3) if a != axis]
        for side in (0, 1):
            face = np.flatnonzero(lattice[:, axis] == (top[axis] if side else 0))
            if axis == opening.axis and (side == 1) == (opening.sign > 0):
                continue  # the open face
            gaps = np.linalg.norm(x[face][:, across] - ball[across], axis=1)
            wall = x[face[np.argsort(gaps)[:4]], axis].mean()
            if (ball[axis] - wall) * (1.0 if side else -1.0) > -r:
                return False
    return True


class Watcher:
    """A plan observer: counts the requests of a throw and notes whether its ball was ever deep
    inside the net's box before it had entered through the opening (through a wall)."""

    def __init__(self, row: int) -> None:
        self.row, self.requests, self.through_a_wall = row, 0, False

    def __call__(self, sim: Simulator) -> None:
        self.requests += 1
        if sim.n_balls and not sim.state.entered[-1] and _deep_inside(sim, sim.state.x[self.row]):
            self.through_a_wall = True


def _throw(sim: Simulator, position: np.ndarray, velocity: np.ndarray, fast: bool) -> tuple[ThrowResult, Watcher]:
    sim.reset()
    watcher = Watcher(sim.model.n_net)
    return throw(sim, position, velocity, fast=fast, observer=watcher), watcher


@pytest.mark.slow
@pytest.mark.parametrize(("scene", "configuration"), CASES)
@settings(max_examples=EXAMPLES, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(data=st.data())
def test_every_throw_returns_stays_outside_the_walls_and_the_fast_path_agrees(scene: str, configuration: tuple,
                                                                              data: st.DataObject) -> None:
    sim = _sim(scene, configuration)
    position, velocity = data.draw(launches(scene))
    cfg = sim.config.simulation
    most = ProgressGuard.bound(0.0, cfg.time_limit, cfg.dt)
    results = {}
    for fast in (True, False):
        result, watcher = _throw(sim, position, velocity, fast)
        assert watcher.requests <= most, f"{watcher.requests} requests, more than the guard's bound {most}"
        assert 0.0 <= result.time <= cfg.time_limit + 0.5 * cfg.dt
        assert not watcher.through_a_wall, f"the ball went into the net's box through a wall (fast={fast})"
        assert np.all(np.isfinite(result.final_position))
        results[fast] = result
    event(f"reason {results[True].reason}")
    if results[True].captured != results[False].captured:
        nudged = [_throw(sim, position, velocity * (1.0 + sign * NUDGE), False)[0].captured for sign in (-1.0, 1.0)]
        assert results[True].captured in nudged, (
            f"the fast path says captured={results[True].captured}, the full simulation and its nudged launches "
            f"{results[False].captured}, {nudged}")
        event("fast path and full simulation differ on a throw decided by a hair")
