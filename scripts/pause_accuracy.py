"""How near does the pause between throws come to the equilibrium of the loaded net? Seeded
loaded basket nets (1-10 balls), each pause against a fine relaxation (0.5 ms, to 3 mm/s) from
the same state: the largest ball distance and the RMS net particle distance, and the cost.

Usage::

    python scripts/pause_accuracy.py              # 200 loaded nets
    python scripts/pause_accuracy.py --quick      # 2 loaded nets, for CI smoke tests
"""

from __future__ import annotations

import argparse

from netgym.bench.pause_accuracy import pause_accuracy, to_markdown


def main() -> None:
    """Parse arguments, run, print the markdown table."""
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--quick", action="store_true", help="2 loaded nets, for smoke tests")
    parser.add_argument("--nets", type=int, default=200)
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args()
    print(to_markdown(pause_accuracy(2 if args.quick else args.nets, args.seed)))


if __name__ == "__main__":
    main()
