"""Wrappers for NetCatch environments."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import Any

import gymnasium as gym
import numpy as np

from netgym.errors import InvalidArgumentError
from netgym.view.video import EpisodeFilm

VIDEO_MODES = {"mp4": "rgb_array_list", "gif": "rgb_array_list", "html": "replay_list"}  # format: render mode
STATE_KEY = "state"
"""The key of a training-only Dict observation's privileged part (:class:`ThrowerView` with
``with_state``, :class:`HiddenState`): critics read it; a policy acts on the other key alone."""
ACTING_KEYS = ("pixels", "observation")
"""The keys of what a policy acts on in those Dicts: an image, or the env's own observation."""


def acting_key(observation_space: gym.spaces.Dict) -> str:
    """The key of the part of such a Dict observation that the policy acts on."""
    found = [key for key in ACTING_KEYS if key in observation_space.spaces]
    if len(found) != 1 or STATE_KEY not in observation_space.spaces:
        raise InvalidArgumentError(f"an asymmetric actor-critic needs a Dict of {STATE_KEY!r} and one of "
                                   f"{ACTING_KEYS}, not {observation_space}")
    return found[0]


class RecordEpisodeVideo(gym.Wrapper):
    """Write a video of every episode ``episode_trigger(episode_index)`` selects (default: all),
    with every frame of every throw: NetCatch's ``rgb_array_list`` frames, ``1 / render_fps``
    simulated seconds apart, so the video plays at the simulation's pace, each captioned with
    its throw and outcome (:class:`~netgym.view.video.EpisodeFilm`).

    Gymnasium's ``RecordVideo`` keeps one frame per step, and a NetCatch step is a whole throw;
    this wrapper keeps them all. Videos go to ``video_folder/{name_prefix}-episode-{i}.mp4``
    (``video_format="gif"`` for GIFs, ``"html"`` for a 3D page you can turn), written when the
    episode ends.

    :param env: an env made with ``render_mode="rgb_array_list"`` (``"replay_list"`` for ``html``).
    """

    def __init__(self, env: gym.Env, video_folder: str | Path, episode_trigger: Callable[[int], bool] | None = None,
                 name_prefix: str = "netcatch", video_format: str = "mp4") -> None:
        super().__init__(env)
        if video_format not in VIDEO_MODES:
            raise InvalidArgumentError(f"video_format = {video_format!r}; allowed: {list(VIDEO_MODES)}")
        if env.render_mode != VIDEO_MODES[video_format]:
            raise InvalidArgumentError(f"RecordEpisodeVideo(video_format={video_format!r}) needs "
                                       f"render_mode={VIDEO_MODES[video_format]!r}, got {env.render_mode!r}")
        self.video_folder = Path(video_folder)
        self.episode_trigger = episode_trigger or (lambda episode: True)
        self.name_prefix, self.video_format = name_prefix, video_format
        self.episode = -1
        self.written: list[Path] = []
        self._film: EpisodeFilm | None = None

    def reset(self, **kwargs: Any) -> tuple[Any, dict]:
        """Reset; start collecting frames if this episode is to be recorded."""
        obs, info = self.env.reset(**kwargs)
        self.episode += 1
        frames = self.env.render()  # the reset frame, handed out (and dropped when not recorded)
        self._film = None
        if self.episode_trigger(self.episode):
            self._film = EpisodeFilm(self.env.unwrapped.balls_per_episode, self.env.metadata["render_fps"])
            self._film.start(frames)
        return obs, info

    def step(self, action: Any) -> tuple[Any, float, bool, bool, dict]:
        """Step; keep the throw's frames; write the video when the episode ends."""
        obs, reward, terminated, truncated, info = self.env.step(action)
        frames = self.env.render()
        if self._film is not None:
            self._film.add_throw(frames, info)
            if terminated or truncated:
                path = self.video_folder / f"{self.name_prefix}-episode-{self.episode}.{self.video_format}"
                self.written.append(self._film.write(path))
                self._film = None
        return obs, reward, terminated, truncated, info


class ThrowerView(gym.ObservationWrapper):
    """Pixel observations: what the thrower sees, a ``size`` x ``size`` RGB image from the
    release point towards the opening's centre (the net, the balls caught so far, the ground).
    The vector observation is dropped; ``info`` is unchanged.

    :param env: a NetCatch env (any render mode).
    :param size: image side in pixels.
    :param fov: vertical field of view (degrees).
    :param with_state: also keep the vector observation: each observation is then a Dict of the
        image (``"pixels"``) and the vector (``"state"``), for training methods whose critic
        reads the state while the policy acts on the image alone (:mod:`agents.asymmetric`).
    """

    def __init__(self, env: gym.Env, size: int = 84, fov: float = 60.0, with_state: bool = False) -> None:
        super().__init__(env)
        if not isinstance(size, int) or not 16 <= size <= 512:
            raise InvalidArgumentError(f"size = {size!r}; allowed: an integer in [16, 512]")
        if not isinstance(with_state, (bool, np.bool_)):
            raise InvalidArgumentError(f"with_state = {with_state!r}; allowed: True or False")
        from netgym.view.render import Renderer

        self.fov, self.with_state = fov, bool(with_state)
        self.renderer = Renderer(env.unwrapped.sim, size, size, supersample=1)
        image = gym.spaces.Box(0, 255, (size, size, 3), np.uint8)
        self.observation_space = gym.spaces.Dict({"pixels": image, STATE_KEY: env.observation_space}) if with_state \
            else image

    def observation(self, observation: np.ndarray) -> np.ndarray | dict[str, np.ndarray]:
        """The image from the current thrower's release point (with the vector ``observation``
        beside it under ``with_state``)."""
        env = self.env.unwrapped
        if self.renderer.camera.eye.tolist() != env.thrower.position.tolist():
            self.renderer.look_from(env.thrower.position, env.sim.opening.centre, self.fov)
        image = self.renderer.draw(env.sim)
        return {"pixels": image, STATE_KEY: observation} if self.with_state else image


class HiddenState(gym.Wrapper, gym.utils.RecordConstructorArgs):
    """Beside each observation, what the episode hides from it: each observation becomes a Dict of
    ``"observation"`` (as it was) and ``"state"`` (the observation followed by the episode's wind,
    x and y over the wind range's top speed, and its randomised scene fields, each mapped from its
    range to [-1, 1]: ``info["wind"]``, ``info["scene_draws"]``). For training critics on what the
    policy cannot see (:mod:`agents.asymmetric`); the policy acts on the ``"observation"`` alone.

    :param env: a NetCatch env with vector observations.
    """

    def __init__(self, env: gym.Env) -> None:
        gym.utils.RecordConstructorArgs.__init__(self)
        gym.Wrapper.__init__(self, env)
        if not isinstance(env.observation_space, gym.spaces.Box) or len(env.observation_space.shape) != 1:
            raise InvalidArgumentError(f"HiddenState wraps vector observations, not {env.observation_space}")
        base = env.unwrapped
        self._wind_scale = 0.0 if base.wind_range is None else base.wind_range.high
        self._ranges = () if base.randomize is None else base.randomize.ranges
        hidden = (2 if base.wind_range is not None else 0) + len(self._ranges)
        bounds = env.observation_space
        state = gym.spaces.Box(np.concatenate([bounds.low, -np.ones(hidden)]).astype(np.float32),
                               np.concatenate([bounds.high, np.ones(hidden)]).astype(np.float32), dtype=np.float32)
        self.observation_space = gym.spaces.Dict({"observation": env.observation_space, STATE_KEY: state})

    def hidden(self, info: dict[str, Any]) -> np.ndarray:
        """The scaled hidden values of the episode ``info`` reports."""
        wind = np.asarray(info["wind"][:2]) / self._wind_scale if self._wind_scale > 0 else np.zeros(0)
        draws = [2.0 * (info["scene_draws"][field] - low) / (high - low) - 1.0 if high > low else 0.0
                 for field, low, high in self._ranges]
        return np.concatenate([wind, draws])

    def _both(self, observation: np.ndarray, info: dict[str, Any]) -> dict[str, np.ndarray]:
        state = np.concatenate([observation, self.hidden(info)]).astype(np.float32)
        return {"observation": observation, STATE_KEY: state}

    def reset(self, **kwargs: Any) -> tuple[dict[str, np.ndarray], dict]:
        """The env's reset, with the hidden state beside the observation."""
        observation, info = self.env.reset(**kwargs)
        return self._both(observation, info), info

    def step(self, action: Any) -> tuple[dict[str, np.ndarray], float, bool, bool, dict]:
        """The env's step, with the hidden state beside the observation."""
        observation, reward, terminated, truncated, info = self.env.step(action)
        return self._both(observation, info), reward, terminated, truncated, info


def thrower_view_env(size: int = 84, with_state: bool = False, **kwargs: Any) -> gym.Env:
    """A NetCatch env (``kwargs``) with :class:`ThrowerView` pixel observations.

    :param size: image side in pixels.
    :param with_state: True: each observation is a Dict of the image (``"pixels"``) and the
        vector observation (``"state"``), for training critics on the state while the policy acts
        on the image alone (``agents/asymmetric.py``).
    """
    from netgym.envs import NetCatchEnv

    return ThrowerView(NetCatchEnv(**kwargs), size, with_state=with_state)
