"""The decisions of a throw: each function answers one question about a throw under way
(a :class:`~netgym.physics.throw.records.ThrowContext`) and returns a
:class:`~netgym.physics.outcomes.Reason`, or None while the outcome is still open.

- :func:`rule_decision`: does the scene's capture rule decide the ball where it is?
- :func:`after_flight`: is the throw decided at the end of a piece of closed-form flight?
- :func:`after_piece`: is it decided after a piece of integration or flight (the rule, the time
  limit, then the fast path's own checks), and if not, may the scene go to sleep?
- :func:`after_check`: does the check after an integrated chunk decide it (flies away, at
  rest, cannot reach the opening)?
- :func:`first_decided_instant`: when, within a flight, does the capture rule first decide it?
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from netgym.physics import stepping
from netgym.physics.outcomes import Reason
from netgym.physics.throw.clearance import can_roll_alone, flight_time
from netgym.physics.throw.records import TUNING, ThrowContext
from netgym.physics.fast_path.watch import far_from_a_slow_scene, near_check


def rule_decision(throw: ThrowContext, position: np.ndarray, entered: bool) -> Reason | None:
    """The capture rule's decision on the ball at ``position`` (``entered``: through the opening)."""
    sim = throw.sim
    return throw.rule.decision(sim.opening, sim.model.ball_radius, position, entered, throw.course.from_front)


def after_flight(throw: ThrowContext) -> Reason | None:
    """The decision at the end of a piece of flight: the capture rule's (noted in the course),
    the time limit, or None."""
    s, course, (index, row) = throw.sim.state, throw.course, throw.ball
    decision = rule_decision(throw, s.x[row], bool(s.entered[index]))
    if decision is not None:
        course.decision = decision
        return decision
    return Reason.TIME_LIMIT if course.deadline - s.time < 0.5 * throw.sim.dt else None


class Verdict(NamedTuple):
    """What :func:`after_piece` finds: the ``reason`` the throw is decided, or None; and
    whether, undecided, the scene may go to sleep (``quiet``: the ball could fly clear for a
    step, or move alone for one, near nothing that moves, and nothing but the ball moves any
    more, or the rest moves slowly and the ball is far from it,
    :func:`~netgym.physics.fast_path.watch.far_from_a_slow_scene`). A ball that can do neither is
    integrated with the rest, however far and slow that is: asleep, the scene would be woken
    again at once, with no time gone by."""

    reason: Reason | None
    quiet: bool = False


def after_piece(throw: ThrowContext) -> Verdict:
    """The :class:`Verdict` after a piece of the throw: the capture rule's decision (the full
    simulation notes it and goes on to the time limit), the time limit, then the fast path's
    check of the integrated scene (:func:`after_check`), and whether the scene is quiet enough
    to sleep, so that the ball flies in closed form again."""
    course, s = throw.course, throw.sim.state
    if course.decision is None:
        course.decision = rule_decision(throw, s.x[throw.ball.row], bool(s.entered[throw.ball.index]))
    if throw.fast and course.decision is not None:
        return Verdict(course.decision)
    if course.deadline - s.time < 0.5 * throw.sim.dt:
        return Verdict(Reason.TIME_LIMIT)
    if not throw.fast:
        return Verdict(None)
    km, watch = throw.sim.kernel_model, course.watch
    others, _, at_rest, unreachable = near_check(s.x, s.v, s.inv_mass, s.time, km, watch)
    reason = after_check(throw, at_rest, unreachable, watch.box[:3].copy(), watch.box[3:].copy())
    m = throw.sim.model
    return Verdict(reason, reason is None and (
        others < watch.sleep_speed
        or far_from_a_slow_scene(s.x, m.n_net, m.ball_radius, m.segments, m.poles, watch, others))
        and (flight_time(throw) > 0.0 or can_roll_alone(throw)))


def after_check(throw: ThrowContext, at_rest: bool, unreachable: bool, lo: np.ndarray,
                hi: np.ndarray) -> Reason | None:
    """The reason the throw's outcome is decided now, or None, from the check after a chunk
    (:func:`~netgym.physics.fast_path.watch.near_check`): the ball flies away (it cannot come back into
    the box ``lo``..``hi`` around everything else), it is ``at_rest``, or it can no longer reach
    the opening (``unreachable``: the energy bound, which counts, besides the energy free now,
    all the wind could still feed the balls before the deadline)."""
    s, row, free = throw.sim.state, throw.ball.row, throw.free_flight
    horizon = math.inf if free.parabola else throw.course.deadline - s.time  # through air the time left bounds it
    if free.never_enters(s.x[row], s.v[row], lo, hi, horizon):
        return Reason.FLIES_AWAY
    if at_rest:
        return Reason.AT_REST
    if unreachable:
        return Reason.CANNOT_REACH_OPENING
    return None


def first_decided_instant(throw: ThrowContext, tau: float, through_opening: bool) -> float:
    """``tau``, or, if the capture rule decides the ball flying for ``tau`` (its crossing booked
    only if it may pass ``through_opening``), the first instant it does (within
    ``line_time_tolerance`` after it)."""
    sim = throw.sim
    s, n_net, (index, row) = sim.state, sim.model.n_net, throw.ball
    start, before = (s.x[row].copy(), s.v[row].copy()), s.x[n_net:].copy()

    def decided_at(t: float) -> bool:
        x, entered = s.x.copy(), s.entered.copy()
        x[row] = throw.free_flight.advance(*start, t)[0]
        if through_opening:
            stepping.update_entered(x, before, n_net, entered, sim.kernel_model.opening)
        return rule_decision(throw, x[row], bool(entered[index])) is not None

    return throw.rule.decision_instant(tau, decided_at, TUNING.line_time_tolerance)
