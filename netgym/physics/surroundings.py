"""What a throw's decisions need to know about a ball's surroundings, in one numba pass."""

from __future__ import annotations

import math

from netgym.physics.jit import kernel


@kernel
def survey(x, v, row, reach, poles, box):
    """Scan every body around the ball in ``row``.

    Writes into ``box`` (6,) the bounding box (min x, y, z, max x, y, z) of every body but the
    ball and of the poles' axis end points. Returns ``(local, others)``: the largest velocity
    component of the bodies whose centres lie closer than ``reach`` to the ball's centre (the ball
    included), and of all bodies but the ball.
    """
    for c in range(3):
        box[c] = math.inf
        box[c + 3] = -math.inf
    for p in range(poles.shape[0]):
        for c in range(3):
            box[c] = min(box[c], poles[p, c], poles[p, c + 3])
            box[c + 3] = max(box[c + 3], poles[p, c], poles[p, c + 3])
    local = 0.0
    others = 0.0
    for k in range(x.shape[0]):
        speed = max(abs(v[k, 0]), abs(v[k, 1]), abs(v[k, 2]))
        d2 = (x[k, 0] - x[row, 0]) ** 2 + (x[k, 1] - x[row, 1]) ** 2 + (x[k, 2] - x[row, 2]) ** 2
        if d2 < reach * reach:
            local = max(local, speed)
        if k != row:
            others = max(others, speed)
            for c in range(3):
                box[c] = min(box[c], x[k, c])
                box[c + 3] = max(box[c + 3], x[k, c])
    return local, others
