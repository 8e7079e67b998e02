"""Static friction of compliant contacts: a contact that slides slower than :data:`STICK_SPEED`
grips an elastic anchor, so that a resting ball holds where Coulomb's cone holds it instead of
creeping at the speed a regularised friction law needs to push back.

A touching contact's grip is one of

- STICK: its tangential force is an anchor's spring and damper, ``-(k_t z_t + c_t u_t)``, ``z``
  the tangential displacement since it gripped (``dz/dt = u_t``, the sliding velocity), ``k_t``
  a share :data:`STICK_SHARE` of its normal stiffness (at most the normal one, so the split's
  frequency bound holds) and ``c_t`` critical damping against the contact's effective mass;
- FAST: sliding, with regularised Coulomb friction
  (:func:`~netgym.physics.compliant.law.friction_factor`), too fast to grip at its last change;
- SLOW: broken away from its anchor, sliding as FAST does for :data:`REGRIP_TIME` (its clock
  in ``z``'s first component) unless it speeds up beyond :data:`STICK_SPEED` first;

FREE while it does not touch. A contact may grip (:func:`grippable`) where it slides slower
than :data:`STICK_SPEED` and its anchor's damper alone stays within Coulomb's cone at that
speed. The changes are events of the state: STICK to SLOW where the anchor's force leaves the
cone (or the normal force vanishes); FAST to STICK where it may grip; SLOW to FAST above
:data:`STICK_SPEED`, to STICK once its clock ran out where it may grip; an onset grips where
it may. A contact that grips anchors where it is (``z = 0``): its friction force falls from the
sliding one to its damper's, a jump RK4 locates like the others (an anchor stretched to keep
the sliding force would push the body back as the force relaxes: a ball that gripped in a hard
landing bounced back from it at 0.4 m/s). A slow one that breaks away grips again only after
its clock, so that no sequence of changes accumulates (as re-gripping at once would, as the
normal force vanishes). RK4 locates these events as it does the normal ones; the other
integrators change a grip at the start of a part.

A grip lives in its contact's slot of the state's ``anchors`` array, a row ``(z_x, z_y, z_z,
grip)`` per possible contact (:func:`~netgym.physics.compliant.contacts.possible_contacts`),
where it persists between steps, calls and checkpoints."""

from __future__ import annotations

import math

import numpy as np

from netgym.physics.compliant import law
from netgym.physics.compliant.contacts import BALL, NET_GROUND, PARTICLE, POLE, SEGMENT, possible_contacts
from netgym.physics.kernels.jit import inline_kernel, kernel

FREE, STICK, FAST, SLOW = 0, 1, 2, 3
STICK_SHARE = 0.5              # an anchor's stiffness, as a share of its contact's normal stiffness
STICK_DAMPING = 1.0            # an anchor's damping ratio against its contact's effective mass
STICK_SPEED = law.SLIP_SPEED   # m/s: a sliding contact grips when it slows below this
REGRIP_TIME = 0.005            # s: a contact that broke away slowly slides this long before it grips again
ANCHOR_COLUMNS = 4             # a slot: the anchor displacement (3) and the grip


@inline_kernel
def slot_of(model, n_balls, kind, a, b):
    """The slot of the contact (``kind``, ``a``, ``b``) (see
    :class:`~netgym.physics.compliant.contacts.ContactList`)."""
    n_net = model.n_net
    n_segments, n_poles = model.segments.shape[0], model.poles.radius.shape[0]
    per_ball = n_net + n_segments + n_poles + n_balls + 1
    if kind == NET_GROUND:
        return n_balls * per_ball + a
    base = (a - n_net) * per_ball
    if kind == PARTICLE:
        return base + b
    if kind == SEGMENT:
        return base + n_net + b
    if kind == POLE:
        return base + n_net + n_segments + b
    if kind == BALL:
        return base + n_net + n_segments + n_poles + (b - n_net)
    return base + per_ball - 1   # the ground


def relaid(anchors: np.ndarray, sizes: tuple[int, int, int], old_balls: int, kept: list[int]) -> np.ndarray:
    """``anchors`` of ``old_balls`` balls laid out for the balls ``kept`` (old ball indices in
    their new order, -1 for a new ball): each kept ball's slots, those between kept balls and
    the net's on the ground carried over. ``sizes``: the net's particles, segments and poles."""
    n_net, n_segments, n_poles = sizes
    fixed = n_net + n_segments + n_poles
    out = np.zeros((possible_contacts(n_net, n_segments, n_poles, len(kept)), ANCHOR_COLUMNS))
    old_per, new_per = fixed + old_balls + 1, fixed + len(kept) + 1
    for new, old in enumerate(kept):
        if old < 0:
            continue
        out[new * new_per:new * new_per + fixed] = anchors[old * old_per:old * old_per + fixed]
        out[new * new_per + new_per - 1] = anchors[old * old_per + old_per - 1]
        for other_new, other_old in enumerate(kept):
            if other_old >= 0:
                out[new * new_per + fixed + other_new] = anchors[old * old_per + fixed + other_old]
    out[len(kept) * new_per:] = anchors[old_balls * old_per:]
    return out


@kernel
def load(model, n_balls, contacts, anchors, z):
    """Each listed contact's slot into ``contacts.slot``, its grip into ``contacts.grip`` and its
    anchor displacement into row ``c`` of ``z``."""
    for c in range(contacts.count[0]):
        s = slot_of(model, n_balls, contacts.kind[c], contacts.a[c], contacts.b[c])
        contacts.slot[c] = s
        contacts.grip[c] = np.int8(anchors[s, 3])
        for k in range(3):
            z[c, k] = anchors[s, k]


@kernel
def store(contacts, anchors, z):
    """Each listed contact's grip and anchor displacement (row ``c`` of ``z``) into its slot; a
    FREE contact's as zeros."""
    for c in range(contacts.count[0]):
        s, grip = contacts.slot[c], contacts.grip[c]
        anchors[s, 3] = grip
        for k in range(3):
            anchors[s, k] = z[c, k] if grip != FREE else 0.0


@inline_kernel
def anchor_terms(stiffness, weight, w_eff):
    """(k_t, c_t): the anchor's stiffness (N/m) and damping (N s/m) of a contact of normal
    stiffness ``stiffness`` at penalty weight ``weight`` between bodies of inverse effective
    mass ``w_eff``."""
    k_t = STICK_SHARE * stiffness * weight
    if w_eff <= 0.0 or k_t <= 0.0:
        return k_t, 0.0
    return k_t, 2.0 * STICK_DAMPING * math.sqrt(k_t / w_eff)


@inline_kernel
def tangential(zx, zy, zz, nx, ny, nz):
    """The part of (zx, zy, zz) across the unit normal (nx, ny, nz)."""
    along = zx * nx + zy * ny + zz * nz
    return zx - along * nx, zy - along * ny, zz - along * nz


@inline_kernel
def anchor_force(k_t, c_t, z, c, nx, ny, nz, tx, ty, tz):
    """The anchor's force on ``a`` of contact ``c`` (anchor displacement row ``c`` of ``z``),
    sliding at (tx, ty, tz) across the normal (nx, ny, nz)."""
    zx, zy, zz = tangential(z[c, 0], z[c, 1], z[c, 2], nx, ny, nz)
    return -(k_t * zx + c_t * tx), -(k_t * zy + c_t * ty), -(k_t * zz + c_t * tz)


@inline_kernel
def grippable(slide, normal, friction, c_t):
    """Not positive where a contact sliding at ``slide`` could grip: slower than STICK_SPEED,
    and slow enough that its anchor's damper alone (``c_t slide``) stays within Coulomb's cone."""
    return max(slide - STICK_SPEED, c_t * slide - friction * normal)


@inline_kernel
def grip_value(grip, normal, friction, fx, fy, fz, slide, clock, c_t):
    """The grip's event function, its sign changing where the grip changes: a STICK contact's
    margin to Coulomb's cone ``friction * normal - |f|`` (f its anchor's force), a FAST one's
    :func:`grippable`, a SLOW one's ``min(STICK_SPEED - slide, max(REGRIP_TIME - clock,
    grippable))``, 1 where nothing can change (no friction; FAST or FREE without a normal force)."""
    if friction <= 0.0:
        return 1.0
    if grip == STICK:
        return friction * normal - math.sqrt(fx * fx + fy * fy + fz * fz)
    if grip == SLOW:
        return min(STICK_SPEED - slide, max(REGRIP_TIME - clock, grippable(slide, normal, friction, c_t)))
    if grip == FAST and normal != 0.0:
        return grippable(slide, normal, friction, c_t)
    return 1.0


@inline_kernel
def regrip(grip, touching, on, value, slide, could_grip):
    """The grip a contact takes at a change (a step's start or a located event) from ``grip``,
    its event ``value`` there (:func:`grip_value`): FREE when not ``touching``; a STICK contact
    whose normal force is off or whose value is not positive breaks away to SLOW; without a
    normal force nothing else changes; an onset (FREE) or a FAST contact grips if it
    ``could_grip`` (:func:`grippable`, and it has friction), else slides FAST; a SLOW one slides
    FAST above STICK_SPEED and grips once its clock ran out where it could."""
    if not touching:
        return FREE
    if grip == STICK:
        return STICK if on and value > 0.0 else SLOW
    if not on:
        return grip
    if grip == FREE or grip == FAST:
        return STICK if could_grip else FAST
    if slide >= STICK_SPEED:
        return FAST
    return STICK if value <= 0.0 else SLOW
