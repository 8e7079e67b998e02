"""The baselines table: algorithms x env ids x seeds, each run trained at its id's fixed budget
of environment steps and evaluated on the same 100 held-out episodes (deterministic actions).

Each run's result is written to ``OUT/ALGORITHM/ENV_ID/seed_K.json`` the moment it ends (its
command, versions, seed, budget, wall-clock, learning curve and final evaluation); a runner
stopped at any point and started again runs only the missing runs. Runs go to local worker
processes (one core each), or with ``--address`` to a Ray cluster as Ray tasks. At the end the
report is written from the result files (:func:`agents.baselines.report.write_report`):
``OUT/report.md`` (every table), ``OUT/stats.json`` (its statistics, which the docs' quoted tables
read), ``OUT/curves-GROUP.png`` (the learning curves of the vector, feedback and pixel tasks) and
``OUT/profiles.png`` (the performance profiles). Needs the ``baselines`` extra (sb3-contrib):
``pip install -e ".[train,baselines]"``.

Usage::

    python scripts/baselines.py --out runs/baselines                  # the full table
    python scripts/baselines.py --out runs/b --algos sac td3 --ids NetCatch-v0 --seeds 0 1
    python scripts/baselines.py --out runs/b --address auto           # on a running Ray cluster
    python scripts/baselines.py --quick --out /tmp/baselines          # about a minute, for CI
    python scripts/baselines.py --out runs/long --algos sac_asym --ids NetCatchWindy-v0 --budget 184320
    python scripts/baselines.py --report --out docs/results/baselines # the docs' report, statistics, figures
    python scripts/baselines.py --plan --out docs/results/baselines   # what is left, in CPU hours
"""

from __future__ import annotations

import argparse
import os
from pathlib import Path

from agents.baselines.grid import ALGORITHMS, BUDGETS, grid
from agents.baselines.report import write_report
from agents.baselines.runner import missing, run_missing


def build_parser() -> argparse.ArgumentParser:
    """The command line of this script."""
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--out", type=Path, default=Path("runs/baselines"), help="the result files' folder")
    parser.add_argument("--algos", nargs="+", choices=list(ALGORITHMS), help="default: all")
    parser.add_argument("--ids", nargs="+", choices=list(BUDGETS), help="default: the table's")
    parser.add_argument("--seeds", nargs="+", type=int, help="default: 0-4 (quick: 0)")
    parser.add_argument("--budget", type=int, help="the learners' env steps (default: the id's, as the table's)")
    parser.add_argument("--workers", type=int, default=os.cpu_count(), help="local processes (default: one a core)")
    parser.add_argument("--address", help="run on the Ray cluster at this address (e.g. auto) instead")
    parser.add_argument("--quick", action="store_true", help="tiny budgets, one seed, two cheap ids")
    parser.add_argument("--plan", action="store_true",
                        help="run nothing: print the runs left under --out and their estimated CPU hours")
    parser.add_argument("--report", action="store_true",
                        help="run nothing: only write the report, statistics and figures of the results under --out")
    return parser


def main() -> None:
    """Parse arguments, run what is missing, write the report."""
    args = build_parser().parse_args()
    runs = grid(args.algos, args.ids, args.seeds, quick=args.quick, budget=args.budget)
    if args.plan:
        left = missing(runs, args.out)
        hours = sum(run.cost for run in left) / 3600
        print(f"{len(left)} of {len(runs)} runs left under {args.out}: about {hours:.1f} CPU hours, "
              f"{hours / args.workers:.1f} hours on {args.workers} workers (estimates: agents/baselines/grid.py)")
        return
    if not args.report:
        run_missing(runs, args.out, workers=args.workers, address=args.address)
    print(f"wrote {write_report(args.out)}")


if __name__ == "__main__":
    main()
