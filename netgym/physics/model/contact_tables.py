"""What contacts read of the scene: the material of each kind of contact and the poles (records
the contact kernels take)."""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from netgym.kinds import Contact


class Material(NamedTuple):
    """How a kind of contact responds: its coefficient of ``restitution`` and its Coulomb ``friction``."""

    restitution: float
    friction: float


class Materials(NamedTuple):
    """The :class:`Material` of each kind of contact (one field per :class:`Contact` member)."""

    ball_net: Material
    ball_pole: Material
    ball_ball: Material
    ball_ground: Material
    net_ground: Material

    @classmethod
    def of_table(cls, table: np.ndarray) -> "Materials":
        """The materials of a (restitution, friction) table with a row per :class:`Contact` kind."""
        return cls(*(Material(float(table[kind, 0]), float(table[kind, 1])) for kind in Contact))


class Poles(NamedTuple):
    """The poles, capsules: pole p runs from ``start[p]`` to ``end[p]`` (m) with ``radius[p]``."""

    start: np.ndarray
    end: np.ndarray
    radius: np.ndarray

    @classmethod
    def none(cls) -> "Poles":
        """No poles at all."""
        return cls(np.zeros((0, 3)), np.zeros((0, 3)), np.zeros(0))
