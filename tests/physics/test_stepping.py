"""The stepping kernels (``netgym/physics/stepping.py``): a ball's flight between contacts, the
substeps a fast ball takes, and the ``entered`` flags kept by :func:`stepping.update_entered`
as balls cross the opening, each against its closed form."""

from __future__ import annotations

import numpy as np
import pytest

from netgym.config import load_scene
from netgym.physics import stepping
from netgym.physics.model.model import Model
from netgym.physics.simulator import Simulator


def test_a_ball_far_from_the_net_flies_the_exact_parabola(basket: Simulator) -> None:
    """Without air, between contacts a ball moves on x0 + v0 t + g t^2 / 2 whatever the
    integrator: no time-discretisation error over 300 steps."""
    assert basket.model.ball_drag == 0.0
    x0, v0 = np.array([5.0, 5.0, 2.0]), np.array([1.0, 2.0, 8.0])
    basket.launch_ball(x0, v0)
    start = basket.state.time
    basket.step(300)
    t = basket.state.time - start
    gravity = np.array([0.0, 0.0, basket.model.gravity])
    assert t == pytest.approx(300 * basket.dt, rel=1e-12)
    assert np.allclose(basket.ball_positions[0], x0 + v0 * t + 0.5 * gravity * t ** 2, rtol=0.0, atol=1e-12)
    assert np.allclose(basket.state.v[basket.model.n_net], v0 + gravity * t, rtol=0.0, atol=1e-12)


@pytest.mark.parametrize(("particle", "particle_speed", "expected"), [
    ([0.0, 0.0, 0.0], 0.0, 3),     # alone: 100 m/s * 2 ms / 7.5 cm = 2.67
    ([5.0, 0.5, 0.0], 40.0, 4),    # a particle within reach closing at 40 m/s more: 3.73
    ([8.0, 0.0, 0.0], 40.0, 3),    # the same particle out of reach within the step: 2.67
    ([5.0, 0.5, 0.0], -40.0, 4),   # speeds, not velocities: the direction is not looked at
])
def test_a_fast_ball_takes_enough_substeps_to_move_at_most_its_travel_relative_to_the_net(
        particle: list[float], particle_speed: float, expected: int) -> None:
    """Substeps = ceil((ball speed + speed of the fastest particle that could reach it within
    the step) * dt / travel); a particle can reach it when it lies within radius + (both
    speeds) * dt of it along every axis (0.3 m + 0.28 m here)."""
    x = np.array([particle, [5.0, 0.0, 0.0]])
    v = np.array([[particle_speed, 0.0, 0.0], [0.0, 100.0, 0.0]])
    substeps = stepping._substeps(x, v, 1, 0.3, 0.002, 0.075, np.empty(1))
    assert substeps == expected


def test_a_slow_ball_takes_one_substep() -> None:
    x = np.array([[5.0, 0.1, 0.0], [5.0, 0.0, 0.0]])
    v = np.array([[10.0, 0.0, 0.0], [0.0, 20.0, 0.0]])  # (10 + 20) m/s * 2 ms = 6 cm < 7.5 cm
    assert stepping._substeps(x, v, 1, 0.3, 0.002, 0.075, np.empty(1)) == 1


@pytest.mark.parametrize("scene", ["basket", "goal"])
def test_a_balls_entered_flag_follows_its_crossings_of_the_opening(scene: str) -> None:
    """Set when the centre crosses the opening's plane inwards inside the rectangle (where the
    move meets the plane, wherever it starts and ends), cleared when it crosses outwards inside
    it, left as it was by a crossing outside the rectangle or a move that does not cross."""
    model = Model.from_config(load_scene(scene))
    opening = model.opening
    u = opening.tangent_axes[0]
    edge = opening.tangent_upper[0]

    def point(depth: float, along_u: float) -> np.ndarray:
        """A point ``depth`` past the plane on the inner side, at ``along_u`` on the first tangent axis."""
        p = opening.centre
        p[opening.axis] = opening.plane - opening.sign * depth
        p[u] = along_u
        return p

    centre = opening.centre[u]
    moves = [  # (before, after, flag before, flag after)
        (point(-0.1, centre), point(0.1, centre), 0, 1),                # in through the middle
        (point(0.1, centre), point(-0.1, centre), 1, 0),                # out through the middle
        (point(-0.1, edge + 0.1), point(0.1, edge - 0.3), 0, 1),        # starts beside it, crosses inside
        (point(-0.1, edge + 0.3), point(0.1, edge - 0.1), 0, 0),        # ends inside, crossed beside it
        (point(0.1, edge + 0.3), point(-0.1, edge - 0.1), 1, 1),        # out, beside it
        (point(-0.2, centre), point(-0.1, centre), 1, 1),               # no crossing
        (point(0.1, centre), point(0.3, centre), 0, 0),                 # no crossing, inside
    ]
    before = np.array([m[0] for m in moves])
    after = np.array([m[1] for m in moves])
    entered = np.array([m[2] for m in moves], dtype=np.int8)
    stepping.update_entered(after, before, 0, entered, model.kernel.opening)
    assert entered.tolist() == [m[3] for m in moves]
