"""In-place updates of rows of (n, 3) arrays (positions, velocities, forces), inlined into the
numba kernels."""

from __future__ import annotations

from netgym.physics.jit import inline_kernel


@inline_kernel
def add_scaled(rows, k, scale, x, y, z):
    """Add ``scale * (x, y, z)`` to row ``k``."""
    rows[k, 0] += scale * x
    rows[k, 1] += scale * y
    rows[k, 2] += scale * z


@inline_kernel
def add_pair_force(f, i, j, fx, fy, fz):
    """Add the force (fx, fy, fz) to body i and its reaction to body j."""
    f[i, 0] += fx
    f[i, 1] += fy
    f[i, 2] += fz
    f[j, 0] -= fx
    f[j, 1] -= fy
    f[j, 2] -= fz
