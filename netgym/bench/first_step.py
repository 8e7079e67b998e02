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
from typing import NamedTuple

_FIRST_STEP = """
import json, sys, time
start = time.perf_counter()
import gymnasium as gym
import numpy as np
import netgym
env = gym.make(sys.argv[1])
env.reset(seed=0)
env.step(np.zeros(env.action_space.shape, dtype=env.action_space.dtype))
seconds = time.perf_counter() - start
from numba.core.registry import CPUDispatcher
kernels = {}
for name, module in list(sys.modules.items()):
    if name.startswith("netgym."):
        for value in vars(module).values():
            if isinstance(value, CPUDispatcher) and value.signatures:
                kernels[value.py_func.__module__ + "." + value.py_func.__name__] = len(value.signatures)
print(json.dumps({"seconds": seconds, "kernels": kernels}))
"""


class FirstStep(NamedTuple):
    """What one fresh process took to its first step: wall ``seconds`` (imports included), the
    netgym kernels it then held (compiled or loaded from the cache; qualified name: number of
    signatures) and what it wrote on stderr."""

    seconds: float
    kernels: dict[str, int]
    stderr: str


def first_step(env_id: str, cache_dir: str) -> FirstStep:
    """Run the first step of ``env_id`` in a fresh process, with numba caching kernels in
    ``cache_dir``."""
    done = subprocess.run([sys.executable, "-c", _FIRST_STEP, env_id], env={**os.environ, "NUMBA_CACHE_DIR": cache_dir},
                          capture_output=True, text=True, check=False)
    if done.returncode != 0:
        raise RuntimeError(f"the first step of {env_id} failed (exit {done.returncode}):\n{done.stderr}")
    result = json.loads(done.stdout.strip().splitlines()[-1])
    return FirstStep(result["seconds"], result["kernels"], done.stderr)


def cold_and_warm(env_id: str = "NetCatch-v0") -> tuple[FirstStep, FirstStep]:
    """The first step of ``env_id`` from an empty numba cache (cold), then again with the kernels
    that run cached (warm), in a new temporary cache folder."""
    with tempfile.TemporaryDirectory(prefix="netgym-numba-") as cache:
        return first_step(env_id, cache), first_step(env_id, cache)
