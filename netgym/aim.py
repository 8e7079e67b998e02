"""The ballistic aim: the launch that sends the ball from a thrower through a point.

It solves the drag-free parabola through the point for each elevation in the scene's range and
keeps the steepest one (a horizontal opening, entered from above) or the flattest one (a
vertical mouth) whose speed is in range. In a scene with air it then corrects the speed and
azimuth by Newton's method on the flight through air (the wind it is given; none by default)
until the ball crosses the opening's plane at the point. The ballistic oracle of ``agents``
aims with it; netgym's tests and benchmarks throw with it.
"""

from __future__ import annotations

import math

import numpy as np

from netgym.config import SceneConfig
from netgym.launch import Thrower, from_range, launch_velocity
from netgym.physics.kernels import air
from netgym.physics.model.model import ball_drag_constant
from netgym.physics.model.opening import Opening

AIM_STEP = 2e-3               # s: step of the flights the aim tries
AIM_ITERATIONS = 8
AIM_TOLERANCE = 1e-3          # m: a miss this small is a hit
AIM_DELTA = (1e-3, 1e-2)      # finite-difference steps of speed (m/s) and azimuth (degrees)
AIM_ELEVATION_STEP = 5.0      # degrees between the elevations tried through air


def _solve_2x2(first: np.ndarray, second: np.ndarray, rhs: np.ndarray) -> np.ndarray | None:
    """The x with ``x[0] first + x[1] second = rhs`` (the matrix's two columns), by Cramer's
    rule, or None if the columns are parallel: plain IEEE arithmetic, the same bits on every
    machine (LAPACK's kernels, chosen by CPU, differ in the last bits)."""
    det = first[0] * second[1] - second[0] * first[1]
    if det == 0.0:
        return None
    return np.array([(rhs[0] * second[1] - second[0] * rhs[1]) / det, (first[0] * rhs[1] - rhs[0] * first[1]) / det])


class BallisticAim:
    """Launches of NetCatch-v0 through a point, by solving the launch parabola.

    :param scene: the environment's scene config (``env.unwrapped.scene``).
    :param max_elevation: steepest elevation considered for a horizontal opening (degrees).
    :param wind: the wind the flights through air are aimed in (m/s; none by default).
    """

    def __init__(self, scene: SceneConfig, max_elevation: float = 75.0, wind: np.ndarray | None = None) -> None:
        self.scene = scene
        self.opening = Opening.of_net(scene.net)
        self.from_above = self.opening.from_above
        self.max_elevation = max_elevation
        self.gravity = -scene.simulation.gravity
        self.drag = ball_drag_constant(scene)
        self.wind = np.zeros(3) if wind is None else np.asarray(wind, dtype=np.float64)

    def launch(self, distance: float, height: float) -> tuple[float, float]:
        """(speed m/s, elevation degrees) of the chosen parabola from a thrower at horizontal
        ``distance`` and ``height`` relative to the point aimed at (for :meth:`action`, the
        opening's centre)."""
        lo, hi = self.scene.throw.elevation
        elevations = np.linspace(lo, min(hi, self.max_elevation) if self.from_above else hi, 241)
        if self.from_above:
            elevations = elevations[::-1]
        vmin, vmax = self.scene.throw.speed
        best = None
        for elevation in elevations:
            theta = math.radians(elevation)
            rise = distance * math.tan(theta) + height  # height is thrower minus point
            if rise <= 0.0:
                continue
            speed = math.sqrt(self.gravity * distance ** 2 / (2.0 * math.cos(theta) ** 2 * rise))
            if vmin <= speed <= vmax:
                return speed, float(elevation)
            if best is None or abs(speed - np.clip(speed, vmin, vmax)) < abs(best[0] - np.clip(best[0], vmin, vmax)):
                best = (float(np.clip(speed, vmin, vmax)), float(elevation))
        return best if best is not None else (vmax, float(elevations[0]))

    def action(self, distance: float, height: float) -> np.ndarray:
        """The action (speed, elevation, azimuth offset in [-1, 1]) of :meth:`launch`."""
        speed, elevation = self.launch(distance, height)
        return np.array([from_range(speed, self.scene.throw.speed),
                         from_range(elevation, self.scene.throw.elevation), 0.0], dtype=np.float32)

    def aim(self, thrower: Thrower, target: np.ndarray) -> np.ndarray:
        """The action that sends the ball from ``thrower`` through ``target`` (a point of the
        opening's plane): the parabola, then, with air, Newton on speed and azimuth."""
        position = thrower.position
        offset = np.asarray(target, dtype=np.float64) - position
        distance = math.hypot(offset[0], offset[1])
        speed, elevation = self.launch(distance, -offset[2])
        azimuth = math.degrees(math.atan2(offset[1], offset[0]) - thrower.facing)
        azimuth = (azimuth + 180.0) % 360.0 - 180.0
        if self.drag > 0.0:
            speed, elevation, azimuth = self._through_air(thrower, target, speed, elevation, azimuth)
        t = self.scene.throw
        return np.clip([from_range(speed, t.speed), from_range(elevation, t.elevation), from_range(azimuth, t.azimuth)],
                       -1.0, 1.0).astype(np.float32)

    def _miss(self, thrower: Thrower, target: np.ndarray, speed: float, elevation: float, azimuth: float) -> np.ndarray:
        """Where the flight through air crosses the opening's plane, minus ``target`` (2 axes)."""
        o = self.opening
        point, _ = air.plane_crossing(thrower.position, launch_velocity(speed, elevation, azimuth, thrower),
                                      air.Plane(o.axis, o.plane, -o.sign), -self.gravity, self.drag, self.wind,
                                      self.scene.ball.radius, AIM_STEP, self.scene.simulation.time_limit)
        return np.array([point[a] - target[a] for a in o.tangent_axes])

    def _through_air(self, thrower: Thrower, target: np.ndarray, speed: float, elevation: float,
                     azimuth: float) -> tuple[float, float, float]:
        """(speed, elevation, azimuth) through air: Newton's method on speed and azimuth at the
        parabola's elevation, then at flatter ones (AIM_ELEVATION_STEP apart) while the speed
        needed is out of range; the smallest miss wins."""
        best = (math.inf, speed, elevation, azimuth)
        lowest = self.scene.throw.elevation[0]
        while elevation >= lowest:
            fit, miss = self._newton(thrower, target, speed, elevation, azimuth)
            if miss < best[0]:
                best = (miss, fit[0], elevation, fit[1])
            if miss < AIM_TOLERANCE or not self.from_above:
                break
            elevation -= AIM_ELEVATION_STEP
        return best[1], best[2], best[3]

    def _newton(self, thrower: Thrower, target: np.ndarray, speed: float, elevation: float,
                azimuth: float) -> tuple[np.ndarray, float]:
        """Newton's method (finite-difference Jacobian) on (speed, azimuth) for a zero miss at
        ``elevation``; returns them and the miss left (m)."""
        x = np.array([speed, azimuth])
        miss = self._miss(thrower, target, x[0], elevation, x[1])
        for _ in range(AIM_ITERATIONS):
            if math.hypot(*miss) < AIM_TOLERANCE:
                break
            faster = self._miss(thrower, target, x[0] + AIM_DELTA[0], elevation, x[1])
            turned = self._miss(thrower, target, x[0], elevation, x[1] + AIM_DELTA[1])
            step = _solve_2x2((faster - miss) / AIM_DELTA[0], (turned - miss) / AIM_DELTA[1], miss)
            if step is None:
                break
            x = x - step
            x[0] = float(np.clip(x[0], *self.scene.throw.speed))
            miss = self._miss(thrower, target, x[0], elevation, x[1])
        return x, math.hypot(*miss)
