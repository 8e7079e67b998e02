"""Capture rates of the reference agents on the registered variants, with 95% confidence
intervals, as a markdown table (docs/AGENTS.md).

Agents: the ballistic oracle (knows the drag of the air, not the wind), the informed oracle
(also told each episode's wind and scene draws: the ceiling), the adaptive oracle (corrects its aim from the
feedback of its own throws), the constant middle action, random actions, PPO trained on the
windy variant (``python scripts/train_ppo.py --env NetCatchWindy-v0 --minutes 20``) and PPO
trained on the episode's last five observations stacked (``--frame-stack 5``). Episodes are
seeded 10000, 10001, ...; each agent meets the same ones. Two processes share the agents.

Usage::

    python scripts/variants_table.py --episodes 1000 --results docs/results/variants.json
    python scripts/variants_table.py --variants NetCatchRandomized-v1 --episodes 1000 \
        --results docs/results/variants_randomized_v1.json
    python scripts/variants_table.py --quick            # a few episodes, for smoke tests
"""

from __future__ import annotations

import argparse
import dataclasses
import time
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

import gymnasium as gym
import numpy as np

import netgym  # noqa: F401  (registers the variants)
from agents.evaluation import CaptureRate, evaluate
from agents.oracle import AdaptiveOracle, BallisticOracle, InformedOracle
from agents.policies import PRETRAINED_WINDY, PRETRAINED_WINDY_STACKED, FrameStackPolicy, load_policy
from agents.random_agent import RandomAgent
from agents.warm_up import compile_kernels
from netgym.bench.results import write_results

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


def _row(job: tuple[str, str, int]) -> dict:
    variant, agent, episodes = job
    kwargs = gym.spec(variant).kwargs
    start = time.perf_counter()
    rate = evaluate(AGENTS[agent], episodes, seed=10_000, progress=f"{variant} {agent}", **kwargs)
    return {"variant": variant, "agent": label(variant, agent), **dataclasses.asdict(rate),
            "throws_per_s": rate.throws / (time.perf_counter() - start)}


def main() -> None:
    """Parse arguments, evaluate every (variant, agent) pair, print the table."""
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--episodes", type=int, default=1000)
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--quick", action="store_true", help="2 episodes per agent")
    parser.add_argument("--results", type=Path, help="also write the rows to this result file (JSON)")
    parser.add_argument("--variants", nargs="+", choices=list(VARIANTS), default=list(VARIANTS),
                        help="the variants to evaluate (default: all)")
    args = parser.parse_args()
    episodes = 2 if args.quick else args.episodes
    jobs = [(variant, agent, episodes) for variant in args.variants for agent in VARIANTS[variant]]
    compile_kernels("NetCatchWindy-v0")  # before the workers start
    with ProcessPoolExecutor(args.workers) as pool:
        rows = list(pool.map(_row, jobs))
    print(f"| variant | agent | capture rate ({episodes} episodes, 95% CI) | throws/s (one process) |")
    print("|---|---|---|---:|")
    for row in rows:
        rate = CaptureRate(row["captured"], row["throws"], row["low"], row["high"])
        print(f"| {row['variant']} | {row['agent']} | {rate} | {row['throws_per_s']:.1f} |")
    if args.results is not None:
        print(f"wrote {write_results(args.results, {'episodes': episodes, 'seed': 10_000, 'rows': rows})}")


if __name__ == "__main__":
    main()
