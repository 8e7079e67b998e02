"""A net's springs as the kernels take them: in wavefront order for the loops that update both
ends of a spring in turn, and grouped by index offset for the force pass, whose arithmetic the
compiler then vectorises.

The force pass (:func:`netgym.physics.kernels.smooth_forces.spring_forces`) gives bitwise the forces of a loop
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


GROUP = np.dtype([("offset", np.uint64), ("first", np.uint64), ("length", np.uint64), ("start", np.uint64),
                  ("dense", np.bool_), ("ks", np.float64), ("kd", np.float64)])
"""A group of the force pass: the ``offset`` of its springs, its ``first`` particle, its
``length`` and its ``start`` (its first column in ``dense_params``, or its first row in
``sparse``); ``dense``: stored dense; a dense group's one stiffness ``ks`` and damping ``kd``
(0 for a sparse group, whose springs carry their own)."""
SPARSE_SPRING = np.dtype([("i", np.uint32), ("j", np.uint32), ("rest", np.float64), ("ks", np.float64),
                          ("kd", np.float64)])
"""A spring of a sparse group: its particles ``i`` < ``j``, ``rest`` length, stiffness and damping."""
SPARSE_FORCE = np.dtype([("x", np.float64), ("y", np.float64), ("z", np.float64), ("exists", np.float64)])
"""The force pass's scratch for a sparse spring: the force on its first particle, and ``exists``
(1.0 where it was computed, 0.0 for a degenerate spring)."""
REST, EXISTS = 0, 1
"""The rows of ``dense_params``: each place's rest length, and 1.0 where a spring fills it (else 0.0)."""
ON_FIRST, ON_SECOND = 0, 1
"""The planes of ``dense_forces`` (each 3 rows, one a coordinate): the force on a dense spring's
first particle and on its second, -0.0 where a spring is missing or degenerate."""
POSITIONS, VELOCITIES, TOTALS = 0, 1, 2
"""The planes of ``columns`` (each 3 rows, one a coordinate, of ``n_particles`` and a margin
the widened dense ranges reach into): the force pass's copies of the positions, velocities and
force totals."""


class Springs(NamedTuple):
    """The springs of a net as the kernels take them (built by :meth:`of`).

    ``pairs`` (uint32) and ``params`` (columns: rest length, ks, kd) are in
    :func:`wavefront_order`. The force pass reads ``groups`` (records of :data:`GROUP`): a
    dense group covers the springs (first + t, first + t + offset) for t < length at columns
    start + t of ``dense_params`` (rows :data:`REST`, :data:`EXISTS`); a sparse one lists
    ``length`` springs from row ``start`` of ``sparse`` (records of :data:`SPARSE_SPRING`). Its
    scratch, ``dense_forces`` (planes :data:`ON_FIRST`, :data:`ON_SECOND`), ``sparse_forces``
    (records of :data:`SPARSE_FORCE`) and ``columns`` (planes :data:`POSITIONS`,
    :data:`VELOCITIES`, :data:`TOTALS`), serves one kernel call at a time (kernels hold the GIL;
    worker processes have their own). Few arrays: a kernel called from Python unboxes each.
    """

    n_particles: int
    pairs: np.ndarray
    params: np.ndarray
    groups: np.ndarray
    dense_params: np.ndarray
    dense_forces: np.ndarray
    sparse: np.ndarray
    sparse_forces: np.ndarray
    columns: np.ndarray

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
        grouping, members = _offset_groups(pairs, params)
        springs = cls(n_particles, kernel_indices(pairs[wavefront]), np.ascontiguousarray(params[wavefront]),
                      grouping.table(), grouping.dense_params(), aligned_zeros((2, 3, grouping.dense_places())),
                      grouping.sparse_list(), np.zeros(grouping.sparse_count(), dtype=SPARSE_FORCE),
                      aligned_zeros((3, 3, _round_up(n_particles, LANES) + LANES)))
        return springs, SpringLayout.of(springs, order, wavefront, members)

    def scratch_copy(self) -> "Springs":
        """The record with scratch arrays of its own (the rest shared)."""
        return self._replace(dense_forces=aligned_zeros(self.dense_forces.shape),
                             sparse_forces=np.zeros(self.sparse_forces.shape, dtype=SPARSE_FORCE),
                             columns=aligned_zeros(self.columns.shape))


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
        dense = springs.groups["dense"]
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
        groups = self.template.groups.copy()
        groups["ks"][dense] = params[self.representatives[dense], 1]
        groups["kd"][dense] = params[self.representatives[dense], 2]
        sparse = self.template.sparse.copy()
        _set_params(sparse, params[self.sparse_rows])
        return self.template.scratch_copy()._replace(params=np.ascontiguousarray(params[self.kernel_rows]),
                                                     groups=groups, sparse=sparse)


def aligned_zeros(shape: tuple[int, ...]) -> np.ndarray:
    """A C-contiguous float64 array of zeros whose first element starts a cache line (numpy
    aligns to 16 bytes only); with a row length that is a multiple of :data:`LANES`, every row
    does."""
    size = int(np.prod(shape))
    buffer = np.zeros(size + LANES)
    skip = (-buffer.ctypes.data // 8) % LANES
    return buffer[skip:skip + size].reshape(shape)


def _round_up(n: int, multiple: int) -> int:
    """The least multiple of ``multiple`` that is at least ``n``."""
    return -(-n // multiple) * multiple


class _Grouping(NamedTuple):
    """The groups of :class:`Springs` as :func:`_offset_groups` finds them, before they are
    laid out: each group's record (the fields of :data:`GROUP`), the dense groups' blocks (rows
    :data:`REST`, :data:`EXISTS`; lengths multiples of :data:`LANES`) and the sparse groups'
    (pairs, params)."""

    records: list[tuple[int, int, int, int, bool, float, float]]
    blocks: list[np.ndarray]
    lists: list[tuple[np.ndarray, np.ndarray]]

    def table(self) -> np.ndarray:
        """The groups as records of :data:`GROUP`."""
        return np.array(self.records, dtype=GROUP)

    def dense_places(self) -> int:
        """Columns of the dense blocks, all groups together."""
        return sum(block.shape[1] for block in self.blocks)

    def dense_params(self) -> np.ndarray:
        """The dense blocks side by side (rows :data:`REST`, :data:`EXISTS`), cache-line aligned."""
        params = aligned_zeros((2, self.dense_places()))
        if self.blocks:
            params[:] = np.concatenate(self.blocks, axis=1)
        return params

    def sparse_count(self) -> int:
        """Springs of the sparse groups, all together."""
        return sum(len(pairs) for pairs, _ in self.lists)

    def sparse_list(self) -> np.ndarray:
        """The sparse groups' springs as records of :data:`SPARSE_SPRING`."""
        springs = np.zeros(self.sparse_count(), dtype=SPARSE_SPRING)
        if self.lists:
            pairs = np.concatenate([p for p, _ in self.lists])
            springs["i"], springs["j"] = pairs[:, 0], pairs[:, 1]
            _set_params(springs, np.concatenate([q for _, q in self.lists]))
        return springs


def _set_params(springs: np.ndarray, params: np.ndarray) -> None:
    """Write ``params`` (n, 3: rest length, ks, kd) into the records ``springs`` of
    :data:`SPARSE_SPRING`."""
    for column, field in enumerate(("rest", "ks", "kd")):
        springs[field] = params[:, column]


def _offset_groups(pairs: np.ndarray, params: np.ndarray) -> tuple[_Grouping, list[np.ndarray]]:
    """The groups of :class:`Springs` in increasing offset (one per offset, stiffness and
    damping), and each group's rows of ``pairs``."""
    offsets = pairs[:, 1] - pairs[:, 0]
    keys, key_of = np.unique(np.column_stack([offsets, params[:, 1:]]), axis=0, return_inverse=True)
    grouping, members = _Grouping([], [], []), []
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
            block[REST, first - lo] = params[rows, 0]
            block[EXISTS, first - lo] = 1.0
            grouping.records.append((int(offset), lo, span, dense_used, True, ks, kd))
            grouping.blocks.append(block)
            dense_used += span
        else:
            grouping.records.append((int(offset), lo, len(rows), sparse_used, False, 0.0, 0.0))
            grouping.lists.append((pairs[rows], params[rows]))
            sparse_used += len(rows)
    return grouping, members
