"""What the NetCatch variants vary and report: a hidden wind drawn per episode, scene fields
drawn per episode (domain randomisation), noise on the launch, and the feedback of the
previous throw (where it passed the opening)."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from netgym.arguments import is_real
from netgym.config import SceneConfig
from netgym.errors import InvalidArgumentError
from netgym.physics.kernels import air
from netgym.physics.simulator import Simulator
from netgym.physics.throw.free_flight import FreeFlight

FEEDBACK_LIMIT = 10.0     # m: feedback offsets are clipped to this


def _pair_or_triple(value: object, name: str, size: int, what: str) -> tuple[float, ...]:
    if (not isinstance(value, (tuple, list)) or len(value) != size
            or not all(is_real(x) and math.isfinite(float(x)) and float(x) >= 0.0 for x in value)):
        raise InvalidArgumentError(f"{name} = {value!r}; allowed: {size} numbers >= 0 ({what})")
    return tuple(float(x) for x in value)


@dataclass(frozen=True)
class WindRange:
    """A horizontal wind drawn per episode: speed uniform in ``[low, high]`` m/s, direction
    uniform around the compass."""

    low: float
    high: float

    @classmethod
    def parse(cls, value: object) -> "WindRange":
        """From a ``(low, high)`` pair of m/s."""
        low, high = _pair_or_triple(value, "wind", 2, "the range of wind speeds, m/s")
        if low > high:
            raise InvalidArgumentError(f"wind = {value!r}; allowed: an increasing (low, high) pair of speeds")
        return cls(low, high)

    def draw(self, rng: np.random.Generator) -> np.ndarray:
        """A wind velocity (m/s)."""
        speed, angle = rng.uniform(self.low, self.high), rng.uniform(0.0, 2.0 * math.pi)
        return np.array([speed * math.cos(angle), speed * math.sin(angle), 0.0])


@dataclass(frozen=True)
class LaunchNoise:
    """Gaussian noise on a release: standard deviations of the speed (m/s), the elevation and
    the azimuth (degrees)."""

    speed: float
    elevation: float
    azimuth: float

    @classmethod
    def parse(cls, value: object) -> "LaunchNoise":
        """From a ``(speed, elevation, azimuth)`` triple of standard deviations."""
        return cls(*_pair_or_triple(value, "launch_noise", 3, "standard deviations of speed m/s, elevation and "
                                                             "azimuth degrees"))

    def apply(self, speed: float, elevation: float, azimuth: float,
              rng: np.random.Generator) -> tuple[float, float, float]:
        """The released (speed, elevation, azimuth) of an intended one (speed kept >= 0)."""
        noise = rng.normal(0.0, 1.0, 3) * (self.speed, self.elevation, self.azimuth)
        return max(0.0, speed + noise[0]), elevation + noise[1], azimuth + noise[2]


@dataclass(frozen=True)
class SceneRanges:
    """Domain randomisation: scene fields drawn uniformly per episode, e.g.
    ``{"ball.mass": (0.5, 2.0), "springs.structural.ks": (1000, 3000)}``."""

    ranges: tuple[tuple[str, float, float], ...]

    @classmethod
    def parse(cls, value: object, scene: SceneConfig) -> "SceneRanges":
        """From a dict of dotted scene fields to ``(low, high)``; both ends must make a valid
        scene (a ConfigError names the field otherwise)."""
        if not isinstance(value, dict) or not value:
            raise InvalidArgumentError(f"randomize = {value!r}; allowed: a dict of scene fields to (low, high) ranges")
        ranges = []
        for field, bounds in value.items():
            if (not isinstance(bounds, (tuple, list)) or len(bounds) != 2
                    or not all(is_real(x) and math.isfinite(float(x)) for x in bounds)):
                raise InvalidArgumentError(f"randomize[{field!r}] = {bounds!r}; allowed: a (low, high) pair of numbers")
            low, high = float(bounds[0]), float(bounds[1])
            if low > high:
                raise InvalidArgumentError(f"randomize[{field!r}] = {bounds!r}; "
                                           "allowed: an increasing (low, high) pair")
            scene.replace({field: low})
            scene.replace({field: high})
            ranges.append((str(field), low, high))
        return cls(tuple(ranges))

    def draw(self, rng: np.random.Generator) -> dict[str, float]:
        """One value per field."""
        return {field: float(rng.uniform(low, high)) for field, low, high in self.ranges}


FEEDBACK_SIZE = 4
"""Feedback entries: caught (0/1), the offset of where the throw crossed the opening's plane
from the opening's centre along the plane's two axes (m; world x and y for the basket, y and z
for the goal), and how far short of the plane it stayed (m; 0 when it crossed)."""


def throw_feedback(sim: Simulator, launch: np.ndarray, velocity: np.ndarray, captured: bool) -> np.ndarray:
    """The :data:`FEEDBACK_SIZE` entries of a throw: its free flight from the launch (through
    the scene's air, without the net) meets the opening's plane somewhere; where, relative to
    the opening's centre."""
    opening = sim.opening
    point, crossed = FreeFlight.of(sim.model).plane_crossing(air.Plane(opening.axis, opening.plane, -opening.sign),
                                                             launch, velocity, sim.config.simulation.time_limit)
    u, w = opening.tangent_axes
    centre = opening.centre
    short = 0.0 if crossed else abs(point[opening.axis] - opening.plane)
    out = np.array([float(captured), point[u] - centre[u], point[w] - centre[w], short])
    out[1:] = np.clip(out[1:], -FEEDBACK_LIMIT, FEEDBACK_LIMIT)
    return out
