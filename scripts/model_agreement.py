"""The two contact models on the same throws (netgym/bench/accuracy/model_agreement.py): sampled
basket throws (half random, half noisy-oracle actions), each from the settled empty net, by
each model's fast path and full simulation; the catches, the shares of equal outcomes, the
time a throw, and a step's cost of each model at the same integrator and dt.

Usage::

    python scripts/model_agreement.py --results docs/results/model_agreement.json     # 1000 throws
    python scripts/model_agreement.py --quick                                          # 6 throws, prints
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path

from netgym.bench.accuracy.model_agreement import block, model_agreement
from netgym.bench.results import write_results
from netgym.bench.throws import sample_throws


def main() -> None:
    """Parse arguments, run the throws each way, write (or print) the figures."""
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--throws", type=int, default=1000)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--workers", type=int, default=1, help="processes")
    parser.add_argument("--results", type=Path, help="the result file (JSON)")
    parser.add_argument("--quick", action="store_true", help="6 throws, 2 rounds of step costs; printed, not written")
    args = parser.parse_args()
    figures = model_agreement(sample_throws("basket", 6 if args.quick else args.throws, args.seed), args.workers,
                              cost_rounds=2 if args.quick else 5)
    if args.quick or args.results is None:
        print(json.dumps(figures, indent=1))
        return
    write_results(args.results, figures)
    print(block(args.results))


if __name__ == "__main__":
    main()
