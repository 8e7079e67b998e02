"""Air on a ball: quadratic drag towards the wind, and the flight of a lone ball through it.

A ball's acceleration is ``g - k |v - wind| (v - wind)`` with ``k = 0.5 rho C_d A / m`` (see
:func:`~netgym.physics.model.model.ball_drag_constant`). Its flight has no closed form, so
:func:`fly` integrates it with classical RK4 in steps of at most ``max_step`` (the fast path's
flight; error far below the contacts' own, see ``tests/physics/test_air.py``), with the same ground
bounce as :mod:`netgym.physics.fast_path.flight`, and sliding on the ground against Coulomb friction
with the wind pushing. :func:`rk4_step` is also the balls' free flight inside the kernels.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np
from netgym.physics.kernels.jit import kernel
from netgym.physics.kernels.rows import copy_vector

MAX_FLIGHT_STEP = 1e-3   # s: longest RK4 step of the fast path's flight through air
SPEED_SLACK = 0.05       # m/s: added to the speed bound of :func:`cannot_reach` (sliding's explicit steps)
CONTACT_ITERATIONS = 4   # Newton iterations on the time a step meets the ground


@kernel
def _acceleration(v0, v1, v2, gravity, k, wind):
    u0, u1, u2 = v0 - wind[0], v1 - wind[1], v2 - wind[2]
    speed = math.sqrt(u0 * u0 + u1 * u1 + u2 * u2)
    return -k * speed * u0, -k * speed * u1, gravity - k * speed * u2


@kernel
def rk4_step(p, v, h, gravity, k, wind):
    """Advance one ball's position ``p`` and velocity ``v`` (3-vectors, in place) by ``h``
    through air: classical RK4 on ``x' = v, v' = g - k |v - wind| (v - wind)``."""
    x0, x1, x2, w0, w1, w2 = p[0], p[1], p[2], v[0], v[1], v[2]
    a0, a1, a2 = _acceleration(w0, w1, w2, gravity, k, wind)
    b0, b1, b2 = _acceleration(w0 + 0.5 * h * a0, w1 + 0.5 * h * a1, w2 + 0.5 * h * a2, gravity, k, wind)
    c0, c1, c2 = _acceleration(w0 + 0.5 * h * b0, w1 + 0.5 * h * b1, w2 + 0.5 * h * b2, gravity, k, wind)
    d0, d1, d2 = _acceleration(w0 + h * c0, w1 + h * c1, w2 + h * c2, gravity, k, wind)
    p[0] = x0 + h / 6.0 * (w0 + 2.0 * (w0 + 0.5 * h * a0) + 2.0 * (w0 + 0.5 * h * b0) + (w0 + h * c0))
    p[1] = x1 + h / 6.0 * (w1 + 2.0 * (w1 + 0.5 * h * a1) + 2.0 * (w1 + 0.5 * h * b1) + (w1 + h * c1))
    p[2] = x2 + h / 6.0 * (w2 + 2.0 * (w2 + 0.5 * h * a2) + 2.0 * (w2 + 0.5 * h * b2) + (w2 + h * c2))
    v[0] = w0 + h / 6.0 * (a0 + 2.0 * b0 + 2.0 * c0 + d0)
    v[1] = w1 + h / 6.0 * (a1 + 2.0 * b1 + 2.0 * c1 + d1)
    v[2] = w2 + h / 6.0 * (a2 + 2.0 * b2 + 2.0 * c2 + d2)


@kernel
def bounce(v, restitution, friction, threshold):
    """A lone ball's ground impulse, on its velocity ``v`` in place (the one law of the closed-form
    flights of :mod:`netgym.physics.fast_path.flight` and of :func:`fly`): restitution above the
    threshold, Coulomb friction bounded by friction times the normal impulse."""
    closing = v[2]
    e = restitution if -closing > threshold else 0.0
    jn = -(1.0 + e) * closing
    v[2] = -e * closing
    slip = math.sqrt(v[0] * v[0] + v[1] * v[1])
    if slip > 1e-12:
        scale = 1.0 - min(friction * jn, slip) / slip
        v[0] *= scale
        v[1] *= scale


@kernel
def _slide_step(v, h, gravity, k, wind, friction):
    """One explicit step of a ball sliding on the ground: wind drag against Coulomb friction
    (``friction * |g|``), which stops the ball rather than reverse it."""
    a0, a1, _ = _acceleration(v[0], v[1], 0.0, 0.0, k, wind)
    speed = math.sqrt(v[0] * v[0] + v[1] * v[1])
    grip = friction * -gravity
    if speed > 1e-12:
        n0, n1 = v[0] + h * (a0 - grip * v[0] / speed), v[1] + h * (a1 - grip * v[1] / speed)
        if n0 * v[0] + n1 * v[1] <= 0.0 and math.sqrt(a0 * a0 + a1 * a1) <= grip:
            n0, n1 = 0.0, 0.0   # friction stops it and holds it
        v[0], v[1] = n0, n1
    else:
        push = math.sqrt(a0 * a0 + a1 * a1)
        if push > grip:
            v[0] += h * (a0 - grip * a0 / push)
            v[1] += h * (a1 - grip * a1 / push)
        else:
            v[0], v[1] = 0.0, 0.0


@kernel
def fly(p, v, tau, k, wind, ground, max_step):
    """Move a lone ball (``p``, ``v`` 3-vectors, in place) through air for ``tau`` seconds:
    RK4 steps of at most ``max_step`` while airborne, the ground bounce where its lowest point
    reaches the ground (the step is cut at the contact), sliding once it no longer bounces.
    ``ground``: a :class:`~netgym.physics.fast_path.flight.Ground` (the ball's radius, gravity, and the
    ground's restitution, friction and restitution threshold)."""
    radius, gravity, restitution, friction, threshold = ground
    left = tau
    start_p, start_v = np.empty(3), np.empty(3)   # the step's start, kept to cut it at the ground
    while left > 1e-15:
        h = min(max_step, left)
        if p[2] <= radius + 1e-12 and abs(v[2]) <= 1e-12:   # on the ground, not bouncing: sliding
            p[2], v[2] = radius, 0.0
            _slide_step(v, h, gravity, k, wind, friction)
            p[0] += h * v[0]
            p[1] += h * v[1]
            left -= h
            continue
        copy_vector(start_p, p)
        copy_vector(start_v, v)
        rk4_step(p, v, h, gravity, k, wind)
        if p[2] < radius and v[2] < 0.0:
            # cut the step where the ball meets the ground (Newton on the height), then bounce
            cut = h * (start_p[2] - radius) / max(start_p[2] - p[2], 1e-15)
            for _ in range(CONTACT_ITERATIONS):
                copy_vector(p, start_p)
                copy_vector(v, start_v)
                rk4_step(p, v, cut, gravity, k, wind)
                if v[2] >= 0.0:
                    break
                cut = min(h, max(0.0, cut - (p[2] - radius) / v[2]))
            copy_vector(p, start_p)
            copy_vector(v, start_v)
            rk4_step(p, v, cut, gravity, k, wind)
            p[2] = radius
            bounce(v, restitution, friction, threshold)
            left -= cut
        else:
            left -= h


@kernel
def held_by_friction(v, gravity, k, wind, radius, friction, p):
    """True if the ball lies still on the ground and the wind cannot push it past friction."""
    if p[2] > radius + 1e-9 or abs(v[0]) + abs(v[1]) + abs(v[2]) > 1e-12:
        return False
    a0, a1, _ = _acceleration(0.0, 0.0, 0.0, 0.0, k, wind)
    return math.sqrt(a0 * a0 + a1 * a1) <= friction * -gravity


@kernel
def cannot_reach(p, v, wind, box, horizon):
    """True if a lone ball at ``p``, ``v`` cannot come into ``box`` (6,: min x, y, z, max x, y,
    z) within ``horizon`` seconds: along a horizontal axis it lies outside the box farther than
    it can travel towards it. Along each horizontal axis its velocity stays between its value
    now, the wind's and zero (drag only relaxes it towards the wind's, the ground's friction
    towards zero), so it travels towards the box at most ``horizon`` times the largest of
    those towards it (plus :data:`SPEED_SLACK`)."""
    for c in range(2):
        if p[c] < box[c]:
            gap, towards = box[c] - p[c], max(v[c], wind[c], 0.0)
        elif p[c] > box[c + 3]:
            gap, towards = p[c] - box[c + 3], max(-v[c], -wind[c], 0.0)
        else:
            continue
        if gap > horizon * (towards + SPEED_SLACK):
            return True
    return False


def wind_power_bound(mass: float, k: float, wind: np.ndarray) -> float:
    """The most power (W) the wind can feed one ball: drag ``F = -m k |u| u`` with
    ``u = v - wind`` does work ``F.v <= m k |v| (|w|^2 - |v|^2)`` (from ``|u| <= |v| + |w|`` and
    ``u.v >= |v|^2 - |w||v|``), largest at ``|v| = |w| / sqrt(3)``: ``2 / (3 sqrt 3) m k |w|^3``."""
    return 2.0 / (3.0 * math.sqrt(3.0)) * mass * k * math.sqrt(wind.dot(wind)) ** 3  # |wind|, as np.linalg.norm sums it


@kernel
def max_acceleration(speed, gravity, k, wind):
    """A bound on a ball's acceleration while its speed stays below ``speed``."""
    w = math.sqrt(wind[0] * wind[0] + wind[1] * wind[1] + wind[2] * wind[2])
    return abs(gravity) + k * (speed + w) ** 2


@kernel
def flight_path(p, v, gravity, k, wind, radius, step, t_max):
    """The positions of a lone ball's free flight from ``p``, ``v`` through air every ``step``
    seconds, from the launch until its lowest point first reaches the ground (that point
    included) or ``t_max``: an (n, 3) array."""
    count = int(t_max / step) + 1
    points = np.empty((count + 1, 3))
    q, u = p.copy(), v.copy()
    copy_vector(points[0], q)
    n = 1
    while n <= count:
        rk4_step(q, u, step, gravity, k, wind)
        copy_vector(points[n], q)
        n += 1
        if q[2] < radius and u[2] < 0.0:
            break
    return points[:n]


class Plane(NamedTuple):
    """The plane ``x[axis] = value``, crossed ``inwards`` (+1 or -1: the way it points)."""

    axis: int
    value: float
    inwards: float


@kernel
def plane_crossing(p, v, plane, gravity, k, wind, radius, step, t_max):
    """Where a lone ball's free flight from ``p``, ``v`` (through air, until its lowest point
    first reaches the ground or ``t_max``) crosses the :class:`Plane` moving the way it points.
    Returns ``(point, crossed)``; when it never crosses, the point of the flight nearest the
    plane (on the side it came from) and False."""
    axis, value, inwards = plane
    q, u = p.copy(), v.copy()
    nearest = q.copy()
    before_q = np.empty(3)
    t = 0.0
    while t < t_max:
        copy_vector(before_q, q)
        rk4_step(q, u, step, gravity, k, wind)
        t += step
        h0 = inwards * (value - before_q[axis])   # > 0: still before the plane
        h1 = inwards * (value - q[axis])
        if h0 > 0.0 and h1 <= 0.0:
            s = h0 / (h0 - h1)
            return before_q + s * (q - before_q), True
        if abs(value - q[axis]) < abs(value - nearest[axis]):
            copy_vector(nearest, q)
        if q[2] < radius and u[2] < 0.0:
            break
    return nearest, False
