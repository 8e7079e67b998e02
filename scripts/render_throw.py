"""Render throws of NetCatch-v0 to an MP4 or animated GIF (or a PNG still with ``--still``).

Every throw is filmed from its launch to its decision (misses decided at launch fly on to the
ground), frames ``1 / render_fps`` simulated seconds apart, so the video runs at the
simulation's pace; ``--settling`` also films the net coming to rest between throws.

Usage::

    python scripts/render_throw.py --output docs/throw.gif                  # three oracle throws
    python scripts/render_throw.py --policy agents/pretrained/ppo_netcatch.zip --output ppo.mp4
    python scripts/render_throw.py --scene goal --policy random --throws 5 --output goal.mp4
"""

from __future__ import annotations

import argparse
from pathlib import Path

import gymnasium as gym
import numpy as np
from PIL import Image

import netgym  # noqa: F401  (registers NetCatch-v0)
from agents.policies import SB3_ALGORITHMS, load_policy
from netgym.video import write_video


def record(scene: str, seed: int, throws: int, policy: str, algorithm: str = "PPO",
           settling: bool = False) -> list[np.ndarray]:
    """Frames of one episode of ``throws`` throws by ``policy`` (``oracle``, ``random`` or a saved model)."""
    env = gym.make("NetCatch-v0", scene=scene, balls_per_episode=throws, render_mode="rgb_array_list",
                   render_settling=settling)
    agent = load_policy(policy, scene, algorithm)
    obs, _ = env.reset(seed=seed)
    frames = list(env.render())
    for _ in range(throws):
        obs, reward, terminated, _, info = env.step(agent.predict(obs, deterministic=True)[0])
        throw_frames = env.render()
        frames += throw_frames
        print(f"throw: {'captured' if info['captured'] else 'missed'} ({info['reason']}, "
              f"{info['sim_time']:.2f} s simulated, {info['substeps']} substeps, {len(throw_frames)} frames)")
    env.close()
    return frames


def main() -> None:
    """Parse arguments, record, write the file."""
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--scene", default="basket")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--throws", type=int, default=3)
    parser.add_argument("--policy", default="oracle", help="oracle, random or the path of a saved SB3 model (.zip)")
    parser.add_argument("--algorithm", default="PPO", choices=SB3_ALGORITHMS, help="the SB3 algorithm of a saved model")
    parser.add_argument("--settling", action="store_true", help="also film the net settling between throws")
    parser.add_argument("--output", type=Path, default=Path("throw.mp4"), help=".mp4 or .gif")
    parser.add_argument("--still", action="store_true", help="write only the last frame as a PNG")
    args = parser.parse_args()
    frames = record(args.scene, args.seed, args.throws, args.policy, args.algorithm, args.settling)
    if args.still:
        args.output.parent.mkdir(parents=True, exist_ok=True)
        Image.fromarray(frames[-1]).save(args.output)
    else:
        write_video(frames, args.output, gym.make("NetCatch-v0").metadata["render_fps"])
    print(f"wrote {args.output} ({len(frames)} frames)")


if __name__ == "__main__":
    main()
