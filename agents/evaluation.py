"""Capture rate of a policy on a registered NetCatch env over seeded episodes, with a 95% confidence interval."""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any, Protocol

import gymnasium as gym
import numpy as np
from tqdm import tqdm

from agents.model_env import DEFAULT_ENV
from netgym.envs import NetCatchEnv


class Policy(Protocol):
    """Anything with a Stable-Baselines3-style ``predict``."""

    def predict(self, observation: np.ndarray, state: Any = None, episode_start: Any = None,
                deterministic: bool = True) -> tuple[np.ndarray, Any]: ...


@dataclass(frozen=True)
class CaptureRate:
    """Captured throws out of all throws, and the Wilson 95% interval of the rate; with
    ``by_throw``, the captures by throw index within the episode (``by_throw[k]``: the
    episodes' throw ``k + 1`` captured) out of ``episodes`` episodes."""

    captured: int
    throws: int
    low: float
    high: float
    by_throw: tuple[int, ...] = ()
    episodes: int = 0

    @property
    def rate(self) -> float:
        """Fraction of throws captured."""
        return self.captured / self.throws

    @property
    def rate_by_throw(self) -> tuple[float, ...]:
        """Fraction of the episodes whose throw ``k + 1`` was captured, for each index ``k``."""
        return tuple(count / self.episodes for count in self.by_throw)

    def __str__(self) -> str:
        return (f"{100 * self.rate:.1f}% ({self.captured}/{self.throws} throws; "
                f"95% CI {100 * self.low:.1f}-{100 * self.high:.1f}%)")


def wilson_interval(successes: int, trials: int, z: float = 1.96) -> tuple[float, float]:
    """Wilson score interval of a binomial proportion."""
    if trials == 0:
        return 0.0, 1.0
    p = successes / trials
    centre = (p + z * z / (2 * trials)) / (1 + z * z / trials)
    half = z * math.sqrt(p * (1 - p) / trials + z * z / (4 * trials * trials)) / (1 + z * z / trials)
    return max(0.0, centre - half), min(1.0, centre + half)


def episode_outcomes(policy: Policy | Callable[[NetCatchEnv], Policy], episodes: int, seed: int = 0,
                     progress: str | None = None, env_id: str = DEFAULT_ENV, **env_kwargs: Any) -> list[str]:
    """Run ``episodes`` episodes of the registered ``env_id`` (its arguments overridden by
    ``env_kwargs``) seeded ``seed, seed + 1, ...``; each episode's outcome as a string of one
    character a throw, ``"1"`` captured and ``"0"`` not (``"101"``: throws 1 and 3 of 3
    captured). With a ``progress`` label, a progress bar with ETA on stderr. ``policy`` may also
    be a function of the :class:`NetCatchEnv` that returns the policy (for one that reads the env,
    such as :class:`~agents.oracle.InformedOracle`). The policy is given its recurrent ``state``
    back and ``episode_start`` (as SB3's ``evaluate_policy`` does), so policies with memory work too."""
    env = gym.make(env_id, disable_env_checker=True, **env_kwargs)
    if isinstance(policy, type) or not hasattr(policy, "predict"):
        policy = policy(env.unwrapped)
    outcomes = []
    for episode in tqdm(range(episodes), desc=progress, unit="episode", disable=progress is None, leave=False):
        obs, _ = env.reset(seed=seed + episode)
        done, state, throws = False, None, []
        while not done:
            action, state = policy.predict(obs, state=state, episode_start=np.array([not throws]), deterministic=True)
            obs, _, terminated, truncated, info = env.step(action)
            throws.append("1" if info["captured"] else "0")
            done = terminated or truncated
        outcomes.append("".join(throws))
    env.close()
    return outcomes


def capture_rate(outcomes: list[str]) -> CaptureRate:
    """The capture rate of episodes' outcomes (:func:`episode_outcomes`), by throw index too."""
    longest = max((len(episode) for episode in outcomes), default=0)
    by_throw = tuple(sum(episode[k:k + 1] == "1" for episode in outcomes) for k in range(longest))
    captured, throws = sum(by_throw), sum(len(episode) for episode in outcomes)
    return CaptureRate(captured, throws, *wilson_interval(captured, throws), by_throw, len(outcomes))


def evaluate(policy: Policy | Callable[[NetCatchEnv], Policy], episodes: int, seed: int = 0,
             progress: str | None = None, env_id: str = DEFAULT_ENV, **env_kwargs: Any) -> CaptureRate:
    """The capture rate of ``policy`` over the episodes :func:`episode_outcomes` runs (the same
    arguments), with its Wilson interval and the captures by throw index within the episode."""
    return capture_rate(episode_outcomes(policy, episodes, seed, progress, env_id, **env_kwargs))
