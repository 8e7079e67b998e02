"""Seconds from a fresh start to the first step of an environment, from an empty numba cache
(every kernel compiles, as on a fresh clone) and from the cache that run left.

Each figure is one fresh Python process: imports, ``gym.make``, ``reset`` and one ``step``.

Usage::

    python scripts/first_step_time.py                   # NetCatch-v0
    python scripts/first_step_time.py --env NetCatchGoal-v0 --repeats 3
"""

from __future__ import annotations

import argparse

from netgym.bench.first_step import cold_and_warm


def main() -> None:
    """Parse arguments, measure, print a markdown table."""
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--env", default="NetCatch-v0", help="a registered environment id")
    parser.add_argument("--repeats", type=int, default=1, help="cold and warm measurements to take, each in a new cache")
    args = parser.parse_args()
    print(f"| {args.env} | empty numba cache (s) | cached kernels (s) |\n|---|---:|---:|")
    for run in range(1, args.repeats + 1):
        cold, warm = cold_and_warm(args.env)
        print(f"| run {run} | {cold.seconds:.1f} | {warm.seconds:.1f} |", flush=True)


if __name__ == "__main__":
    main()
