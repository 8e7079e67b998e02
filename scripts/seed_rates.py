"""Every saved model of one algorithm's runs on one env id (``scripts/baselines.py`` saves them
under ``OUT/models/``, which git does not keep), each evaluated on the same held-out episodes
(seeds 10000, ..., the table's) with its captures counted by throw; prints the table and writes
the result file. For how a cell's seeds spread where the table's 100 episodes are too few: the
windy task's first throw against its best fixed first throw (``scripts/windy_per_throw.py``).

Usage::

    python scripts/seed_rates.py sac_asym NetCatchWindy-v0 --out docs/results/baselines_long \\
        --episodes 1000 --results docs/results/windy_long_seeds.json
"""

from __future__ import annotations

import argparse
import dataclasses
from pathlib import Path

from agents.baselines.grid import FINAL_SEED
from agents.baselines.runner import evaluate_saved
from agents.windy_throws import table
from netgym.bench.results import write_results
from netgym.errors import InvalidArgumentError


def main() -> None:
    """Parse arguments, evaluate every saved seed, write the result file, print the table."""
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("algorithm", help="the algorithm's name in the baselines (its yml's name), e.g. sac_asym")
    parser.add_argument("env_id", help="the registered id its runs trained on")
    parser.add_argument("--out", type=Path, default=Path("docs/results/baselines"), help="the baselines' folder")
    parser.add_argument("--episodes", type=int, default=1000, help="held-out episodes of every model")
    parser.add_argument("--results", type=Path, required=True, help="the result file (JSON)")
    args = parser.parse_args()
    try:
        rates = evaluate_saved(args.out, args.algorithm, args.env_id, args.episodes, FINAL_SEED)
    except InvalidArgumentError as error:
        parser.error(str(error))
    rows = [{"policy": f"{args.algorithm} {path.stem.replace('_', ' ')}", **dataclasses.asdict(rate)}
            for path, rate in rates.items()]
    figures = {"env_id": args.env_id, "algorithm": args.algorithm, "folder": str(args.out),
               "episodes": args.episodes, "seed": FINAL_SEED, "rows": rows}
    print(table(figures))
    print(f"wrote {write_results(args.results, figures)}")


if __name__ == "__main__":
    main()
