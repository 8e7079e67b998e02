"""Training throughput on this machine: RLlib's PPO with 2 env runners (one Ray node, and two
nodes on the same machine) against Stable-Baselines3's PPO with 2 ``SubprocVecEnv`` envs.

Each figure is env steps per second of training, sampling and learning together (PPO's settings
from agents/hyperparams/ppo.yml; the same number of env steps for each), setup excluded: Ray's
start, the algorithm's build, the envs' start. The Ray runs use ``scripts/local_cluster.py``
(network and process namespaces of their own: root, ``unshare``, ``ip``); the "two nodes" figure
is two Ray nodes of one CPU each on this one machine, not two machines. Needs the ``rllib`` and
``train`` extras. Writes ``docs/results/rllib.json`` (``--results``).

Usage::

    python scripts/bench_rllib.py --iterations 6 --repeats 2 --results docs/results/rllib.json
    python scripts/bench_rllib.py --quick
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from netgym.bench.results import write_results

ROOT = Path(__file__).resolve().parents[1]
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


def main() -> None:
    """Measure the three setups in rounds, print each run and the medians, write the result file."""
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--iterations", type=int, default=8, help="RLlib iterations (SB3 rollouts) of 1024 env steps")
    parser.add_argument("--results", type=Path, help="write the figures here (docs/results/rllib.json)")
    parser.add_argument("--repeats", type=int, default=2, help="runs of each setup, one round after another")
    parser.add_argument("--quick", action="store_true", help="2 iterations, one round, for smoke tests")
    args = parser.parse_args()
    iterations, repeats = (2, 1) if args.quick else (args.iterations, args.repeats)
    setups = {"sb3_subproc_2_envs": lambda: sb3_steps_per_s(iterations),
              "rllib_2_env_runners_1_node": lambda: rllib_steps_per_s(iterations, 1),
              "rllib_2_env_runners_2_nodes_one_machine": lambda: rllib_steps_per_s(iterations, 2)}
    runs: dict[str, list[dict]] = {name: [] for name in setups}
    for round_ in range(repeats):
        for name, measure in setups.items():
            print(f"round {round_ + 1}/{repeats}: measuring {name} ({iterations * BATCH} env steps)...", flush=True)
            runs[name].append(measure())
    figures = {"cpus": os.cpu_count(), "batch": BATCH, "env_steps": iterations * BATCH, "runs": runs,
               "median_env_steps_per_s": {name: statistics.median(run["env_steps_per_s"] for run in measured)
                                          for name, measured in runs.items()}}
    print("| training | env steps/s, each run | median |\n|---|---|---|")
    for name, measured in runs.items():
        each = ", ".join(f"{run['env_steps_per_s']:.1f}" for run in measured)
        print(f"| {name} | {each} | {figures['median_env_steps_per_s'][name]:.1f} |")
    if args.results is not None:
        print(f"written: {write_results(args.results, figures)}")


if __name__ == "__main__":
    main()
