"""The ball's approach to the sleeping scene, in numba: the pieces of flight of the fast path
(see :func:`~netgym.physics.throw.clear_flight.fly_clear`) that nothing can decide, in closed form
(:func:`approach`) or through air (:func:`approach_through_air`).

A piece flies the ball, held clear of everything by its clearance, for the longest time it
cannot travel that far, to the full simulation's step grid. :func:`approach` flies piece after
piece in one kernel call while each certainly ends undecided (the ball stays inside the box
around the scene, off the ground, short of the capture rule's depth and of the time limit),
and hands back to the throw before the first piece that might not; the throw flies that one
itself. The pieces are those the throw would fly, with the same arithmetic.
"""

from __future__ import annotations

import math

import numpy as np

from netgym.physics.kernels import air
from netgym.physics.fast_path.flight import ground_time, sliding
from netgym.physics.kernels.jit import inline_kernel, kernel
from netgym.physics.model.opening import opening_depth
from netgym.physics.stepping import net_box, update_entered
from netgym.physics.kernels.surroundings import air_safe_time, clearance, clearance_at_least, speed, travel_time


@kernel
def on_step_grid(now, tau, launched, dt):
    """The longest flight of at most ``tau`` from ``now`` that ends on the step grid
    ``launched`` + whole steps of ``dt``, or 0.0."""
    steps = math.floor((now + tau - launched) / dt + 1e-9)
    return max(0.0, launched + steps * dt - now)


@inline_kernel
def _move_ball(x, before, n_net, entered, opening, p, end):
    """Move the ball whose position is the row ``p`` of ``x`` to ``end``, booking its crossing of
    the opening along the chord (``before``: room for the balls' positions)."""
    for b in range(before.shape[0]):
        for c in range(3):
            before[b, c] = x[n_net + b, c]
    for c in range(3):
        p[c] = end[c]
    update_entered(x, before, n_net, entered, opening)


@kernel
def approach(x, v, entered, model, ground, watch, box, time):
    """Fly the ball of ``watch.row`` from ``time``, piece after piece, while each certainly ends
    undecided; returns the time reached (``x``, ``v`` and ``entered`` moved on in place).

    A piece starts only while the ball lies inside ``box`` (6,: min x, y, z, max x, y, z;
    outside it, it may never come back), is not sliding on the ground, and is farther than
    ``watch.clearance`` from the net, the poles and the other balls (all held still: the
    scene sleeps); it lasts the longest time within which the ball cannot travel that far
    (gravity bounding its acceleration) and ends on the step grid from ``watch.launched``. It
    is flown only if the ball meets no ground, stops short of the capture rule's depth and the
    deadline is more than half a step after it; its crossing of the opening is booked along
    its chord.
    """
    row, n_net, radius, opening = watch.row, model.n_net, model.ball_radius, model.opening
    before = np.empty((x.shape[0] - n_net, 3))
    t = time
    while True:
        p, u = x[row], v[row]
        for c in range(3):
            if not box[c] <= p[c] <= box[c + 3]:
                return t
        if sliding(p, u, ground):
            return t
        gap = clearance(x, n_net, row, radius, model.segments, model.poles)
        if gap <= watch.clearance:
            return t
        bound = travel_time(speed(u), abs(model.gravity), gap)
        tau = on_step_grid(t, min(bound, watch.deadline - t), watch.launched, watch.dt)
        if tau <= 0.0 or ground_time(p, u, ground) < tau or watch.deadline - (t + tau) < 0.5 * watch.dt:
            return t
        end = (p[0] + u[0] * tau, p[1] + u[1] * tau, p[2] + u[2] * tau + 0.5 * model.gravity * tau * tau)
        if opening_depth(opening, end) >= watch.rule_depth:
            return t
        _move_ball(x, before, n_net, entered, opening, p, end)
        u[2] += model.gravity * tau
        t = t + tau


@kernel
def approach_through_air(x, v, entered, model, ground, watch, box, time, piece):
    """:func:`approach` through air: fly the ball of ``watch.row`` from ``time`` piece after
    piece (:func:`~netgym.physics.kernels.air.fly`, bounces and sliding included) while each certainly
    ends undecided; returns the time reached (``x``, ``v`` and ``entered`` moved on in place).

    A piece starts only while the ball is not outside ``box`` for good (lying there held by
    friction, or farther than it can travel back before the deadline: then it flies away) and is farther than ``watch.clearance`` from the net, the poles and the other
    balls; it lasts :func:`air_safe_time` (at most ``piece``), ends on the step grid from
    ``watch.launched``, and is flown only if it stops short of the capture rule's depth and
    the deadline is more than half a step after it. These are the pieces the throw would fly
    itself, with the same arithmetic."""
    row, n_net, radius, opening = watch.row, model.n_net, model.ball_radius, model.opening
    k, wind, gravity = model.ball_drag, model.wind, model.gravity
    before = np.empty((x.shape[0] - n_net, 3))
    end_p, end_v = np.empty(3), np.empty(3)
    asleep = np.empty(6)
    net_box(x, n_net, asleep)  # the net does not move while the ball approaches
    t = time
    while True:
        p, u = x[row], v[row]
        outside = False
        for c in range(3):
            outside = outside or not box[c] <= p[c] <= box[c + 3]
        if outside and (air.held_by_friction(u, gravity, k, wind, radius, ground.friction, p)
                        or air.cannot_reach(p, u, wind, box, watch.deadline - t)):
            return t
        gap = clearance_at_least(x, n_net, row, radius, asleep, model.poles)
        bound = air_safe_time(speed(u), gap, gravity, k, wind, piece)
        if gap <= watch.clearance or bound < piece:  # the exact clearance could change the piece
            gap = clearance(x, n_net, row, radius, model.segments, model.poles)
            if gap <= watch.clearance:
                return t
            bound = air_safe_time(speed(u), gap, gravity, k, wind, piece)
        tau = on_step_grid(t, min(bound, watch.deadline - t), watch.launched, watch.dt)
        if tau <= 0.0 or watch.deadline - (t + tau) < 0.5 * watch.dt:
            return t
        for c in range(3):
            end_p[c], end_v[c] = p[c], u[c]
        air.fly(end_p, end_v, tau, k, wind, ground, air.MAX_FLIGHT_STEP)
        if opening_depth(opening, end_p) >= watch.rule_depth:
            return t
        for c in range(3):
            u[c] = end_v[c]
        _move_ball(x, before, n_net, entered, opening, p, end_p)
        t = t + tau
