"""The ballistic oracle: a closed-form launch through the centre of the opening.

From the thrower's distance and height (the observation), it solves the drag-free parabola
through the opening's centre for each elevation in the scene's range and keeps the steepest
one (a horizontal opening, entered from above) or the flattest one (a vertical mouth) whose
speed is in range. No learning; its capture rate is the reference ceiling for learned agents.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from netgym.config import SceneConfig, load_scene
from netgym.envs import ObservationIndex
from netgym.launch import from_range
from netgym.physics.opening import Opening


class BallisticOracle:
    """Chooses actions of NetCatch-v0 by solving the launch parabola.

    :param scene: the environment's scene config (``env.unwrapped.scene``).
    :param max_elevation: steepest elevation considered for a horizontal opening (degrees).
    """

    def __init__(self, scene: SceneConfig, max_elevation: float = 75.0) -> None:
        self.scene = scene
        self.from_above = Opening.of_net(scene.net).from_above
        self.max_elevation = max_elevation
        self.gravity = -scene.simulation.gravity

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

    def predict(self, observation: np.ndarray, state=None, episode_start=None, deterministic: bool = True):
        """Stable-Baselines3-style ``predict`` for one observation or a batch of them (it reads
        the thrower's distance and height relative to the opening)."""
        obs = np.asarray(observation, dtype=np.float64)
        batch = obs.reshape(-1, obs.shape[-1])
        actions = np.stack([self.action(float(row[ObservationIndex.DISTANCE]), float(row[ObservationIndex.HEIGHT]))
                            for row in batch])
        return (actions if obs.ndim > 1 else actions[0]), state
