"""The variants table: every variant evaluated under the agents that tell its difficulty apart
(oracles blind or told what the variant hides, the adaptive oracle, random and constant actions,
the shipped windy PPO models), for ``scripts/variants_table.py``."""

from __future__ import annotations

import dataclasses
import time
from concurrent.futures import ProcessPoolExecutor

import gymnasium as gym
import numpy as np

import netgym  # noqa: F401  (registers the variants)
from agents.evaluation import CaptureRate, evaluate
from agents.oracle import AdaptiveOracle, BallisticOracle, InformedOracle
from agents.policies import PRETRAINED_WINDY, PRETRAINED_WINDY_STACKED, FrameStackPolicy, load_policy
from agents.random_agent import RandomAgent
from agents.warm_up import compile_kernels

AGENTS = {
    "ballistic oracle": lambda env: BallisticOracle(env.scene),
    "informed oracle": InformedOracle,
    "adaptive oracle (uses the feedback)": lambda env: AdaptiveOracle(env.scene),
    "constant action (10 m/s, 50 degrees, straight)": lambda env: ConstantAction(),
    "random": lambda env: RandomAgent(0),
    "PPO, MLP with the feedback (agents/pretrained/ppo_windy.zip)": lambda env: load_policy(PRETRAINED_WINDY),
    "PPO, MLP on the last 5 observations (agents/pretrained/ppo_windy_stack5.zip)":
        lambda env: FrameStackPolicy(load_policy(PRETRAINED_WINDY_STACKED), 5),
}
VARIANTS = {"NetCatchWindy-v0": list(AGENTS),  # the windy PPO model was trained on NetCatchWindy-v0
            "NetCatchNoisy-v0": ["ballistic oracle", "random"],
            "NetCatchRandomized-v0": ["ballistic oracle", "random"],
            "NetCatchRandomized-v1": ["ballistic oracle", "informed oracle", "adaptive oracle (uses the feedback)",
                                      "random"]}
REMARKS = {"NetCatchWindy-v0": {"ballistic oracle": "blind to the wind", "informed oracle": "knows the wind"},
           "NetCatchRandomized-v1": {"ballistic oracle": "blind to the draws", "informed oracle": "knows the draws"}}
"""What an agent's label adds on the variants that hide what moves the aim (a wind, the ball)."""


def label(variant: str, agent: str) -> str:
    """``agent``'s label in ``variant``'s rows: with its remark on what the variant hides."""
    remark = REMARKS.get(variant, {}).get(agent)
    return agent if remark is None else f"{agent} ({remark})"


class ConstantAction:
    """The middle of the action space every time: a baseline that needs no aim at all."""

    def predict(self, observation: np.ndarray, state=None, episode_start=None, deterministic: bool = True):
        """The zero action."""
        return np.zeros(3, dtype=np.float32), state


def row(job: tuple[str, str, int]) -> dict:
    """One (variant, agent, episodes) job's row: its capture rate and throws/s in one process."""
    variant, agent, episodes = job
    kwargs = gym.spec(variant).kwargs
    start = time.perf_counter()
    rate = evaluate(AGENTS[agent], episodes, seed=10_000, progress=f"{variant} {agent}", **kwargs)
    return {"variant": variant, "agent": label(variant, agent), **dataclasses.asdict(rate),
            "throws_per_s": rate.throws / (time.perf_counter() - start)}


def rows(variants: list[str], episodes: int, workers: int) -> list[dict]:
    """The rows of every (variant, agent) pair of ``variants``, on ``workers`` processes (the
    kernels compiled before they start)."""
    jobs = [(variant, agent, episodes) for variant in variants for agent in VARIANTS[variant]]
    compile_kernels("NetCatchWindy-v0")
    with ProcessPoolExecutor(workers) as pool:
        return list(pool.map(row, jobs))


def to_markdown(table: list[dict], episodes: int) -> str:
    """The rows as a markdown table."""
    lines = [f"| variant | agent | capture rate ({episodes} episodes, 95% CI) | throws/s (one process) |",
             "|---|---|---|---:|"]
    for r in table:
        rate = CaptureRate(r["captured"], r["throws"], r["low"], r["high"])
        lines.append(f"| {r['variant']} | {r['agent']} | {rate} | {r['throws_per_s']:.1f} |")
    return "\n".join(lines)
