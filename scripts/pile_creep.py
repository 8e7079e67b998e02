"""Do balls at rest stay at rest? How far the balls of piles in the basket move over 2 s once
they came to rest: arranged piles (balls side by side on the bottom, a ball on two others) and
seeded loaded nets (2-10 balls, paused as between throws), at several dt of the basket's
integrator.

Usage::

    python scripts/pile_creep.py              # 2, 1 and 0.5 ms; 48 loaded nets each
    python scripts/pile_creep.py --quick      # 2 ms, 3 loaded nets, for CI smoke tests
"""

from __future__ import annotations

import argparse

from netgym.bench.accuracy.creep import DTS, NETS, QUICK_DTS, QUICK_NETS, creep, to_markdown


def main() -> None:
    """Parse arguments, run, print the markdown table."""
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--quick", action="store_true", help="2 ms and 3 loaded nets, for smoke tests")
    parser.add_argument("--nets", type=int, default=NETS,
                        help="seeded loaded nets per dt (those of 1 ball are skipped)")
    parser.add_argument("--dt", type=float, action="append", help=f"s (repeatable); default {', '.join(map(str, DTS))}")
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args()
    dts = QUICK_DTS if args.quick else (args.dt or DTS)
    print(to_markdown(creep(dts, QUICK_NETS if args.quick else args.nets, args.seed)))


if __name__ == "__main__":
    main()
