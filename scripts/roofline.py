"""A roofline of the spring pass: this machine's bandwidth (L2-resident and DRAM-sized triads),
floating-point peak and square-root/division rate, the pass's floor per spring from its bytes,
flops and one square root and division, and its measured time per spring on the basket (one
thread), with the count of packed (vectorised) and scalar instructions in its machine code.

Usage::

    python scripts/roofline.py --results docs/results/roofline.json
    python scripts/roofline.py --quick          # small sizes and few repeats, for smoke tests
"""

from __future__ import annotations

import argparse
from pathlib import Path

from netgym.bench.results import write_results
from netgym.bench.speed.roofline import roofline


def main() -> None:
    """Parse arguments, measure, print (and write) the figures."""
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--scene", default="basket")
    parser.add_argument("--quick", action="store_true", help="small sizes and few repeats, for smoke tests")
    parser.add_argument("--results", type=Path, help="also write the figures to this result file (JSON)")
    args = parser.parse_args()
    figures = roofline(args.scene, args.quick)
    width = max(len(name) for name in figures)
    for name, value in figures.items():
        print(f"{name:<{width}}  {value:.3g}" if isinstance(value, float) else f"{name:<{width}}  {value}")
    if args.results is not None:
        print(f"wrote {write_results(args.results, figures)}")


if __name__ == "__main__":
    main()
