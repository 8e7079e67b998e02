"""Throws per second with the fast path and with full simulation, their outcome agreement, and
the throughput of 8 environments stepped together: a Gymnasium ``SyncVectorEnv`` in one process
and SB3's ``SubprocVecEnv`` training environment (noisy oracle actions, the same run).

Scenes: the basket, the goal (its ``line`` rule) and the goal under the ``held`` rule.
Throws are drawn per seed: the thrower uniformly from the scene's ranges, the action either
uniform in [-1, 1]^3 (half of them) or the ballistic oracle's plus Gaussian noise (sd 0.15),
so that captures, rim hits and misses all occur. Each throw starts from the empty net at rest
and is simulated twice: ``fast=True`` (closed-form flight, sleeping net, early decision) and
``fast=False`` (everything integrated from launch to the time limit).

With ``--reference-dt`` every throw is also simulated fully at that finer step, and the table
says how often the fast path and the full simulation at the scene's own step agree with that
converged outcome (``--case`` picks the cases to run, and leaves out the vector environments).

Usage::

    python scripts/bench_env.py                 # 1000 throws per scene, both cores
    python scripts/bench_env.py --throws 300 --case "goal, held" --reference-dt 0.0001   # ~10 min
    python scripts/bench_env.py --quick         # 2 throws a case and 2 environments, for CI smoke tests
"""

from __future__ import annotations

import argparse

from agents.bench.env_throughput import SETUPS, env_throughput
from netgym.bench.accuracy.fast_path import CASES, compare, summarise
from netgym.bench.throws import sample_throws


def main() -> None:
    """Parse arguments, run, print a markdown report."""
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--quick", action="store_true", help="a few throws, for smoke tests")
    parser.add_argument("--throws", type=int, default=1000)
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--case", action="append", choices=list(CASES), metavar="CASE",
                        help=f"run only this case (repeatable; one of {', '.join(repr(c) for c in CASES)})")
    parser.add_argument("--reference-dt", type=float, help="also simulate every throw fully at this step (s)")
    args = parser.parse_args()
    count = 2 if args.quick else args.throws
    reference = "" if args.reference_dt is None else \
        f" fast agrees with full at {args.reference_dt:g} s | full agrees with it |"
    print("| scene | throws | outcome agreement | captured | fast throws/s | full throws/s | speed-up | "
          f"throws touching the net | fast throws/s on those |{reference}")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|" + ("---:|---:|" if reference else ""))
    for label in args.case or CASES:
        scene, overrides = CASES[label]
        s = summarise(compare(scene, sample_throws(scene, count), 1 if args.quick else args.workers, overrides,
                              args.reference_dt))
        print(f"| {label} | {s['throws']} | {100 * s['agreement']:.1f}% | {100 * s['captured']:.0f}% | "
              f"{s['fast_throws_per_s']:.1f} | {s['full_throws_per_s']:.2f} | "
              f"{s['fast_throws_per_s'] / s['full_throws_per_s']:.0f}x | {s['touching']} | "
              f"{s['fast_touching_throws_per_s']:.1f} |"
              + (f" {100 * s['fast_vs_reference']:.1f}% | {100 * s['full_vs_reference']:.1f}% |" if reference else ""))
    if args.case is None:
        envs = 2 if args.quick else 8
        print(f"\n| {envs} environments (basket, noisy oracle actions) | env steps/s |\n|---|---:|")
        for kind, rate in env_throughput(envs, 2 if args.quick else 30).items():
            print(f"| {SETUPS[kind]} | {rate:.1f} |")
    print("\n(per-process figures; agreement and full-simulation runs use "
          f"{1 if args.quick else args.workers} process(es))")


if __name__ == "__main__":
    main()
