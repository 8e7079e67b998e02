"""Closed-form motion of a lone ball: parabolic arcs, ground bounces and sliding to rest.

Used by the simulator's fast path while the ball cannot touch the net. The bounce is the
same impulse as the ground contact of :mod:`netgym.physics.kernels.impulse_contacts` (restitution above the
threshold, Coulomb friction bounded by friction times the normal impulse); a ball that no
longer bounces slides, decelerating at ``friction * |g|``.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from netgym.physics.kernels.air import bounce
from netgym.physics.kernels.jit import kernel

_MAX_ARCS = 200
STILL_SPEED = 1e-9  # m/s: a ball sliding slower than this on the ground lies still


class Ground(NamedTuple):
    """What a ball meets at the ground: its radius, gravity, restitution, friction, threshold
    (a record the kernels take too)."""

    radius: float
    gravity: float
    restitution: float
    friction: float
    threshold: float


Interval = tuple[float, float]


def _where_nonnegative(a: float, b: float, c: float) -> list[Interval]:
    """Times where ``a t^2 + b t + c >= 0``, as closed intervals."""
    if a == 0.0:
        if b == 0.0:
            return [(-math.inf, math.inf)] if c >= 0.0 else []
        root = -c / b
        return [(root, math.inf)] if b > 0.0 else [(-math.inf, root)]
    disc = b * b - 4.0 * a * c
    if disc < 0.0:
        return [(-math.inf, math.inf)] if a > 0.0 else []
    s = math.sqrt(disc)
    t1, t2 = sorted(((-b - s) / (2.0 * a), (-b + s) / (2.0 * a)))
    return [(-math.inf, t1), (t2, math.inf)] if a > 0.0 else [(t1, t2)]


def _intersect(first: list[Interval], second: list[Interval]) -> list[Interval]:
    out = []
    for lo1, hi1 in first:
        for lo2, hi2 in second:
            lo, hi = max(lo1, lo2), min(hi1, hi2)
            if lo <= hi:
                out.append((lo, hi))
    return out


def _arc_entry(p: np.ndarray, v: np.ndarray, g: float, lo: np.ndarray, hi: np.ndarray,
               duration: float) -> float | None:
    """First time in [0, duration] at which the parabola from (p, v) is inside the box."""
    times = [(0.0, duration)]
    for axis in range(2):
        times = _intersect(times, _where_nonnegative(0.0, v[axis], p[axis] - lo[axis]))
        times = _intersect(times, _where_nonnegative(0.0, -v[axis], hi[axis] - p[axis]))
    times = _intersect(times, _where_nonnegative(0.5 * g, v[2], p[2] - lo[2]))
    times = _intersect(times, _where_nonnegative(-0.5 * g, -v[2], hi[2] - p[2]))
    return min((t for t, _ in times), default=None)


@kernel
def ground_time(p: np.ndarray, v: np.ndarray, ground: Ground) -> float:
    """Time until the ball's lowest point reaches the ground (inf if it never does)."""
    height = p[2] - ground.radius
    if ground.gravity == 0.0:
        return height / -v[2] if v[2] < 0.0 else math.inf
    a, b = 0.5 * ground.gravity, v[2]
    disc = b * b - 4.0 * a * height
    return max(0.0, (-b - math.sqrt(max(disc, 0.0))) / (2.0 * a))


def _bounce(v: np.ndarray, ground: Ground) -> np.ndarray:
    """The velocity after the ground's impulse (:func:`~netgym.physics.kernels.air.bounce`)."""
    out = v.copy()
    bounce(out, ground.restitution, ground.friction, ground.threshold)
    return out


@kernel
def sliding(p: np.ndarray, v: np.ndarray, ground: Ground) -> bool:
    """The ball lies on the ground with no vertical speed (to rounding): it slides or lies still."""
    return p[2] <= ground.radius + 1e-12 and abs(v[2]) <= 1e-12


def lies_still(p: np.ndarray, v: np.ndarray, ground: Ground) -> bool:
    """The ball lies on the ground and has stopped sliding (to rounding: under 1 nm/s)."""
    return sliding(p, v, ground) and math.hypot(v[0], v[1]) < STILL_SPEED


def _slide(p: np.ndarray, v: np.ndarray, tau: float, ground: Ground) -> tuple[np.ndarray, np.ndarray]:
    speed = math.hypot(v[0], v[1])
    decel = ground.friction * -ground.gravity
    if speed == 0.0:
        return p.copy(), np.zeros(3)
    t = min(tau, speed / decel) if decel > 0.0 else tau
    dist = speed * t - 0.5 * decel * t * t
    direction = np.array([v[0], v[1], 0.0]) / speed
    new_speed = speed - decel * t
    return p + dist * direction, direction * new_speed


def advance(p: np.ndarray, v: np.ndarray, tau: float, ground: Ground) -> tuple[np.ndarray, np.ndarray]:
    """Position and velocity of the ball after ``tau`` seconds."""
    p, v = np.array(p, dtype=float), np.array(v, dtype=float)
    for _ in range(_MAX_ARCS):
        if sliding(p, v, ground):
            return _slide(p, v, tau, ground)
        t_ground = ground_time(p, v, ground)
        t = min(tau, t_ground)
        p = p + v * t
        p[2] += 0.5 * ground.gravity * t * t
        v = v.copy()
        v[2] += ground.gravity * t
        tau -= t
        if tau <= 0.0:
            return p, v
        p[2] = ground.radius
        v = _bounce(v, ground)
    return p, v


def entry_time(p: np.ndarray, v: np.ndarray, lo: np.ndarray, hi: np.ndarray, ground: Ground,
               horizon: float) -> float | None:
    """First time within ``horizon`` at which the ball's centre is inside the box [lo, hi]
    (bounces and sliding included); None if it never is."""
    p, v = np.array(p, dtype=float), np.array(v, dtype=float)
    elapsed = 0.0
    for _ in range(_MAX_ARCS):
        if elapsed > horizon:
            return None
        if sliding(p, v, ground):
            return _slide_entry(p, v, lo, hi, ground, elapsed, horizon)
        t_ground = min(ground_time(p, v, ground), horizon - elapsed)
        hit = _arc_entry(p, v, ground.gravity, lo, hi, t_ground)
        if hit is not None:
            return elapsed + hit
        if not math.isfinite(t_ground):
            return None
        p, v = advance(p, v, t_ground, ground)
        elapsed += t_ground
        if elapsed >= horizon:
            return None
        v = _bounce(v, ground)
    return None


def _slide_entry(p: np.ndarray, v: np.ndarray, lo: np.ndarray, hi: np.ndarray, ground: Ground,
                 elapsed: float, horizon: float) -> float | None:
    """Entry time of a ball sliding to rest along a straight line on the ground."""
    if not lo[2] <= p[2] <= hi[2]:
        return None
    speed = math.hypot(v[0], v[1])
    if speed == 0.0:
        return elapsed if (p >= lo).all() and (p <= hi).all() else None
    decel = ground.friction * -ground.gravity
    # at constant speed, the time that covers the stopping distance speed^2 / (2 decel)
    reach = speed / (2.0 * decel) if decel > 0.0 else horizon - elapsed
    hit = _arc_entry(p, np.array([v[0], v[1], 0.0]), 0.0, lo, hi, reach)
    if hit is None:
        return None
    distance = speed * hit
    if decel > 0.0:
        t = (speed - math.sqrt(max(speed * speed - 2.0 * decel * distance, 0.0))) / decel
    else:
        t = hit
    return elapsed + t if elapsed + t <= horizon else None
