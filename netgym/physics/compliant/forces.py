"""The compliant model's contact forces: each listed contact's normal force in its mode, its
friction by its grip (:mod:`~netgym.physics.compliant.grip`), the grips' event functions and
their changes."""

from __future__ import annotations

import math
from typing import NamedTuple

from netgym.physics.compliant import contacts as cl
from netgym.physics.compliant import grip, law
from netgym.physics.compliant.contacts import Feature
from netgym.physics.kernels.jit import inline_kernel, kernel


@inline_kernel
def inverse_effective_mass(inv_mass, a, ft):
    """The inverse mass a contact's force meets: ``a``'s and the point's bodies' by their weights squared."""
    w = inv_mass[a]
    if ft.at.i >= 0:
        w += ft.at.wi * ft.at.wi * inv_mass[ft.at.i]
    if ft.at.j >= 0:
        w += ft.at.wj * ft.at.wj * inv_mass[ft.at.j]
    return w


class Tangent(NamedTuple):
    """A contact in a mode: its :class:`Feature` ``ft``, ``mode``, ``normal`` force (N), sliding
    velocity (tx, ty, tz) and speed ``slide``, ``friction`` coefficient and, for its grip, the
    anchor's stiffness ``k_t`` and damping ``c_t``."""

    ft: Feature
    mode: int
    normal: float
    tx: float
    ty: float
    tz: float
    slide: float
    friction: float
    k_t: float
    c_t: float


@inline_kernel
def tangent(x, v, inv_mass, model, contacts, c, stiffness, damping, frozen):
    """The :class:`Tangent` of listed contact ``c``: in its frozen mode and region if ``frozen``
    (ON contacts by the law's continuation), else in those of the state. ``damping``: by kind."""
    kind, a = contacts.kind[c], contacts.a[c]
    ft = cl.feature(x, model, kind, a, contacts.b[c], contacts.region[c] if frozen else cl.LIVE)
    ux, uy, uz, closing = cl.approach(v, a, ft)
    d = damping[kind]
    mode = contacts.mode[c] if frozen else cl.mode_of(ft.delta, closing, d)
    normal = law.free_normal_force(stiffness * ft.at.weight, ft.delta, closing, d) if mode == cl.ON else 0.0
    tx, ty, tz = ux + closing * ft.nx, uy + closing * ft.ny, uz + closing * ft.nz
    k_t, c_t = grip.anchor_terms(stiffness, ft.at.weight, inverse_effective_mass(inv_mass, a, ft))
    return Tangent(ft, mode, normal, tx, ty, tz, math.sqrt(tx * tx + ty * ty + tz * tz), cl.material(model, kind)[1],
                   k_t, c_t)


@kernel
def add_forces(x, v, inv_mass, model, contacts, stiffness, damping, frozen, f, anchor):
    """Add every listed contact's force to ``f`` (n, 3): in its frozen mode and region if
    ``frozen`` (ON contacts by the law's continuation), else in those of the state; its friction
    by its grip, a STICK contact's from its anchor displacement (row ``c`` of ``anchor[0]``),
    whose rate of change it writes into ``anchor[1]`` (a SLOW one's clock's, 0 elsewhere).
    ``damping``: by kind."""
    z, rate = anchor[0], anchor[1]
    for c in range(contacts.count[0]):
        rate[c, 0], rate[c, 1], rate[c, 2] = (1.0 if contacts.grip[c] == grip.SLOW else 0.0), 0.0, 0.0  # its clock
        tg = tangent(x, v, inv_mass, model, contacts, c, stiffness, damping, frozen)
        if tg.mode == cl.OFF:
            continue
        a, ft, normal = contacts.a[c], tg.ft, tg.normal
        cl.spread(f, a, ft, normal * ft.nx, normal * ft.ny, normal * ft.nz)
        if ft.at.slope != 0.0:
            cl.segment_slope_force(f, x, a, ft, stiffness)
        if tg.friction <= 0.0 or normal == 0.0:  # frozen ON: the continuation's, up to the event
            continue
        if contacts.grip[c] == grip.STICK:
            fx, fy, fz = _anchor_force(tg, z, c)
            cl.spread(f, a, ft, fx, fy, fz)
            rate[c, 0], rate[c, 1], rate[c, 2] = tg.tx, tg.ty, tg.tz
        else:
            drag = law.friction_factor(tg.friction, normal, tg.slide)
            cl.spread(f, a, ft, -drag * tg.tx, -drag * tg.ty, -drag * tg.tz)


@inline_kernel
def _anchor_force(tg, z, c):
    """The anchor's force on ``a`` of contact ``c`` of :class:`Tangent` ``tg`` (row ``c`` of ``z``)."""
    ft = tg.ft
    return grip.anchor_force(tg.k_t, tg.c_t, z, c, ft.nx, ft.ny, ft.nz, tg.tx, tg.ty, tg.tz)


@inline_kernel
def _grip_value(tg, g, z, c):
    """:func:`~netgym.physics.compliant.grip.grip_value` of contact ``c`` of :class:`Tangent`
    ``tg`` in the grip ``g``."""
    fx, fy, fz = _anchor_force(tg, z, c) if g == grip.STICK else (0.0, 0.0, 0.0)
    return grip.grip_value(g, tg.normal, tg.friction, fx, fy, fz, tg.slide, z[c, 0], tg.c_t)


@kernel
def grip_values(x, v, inv_mass, model, contacts, z, stiffness, damping, value):
    """Each listed contact's grip event function (:func:`~netgym.physics.compliant.grip.grip_value`)
    into ``value``, in its frozen mode and region; ``z``: the anchor displacements."""
    for c in range(contacts.count[0]):
        tg = tangent(x, v, inv_mass, model, contacts, c, stiffness, damping, True)
        value[c] = _grip_value(tg, contacts.grip[c], z, c)


@kernel
def regrip(x, v, inv_mass, model, contacts, z, stiffness, damping, breaks):
    """Give each listed contact, its modes and regions frozen at (x, v), the grip it takes there
    (:func:`~netgym.physics.compliant.grip.regrip`), one that grips its anchor where it is.
    Unless ``breaks`` (IMEX Euler, whose impulses break a grip where holding it would leave the
    cone), a gripping contact holds while it touches: what pushes is its overlap, not the
    explicit law's mode."""
    for c in range(contacts.count[0]):
        tg = tangent(x, v, inv_mass, model, contacts, c, stiffness, damping, True)
        old = contacts.grip[c]
        value = _grip_value(tg, old, z, c) if breaks or old != grip.STICK else 1.0
        on = tg.mode == cl.ON if breaks else tg.mode != cl.OFF
        could_grip = tg.friction > 0.0 and grip.grippable(tg.slide, tg.normal, tg.friction, tg.c_t) <= 0.0
        new = grip.regrip(old, tg.mode != cl.OFF, on, value, tg.slide, could_grip)
        if new != old:   # a new anchor where it is, or a SLOW one's clock
            z[c, 0], z[c, 1], z[c, 2] = 0.0, 0.0, 0.0
        contacts.grip[c] = new
