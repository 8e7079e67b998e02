"""Do the shortcuts change episodes? The outcomes of seeded 5-ball episodes in the default
pipeline (IMEX Euler at 2 ms, the fast path, the pause relaxed to 1 cm/s) against a reference
pipeline (0.5 ms, every throw simulated to its time limit, the pause relaxed to 1 mm/s), on
the same throwers and actions: half noisy-oracle episodes, half random. Throws 2..N meet the
net and the balls as each pipeline left them.

Usage::

    python scripts/episode_agreement.py                  # 250 episodes: 1000 throws at positions 2..5
    python scripts/episode_agreement.py --quick          # 2 episodes, for smoke tests
"""

from __future__ import annotations

import argparse

from netgym.bench.episode_agreement import episode_agreement, to_markdown


def main() -> None:
    """Parse arguments, run both pipelines, print the agreement table."""
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--quick", action="store_true", help="2 episodes, for smoke tests")
    parser.add_argument("--episodes", type=int, default=250)
    parser.add_argument("--balls", type=int, default=5, help="throws per episode")
    parser.add_argument("--scene", default="basket")
    parser.add_argument("--workers", type=int, default=2, help="processes")
    args = parser.parse_args()
    pairs = episode_agreement(args.scene, 2 if args.quick else args.episodes, args.balls, workers=args.workers)
    print(to_markdown(pairs))


if __name__ == "__main__":
    main()
