"""What a goal under the ``held`` rule waits for: seeded throws (half random, half noisy oracle)
into the empty goal; for the captured ones, when the ball's horizontal motion ends, when it last
leaves the floor, when the fast path decides, and how fast the net still moves.

Usage::

    python scripts/held_goal_phases.py               # 60 throws, seed 3
    python scripts/held_goal_phases.py --quick       # 6 throws, for smoke tests
"""

from __future__ import annotations

import argparse

from agents.bench.held_goal import held_captures, summary


def main() -> None:
    """Parse arguments, throw, print the summary."""
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--throws", type=int, default=60)
    parser.add_argument("--seed", type=int, default=3)
    parser.add_argument("--quick", action="store_true", help="6 throws")
    args = parser.parse_args()
    print(summary(held_captures(6 if args.quick else args.throws, args.seed)))


if __name__ == "__main__":
    main()
