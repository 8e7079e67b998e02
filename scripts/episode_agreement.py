"""Do the shortcuts change episodes? The outcomes of seeded 5-ball episodes in the default
pipeline (IMEX Euler at 2 ms, the fast path, the pause relaxed to 10 cm/s) against a reference
pipeline (0.5 ms, every throw simulated to its time limit, the pause relaxed to 1 mm/s), on
the same throwers and actions: half noisy-oracle episodes, half random. Throws 2..N meet the
net and the balls as each pipeline left them.

The reference is computed once and stored (``--reference``, JSON); later runs reuse it, so
other settings can be compared against it cheaply with ``--candidate``.

Usage::

    python scripts/episode_agreement.py                  # 250 episodes: 1000 throws at positions 2..5
    python scripts/episode_agreement.py --candidate simulation.settle_speed=0.03
    python scripts/episode_agreement.py --quick          # 2 3-ball episodes, nothing stored, for smoke tests
"""

from __future__ import annotations

import argparse
from pathlib import Path

from netgym.arguments import parse_overrides
from agents.bench.episode_agreement import agreement_table, load, reference, save

ROOT = Path(__file__).resolve().parents[1]


def main() -> None:
    """Parse arguments, get the reference, run the default and the candidates, print the table."""
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--quick", action="store_true", help="2 3-ball episodes, reference not stored")
    parser.add_argument("--episodes", type=int, default=250)
    parser.add_argument("--balls", type=int, default=5, help="throws per episode")
    parser.add_argument("--scene", default="basket")
    parser.add_argument("--workers", type=int, default=2, help="processes")
    parser.add_argument("--reference", type=Path, default=ROOT / "docs" / "figures" / "episode_reference.json")
    parser.add_argument("--recompute", action="store_true", help="recompute the stored reference")
    parser.add_argument("--candidate", action="append", default=[], metavar="FIELD=VALUE[,FIELD=VALUE]",
                        help="scene overrides of a pipeline to compare too (repeatable)")
    args = parser.parse_args()
    if args.quick:
        scene, reference_episodes = args.scene, reference(args.scene, 2, 3, workers=args.workers)
    elif args.reference.exists() and not args.recompute:
        scene, reference_episodes = load(args.reference)
    else:
        scene = args.scene
        reference_episodes = reference(scene, args.episodes, args.balls, workers=args.workers)
        save(reference_episodes, args.reference, scene)
    candidates = [("default", {}), *((label, parse_overrides(label)) for label in args.candidate)]
    print(agreement_table(scene, reference_episodes, candidates, args.workers))


if __name__ == "__main__":
    main()
