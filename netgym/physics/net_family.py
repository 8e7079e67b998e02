"""Nets drawn per episode (domain randomisation) without settling each one from scratch.

A scene whose fields are drawn from ranges every episode needs, for each draw, the settled net
(the equilibrium of the empty net under gravity) and the stability of its integrators there
(the scene's ``dt`` is checked against it, and the pause steps at a share of it). Settling a
new net and analysing its modes takes about half a second a draw; a :class:`NetFamily` does
that work once, on a few members of the family, and serves every draw from them:

- **the equilibrium**: fields the empty net's equilibrium does not depend on (the ball, the
  contacts, the air, the springs' damping) leave the settled net as it is; one drawn spring
  stiffness moves it smoothly, so the family settles the net from scratch at
  :data:`EQUILIBRIA` stiffnesses across its range and interpolates between the three nearest
  (quadratic in ``1 / ks``: the sag of a spring goes as its compliance);
- **the stability**: the net's modes at every corner of the drawn springs' ranges and at their
  centre; each draw gets the least stable of them (the highest frequency and damping rate, the
  smallest IMEX Euler limit).

Draws of other fields, of more than one stiffness, or scenes that differ from the family's in
anything but its drawn fields are settled from scratch as before. ``tests/physics/test_net_family.py``
holds the interpolated nets to nets settled from scratch, and the modes to each draw's own.
"""

from __future__ import annotations

import dataclasses
import functools
import itertools
from collections.abc import Sequence
from typing import Any

import numpy as np

from netgym.config import SceneConfig, to_dict
from netgym.physics.model.model import Model
from netgym.physics.simulator import PreparedNet, Simulator, prepare_net
from netgym.physics.stability import NetModes, net_modes

EQUILIBRIUM_FREE_SECTIONS = ("ball", "contact", "air")
"""Scene sections none of whose fields moves the empty net's equilibrium."""
EQUILIBRIA = 5
"""Stiffnesses across a drawn stiffness range at which the family settles the net from scratch."""

CACHED_FAMILIES = 8
"""Families kept per process."""

Range = tuple[str, float, float]   # a drawn field: (dotted name, low, high)


def field_value(config: SceneConfig, dotted: str) -> Any:
    """The value of the dotted field ``dotted`` of ``config``."""
    node: Any = to_dict(config)
    for key in dotted.split("."):
        node = node[key]
    return node


def _kind(dotted: str) -> str:
    """How a drawn field bears on the net: ``"free"`` (not on its equilibrium), ``"damping"``,
    ``"stiffness"`` (of a spring type) or ``"other"``."""
    parts = dotted.split(".")
    if parts[0] in EQUILIBRIUM_FREE_SECTIONS:
        return "free"
    if parts[0] == "springs" and len(parts) == 3:
        return {"kd": "damping", "ks": "stiffness"}.get(parts[2], "other")
    return "other"


class NetFamily:
    """The nets of ``scene`` with the fields of ``ranges`` drawn (see the module docstring).

    :param scene: the scene every draw starts from.
    :param ranges: the drawn fields, ``(dotted name, low, high)``.
    """

    def __init__(self, scene: SceneConfig, ranges: Sequence[Range]) -> None:
        self.scene = scene
        self.ranges = tuple(ranges)
        kinds = [_kind(field) for field, _, _ in self.ranges]
        self.stiffness = [r for r, kind in zip(self.ranges, kinds) if kind == "stiffness"]
        self.springs = [r for r, kind in zip(self.ranges, kinds) if kind in ("stiffness", "damping")]
        self.served = "other" not in kinds and len(self.stiffness) <= 1
        self._nominal = {field: field_value(scene, field) for field, _, _ in self.ranges}
        self._equilibria: list[tuple[float, np.ndarray]] | None = None
        self._modes: tuple[NetModes, NetModes] | None = None

    def serves(self, config: SceneConfig) -> bool:
        """Whether ``config`` is a member: the family's scene with only its drawn fields (and its
        air) changed, and the family can serve draws at all (no other fields, at most one stiffness)."""
        return self.served and dataclasses.replace(config.replace(self._nominal), air=self.scene.air) == self.scene

    def simulator(self, config: SceneConfig, like: Simulator | None = None) -> Simulator:
        """A simulator of ``config`` with the net settled: from the family if it
        :meth:`serves` it, else from scratch (``like``: see :class:`Simulator`)."""
        if not self.serves(config):
            return Simulator(config, like=like)
        modes, settle_modes = self.modes()
        return Simulator(config, like=like, prepared=PreparedNet(self.equilibrium(config), modes, settle_modes))

    def equilibrium(self, config: SceneConfig) -> np.ndarray:
        """The settled net of member ``config`` (interpolated in its drawn stiffness)."""
        equilibria = self._settled_equilibria()
        if not self.stiffness:
            return equilibria[0][1].copy()
        field = self.stiffness[0][0]
        compliance = 1.0 / float(field_value(config, field))
        nearest = sorted(equilibria, key=lambda e: abs(1.0 / e[0] - compliance))[:3]
        points = [1.0 / ks for ks, _ in nearest]
        out = np.zeros_like(nearest[0][1])
        for i, (_, positions) in enumerate(nearest):
            weight = np.prod([(compliance - points[j]) / (points[i] - points[j]) for j in range(len(points)) if j != i])
            out += weight * positions
        return out

    def modes(self) -> tuple[NetModes, NetModes]:
        """The least stable modes of the family at the net's own inertia and at the pause's."""
        if self._modes is None:
            corners = [dict(zip([f for f, _, _ in self.springs], values))
                       for values in itertools.product(*[(lo, hi) for _, lo, hi in self.springs])]
            corners.append({field: 0.5 * (lo + hi) for field, lo, hi in self.springs})
            models = [Model.from_config(self.scene.replace(corner)) for corner in corners]
            self._modes = (_least_stable(models, 1.0),
                           _least_stable(models, self.scene.simulation.settle_inertia))
        return self._modes

    def _settled_equilibria(self) -> list[tuple[float, np.ndarray]]:
        """``(stiffness, settled positions)`` at :data:`EQUILIBRIA` stiffnesses across the drawn
        range (the family's scene itself if none is drawn), settled from scratch."""
        if self._equilibria is None:
            if self.stiffness:
                field, lo, hi = self.stiffness[0]
                points = [lo] if lo == hi else list(np.linspace(lo, hi, EQUILIBRIA))
                self._equilibria = [(float(ks), prepare_net(self.scene.replace({field: float(ks)})).positions.copy())
                                    for ks in points]
            else:
                self._equilibria = [(0.0, prepare_net(self.scene).positions.copy())]
        return self._equilibria


@functools.lru_cache(maxsize=CACHED_FAMILIES)
def family_of(scene: SceneConfig, ranges: tuple[Range, ...]) -> NetFamily:
    """The :class:`NetFamily` of ``scene`` and ``ranges``, one per process (its members' nets
    are settled once)."""
    return NetFamily(scene, ranges)


def _least_stable(models: list[Model], inertia: float) -> NetModes:
    """The highest frequency, highest damping rate and smallest IMEX Euler limit among the
    modes of ``models`` at ``inertia`` times their mass."""
    modes = [net_modes(m.geometry.positions, m.net_inv_mass / inertia, m.springs, m.spring_params, m.drag)
             for m in models]
    return dataclasses.replace(modes[0], omega2=max(m.omega2 for m in modes),
                               damping=max(m.damping for m in modes),
                               imex_limit=min(m.imex_limit for m in modes))
