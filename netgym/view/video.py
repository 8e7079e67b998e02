"""Writing an episode to a file: animated GIF (Pillow), MP4 (imageio with its ffmpeg), or a 3D
page you can turn (``.html``, plotly; :mod:`netgym.view.replay_page`).

All come with the ``render`` extra (``pip install netgym[render]``). A video of an episode is
the ``rgb_array_list`` frames of its steps, which are ``1 / render_fps`` simulated seconds
apart, so ``fps = env.metadata["render_fps"]`` plays it at the simulation's own pace; a page is
the ``replay_list`` snapshots of the same instants. :class:`EpisodeFilm` collects either, with a
caption per frame saying which throw it is and, once decided, its outcome.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from netgym.errors import InvalidArgumentError

FORMATS = (".gif", ".mp4", ".html")
HOLD = 0.5          # simulated seconds the last frame of each throw is held, to read its outcome


def write_video(frames: Sequence[Any], path: str | Path, fps: int, captions: Sequence[str] | None = None) -> Path:
    """Write ``frames`` to ``path`` at ``fps``, each with its caption (if given), and return the
    path: (H, W, 3) uint8 frames to ``.gif`` or ``.mp4``, :class:`~netgym.view.replay.Snapshot` to ``.html``."""
    path = Path(path)
    suffix = path.suffix.lower()
    if suffix not in FORMATS:
        raise InvalidArgumentError(f"video path {str(path)!r}: the suffix must be one of {list(FORMATS)}")
    if len(frames) == 0:
        raise InvalidArgumentError("no frames to write (render_mode='rgb_array_list' or 'replay_list' collects them)")
    if captions is not None and len(captions) != len(frames):
        raise InvalidArgumentError(f"{len(captions)} captions for {len(frames)} frames; give one per frame")
    from netgym.view.replay import Snapshot

    snapshots = isinstance(frames[0], Snapshot)
    if snapshots != (suffix == ".html"):
        raise InvalidArgumentError(f"video path {str(path)!r}: .html takes the snapshots of render_mode='replay_list', "
                                   f".gif and .mp4 the images of 'rgb_array_list'; got {type(frames[0]).__name__}")
    path.parent.mkdir(parents=True, exist_ok=True)
    if suffix == ".html":
        from netgym.view.replay_page import write_replay_page

        return write_replay_page(frames, path, fps, captions)
    if captions is not None:
        from netgym.view.render import caption_frame

        frames = [caption_frame(frame, caption) for frame, caption in zip(frames, captions)]
    if suffix == ".gif":
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


def outcome_text(info: Mapping[str, Any]) -> str:
    """A throw's outcome in words from its step ``info``, e.g. ``"caught (at rest)"``."""
    return f"{'caught' if info['captured'] else 'missed'} ({str(info['reason']).replace('_', ' ')})"


class EpisodeFilm:
    """The frames of one episode (images or snapshots) with a caption for each: which throw it
    is (``throw 2/3``) and, from the frame of its decision on, its outcome. The last frame of
    each throw is held for ``hold`` seconds, to show the settled scene and its outcome.

    :param throws: throws in the episode.
    :param fps: frames per simulated second (the env's ``render_fps``).
    """

    def __init__(self, throws: int, fps: int, hold: float = HOLD) -> None:
        self.throws, self.fps, self.hold = throws, fps, hold
        self.frames: list[Any] = []
        self.captions: list[str] = []
        self.done = 0

    def start(self, frames: Sequence[Any]) -> None:
        """Add the frames of the reset (before the first throw)."""
        self.frames += frames
        self.captions += [f"throw 1/{self.throws}"] * len(frames)

    def add_throw(self, frames: Sequence[Any], info: Mapping[str, Any]) -> None:
        """Add the frames of the next throw's step (its first frame is the launch) and its ``info``."""
        self.done += 1
        if not frames:
            return
        name = f"throw {self.done}/{self.throws}"
        decided = math.ceil(float(info["sim_time"]) * self.fps - 1e-9)
        held = [frames[-1]] * round(self.hold * self.fps)
        self.frames += list(frames) + held
        self.captions += [name if i < decided else f"{name}: {outcome_text(info)}"
                          for i in range(len(frames) + len(held))]

    def write(self, path: str | Path) -> Path:
        """Write the film to ``path`` (:func:`write_video`)."""
        return write_video(self.frames, path, self.fps, self.captions)
