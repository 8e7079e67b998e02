"""Do the shortcuts change episodes? Outcomes of the same seeded episodes (same throwers, same
actions) in the default pipeline and in a reference pipeline: a fine dt, the pause between
throws relaxed to a ten times stricter rest test, and every throw simulated in full to the
time limit (no fast path). Throw 1 meets the settled empty net in both; throws 2..N meet the
net as each pipeline left it, so they test the pause and everything before it too.

Half the episodes are thrown by the ballistic oracle with Gaussian noise on its actions (so
rim hits and near misses occur), half with uniform-random actions.
"""

from __future__ import annotations

import time
from concurrent.futures import ProcessPoolExecutor
from dataclasses import dataclass

import numpy as np
from tqdm import tqdm

from netgym.bench.throws import ballistic_oracle
from netgym.envs import NetCatchEnv

REFERENCE_DT = 5e-4           # s, a quarter of the default
REFERENCE_REST_SPEED = 1e-3   # m/s (the default pipeline: 1e-2; at 1e-4 a resting ball and the net under it keep a stick-slip cycle of ~0.4 mm/s at this dt)
ACTION_NOISE = 0.15           # standard deviation of the noise on the oracle's actions


@dataclass(frozen=True)
class EpisodePair:
    """One seeded episode in both pipelines: per throw, captured in each, and the wall times."""

    policy: str
    fast: list[bool]
    reference: list[bool]
    fast_seconds: float
    reference_seconds: float


def _actions(episode: int, seed: int, observations: list[np.ndarray], oracle) -> np.ndarray:
    """The action of throw ``len(observations) - 1``: noisy oracle in even episodes, random in odd."""
    rng = np.random.default_rng([seed, episode, len(observations)])
    if episode % 2:
        return rng.uniform(-1.0, 1.0, 3).astype(np.float32)
    action = oracle.predict(observations[-1])[0] + rng.normal(0.0, ACTION_NOISE, 3)
    return np.clip(action, -1.0, 1.0).astype(np.float32)


def _run(env: NetCatchEnv, episode: int, seed: int, actions: list[np.ndarray] | None,
         oracle) -> tuple[list[bool], list[np.ndarray], list[np.ndarray], float]:
    """Run one episode; with ``actions`` None, choose them (and return them), else replay them.
    Returns (captured per throw, actions, launch positions, wall seconds)."""
    obs, _ = env.reset(seed=seed + episode)
    chosen = actions if actions is not None else []
    captured, launches, done, k = [], [], False, 0
    observations = [obs]
    start = time.perf_counter()
    while not done:
        if actions is None:
            chosen.append(_actions(episode, seed, observations, oracle))
        obs, _, done, _, info = env.step(chosen[k])
        observations.append(obs)
        captured.append(bool(info["captured"]))
        launches.append(np.asarray(info["launch_position"]))
        k += 1
    return captured, chosen, launches, time.perf_counter() - start


def _pairs(job: tuple[str, list[int], int, int, bool]) -> list[EpisodePair]:
    scene, episodes, balls, seed, progress = job
    fast_env = NetCatchEnv(scene=scene, balls_per_episode=balls)
    reference_env = NetCatchEnv(scene=scene, balls_per_episode=balls, fast=False,
                                overrides={"simulation.dt": REFERENCE_DT,
                                           "simulation.rest_speed": REFERENCE_REST_SPEED})
    oracle = ballistic_oracle(scene)
    _run(fast_env, 0, seed - 1, None, oracle)  # compile the kernels outside the timed episodes
    pairs = []
    for episode in tqdm(episodes, desc=f"{scene} episodes in both pipelines", unit="episode", disable=not progress):
        fast, actions, launches, fast_seconds = _run(fast_env, episode, seed, None, oracle)
        reference, _, reference_launches, reference_seconds = _run(reference_env, episode, seed, actions, oracle)
        if not np.array_equal(np.array(launches), np.array(reference_launches)):
            raise RuntimeError(f"episode {episode}: the two pipelines drew different throwers")
        pairs.append(EpisodePair("noisy oracle" if episode % 2 == 0 else "random", fast, reference,
                                 fast_seconds, reference_seconds))
    return pairs


def episode_agreement(scene: str, episodes: int, balls: int, seed: int = 50_000,
                      workers: int = 2) -> list[EpisodePair]:
    """``episodes`` seeded episodes of ``balls`` throws in both pipelines, shared by ``workers``
    processes (the first shows a progress bar)."""
    parts = [list(range(w, episodes, workers)) for w in range(workers)]
    jobs = [(scene, part, balls, seed, w == 0) for w, part in enumerate(parts) if part]
    if len(jobs) == 1:
        return _pairs(jobs[0])
    with ProcessPoolExecutor(len(jobs)) as pool:
        return [pair for part in pool.map(_pairs, jobs) for pair in part]


def to_markdown(pairs: list[EpisodePair]) -> str:
    """Agreement by throw position and by policy, with the wall time of each pipeline."""
    from agents.evaluation import wilson_interval

    lines = ["| throws | policy | compared | agree | 95% CI | captured (default / reference) |",
             "|---|---|---:|---:|---|---|"]
    for label, first, last in (("1 (empty net)", 0, 1), ("2..N", 1, None)):
        for policy in ("noisy oracle", "random", "all"):
            chosen = [p for p in pairs if policy in ("all", p.policy)]
            got = [(f, r) for p in chosen for f, r in zip(p.fast[first:last], p.reference[first:last])]
            agree = sum(f == r for f, r in got)
            low, high = wilson_interval(agree, len(got))
            lines.append(f"| {label} | {policy} | {len(got)} | {100 * agree / max(len(got), 1):.2f}% | "
                         f"{100 * low:.2f}-{100 * high:.2f}% | {sum(f for f, _ in got)} / {sum(r for _, r in got)} |")
    fast = sum(p.fast_seconds for p in pairs)
    reference = sum(p.reference_seconds for p in pairs)
    throws = sum(len(p.fast) for p in pairs)
    lines.append("")
    lines.append(f"Wall time over {throws} throws: default pipeline {fast:.1f} s ({throws / fast:.1f} throws/s), "
                 f"reference {reference:.1f} s ({throws / reference:.2f} throws/s): the default is "
                 f"{reference / fast:.0f}x faster.")
    return "\n".join(lines)
