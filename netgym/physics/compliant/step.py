"""A substep of the compliant model: every body's motion under the smooth forces and the
contacts' (:mod:`~netgym.physics.compliant.forces`), by the integrator the settings are made for.

- RK4 locates every change of a contact's mode, region or grip inside its steps
  (:mod:`~netgym.physics.compliant.rk4`) and keeps its fourth order through contact.
- Explicit and symplectic Euler take the forces of the modes the state is in, the grips changed
  at the start of a part.
- IMEX Euler takes the contacts' springs explicitly and their dampers and friction implicitly
  (:mod:`~netgym.physics.compliant.imex`).

Contact springs are stiff: while any contact is listed, a substep is split further so that
``h omega <= 1``, ``omega`` a bound on the highest frequency the listed contacts' springs give
the bodies (:func:`~netgym.physics.compliant.split.frequency_bound`); ``<= 1.5`` for IMEX
Euler, whose explicit part treats those springs by symplectic Euler (stable below 2) and
their dampers implicitly. Each part lists the contacts, takes their grips from the state's
anchors (:mod:`~netgym.physics.compliant.grip`) and puts them back after it.
"""

from __future__ import annotations

import math

from numba.core.errors import NumbaTypeError
from numba.extending import overload

from netgym.kinds import Integrator
from netgym.physics.compliant import contacts as cl
from netgym.physics.compliant import grip, split
from netgym.physics.compliant.imex import imex
from netgym.physics.compliant.rk4 import rk4_located
from netgym.physics.compliant.system import RATE, Z, Z0, freeze, rhs
from netgym.physics.kernels.integrators import euler_update
from netgym.physics.kernels.jit import kernel
from netgym.physics.kernels.rows import copy_first_rows


@kernel
def _euler(x, v, inv_mass, model, net_gravity, h, work, stiffness, symplectic):
    """Explicit (x by the old velocity) or symplectic (by the new) Euler over ``h``, the
    contacts in the mode the state is in, their grips changed at its start and their anchors
    (``work.anchor[Z0]``) moved by the sliding velocity of its start."""
    rows, anchor, count = work.rows, work.anchor, work.contacts.count[0]
    a, f = rows[0], rows[1]
    z0 = anchor[Z0]
    freeze(x, v, inv_mass, model, work, stiffness, z0, True)
    copy_first_rows(anchor[Z], z0, count)
    rhs(x, v, inv_mass, model, net_gravity, work, stiffness, False, f, a)
    euler_update(x, v, a, h, symplectic)
    rate = anchor[RATE]
    for c in range(count):
        for k in range(3):
            z0[c, k] += h * rate[c, k]


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
        stiffness, contacts, z = settings.contact_stiffness, work.contacts, work.anchor[Z0]
        n_balls = x.shape[0] - model.n_net
        cl.gather(x, model, _margin(v, h), contacts)
        parts = split.parts(x, inv_mass, model, h, stiffness, contacts, work.load, limit)
        part = h / parts
        for p in range(parts):
            if p > 0:
                cl.gather(x, model, _margin(v, part), contacts)
            grip.load(model, n_balls, contacts, work.anchors, z)
            if integrator == Integrator.RK4:
                rk4_located(x, v, inv_mass, model, net_gravity, part, work, stiffness)
            elif integrator == Integrator.IMEX_EULER:
                imex(x, v, inv_mass, model, net_gravity, part, work, stiffness, scratch)
            else:
                _euler(x, v, inv_mass, model, net_gravity, part, work, stiffness,
                       integrator == Integrator.SYMPLECTIC_EULER)
            grip.store(contacts, work.anchors, z)
        return parts
    return step
