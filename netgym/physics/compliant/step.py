"""A substep of the compliant model: every body's motion under the smooth forces and the
contacts' (:mod:`~netgym.physics.compliant.contacts`), by the integrator the settings are made for.

- RK4 freezes the contacts' modes (and touching pole contacts' regions) at a step's start and
  integrates the smooth system they give; where the step's end finds a mode or region
  changed, it finds the earliest instant a changed contact's event function crosses zero
  (Illinois' regula falsi on RK4 steps of a fraction of the step, bisecting where it stalls),
  steps to just past it, takes the modes there and goes on. Between events the forces are
  smooth, so RK4 keeps its fourth order through contact.
- Explicit and symplectic Euler take the forces of the mode the state is in.
- IMEX Euler takes the contacts' springs explicitly and their dampers and friction implicitly
  (each contact's normal and then tangential velocity solved by backward Euler, in list order),
  then the net's smooth forces as :func:`~netgym.physics.kernels.integrators.step_imex_euler`.

Contact springs are stiff: while any contact is listed, a substep is split further so that
``h omega <= 1``, ``omega`` a bound on the highest frequency the listed contacts' springs give
the bodies (:func:`~netgym.physics.compliant.split.frequency_bound`); ``<= 1.5`` for IMEX
Euler, whose explicit part treats those springs by symplectic Euler (stable below 2) and
their dampers implicitly.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np
from numba.core.errors import NumbaTypeError
from numba.extending import overload

from netgym.kinds import Integrator
from netgym.physics.compliant import contacts as cl
from netgym.physics.compliant import law, split
from netgym.physics.kernels.air import _acceleration as air_acceleration
from netgym.physics.kernels.forces import accelerations
from netgym.physics.kernels.integrators import (euler_update, rk4_accumulate, rk4_combine, rk4_stage_state,
                                                step_imex_euler)
from netgym.physics.kernels.jit import inline_kernel, kernel
from netgym.physics.kernels.rows import copy_rows

MAX_EVENTS = 256          # events located in one step at most; later ones are stepped over
LOCATE_ITERATIONS = 100   # trial steps at most per event
LOCATE_TOLERANCE = 1e-13  # of the step: an event's bracket narrower than this is located


class Work(NamedTuple):
    """Scratch of a compliant substep: the contact list, its event values at the start, end
    and a trial (``touch0``, ``on0`` ...), the trial's modes, the changed contacts, and (n, 3)
    rows: RK4's stages and the states of the event search; ``events``: the events located and
    the brief contacts (grazes) among them, counted; ``damping`` by contact kind; ``load``: (n,)
    scratch of the split's frequency bound; the pole contacts' axis parameters at the start and
    the end or a trial (``side0``, ``side1``) and the regions of the latter."""

    contacts: cl.ContactList
    touch0: np.ndarray
    on0: np.ndarray
    touch1: np.ndarray
    on1: np.ndarray
    rate0: np.ndarray
    rate1: np.ndarray
    modes: np.ndarray
    changed: np.ndarray
    rows: np.ndarray
    events: np.ndarray
    damping: np.ndarray
    load: np.ndarray
    side0: np.ndarray
    side1: np.ndarray
    regions: np.ndarray


@kernel
def new_work(x, model):
    """Scratch of :func:`compliant_step` for states like ``x``."""
    contacts = cl.new_list(x, model)
    size = contacts.kind.shape[0]
    return Work(contacts, np.empty(size), np.empty(size), np.empty(size), np.empty(size), np.empty(size),
                np.empty(size), np.empty(size, dtype=np.int8), np.empty(size, dtype=np.int64),
                np.empty((13, x.shape[0], 3)), np.zeros(2, dtype=np.int64), cl.dampings(model),
                np.zeros(x.shape[0]), np.empty(size), np.empty(size), np.empty(size, dtype=np.int8))


@kernel
def rhs(x, v, inv_mass, model, net_gravity, contacts, stiffness, damping, frozen, f, a):
    """Write into ``a`` every body's acceleration: the net's springs, weight and air drag, the
    balls' weight and air, and the listed contacts (in their frozen modes if ``frozen``);
    ``f``: scratch rows for the contact forces."""
    accelerations(x, v, inv_mass, net_gravity, model.drag, model.springs, a)
    for k in range(model.n_net, x.shape[0]):
        a[k, 0], a[k, 1], a[k, 2] = _ball_acceleration(v, k, model)
    f[:] = 0.0
    cl.add_forces(x, v, model, contacts, stiffness, damping, frozen, f)
    for k in range(x.shape[0]):
        w = inv_mass[k]
        for c in range(3):
            a[k, c] += w * f[k, c]


@inline_kernel
def _ball_acceleration(v, k, model):
    """A ball's acceleration by its weight and, in a scene with air, the drag towards the wind."""
    if model.ball_drag > 0.0:
        return air_acceleration(v[k, 0], v[k, 1], v[k, 2], model.gravity, model.ball_drag, model.wind)
    return 0.0, 0.0, model.gravity


@kernel
def _rk4(x0, v0, inv_mass, model, net_gravity, h, work, stiffness, damping, x1, v1):
    """One classical RK4 step of ``h`` from (x0, v0) into (x1, v1), the contacts' modes frozen."""
    rows = work.rows
    xs, vs, a, xsum, vsum, f = rows[0], rows[1], rows[2], rows[3], rows[4], rows[5]
    rhs(x0, v0, inv_mass, model, net_gravity, work.contacts, stiffness, damping, True, f, a)
    copy_rows(xsum, v0)
    copy_rows(vsum, a)
    for stage in range(3):
        rk4_stage_state(x0, v0, a, xs, vs, stage, h)
        rhs(xs, vs, inv_mass, model, net_gravity, work.contacts, stiffness, damping, True, f, a)
        rk4_accumulate(xsum, vsum, vs, a, stage)
    rk4_combine(x0, v0, xsum, vsum, h, x1, v1)


@kernel
def _changes(x, v, model, work, damping):
    """Event values of the listed contacts in (x, v) into ``touch1``, ``on1``, ``side1``, their
    modes and regions into ``modes`` and ``regions``, and the contacts whose mode or region
    differs from the frozen one into ``changed``; returns how many did."""
    contacts, count = work.contacts, work.contacts.count[0]
    cl.event_values(x, v, model, contacts, damping, work.touch1, work.on1, work.rate1, work.side1)
    cl.modes_from(work.touch1, work.on1, count, work.modes)
    cl.regions_from(work.side1, contacts, work.modes, work.regions)
    n = 0
    for c in range(count):
        if work.modes[c] != contacts.mode[c] or work.regions[c] != contacts.region[c]:
            work.changed[n] = c
            n += 1
    return n


@inline_kernel
def _crossing(work, n_changed, end):
    """The least of the changed contacts' event functions, each signed to be positive at the
    step's start (values of the start in ``touch0``, ``on0``, ``side0``); of the state whose
    values are in ``touch1``, ``on1``, ``side1`` if ``end``, of the start otherwise. Negative:
    some mode or region changed."""
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
def _freeze(x, v, model, work, damping):
    """Freeze the listed contacts' modes and pole regions at (x, v), their event values there
    (in the regions the state is in) into ``touch0``, ``on0``, ``rate0``, ``side0``."""
    contacts, count = work.contacts, work.contacts.count[0]
    contacts.region[:count] = cl.LIVE
    cl.event_values(x, v, model, contacts, damping, work.touch0, work.on0, work.rate0, work.side0)
    cl.modes_from(work.touch0, work.on0, count, contacts.mode)
    cl.regions_from(work.side0, contacts, contacts.mode, contacts.region)


@kernel
def _rk4_located(x, v, inv_mass, model, net_gravity, h, work, stiffness, damping):
    """RK4 over ``h`` in place, each change of a contact's mode or region located (see the module)."""
    rows = work.rows
    x0, v0, x1, v1, xlo, vlo = rows[6], rows[7], rows[8], rows[9], rows[10], rows[11]
    contacts, count = work.contacts, work.contacts.count[0]
    copy_rows(x0, x)
    copy_rows(v0, v)
    _freeze(x0, v0, model, work, damping)
    left = h
    for _event in range(MAX_EVENTS + 1):
        _rk4(x0, v0, inv_mass, model, net_gravity, left, work, stiffness, damping, x1, v1)
        n_changed = _changes(x1, v1, model, work, damping)
        hi = 1.0
        if _event < MAX_EVENTS:
            peak = _graze(work, count, left)
            if peak < 1.0:
                _rk4(x0, v0, inv_mass, model, net_gravity, peak * left, work, stiffness, damping, xlo, vlo)
                grazed = _changes(xlo, vlo, model, work, damping)
                if grazed > 0:
                    n_changed, hi = grazed, peak
                    copy_rows(x1, xlo)
                    copy_rows(v1, vlo)
                    work.events[1] += 1
                else:
                    _changes(x1, v1, model, work, damping)
        if n_changed == 0 or _event == MAX_EVENTS:
            break
        work.events[0] += 1
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
            _rk4(x0, v0, inv_mass, model, net_gravity, theta * left, work, stiffness, damping, xlo, vlo)
            cl.event_values(xlo, vlo, model, contacts, damping, work.touch1, work.on1, work.rate1, work.side1)
            value = _crossing(work, n_changed, True)
            if value >= 0.0:  # not past the event: an overlap of exactly 0 still leaves the mode
                lo, f_lo = theta, value
                f_hi = 0.5 * f_hi if side == -1 else f_hi   # Illinois: the stale end's value halved
                side = -1
            else:
                hi, f_hi = theta, value
                copy_rows(x1, xlo)
                copy_rows(v1, vlo)
                f_lo = 0.5 * f_lo if side == 1 else f_lo
                side = 1
            if hi - lo <= 0.5 * width:
                width, stale = hi - lo, 0
            else:
                stale += 1
        # just past the earliest event: its modes and regions frozen from here
        copy_rows(x0, x1)
        copy_rows(v0, v1)
        _freeze(x0, v0, model, work, damping)
        left *= 1.0 - hi
    copy_rows(x, x1)
    copy_rows(v, v1)


@kernel
def _euler(x, v, inv_mass, model, net_gravity, h, work, stiffness, damping, symplectic):
    """Explicit (x by the old velocity) or symplectic (by the new) Euler over ``h``, the
    contacts in the mode the state is in."""
    rows = work.rows
    a, f = rows[0], rows[1]
    rhs(x, v, inv_mass, model, net_gravity, work.contacts, stiffness, damping, False, f, a)
    euler_update(x, v, a, h, symplectic)


@inline_kernel
def _impulse(v, inv_mass, a, ft, jx, jy, jz):
    """Apply the impulse (jx, jy, jz) to ``a`` and its reaction to the point's bodies."""
    for k, share in ((a, 1.0), (ft.i, -ft.wi), (ft.j, -ft.wj)):
        if k >= 0:
            w = inv_mass[k] * share
            v[k, 0] += w * jx
            v[k, 1] += w * jy
            v[k, 2] += w * jz


@kernel
def _contact_impulses(x, v, inv_mass, model, h, contacts, stiffness, damping):
    """IMEX Euler's contacts over ``h``, at the positions of its start, in list order: the
    spring and the damper of each along its normal together by backward Euler on its closing
    rate (no pull), then its friction by backward Euler on its sliding velocity."""
    for c in range(contacts.count[0]):
        kind, a = contacts.kind[c], contacts.a[c]
        ft = cl.feature(x, model, kind, a, contacts.b[c])
        if ft.delta <= 0.0 or ft.weight == 0.0:
            continue
        w_eff = inv_mass[a] + (ft.wi * ft.wi * inv_mass[ft.i] if ft.i >= 0 else 0.0) \
            + (ft.wj * ft.wj * inv_mass[ft.j] if ft.j >= 0 else 0.0)
        hk = h * stiffness * ft.weight * ft.delta
        d = damping[kind]
        _, _, _, closing = cl.approach(v, a, ft)
        after = (closing - w_eff * hk) / (1.0 + w_eff * hk * d)
        push = max(0.0, hk * (1.0 + d * after))
        _impulse(v, inv_mass, a, ft, push * ft.nx, push * ft.ny, push * ft.nz)
        friction = cl.material(model, kind)[1]
        if friction > 0.0 and push > 0.0 and w_eff > 0.0:
            ux, uy, uz, closing = cl.approach(v, a, ft)
            tx, ty, tz = ux + closing * ft.nx, uy + closing * ft.ny, uz + closing * ft.nz
            factor = law.friction_factor(friction, push / h, math.sqrt(tx * tx + ty * ty + tz * tz))
            keep = 1.0 / (1.0 + h * factor * w_eff)
            scale = -(1.0 - keep) / w_eff
            _impulse(v, inv_mass, a, ft, scale * tx, scale * ty, scale * tz)


@kernel
def _imex(x, v, inv_mass, model, net_gravity, h, work, stiffness, damping, scratch):
    """IMEX Euler over ``h`` (see the module); the balls' own weight and air explicitly."""
    rows = work.rows
    f, start = rows[0], rows[1]
    contacts, n_net = work.contacts, model.n_net
    copy_rows(start, x)
    f[:] = 0.0
    for c in range(contacts.count[0]):
        ft = cl.feature(x, model, contacts.kind[c], contacts.a[c], contacts.b[c])
        if ft.delta > 0.0 and ft.slope != 0.0:
            cl.segment_slope_force(f, x, contacts.a[c], ft, stiffness)
    for k in range(x.shape[0]):
        for c in range(3):
            v[k, c] += h * inv_mass[k] * f[k, c]
    _contact_impulses(x, v, inv_mass, model, h, contacts, stiffness, damping)
    balls = rows[2][n_net:]
    copy_rows(balls, v[n_net:])
    step_imex_euler(x, v, inv_mass, net_gravity, model.drag, model.springs, h, scratch)
    for k in range(n_net, x.shape[0]):
        ax, ay, az = _ball_acceleration(balls, k - n_net, model)
        v[k, 0], v[k, 1], v[k, 2] = balls[k - n_net, 0] + h * ax, balls[k - n_net, 1] + h * ay, \
            balls[k - n_net, 2] + h * az
        for c in range(3):
            x[k, c] = start[k, c] + h * v[k, c]


@kernel
def _margin(v, h):
    """How much closer two bodies may come within ``h``: twice the two fastest speeds' sum over
    it, and a centimetre."""
    first, second = 0.0, 0.0
    for k in range(v.shape[0]):
        s = math.sqrt(v[k, 0] ** 2 + v[k, 1] ** 2 + v[k, 2] ** 2)
        if s > first:
            first, second = s, first
        elif s > second:
            second = s
    return 2.0 * h * (first + second) + 0.01


def compliant_step(settings, x, v, inv_mass, model, net_gravity, h, scratch, work):
    """One substep of ``h`` of the compliant model with the integrator of ``settings``; the
    net's weight ``net_gravity``; ``scratch``: the integrators'
    :class:`~netgym.physics.kernels.integrators.Scratch`; ``work``: :func:`new_work`'s. Returns
    the parts the contacts' springs split it into. For numba kernels only: the integrator is
    chosen when the calling kernel compiles."""
    raise TypeError("compliant_step runs inside numba kernels only")


@overload(compliant_step, jit_options={"error_model": "numpy"})
def _compliant_step(settings, x, v, inv_mass, model, net_gravity, h, scratch, work):
    """The implementation of :func:`compliant_step` for the integrator of ``settings``' type."""
    integrator = getattr(getattr(settings, "instance_class", None), "INTEGRATOR", None)
    if integrator == Integrator.IMPLICIT_EULER or integrator is None:
        raise NumbaTypeError(f"the compliant contact model has no step for {integrator}")

    limit = split.IMEX_SPLIT_LIMIT if integrator == Integrator.IMEX_EULER else split.SPLIT_LIMIT

    def step(settings, x, v, inv_mass, model, net_gravity, h, scratch, work):
        stiffness, damping = settings.contact_stiffness, work.damping
        cl.gather(x, model, _margin(v, h), work.contacts)
        parts = split.parts(x, inv_mass, model, h, stiffness, work.contacts, work.load, limit)
        part = h / parts
        for p in range(parts):
            if p > 0:
                cl.gather(x, model, _margin(v, part), work.contacts)
            if integrator == Integrator.RK4:
                _rk4_located(x, v, inv_mass, model, net_gravity, part, work, stiffness, damping)
            elif integrator == Integrator.IMEX_EULER:
                _imex(x, v, inv_mass, model, net_gravity, part, work, stiffness, damping, scratch)
            else:
                _euler(x, v, inv_mass, model, net_gravity, part, work, stiffness, damping,
                       integrator == Integrator.SYMPLECTIC_EULER)
        return parts
    return step
