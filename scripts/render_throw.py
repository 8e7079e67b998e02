"""Render an episode of NetCatch-v0 to an MP4, an animated GIF, a 3D page you can turn (.html),
or a PNG still with ``--still``; the output's suffix picks the format.

Every throw is filmed from its launch to its decision (misses decided at launch fly on to the
ground), frames ``1 / render_fps`` simulated seconds apart, so the video runs at the
simulation's pace, and then the net settling for the next throw (``--no-settling``: not
filmed); the last frame of each throw is held half a second. The camera frames each throw
side-on (the thrower, the flight, the net); each frame says which throw it is and, once
decided, its outcome. The ``.html`` page shows the episode in 3D (plotly): orbit and zoom,
play/pause, a time slider.

Usage::

    python scripts/render_throw.py --output docs/throw.gif                  # three oracle throws
    python scripts/render_throw.py --output episode.html                    # the same in 3D
    python scripts/render_throw.py --policy agents/pretrained/ppo_netcatch.zip --output ppo.mp4
    python scripts/render_throw.py --scene goal --policy random --throws 5 --output goal.mp4
"""

from __future__ import annotations

import argparse
from pathlib import Path

from PIL import Image

from agents.episode_film import record
from agents.policies import SB3_ALGORITHMS
from netgym.view.render import caption_frame
from netgym.view.video import FORMATS


def main() -> None:
    """Parse arguments, record, write the file."""
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--scene", default="basket")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--throws", type=int, default=3)
    parser.add_argument("--policy", default="oracle", help="oracle, random or the path of a saved SB3 model (.zip)")
    parser.add_argument("--algorithm", choices=SB3_ALGORITHMS,
                        help="the algorithm of a saved model (default: the one it was saved with, else PPO)")
    parser.add_argument("--settling", action=argparse.BooleanOptionalAction, default=True,
                        help="film the net settling between throws (default: yes)")
    parser.add_argument("--output", type=Path, default=Path("throw.mp4"), help=" or ".join(FORMATS))
    parser.add_argument("--still", action="store_true", help="write only the last frame as a PNG")
    args = parser.parse_args()
    suffix = args.output.suffix.lower()
    if args.still and suffix != ".png":
        parser.error(f"--still writes a PNG: --output must end in .png, got {str(args.output)!r}")
    if not args.still and suffix not in FORMATS:
        parser.error(f"--output {str(args.output)!r}: the suffix must be one of {list(FORMATS)} (or .png with --still)")
    render_mode = "replay_list" if suffix == ".html" else "rgb_array_list"
    film = record(args.scene, args.seed, args.throws, args.policy, args.algorithm, args.settling, render_mode)
    if args.still:
        args.output.parent.mkdir(parents=True, exist_ok=True)
        Image.fromarray(caption_frame(film.frames[-1], film.captions[-1])).save(args.output)
    else:
        film.write(args.output)
    print(f"wrote {args.output} ({len(film.frames)} frames, {args.output.stat().st_size / 1e6:.1f} MB)")


if __name__ == "__main__":
    main()
