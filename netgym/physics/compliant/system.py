"""What every compliant integrator shares: its scratch (:class:`Work`), the accelerations and
anchor rates of the whole system (:func:`rhs`), and the freezing of the listed contacts' modes,
regions and grips at a state (:func:`freeze`)."""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from netgym.physics.compliant import contacts as cl
from netgym.physics.compliant import forces, grip
from netgym.physics.kernels.air import _acceleration as air_acceleration
from netgym.physics.kernels.smooth_forces import accelerations
from netgym.physics.kernels.jit import inline_kernel, kernel

Z, RATE, Z0, ZSUM, Z1, ZLO = 0, 1, 2, 3, 4, 5   # rows of Work.anchor
ANCHOR_ROWS = 6


class Work(NamedTuple):
    """Scratch of a compliant substep: the contact list, its event values at the start, end
    and a trial (``touch0``, ``on0`` ...), the trial's modes, the changed contacts, and (n, 3)
    rows: RK4's stages and the states of the event search; ``events``: the events located and
    the brief contacts (grazes) among them, counted; ``damping`` by contact kind; ``load``: (n,)
    scratch of the split's frequency bound; the pole contacts' axis parameters at the start and
    the end or a trial (``side0``, ``side1``) and the regions of the latter; the listed contacts'
    anchor displacements and their rates by stage (``anchor``, rows Z .. ZLO), their grips'
    event values at the start and the end or a trial (``grip0``, ``grip1``); ``anchors``: the
    state's slots (:mod:`~netgym.physics.compliant.grip`)."""

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
    anchor: np.ndarray
    grip0: np.ndarray
    grip1: np.ndarray
    anchors: np.ndarray


@kernel
def new_work(x, model, anchors):
    """Scratch of a compliant substep for states like ``x``, keeping grips in ``anchors`` (the
    state's slots; where it has not as many as ``x`` needs, in slots of its own that last as
    long as the scratch)."""
    contacts = cl.new_list(x, model)
    size = contacts.kind.shape[0]
    if anchors.shape[0] != size:   # a slot per possible contact
        anchors = np.zeros((size, grip.ANCHOR_COLUMNS))
    return Work(contacts, np.empty(size), np.empty(size), np.empty(size), np.empty(size), np.empty(size),
                np.empty(size), np.empty(size, dtype=np.int8), np.empty(size, dtype=np.int64),
                np.empty((13, x.shape[0], 3)), np.zeros(2, dtype=np.int64), cl.dampings(model),
                np.zeros(x.shape[0]), np.empty(size), np.empty(size), np.empty(size, dtype=np.int8),
                np.zeros((ANCHOR_ROWS, size, 3)), np.empty(size), np.empty(size), anchors)


@kernel
def rhs(x, v, inv_mass, model, net_gravity, work, stiffness, frozen, f, a):
    """Write into ``a`` every body's acceleration: the net's springs, weight and air drag, the
    balls' weight and air, and the listed contacts (in their frozen modes if ``frozen``), their
    anchors at ``work.anchor[Z]`` (whose rates go to ``work.anchor[RATE]``); ``f``: scratch rows
    for the contact forces."""
    accelerations(x, v, inv_mass, net_gravity, model.drag, model.springs, a)
    for k in range(model.n_net, x.shape[0]):
        a[k, 0], a[k, 1], a[k, 2] = ball_acceleration(v, k, model)
    f[:] = 0.0
    forces.add_forces(x, v, inv_mass, model, work.contacts, stiffness, work.damping, frozen, f, work.anchor)
    for k in range(x.shape[0]):
        w = inv_mass[k]
        for c in range(3):
            a[k, c] += w * f[k, c]


@inline_kernel
def ball_acceleration(v, k, model):
    """A ball's acceleration by its weight and, in a scene with air, the drag towards the wind."""
    if model.ball_drag > 0.0:
        return air_acceleration(v[k, 0], v[k, 1], v[k, 2], model.gravity, model.ball_drag, model.wind)
    return 0.0, 0.0, model.gravity


@kernel
def freeze(x, v, inv_mass, model, work, stiffness, z, breaks):
    """Freeze the listed contacts' modes, pole regions and grips at (x, v) (the grips changed as
    :func:`~netgym.physics.compliant.forces.regrip` says, anchors ``z``; ``breaks``: whether a
    gripping contact breaks away outside Coulomb's cone), their event values there (in the
    regions the state is in) into ``touch0``, ``on0``, ``rate0``, ``side0`` and ``grip0``."""
    contacts, count, damping = work.contacts, work.contacts.count[0], work.damping
    contacts.region[:count] = cl.LIVE
    cl.event_values(x, v, model, contacts, damping, work.touch0, work.on0, work.rate0, work.side0)
    cl.modes_from(work.touch0, work.on0, count, contacts.mode)
    cl.regions_from(work.side0, contacts, contacts.mode, contacts.region)
    forces.regrip(x, v, inv_mass, model, contacts, z, stiffness, damping, breaks)
    forces.grip_values(x, v, inv_mass, model, contacts, z, stiffness, damping, work.grip0)
