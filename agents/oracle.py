"""The ballistic oracle: a launch through the centre of the opening, and its relatives.

From the thrower's distance and height (the observation), it solves the drag-free parabola
through the opening's centre for each elevation in the scene's range and keeps the steepest
one (a horizontal opening, entered from above) or the flattest one (a vertical mouth) whose
speed is in range. In a scene with air it then corrects the speed and azimuth by Newton's
method on the flight through air (the wind it is given; none by default) until the ball
crosses the opening's plane at the centre. No learning; on NetCatch-v0 its capture rate is the
reference ceiling for learned agents.

- :class:`InformedOracle` is told each episode's hidden wind and draws (the ceiling of the
  variants that hide them);
- :class:`AdaptiveOracle` is not, and corrects its aim point from the feedback of its throws.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import numpy as np

from netgym.config import SceneConfig, load_scene
from netgym.envs import ObservationIndex
from netgym.errors import InvalidArgumentError
from netgym.launch import Thrower, from_range, launch_velocity
from netgym.physics.kernels import air
from netgym.physics.model.model import ball_drag_constant
from netgym.physics.model.opening import Opening

AIM_STEP = 2e-3               # s: step of the flights the oracle tries
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


class BallisticOracle:
    """Chooses actions of NetCatch-v0 by solving the launch parabola.

    :param scene: the environment's scene config (``env.unwrapped.scene``).
    :param max_elevation: steepest elevation considered for a horizontal opening (degrees).
    """

    def __init__(self, scene: SceneConfig, max_elevation: float = 75.0, wind: np.ndarray | None = None) -> None:
        self.scene = scene
        self.opening = Opening.of_net(scene.net)
        self.from_above = self.opening.from_above
        self.max_elevation = max_elevation
        self.gravity = -scene.simulation.gravity
        self.drag = ball_drag_constant(scene)
        self.wind = np.zeros(3) if wind is None else np.asarray(wind, dtype=np.float64)

    @classmethod
    def from_scene(cls, scene: SceneConfig | str | Path = "basket", max_elevation: float = 75.0) -> "BallisticOracle":
        """The oracle of a scene config, built-in scene name or TOML path."""
        return cls(scene if isinstance(scene, SceneConfig) else load_scene(scene), max_elevation)

    def launch(self, distance: float, height: float) -> tuple[float, float]:
        """(speed m/s, elevation degrees) of the chosen parabola from a thrower at horizontal
        ``distance`` and ``height`` relative to the opening's centre."""
        lo, hi = self.scene.throw.elevation
        elevations = np.linspace(lo, min(hi, self.max_elevation) if self.from_above else hi, 241)
        if self.from_above:
            elevations = elevations[::-1]
        vmin, vmax = self.scene.throw.speed
        best = None
        for elevation in elevations:
            theta = math.radians(elevation)
            rise = distance * math.tan(theta) + height  # height is thrower minus centre
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

    def thrower_of(self, row: np.ndarray) -> Thrower:
        """The thrower an observation describes."""
        centre = self.opening.centre
        bearing = math.degrees(math.atan2(row[ObservationIndex.BEARING_SIN], row[ObservationIndex.BEARING_COS]))
        return Thrower(distance=float(row[ObservationIndex.DISTANCE]), bearing=bearing,
                       height=float(row[ObservationIndex.HEIGHT]) + float(centre[2]),
                       centre=(float(centre[0]), float(centre[1])))

    def act(self, row: np.ndarray) -> np.ndarray:
        """The action for one observation: through the centre of the opening."""
        if self.drag == 0.0:
            return self.action(float(row[ObservationIndex.DISTANCE]), float(row[ObservationIndex.HEIGHT]))
        return self.aim(self.thrower_of(row), self.opening.centre)

    def predict(self, observation: np.ndarray, state=None, episode_start=None, deterministic: bool = True):
        """Stable-Baselines3-style ``predict`` for one observation or a batch of them (it reads
        the thrower's place relative to the opening)."""
        obs = np.asarray(observation, dtype=np.float64)
        batch = obs.reshape(-1, obs.shape[-1])
        actions = np.stack([self.act(row) for row in batch])
        return (actions if obs.ndim > 1 else actions[0]), state


class InformedOracle(BallisticOracle):
    """The ballistic oracle told each episode's hidden draws by the env (``env.unwrapped``): the
    wind and the scene the episode runs (the ball's mass and drag); the ceiling of the variants
    that hide them."""

    def __init__(self, env: Any, max_elevation: float = 75.0) -> None:
        super().__init__(env.unwrapped.scene, max_elevation)
        self.env = env.unwrapped

    def act(self, row: np.ndarray) -> np.ndarray:
        """Aim through the air, ball and wind of this episode."""
        self.scene = self.env.scene
        self.drag = self.env.sim.model.ball_drag
        self.wind = self.env.sim.model.wind.copy()
        return super().act(row)


class AdaptiveOracle(BallisticOracle):
    """The ballistic oracle (knows the drag, not the wind) that learns within an episode: it
    aims at ``centre - c`` and, after each throw, adds to ``c`` where the throw crossed the
    opening's plane relative to the centre (the env's ``feedback``), cancelling a steady drift.
    One env at a time (it keeps ``c`` between calls); ``c`` restarts with each episode."""

    def __init__(self, scene: SceneConfig, max_elevation: float = 75.0, gain: float = 1.0) -> None:
        super().__init__(scene, max_elevation)
        self.gain = gain
        self.correction = np.zeros(3)

    def act(self, row: np.ndarray) -> np.ndarray:
        """Update the correction from the feedback, then aim at the corrected point."""
        if len(row) <= ObservationIndex.LAST_SHORT:
            raise InvalidArgumentError("AdaptiveOracle needs the env's feedback (feedback=True)")
        if row[ObservationIndex.THROWS_LEFT] == 1.0:  # the first throw of an episode
            self.correction[:] = 0.0
        else:
            u, w = self.opening.tangent_axes
            self.correction[u] += self.gain * row[ObservationIndex.LAST_OFFSET_U]
            self.correction[w] += self.gain * row[ObservationIndex.LAST_OFFSET_W]
        return self.aim(self.thrower_of(row), self.opening.centre - self.correction)
