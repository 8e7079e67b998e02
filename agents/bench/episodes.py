"""Whole episodes, as a user trains on them: the step times and throws per second of NetCatch-v0
with the ballistic oracle or a trained model (every ball caught, so the net fills and must settle
between throws) and with random actions, the settling pauses booked in ``info``."""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from agents.oracle import BallisticOracle
from netgym.arguments import describe_overrides
from netgym.envs import NetCatchEnv

SHIPPED_PPO = "shipped PPO"
ROWS = (("basket", "oracle", 3), ("basket", SHIPPED_PPO, 3), ("basket", "random", 3), ("basket", "oracle", 10),
        ("goal", "oracle", 3), ("goal", "random", 3), ("basket", "oracle", 1))
"""The table's rows: scene, policy, balls per episode (1: single throws into the empty net, the
best case, measured in the same run as the episodes a user trains on)."""


@dataclass(frozen=True)
class EpisodeFigures:
    """Figures of ``throws`` steps of one policy on one scene."""

    scene: str                                    # with the overrides, if any
    policy: str
    balls: int
    throws: int
    capture_rate: float
    throws_per_s: float
    step_ms: tuple[float, float, float]           # p50, p99, max
    settle_substeps: tuple[float, float, float]   # p50, p90, max
    settle_share: float                           # settling substeps / all substeps


def policy_of(name: str) -> Any:
    """A row's policy: the PPO model shipped in the sibling package ``agents`` (imported on call;
    None without Stable-Baselines3, the ``[train]`` extra), else the name (oracle, random)."""
    if name != SHIPPED_PPO:
        return name
    from agents.policies import PRETRAINED, load_policy

    try:
        return load_policy(PRETRAINED)
    except ImportError:
        return None


def run_rows(episodes: int, settings: list[dict | None], announce: Callable[[str], None] | None = None
             ) -> list[EpisodeFigures]:
    """Every row of ROWS with each scene override setting of ``settings`` (None: the default),
    ``episodes`` x 3 / balls episodes each; ``announce`` is told each row as it starts. The
    shipped PPO's row is left out without Stable-Baselines3."""
    figures = []
    for k, (scene, name, balls) in enumerate(ROWS):
        if announce is not None:
            announce(f"[{k + 1}/{len(ROWS)}] {scene}, {name}, {balls}-ball episodes ...")
        policy = policy_of(name)
        if policy is None and announce is not None:
            announce("  left out: the shipped PPO model needs Stable-Baselines3 (the [train] extra)")
        for overrides in [] if policy is None else settings:
            figures.append(run_episodes(scene, policy, max(1, episodes * 3 // balls), balls, overrides=overrides,
                                        label=name))
    return figures


def _chooser(policy: Any, scene: str, seed: int) -> Callable[[np.ndarray], np.ndarray]:
    """The action for an observation: random actions (seeded), the scene's ballistic oracle, or
    the deterministic action of a model with Stable-Baselines3's ``predict``."""
    if policy == "random":
        rng = np.random.default_rng(seed)
        return lambda obs: rng.uniform(-1, 1, 3).astype(np.float32)
    model = BallisticOracle.from_scene(scene) if policy == "oracle" else policy
    return lambda obs: model.predict(obs, deterministic=True)[0]


def run_episodes(scene: str, policy: Any, episodes: int, balls: int, seed: int = 0,
                 overrides: dict | None = None, label: str | None = None) -> EpisodeFigures:
    """Time every step of ``episodes`` seeded episodes of ``balls`` throws in ``scene`` with
    ``overrides``, after one warm-up episode that compiles the kernels. ``policy``: ``"oracle"``,
    ``"random"`` or a trained model (anything with Stable-Baselines3's ``predict``, shown as
    ``label``); only the steps are timed, not the policy's choice of action."""
    env = NetCatchEnv(scene=scene, balls_per_episode=balls, overrides=overrides)
    choose = _chooser(policy, scene, seed)
    steps, settle, total, caught = [], [], [], 0.0
    for episode in range(-1, episodes):
        obs, _ = env.reset(seed=seed + episode + 1)
        done = False
        while not done:
            action = choose(obs)
            start = time.perf_counter()
            obs, reward, done, _, info = env.step(action)
            if episode >= 0:
                steps.append(time.perf_counter() - start)
                settle.append(info["settle_substeps"])
                total.append(info["substeps"])
                caught += float(info["captured"])
    ms = 1e3 * np.array(steps)
    where = f"{scene} ({describe_overrides(overrides)})" if overrides else scene
    name = policy if isinstance(policy, str) else label or type(policy).__name__
    return EpisodeFigures(where, name, balls, len(steps), caught / len(steps), len(steps) / float(np.sum(steps)),
                          (float(np.median(ms)), float(np.percentile(ms, 99)), float(ms.max())),
                          (float(np.median(settle)), float(np.percentile(settle, 90)), float(max(settle))),
                          float(np.sum(settle)) / max(float(np.sum(total)), 1.0))


def to_markdown(rows: list[EpisodeFigures]) -> str:
    """The episodes table."""
    lines = ["| scene | policy | balls per episode | throws | caught | throws/s | step p50 / p99 / max (ms) | "
             "settle substeps p50 / p90 / max | settling share of substeps |",
             "|---|---|---:|---:|---:|---:|---|---|---:|"]
    for r in rows:
        lines.append(f"| {r.scene} | {r.policy} | {r.balls} | {r.throws} | {100 * r.capture_rate:.1f}% | "
                     f"{r.throws_per_s:.1f} | {r.step_ms[0]:.1f} / {r.step_ms[1]:.1f} / {r.step_ms[2]:.1f} | "
                     f"{r.settle_substeps[0]:.0f} / {r.settle_substeps[1]:.0f} / {r.settle_substeps[2]:.0f} | "
                     f"{100 * r.settle_share:.0f}% |")
    return "\n".join(lines)
