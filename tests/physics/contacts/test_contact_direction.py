"""Bodies that start inside one another: the direction contacts push them apart along, and a
ball launched on the net decided alike by the fast path and the full simulation."""

from __future__ import annotations

import numpy as np
import pytest

from netgym.physics.simulator import Simulator
from netgym.physics.throw import throw


@pytest.mark.parametrize("position", [[1.0, 0.0, 1.8],    # centre on the +x wall
                                      [1.0, 1.0, 1.8],    # centre on a corner pole's axis
                                      [-1.0, 0.0, 2.2]])  # centre on the -x wall
def test_fast_path_and_full_simulation_agree_for_a_ball_launched_on_the_net(position: list[float]) -> None:
    sim = Simulator("basket")
    fast = throw(sim, position, [0.0, 0.0, 0.0])
    sim.reset()
    full = throw(sim, position, [0.0, 0.0, 0.0], fast=False)
    assert fast.substeps > 0  # decided only after the contacts acted
    assert fast.captured == full.captured


def test_coincident_centres_are_pushed_apart_along_a_defined_direction() -> None:
    balls = Simulator("basket")
    balls.launch_ball([3.0, 3.0, 1.0], [0.0, 0.0, 0.0])
    balls.launch_ball([3.0, 3.0, 1.0], [0.0, 0.0, 0.0])
    balls.step(1)
    lower, upper = balls.ball_positions
    assert upper[2] - lower[2] == pytest.approx(2 * balls.model.ball_radius, rel=1e-6)  # along +z
    assert np.allclose(upper[:2], lower[:2])
    pole = Simulator("basket")  # a ball centred on the axis of the vertical corner pole at x = y = 1
    pole.launch_ball([1.0, 1.0, 1.8], [0.0, 0.0, 0.0])
    pole.step(1)
    reach = pole.model.ball_radius + pole.config.net.pole_radius
    x, y, _ = pole.ball_positions[0]
    assert y >= 1.0 + reach - 1e-9 and x == pytest.approx(1.0, abs=1e-3)  # pushed off the axis along +y
