"""The net's opening: the open face of the box, through which a ball must come in.

Every question about the opening (its centre, its lowest point, whether a point is inside the
box, how far a point is from it, its packed form for the kernels) is answered here.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from netgym.config import NetConfig
from netgym.physics.kernels.jit import inline_kernel, kernel


class OpeningRecord(NamedTuple):
    """The opening as the kernels take it (see :class:`Opening`): the plane ``p[axis] = plane``,
    ``sign`` (+1.0 or -1.0) towards its outer side, and the rectangle ``u_lo..u_hi`` x
    ``w_lo..w_hi`` on the tangent axes ``u`` and ``w``."""

    axis: int
    sign: float
    plane: float
    u: int
    w: int
    u_lo: float
    u_hi: float
    w_lo: float
    w_hi: float


@dataclass(frozen=True)
class Opening:
    """An axis-aligned rectangle in the plane ``p[axis] = plane``; points with
    ``sign * (p[axis] - plane) > 0`` are on the outer side of the box.

    ``tangent_axes`` are the two other axes; ``tangent_lower``/``tangent_upper`` bound the
    rectangle on them.
    """

    axis: int
    sign: int
    plane: float
    tangent_axes: tuple[int, int]
    tangent_lower: tuple[float, float]
    tangent_upper: tuple[float, float]

    @classmethod
    def of_net(cls, net: NetConfig) -> "Opening":
        """The opening of a scene's net: its ``open_face`` of the box ``lower``..``upper``."""
        axis, upper_side = "xyz".index(net.open_face[1]), net.open_face[0] == "+"
        u, w = [a for a in range(3) if a != axis]
        return cls(axis=axis, sign=1 if upper_side else -1,
                   plane=float(net.upper[axis] if upper_side else net.lower[axis]), tangent_axes=(u, w),
                   tangent_lower=(float(net.lower[u]), float(net.lower[w])),
                   tangent_upper=(float(net.upper[u]), float(net.upper[w])))

    @property
    def centre(self) -> np.ndarray:
        """Centre of the rectangle (a new array)."""
        centre = np.zeros(3)
        centre[self.axis] = self.plane
        for axis, lo, hi in zip(self.tangent_axes, self.tangent_lower, self.tangent_upper):
            centre[axis] = 0.5 * (lo + hi)
        return centre

    @property
    def lowest_z(self) -> float:
        """Height of the rectangle's lowest point."""
        if self.axis == 2:
            return self.plane
        return self.tangent_lower[self.tangent_axes.index(2)]

    @property
    def from_above(self) -> bool:
        """True for a horizontal opening (entered from above), False for a vertical mouth."""
        return self.axis == 2

    def depth(self, point: np.ndarray) -> float:
        """How far ``point`` lies past the opening's plane on the inner side (negative outside)."""
        return float(-self.sign * (point[self.axis] - self.plane))

    def contains(self, point: np.ndarray) -> bool:
        """True if ``point`` is on the inner side of the opening's plane and within the
        rectangle's extent: inside the box the opening closes."""
        u, w = self.tangent_axes
        inner = self.sign * (point[self.axis] - self.plane) < 0.0
        return bool(inner and self.tangent_lower[0] <= point[u] <= self.tangent_upper[0]
                    and self.tangent_lower[1] <= point[w] <= self.tangent_upper[1])

    def distance(self, points: np.ndarray) -> np.ndarray:
        """Distances from points (k, 3) to the rectangle."""
        out = np.empty(len(points))
        opening_distances(self.kernel_record(), np.asarray(points, dtype=np.float64), out)
        return out

    def kernel_record(self) -> OpeningRecord:
        """The form the kernels take."""
        (u, w), (ulo, wlo), (uhi, whi) = self.tangent_axes, self.tangent_lower, self.tangent_upper
        return OpeningRecord(int(self.axis), float(self.sign), float(self.plane), int(u), int(w), float(ulo),
                             float(uhi), float(wlo), float(whi))


@inline_kernel
def opening_depth(opening, point):
    """How far ``point`` (3 coordinates) lies past the plane of an :class:`OpeningRecord` on
    the inner side (negative outside), as :meth:`Opening.depth`."""
    return -opening.sign * (point[opening.axis] - opening.plane)


@inline_kernel
def opening_distance(opening, point):
    """Distance from ``point`` (3,) to the rectangle of an :class:`OpeningRecord`."""
    total = 0.0
    for c in range(3):
        if c == opening.axis:
            d = point[c] - opening.plane
        elif c == opening.u:
            d = point[c] - min(max(point[c], opening.u_lo), opening.u_hi)
        else:
            d = point[c] - min(max(point[c], opening.w_lo), opening.w_hi)
        total += d * d
    return math.sqrt(total)


@kernel
def opening_distances(opening, points, out):
    """Write into ``out`` (k,) the distances from ``points`` (k, 3) to the opening's rectangle."""
    for k in range(points.shape[0]):
        out[k] = opening_distance(opening, points[k])
