"""Capture rate of a saved PPO model, the ballistic oracle or the random policy on NetCatch-v0.

Usage::

    python scripts/evaluate.py agents/pretrained/ppo_netcatch.zip --episodes 1000
    python scripts/evaluate.py oracle --episodes 1000
    python scripts/evaluate.py random --scene goal
"""

from __future__ import annotations

import argparse
import time

from agents.evaluation import evaluate
from agents.policies import load_policy


def main() -> None:
    """Parse arguments, evaluate, print the rate with its 95% confidence interval."""
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("policy", help="path of a saved SB3 model (.zip), 'oracle' or 'random'")
    parser.add_argument("--episodes", type=int, default=100)
    parser.add_argument("--seed", type=int, default=10_000, help="episode i uses seed + i")
    parser.add_argument("--scene", default="basket")
    args = parser.parse_args()
    policy = load_policy(args.policy, args.scene)
    start = time.perf_counter()
    result = evaluate(policy, args.episodes, seed=args.seed, progress=str(args.policy), scene=args.scene)
    seconds = time.perf_counter() - start
    print(f"{args.policy} on {args.scene}: capture rate {result} over {args.episodes} episodes "
          f"(seeds {args.seed}..{args.seed + args.episodes - 1}; {result.throws / seconds:.1f} throws/s)")


if __name__ == "__main__":
    main()
