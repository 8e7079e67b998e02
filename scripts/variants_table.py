"""Capture rates of the reference agents on the registered variants, with 95% confidence
intervals, as a markdown table (docs/AGENTS.md).

Agents: the ballistic oracle (knows the drag of the air, not the wind), the informed oracle
(also told each episode's wind and scene draws: the ceiling), the adaptive oracle (corrects its aim from the
feedback of its own throws), the constant middle action, random actions, PPO trained on the
windy variant (``python scripts/train_ppo.py --env NetCatchWindy-v0 --minutes 20``) and PPO
trained on the episode's last five observations stacked (``--frame-stack 5``). Episodes are
seeded 10000, 10001, ...; each agent meets the same ones. Two processes share the agents.

Usage::

    python scripts/variants_table.py --episodes 1000 --results docs/results/variants.json
    python scripts/variants_table.py --variants NetCatchRandomized-v1 --episodes 1000 \
        --results docs/results/variants_randomized_v1.json
    python scripts/variants_table.py --quick            # a few episodes, for smoke tests
"""

from __future__ import annotations

import argparse
from pathlib import Path

from agents.variants_table import VARIANTS, rows, to_markdown
from netgym.bench.results import write_results


def main() -> None:
    """Parse arguments, evaluate every (variant, agent) pair, print the table."""
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--episodes", type=int, default=1000)
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--quick", action="store_true", help="2 episodes per agent")
    parser.add_argument("--results", type=Path, help="also write the rows to this result file (JSON)")
    parser.add_argument("--variants", nargs="+", choices=list(VARIANTS), default=list(VARIANTS),
                        help="the variants to evaluate (default: all)")
    args = parser.parse_args()
    episodes = 2 if args.quick else args.episodes
    table = rows(args.variants, episodes, args.workers)
    print(to_markdown(table, episodes))
    if args.results is not None:
        print(f"wrote {write_results(args.results, {'episodes': episodes, 'seed': 10_000, 'rows': table})}")


if __name__ == "__main__":
    main()
