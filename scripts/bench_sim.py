"""Simulator throughput: substeps per second and ns per spring per substep, per integrator
and scene, on one thread.

Two workloads per (scene, integrator):

- ``net``: the settled net alone;
- ``impact``: a ball driven into the net at 10 m/s and then resting in it (all contacts live).

Each figure is the best of ``--repeats`` timed runs, after a warm-up run that compiles the
kernels. Usage::

    python scripts/bench_sim.py            # full run, prints a markdown table
    python scripts/bench_sim.py --quick    # seconds, for CI smoke tests
"""

from __future__ import annotations

import argparse
import platform

from netgym.bench.speed.sim_throughput import run, to_markdown


def main() -> None:
    """Parse arguments, run, print."""
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--quick", action="store_true", help="tiny run for smoke tests")
    args = parser.parse_args()
    print(f"# bench_sim on {platform.processor() or platform.machine()}, Python {platform.python_version()}, one thread")
    print(to_markdown(run(args.quick)))


if __name__ == "__main__":
    main()
