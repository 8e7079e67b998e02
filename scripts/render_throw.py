"""Render throws of NetCatch-v0 to an animated GIF (or a PNG still with ``--still``).

Usage::

    python scripts/render_throw.py --output docs/throw.gif           # three oracle throws
    python scripts/render_throw.py --scene goal --policy random --output goal.gif
"""

from __future__ import annotations

import argparse
from pathlib import Path

import gymnasium as gym
import numpy as np
from PIL import Image

import netgym  # noqa: F401  (registers NetCatch-v0)
from agents.oracle import BallisticOracle
from netgym.envs import NetCatchEnv


def record(scene: str, seed: int, throws: int, policy: str) -> list[np.ndarray]:
    """Frames of ``throws`` throws by ``policy`` (``oracle`` or ``random``)."""
    env = gym.make("NetCatch-v0", scene=scene, balls_per_episode=throws, render_mode="rgb_array_list").unwrapped
    obs, _ = env.reset(seed=seed)
    oracle = BallisticOracle(env.scene)
    rng = np.random.default_rng(seed)
    frames = list(env.render())
    for _ in range(throws):
        action = oracle.predict(obs)[0] if policy == "oracle" else rng.uniform(-1, 1, 3).astype(np.float32)
        obs, reward, terminated, _, info = env.step(action)
        frames += env.render()
        print(f"throw: {'captured' if info['captured'] else 'missed'} ({info['reason']}, "
              f"{info['sim_time']:.2f} s simulated, {info['substeps']} substeps)")
    env.close()
    return frames


def main() -> None:
    """Parse arguments, record, write the file."""
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--scene", default="basket")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--throws", type=int, default=3)
    parser.add_argument("--policy", choices=("oracle", "random"), default="oracle")
    parser.add_argument("--output", type=Path, default=Path("throw.gif"))
    parser.add_argument("--still", action="store_true", help="write only the last frame as a PNG")
    args = parser.parse_args()
    frames = record(args.scene, args.seed, args.throws, args.policy)
    images = [Image.fromarray(f) for f in frames]
    args.output.parent.mkdir(parents=True, exist_ok=True)
    if args.still:
        images[-1].save(args.output)
    else:
        fps = NetCatchEnv.metadata["render_fps"]
        images[0].save(args.output, save_all=True, append_images=images[1:], duration=int(1000 / fps), loop=0,
                       optimize=True)
    print(f"wrote {args.output} ({len(images)} frames)")


if __name__ == "__main__":
    main()
