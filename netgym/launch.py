"""Throwers and launches: where a thrower stands, and how an action becomes a launch velocity.

A thrower stands at a horizontal ``distance`` and ``bearing`` from the centre of the net's
opening, at release ``height``. An action in ``[-1, 1]^3`` maps linearly onto the scene's
ranges of launch speed, elevation and azimuth offset (from the horizontal direction towards
the opening's centre).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from netgym.config import ThrowConfig
from netgym.physics.net import Opening


@dataclass(frozen=True)
class Thrower:
    """A release point: ``distance`` (m), ``bearing`` (degrees), ``height`` (m) around ``centre``."""

    distance: float
    bearing: float
    height: float
    centre: tuple[float, float]

    @property
    def position(self) -> np.ndarray:
        """Release point in world coordinates."""
        b = math.radians(self.bearing)
        return np.array([self.centre[0] + self.distance * math.cos(b),
                         self.centre[1] + self.distance * math.sin(b), self.height])

    @property
    def facing(self) -> float:
        """Horizontal direction (radians) from the thrower to the opening's centre."""
        return math.radians(self.bearing) + math.pi


def opening_centre(opening: Opening) -> np.ndarray:
    """Centre of the opening rectangle."""
    centre = np.zeros(3)
    centre[opening.axis] = opening.plane
    for axis, lo, hi in zip(opening.tangent_axes, opening.tangent_lower, opening.tangent_upper):
        centre[axis] = 0.5 * (lo + hi)
    return centre


def sample_thrower(cfg: ThrowConfig, opening: Opening, rng: np.random.Generator) -> Thrower:
    """Draw a thrower uniformly within the scene's distance, bearing and height ranges."""
    centre = opening_centre(opening)
    return Thrower(distance=float(rng.uniform(*cfg.distance)), bearing=float(rng.uniform(*cfg.bearing)),
                   height=float(rng.uniform(*cfg.height)), centre=(float(centre[0]), float(centre[1])))


def _scale(unit: float, bounds: tuple[float, float]) -> float:
    return bounds[0] + 0.5 * (unit + 1.0) * (bounds[1] - bounds[0])


def _unscale(value: float, bounds: tuple[float, float]) -> float:
    span = bounds[1] - bounds[0]
    return 0.0 if span == 0.0 else 2.0 * (value - bounds[0]) / span - 1.0


def action_to_velocity(action: np.ndarray, thrower: Thrower, cfg: ThrowConfig) -> np.ndarray:
    """Launch velocity (m/s) of an action in [-1, 1]^3 = (speed, elevation, azimuth offset)."""
    speed = _scale(float(action[0]), cfg.speed)
    elevation = math.radians(_scale(float(action[1]), cfg.elevation))
    azimuth = thrower.facing + math.radians(_scale(float(action[2]), cfg.azimuth))
    return speed * np.array([math.cos(elevation) * math.cos(azimuth),
                             math.cos(elevation) * math.sin(azimuth), math.sin(elevation)])


def velocity_to_action(velocity: np.ndarray, thrower: Thrower, cfg: ThrowConfig) -> np.ndarray:
    """The action (unclipped) whose launch velocity is ``velocity``; inverse of
    :func:`action_to_velocity` inside the ranges."""
    speed = float(np.linalg.norm(velocity))
    elevation = math.degrees(math.asin(velocity[2] / speed)) if speed > 0 else 0.0
    heading = math.atan2(velocity[1], velocity[0]) - thrower.facing
    offset = math.degrees(math.atan2(math.sin(heading), math.cos(heading)))
    return np.array([_unscale(speed, cfg.speed), _unscale(elevation, cfg.elevation), _unscale(offset, cfg.azimuth)])
