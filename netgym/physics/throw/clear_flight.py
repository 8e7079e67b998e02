"""The ball flown in closed form while it is clear of everything (the scene asleep)."""

from __future__ import annotations

import numpy as np

from netgym.physics.fast_path import approach, flight

from netgym.physics import stepping
from netgym.physics.outcomes import Reason
from netgym.physics.plans import Plan, Tick
from netgym.physics.throw import decisions
from netgym.physics.throw.clearance import flight_time, on_step_grid, surveyed_box
from netgym.physics.throw.filming import film_flight
from netgym.physics.throw.records import TUNING, ThrowContext


def fly_clear(throw: ThrowContext) -> Plan:
    """Move the ball on its free flight (closed form; through air, RK4) while it is clear of
    everything. Returns a decision reason, or None when the ball came close enough to need
    simulating."""
    s, course, free = throw.sim.state, throw.course, throw.free_flight
    row = throw.ball.row
    _, lo, hi = surveyed_box(throw, TUNING.clearance)
    if free.parabola:  # whether and when it comes into the box is one answer along the whole flight
        entry = flight.entry_time(s.x[row], s.v[row], lo, hi, free.ground, course.deadline - s.time)
        if entry is None:
            return Reason.FLIES_AWAY
        entry = on_step_grid(throw, entry)
        if entry > 0.0:  # until then it is clear of everything and cannot cross the opening (inside the box)
            entry = decisions.first_decided_instant(throw, entry, through_opening=False)  # the line beside the frame
            yield from move(throw, entry, through_opening=False)
            reason = decisions.after_flight(throw)
            if reason is not None:
                return reason
    box, km = np.concatenate((lo, hi)), throw.sim.kernel_model
    while True:
        if throw.film is None:  # the pieces that certainly end undecided, in one kernel call
            s.time = (approach.approach(s.x, s.v, s.entered, km, free.ground, course.watch, box, s.time)
                      if free.parabola
                      else approach.approach_through_air(s.x, s.v, s.entered, km, free.ground, course.watch, box,
                                                         s.time, TUNING.air_piece))
        if free.never_enters(s.x[row], s.v[row], lo, hi, course.deadline - s.time):  # it left the box, for good
            return Reason.FLIES_AWAY
        if free.parabola and flight.lies_still(s.x[row], s.v[row], free.ground):
            return Reason.AT_REST  # beside the sleeping scene, nothing can move it any more
        tau = flight_time(throw)
        if tau <= 0.0:
            return None  # near something: integrate from here (on the full simulation's step grid)
        tau = decisions.first_decided_instant(throw, tau, through_opening=True)
        yield from move(throw, tau, through_opening=True)
        reason = decisions.after_flight(throw)
        if reason is not None:
            return reason


def move(throw: ThrowContext, tau: float, through_opening: bool) -> Plan:
    """Fly the ball for ``tau`` (filmed if there is a film); if it may pass ``through_opening``,
    book its crossing along the chord of the flight (a conservative step's chord stays, like its
    arc, within the clearance about its start)."""
    sim = throw.sim
    s, n_net, row = sim.state, sim.model.n_net, throw.ball.row
    before = s.x[n_net:].copy()
    start = s.x[row].copy(), s.v[row].copy(), s.time
    if throw.film is not None:
        yield from film_flight(throw, *start, start[2] + tau)
    s.x[row], s.v[row] = throw.free_flight.advance(start[0], start[1], tau)
    if through_opening:
        stepping.update_entered(s.x, before, n_net, s.entered, sim.kernel_model.opening)
    s.time = start[2] + tau
    if throw.film is not None:
        yield Tick()  # an instant within half a step after the flight's end: here is its nearest substep
