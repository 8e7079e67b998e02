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
        """Random action(s) for one observation (a vector, or an H x W x 3 image) or a batch of them."""
        obs = np.asarray(observation)
        shape = (obs.shape[0], 3) if obs.ndim in (2, 4) else (3,)
        return self.rng.uniform(-1.0, 1.0, shape).astype(np.float32), state
