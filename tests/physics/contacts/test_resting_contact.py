"""Resting contact: a ball at rest on a net stays at rest, and slides only where the slope
beats friction (Coulomb's cone), at every integrator and dt up to the scene's default."""

from __future__ import annotations

import math

import numpy as np
import pytest

from netgym.physics import stepping
from netgym.physics.model.contact_tables import Materials, Poles
from netgym.physics.kernels.integrators import Scratch
from netgym.kinds import Contact, ContactModel, Integrator
from netgym.physics.model.model import KernelModel, Settings, index_segments
from netgym.physics.model.opening import Opening
from netgym.physics.simulator import Simulator
from netgym.physics.kernels.springs import Springs
from netgym.physics.throw import throw


@pytest.mark.parametrize(("integrator", "dt"), [("imex_euler", 5e-4), ("imex_euler", 1e-3), ("imex_euler", 2e-3),
                                                ("implicit_euler", 2e-3), ("symplectic_euler", 5e-4),
                                                ("rk4", 1e-3)])
def test_a_ball_settled_on_the_basket_bottom_stays_put(integrator: str, dt: float) -> None:
    sim = Simulator("basket", {"simulation.integrator": integrator, "simulation.dt": dt})
    sim.launch_ball([0.3, 0.2, 1.5], [0.0, 0.0, 0.0])  # off centre: on the sloped part of the bottom
    sim.step(round(3.0 / dt))  # dropped, bounced and settled
    settled = sim.ball_positions[0]
    sim.step(round(2.0 / dt))
    assert np.linalg.norm(sim.ball_positions[0] - settled) < 1e-3


@pytest.mark.parametrize(("integrator", "dt"), [("imex_euler", 2e-3), ("imex_euler", 1e-3), ("imex_euler", 5e-4),
                                                ("symplectic_euler", 5e-4)])
def test_a_ball_resting_on_two_others_in_the_net_stays_put(integrator: str, dt: float) -> None:
    """A pile: one ball dropped onto two in the basket's bottom. Once settled it stays (the
    contacts between balls are resolved before each ball's supports, whose static friction then
    holds what those contacts pushed; resolved after them, the pushes escaped it and the pile
    crept on at 1-6 mm/s, the top ball sinking between the others)."""
    sim = Simulator("basket", {"simulation.integrator": integrator, "simulation.dt": dt})
    for position in ([0.3, 0.0, 1.2], [-0.3, 0.0, 1.2], [0.0, 0.0, 2.2]):
        sim.launch_ball(position, [0.0, 0.0, 0.0])
    sim.step(round(6.0 / dt))  # dropped, bounced and settled
    assert sim.ball_positions[2, 2] > sim.ball_positions[:2, 2].max() + sim.model.ball_radius  # a pile, on top
    settled = sim.ball_positions.copy()
    sim.step(round(2.0 / dt))
    assert np.linalg.norm(sim.ball_positions - settled, axis=1).max() < 1e-3


def _tilted_patch(angle: float, spacing: float = 0.05, half: int = 30) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """A flat, immovable square grid of particles and structural segments, tilted by ``angle``
    about the y axis (it descends towards +x); returns positions, segments and the downhill unit vector."""
    ij = np.array([(i, j) for i in range(-half, half + 1) for j in range(-half, half + 1)], dtype=float) * spacing
    downhill = np.array([math.cos(angle), 0.0, -math.sin(angle)])
    points = ij[:, :1] * downhill + ij[:, 1:] * np.array([0.0, 1.0, 0.0]) + np.array([0.0, 0.0, 10.0])
    side = 2 * half + 1
    index = np.arange(side * side).reshape(side, side)
    segments = np.concatenate([np.stack([index[:-1, :].ravel(), index[1:, :].ravel()], axis=1),
                               np.stack([index[:, :-1].ravel(), index[:, 1:].ravel()], axis=1)])
    return points, segments.astype(np.int64), downhill


def _slide(angle: float, friction: float, seconds: float, dt: float = 1e-3,
           contact_model: ContactModel = ContactModel.IMPULSE) -> float:
    """Distance a ball released at rest on the tilted patch travels downhill in ``seconds``
    (compliant contacts: 2e4 N/m, the ball released touching)."""
    points, segments, downhill = _tilted_patch(angle)
    normal = np.cross(downhill, [0.0, 1.0, 0.0])
    radius = 0.3
    x = np.vstack([points, points[len(points) // 2] + radius * normal])
    v = np.zeros_like(x)
    inv_mass = np.zeros(len(x))
    inv_mass[-1] = 1.0
    contact = np.zeros((len(Contact), 2))
    contact[Contact.BALL_NET] = (0.0, friction)
    nowhere = Opening(2, 1, 100.0, (0, 1), (-1.0, -1.0), (1.0, 1.0))
    segments, segment_start = index_segments(segments, len(points))
    model = KernelModel(n_net=len(points), springs=Springs.of(np.zeros((0, 2)), np.zeros((0, 3)), len(points)),
                        segments=segments, segment_start=segment_start, poles=Poles.none(),
                        materials=Materials.of_table(contact),
                        restitution_threshold=0.2,
                        gravity=-9.81, drag=0.0, ball_radius=radius, opening=nowhere.kernel_record(), ball_drag=0.0,
                        wind=np.zeros(3))
    settings = Settings.make(Integrator.SYMPLECTIC_EULER, dt, 0.25, 1e-10, 100, 1e3, contact_model, 2e4)
    start = x[-1].copy()
    status = stepping.advance(x, v, inv_mass, np.zeros(1, dtype=np.int8), model, settings, round(seconds / dt),
                              Scratch.sized(len(x), 1), stepping.new_counters())
    assert status == stepping.OK
    return float((x[-1] - start) @ downhill)


@pytest.mark.parametrize("contact_model", list(ContactModel), ids=lambda m: m.label)
def test_a_ball_on_a_slope_within_the_friction_cone_does_not_creep(contact_model: ContactModel) -> None:
    """Compliant contacts hold it by their anchors (a regularised friction alone lets it creep
    at 5 cm/s times the load's share of the cone: 29 mm in this second)."""
    friction = 0.3  # friction angle 16.7 degrees
    assert abs(_slide(math.radians(10.0), friction, 1.0, contact_model=contact_model)) < 1e-3


@pytest.mark.parametrize("contact_model", list(ContactModel), ids=lambda m: m.label)
def test_a_ball_on_a_slope_steeper_than_the_friction_angle_slides_as_coulomb_says(contact_model: ContactModel) -> None:
    friction, angle, seconds = 0.3, math.radians(30.0), 0.5
    expected = 0.5 * 9.81 * (math.sin(angle) - friction * math.cos(angle)) * seconds ** 2
    assert _slide(angle, friction, seconds, contact_model=contact_model) == pytest.approx(expected, rel=0.1)


def test_static_friction_holds_resting_contacts_only_and_never_drags_a_ball_through_the_net() -> None:
    """A 25 m/s oblique shot into the goal's back net (IMEX Euler at 2 ms): held on positions
    during the impact, the net's particles would be dragged along with the ball and open a
    hole; only resting contacts are held, and the ball stays in the net."""
    sim = Simulator("goal", {"simulation.integrator": "imex_euler", "simulation.dt": 2e-3})
    result = throw(sim, [-7.2037, -3.1822, 2.0430], [22.7389, 10.0446, -1.7383])
    assert result.captured
    assert result.final_position[0] < sim.config.net.upper[0]
