"""The compliant contact law: Hunt-Crossley normal forces, their restitution, the weight of a
segment's line penalty and regularised Coulomb friction. Scalars in, scalars out; inlined into
the kernels of :mod:`~netgym.physics.compliant.contacts`.

A contact of overlap ``delta`` (m) closing at ``rate`` (m/s) pushes its bodies apart with
``k w delta max(0, 1 + d rate)``: its elastic part the gradient of the potential
``k w delta^2 / 2``, its damping part ``k w delta d rate`` (Hunt and Crossley 1975, linear in
the overlap), which vanishes with the overlap, so the force is continuous at the onset and
the separation. Such a contact of a body of any mass returns a fraction ``e`` of an approach
speed ``v0`` with ``d v0 = y(e)``, where ``y - ln(1 + y) + e y + ln(1 - e y) = 0`` (integrate
``m u du / (1 + d u) = -k delta d delta`` from ``u = v0`` to ``u = -e v0``): the configured
restitution holds at :data:`REFERENCE_SPEED`; faster approaches bounce less, slower ones more.
"""

from __future__ import annotations

import math

from netgym.physics.kernels.jit import inline_kernel, kernel

REFERENCE_SPEED = 5.0    # m/s: the approach speed at which a contact returns its restitution
SLIP_SPEED = 0.05        # m/s: Coulomb friction is regularised below this sliding speed
LOWEST_RESTITUTION = 0.01  # a restitution of 0 would need an infinite damping


@kernel
def dissipation(restitution, speed):
    """``d`` (s/m) of a contact that returns ``restitution`` of an approach at ``speed`` (see
    the module): bisection on ``y = d speed`` in (0, 1 / e)."""
    e = min(1.0, max(LOWEST_RESTITUTION, restitution))
    if e >= 1.0:
        return 0.0
    lo, hi = 0.0, 1.0 / e
    for _ in range(100):
        y = 0.5 * (lo + hi)
        if y - math.log1p(y) + e * y + math.log1p(-e * y) > 0.0:
            lo = y
        else:
            hi = y
    return 0.5 * (lo + hi) / speed


@inline_kernel
def segment_weight(s):
    """(w, dw/ds) of a segment's line penalty at the parameter ``s`` of its closest point:
    ``(4 s (1 - s))^3`` inside (1 at the middle), 0 outside, twice continuously differentiable
    at the ends, where the particles' own contacts take over."""
    if s <= 0.0 or s >= 1.0:
        return 0.0, 0.0
    q = 4.0 * s * (1.0 - s)
    return q * q * q, 12.0 * q * q * (1.0 - 2.0 * s)


@inline_kernel
def normal_force(stiffness, delta, rate, damping):
    """The normal force of a contact of weighted stiffness ``stiffness`` (N/m), overlap
    ``delta`` > 0 closing at ``rate``, with its damper clamped so that it never pulls."""
    return stiffness * delta * max(0.0, 1.0 + damping * rate)


@inline_kernel
def free_normal_force(stiffness, delta, rate, damping):
    """:func:`normal_force` without the clamp: its smooth continuation, which a step that
    froze the contact's mode evaluates up to the located event."""
    return stiffness * delta * (1.0 + damping * rate)


@inline_kernel
def friction_factor(friction, normal, slip_speed):
    """The friction force per unit sliding velocity (N s/m) at a sliding speed ``slip_speed``:
    ``friction * normal / sqrt(slip_speed^2 + SLIP_SPEED^2)``, Coulomb's ``friction * normal``
    when sliding fast, a smooth viscous law through zero."""
    return friction * normal / math.sqrt(slip_speed * slip_speed + SLIP_SPEED * SLIP_SPEED)
