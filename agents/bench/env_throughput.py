"""Environment throughput under noisy oracle actions, the two ways of stepping many NetCatch-v0
environments: Gymnasium's ``SyncVectorEnv`` of ``gym.make("NetCatch-v0")`` environments in one
process, and the Stable-Baselines3 training environment (``make_vec_env`` with
``SubprocVecEnv``, one process per environment)."""

from __future__ import annotations

import time
from typing import Any

import gymnasium as gym
import numpy as np
from gymnasium.vector import AutoresetMode, SyncVectorEnv

from agents.oracle import BallisticOracle

SETUPS = {
    "sync": 'Gymnasium SyncVectorEnv of gym.make("NetCatch-v0"), one process',
    "subproc": "SB3 make_vec_env with SubprocVecEnv (the training environment), one process per env",
}
"""The measured setups: key -> what it is (the row label of the reports)."""


def _noisy_oracle_rate(env: Any, oracle: Any, obs: np.ndarray, num_envs: int, steps: int) -> float:
    """Environment steps per second of ``env`` (Gymnasium vector env or SB3 VecEnv) over
    ``steps`` steps of oracle actions plus noise (sd 0.1) from ``obs``, after one warm-up step."""
    rng = np.random.default_rng(0)
    env.step(oracle.predict(obs)[0])  # warm-up
    start = time.perf_counter()
    for _ in range(steps):
        actions = np.clip(oracle.predict(obs)[0] + rng.normal(0, 0.1, (num_envs, 3)), -1, 1)
        obs, *_ = env.step(actions.astype(np.float32))
    return steps * num_envs / (time.perf_counter() - start)


def _sync_rate(num_envs: int, steps: int) -> float:
    """``SyncVectorEnv`` of ``num_envs`` ``gym.make("NetCatch-v0")``. Same-step autoreset, as
    SB3's, so that every environment step is a throw."""
    env = SyncVectorEnv([lambda: gym.make("NetCatch-v0") for _ in range(num_envs)],
                        autoreset_mode=AutoresetMode.SAME_STEP)
    obs, _ = env.reset(seed=0)
    rate = _noisy_oracle_rate(env, BallisticOracle.from_scene("basket"), obs, num_envs, steps)
    env.close()
    return rate


def _subproc_rate(num_envs: int, steps: int) -> float:
    """The SB3 training environment of ``agents.training`` (its subprocesses start with
    forkserver: call this under ``if __name__ == "__main__":``)."""
    from agents.training import make_training_env

    env = make_training_env(num_envs, seed=0)
    rate = _noisy_oracle_rate(env, BallisticOracle.from_scene("basket"), env.reset(), num_envs, steps)
    env.close()
    return rate


def env_throughput(num_envs: int, steps: int) -> dict[str, float]:
    """Environment steps (throws) per second of each of :data:`SETUPS` on the basket, measured
    one after the other in this run: ``num_envs`` environments, ``steps`` steps of noisy oracle
    actions."""
    return {"sync": _sync_rate(num_envs, steps), "subproc": _subproc_rate(num_envs, steps)}
