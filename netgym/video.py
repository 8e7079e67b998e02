"""Writing rendered frames to a file: animated GIF (Pillow) or MP4 (imageio with its ffmpeg).

Both come with the ``render`` extra (``pip install netgym[render]``). A video of an episode is
the ``rgb_array_list`` frames of its steps, which are ``1 / render_fps`` simulated seconds
apart, so ``fps = env.metadata["render_fps"]`` plays it at the simulation's own pace.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

import numpy as np

FORMATS = (".gif", ".mp4")


def write_video(frames: Sequence[np.ndarray], path: str | Path, fps: int) -> Path:
    """Write ``frames`` (H, W, 3) uint8 to ``path`` (``.gif`` or ``.mp4``) at ``fps``; returns the path."""
    path = Path(path)
    if path.suffix.lower() not in FORMATS:
        raise ValueError(f"video path {str(path)!r}: the suffix must be one of {list(FORMATS)}")
    if len(frames) == 0:
        raise ValueError("no frames to write (render_mode='rgb_array_list' collects them)")
    path.parent.mkdir(parents=True, exist_ok=True)
    if path.suffix.lower() == ".gif":
        from PIL import Image

        images = [Image.fromarray(f) for f in frames]
        images[0].save(path, save_all=True, append_images=images[1:], duration=round(1000 / fps), loop=0,
                       optimize=True)
    else:
        import imageio.v2 as imageio

        with imageio.get_writer(path, fps=fps, codec="libx264", quality=7, macro_block_size=8) as writer:
            for frame in frames:
                writer.append_data(frame)
    return path
