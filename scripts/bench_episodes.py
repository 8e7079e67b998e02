"""Whole episodes, what training pays: NetCatch-v0 step times (p50, p99, max) and throws per
second with the ballistic oracle and the shipped PPO model (every ball caught: the net fills and
settles between throws) and with random actions, on one process, with the settling pauses booked in ``info``.

Usage::

    python scripts/bench_episodes.py               # 60 episodes per row
    python scripts/bench_episodes.py --quick       # 2 episodes per row, for CI smoke tests
    python scripts/bench_episodes.py --candidate simulation.settle_dt=0.006   # each row also so, in the same run
"""

from __future__ import annotations

import argparse

from typing import Any

from agents.policies import PRETRAINED, load_policy
from netgym.arguments import parse_overrides
from netgym.bench.episodes import run_episodes, to_markdown

SHIPPED = "shipped PPO"
ROWS = (("basket", "oracle", 3), ("basket", SHIPPED, 3), ("basket", "random", 3), ("basket", "oracle", 10),
        ("goal", "oracle", 3), ("goal", "random", 3))


def _policy(name: str) -> Any:
    """A row's policy: the shipped PPO model (None without Stable-Baselines3), else its name."""
    if name != SHIPPED:
        return name
    try:
        return load_policy(PRETRAINED)
    except ImportError:
        print("  (skipped: the shipped PPO model needs the [train] extra)")
        return None


def main() -> None:
    """Parse arguments, run every row, print a markdown table."""
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--quick", action="store_true", help="2 episodes per row, for smoke tests")
    parser.add_argument("--episodes", type=int, default=60)
    parser.add_argument("--candidate", action="append", default=[], metavar="FIELD=VALUE[,FIELD=VALUE]",
                        help="scene overrides to run every row with too, right after the default (repeatable)")
    args = parser.parse_args()
    episodes = 2 if args.quick else args.episodes
    settings = [None, *(parse_overrides(text) for text in args.candidate)]
    rows = []
    for k, (scene, policy, balls) in enumerate(ROWS):
        print(f"[{k + 1}/{len(ROWS)}] {scene}, {policy}, {balls}-ball episodes ...", flush=True)
        chosen = _policy(policy)
        for overrides in [] if chosen is None else settings:
            rows.append(run_episodes(scene, chosen, max(1, episodes * 3 // balls), balls, overrides=overrides,
                                     label=policy))
    print(to_markdown(rows))


if __name__ == "__main__":
    main()
