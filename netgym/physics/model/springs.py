"""A net's springs as the kernels take them: in wavefront order for the loops that update both
ends of a spring in turn, and grouped by index offset for the force pass, whose arithmetic the
compiler then vectorises.

The force pass (:func:`netgym.physics.kernels.forces.spring_forces`) gives bitwise the forces of a loop
over the springs in the order they were given (sorted by their first particle, then their
second), because every particle receives the same contributions in the same order. A spring
(i, j), i < j, has the offset d = j - i. In the given order a particle p first receives the
forces of the springs (i, p) by increasing i, that is by decreasing offset, and then those of
the springs (p, j) by increasing j, that is by increasing offset. So the pass adds the forces
on the second particles group by group in decreasing offset, then those on the first particles
in increasing offset; within a group no two springs share a first or a second particle, so the
order inside it does not matter.

A group holds the springs of one offset and one stiffness and damping (in a net, one kind of
spring). One whose springs fill at least half the range of first particles they span is
*dense*: it is stored over that whole range, widened to whole vector registers, the missing
springs flagged, so that the springs' particles are ``lo + t`` and ``lo + t + d``, contiguous
in memory (the pass copies positions, velocities and forces into columns, one per coordinate),
and its stiffness and damping are read once for the group. The other groups are *sparse*: a
list of pairs with their parameters.

The dense blocks and the columns start on cache-line boundaries and every dense range starts
at a multiple of :data:`LANES` particles, so that the pass's vector loads and stores of first
particles, parameters and forces do not straddle two cache lines; the results do not depend on
it (a copy of a record, e.g. after pickling, may lose the alignment and only runs slower).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

DENSE_FILL = 0.5
"""The least fraction of its range of first particles a group's springs fill to be stored dense."""
DENSE_MIN_SPRINGS = 8
"""The fewest springs a dense group holds (shorter ones do not fill a vector register well)."""
LANES = 8
"""float64 values in a cache line (64 bytes) and in the widest vector register (AVX-512)."""


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
    of one particle come one after the other); ``docs/BENCHMARKS.md`` says what that saves.
    """
    latest = [0] * n_particles
    wavefront = np.empty(len(springs), dtype=np.int64)
    for s, (i, j) in enumerate(springs.tolist()):
        wavefront[s] = latest[i] = latest[j] = max(latest[i], latest[j]) + 1
    return np.argsort(wavefront, kind="stable")


class SpringGroups(NamedTuple):
    """The force pass's groups, one entry each, in increasing offset: the ``offset`` of its
    springs, its ``first`` particle, its ``length`` and its ``start`` (the column of its block in
    :class:`DenseSprings`, or its first row in :class:`SparseSprings`), all uint64; ``dense``
    (bool): stored dense; a dense group's one stiffness ``ks`` and damping ``kd`` (0 for a
    sparse group, whose springs carry their own)."""

    offset: np.ndarray
    first: np.ndarray
    length: np.ndarray
    start: np.ndarray
    dense: np.ndarray
    ks: np.ndarray
    kd: np.ndarray


class DenseSprings(NamedTuple):
    """The dense groups' blocks, one column a place: the spring's ``rest`` length and
    ``exists`` (1.0, or 0.0 where no spring fills the place); the pass's scratch ``on_first`` and
    ``on_second`` (3 rows each): the force on the spring's first and second particle by
    coordinate, -0.0 where a spring is missing or degenerate. Rows start cache lines."""

    rest: np.ndarray
    exists: np.ndarray
    on_first: np.ndarray
    on_second: np.ndarray


class SparseSprings(NamedTuple):
    """The sparse groups' springs, one row each: their ``pairs`` (uint32), ``rest`` length,
    stiffness ``ks`` and damping ``kd``; the pass's scratch ``on_first`` (3 rows: the force on
    the first particle by coordinate) and ``exists`` (1.0 where that force was computed, 0.0 for
    a degenerate spring)."""

    pairs: np.ndarray
    rest: np.ndarray
    ks: np.ndarray
    kd: np.ndarray
    on_first: np.ndarray
    exists: np.ndarray


class Columns(NamedTuple):
    """The force pass's copies of the particles' ``positions``, ``velocities`` and force
    ``totals``, one row a coordinate (3 rows each, of ``n_particles`` and a margin the widened
    dense ranges reach into); rows start cache lines."""

    positions: np.ndarray
    velocities: np.ndarray
    totals: np.ndarray

    @classmethod
    def sized(cls, n_particles: int) -> "Columns":
        """Zeroed columns for ``n_particles`` particles."""
        width = _round_up(n_particles, LANES) + LANES
        return cls(aligned_zeros((3, width)), aligned_zeros((3, width)), aligned_zeros((3, width)))


class Springs(NamedTuple):
    """The springs of a net as the kernels take them (built by :meth:`of`).

    ``pairs`` (uint32) and ``params`` (columns: rest length, ks, kd) are in
    :func:`wavefront_order`. The force pass reads the :class:`SpringGroups` ``groups``: a dense
    group covers the springs (first + t, first + t + offset) for t < length at columns start + t
    of the :class:`DenseSprings` ``dense``; a sparse one lists ``length`` springs from row
    ``start`` of the :class:`SparseSprings` ``sparse``. Their force scratch and the
    :class:`Columns` ``columns`` serve one kernel call at a time (kernels hold the GIL; worker
    processes have their own).
    """

    n_particles: int
    pairs: np.ndarray
    params: np.ndarray
    groups: SpringGroups
    dense: DenseSprings
    sparse: SparseSprings
    columns: Columns

    @classmethod
    def of(cls, pairs: np.ndarray, params: np.ndarray, n_particles: int) -> "Springs":
        """The springs ``pairs`` (n, 2) with ``params`` (n, 3) among ``n_particles`` particles.
        Each pair names two different particles (a pair's order does not change its force) and no
        pair comes twice; the kernels' results are those of a loop over the springs sorted by
        (smaller, larger) particle index."""
        return cls.laid_out(pairs, params, n_particles)[0]

    @classmethod
    def laid_out(cls, pairs: np.ndarray, params: np.ndarray, n_particles: int) -> tuple["Springs", "SpringLayout"]:
        """:meth:`of`, and the :class:`SpringLayout` that refills the record with other
        stiffness and damping."""
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
        groups, members = _offset_groups(pairs, params)
        springs = cls(n_particles, kernel_indices(pairs[wavefront]), np.ascontiguousarray(params[wavefront]),
                      groups.table(), groups.dense_block(), groups.sparse_list(), Columns.sized(n_particles))
        return springs, SpringLayout.of(springs, order, wavefront, members)

    def scratch_copy(self) -> "Springs":
        """The record with scratch arrays of its own (the rest shared)."""
        dense, sparse = self.dense, self.sparse
        return self._replace(dense=dense._replace(on_first=aligned_zeros(dense.on_first.shape),
                                                  on_second=aligned_zeros(dense.on_second.shape)),
                             sparse=sparse._replace(on_first=np.zeros(sparse.on_first.shape),
                                                    exists=np.zeros(sparse.exists.shape)),
                             columns=Columns.sized(self.n_particles))


class SpringLayout(NamedTuple):
    """Where each spring of a list given to :meth:`Springs.laid_out` lies in its record, to
    refill the record with other stiffness and damping for the same pairs (nets drawn per
    episode): the ``template`` record, the list's rows in the record's ``params`` order
    (``kernel_rows``) and in its sparse list's order (``sparse_rows``), and for each dense
    group its member rows (``dense_members``, the group of each in ``member_group``) and one
    of them (``representatives``, -1 for a sparse group)."""

    template: Springs
    kernel_rows: np.ndarray
    sparse_rows: np.ndarray
    dense_members: np.ndarray
    member_group: np.ndarray
    representatives: np.ndarray

    @classmethod
    def of(cls, springs: Springs, order: np.ndarray, wavefront: np.ndarray, members: list[np.ndarray]) -> "SpringLayout":
        """The layout of ``springs``, built from the list's rows sorted by ``order``, then put in
        ``wavefront`` order, and grouped into ``members`` (sorted rows of each group)."""
        dense = springs.groups.dense
        sparse = [order[rows] for rows, is_dense in zip(members, dense) if not is_dense]
        grouped = [(g, order[rows]) for g, (rows, is_dense) in enumerate(zip(members, dense)) if is_dense]
        return cls(springs, order[wavefront], np.concatenate(sparse) if sparse else np.zeros(0, dtype=np.int64),
                   np.concatenate([rows for _, rows in grouped]) if grouped else np.zeros(0, dtype=np.int64),
                   np.concatenate([np.full(len(rows), g) for g, rows in grouped]) if grouped else np.zeros(0, dtype=np.int64),
                   np.array([order[rows[0]] if is_dense else -1 for rows, is_dense in zip(members, dense)], dtype=np.int64))

    def refill(self, params: np.ndarray) -> Springs | None:
        """The record of the same pairs with ``params`` (in the list's order), with scratch of its
        own; None if the springs of a dense group no longer share one stiffness and damping
        (then build it with :meth:`Springs.of`). Its forces are those :meth:`Springs.of` gives:
        a dense group only needs one stiffness and damping, whatever others share it."""
        params = np.asarray(params, dtype=np.float64)
        if not np.array_equal(params[self.dense_members, 1:], params[self.representatives[self.member_group], 1:]):
            return None
        dense = self.representatives >= 0
        ks, kd = np.zeros(len(dense)), np.zeros(len(dense))
        ks[dense], kd[dense] = params[self.representatives[dense], 1], params[self.representatives[dense], 2]
        springs = self.template.scratch_copy()
        sparse = params[self.sparse_rows]
        return springs._replace(params=np.ascontiguousarray(params[self.kernel_rows]),
                                groups=springs.groups._replace(ks=ks, kd=kd),
                                sparse=springs.sparse._replace(rest=np.ascontiguousarray(sparse[:, 0]),
                                                               ks=np.ascontiguousarray(sparse[:, 1]),
                                                               kd=np.ascontiguousarray(sparse[:, 2])))


def aligned_zeros(shape: tuple[int, int]) -> np.ndarray:
    """A C-contiguous float64 array of zeros whose first element starts a cache line (numpy
    aligns to 16 bytes only); with a row length that is a multiple of :data:`LANES`, every row
    does."""
    size = shape[0] * shape[1]
    buffer = np.zeros(size + LANES)
    skip = (-buffer.ctypes.data // 8) % LANES
    return buffer[skip:skip + size].reshape(shape)


def _round_up(n: int, multiple: int) -> int:
    """The least multiple of ``multiple`` that is at least ``n``."""
    return -(-n // multiple) * multiple


class _Grouping(NamedTuple):
    """The groups of :class:`Springs` as :func:`_offset_groups` finds them, before they are
    laid out: each group's (offset, first, length, start, dense) and (ks, kd) (zero for sparse
    groups), the dense groups' (rest length, exists) blocks (lengths multiples of
    :data:`LANES`) and the sparse groups' (pairs, params)."""

    rows: list[tuple[int, int, int, int, bool]]
    stiffness: list[tuple[float, float]]
    blocks: list[np.ndarray]
    lists: list[tuple[np.ndarray, np.ndarray]]

    def table(self) -> SpringGroups:
        """The groups' :class:`SpringGroups`."""
        rows = np.array([row[:4] for row in self.rows], dtype=np.uint64).reshape(-1, 4)
        stiffness = np.array(self.stiffness, dtype=np.float64).reshape(-1, 2)
        return SpringGroups(*(np.ascontiguousarray(rows[:, c]) for c in range(4)),
                            np.array([row[4] for row in self.rows], dtype=np.bool_),
                            np.ascontiguousarray(stiffness[:, 0]), np.ascontiguousarray(stiffness[:, 1]))

    def dense_block(self) -> DenseSprings:
        """The dense groups' :class:`DenseSprings`, cache-line aligned."""
        places = sum(block.shape[1] for block in self.blocks)
        rest, exists = aligned_zeros((1, places)), aligned_zeros((1, places))
        if self.blocks:
            rest[0], exists[0] = np.concatenate(self.blocks, axis=1)
        return DenseSprings(rest[0], exists[0], aligned_zeros((3, places)), aligned_zeros((3, places)))

    def sparse_list(self) -> SparseSprings:
        """The sparse groups' :class:`SparseSprings`."""
        pairs = np.concatenate([p for p, _ in self.lists]) if self.lists else np.zeros((0, 2), dtype=np.int64)
        params = np.concatenate([q for _, q in self.lists]) if self.lists else np.zeros((0, 3))
        return SparseSprings(kernel_indices(pairs), *(np.ascontiguousarray(params[:, c]) for c in range(3)),
                             np.zeros((3, len(pairs))), np.zeros(len(pairs)))


def _offset_groups(pairs: np.ndarray, params: np.ndarray) -> tuple[_Grouping, list[np.ndarray]]:
    """The groups of :class:`Springs` in increasing offset (one per offset, stiffness and
    damping), and each group's rows of ``pairs``."""
    offsets = pairs[:, 1] - pairs[:, 0]
    keys, key_of = np.unique(np.column_stack([offsets, params[:, 1:]]), axis=0, return_inverse=True)
    grouping, members = _Grouping([], [], [], []), []
    dense_used = sparse_used = 0
    for k, (offset, ks, kd) in enumerate(keys):
        rows = np.flatnonzero(key_of.reshape(-1) == k)
        members.append(rows)
        first = pairs[rows, 0]
        lo, span = int(first.min()), int(first.max() - first.min() + 1)
        if len(rows) >= DENSE_MIN_SPRINGS and len(rows) >= DENSE_FILL * span:
            lo -= lo % LANES
            span = _round_up(int(first.max()) + 1 - lo, LANES)
            block = np.zeros((2, span))
            block[0, first - lo] = params[rows, 0]
            block[1, first - lo] = 1.0
            grouping.rows.append((int(offset), lo, span, dense_used, True))
            grouping.stiffness.append((ks, kd))
            grouping.blocks.append(block)
            dense_used += span
        else:
            grouping.rows.append((int(offset), lo, len(rows), sparse_used, False))
            grouping.stiffness.append((0.0, 0.0))
            grouping.lists.append((pairs[rows], params[rows]))
            sparse_used += len(rows)
    return grouping, members
