"""Training speed of RLlib's PPO on a local Ray cluster (one node, or two on one machine) against
SB3's PPO on SubprocVecEnv, the same env steps each (``scripts/bench_rllib.py``)."""

from __future__ import annotations

import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
BATCH = 1024
"""Env steps per RLlib iteration and per SB3 rollout (n_steps x 2 envs)."""


def rllib_steps_per_s(iterations: int, nodes: int) -> dict:
    """Train RLlib's PPO on a local cluster of ``nodes`` nodes (2 CPUs in all, 2 env runners)."""
    with tempfile.TemporaryDirectory() as folder:
        summary = Path(folder) / "summary.json"
        cpus = ["--nodes", "2", "--head-cpus", "1", "--worker-cpus", "1"] if nodes == 2 else [
            "--nodes", "1", "--head-cpus", "2"]
        command = [sys.executable, str(ROOT / "scripts" / "local_cluster.py"), *cpus, "--",
                   sys.executable, str(ROOT / "scripts" / "train_rllib.py"), "--address", "127.0.0.1:6380",
                   "--env-runners", "2", "--batch", str(BATCH), "--iterations", str(iterations),
                   "--out", str(Path(folder) / "checkpoint"), "--summary", str(summary)]
        subprocess.run(command, cwd=ROOT, check=True, stdout=subprocess.DEVNULL)
        runs = json.loads(summary.read_text())["iterations"]
    seconds = sum(it["seconds"] for it in runs)
    return {"env_steps": runs[-1]["env_steps"], "seconds": seconds, "env_steps_per_s": runs[-1]["env_steps"] / seconds,
            "nodes": nodes}


def sb3_steps_per_s(iterations: int) -> dict:
    """Train SB3's PPO on 2 ``SubprocVecEnv`` envs (agents/training.py) for the same env steps."""
    from stable_baselines3 import PPO

    from agents.hyperparams import POLICY, PPO_PARAMS
    from agents.training import TRAINER_THREADS, make_training_env, torch_threads

    env = make_training_env(2, seed=0)
    model = PPO(POLICY, env, **{**PPO_PARAMS, "n_steps": BATCH // 2}, device="cpu", seed=0)
    start = time.perf_counter()
    with torch_threads(TRAINER_THREADS):
        model.learn(total_timesteps=iterations * BATCH)
    seconds = time.perf_counter() - start
    env.close()
    return {"env_steps": model.num_timesteps, "seconds": seconds, "env_steps_per_s": model.num_timesteps / seconds}


def measure(iterations: int, repeats: int) -> dict:
    """Each setup ``repeats`` times, one round after another, ``iterations`` batches each: every
    run's figures and each setup's median env steps/s."""
    setups = {"sb3_subproc_2_envs": lambda: sb3_steps_per_s(iterations),
              "rllib_2_env_runners_1_node": lambda: rllib_steps_per_s(iterations, 1),
              "rllib_2_env_runners_2_nodes_one_machine": lambda: rllib_steps_per_s(iterations, 2)}
    runs: dict[str, list[dict]] = {name: [] for name in setups}
    for round_ in range(repeats):
        for name, run in setups.items():
            print(f"round {round_ + 1}/{repeats}: measuring {name} ({iterations * BATCH} env steps)...", flush=True)
            runs[name].append(run())
    return {"cpus": os.cpu_count(), "batch": BATCH, "env_steps": iterations * BATCH, "runs": runs,
            "median_env_steps_per_s": {name: statistics.median(run["env_steps_per_s"] for run in measured)
                                       for name, measured in runs.items()}}


def to_markdown(figures: dict) -> str:
    """The table of each run's and the median env steps/s per setup."""
    lines = ["| training | env steps/s, each run | median |", "|---|---|---|"]
    for name, measured in figures["runs"].items():
        each = ", ".join(f"{run['env_steps_per_s']:.1f}" for run in measured)
        lines.append(f"| {name} | {each} | {figures['median_env_steps_per_s'][name]:.1f} |")
    return "\n".join(lines)
