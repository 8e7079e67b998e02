"""The poster of every registered id for its env card in the docs (``docs/figures/envs/ID.png``):
the scene after the ballistic oracle's first two throws of a seeded episode (for the pixel id, the
observation it returns, enlarged). ``docs/_scripts/env_cards.py`` refuses an id without one.

Usage::

    python scripts/render_posters.py                     # every id
    python scripts/render_posters.py NetCatchWindy-v0    # one
"""

from __future__ import annotations

import argparse
from pathlib import Path

import gymnasium as gym
import numpy as np
from PIL import Image
from tqdm import tqdm

import netgym
from agents.oracle import BallisticOracle

POSTERS = Path(__file__).resolve().parents[1] / "docs" / "figures" / "envs"


def poster(env_id: str, seed: int = 0, throws: int = 2) -> np.ndarray:
    """An (H, W, 3) uint8 picture of ``env_id`` after ``throws`` oracle throws of episode ``seed``."""
    env = gym.make(env_id, render_mode="rgb_array")
    oracle = BallisticOracle(env.unwrapped.scene)
    obs, _ = env.reset(seed=seed)
    for _ in range(throws):
        vector = env.unwrapped._observation()  # the oracle reads the vector observation, also behind ThrowerView
        obs, *_ = env.step(oracle.predict(vector, deterministic=True)[0])
    frame = np.kron(obs, np.ones((4, 4, 1), dtype=np.uint8)) if obs.ndim == 3 else env.render()
    env.close()
    return frame


def main() -> None:
    """Parse arguments, write the posters."""
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("ids", nargs="*", default=list(netgym.ENVIRONMENTS), help="registered ids (default: all)")
    args = parser.parse_args()
    POSTERS.mkdir(parents=True, exist_ok=True)
    for env_id in tqdm(args.ids, desc="posters", unit="id"):
        Image.fromarray(poster(env_id)).save(POSTERS / f"{env_id}.png", optimize=True)
    print(f"wrote {len(args.ids)} posters to {POSTERS}")


if __name__ == "__main__":
    main()
