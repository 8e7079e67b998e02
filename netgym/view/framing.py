"""What a view of a throw shows: the thrower's stick figure and a camera that frames the net,
the thrower and the ball's whole flight up to the net (its apex included).

Pure geometry, shared by the frames of :mod:`netgym.view.render` and the 3D page of
:mod:`netgym.view.replay_page`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

UP = np.array([0.0, 0.0, 1.0])
HIP, SHOULDER, HEAD = 0.95, 1.45, 1.65   # m above the ground
HEAD_RADIUS = 0.12                       # m
BODY_BEHIND = 0.3                        # m the body stands behind the release point
FLIGHT_POINTS = 60                       # samples of the flight that the camera frames
SIDE_ANGLE = 15.0                        # degrees the view turns from side-on to behind the thrower
LOOK_DOWN = 22.0                         # degrees below the horizon the camera looks
MARGIN = 0.88                            # of the half field of view the framed points may fill


@dataclass(frozen=True)
class Figure:
    """A thrower drawn as a stick figure: ``segments`` (k, 2, 3) limbs, a head at ``head``."""

    segments: np.ndarray
    head: np.ndarray
    head_radius: float = HEAD_RADIUS

    @property
    def points(self) -> np.ndarray:
        """Every end point of the limbs and the top of the head, (m, 3)."""
        return np.vstack([self.segments.reshape(-1, 3), self.head + [0.0, 0.0, self.head_radius]])


def _horizontal(direction: np.ndarray) -> np.ndarray:
    flat = np.array([direction[0], direction[1], 0.0])
    norm = float(np.linalg.norm(flat))
    return flat / norm if norm > 1e-9 else np.array([1.0, 0.0, 0.0])


def thrower_figure(release: np.ndarray, towards: np.ndarray) -> Figure:
    """The stick figure of a thrower whose hand is at ``release`` and who faces ``towards`` (a point)."""
    release = np.asarray(release, dtype=float)
    ahead = _horizontal(np.asarray(towards, dtype=float) - release)
    side = np.cross(UP, ahead)
    base = np.array([release[0], release[1], 0.0]) - BODY_BEHIND * ahead
    hip, shoulder = base + HIP * UP, base + SHOULDER * UP
    limbs = [(base + 0.18 * side, hip), (base - 0.18 * side, hip), (hip, shoulder), (shoulder, release),
             (shoulder, shoulder - 0.15 * ahead - 0.2 * side - 0.55 * UP)]
    return Figure(np.array(limbs, dtype=float), base + HEAD * UP)


def flight_points(release: np.ndarray, velocity: np.ndarray, gravity: float, reach: float,
                  floor: float) -> np.ndarray:
    """Points of the drag-free flight from ``release`` until it falls to height ``floor`` or is
    ``reach`` metres away horizontally, whichever comes first (air only lowers the apex)."""
    release, velocity = np.asarray(release, dtype=float), np.asarray(velocity, dtype=float)
    vz, g = velocity[2], -gravity
    fall = (vz + math.sqrt(max(vz * vz + 2.0 * g * (release[2] - floor), 0.0))) / g if g > 0 else math.inf
    speed = float(np.linalg.norm(velocity[:2]))
    end = min(fall, reach / speed) if speed > 1e-9 else fall
    end = end if math.isfinite(end) else 0.0
    t = np.linspace(0.0, max(end, 0.0), FLIGHT_POINTS)[:, None]
    return release + t * velocity + 0.5 * t * t * np.array([0.0, 0.0, gravity])


def side_view(release: np.ndarray, target: np.ndarray) -> np.ndarray:
    """The camera's forward direction for a throw from ``release`` to ``target``: side-on (the
    thrower on the left of the picture, the net on the right), turned a little to look from
    behind the thrower, looking down."""
    ahead = _horizontal(np.asarray(target, dtype=float) - np.asarray(release, dtype=float))
    turn = math.radians(SIDE_ANGLE)
    flat = math.cos(turn) * np.cross(UP, ahead) + math.sin(turn) * ahead
    down = math.radians(LOOK_DOWN)
    return math.cos(down) * flat - math.sin(down) * UP


def frame_points(points: np.ndarray, forward: np.ndarray, aspect: float, fov: float) -> tuple[np.ndarray, np.ndarray]:
    """``(eye, target)`` of the nearest camera looking along ``forward`` with vertical field of
    view ``fov`` (degrees) and width/height ``aspect`` that sees all ``points`` (k, 3)."""
    forward = np.asarray(forward, dtype=float) / np.linalg.norm(forward)
    right = np.cross(forward, UP)
    right /= np.linalg.norm(right)
    up = np.cross(right, forward)
    target = 0.5 * (points.min(axis=0) + points.max(axis=0))
    offset = points - target
    depth = offset @ forward
    tan_v = MARGIN * math.tan(math.radians(fov) / 2)
    distance = max(float(np.max(np.abs(offset @ right) / (aspect * tan_v) - depth)),
                   float(np.max(np.abs(offset @ up) / tan_v - depth)), 1.0)
    return target - distance * forward, target
