"""A filmed throw's extra frames: closed-form flight at the film's instants, a miss flown on to
its landing, a ball the capture rule decided filmed on; each put back as decided, so that
filming changes nothing."""

from __future__ import annotations

import numpy as np

from netgym.physics.outcomes import Reason
from netgym.physics.plans import Integrate, Plan, Tick
from netgym.physics.throw.records import TUNING, ThrowContext


def film_after(throw: ThrowContext, reason: Reason, t_limit: float) -> Plan:
    """When filmed: a miss decided in closed form flown on to its landing (or ``t_limit``), a
    ball the capture rule decided filmed on; both put back as decided."""
    if throw.film is None:
        return
    if reason is Reason.FLIES_AWAY:
        yield from _film_miss(throw, t_limit)
    if reason is throw.course.decision:
        yield from _film_on(throw)


def film_flight(throw: ThrowContext, x: np.ndarray, v: np.ndarray, t: float, end: float) -> Plan:
    """Put the ball, flying in closed form from ``x``, ``v`` at time ``t``, where it is at each
    frame instant before ``end``, and stop there (a Tick). The flight itself is computed apart,
    so that filming changes nothing."""
    assert throw.film is not None
    s, row, eps = throw.sim.state, throw.ball.row, TUNING.time_epsilon
    while (instant := throw.film.clock.next_instant(s.time, eps)) < end - eps:
        s.x[row], s.v[row] = throw.free_flight.advance(x, v, instant - t)
        s.time = instant
        yield Tick()


def _film_miss(throw: ThrowContext, t_limit: float) -> Plan:
    """Film a missed ball's closed-form flight on until ``miss_filmed_after_landing`` after it
    first lands (or ``t_limit``); then put the ball and the time back as decided."""
    s, row = throw.sim.state, throw.ball.row
    kept = s.x[row].copy(), s.v[row].copy(), s.time
    landing = throw.free_flight.landing_time(s.x[row], s.v[row])
    end = min(t_limit, s.time + landing + TUNING.miss_filmed_after_landing)
    yield from film_flight(throw, *kept, end)
    s.x[row], s.v[row], s.time = kept


def _film_on(throw: ThrowContext) -> Plan:
    """Film a ball the capture rule decided on for ``rule_filmed`` seconds, everything integrated
    (a goal runs into the net, a ball out of play onto it or past it), then put the scene, its
    time and its work counters back as decided."""
    sim = throw.sim
    kept = sim.checkpoint()
    cfg = sim.config.simulation
    sim.wake()
    yield Integrate(round(TUNING.rule_filmed / cfg.dt), sim.integrator, cfg.dt)
    sim.restore(kept)
