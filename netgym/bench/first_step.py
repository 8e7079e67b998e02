"""Time to the first step of an environment: a fresh Python process imports gymnasium and
netgym, makes the environment, resets it and takes one step (a fixed action), once with an
empty numba cache (every kernel compiles) and once more with the cache that run left (the
kernels load from disk): what a user waits for on the first and on every later start."""

from __future__ import annotations

import json
import os
import subprocess
import sys
import tempfile

_FIRST_STEP = """
import json, sys, time
start = time.perf_counter()
import gymnasium as gym
import numpy as np
import netgym
env = gym.make(sys.argv[1])
env.reset(seed=0)
env.step(np.zeros(env.action_space.shape, dtype=env.action_space.dtype))
print(json.dumps({"seconds": time.perf_counter() - start}))
"""


def first_step_seconds(env_id: str, cache_dir: str, threads: int | None = None) -> tuple[float, str]:
    """Wall seconds from the start of a fresh process (its imports included) to the end of its
    first ``env.step`` of ``env_id``, with numba caching kernels in ``cache_dir``, and what the
    process wrote on stderr. ``threads`` sets ``NUMBA_NUM_THREADS`` when given."""
    env = {**os.environ, "NUMBA_CACHE_DIR": cache_dir}
    if threads is not None:
        env["NUMBA_NUM_THREADS"] = str(threads)
    done = subprocess.run([sys.executable, "-c", _FIRST_STEP, env_id], env=env, capture_output=True, text=True,
                          check=False)
    if done.returncode != 0:
        raise RuntimeError(f"the first step of {env_id} failed (exit {done.returncode}):\n{done.stderr}")
    return json.loads(done.stdout.strip().splitlines()[-1])["seconds"], done.stderr


def cold_and_warm(env_id: str = "NetCatch-v0") -> dict[str, float]:
    """Seconds to the first step of ``env_id`` from an empty numba cache (``cold``), then again
    with the kernels that run cached (``warm``), in a new temporary cache folder."""
    with tempfile.TemporaryDirectory(prefix="netgym-numba-") as cache:
        cold, _ = first_step_seconds(env_id, cache)
        warm, _ = first_step_seconds(env_id, cache)
    return {"cold": cold, "warm": warm}
