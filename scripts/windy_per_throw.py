"""Capture rates by throw index on NetCatchWindy-v0 (agents/windy_throws.py): the informed,
blind and adaptive oracles and the shipped PPO models on held-out episodes (seeds 10000, ...,
the baselines'), and the best fixed first throw: the blind aim searched on training episodes
(seeds 0, ...) over a grid of elevations and aim points, refined locally, then evaluated on the
held-out episodes. Prints the table and writes the result file.

Usage::

    python scripts/windy_per_throw.py --episodes 1000      # docs/results/windy_per_throw.json (~17 min)
    python scripts/windy_per_throw.py --quick --results /tmp/windy.json   # a smoke test of seconds
"""

from __future__ import annotations

import argparse
from pathlib import Path

from agents.windy_throws import QUICK_PLAN, SearchPlan, measure, search_summary, table
from netgym.bench.results import RESULTS, write_results


def main() -> None:
    """Parse arguments, measure, write the result file, print the table."""
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--episodes", type=int, default=100, help="held-out episodes of every row")
    parser.add_argument("--search-episodes", type=int, default=SearchPlan.episodes,
                        help="training episodes each aim of the first-throw search is evaluated on")
    parser.add_argument("--quick", action="store_true", help="2 episodes; a search of 2 aims and one round of refinement on 3 episodes")
    parser.add_argument("--results", type=Path, default=RESULTS / "windy_per_throw.json", help="the result file (JSON)")
    args = parser.parse_args()
    episodes, plan = (2, QUICK_PLAN) if args.quick else (args.episodes,
                                                         SearchPlan(episodes=args.search_episodes))
    figures = measure(episodes, plan)
    print(table(figures))
    print(f"\n{search_summary(figures)}\n\n{figures['wall_s']['total']:.0f} s in all")
    print(f"wrote {write_results(args.results, figures)}")


if __name__ == "__main__":
    main()
