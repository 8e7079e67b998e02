"""The compliant model's contacts: the list of those that may act within a step, their forces
in a mode, their modes and event values, and the energy their springs hold.

A contact is a body ``a`` (a ball, or a net particle on the ground) against a point ``p`` on
the other side: a net particle, a ball, the interior of a structural segment (``p`` its closest
point, at parameter ``s``, weighted by :func:`~netgym.physics.compliant.law.segment_weight`), a
pole's axis or the ground. Its overlap is ``delta = reach - |x_a - p|``, its closing rate
``delta'`` (exact: the segment's closest point moves along the segment, across the normal).

A contact's mode is OFF (no overlap), ON (overlap, the damper pushing or idle) or CLAMPED
(overlap, the damper would pull: no normal force). Within a step of RK4 the modes of its start
are frozen and ON contacts take the law's smooth continuation
(:func:`~netgym.physics.compliant.law.free_normal_force`); the step is cut where a mode changes.
So is a pole contact's region: the closest point of a capsule's axis lies on its start cap, its
side or its end cap (the axis parameter below 0, within [0, 1], above 1); the distance is only
once differentiable across them, so a step freezes the region of its start (the side's distance
to the whole line, a cap's to its end point) and is cut where the parameter crosses 0 or 1.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from netgym.physics.compliant import law
from netgym.physics.kernels.jit import inline_kernel, kernel

PARTICLE, SEGMENT, POLE, BALL, GROUND, NET_GROUND = 0, 1, 2, 3, 4, 5
OFF, ON, CLAMPED = 0, 1, 2
START_CAP, SIDE, END_CAP = 0, 1, 2   # a pole contact's region
LIVE = -1   # no frozen mode or region: those the state is in


class ContactList(NamedTuple):
    """Contacts that may act within a step: ``kind`` (one of PARTICLE .. NET_GROUND), body ``a``,
    the other side ``b`` (a particle or ball row, a segment or pole index, -1 for the ground),
    their frozen ``mode`` and ``region`` (a pole's, LIVE elsewhere and outside RK4's steps),
    their ``grip`` (:mod:`~netgym.physics.compliant.grip`) and its ``slot`` in the state's
    anchors, and ``count`` (1,), the contacts in use."""

    kind: np.ndarray
    a: np.ndarray
    b: np.ndarray
    mode: np.ndarray
    region: np.ndarray
    count: np.ndarray
    grip: np.ndarray
    slot: np.ndarray


@inline_kernel
def possible_contacts(n_net, n_segments, n_poles, n_balls):
    """How many contacts a scene with these many net particles, segments, poles and balls can
    have: per ball one with each particle, segment, pole, ball and the ground, then one per
    particle with the ground."""
    return n_balls * (n_net + n_segments + n_poles + n_balls + 1) + n_net


@kernel
def new_list(x, model):
    """An empty :class:`ContactList` with room for every contact of a state like ``x``."""
    size = possible_contacts(model.n_net, model.segments.shape[0], model.poles.radius.shape[0],
                             x.shape[0] - model.n_net)
    return ContactList(np.empty(size, dtype=np.int64), np.empty(size, dtype=np.int64),
                       np.empty(size, dtype=np.int64), np.zeros(size, dtype=np.int8),
                       np.full(size, LIVE, dtype=np.int8), np.zeros(1, dtype=np.int64),
                       np.zeros(size, dtype=np.int8), np.zeros(size, dtype=np.int64))


NO_CONTACTS = ContactList(np.empty(0, dtype=np.int64), np.empty(0, dtype=np.int64), np.empty(0, dtype=np.int64),
                          np.zeros(0, dtype=np.int8), np.zeros(0, dtype=np.int8), np.zeros(1, dtype=np.int64),
                          np.zeros(0, dtype=np.int8), np.zeros(0, dtype=np.int64))
"""A :class:`ContactList` with room for none, shared: where a kernel takes one that impulse
contacts never fill (its count stays 0)."""


class Point(NamedTuple):
    """The point a contact touches: its bodies ``i``, ``j`` (-1: none, static) with weights ``wi``,
    ``wj`` of the point, the penalty's ``weight`` and its derivative ``slope`` along the segment's
    parameter ``s``, the segment's axis (ex, ey, ez) and its squared length ``l2`` (1 elsewhere)."""

    i: int
    wi: float
    j: int
    wj: float
    weight: float
    slope: float
    s: float
    ex: float
    ey: float
    ez: float
    l2: float


class Feature(NamedTuple):
    """Where a contact touches: overlap ``delta``, unit normal (nx, ny, nz) towards ``a``, and the
    :class:`Point` ``at`` on the other side."""

    delta: float
    nx: float
    ny: float
    nz: float
    at: Point


@inline_kernel
def _body(i):
    """The :class:`Point` of body ``i`` (a particle or a ball), or of a static one (-1): the
    whole point, of full penalty weight."""
    return Point(i, 1.0, -1, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0)


@inline_kernel
def _towards(dx, dy, dz, reach, p):
    """The :class:`Feature` of ``a`` at (dx, dy, dz) from the :class:`Point` ``p``, ``reach``
    (m) apart at touch."""
    dist = math.sqrt(dx * dx + dy * dy + dz * dz)
    inv = 1.0 / dist if dist > 1e-12 else 0.0
    return Feature(reach - dist, dx * inv, dy * inv, dz * inv if dist > 1e-12 else 1.0, p)


@kernel
def feature(x, model, kind, a, b, region=LIVE):
    """The :class:`Feature` of the contact (``kind``, ``a``, ``b``) in the positions ``x``; a
    pole's in its frozen ``region`` (its continuation past it), or in the one it is in (LIVE)."""
    radius = model.ball_radius
    xa, ya, za = x[a, 0], x[a, 1], x[a, 2]
    if kind == GROUND or kind == NET_GROUND:
        reach = radius if kind == GROUND else 0.0
        return Feature(reach - za, 0.0, 0.0, 1.0, Point(-1, 0.0, -1, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0))
    if kind == PARTICLE or kind == BALL:
        reach = radius if kind == PARTICLE else 2.0 * radius
        return _towards(xa - x[b, 0], ya - x[b, 1], za - x[b, 2], reach, _body(b))
    if kind == POLE:
        poles = model.poles
        px, py, pz = poles.start[b, 0], poles.start[b, 1], poles.start[b, 2]
        ex, ey, ez = poles.end[b, 0] - px, poles.end[b, 1] - py, poles.end[b, 2] - pz
        t = pole_parameter(x, model, a, b)
        if region == LIVE:
            t = min(max(t, 0.0), 1.0)
        elif region != SIDE:
            t = 0.0 if region == START_CAP else 1.0
        return _towards(xa - px - t * ex, ya - py - t * ey, za - pz - t * ez, radius + poles.radius[b], _body(-1))
    i, j = np.int64(model.segments[b, 0]), np.int64(model.segments[b, 1])
    ex, ey, ez = x[j, 0] - x[i, 0], x[j, 1] - x[i, 1], x[j, 2] - x[i, 2]
    l2 = ex * ex + ey * ey + ez * ez
    s = ((xa - x[i, 0]) * ex + (ya - x[i, 1]) * ey + (za - x[i, 2]) * ez) / l2
    weight, slope = law.segment_weight(s)
    return _towards(xa - x[i, 0] - s * ex, ya - x[i, 1] - s * ey, za - x[i, 2] - s * ez, radius,
                    Point(i, 1.0 - s, j, s, weight, slope, s, ex, ey, ez, l2))


@inline_kernel
def pole_parameter(x, model, a, b):
    """Where the body ``a`` projects onto pole ``b``'s axis: 0 at its start, 1 at its end."""
    poles = model.poles
    px, py, pz = poles.start[b, 0], poles.start[b, 1], poles.start[b, 2]
    ex, ey, ez = poles.end[b, 0] - px, poles.end[b, 1] - py, poles.end[b, 2] - pz
    return ((x[a, 0] - px) * ex + (x[a, 1] - py) * ey + (x[a, 2] - pz) * ez) / (ex * ex + ey * ey + ez * ez)


@inline_kernel
def region_of(parameter):
    """The region of a pole contact whose axis parameter is ``parameter``."""
    return START_CAP if parameter < 0.0 else (END_CAP if parameter > 1.0 else SIDE)


@inline_kernel
def region_value(region, parameter):
    """The event function of a pole contact frozen in ``region``: positive while its axis
    parameter stays in it, zero where it leaves."""
    if region == START_CAP:
        return -parameter
    if region == END_CAP:
        return parameter - 1.0
    return min(parameter, 1.0 - parameter)


@inline_kernel
def approach(v, a, f):
    """(ux, uy, uz, closing): the velocity of ``a`` relative to the point of :class:`Feature`
    ``f``, and the rate at which their overlap grows (its normal component, negated)."""
    ux, uy, uz = v[a, 0], v[a, 1], v[a, 2]
    if f.at.i >= 0:
        ux -= f.at.wi * v[f.at.i, 0]
        uy -= f.at.wi * v[f.at.i, 1]
        uz -= f.at.wi * v[f.at.i, 2]
    if f.at.j >= 0:
        ux -= f.at.wj * v[f.at.j, 0]
        uy -= f.at.wj * v[f.at.j, 1]
        uz -= f.at.wj * v[f.at.j, 2]
    return ux, uy, uz, -(ux * f.nx + uy * f.ny + uz * f.nz)


@kernel
def material(model, kind):
    """(restitution, friction) of a contact kind."""
    m = model.materials
    if kind == PARTICLE or kind == SEGMENT:
        return m.ball_net.restitution, m.ball_net.friction
    if kind == POLE:
        return m.ball_pole.restitution, m.ball_pole.friction
    if kind == BALL:
        return m.ball_ball.restitution, m.ball_ball.friction
    if kind == GROUND:
        return m.ball_ground.restitution, m.ball_ground.friction
    return m.net_ground.restitution, m.net_ground.friction


@kernel
def dampings(model):
    """The damping ``d`` (s/m) of every contact kind, from its restitution (an array by kind)."""
    out = np.empty(6)
    for kind in range(6):
        out[kind] = law.dissipation(material(model, kind)[0], law.REFERENCE_SPEED)
    return out


@inline_kernel
def _push(f, k, fx, fy, fz, scale):
    """Add ``scale * (fx, fy, fz)`` to row ``k`` of ``f`` if ``k`` is a body."""
    if k >= 0:
        f[k, 0] += scale * fx
        f[k, 1] += scale * fy
        f[k, 2] += scale * fz


@inline_kernel
def spread(f, a, ft, fx, fy, fz):
    """Add (fx, fy, fz) to ``a`` and its reaction to the point's bodies, by their weights."""
    _push(f, a, fx, fy, fz, 1.0)
    _push(f, ft.at.i, fx, fy, fz, -ft.at.wi)
    _push(f, ft.at.j, fx, fy, fz, -ft.at.wj)


@inline_kernel
def mode_of(delta, rate, damping):
    """The mode a contact is in: OFF without overlap, CLAMPED where its damper would pull, else ON."""
    if delta <= 0.0:
        return OFF
    return ON if 1.0 + damping * rate > 0.0 else CLAMPED


@inline_kernel
def segment_slope_force(f, x, a, ft, stiffness):
    """The force of the segment penalty's weight changing along the segment: minus the gradient
    of ``stiffness delta^2 w(s) / 2`` through ``s``, on the ball and the segment's two ends."""
    scale = -0.5 * stiffness * ft.delta * ft.delta * ft.at.slope / ft.at.l2
    i = ft.at.i
    ax, ay, az = x[a, 0] - x[i, 0], x[a, 1] - x[i, 1], x[a, 2] - x[i, 2]
    # ds/dx_a = e / l2; ds/dx_j = (a - 2 s e) / l2; ds/dx_i = -(both)
    gx, gy, gz = ax - 2.0 * ft.at.s * ft.at.ex, ay - 2.0 * ft.at.s * ft.at.ey, az - 2.0 * ft.at.s * ft.at.ez
    _push(f, a, ft.at.ex, ft.at.ey, ft.at.ez, scale)
    _push(f, ft.at.j, gx, gy, gz, scale)
    _push(f, i, ft.at.ex + gx, ft.at.ey + gy, ft.at.ez + gz, -scale)


@kernel
def event_values(x, v, model, contacts, damping, touch, on, rate, side):
    """Each listed contact's event functions in the state, in its frozen region: its overlap
    (``touch``) and ``min(overlap, 1 + d rate)`` (``on``): OFF where touch <= 0, ON where on > 0,
    else CLAMPED; the overlap's ``rate`` of change (m/s); and a pole's axis parameter (``side``,
    0.5 for the other kinds)."""
    for c in range(contacts.count[0]):
        kind, a, b = contacts.kind[c], contacts.a[c], contacts.b[c]
        ft = feature(x, model, kind, a, b, contacts.region[c])
        ux, uy, uz, closing = approach(v, a, ft)
        touch[c] = ft.delta
        on[c] = min(ft.delta, 1.0 + damping[kind] * closing)
        rate[c] = closing
        side[c] = pole_parameter(x, model, a, b) if kind == POLE else 0.5


@kernel
def modes_from(touch, on, count, mode):
    """Write into ``mode`` the mode each of ``count`` contacts is in, from its event values."""
    for c in range(count):
        mode[c] = OFF if touch[c] <= 0.0 else (ON if on[c] > 0.0 else CLAMPED)


@kernel
def regions_from(side, contacts, mode, region):
    """Write into ``region`` the region each listed pole contact in ``mode`` other than OFF is
    in, from its axis parameter ``side``; LIVE for the rest (an OFF contact's onset is found
    on its true distance)."""
    for c in range(contacts.count[0]):
        region[c] = region_of(side[c]) if contacts.kind[c] == POLE and mode[c] != OFF else LIVE


@kernel
def potential(x, model, contacts, stiffness):
    """The energy (J) the listed contacts' springs hold: ``stiffness w delta^2 / 2`` each."""
    total = 0.0
    for c in range(contacts.count[0]):
        ft = feature(x, model, contacts.kind[c], contacts.a[c], contacts.b[c])
        if ft.delta > 0.0:
            total += 0.5 * stiffness * ft.at.weight * ft.delta * ft.delta
    return total


@inline_kernel
def _add(contacts, kind, a, b):
    """List the contact (``kind``, ``a``, ``b``)."""
    c = contacts.count[0]
    contacts.kind[c], contacts.a[c], contacts.b[c], contacts.region[c] = kind, a, b, LIVE
    contacts.count[0] = c + 1


@kernel
def gather(x, model, margin, contacts):
    """List every contact whose overlap is above ``-margin`` (m) now: those that may act before
    the bodies have moved ``margin`` closer. Segments by the distance to their closed span."""
    contacts.count[0] = 0
    n_net, radius = model.n_net, model.ball_radius
    reach = radius + margin
    for a in range(n_net, x.shape[0]):
        for p in range(n_net):
            if _within(x, p, p, a, reach) and feature(x, model, PARTICLE, a, p).delta > -margin:
                _add(contacts, PARTICLE, a, p)
        for s in range(model.segments.shape[0]):
            i, j = model.segments[s, 0], model.segments[s, 1]
            if _within(x, i, j, a, reach) and _segment_gap(x, i, j, a) < reach:
                _add(contacts, SEGMENT, a, s)
        for p in range(model.poles.radius.shape[0]):
            if feature(x, model, POLE, a, p).delta > -margin:
                _add(contacts, POLE, a, p)
        for other in range(a + 1, x.shape[0]):
            if feature(x, model, BALL, a, other).delta > -margin:
                _add(contacts, BALL, a, other)
        if x[a, 2] < radius + margin:
            _add(contacts, GROUND, a, -1)
    for p in range(n_net):
        if x[p, 2] < margin:
            _add(contacts, NET_GROUND, p, -1)


@inline_kernel
def _within(x, i, j, a, reach):
    """Whether the box around the span i-j comes within ``reach`` of ``a`` along every axis:
    true of every span within ``reach`` of it, a cheap test before the exact one."""
    for c in range(3):
        if min(x[i, c], x[j, c]) > x[a, c] + reach or max(x[i, c], x[j, c]) < x[a, c] - reach:
            return False
    return True


@inline_kernel
def _segment_gap(x, i, j, a):
    """Distance from ``a`` to the closed segment i-j."""
    ex, ey, ez = x[j, 0] - x[i, 0], x[j, 1] - x[i, 1], x[j, 2] - x[i, 2]
    s = ((x[a, 0] - x[i, 0]) * ex + (x[a, 1] - x[i, 1]) * ey + (x[a, 2] - x[i, 2]) * ez) / (ex * ex + ey * ey + ez * ez)
    s = min(max(s, 0.0), 1.0)
    dx, dy, dz = x[a, 0] - x[i, 0] - s * ex, x[a, 1] - x[i, 1] - s * ey, x[a, 2] - x[i, 2] - s * ez
    return math.sqrt(dx * dx + dy * dy + dz * dz)
