"""Throws per second with the fast path and with full simulation, their outcome agreement, and
vector-environment scaling over 1 and 2 threads.

Throws are drawn per seed: the thrower uniformly from the scene's ranges, the action either
uniform in [-1, 1]^3 (half of them) or the ballistic oracle's plus Gaussian noise (sd 0.15),
so that captures, rim hits and misses all occur. Each throw starts from the empty net at rest
and is simulated twice: ``fast=True`` (closed-form flight, sleeping net, early decision) and
``fast=False`` (everything integrated from launch to the time limit).

Usage::

    python scripts/bench_env.py                 # 1000 throws per scene, both cores
    python scripts/bench_env.py --quick         # a few throws, for CI smoke tests
"""

from __future__ import annotations

import argparse
import multiprocessing
import time
from concurrent.futures import ProcessPoolExecutor
from dataclasses import dataclass

import numba
import numpy as np

from agents.oracle import BallisticOracle
from netgym.envs.vector import NetCatchVectorEnv
from netgym.launch import action_to_velocity, opening_centre, sample_thrower
from netgym.physics.simulator import Simulator

Throw = tuple[np.ndarray, np.ndarray]


def sample_throws(scene: str, count: int, seed: int = 0) -> list[Throw]:
    """``count`` (launch position, velocity) pairs, half random, half noisy oracle throws."""
    sim = Simulator(scene)
    opening = sim.model.geometry.opening
    oracle = BallisticOracle(sim.config, opening)
    centre_z = float(opening_centre(opening)[2])
    rng = np.random.default_rng(seed)
    throws = []
    for k in range(count):
        thrower = sample_thrower(sim.config.throw, opening, rng)
        if k % 2:
            action = oracle.action(thrower.distance, thrower.height - centre_z) + rng.normal(0.0, 0.15, 3)
        else:
            action = rng.uniform(-1.0, 1.0, 3)
        throws.append((thrower.position, action_to_velocity(np.clip(action, -1, 1), thrower, sim.config.throw)))
    return throws


@dataclass(frozen=True)
class Outcome:
    """One throw simulated both ways."""

    fast_captured: bool
    full_captured: bool
    fast_seconds: float
    full_seconds: float
    touched: bool  # the fast path had to integrate (the ball came near the net or poles)


def _simulate(args: tuple[str, list[Throw]]) -> list[Outcome]:
    scene, throws = args
    sim = Simulator(scene)
    out = []
    for position, velocity in throws:
        sim.reset()
        start = time.perf_counter()
        fast = sim.throw(position, velocity)
        fast_seconds = time.perf_counter() - start
        sim.reset()
        start = time.perf_counter()
        full = sim.throw(position, velocity, fast=False)
        out.append(Outcome(fast.captured, full.captured, fast_seconds, time.perf_counter() - start, fast.substeps > 0))
    return out


def compare(scene: str, throws: list[Throw], workers: int = 1) -> list[Outcome]:
    """Simulate every throw fast and fully, on ``workers`` processes (forked after compiling)."""
    Simulator(scene).throw(*throws[0])  # compile and settle before forking
    if workers == 1:
        return _simulate((scene, throws))
    chunks = [(scene, throws[i::workers]) for i in range(workers)]
    with ProcessPoolExecutor(workers, mp_context=multiprocessing.get_context("fork")) as pool:
        parts = list(pool.map(_simulate, chunks))
    return [o for part in parts for o in part]


def summarise(outcomes: list[Outcome]) -> dict[str, float]:
    """Agreement and throughput figures of a comparison."""
    n = len(outcomes)
    touched = [o for o in outcomes if o.touched]
    return {
        "throws": n,
        "agreement": sum(o.fast_captured == o.full_captured for o in outcomes) / n,
        "captured": sum(o.full_captured for o in outcomes) / n,
        "fast_throws_per_s": n / sum(o.fast_seconds for o in outcomes),
        "full_throws_per_s": n / sum(o.full_seconds for o in outcomes),
        "touching": len(touched),
        "fast_touching_throws_per_s": len(touched) / max(sum(o.fast_seconds for o in touched), 1e-12),
    }


def vector_scaling(scene: str, num_envs: int, steps: int) -> dict[int, float]:
    """Throws per second of NetCatchVectorEnv with noisy oracle actions, on 1 and 2 threads."""
    rates = {}
    for threads in (1, min(2, numba.config.NUMBA_NUM_THREADS)):
        numba.set_num_threads(threads)
        env = NetCatchVectorEnv(num_envs=num_envs, scene=scene)
        single = env.envs[0]
        oracle = BallisticOracle(single.scene, single.sim.model.geometry.opening)
        rng = np.random.default_rng(0)
        obs, _ = env.reset(seed=0)
        env.step(oracle.predict(obs)[0])  # warm-up
        start = time.perf_counter()
        for _ in range(steps):
            actions = np.clip(oracle.predict(obs)[0] + rng.normal(0, 0.1, (num_envs, 3)), -1, 1)
            obs, *_ = env.step(actions.astype(np.float32))
        rates[threads] = steps * num_envs / (time.perf_counter() - start)
    numba.set_num_threads(numba.config.NUMBA_NUM_THREADS)
    return rates


def sb3_throughput(kind: str, num_envs: int, steps: int) -> float:
    """Environment steps per second of the SB3 training environment (``native``: the vector env
    through the adapter; ``subproc``: ``make_vec_env`` with ``SubprocVecEnv``), noisy oracle actions."""
    from agents.training import make_training_env

    env = make_training_env(kind, num_envs, seed=0)
    scene = Simulator("basket")
    oracle = BallisticOracle(scene.config, scene.model.geometry.opening)
    rng = np.random.default_rng(0)
    obs = env.reset()
    env.step(oracle.predict(obs)[0])  # warm-up
    start = time.perf_counter()
    for _ in range(steps):
        actions = np.clip(oracle.predict(obs)[0] + rng.normal(0, 0.1, (num_envs, 3)), -1, 1)
        obs, *_ = env.step(actions.astype(np.float32))
    rate = steps * num_envs / (time.perf_counter() - start)
    env.close()
    return rate


def main() -> None:
    """Parse arguments, run, print a markdown report."""
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--quick", action="store_true", help="a few throws, for smoke tests")
    parser.add_argument("--throws", type=int, default=1000)
    parser.add_argument("--workers", type=int, default=2)
    args = parser.parse_args()
    count = 6 if args.quick else args.throws
    print("| scene | throws | outcome agreement | captured | fast throws/s | full throws/s | speed-up | "
          "throws touching the net | fast throws/s on those |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|")
    for scene in ("basket", "goal"):
        s = summarise(compare(scene, sample_throws(scene, count), 1 if args.quick else args.workers))
        print(f"| {scene} | {s['throws']} | {100 * s['agreement']:.1f}% | {100 * s['captured']:.0f}% | "
              f"{s['fast_throws_per_s']:.1f} | {s['full_throws_per_s']:.2f} | "
              f"{s['fast_throws_per_s'] / s['full_throws_per_s']:.0f}x | {s['touching']} | "
              f"{s['fast_touching_throws_per_s']:.1f} |")
    print("\n| vector env (basket, 8 envs) | throws/s |\n|---|---:|")
    for threads, rate in vector_scaling("basket", 8, 2 if args.quick else 30).items():
        print(f"| {threads} thread(s) | {rate:.1f} |")
    print("\n| SB3 training env (basket, 8 envs) | env steps/s |\n|---|---:|")
    for kind in ("native", "subproc"):
        print(f"| {kind} | {sb3_throughput(kind, 8, 2 if args.quick else 30):.1f} |")
    print("\n(per-process figures; agreement and full-simulation runs use "
          f"{1 if args.quick else args.workers} process(es))")


if __name__ == "__main__":
    main()
