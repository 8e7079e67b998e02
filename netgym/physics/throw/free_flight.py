"""One lone ball's free flight: the one object every question about it is asked of.

Without air the flight is closed form (:mod:`netgym.physics.fast_path.flight`: arcs, bounces, sliding);
through air it is integrated (:mod:`netgym.physics.kernels.air`: RK4 steps, the same bounce). The fast
path asks it where the ball is after a while, whether it can still come into a box, and how
long it certainly takes to travel a distance; the environment asks how close a throw's flight
came to the opening (the shaped reward) and where it crossed the opening's plane (the
feedback), both measured on its flight from the launch to the ground in steps of
:data:`MEASURE_STEP`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from netgym.physics.kernels import air, surroundings

from netgym.physics.fast_path import flight
from netgym.physics.model.model import Model
from netgym.physics.model.opening import Opening

MEASURE_STEP = 2e-3  # s: step of the flights the shaped reward and the feedback are measured on


@dataclass(frozen=True)
class FreeFlight:
    """The free flight of a scene's ball: its ``ground`` (radius, gravity, the ground's
    restitution, friction and threshold), the air's drag constant ``drag`` (0: no air) and
    ``wind`` (m/s)."""

    ground: flight.Ground
    drag: float
    wind: np.ndarray

    @classmethod
    def of(cls, model: Model) -> "FreeFlight":
        """The free flight of ``model``'s ball over its ground, through its air."""
        ground = model.kernel.materials.ball_ground
        return cls(flight.Ground(model.ball_radius, model.gravity, ground.restitution, ground.friction,
                                 model.restitution_threshold), model.ball_drag, model.wind)

    @property
    def parabola(self) -> bool:
        """No air: the flight is closed form."""
        return self.drag == 0.0

    def advance(self, x: np.ndarray, v: np.ndarray, tau: float) -> tuple[np.ndarray, np.ndarray]:
        """Where a ball starting at ``x``, ``v`` is after ``tau``: closed form without air, RK4
        steps through air."""
        if self.parabola:
            return flight.advance(x, v, tau, self.ground)
        p, u = np.array(x, dtype=np.float64), np.array(v, dtype=np.float64)
        air.fly(p, u, tau, self.drag, self.wind, self.ground, air.MAX_FLIGHT_STEP)
        return p, u

    def never_enters(self, p: np.ndarray, v: np.ndarray, lo: np.ndarray, hi: np.ndarray, horizon: float) -> bool:
        """The ball at ``p``, ``v`` cannot come into the box ``lo``..``hi`` within ``horizon``:
        its parabola (with bounces) misses it; through air, it lies outside, held by friction,
        or too far to come back within ``horizon`` (:func:`~netgym.physics.kernels.air.cannot_reach`)."""
        if not ((p < lo).any() or (p > hi).any()):
            return False  # inside it already
        if self.parabola:
            return flight.entry_time(p, v, lo, hi, self.ground, horizon) is None
        g = self.ground
        return (air.held_by_friction(v, g.gravity, self.drag, self.wind, g.radius, g.friction, p)
                or air.cannot_reach(p, v, self.wind, np.concatenate((lo, hi)), horizon))

    def safe_time(self, v: np.ndarray, gap: float, air_piece: float) -> float:
        """A time within which a ball at velocity ``v`` cannot travel ``gap`` (through air, at
        most ``air_piece``)."""
        speed = surroundings.speed(v)
        if self.parabola:
            return surroundings.travel_time(speed, abs(self.ground.gravity), gap)
        return surroundings.air_safe_time(speed, gap, self.ground.gravity, self.drag, self.wind, air_piece)

    def landing_time(self, p: np.ndarray, v: np.ndarray) -> float:
        """Time until the ball's lowest point first reaches the ground (its parabola)."""
        return flight.ground_time(p, v, self.ground)

    def miss_distance(self, opening: Opening, p: np.ndarray, v: np.ndarray, t_max: float) -> float:
        """Closest distance between the ``opening`` rectangle and the ball's flight from ``p``,
        ``v`` until its lowest point first reaches the ground (or ``t_max``), the net and the
        poles ignored: how close a throw came."""
        points = air.flight_path(_vector(p), _vector(v), self.ground.gravity, self.drag, self.wind,
                                 self.ground.radius, MEASURE_STEP, t_max)
        return float(opening.distance(points).min())

    def plane_crossing(self, plane: air.Plane, p: np.ndarray, v: np.ndarray, t_max: float) -> tuple[np.ndarray, bool]:
        """Where the ball's flight from ``p``, ``v`` (until the ground or ``t_max``) crosses
        ``plane`` the way it points, and True; else the point of it nearest the plane, and False."""
        return air.plane_crossing(_vector(p), _vector(v), plane, self.ground.gravity, self.drag, self.wind,
                                  self.ground.radius, MEASURE_STEP, t_max)


def _vector(x: np.ndarray) -> np.ndarray:
    """``x`` as the float64 3-vector the kernels take."""
    return np.asarray(x, dtype=np.float64)
