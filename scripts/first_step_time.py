"""Seconds from a fresh start to the first step of an environment, from an empty numba cache
(every kernel compiles, as on a fresh clone) and from the cache that run left; and of the next
step, a throw aimed at the opening (the first to reach the net).

Each figure is one fresh Python process: imports, ``gym.make``, ``reset`` and one ``step``.
With ``--results``, the runs are added to that result file under ``--label`` (the code they
measured), replacing its earlier runs of that label; the README quotes the label written last.

Usage::

    python scripts/first_step_time.py                   # NetCatch-v0
    python scripts/first_step_time.py --env NetCatchGoal-v0 --repeats 3
    python scripts/first_step_time.py --repeats 3 --results docs/results/first_step.json --label "lazy contacts"
"""

from __future__ import annotations

import argparse
import os
from pathlib import Path

from agents.bench.first_step import add_runs, cold_and_warm, run_figures


def main() -> None:
    """Parse arguments, measure, print a markdown table (and add the runs to ``--results``)."""
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--env", default="NetCatch-v0", help="a registered environment id")
    parser.add_argument("--repeats", type=int, default=1, help="cold and warm measurements to take, each in a new cache")
    parser.add_argument("--results", type=Path, help="add the runs to this result file (docs/results/first_step.json)")
    parser.add_argument("--label", default="this tree", help="what code the runs measured, in --results")
    args = parser.parse_args()
    print(f"| {args.env} | load | empty cache: first step s (CPU s) | then aimed step s | "
          f"cached: first step s (CPU s) |\n|---|---:|---:|---:|---:|")
    runs = []
    for run in range(1, args.repeats + 1):
        load = os.getloadavg()[0]
        cold, warm = cold_and_warm(args.env)
        runs.append(run_figures(args.label, load, cold, warm))
        print(f"| run {run} | {load:.1f} | {cold.seconds:.1f} ({cold.cpu_seconds:.1f}) | {cold.aimed_seconds:.1f} | "
              f"{warm.seconds:.1f} ({warm.cpu_seconds:.1f}) |", flush=True)
    if args.results is not None:
        print(f"wrote {add_runs(args.results, args.env, runs)}")


if __name__ == "__main__":
    main()
