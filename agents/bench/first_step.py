"""Time to the first step of an environment: a fresh Python process imports gymnasium and
netgym, makes the environment, resets it and takes one step (a fixed action), then one more
aimed at the opening by the ballistic oracle (the throw that reaches the net), once with an
empty numba cache (every kernel compiles) and once more with the cache that run left (the
kernels load from disk): what a user waits for on the first and on every later start.

Wall seconds depend on what else the machine runs; each run therefore records the load
average before it and the process's CPU seconds too."""

from __future__ import annotations

import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path
from typing import Any, NamedTuple

from netgym.bench.results import read_results, write_results
from netgym.errors import InvalidArgumentError

_FIRST_STEP = """
import json, sys, time
start, cpu = time.perf_counter(), time.process_time()
import gymnasium as gym
import numpy as np
import netgym
env = gym.make(sys.argv[1])
observation, _ = env.reset(seed=0)
observation, *_ = env.step(np.zeros(env.action_space.shape, dtype=env.action_space.dtype))
first = time.perf_counter() - start, time.process_time() - cpu
from numba.core.registry import CPUDispatcher
kernels = {}
for name, module in list(sys.modules.items()):
    if name.startswith("netgym."):
        for value in vars(module).values():
            if isinstance(value, CPUDispatcher) and value.signatures:
                kernels[value.py_func.__module__ + "." + value.py_func.__name__] = len(value.signatures)
from agents.oracle import BallisticOracle
action, _ = BallisticOracle(env.unwrapped.scene).predict(observation)
start, cpu = time.perf_counter(), time.process_time()
env.step(action)
aimed = time.perf_counter() - start, time.process_time() - cpu
print(json.dumps({"first": first, "aimed": aimed, "kernels": kernels}))
"""


class FirstStep(NamedTuple):
    """What one fresh process took to its first step: wall ``seconds`` and ``cpu_seconds``
    (imports included), the same for its next step, aimed at the opening (``aimed_seconds``,
    ``aimed_cpu_seconds``), the netgym kernels it held after the first step (compiled or loaded
    from the cache; qualified name: number of signatures) and what it wrote on stderr."""

    seconds: float
    cpu_seconds: float
    aimed_seconds: float
    aimed_cpu_seconds: float
    kernels: dict[str, int]
    stderr: str

    def figures(self) -> dict[str, float]:
        """The four timings, rounded to 0.1 s, as a result file keeps them."""
        return {name: round(getattr(self, name), 1)
                for name in ("seconds", "cpu_seconds", "aimed_seconds", "aimed_cpu_seconds")}


def first_step(env_id: str, cache_dir: str) -> FirstStep:
    """Run the first steps of ``env_id`` in a fresh process, with numba caching kernels in
    ``cache_dir``."""
    done = subprocess.run([sys.executable, "-c", _FIRST_STEP, env_id], env={**os.environ, "NUMBA_CACHE_DIR": cache_dir},
                          capture_output=True, text=True, check=False)
    if done.returncode != 0:
        raise RuntimeError(f"the first step of {env_id} failed (exit {done.returncode}):\n{done.stderr}")
    result = json.loads(done.stdout.strip().splitlines()[-1])
    return FirstStep(*result["first"], *result["aimed"], result["kernels"], done.stderr)


def cold_and_warm(env_id: str = "NetCatch-v0") -> tuple[FirstStep, FirstStep]:
    """The first step of ``env_id`` from an empty numba cache (cold), then again with the kernels
    that run cached (warm), in a new temporary cache folder."""
    with tempfile.TemporaryDirectory(prefix="netgym-numba-") as cache:
        return first_step(env_id, cache), first_step(env_id, cache)


def run_figures(label: str, load: float, cold: FirstStep, warm: FirstStep) -> dict[str, Any]:
    """One run as a result file keeps it: ``label`` (the code measured), the 1-minute ``load``
    average before it, the kernels the cold first step compiled, and both timings."""
    return {"label": label, "load_1min": round(load, 2), "cold_kernels": len(cold.kernels),
            "cold": cold.figures(), "warm": warm.figures()}


def add_runs(path: str | Path, env_id: str, runs: list[dict[str, Any]]) -> Path:
    """Write ``runs`` (from :func:`run_figures`) to the result file at ``path`` after the runs
    it holds of other labels (its runs of the same label are replaced); returns the path."""
    path = Path(path)
    figures = read_results(path)["figures"] if path.is_file() else {"env": env_id, "cpus": os.cpu_count(), "runs": []}
    if figures["env"] != env_id:
        raise InvalidArgumentError(f"{path} holds first steps of {figures['env']}, not {env_id}")
    labels = {run["label"] for run in runs}
    figures["runs"] = [run for run in figures["runs"] if run["label"] not in labels] + runs
    return write_results(path, figures)


def latest_runs(figures: dict[str, Any]) -> list[dict[str, Any]]:
    """The runs of the label written last (the code as it is now, once it has been measured)."""
    label = figures["runs"][-1]["label"]
    return [run for run in figures["runs"] if run["label"] == label]
