"""Training throughput on this machine: RLlib's PPO with 2 env runners (one Ray node, and two
nodes on the same machine) against Stable-Baselines3's PPO with 2 ``SubprocVecEnv`` envs.

Each figure is env steps per second of training, sampling and learning together (PPO's settings
from agents/hyperparams/ppo.yml; the same number of env steps for each), setup excluded: Ray's
start, the algorithm's build, the envs' start. The Ray runs use ``scripts/local_cluster.py``
(network and process namespaces of their own: root, ``unshare``, ``ip``); the "two nodes" figure
is two Ray nodes of one CPU each on this one machine, not two machines. Needs the ``rllib`` and
``train`` extras. Writes ``docs/results/rllib.json`` (``--results``).

Usage::

    python scripts/bench_rllib.py --iterations 6 --repeats 2 --results docs/results/rllib.json
    python scripts/bench_rllib.py --quick
"""

from __future__ import annotations

import argparse
from pathlib import Path

from agents.bench.rllib_speed import measure, to_markdown
from netgym.bench.results import write_results


def main() -> None:
    """Measure the three setups in rounds, print each run and the medians, write the result file."""
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--iterations", type=int, default=8, help="RLlib iterations (SB3 rollouts) of 1024 env steps")
    parser.add_argument("--results", type=Path, help="write the figures here (docs/results/rllib.json)")
    parser.add_argument("--repeats", type=int, default=2, help="runs of each setup, one round after another")
    parser.add_argument("--quick", action="store_true", help="2 iterations, one round, for smoke tests")
    args = parser.parse_args()
    figures = measure(*((2, 1) if args.quick else (args.iterations, args.repeats)))
    print(to_markdown(figures))
    if args.results is not None:
        print(f"written: {write_results(args.results, figures)}")


if __name__ == "__main__":
    main()
