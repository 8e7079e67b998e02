"""In-place updates of rows of (n, 3) arrays (positions, velocities, forces), inlined into the
numba kernels.

Copies go component by component: numba's array assignment (``a[k] = b[j]``, ``a[:] = b``)
brings in its broadcasting machinery, whose first use adds seconds of compilation to a process
(``docs/BENCHMARKS.md``).
"""

from __future__ import annotations

from netgym.physics.kernels.jit import inline_kernel, kernel


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


@inline_kernel
def copy_row(rows, k, source, j):
    """Set row ``k`` to row ``j`` of ``source``."""
    rows[k, 0] = source[j, 0]
    rows[k, 1] = source[j, 1]
    rows[k, 2] = source[j, 2]


@inline_kernel
def copy_first_rows(rows, source, count):
    """Set the first ``count`` rows to those of ``source``."""
    for k in range(count):
        copy_row(rows, k, source, k)


@kernel
def copy_rows(rows, source):
    """Set every row to the same row of ``source`` (of the same shape)."""
    copy_first_rows(rows, source, source.shape[0])


@kernel
def copy_vector(vector, source):
    """Set every element of a 1-d ``vector`` to that of ``source`` (of the same length)."""
    for c in range(source.shape[0]):
        vector[c] = source[c]
