"""The spring law, written once: a linear spring with a damper along it.

A spring of rest length ``L``, stiffness ``ks`` and damping ``kd`` between particles i and j,
``l = |x_i - x_j|``, ``u = (x_i - x_j) / l``, pushes i along ``u`` with :func:`tension` (and j
with the opposite): ``-ks (l - L) - kd c``, ``c = (v_i - v_j) . u`` its closing speed. Its
stiffness (the force's derivative by the positions) is ``ks`` along ``u`` and ``ks`` times
:func:`stretch` across it; its energy is :func:`energy`. Every force pass, integrator, energy
and the stability analysis call these (numba inlines them: the same operations in the same order
as written out in place).
"""

from __future__ import annotations

from netgym.physics.kernels.jit import inline_kernel

DEGENERATE = 1e-12  # m: a spring shorter than this has no direction, and exerts nothing


@inline_kernel
def elastic_tension(length, rest, ks):
    """The spring's elastic force along its axis (positive pushes its ends apart)."""
    return -ks * (length - rest)


@inline_kernel
def tension(length, rest, ks, kd, closing):
    """The spring's force along its axis with its damper's (``closing``: the closing speed)."""
    return elastic_tension(length, rest, ks) - kd * closing


@inline_kernel
def stretch(length, rest):
    """The across-axis stiffness over ``ks``: ``1 - L / l`` for a stretched spring, 0 for a
    compressed or degenerate one (whose across-axis stiffness would be negative or undefined)."""
    ratio = 1.0 - rest / length if length > DEGENERATE else 0.0
    return max(ratio, 0.0)


@inline_kernel
def energy(length, rest, ks):
    """The spring's elastic energy (J)."""
    return 0.5 * ks * (length - rest) ** 2
