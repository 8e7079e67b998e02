"""RK4 through contact: the listed contacts' modes, pole regions and grips are frozen at a
step's start and the smooth system they give is integrated; where the step's end finds one
changed, the earliest instant a changed contact's event function crosses zero is found
(Illinois' regula falsi on RK4 steps of a fraction of the step, bisecting where it stalls), the
step goes to just past it, takes the modes there and goes on. Between events the forces are
smooth, so RK4 keeps its fourth order through contact."""

from __future__ import annotations

import math
from typing import Any, NamedTuple

import numpy as np

from netgym.physics.compliant import contacts as cl
from netgym.physics.compliant import forces
from netgym.physics.compliant.system import RATE, Z, Z0, Z1, ZLO, ZSUM, Work, freeze, rhs
from netgym.physics.kernels.integrators import rk4_accumulate, rk4_combine, rk4_stage_state
from netgym.physics.kernels.jit import inline_kernel, kernel
from netgym.physics.kernels.rows import copy_first_rows, copy_rows

MAX_EVENTS = 256          # events located in one step at most; later ones are stepped over
LOCATE_ITERATIONS = 100   # trial steps at most per event
LOCATE_TOLERANCE = 1e-13  # of the step: an event's bracket narrower than this is located


class System(NamedTuple):
    """What a located step integrates, the same all through it: the bodies' ``inv_mass``, the
    scene's :class:`~netgym.physics.model.model.KernelModel`, the acceleration ``net_gravity``
    of the net's weight, the scratch ``work`` and the contacts' ``stiffness`` (N/m)."""

    inv_mass: np.ndarray
    model: Any
    net_gravity: float
    work: Work
    stiffness: float


class Phase(NamedTuple):
    """The bodies' positions ``x`` and velocities ``v`` and the listed contacts' anchors ``z``
    at one instant of a located step: its start, its end, or a trial instant inside it (rows
    of ``work.rows`` and ``work.anchor``)."""

    x: np.ndarray
    v: np.ndarray
    z: np.ndarray


@kernel
def _rk4(system, start, h, end):
    """One classical RK4 step of ``h`` from the :class:`Phase` ``start`` (its anchors
    ``work.anchor[Z0]``) into the :class:`Phase` ``end``, the contacts' modes, regions and grips
    frozen."""
    inv_mass, model, net_gravity, work, stiffness = system
    x0, v0, z0 = start
    rows, anchor, count = work.rows, work.anchor, work.contacts.count[0]
    xs, vs, a, xsum, vsum, f = rows[0], rows[1], rows[2], rows[3], rows[4], rows[5]
    z, rate, zsum = anchor[Z], anchor[RATE], anchor[ZSUM]
    copy_first_rows(z, z0, count)
    rhs(x0, v0, inv_mass, model, net_gravity, work, stiffness, True, f, a)
    copy_rows(xsum, v0)
    copy_rows(vsum, a)
    copy_first_rows(zsum, rate, count)
    for stage in range(3):
        rk4_stage_state(x0, v0, a, xs, vs, stage, h)
        _anchor_stage(z0, rate, z, count, 0.5 * h if stage < 2 else h)
        rhs(xs, vs, inv_mass, model, net_gravity, work, stiffness, True, f, a)
        rk4_accumulate(xsum, vsum, vs, a, stage)
        _anchor_stage(zsum, rate, zsum, count, 1.0 if stage == 2 else 2.0)
    rk4_combine(x0, v0, xsum, vsum, h, end.x, end.v)
    _anchor_stage(z0, zsum, end.z, count, h / 6.0)


@inline_kernel
def _anchor_stage(base, rate, out, count, scale):
    """``out = base + scale * rate`` over the first ``count`` rows (``out`` may be ``base``)."""
    for c in range(count):
        for k in range(3):
            out[c, k] = base[c, k] + scale * rate[c, k]


@kernel
def _values(system, at):
    """Event values of the listed contacts in the :class:`Phase` ``at``, in their frozen modes,
    regions and grips, into ``touch1``, ``on1``, ``rate1``, ``side1`` and ``grip1``."""
    inv_mass, model, _, work, stiffness = system
    contacts, damping = work.contacts, work.damping
    cl.event_values(at.x, at.v, model, contacts, damping, work.touch1, work.on1, work.rate1, work.side1)
    forces.grip_values(at.x, at.v, inv_mass, model, contacts, at.z, stiffness, damping, work.grip1)


@kernel
def _changes(system, at):
    """:func:`_values` in the :class:`Phase` ``at``, the modes and regions there into ``modes``
    and ``regions``, and the contacts whose mode, region or grip's event sign differs from the
    frozen one into ``changed``; returns how many did."""
    work = system.work
    contacts, count = work.contacts, work.contacts.count[0]
    _values(system, at)
    cl.modes_from(work.touch1, work.on1, count, work.modes)
    cl.regions_from(work.side1, contacts, work.modes, work.regions)
    n = 0
    for c in range(count):
        if work.modes[c] != contacts.mode[c] or work.regions[c] != contacts.region[c] \
                or (work.grip1[c] > 0.0) != (work.grip0[c] > 0.0):
            work.changed[n] = c
            n += 1
    return n


@inline_kernel
def _crossing(work, n_changed, end):
    """The least of the changed contacts' event functions, each signed to be positive at the
    step's start (values of the start in ``touch0``, ``on0``, ``side0``, ``grip0``); of the
    state whose values are in ``touch1``, ``on1``, ``side1``, ``grip1`` if ``end``, of the start
    otherwise. Negative: some mode, region or grip changed."""
    least = math.inf
    for t in range(n_changed):
        c = work.changed[t]
        frozen = work.contacts.mode[c]
        # a change to or from ON shows in ``on``; between OFF and CLAMPED in ``touch``
        by_on = frozen == cl.ON or work.modes[c] == cl.ON
        start = work.on0[c] if by_on else work.touch0[c]
        value = (work.on1[c] if by_on else work.touch1[c]) if end else start
        least = min(least, value if start > 0.0 else -value)
        region = work.contacts.region[c]
        if region != cl.LIVE:  # a pole's frozen region: positive while its parameter stays in it
            start = cl.region_value(region, work.side0[c])
            value = cl.region_value(region, work.side1[c]) if end else start
            least = min(least, value if start > 0.0 else -value)
        start = work.grip0[c]
        value = work.grip1[c] if end else start
        least = min(least, value if start > 0.0 else -value)
    return least


@kernel
def _graze(work, count, h):
    """The earliest fraction of a step of ``h`` at which a contact whose overlap has one sign at
    both ends may have had the other (a brief touch, or a brief separation): where the cubic
    through the overlaps and their rates at the two ends crosses zero, 1.0 if none does."""
    earliest = 1.0
    for c in range(count):
        d0, d1 = work.touch0[c], work.touch1[c]
        if (d0 > 0.0) != (d1 > 0.0):
            continue
        r0, r1 = work.rate0[c] * h, work.rate1[c] * h
        b = 3.0 * (d1 - d0) - 2.0 * r0 - r1
        a = 2.0 * (d0 - d1) + r0 + r1
        # extremes of d0 + r0 t + b t^2 + a t^3: r0 + 2 b t + 3 a t^2 = 0
        disc = b * b - 3.0 * a * r0
        if disc < 0.0:
            continue
        root = math.sqrt(disc)
        if a != 0.0:
            roots = ((-b - root) / (3.0 * a), (-b + root) / (3.0 * a))
        else:
            roots = (-r0 / (2.0 * b), -1.0)
        for t in roots:
            if 0.0 < t < earliest:
                value = d0 + t * (r0 + t * (b + t * a))
                if (value > 0.0) != (d0 > 0.0):
                    earliest = t
    return earliest


@kernel
def rk4_located(x, v, inv_mass, model, net_gravity, h, work, stiffness):
    """RK4 over ``h`` in place, the anchors in ``work.anchor[Z0]`` too, each change of a
    contact's mode, region or grip located (see the module): a step to the end of what is left,
    its changes, brief ones among them (:func:`_grazed`), the earliest located
    (:func:`_locate`), and on from just past it."""
    system = System(inv_mass, model, net_gravity, work, stiffness)
    rows, anchor, count = work.rows, work.anchor, work.contacts.count[0]
    start, end = Phase(rows[6], rows[7], anchor[Z0]), Phase(rows[8], rows[9], anchor[Z1])
    trial = Phase(rows[10], rows[11], anchor[ZLO])
    copy_rows(start.x, x)
    copy_rows(start.v, v)
    freeze(start.x, start.v, inv_mass, model, work, stiffness, start.z, True)
    left = h
    for _event in range(MAX_EVENTS + 1):
        _rk4(system, start, left, end)
        n_changed = _changes(system, end)
        hi = 1.0
        if _event < MAX_EVENTS:
            n_changed, hi = _grazed(system, start, end, trial, left, n_changed)
        if n_changed == 0 or _event == MAX_EVENTS:
            break
        work.events[0] += 1
        hi = _locate(system, start, end, trial, left, n_changed, hi)
        # just past the earliest event: its modes, regions and grips frozen from here
        copy_rows(start.x, end.x)
        copy_rows(start.v, end.v)
        copy_first_rows(start.z, end.z, count)
        freeze(start.x, start.v, inv_mass, model, work, stiffness, start.z, True)
        left *= 1.0 - hi
    copy_rows(x, end.x)
    copy_rows(v, end.v)
    copy_first_rows(start.z, end.z, count)


@kernel
def _grazed(system, start, end, trial, h, n_changed):
    """Look inside the step of ``h`` from ``start`` to ``end`` (where :func:`_changes` found
    ``n_changed`` changes) for a brief touch or separation (:func:`_graze`): if the trial step
    to its earliest instant finds changes, that trial is the end and the events are located
    within it. Returns (the changes, the fraction of the step they lie within)."""
    work = system.work
    peak = _graze(work, work.contacts.count[0], h)
    if peak < 1.0:
        _rk4(system, start, peak * h, trial)
        grazed = _changes(system, trial)
        if grazed > 0:
            _accept(work, end, trial)
            work.events[1] += 1
            return grazed, peak
        _changes(system, end)
    return n_changed, 1.0


@kernel
def _locate(system, start, end, trial, h, n_changed, hi):
    """The earliest event of the ``n_changed`` changed contacts within the first fraction
    ``hi`` of the step of ``h`` from ``start`` (``end``: the state there): Illinois' regula
    falsi on trial steps, bisecting where it stalls, each trial past the event taken as the
    end. Returns the fraction of the step just past the event."""
    work = system.work
    lo = 0.0
    f_lo, f_hi = _crossing(work, n_changed, False), _crossing(work, n_changed, True)
    side, stale, width = 0, 0, hi
    for _ in range(LOCATE_ITERATIONS):
        if hi - lo <= LOCATE_TOLERANCE:
            break
        if stale >= 3:
            theta, stale = 0.5 * (lo + hi), 0          # regula falsi stalled: bisect
        elif f_lo <= 0.0:
            theta = lo + LOCATE_TOLERANCE              # lo lies on the event within rounding
        else:
            theta = (lo * f_hi - hi * f_lo) / (f_hi - f_lo)
        theta = min(max(theta, lo + 0.5 * LOCATE_TOLERANCE), hi - 0.5 * LOCATE_TOLERANCE)
        _rk4(system, start, theta * h, trial)
        _values(system, trial)
        value = _crossing(work, n_changed, True)
        if value >= 0.0:  # not past the event: an overlap of exactly 0 still leaves the mode
            lo, f_lo = theta, value
            f_hi = 0.5 * f_hi if side == -1 else f_hi   # Illinois: the stale end's value halved
            side = -1
        else:
            hi, f_hi = theta, value
            _accept(work, end, trial)
            f_lo = 0.5 * f_lo if side == 1 else f_lo
            side = 1
        if hi - lo <= 0.5 * width:
            width, stale = hi - lo, 0
        else:
            stale += 1
    return hi


@inline_kernel
def _accept(work, end, trial):
    """Take the :class:`Phase` ``trial`` as the step's end, ``end``."""
    copy_rows(end.x, trial.x)
    copy_rows(end.v, trial.v)
    copy_first_rows(end.z, trial.z, work.contacts.count[0])
