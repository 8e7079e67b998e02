"""The simulator's whole input domain, as properties: launches from anywhere around each scene,
at any speed up to the documented limit, in both scenes, with every integrator and both
contact models. Each throw returns within its bounded number of pieces and of simulated
seconds, no ball passes through a net wall, and the fast path's outcome is the full
simulation's, unless that outcome is itself decided by a hair (it flips under a launch
velocity nudged by one part in a million). Through a wall: the ball's centre inside the net's
closed surface (its faces as they are now, the opening closing it) before the ball entered
through the opening, checked after every request of both simulations.

The default (CI) run draws a few derandomized examples for each scene and configuration; the
long run, before a change to the fast path is called done (docs/CONTRIBUTING.md)::

    HYPOTHESIS_PROFILE=domain python -m pytest -m slow tests/physics/test_throw_domain.py --hypothesis-show-statistics

draws :data:`LONG_EXAMPLES` per scene and configuration (100, or ``NETGYM_DOMAIN_EXAMPLES``;
1,400 in all). The goal's
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

LONG_EXAMPLES = int(os.environ.get("NETGYM_DOMAIN_EXAMPLES", "100"))
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
MESH_GIVES_WAY = {"goal"}
"""Scenes where a fast ball is known to push its centre through a stretched mesh cell, counted
(``--hypothesis-show-statistics``) but not asserted: on the goal (0.125 m mesh, a ball of radius
0.095 m) a 23 m/s throw into the side net by the post, within NetCatchGoal-v0's 8-25 m/s, came to
rest with its centre 5-9 cm past the corners of a cell stretched to 0.15 m, held from the inside
(found by this property on 2026-12-07; ball/net contacts act on particles and edges, not cells)."""
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
    speed = draw(st.floats(1.0, MAX_LAUNCH_SPEED * (1.0 - 4.0 * NUDGE)))  # nudged and rounded, still allowed
    direction = target - position
    return position, speed * direction / np.linalg.norm(direction)


def _closed_surface(sim: Simulator) -> tuple[np.ndarray, np.ndarray]:
    """The net's box as a closed surface of triangles: each cell of the five net faces (particle
    indices into the state, two triangles a cell) and the opening (its four corner particles,
    two triangles): ``(net_triangles (k, 3), cap_corners (4,))``."""
    geometry = sim.model.geometry
    lattice, top = geometry.lattice, geometry.lattice.max(axis=0)
    index = {tuple(point): k for k, point in enumerate(lattice)}
    opening = sim.opening
    triangles = []
    for axis in range(3):
        u, w = [a for a in range(3) if a != axis]
        for side in (0, 1):
            if axis == opening.axis and (side == 1) == (opening.sign > 0):
                continue  # the open face: the cap below closes it
            for i in range(top[u]):
                for j in range(top[w]):
                    cell = []
                    for di, dj in ((0, 0), (1, 0), (1, 1), (0, 1)):
                        point = [0, 0, 0]
                        point[axis], point[u], point[w] = side * top[axis], i + di, j + dj
                        cell.append(index[tuple(point)])
                    triangles += [(cell[0], cell[1], cell[2]), (cell[0], cell[2], cell[3])]
    u, w = [a for a in range(3) if a != opening.axis]
    side = top[opening.axis] if opening.sign > 0 else 0
    corners = []
    for i, j in ((0, 0), (1, 0), (1, 1), (0, 1)):
        point = [0, 0, 0]
        point[opening.axis], point[u], point[w] = side, i * top[u], j * top[w]
        corners.append(index[tuple(point)])
    return np.array(triangles), np.array(corners)


def _crossings(origin: np.ndarray, direction: np.ndarray, a: np.ndarray, b: np.ndarray, c: np.ndarray) -> int:
    """How many of the triangles (a, b, c) (rows) the ray from ``origin`` along ``direction``
    crosses (Moller-Trumbore)."""
    e1, e2 = b - a, c - a
    h = np.cross(direction, e2)
    det = np.einsum("ij,ij->i", e1, h)
    ok = np.abs(det) > 1e-14
    inv = np.where(ok, 1.0 / np.where(ok, det, 1.0), 0.0)
    s = origin - a
    bu = inv * np.einsum("ij,ij->i", s, h)
    q = np.cross(s, e1)
    bv = inv * (q @ direction)
    distance = inv * np.einsum("ij,ij->i", e2, q)
    return int(np.count_nonzero(ok & (bu >= 0.0) & (bv >= 0.0) & (bu + bv <= 1.0) & (distance > 0.0)))


def _inside(sim: Simulator, surface: tuple[np.ndarray, np.ndarray], point: np.ndarray) -> bool:
    """Whether ``point`` lies inside the closed surface of the net's box as the net is now (its
    faces deformed as they are, the opening closing it): an odd number of crossings of a ray cast
    from it away from the opening (into the box's back), tilted a little off the axes."""
    x, (triangles, corners) = sim.state.x, surface
    direction = np.array([0.0123, 0.0371, 0.0257])  # a little off every axis: no ray along a shared edge
    direction[sim.opening.axis] = -sim.opening.sign
    cap = x[corners]
    hits = _crossings(point, direction, x[triangles[:, 0]], x[triangles[:, 1]], x[triangles[:, 2]])
    hits += _crossings(point, direction, cap[[0, 0]], cap[[1, 2]], cap[[2, 3]])
    return hits % 2 == 1


class Watcher:
    """A plan observer: counts the requests of a throw and notes whether its ball's centre was
    ever inside the net's box (its closed surface as the net is now) before the ball had entered
    through the opening: through a wall."""

    def __init__(self, sim: Simulator) -> None:
        self.row, self.surface = sim.model.n_net, _closed_surface(sim)
        self.requests, self.through_a_wall = 0, False

    def __call__(self, sim: Simulator) -> None:
        self.requests += 1
        if sim.n_balls and not sim.state.entered[-1] and _inside(sim, self.surface, sim.state.x[self.row]):
            self.through_a_wall = True


def _throw(sim: Simulator, position: np.ndarray, velocity: np.ndarray, fast: bool) -> tuple[ThrowResult, Watcher]:
    sim.reset()
    watcher = Watcher(sim)
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
        if scene in MESH_GIVES_WAY:
            event(f"ball centre through a mesh cell (fast={fast})" if watcher.through_a_wall else "walls held")
        else:
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
