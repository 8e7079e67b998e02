"""A net's springs as the kernels take them: in wavefront order for the loops that update both
ends of a spring in turn, and grouped by index offset for the force pass, whose arithmetic the
compiler then vectorises.

The force pass (:func:`netgym.physics.forces.spring_forces`) gives bitwise the forces of a loop
over the springs in the order they were given (sorted by their first particle, then their
second), because every particle receives the same contributions in the same order. A spring
(i, j), i < j, has the offset d = j - i. In the given order a particle p first receives the
forces of the springs (i, p) by increasing i, that is by decreasing offset, and then those of
the springs (p, j) by increasing j, that is by increasing offset. So the pass adds the forces
on the second particles group by group in decreasing offset, then those on the first particles
in increasing offset; within a group no two springs share a first or a second particle, so the
order inside it does not matter.

A group whose springs fill at least half the range of first particles they span is *dense*: it
is stored over that whole range, the missing springs flagged, so that the springs' particles
are ``lo + t`` and ``lo + t + d``, contiguous in memory (the pass copies positions, velocities
and forces into columns, one per coordinate). The other groups are *sparse*: a list of pairs.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

DENSE_FILL = 0.5
"""The least fraction of its range of first particles a group's springs fill to be stored dense."""
DENSE_MIN_SPRINGS = 8
"""The fewest springs a dense group holds (shorter ones do not fill a vector register well)."""


def kernel_indices(pairs: np.ndarray) -> np.ndarray:
    """Particle index pairs as the kernels take them: unsigned, so that numba indexes with them
    directly instead of first wrapping a negative index around (an index can never be negative
    here); the same results, bitwise, in fewer instructions a spring."""
    return np.ascontiguousarray(pairs, dtype=np.uint32)


def wavefront_order(springs: np.ndarray, n_particles: int) -> np.ndarray:
    """An order of ``springs`` for the kernels' loops that gives bitwise the same results as
    the given order, faster.

    A loop that updates both ends of each spring in turn (IMEX Euler's elastic forces and damper
    sweep, implicit Euler's assembly) depends on the order only through the springs that share a
    particle. Each spring
    gets a wavefront: one past the latest wavefront of the springs before it at either end. No
    two springs of a wavefront share a particle, and the springs sharing a particle keep their
    order, so every particle sees the same updates in the same order. The processor no longer
    waits at every spring for the store of the spring before it (in memory order the springs
    of one particle come one after the other); what that saves is measured in the benchmark
    report (``docs/BENCHMARKS.md``, what the optimisations bought).
    """
    latest = [0] * n_particles
    wavefront = np.empty(len(springs), dtype=np.int64)
    for s, (i, j) in enumerate(springs.tolist()):
        wavefront[s] = latest[i] = latest[j] = max(latest[i], latest[j]) + 1
    return np.argsort(wavefront, kind="stable")


class Springs(NamedTuple):
    """The springs of a net as the kernels take them (built by :meth:`of`).

    ``pairs`` (uint32) and ``params`` (rest length, ks, kd) are in :func:`wavefront_order`.
    ``groups`` rows are (offset, first particle, length, start, dense) as uint64: a dense group
    covers the springs (first + t, first + t + offset) for t < length at columns start + t of
    ``dense_params`` (rest length, ks, kd, 1 where the spring exists else 0); a sparse one lists
    ``length`` springs from row ``start`` of ``sparse_pairs`` and ``sparse_params``.
    ``dense_forces`` (6 rows), ``sparse_forces`` (4 rows) and ``columns`` (positions,
    velocities and forces by coordinate, 9 rows by particle) are the force pass's scratch, so a
    record serves one kernel call at a time (kernels hold the GIL; worker processes have their own).
    """

    pairs: np.ndarray
    params: np.ndarray
    groups: np.ndarray
    dense_params: np.ndarray
    sparse_pairs: np.ndarray
    sparse_params: np.ndarray
    dense_forces: np.ndarray
    sparse_forces: np.ndarray
    columns: np.ndarray

    @classmethod
    def of(cls, pairs: np.ndarray, params: np.ndarray, n_particles: int) -> "Springs":
        """The springs ``pairs`` (n, 2) with ``params`` (n, 3) among ``n_particles`` particles.
        Each pair names two different particles (a pair's order does not change its force) and no
        pair comes twice; the kernels' results are those of a loop over the springs sorted by
        (smaller, larger) particle index."""
        pairs = np.sort(np.asarray(pairs, dtype=np.int64).reshape(-1, 2), axis=1)
        params = np.asarray(params, dtype=np.float64).reshape(-1, 3)
        if len(pairs) != len(params):
            raise ValueError(f"{len(pairs)} spring pairs but {len(params)} rows of spring parameters")
        if len(pairs) and (np.any(pairs[:, 0] == pairs[:, 1]) or pairs.min() < 0 or pairs.max() >= n_particles):
            raise ValueError(f"spring pairs must name two different particles of 0..{n_particles - 1}")
        if len(np.unique(pairs, axis=0)) != len(pairs):
            raise ValueError("a spring pair comes twice")
        order = np.lexsort((pairs[:, 1], pairs[:, 0]))
        pairs, params = pairs[order], params[order]
        wavefront = wavefront_order(pairs, n_particles)
        groups, dense, sparse = _offset_groups(pairs, params)
        dense_params = np.concatenate(dense, axis=1) if dense else np.zeros((4, 0))
        sparse_pairs = np.concatenate([p for p, _ in sparse]) if sparse else np.zeros((0, 2), dtype=np.int64)
        sparse_params = np.concatenate([q for _, q in sparse]) if sparse else np.zeros((0, 3))
        return cls(kernel_indices(pairs[wavefront]), np.ascontiguousarray(params[wavefront]),
                   np.array(groups, dtype=np.uint64).reshape(-1, 5), np.ascontiguousarray(dense_params),
                   kernel_indices(sparse_pairs), np.ascontiguousarray(sparse_params),
                   np.zeros((6, dense_params.shape[1])), np.zeros((4, len(sparse_pairs))),
                   np.zeros((9, n_particles)))


def _offset_groups(pairs: np.ndarray, params: np.ndarray) -> tuple[list, list, list]:
    """The groups of :class:`Springs` in increasing offset: their table rows, the dense groups'
    parameter blocks and the sparse groups' (pairs, params)."""
    offsets = pairs[:, 1] - pairs[:, 0]
    groups, dense, sparse = [], [], []
    dense_used = sparse_used = 0
    for offset in np.unique(offsets):
        rows = np.flatnonzero(offsets == offset)
        first = pairs[rows, 0]
        lo, span = int(first.min()), int(first.max() - first.min() + 1)
        if len(rows) >= DENSE_MIN_SPRINGS and len(rows) >= DENSE_FILL * span:
            block = np.zeros((4, span))
            block[:3, first - lo] = params[rows].T
            block[3, first - lo] = 1.0
            groups.append((offset, lo, span, dense_used, 1))
            dense.append(block)
            dense_used += span
        else:
            groups.append((offset, lo, len(rows), sparse_used, 0))
            sparse.append((pairs[rows], params[rows]))
            sparse_used += len(rows)
    return groups, dense, sparse
