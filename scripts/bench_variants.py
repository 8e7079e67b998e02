"""Every registered id's speed as a user pays it (agents/variant_speed.py): whole episodes with
resets under the ballistic oracle, random actions and the model shipped for each id, interleaved
over rounds, as ratios to NetCatch-v0 in the same run; where each id's time goes (cProfile); and
PPO training's env steps/s on NetCatch-v0 and NetCatchWindy-v0.

Usage::

    python scripts/bench_variants.py --episodes 40 --rounds 3 --results docs/results/variant_speed.json
    python scripts/bench_variants.py --quick            # a few episodes, no training: a smoke test
"""

from __future__ import annotations

import argparse
import dataclasses
from pathlib import Path

from agents.variant_speed import POLICIES, VECTOR_IDS, measure, profile, training_steps_per_s
from netgym.bench.results import write_results
from netgym.bench.speed.speed_table import to_markdown


def main() -> None:
    """Parse arguments, measure, print the table, write the result file."""
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--episodes", type=int, default=40, help="episodes of each id and policy a round")
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--training-steps", type=int, default=4096, help="timed PPO env steps per id (0: none)")
    parser.add_argument("--profile-episodes", type=int, default=10, help="episodes profiled per id and policy")
    parser.add_argument("--quick", action="store_true", help="2 episodes, 1 round, 1 profiled, no training")
    parser.add_argument("--results", type=Path, help="also write the figures to this result file (JSON)")
    args = parser.parse_args()
    episodes, rounds = (2, 1) if args.quick else (args.episodes, args.rounds)
    rows = [dataclasses.asdict(row) for row in measure(episodes, rounds)]
    profiled = 1 if args.quick else args.profile_episodes
    shares = {env_id: {policy: profile(env_id, policy, profiled) for policy in POLICIES} for env_id in VECTOR_IDS}
    training = None if args.quick or args.training_steps == 0 else training_steps_per_s(steps=args.training_steps)
    print(to_markdown(rows, training, shares))
    if args.results is not None:
        figures = {"episodes_per_round": episodes, "rounds": rounds, "rows": rows, "training": training,
                   "profile": shares, "profile_episodes": profiled}
        print(f"wrote {write_results(args.results, figures)}")


if __name__ == "__main__":
    main()
