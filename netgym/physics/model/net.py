"""Builds the five-face net (particles, springs, fixed particles, poles) from a scene config.

The net is the surface of an axis-aligned box sampled on a lattice of ``particles`` points per
axis, less the interior of the open face. Faces share their edge particles. Springs are laid
per face on its 2D grid: structural (grid neighbours), shear (both diagonals) and bending
(second neighbours); a spring on an edge shared by two faces exists once.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from netgym.config import NetConfig
from netgym.kinds import SpringKind
from netgym.physics.model.opening import Opening

_OFFSETS = {
    SpringKind.STRUCTURAL: ((1, 0), (0, 1)),
    SpringKind.SHEAR: ((1, 1), (1, -1)),
    SpringKind.BENDING: ((2, 0), (0, 2)),
}


@dataclass(frozen=True)
class NetGeometry:
    """The built net: rest positions, fixed flags, springs (by kind) and pole capsules."""

    positions: np.ndarray          # (n, 3) rest positions
    lattice: np.ndarray            # (n, 3) integer lattice coordinates
    fixed: np.ndarray              # (n,) bool
    springs: np.ndarray            # (s, 2) particle indices, i < j
    spring_kind: np.ndarray        # (s,) SpringKind codes
    poles: np.ndarray              # (p, 6) capsule axis end points a, b
    opening: Opening


def face_list(open_face: str) -> list[tuple[int, int]]:
    """The five net faces as (axis, side) pairs, side 0 = lower, 1 = upper; the open one left out."""
    open_axis, open_side = "xyz".index(open_face[1]), int(open_face[0] == "+")
    return [(a, s) for a in range(3) for s in (0, 1) if (a, s) != (open_axis, open_side)]


def _face_grid(counts: tuple[int, int, int], axis: int, side: int) -> tuple[tuple[int, int], np.ndarray]:
    """The lattice points of one face as a 2D grid: ((nu, nw), array (nu, nw, 3))."""
    u, w = [a for a in range(3) if a != axis]
    nu, nw = counts[u], counts[w]
    grid = np.zeros((nu, nw, 3), dtype=np.int64)
    grid[..., axis] = side * (counts[axis] - 1)
    grid[..., u] = np.arange(nu)[:, None]
    grid[..., w] = np.arange(nw)[None, :]
    return (nu, nw), grid


def build_net(cfg: NetConfig, keep_fixed_pairs: bool = False) -> NetGeometry:
    """Build the net of ``cfg``.

    :param cfg: the net section of a scene.
    :param keep_fixed_pairs: keep springs whose two ends are both fixed (they exert no force
        on anything; they are dropped by default).
    """
    counts = cfg.particles
    lower, upper = np.asarray(cfg.lower), np.asarray(cfg.upper)
    open_axis, open_side = "xyz".index(cfg.open_face[1]), int(cfg.open_face[0] == "+")

    index: dict[tuple[int, int, int], int] = {}
    pairs: dict[tuple[int, int], int] = {}
    for axis, side in face_list(cfg.open_face):
        (nu, nw), grid = _face_grid(counts, axis, side)
        ids = np.empty((nu, nw), dtype=np.int64)
        for a in range(nu):
            for b in range(nw):
                key = tuple(int(c) for c in grid[a, b])
                ids[a, b] = index.setdefault(key, len(index))
        for kind, offsets in _OFFSETS.items():
            for da, db in offsets:
                for a in range(nu):
                    for b in range(nw):
                        a2, b2 = a + da, b + db
                        if 0 <= a2 < nu and 0 <= b2 < nw:
                            i, j = sorted((int(ids[a, b]), int(ids[a2, b2])))
                            pairs.setdefault((i, j), kind)

    lattice = np.array(list(index), dtype=np.int64)
    top = np.array(counts) - 1
    positions = lower + (upper - lower) * lattice / top
    on_open = lattice[:, open_axis] == open_side * top[open_axis]
    others = [a for a in range(3) if a != open_axis]
    at_extreme = (lattice == 0) | (lattice == top)
    on_side_edge = at_extreme[:, others[0]] & at_extreme[:, others[1]]
    fixed = on_open | (on_side_edge if cfg.fix_side_edges else False)

    springs = np.array(list(pairs), dtype=np.int64).reshape(-1, 2)
    kinds = np.array(list(pairs.values()), dtype=np.int8)
    if not keep_fixed_pairs:
        moving = ~(fixed[springs[:, 0]] & fixed[springs[:, 1]])
        springs, kinds = springs[moving], kinds[moving]
    order = np.lexsort((springs[:, 1], springs[:, 0]))  # memory order: cache-friendly loop
    return NetGeometry(
        positions=positions,
        lattice=lattice,
        fixed=fixed,
        springs=springs[order],
        spring_kind=kinds[order],
        poles=_poles(cfg, lower, upper, open_axis, open_side),
        opening=Opening.of_net(cfg),
    )


def _poles(cfg: NetConfig, lower: np.ndarray, upper: np.ndarray, open_axis: int, open_side: int) -> np.ndarray:
    """Fixed box edges above the ground, as capsule axes (a, b): the rim / frame and the side
    edges when they are fixed."""
    u, w = [a for a in range(3) if a != open_axis]
    # an edge runs along one axis from lower to upper; the other two axes sit at a side (0 / 1)
    edges = [(along, {open_axis: open_side, across: s}) for along, across in ((u, w), (w, u)) for s in (0, 1)]
    if cfg.fix_side_edges:
        edges += [(open_axis, {u: su, w: sw}) for su in (0, 1) for sw in (0, 1)]
    poles = []
    for along, sides in edges:
        a = np.array([upper[k] if sides.get(k, 0) else lower[k] for k in range(3)])
        b = a.copy()
        b[along] = upper[along]
        if max(a[2], b[2]) > 0.0:  # an edge lying on the ground is no pole
            poles.append(np.concatenate([a, b]))
    return np.array(poles, dtype=np.float64).reshape(-1, 6)
