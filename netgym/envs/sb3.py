"""Stable-Baselines3 adapter: NetCatchVectorEnv presented as an SB3 ``VecEnv``.

Requires the ``train`` extra (stable-baselines3). Wrap it in ``VecMonitor`` for episode
statistics::

    from stable_baselines3 import PPO
    from stable_baselines3.common.vec_env import VecMonitor
    from netgym.envs.sb3 import NetCatchSB3VecEnv

    env = VecMonitor(NetCatchSB3VecEnv(num_envs=8))
    PPO("MlpPolicy", env).learn(10_000)
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import gymnasium as gym
import numpy as np
from stable_baselines3.common.vec_env.base_vec_env import VecEnv, VecEnvIndices, VecEnvStepReturn

from netgym.envs.vector import NetCatchVectorEnv


class NetCatchSB3VecEnv(VecEnv):
    """SB3 ``VecEnv`` over :class:`NetCatchVectorEnv` (all throws of a step simulated in one
    parallel call). Keyword arguments are those of :class:`netgym.envs.NetCatchEnv`.

    :param num_envs: number of environments.
    """

    def __init__(self, num_envs: int = 8, **kwargs: Any) -> None:
        self.vector = NetCatchVectorEnv(num_envs=num_envs, **kwargs)
        super().__init__(num_envs, self.vector.single_observation_space, self.vector.single_action_space)
        self._actions: np.ndarray | None = None

    @property
    def envs(self) -> list[gym.Env]:
        """The sub-environments."""
        return self.vector.envs

    def reset(self) -> np.ndarray:
        """Reset all environments, with the seeds and options set by ``seed()``/``set_options()``."""
        observations = []
        for i, env in enumerate(self.envs):
            options = {"options": self._options[i]} if self._options[i] else {}
            obs, self.reset_infos[i] = env.reset(seed=self._seeds[i], **options)
            observations.append(obs)
        self._reset_seeds()
        self._reset_options()
        return np.stack(observations)

    def step_async(self, actions: np.ndarray) -> None:
        """Remember the actions of the next step."""
        self._actions = np.asarray(actions, dtype=np.float32).reshape(self.num_envs, -1)

    def step_wait(self) -> VecEnvStepReturn:
        """Throw in every environment; finished episodes restart at once (SB3 convention)."""
        assert self._actions is not None, "step_async() must come before step_wait()"
        obs, rewards, terminated, truncated, infos = self.vector.step(self._actions)
        dones = terminated | truncated
        out_infos: list[dict[str, Any]] = []
        for i in range(self.num_envs):
            info = {key: value[i] for key, value in infos.items()
                    if not key.startswith("_") and key not in ("final_obs", "final_info") and infos[f"_{key}"][i]}
            info["TimeLimit.truncated"] = bool(truncated[i] and not terminated[i])
            if dones[i]:
                info["terminal_observation"] = infos["final_obs"][i]
            out_infos.append(info)
        return obs, rewards.astype(np.float32), dones, out_infos

    def close(self) -> None:
        """Close the environments."""
        self.vector.close()

    def get_attr(self, attr_name: str, indices: VecEnvIndices = None) -> list[Any]:
        """An attribute of each selected environment."""
        return [getattr(env, attr_name) for env in self._targets(indices)]

    def set_attr(self, attr_name: str, value: Any, indices: VecEnvIndices = None) -> None:
        """Set an attribute of each selected environment."""
        for env in self._targets(indices):
            setattr(env, attr_name, value)

    def env_method(self, method_name: str, *method_args: Any, indices: VecEnvIndices = None,
                   **method_kwargs: Any) -> list[Any]:
        """Call a method of each selected environment."""
        return [getattr(env, method_name)(*method_args, **method_kwargs) for env in self._targets(indices)]

    def env_is_wrapped(self, wrapper_class: type[gym.Wrapper], indices: VecEnvIndices = None) -> list[bool]:
        """Sub-environments are never wrapped."""
        return [False for _ in self._targets(indices)]

    def get_images(self) -> Sequence[np.ndarray | None]:
        """The vector environment does not render."""
        return [None for _ in self.envs]

    def _targets(self, indices: VecEnvIndices) -> list[gym.Env]:
        return [self.envs[i] for i in self._get_indices(indices)]
