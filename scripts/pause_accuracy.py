"""How near does the pause between throws come to the equilibrium of the loaded net? Seeded
loaded basket nets (1-10 balls), each pause against a fine relaxation (0.5 ms, to 3 mm/s) from
the same state: the largest ball distance and the RMS net particle distance, and the cost.

Usage::

    python scripts/pause_accuracy.py              # 200 loaded nets
    python scripts/pause_accuracy.py --quick      # 2 loaded nets, for CI smoke tests
    python scripts/pause_accuracy.py --candidate simulation.settle_dt=0.006   # that pause too, same nets
"""

from __future__ import annotations

import argparse

from netgym.arguments import parse_overrides
from netgym.bench.accuracy.pause_accuracy import pause_accuracy, to_markdown


def main() -> None:
    """Parse arguments, run, print the markdown table."""
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--quick", action="store_true", help="2 loaded nets, for smoke tests")
    parser.add_argument("--nets", type=int, default=200)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--candidate", action="append", default=[], metavar="FIELD=VALUE[,FIELD=VALUE]",
                        help="scene overrides whose default pause runs from the same loaded nets too (repeatable)")
    args = parser.parse_args()
    candidates = [parse_overrides(text) for text in args.candidate]
    print(to_markdown(pause_accuracy(2 if args.quick else args.nets, args.seed, candidates=candidates)))


if __name__ == "__main__":
    main()
