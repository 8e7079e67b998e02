"""What a throw's decisions need to know about a ball's surroundings, in one numba pass."""

from __future__ import annotations

import math

from netgym.physics.kernels.jit import kernel


@kernel
def survey(x, v, row, poles, box):
    """Scan every body around the ball in ``row``.

    Writes into ``box`` (6,) the bounding box (min x, y, z, max x, y, z) of every body but the
    ball and of the poles' axis end points. Returns the largest velocity component of all bodies
    but the ball.
    """
    for c in range(3):
        box[c] = math.inf
        box[c + 3] = -math.inf
    for p in range(poles.radius.shape[0]):
        for c in range(3):
            box[c] = min(box[c], poles.start[p, c], poles.end[p, c])
            box[c + 3] = max(box[c + 3], poles.start[p, c], poles.end[p, c])
    others = 0.0
    for k in range(x.shape[0]):
        if k != row:
            others = max(others, abs(v[k, 0]), abs(v[k, 1]), abs(v[k, 2]))
            for c in range(3):
                box[c] = min(box[c], x[k, c])
                box[c + 3] = max(box[c + 3], x[k, c])
    return others


@kernel
def still_since(x, earlier, row, reach, bound):
    """True if the ball in ``row`` and every body whose centre lies within ``reach`` of it now
    moved no coordinate by ``bound`` or more between ``earlier`` and ``x``."""
    cx, cy, cz = x[row, 0], x[row, 1], x[row, 2]
    for k in range(x.shape[0]):
        if (x[k, 0] - cx) ** 2 + (x[k, 1] - cy) ** 2 + (x[k, 2] - cz) ** 2 < reach * reach:
            for c in range(3):
                if not abs(x[k, c] - earlier[k, c]) < bound:
                    return False
    return True
