"""What a throw's decisions need to know about a ball's surroundings, in one numba pass each:
the bodies around it, how far it is from them, and how long it takes to travel that far."""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from netgym.physics.kernels import air
from netgym.physics.kernels.impulse_contacts import COINCIDENT
from netgym.physics.kernels.jit import inline_kernel, kernel


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


@kernel
def speed(v):
    """Length of the velocity ``v`` (3,), summed in coordinate order (as every piece of flight
    measures it, whatever the machine's BLAS)."""
    return math.sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2])


@kernel
def travel_time(speed, acceleration, gap):
    """A time within which a body at ``speed``, accelerated by at most ``acceleration``, cannot
    travel ``gap``."""
    if acceleration == 0.0:
        return gap / speed
    return (-speed + math.sqrt(speed * speed + 4.0 * acceleration * gap)) / (2.0 * acceleration)


@kernel
def air_safe_time(speed, gap, gravity, k, wind, piece):
    """A time within which a ball at ``speed`` through air (drag constant ``k``, ``wind``)
    cannot travel ``gap``, at most ``piece``: its acceleration bounded over ``piece`` with the
    speed it could gain meanwhile (:func:`~netgym.physics.kernels.air.max_acceleration`)."""
    g0 = air.max_acceleration(speed, gravity, k, wind)
    g = air.max_acceleration(speed + g0 * piece, gravity, k, wind)
    return min(travel_time(speed, g, gap), piece)


@kernel
def clearance(x, n_net, row, radius, segments, poles):
    """How far the ball in ``row`` can move before it could touch a net particle or structural
    spring segment, a pole or another ball, all held still (exact distances). Negative when it
    already touches."""
    nearest = _net_nearest2(x, n_net, row, segments, None)
    return _balls_gap(x, n_net, row, radius, _poles_gap(x, row, radius, poles, math.sqrt(nearest) - radius))


@kernel
def movable_clearance(x, inv_mass, n_net, row, radius, segments):
    """How far the ball in ``row`` can move before it could touch anything that can move, all
    held still: a net particle of positive inverse mass, a structural spring segment with one,
    another ball (exact distances; poles, pinned particles and the ground left out). Negative
    when it already touches."""
    nearest = _net_nearest2(x, n_net, row, segments, inv_mass)
    return _balls_gap(x, n_net, row, radius, math.sqrt(nearest) - radius)


class LoneBall(NamedTuple):
    """What :func:`alone_for_a_step` reads of a scene: a record far cheaper to hand a kernel
    from Python than the :class:`~netgym.physics.model.model.KernelModel`, whose fields of the
    same names the kernels hand it instead."""

    n_net: int
    ball_radius: float
    segments: np.ndarray
    gravity: float
    ball_drag: float
    wind: np.ndarray

    @classmethod
    def of(cls, model) -> "LoneBall":
        """The record of a :class:`~netgym.physics.model.model.KernelModel`."""
        return cls(model.n_net, model.ball_radius, model.segments, model.gravity, model.ball_drag, model.wind)


@kernel
def alone_for_a_step(x, v, inv_mass, model, row, dt):
    """True if the ball in ``row`` can touch nothing that moves (:func:`movable_clearance`) within
    a step of ``dt``, everything else held still: it cannot travel a third of that gap meanwhile
    (the overlaps its contacts with poles and the ground push it out of are at most what it
    travelled into them, and a contact cannot speed it up). ``model``: the
    :class:`~netgym.physics.model.model.KernelModel`, or its :class:`LoneBall`."""
    gap = movable_clearance(x, inv_mass, model.n_net, row, model.ball_radius, model.segments)
    return gap > 0.0 and air_safe_time(speed(v[row]), gap / 3.0, model.gravity, model.ball_drag, model.wind, dt) >= dt


@kernel
def _net_nearest2(x, n_net, row, segments, inv_mass):
    """Squared distance from the centre of the ball in ``row`` to the nearest net particle or
    structural spring segment; with ``inv_mass`` (else None), to the nearest that can move."""
    cx, cy, cz = x[row, 0], x[row, 1], x[row, 2]
    nearest = math.inf
    for k in range(n_net):
        if inv_mass is not None and inv_mass[k] == 0.0:
            continue
        nearest = min(nearest, (x[k, 0] - cx) ** 2 + (x[k, 1] - cy) ** 2 + (x[k, 2] - cz) ** 2)
    for s in range(segments.shape[0]):
        i = segments[s, 0]
        j = segments[s, 1]
        if inv_mass is not None and inv_mass[i] == 0.0 and inv_mass[j] == 0.0:
            continue
        ex, ey, ez = x[j, 0] - x[i, 0], x[j, 1] - x[i, 1], x[j, 2] - x[i, 2]
        len2 = ex * ex + ey * ey + ez * ez
        if len2 < COINCIDENT:
            continue
        t = ((cx - x[i, 0]) * ex + (cy - x[i, 1]) * ey + (cz - x[i, 2]) * ez) / len2
        t = min(max(t, 0.0), 1.0)
        nearest = min(nearest, (x[i, 0] + t * ex - cx) ** 2 + (x[i, 1] + t * ey - cy) ** 2
                      + (x[i, 2] + t * ez - cz) ** 2)
    return nearest


@kernel
def clearance_at_least(x, n_net, row, radius, box, poles):
    """A lower bound on :func:`clearance`, cheaper: the net's part measured to its bounding
    ``box`` (6,: min x, y, z, max x, y, z), which holds every particle and spring segment."""
    nearest = 0.0
    for c in range(3):
        outside = max(box[c] - x[row, c], 0.0, x[row, c] - box[c + 3])
        nearest += outside * outside
    return _balls_gap(x, n_net, row, radius, _poles_gap(x, row, radius, poles, math.sqrt(nearest) - radius))


@inline_kernel
def _poles_gap(x, row, radius, poles, gap):
    """``gap``, or less: how far the ball in ``row`` is from the poles."""
    cx, cy, cz = x[row, 0], x[row, 1], x[row, 2]
    for p in range(poles.radius.shape[0]):
        ax, ay, az = poles.start[p, 0], poles.start[p, 1], poles.start[p, 2]
        ex, ey, ez = poles.end[p, 0] - ax, poles.end[p, 1] - ay, poles.end[p, 2] - az
        t = ((cx - ax) * ex + (cy - ay) * ey + (cz - az) * ez) / (ex * ex + ey * ey + ez * ez)
        t = min(max(t, 0.0), 1.0)
        d = math.sqrt((cx - ax - t * ex) ** 2 + (cy - ay - t * ey) ** 2 + (cz - az - t * ez) ** 2)
        gap = min(gap, d - radius - poles.radius[p])
    return gap


@inline_kernel
def _balls_gap(x, n_net, row, radius, gap):
    """``gap``, or less: how far the ball in ``row`` is from the other balls."""
    cx, cy, cz = x[row, 0], x[row, 1], x[row, 2]
    for b in range(n_net, x.shape[0]):
        if b != row:
            d = math.sqrt((x[b, 0] - cx) ** 2 + (x[b, 1] - cy) ** 2 + (x[b, 2] - cz) ** 2)
            gap = min(gap, d - 2.0 * radius)
    return gap
