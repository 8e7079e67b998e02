"""The random baseline: uniform actions in [-1, 1]^3."""

from __future__ import annotations

import numpy as np


class RandomAgent:
    """Stable-Baselines3-style ``predict`` with uniformly random actions.

    :param seed: seed of its own generator (evaluations stay reproducible).
    """

    def __init__(self, seed: int = 0) -> None:
        self.rng = np.random.default_rng(seed)

    def predict(self, observation: np.ndarray, state=None, episode_start=None, deterministic: bool = True):
        """Random action(s) for one observation or a batch."""
        obs = np.asarray(observation)
        shape = (obs.shape[0], 3) if obs.ndim > 1 else (3,)
        return self.rng.uniform(-1.0, 1.0, shape).astype(np.float32), state
