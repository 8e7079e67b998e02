"""The ballistic oracle: a launch through the centre of the opening, and its relatives.

From the thrower's distance and height (the observation), it aims through the opening's centre
with netgym's :class:`~netgym.aim.BallisticAim`: the drag-free parabola, steepest (a horizontal
opening, entered from above) or flattest (a vertical mouth) with its speed in range, corrected
by Newton's method on the flight through air in a scene with air (the wind it is given; none by
default). No learning; on NetCatch-v0 its capture rate is the reference ceiling for learned
agents.

- :class:`InformedOracle` is told each episode's hidden wind and draws (the ceiling of the
  variants that hide them);
- :class:`AdaptiveOracle` is not, and corrects its aim point from the feedback of its throws.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from netgym.aim import BallisticAim
from netgym.config import SceneConfig, load_scene
from netgym.envs import ObservationIndex
from netgym.envs.observation import aim_at_centre, thrower_of
from netgym.errors import InvalidArgumentError
from netgym.launch import Thrower


class BallisticOracle(BallisticAim):
    """Chooses actions of NetCatch-v0 by aiming through the opening's centre (its parameters are
    :class:`~netgym.aim.BallisticAim`'s).

    :param scene: the environment's scene config (``env.unwrapped.scene``).
    :param max_elevation: steepest elevation considered for a horizontal opening (degrees).
    """

    @classmethod
    def from_scene(cls, scene: SceneConfig | str | Path = "basket", max_elevation: float = 75.0) -> "BallisticOracle":
        """The oracle of a scene config, built-in scene name or TOML path."""
        return cls(scene if isinstance(scene, SceneConfig) else load_scene(scene), max_elevation)

    def thrower_of(self, row: np.ndarray) -> Thrower:
        """The thrower an observation describes."""
        return thrower_of(row, self.opening.centre)

    def act(self, row: np.ndarray) -> np.ndarray:
        """The action for one observation: through the centre of the opening."""
        return aim_at_centre(self, row)

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
