"""What a throw watches while its scene is integrated, in numba: the check after each chunk of
steps, its rest window, and the loop that integrates chunk after chunk while nothing could be
decided.

The fast path's decisions stay in :mod:`netgym.physics.throw.decisions`; after each chunk they read
:func:`near_check` (how fast everything else moves, whether the ball is still inside the box
around everything else, at rest, or out of the opening's reach). :func:`integrate_watched`
makes the same check after each chunk within one kernel call and hands back to the throw as
soon as it, the capture rule or the time limit could decide anything (or the scene could go
to sleep); :func:`roll_watched` does the same for the ball stepped alone while the scene
sleeps. The throw then decides on that state with the same check, so a throw crosses into
Python once per decision, not once per chunk, and decides exactly as if it had looked after
every chunk.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from netgym.physics.compliant.contacts import ContactList
from netgym.physics.kernels.jit import inline_kernel, kernel
from netgym.physics.model.opening import opening_depth
from netgym.physics.fast_path.reach import Budget, out_of_reach
from netgym.physics.kernels.rows import copy_rows
from netgym.physics.stepping import DIVERGED, OK, advance, advance_alone
from netgym.physics.kernels.surroundings import clearance, still_since, survey


class RestWindow(NamedTuple):
    """The positions a throw's rest test compares against: ``times`` (capacity,) and
    ``positions`` (capacity, n_bodies, 3) of the checks of the last ``window`` (s), a ring of
    ``ring[1]`` entries from slot ``ring[0]`` (oldest first). At rest: the ball and the bodies
    whose centres lie within ``near`` (m) of it moved no coordinate by ``bound`` (m) or more
    since any of them. ``epsilon`` (s): instants closer than this are the same."""

    times: np.ndarray
    positions: np.ndarray
    ring: np.ndarray
    window: float
    epsilon: float
    near: float
    bound: float

    @classmethod
    def sized(cls, n_bodies: int, dt: float, window: float, epsilon: float, near: float,
              bound: float) -> "RestWindow":
        """An empty window for states of ``n_bodies``, checked at most once a step of ``dt``
        (a throw checks after whole steps; checks closer than ``epsilon`` are one): room for the
        checks within ``window`` and the latest one before it."""
        capacity = math.ceil(window / dt) + 3
        return cls(np.empty(capacity), np.empty((capacity, n_bodies, 3)), np.zeros(2, dtype=np.int64),
                   float(window), float(epsilon), float(near), float(bound))


class Watch(NamedTuple):
    """What a throw's kernels (these and :func:`~netgym.physics.fast_path.approach.approach`) know of it:
    the ball's ``row``, its ``launched`` and ``deadline`` times (s), the scene's ``dt`` (s),
    ``chunk`` (steps between two checks), ``clearance`` (m: closer than this to anything, the
    ball is simulated, not flown), ``grow`` (m: the box around everything but the ball grows by
    this), ``rule_depth`` (m: past the opening's plane from this depth, the capture rule may
    decide; inf: never), ``sleep_speed`` (m/s: slower than this, everything but the ball may go
    to sleep), ``far_clearance`` (m) and ``far_sleep_speed`` (m/s: the same while the ball is
    farther than that from everything, :func:`far_from_a_slow_scene`), its
    :class:`~netgym.physics.fast_path.reach.Budget`, its :class:`RestWindow` and ``box`` (6,), the
    grown box of the last check (min x, y, z, max x, y, z), and room for the compliant contacts
    the energy bound lists (:data:`~netgym.physics.compliant.contacts.NO_CONTACTS` with impulse
    contacts)."""

    row: int
    launched: float
    deadline: float
    dt: float
    chunk: int
    clearance: float
    grow: float
    rule_depth: float
    sleep_speed: float
    far_clearance: float
    far_sleep_speed: float
    budget: Budget
    rest: RestWindow
    box: np.ndarray
    contacts: ContactList


@kernel
def remember(rest, time, x):
    """Note the positions ``x`` at ``time`` in the :class:`RestWindow` (in place of the newest
    if that is of the same instant, within ``epsilon``: a check made again on the same state,
    or after a flight of a rounding error to the step grid) and forget those it no longer
    needs: the oldest kept is the latest at least ``window`` old."""
    capacity = rest.times.shape[0]
    first, count = rest.ring[0], rest.ring[1]
    if count > 0 and time - rest.times[(first + count - 1) % capacity] < rest.epsilon:
        count -= 1
    if count == capacity:
        raise RuntimeError("the rest window is full: a throw checked more than once a step")
    slot = (first + count) % capacity
    rest.times[slot] = time
    copy_rows(rest.positions[slot], x)
    count += 1
    while count > 1 and rest.times[(first + 1) % capacity] <= time - rest.window + rest.epsilon:
        first = (first + 1) % capacity
        count -= 1
    rest.ring[0], rest.ring[1] = first, count


@kernel
def at_rest(rest, x, row, time):
    """The ball in ``row`` and the bodies near it moved no coordinate by ``bound`` or more
    between any check of the :class:`RestWindow` (which covers the whole window) and ``x``
    now. Positions, not velocities: a light net under a resting ball keeps a velocity jitter
    of the order of its acceleration x dt while nothing moves."""
    capacity = rest.times.shape[0]
    first, count = rest.ring[0], rest.ring[1]
    if time - rest.times[first] < rest.window - rest.epsilon:
        return False
    for k in range(count - 1):  # the newest is now
        if not still_since(x, rest.positions[(first + k) % capacity], row, rest.near, rest.bound):
            return False
    return True


@kernel
def near_check(x, v, inv_mass, time, model, watch):
    """The check after a chunk, remembered in the watch's rest window: ``(others, inside,
    at_rest, unreachable)``, the largest velocity component of everything but the ball,
    whether the ball lies inside the box around everything else (the watch's ``box``, written
    here: every body but the ball and the poles' axes, grown by ``grow``), whether it is at
    rest (:func:`at_rest`), and whether it can no longer reach the opening before its deadline
    (:func:`~netgym.physics.fast_path.reach.out_of_reach`)."""
    row, box = watch.row, watch.box
    others = survey(x, v, row, model.poles, box)
    inside = True
    for c in range(3):
        box[c] = box[c] - watch.grow
        box[c + 3] = box[c + 3] + watch.grow
        inside = inside and box[c] <= x[row, c] <= box[c + 3]
    remember(watch.rest, time, x)
    rest = at_rest(watch.rest, x, row, time)
    unreachable = out_of_reach(x, v, inv_mass, row, model, watch.budget, watch.deadline - time, watch.contacts)
    return others, inside, rest, unreachable


@kernel
def far_from_a_slow_scene(x, n_net, radius, segments, poles, watch, others):
    """Whether everything but the watch's ball, its largest velocity component ``others``, may
    go to sleep though it moves faster than ``sleep_speed``: slower than ``far_sleep_speed``,
    with the ball more than ``far_clearance`` from all of it (a net swaying after the ball left
    it off the rim, the ball flying over it). The net then sleeps as a still one does (its
    velocities zeroed) until the ball comes near again."""
    return others < watch.far_sleep_speed and clearance(x, n_net, watch.row, radius, segments,
                                                        poles) > watch.far_clearance


@inline_kernel
def _next_chunk(watch, t, dt):
    """Steps of the chunk from ``t``: ``watch.chunk``, fewer before the deadline, none at it."""
    return max(0, min(watch.chunk, round((watch.deadline - t) / dt)))


@inline_kernel
def _decidable(x, v, inv_mass, model, watch, t, dt):
    """After a chunk that ended at ``t``: (whether something could be decided now, the largest
    velocity component of everything but the ball): the deadline is within half a step, the ball
    lies at least ``rule_depth`` past the opening's plane, or :func:`near_check` (not made in
    those two cases) finds it outside the box, at rest or out of reach."""
    if watch.deadline - t < 0.5 * dt or opening_depth(model.opening, x[watch.row]) >= watch.rule_depth:
        return True, 0.0
    others, inside, rest, unreachable = near_check(x, v, inv_mass, t, model, watch)
    return not inside or rest or unreachable, others


@kernel
def integrate_watched(x, v, inv_mass, entered, model, settings, scratch, stats, watch, time):
    """Integrate chunk after chunk of ``watch.chunk`` steps (fewer before the deadline), with
    :func:`~netgym.physics.stepping.advance`, from ``time`` while nothing could be decided:
    stop after the chunk at which the deadline is within half a step, the ball lies at least
    ``rule_depth`` past the opening's plane, or :func:`near_check` finds everything else
    slower than ``sleep_speed`` (or far enough and slow enough: :func:`far_from_a_slow_scene`),
    the ball outside the box, at rest or out of reach. Returns
    (OK or DIVERGED, the time reached), each chunk's time added as the throw adds it."""
    dt, t = settings.dt, time
    while True:
        n = _next_chunk(watch, t, dt)
        if n == 0:
            return OK, t
        if advance(x, v, inv_mass, entered, model, settings, n, scratch, stats) != OK:
            return DIVERGED, t
        t += n * dt
        decidable, others = _decidable(x, v, inv_mass, model, watch, t, dt)
        if decidable or others < watch.sleep_speed or far_from_a_slow_scene(
                x, model.n_net, model.ball_radius, model.segments, model.poles, watch, others):
            return OK, t


@kernel
def roll_watched(x, v, inv_mass, entered, model, settings, stats, watch, time):
    """:func:`integrate_watched` for the ball of ``watch.row`` alone, everything else asleep
    (:func:`~netgym.physics.stepping.advance_alone`): chunk after chunk, until a chunk
    stops short (the ball could touch something that moves), or after the chunk at which the
    deadline is within half a step, the ball lies at least ``rule_depth`` past the opening's
    plane, :func:`near_check` finds it outside the box, at rest or out of reach, or it is clear
    of everything (it may fly in closed form again). Returns (OK or DIVERGED, the time reached)."""
    dt, t, row = settings.dt, time, watch.row
    while True:
        n = _next_chunk(watch, t, dt)
        if n == 0:
            return OK, t
        status, taken = advance_alone(x, v, inv_mass, entered, model, settings, n, row, stats)
        if status != OK:
            return DIVERGED, t
        t += taken * dt
        if taken == 0:
            return OK, t
        decidable, _ = _decidable(x, v, inv_mass, model, watch, t, dt)
        if decidable or taken < n or clearance(x, model.n_net, row, model.ball_radius, model.segments,
                                                model.poles) > watch.clearance:
            return OK, t
