"""Environment throughput under noisy oracle actions: ``NetCatchVectorEnv`` on 1 and 2 numba
threads, and the Stable-Baselines3 training environment (native adapter or SubprocVecEnv)."""

from __future__ import annotations

import time
from typing import Any

import numba
import numpy as np

from netgym.bench.throws import ballistic_oracle
from netgym.envs.vector import NetCatchVectorEnv


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


def vector_scaling(scene: str, num_envs: int, steps: int) -> dict[int, float]:
    """Throws per second of NetCatchVectorEnv with noisy oracle actions, on 1 and 2 threads."""
    rates = {}
    for threads in (1, min(2, numba.config.NUMBA_NUM_THREADS)):
        numba.set_num_threads(threads)
        env = NetCatchVectorEnv(num_envs=num_envs, scene=scene)
        oracle = ballistic_oracle(scene)
        obs, _ = env.reset(seed=0)
        rates[threads] = _noisy_oracle_rate(env, oracle, obs, num_envs, steps)
    numba.set_num_threads(numba.config.NUMBA_NUM_THREADS)
    return rates


def sb3_throughput(kind: str, num_envs: int, steps: int) -> float:
    """Environment steps per second of the SB3 training environment (``native``: the vector env
    through the adapter; ``subproc``: ``make_vec_env`` with ``SubprocVecEnv``), noisy oracle actions."""
    from agents.training import make_training_env

    env = make_training_env(kind, num_envs, seed=0)
    oracle = ballistic_oracle("basket")  # the scene make_training_env trains on
    rate = _noisy_oracle_rate(env, oracle, env.reset(), num_envs, steps)
    env.close()
    return rate
