"""Compile the simulator's kernels before worker processes start, so that they load them from
numba's cache instead of each compiling them (and racing on the cache)."""

from __future__ import annotations

from typing import Any

from agents.evaluation import evaluate
from agents.model_env import DEFAULT_ENV, vector_counterpart
from agents.policies import policy_in_env


def compile_kernels(env_id: str = DEFAULT_ENV, **env_kwargs: Any) -> None:
    """Compile (or load from numba's cache) every kernel an episode of ``env_id`` uses: one
    episode of the ballistic oracle, whose throws fly, hit the net and are paused after. An env
    the oracle cannot read (pixels) is warmed up as NetCatch-v0 with the same arguments."""
    env_id, env_kwargs = vector_counterpart(env_id, **env_kwargs)
    evaluate(policy_in_env("oracle", env_id)[1], 1, env_id=env_id, **env_kwargs)
