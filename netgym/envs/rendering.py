"""NetCatchEnv's rendering: frames (or 3D snapshots) of the scene with its thrower, the camera
framed on the throw being simulated, as the render mode asks."""

from __future__ import annotations

import gymnasium as gym
import numpy as np

from netgym.physics.simulator import Simulator
from netgym.view.replay import Scenery, Snapshot


class EnvRendering:
    """The render methods of :class:`~netgym.envs.NetCatchEnv` (a mixin over its ``sim``,
    ``thrower``, ``render_mode``, ``metadata`` and frame buffers)."""

    def _get_renderer(self):
        if self._renderer is None:
            from netgym.view.render import Renderer

            self._renderer = Renderer(self.sim, human=self.render_mode == "human", fps=self.metadata["render_fps"])
        return self._renderer

    def _record_frame(self, sim: Simulator) -> None:
        """Take a frame of ``sim`` as the render mode asks (the env's :class:`Film` records at its instants)."""
        if self.render_mode == "replay_list":
            if self._scenery is None:
                self._scenery = Scenery.of(sim)
            thrower = None if self.thrower is None else self.thrower.position
            self._frames.append(Snapshot.of(sim, self._scenery, thrower))
        elif self.render_mode == "rgb_array_list":
            self._frames.append(self._draw())
        else:
            self._get_renderer().show(self._draw())

    def _draw(self) -> np.ndarray:
        """A frame of the scene now, with the thrower, the camera framing the current throw."""
        renderer = self._get_renderer()
        if self.thrower is not None:
            renderer.film(self.sim, self.thrower.position, self._flight)
        return renderer.draw(self.sim)

    def _renderer_show(self) -> None:
        self._get_renderer().show(self._draw())

    def render(self) -> np.ndarray | list[np.ndarray] | list[Snapshot] | None:
        """``rgb_array``: the current frame (H, W, 3) uint8; ``rgb_array_list``: the frames since
        the last render or reset; ``replay_list``: the :class:`~netgym.view.replay.Snapshot` of each of
        those instants; ``human``: shows the current frame, returns None. Frames show the current
        thrower and follow the throw being simulated."""
        if self.render_mode is None:
            gym.logger.warn("render() called without a render_mode; pass render_mode to make()")
            return None
        if self.render_mode == "rgb_array":
            return self._draw()
        if self.render_mode in ("rgb_array_list", "replay_list"):
            frames, self._frames = self._frames, []
            return frames
        self._renderer_show()
        return None

    def close(self) -> None:
        """Release the window, if any; safe to call more than once."""
        if self._renderer is not None:
            self._renderer.close()
            self._renderer = None

    def __getstate__(self) -> dict:
        state = self.__dict__.copy()
        state["_renderer"] = None  # windows and fonts do not travel; a new one opens on demand
        return state
