"""How far a thrown ball is from everything else, and how long it can fly clear of it."""

from __future__ import annotations

import numpy as np

from netgym.kinds import ContactModel
from netgym.physics.fast_path import approach

from netgym.physics.kernels import surroundings
from netgym.physics.kernels.surroundings import survey
from netgym.physics.throw.records import TUNING, ThrowContext


def clearance(throw: ThrowContext) -> float:
    """Distance the ball can travel before it could touch the net, a pole or another ball (the
    net held still)."""
    m = throw.sim.model
    return surroundings.clearance(throw.sim.state.x, m.n_net, throw.ball.row, m.ball_radius, m.segments, m.poles)


def on_step_grid(throw: ThrowContext, tau: float) -> float:
    """The longest flight of at most ``tau`` from now that ends on the step grid of the full
    simulation (the launch plus whole steps of the scene's dt), or 0.0: where the fast path
    integrates, it then takes the steps the full simulation takes there."""
    sim = throw.sim
    return approach.on_step_grid(sim.state.time, tau, throw.course.launched, sim.config.simulation.dt)


def flight_time(throw: ThrowContext) -> float:
    """How long the ball can fly in closed form from now, clear of everything and at most to the
    deadline, ending on the full simulation's step grid; 0.0 if it cannot fly to the next step
    there, and must be simulated."""
    gap = clearance(throw)
    if gap <= TUNING.clearance:
        return 0.0
    s = throw.sim.state
    safe = throw.free_flight.safe_time(s.v[throw.ball.row], gap, TUNING.air_piece)
    return on_step_grid(throw, min(safe, throw.course.deadline - s.time))


def can_roll_alone(throw: ThrowContext) -> bool:
    """Whether the ball may be stepped alone for a step, everything else asleep: it can touch
    nothing that moves meanwhile, only poles, pinned particles and the ground, which the rest's
    sleep does not change (:func:`~netgym.physics.kernels.surroundings.alone_for_a_step`). Not
    with compliant contacts: the lone ball's step is the impulse model's."""
    sim, course = throw.sim, throw.course
    s, dt = sim.state, sim.config.simulation.dt
    return (sim.contact_model == ContactModel.IMPULSE and round((course.deadline - s.time) / dt) > 0
            and surroundings.alone_for_a_step(s.x, s.v, s.inv_mass, throw.lone, throw.ball.row, dt))


def surveyed_box(throw: ThrowContext, margin: float) -> tuple[float, np.ndarray, np.ndarray]:
    """``(others, lo, hi)``: the largest velocity component of every body but the ball, and the
    bounding box of the net particles, the poles' axes and the other balls' centres, grown by the
    ball radius + the largest radius about those (a pole's, another ball's) + ``margin``: outside
    it the ball is more than ``margin`` from everything."""
    s = throw.sim.state
    box = np.empty(6)
    others = survey(s.x, s.v, throw.ball.row, throw.sim.model.poles, box)
    grow = throw.course.about + margin
    return others, box[:3] - grow, box[3:] + grow
