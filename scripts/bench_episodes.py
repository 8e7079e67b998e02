"""Whole episodes, what training pays: NetCatch-v0 step times (p50, p99, max) and throws per
second with the ballistic oracle and the shipped PPO model (every ball caught: the net fills and
settles between throws) and with random actions, on one process, with the settling pauses booked in ``info``.

Usage::

    python scripts/bench_episodes.py               # 60 episodes per row
    python scripts/bench_episodes.py --quick       # 2 episodes per row, for CI smoke tests
    python scripts/bench_episodes.py --candidate simulation.settle_dt=0.006   # each row also so, in the same run
    python scripts/bench_episodes.py --episodes 1000 --results docs/results/episodes.json   # the README's figures
"""

from __future__ import annotations

import argparse
import dataclasses
from pathlib import Path

from netgym.arguments import parse_overrides
from agents.bench.episodes import run_rows, to_markdown
from netgym.bench.results import write_results


def main() -> None:
    """Parse arguments, run every row, print a markdown table."""
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--quick", action="store_true", help="2 episodes per row, for smoke tests")
    parser.add_argument("--episodes", type=int, default=60)
    parser.add_argument("--candidate", action="append", default=[], metavar="FIELD=VALUE[,FIELD=VALUE]",
                        help="scene overrides to run every row with too, right after the default (repeatable)")
    parser.add_argument("--results", type=Path, help="also write the rows to this result file (JSON)")
    args = parser.parse_args()
    episodes = 2 if args.quick else args.episodes
    settings = [None, *(parse_overrides(text) for text in args.candidate)]
    rows = run_rows(episodes, settings, announce=lambda line: print(line, flush=True))
    print(to_markdown(rows))
    if args.results is not None:
        figures = {"episodes": episodes, "rows": [dataclasses.asdict(row) for row in rows]}
        print(f"wrote {write_results(args.results, figures)}")


if __name__ == "__main__":
    main()
