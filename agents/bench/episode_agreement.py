"""Do the shortcuts change episodes? Outcomes of the same seeded episodes (same throwers, same
actions) in a pipeline under test and in a reference pipeline: a fine dt, the pause between
throws relaxed until nothing moves faster than 1 mm/s (the default: 10 cm/s), and every throw
simulated in full to the time limit (no fast path). Throw 1 meets the settled empty net in both; throws 2..N meet the net as
each pipeline left it, so they test the pause and everything before it too.

Half the episodes are thrown by the ballistic oracle with Gaussian noise on its actions (so
rim hits and near misses occur), half with uniform-random actions. The oracle reads only the
thrower's place, which both pipelines draw alike, so the reference's actions are replayed as
they are in every pipeline under test; the reference is computed once and stored as JSON.
"""

from __future__ import annotations

import json
import time
from concurrent.futures import ProcessPoolExecutor
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Any, Mapping

import numpy as np
from tqdm import tqdm

from agents.oracle import BallisticOracle
from netgym.envs import NetCatchEnv
from netgym.errors import NetNotAtRestError

REFERENCE_OVERRIDES = {
    "simulation.dt": 5e-4,           # s, a quarter of the default
    "simulation.settle_dt": 5e-4,    # s, the pause steps as finely (default 26.9 ms on the basket)
    "simulation.settle_inertia": 1.0,  # the pause's net with its own inertia (default 4x on the basket)
    "simulation.settle_speed": 1e-3,  # m/s, the pause's rest test (default 0.1; at 1e-4 a resting ball and
                                      # the net under it keep a stick-slip cycle of ~0.4 mm/s at this dt)
}
ACTION_NOISE = 0.15                  # standard deviation of the noise on the oracle's actions


@dataclass(frozen=True)
class Episode:
    """One seeded episode as a pipeline ran it: its actions, whether each throw was caught, and
    the wall seconds of its steps."""

    seed: int
    policy: str
    actions: list[list[float]]
    captured: list[bool]
    seconds: float


def _action(rng: np.random.Generator, noisy_oracle: bool, observation: np.ndarray, oracle) -> np.ndarray:
    if not noisy_oracle:
        return rng.uniform(-1.0, 1.0, 3).astype(np.float32)
    action = oracle.predict(observation)[0] + rng.normal(0.0, ACTION_NOISE, 3)
    return np.clip(action, -1.0, 1.0).astype(np.float32)


def _run(env: NetCatchEnv, seed: int, policy: str, actions: list[list[float]] | None, oracle) -> Episode:
    """Run the episode seeded ``seed``, replaying ``actions``, or choosing them by ``policy``
    (``"noisy oracle"`` or ``"random"``) when None."""
    obs, _ = env.reset(seed=seed)
    rng = np.random.default_rng(seed)
    chosen = [] if actions is None else actions
    captured, seconds, done = [], 0.0, False
    while not done:
        if actions is None:
            chosen.append(_action(rng, policy == "noisy oracle", obs, oracle).tolist())
        start = time.perf_counter()
        obs, _, done, _, info = env.step(np.array(chosen[len(captured)], dtype=np.float32))
        seconds += time.perf_counter() - start
        captured.append(bool(info["captured"]))
    return Episode(seed, policy, chosen, captured, seconds)


def _episodes(job: tuple[str, int, bool, Mapping[str, Any], list[Episode | int], bool]) -> list[Episode]:
    """The episodes of one worker. New episodes (seeds) whose pause never comes to rest (a pile
    creeping on faster than the rest test allows, for the pause's whole time limit) are left out."""
    scene, balls, fast, overrides, todo, progress = job
    env = NetCatchEnv(scene=scene, balls_per_episode=balls, fast=fast, overrides=dict(overrides))
    oracle = BallisticOracle.from_scene(scene)
    try:
        _run(env, 0, "noisy oracle", None, oracle)  # compile the kernels outside the timed episodes
    except NetNotAtRestError:
        pass  # compiled all the same
    done = []
    for item in tqdm(todo, desc=f"{scene}, {'fast' if fast else 'full'} {dict(overrides)}", unit="episode",
                     disable=not progress):
        if isinstance(item, Episode):
            done.append(_run(env, item.seed, item.policy, item.actions, oracle))
            continue
        try:
            done.append(_run(env, item, "noisy oracle" if item % 2 == 0 else "random", None, oracle))
        except NetNotAtRestError as error:
            tqdm.write(f"episode {item} left out: {error}")
    return done


def run_pipeline(scene: str, balls: int, todo: list[Episode] | list[int], fast: bool = True,
                 overrides: Mapping[str, Any] | None = None, workers: int = 2) -> list[Episode]:
    """Run ``todo`` (seeds, to choose the actions; or episodes, to replay theirs) in the pipeline
    ``fast``/``overrides``, shared by ``workers`` processes (the first shows a progress bar)."""
    parts = [todo[w::workers] for w in range(workers)]
    jobs = [(scene, balls, fast, dict(overrides or {}), part, w == 0) for w, part in enumerate(parts) if part]
    if len(jobs) == 1:
        return _episodes(jobs[0])
    with ProcessPoolExecutor(len(jobs)) as pool:
        results = list(pool.map(_episodes, jobs))
    order = {episode.seed: episode for part in results for episode in part}
    return [order[seed] for seed in (item.seed if isinstance(item, Episode) else item for item in todo) if seed in order]


def reference(scene: str, episodes: int, balls: int, seed: int = 50_000, workers: int = 2) -> list[Episode]:
    """The reference pipeline on ``episodes`` episodes seeded ``seed, seed + 1, ...`` (those whose
    pause never comes to rest left out: the seeds missing from the list)."""
    return run_pipeline(scene, balls, list(range(seed, seed + episodes)), False, REFERENCE_OVERRIDES, workers)


def save(episodes: list[Episode], path: Path, scene: str) -> None:
    """Store episodes as JSON, with the scene and the reference settings."""
    path.write_text(json.dumps({"scene": scene, "reference_overrides": REFERENCE_OVERRIDES,
                                "episodes": [asdict(e) for e in episodes]}) + "\n")


def load(path: Path) -> tuple[str, list[Episode]]:
    """(scene, episodes) stored by :func:`save`."""
    data = json.loads(path.read_text())
    return data["scene"], [Episode(**e) for e in data["episodes"]]


def agreement_rows(label: str, candidate: list[Episode], reference_episodes: list[Episode]) -> list[str]:
    """Markdown rows: agreement of ``candidate`` with the reference on throw 1 and on throws
    2..N, per policy and for all, with the candidate's throws per second."""
    from agents.evaluation import wilson_interval

    rows = []
    seconds = sum(e.seconds for e in candidate)
    rate = sum(len(e.captured) for e in candidate) / seconds
    for positions, first, last in (("1", 0, 1), ("2..N", 1, None)):
        for policy in ("noisy oracle", "random", "all"):
            pairs = [(c, r) for got, ref in zip(candidate, reference_episodes) if policy in ("all", ref.policy)
                     for c, r in zip(got.captured[first:last], ref.captured[first:last])]
            agree = sum(c == r for c, r in pairs)
            low, high = wilson_interval(agree, len(pairs))
            rows.append(f"| {label} | {positions} | {policy} | {len(pairs)} | {100 * agree / max(len(pairs), 1):.2f}% "
                        f"({100 * low:.2f}-{100 * high:.2f}%) | {sum(c for c, _ in pairs)} / {sum(r for _, r in pairs)} "
                        f"| {rate:.1f} |")
    return rows


TABLE_HEADER = ["| pipeline | throws | policy | compared | agree (95% CI) | caught (pipeline / reference) | throws/s |",
                "|---|---|---|---:|---|---|---:|"]


def agreement_table(scene: str, reference_episodes: list[Episode], candidates: list[tuple[str, Mapping[str, Any]]],
                    workers: int = 2) -> str:
    """The markdown table of every ``(label, overrides)`` fast pipeline replaying the reference
    episodes, and a line on the reference itself."""
    balls = len(reference_episodes[0].captured)
    rows = list(TABLE_HEADER)
    for label, overrides in candidates:
        candidate = run_pipeline(scene, balls, reference_episodes, True, overrides, workers)
        rows += agreement_rows(label, candidate, reference_episodes)
    throws = sum(len(e.captured) for e in reference_episodes)
    seconds = sum(e.seconds for e in reference_episodes)
    seeds = [e.seed for e in reference_episodes]
    left_out = max(seeds) - min(seeds) + 1 - len(seeds)
    return "\n".join(rows) + (f"\n\nReference: {len(reference_episodes)} {scene} episodes of {balls} throws, "
                              f"{throws / seconds:.2f} throws/s; left out: {left_out} (their pause never came "
                              f"to rest).")
