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
from netgym.physics.model.opening import Opening


LAUNCH_ENTRIES = (("speed", "launch speed", "m/s"), ("elevation", "elevation above the horizon", "degrees"),
                  ("azimuth", "azimuth offset from the direction to the opening's centre", "degrees"))
"""An action's entries in order: the :class:`~netgym.config.ThrowConfig` range each is mapped
onto, what it sets and its unit."""


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


def sample_thrower(cfg: ThrowConfig, opening: Opening, rng: np.random.Generator) -> Thrower:
    """Draw a thrower uniformly within the scene's distance, bearing and height ranges."""
    centre = opening.centre
    return Thrower(distance=float(rng.uniform(*cfg.distance)), bearing=float(rng.uniform(*cfg.bearing)),
                   height=float(rng.uniform(*cfg.height)), centre=(float(centre[0]), float(centre[1])))


def to_range(unit: float, bounds: tuple[float, float]) -> float:
    """Map ``unit`` in [-1, 1] linearly onto ``bounds``."""
    return bounds[0] + 0.5 * (unit + 1.0) * (bounds[1] - bounds[0])


def from_range(value: float, bounds: tuple[float, float]) -> float:
    """Inverse of :func:`to_range` (0 for an empty range)."""
    span = bounds[1] - bounds[0]
    return 0.0 if span == 0.0 else 2.0 * (value - bounds[0]) / span - 1.0


def action_to_launch(action: np.ndarray, cfg: ThrowConfig) -> tuple[float, float, float]:
    """(speed m/s, elevation degrees, azimuth offset degrees) of an action in [-1, 1]^3."""
    speed, elevation, azimuth = (to_range(float(a), getattr(cfg, field))
                                 for a, (field, _, _) in zip(action, LAUNCH_ENTRIES))
    return speed, elevation, azimuth


def launch_velocity(speed: float, elevation: float, azimuth: float, thrower: Thrower) -> np.ndarray:
    """Launch velocity (m/s) of a ``speed``, ``elevation`` (degrees above the horizon) and
    ``azimuth`` offset (degrees, to the left of the direction to the opening's centre)."""
    theta, phi = math.radians(elevation), thrower.facing + math.radians(azimuth)
    return speed * np.array([math.cos(theta) * math.cos(phi), math.cos(theta) * math.sin(phi), math.sin(theta)])
