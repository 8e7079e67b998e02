"""Ship a baseline's model: of one algorithm's runs on one env id, the model that catches the
most throws of fresh episodes (seeds 50000, ...: neither training's nor the table's), written to
``agents/pretrained/`` without what only training reads (:func:`~agents.policies.for_acting`: a
shipped model is for acting; training it further starts its optimizers afresh).
The runs' models are those ``scripts/baselines.py`` saved under ``OUT/models/``.

Usage::

    python scripts/ship_model.py sac_asym NetCatchPixels-v0 sac_asym_pixels.zip
    python scripts/ship_model.py sac_asym NetCatchWindy-v0 sac_asym_windy.zip --out docs/results/baselines_long
"""

from __future__ import annotations

import argparse
from pathlib import Path

from agents.baselines.runner import evaluate_saved
from agents.policies import PRETRAINED, for_acting, load_policy
from netgym.errors import InvalidArgumentError

SELECTION_SEED = 50_000


def main() -> None:
    """Parse arguments, evaluate every saved seed, write the best one's model."""
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("algorithm", help="the algorithm's name in the baselines (its yml's name), e.g. sac_asym")
    parser.add_argument("env_id", help="the registered id its runs trained on")
    parser.add_argument("name", help="the file name in agents/pretrained/")
    parser.add_argument("--out", type=Path, default=Path("docs/results/baselines"), help="the baselines' folder")
    parser.add_argument("--episodes", type=int, default=400, help="fresh episodes each saved model is evaluated on")
    args = parser.parse_args()
    try:
        rates = evaluate_saved(args.out, args.algorithm, args.env_id, args.episodes, SELECTION_SEED)
    except InvalidArgumentError as error:
        parser.error(str(error))
    for path, rate in rates.items():
        print(f"{path.stem}: {rate}")
    best = max(rates, key=lambda path: rates[path].rate)   # the lowest seed of a tie
    model = load_policy(best)
    for_acting(model)
    target = PRETRAINED.parent / args.name
    model.save(target)
    print(f"wrote {target} ({best.stem}, {target.stat().st_size / 1e6:.1f} MB)")


if __name__ == "__main__":
    main()
