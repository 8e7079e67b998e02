"""How many parts a compliant substep is split into: contact springs are stiff, and a part of
``h`` must keep ``h omega`` within an integrator's limit, ``omega`` the highest frequency the
listed contacts' springs can give the bodies (a bound: :func:`frequency_bound`). IMEX Euler's
explicit part treats those springs by symplectic Euler (stable below 2) and their dampers
implicitly: it takes :data:`IMEX_SPLIT_LIMIT`; the other integrators :data:`SPLIT_LIMIT`."""

from __future__ import annotations

import math

import numpy as np

from netgym.physics.compliant.contacts import BALL, PARTICLE, SEGMENT, feature
from netgym.physics.kernels.jit import inline_kernel, kernel

SPLIT_LIMIT = 1.0        # h omega at most, omega the contacts' highest frequency (bounded)
IMEX_SPLIT_LIMIT = 1.5   # IMEX Euler's contact springs: symplectic Euler, stable below 2


@inline_kernel
def _other_bodies(model, kind, b):
    """The bodies on a contact's other side (-1: none, static)."""
    if kind == PARTICLE or kind == BALL:
        return b, np.int64(-1)
    if kind == SEGMENT:
        return np.int64(model.segments[b, 0]), np.int64(model.segments[b, 1])
    return np.int64(-1), np.int64(-1)


@inline_kernel
def _load(load, k, share):
    """Add ``share`` to ``load[k]`` if ``k`` is a body."""
    if k >= 0:
        load[k] += share


@kernel
def frequency_bound(x, inv_mass, model, contacts, stiffness, load):
    """A bound (rad/s) on the highest frequency the listed contacts' springs give the bodies, as
    if every listed contact touched, at its penalty's weight now: block Gershgorin on
    ``M^-1/2 K M^-1/2``, where a contact adds ``k w g g^T`` along its normal (``g``: 1 on ``a``,
    minus the point's weights on its bodies), so that body ``b`` meets at most
    ``k w |g_b| sqrt(w_b) sum_b' |g_b'| sqrt(w_b')`` from it (``w``: inverse masses). ``load``:
    (n,) scratch."""
    count = contacts.count[0]
    for c in range(count):
        i, j = _other_bodies(model, contacts.kind[c], contacts.b[c])
        for k in (contacts.a[c], i, j):
            if k >= 0:
                load[k] = 0.0
    top = 0.0
    for c in range(count):
        a = contacts.a[c]
        ft = feature(x, model, contacts.kind[c], a, contacts.b[c])
        ra = math.sqrt(inv_mass[a])
        ri = ft.at.wi * math.sqrt(inv_mass[ft.at.i]) if ft.at.i >= 0 else 0.0
        rj = ft.at.wj * math.sqrt(inv_mass[ft.at.j]) if ft.at.j >= 0 else 0.0
        scale = ft.at.weight * (ra + ri + rj)
        _load(load, a, scale * ra)
        _load(load, ft.at.i, scale * ri)
        _load(load, ft.at.j, scale * rj)
    for c in range(count):
        i, j = _other_bodies(model, contacts.kind[c], contacts.b[c])
        top = max(top, load[contacts.a[c]], load[i] if i >= 0 else 0.0, load[j] if j >= 0 else 0.0)
    return math.sqrt(stiffness * top)


@kernel
def parts(x, inv_mass, model, h, stiffness, contacts, load, limit):
    """Parts of ``h`` such that each times :func:`frequency_bound` is at most ``limit``: 1 with
    no contact listed. ``load``: (n,) scratch."""
    if contacts.count[0] == 0:
        return 1
    omega = frequency_bound(x, inv_mass, model, contacts, stiffness, load)
    return max(1, int(math.ceil(h * omega / limit)))
