"""Whether a ball can still reach the opening: the fast path's energy bound, in one numba pass.

Everything but the ball started the throw at rest, with the potential energy its launch
measured (the reference); the dampers, friction and inelastic contacts only take energy away,
and the wind feeds at most a known power. So the energy the ball can still turn into height
is at most the kinetic energy of everything plus the potential energy everything else holds
above the reference, plus the wind's work until the deadline; with compliant contacts, plus the
energy their springs hold.
"""

from __future__ import annotations

import math
from typing import NamedTuple

from netgym.physics.compliant.contacts import gather, potential
from netgym.physics.kernels.smooth_forces import energies
from netgym.physics.kernels.jit import inline_kernel, kernel
from netgym.physics.model.opening import opening_distance


@inline_kernel
def _without_ball(x, inv_mass, row, gravity, spring, potential_g):
    """Potential energy of everything but the ball in ``row``, from the spring and
    gravitational potential energy of all free bodies."""
    return spring + potential_g + gravity / inv_mass[row] * x[row, 2]


@kernel
def potential_without_ball(x, v, inv_mass, row, gravity, springs, params):
    """Potential energy (J) of every free body but the ball in ``row``: the reference a throw
    measures its free energy against."""
    _, spring, potential_g = energies(x, v, inv_mass, gravity, springs, params)
    return _without_ball(x, inv_mass, row, gravity, spring, potential_g)


class Budget(NamedTuple):
    """What one throw's energy bound measures against: the ``reference`` potential energy of
    everything but the ball at the launch (J), the most ``wind_power`` the wind can feed all
    the balls (W), ``gravity`` (m/s^2, along z), the ball's ``radius`` (m), the ``lowest_z``
    of the opening (m) and the ``contact_stiffness`` (N/m) of compliant contacts, whose springs'
    energy counts as free (0.0: impulse contacts, which hold none). A small record, so that a
    kernel taking it starts fast."""

    reference: float
    wind_power: float
    gravity: float
    radius: float
    lowest_z: float
    contact_stiffness: float


@kernel
def out_of_reach(x, v, inv_mass, row, model, budget, time_left, contacts):
    """True if the ball in ``row`` can no longer reach the opening of ``model`` (a
    :class:`~netgym.physics.model.model.KernelModel`) within ``time_left``: the energy free now
    (kinetic, potential above the :class:`Budget`'s reference and, with compliant contacts, that
    of their springs, listed into ``contacts``) and the wind's work until then cannot lift it to
    the opening's lowest point, or cannot carry it there in time at the speed that energy and
    its own fall to the ground could give it (a vertical mouth has no height to climb)."""
    gravity, opening = budget.gravity, model.opening
    kinetic, spring, potential_g = energies(x, v, inv_mass, gravity, model.springs.pairs, model.springs.params)
    w, z = inv_mass[row], x[row, 2]
    free = kinetic + max(0.0, _without_ball(x, inv_mass, row, gravity, spring, potential_g) - budget.reference)
    free += budget.wind_power * max(0.0, time_left)
    if budget.contact_stiffness > 0.0:
        gather(x, model, 0.0, contacts)
        free += potential(x, model, contacts, budget.contact_stiffness)
    if gravity != 0.0 and z + free * w / abs(gravity) < budget.lowest_z:
        return True
    fall = abs(gravity) * max(0.0, z - budget.radius) / w
    top_speed = math.sqrt(2.0 * (free + fall) * w)
    return top_speed * time_left < opening_distance(opening, x[row])
