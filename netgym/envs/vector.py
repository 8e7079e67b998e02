"""NetCatchVectorEnv: many NetCatch-v0 environments stepped together.

Each sub-environment keeps its own simulator and decisions; the integration work of all the
throws in a step runs in one numba call, parallel across environments (``prange``). Results
are identical to the same number of :class:`NetCatchEnv` with the same seeds.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from gymnasium.vector import AutoresetMode, VectorEnv
from gymnasium.vector.utils import batch_space

from netgym.arguments import integer_argument
from netgym.envs.net_catch import NetCatchEnv
from netgym.errors import NetgymError
from netgym.physics.integration import Workspace
from netgym.physics.plans import drive


class NetCatchVectorEnv(VectorEnv):
    """``num_envs`` copies of :class:`NetCatchEnv`, stepped in one parallel call.

    ``autoreset_mode`` is ``SAME_STEP`` (the default here, what the SB3 adapter uses): when an
    episode ends, ``step`` returns the first observation of the next episode, and the last
    observation and info are in ``infos["final_obs"]`` and ``infos["final_info"]`` (masked by
    ``infos["_final_obs"]``); or ``NEXT_STEP`` (Gymnasium's default, which its vector wrappers such
    as ``NormalizeObservation`` expect): ``step`` returns the last observation, and the next
    ``step`` resets that sub-environment (ignoring its action; reward 0). Keyword arguments are those of :class:`NetCatchEnv`; ``render_mode`` is not supported.
    ``max_episode_steps`` truncates each episode after that many throws, as ``gym.make``'s
    ``TimeLimit`` does. A step that fails (a divergence in any sub-environment) leaves every
    sub-environment as it was before the step and raises the error, naming the sub-environment.
    """

    metadata = {"autoreset_mode": AutoresetMode.SAME_STEP, "render_modes": []}

    def __init__(self, num_envs: int = 1, max_episode_steps: int | None = None,
                 autoreset_mode: AutoresetMode | str = AutoresetMode.SAME_STEP, **kwargs: Any) -> None:
        num_envs = integer_argument(num_envs, "num_envs", 1)
        modes = {key: mode for mode in (AutoresetMode.SAME_STEP, AutoresetMode.NEXT_STEP)
                 for key in (mode, mode.value, mode.name.lower())}
        if autoreset_mode not in modes:
            raise ValueError(f"autoreset_mode = {autoreset_mode!r} is not one of 'same_step', 'next_step' "
                             f"(or a gymnasium.vector.AutoresetMode)")
        self.autoreset_mode = modes[autoreset_mode]
        self.metadata = {**self.metadata, "autoreset_mode": self.autoreset_mode}
        self._needs_reset = np.zeros(num_envs, dtype=bool)
        if max_episode_steps is not None:
            max_episode_steps = integer_argument(max_episode_steps, "max_episode_steps", 1)
        if kwargs.get("render_mode") is not None:
            raise ValueError("NetCatchVectorEnv does not render; use NetCatchEnv for render_mode")
        kwargs.pop("render_mode", None)
        self.max_episode_steps = max_episode_steps
        self._episode_steps = np.zeros(num_envs, dtype=np.int64)
        self.envs = [NetCatchEnv(**kwargs) for _ in range(num_envs)]
        self.num_envs = num_envs
        self.single_observation_space = self.envs[0].observation_space
        self.single_action_space = self.envs[0].action_space
        self.observation_space = batch_space(self.single_observation_space, num_envs)
        self.action_space = batch_space(self.single_action_space, num_envs)
        self._workspace = Workspace()

    def reset(self, *, seed: int | list[int | None] | None = None,
              options: dict[str, Any] | None = None) -> tuple[np.ndarray, dict[str, Any]]:
        """Reset every environment; an int ``seed`` seeds environment ``i`` with ``seed + i``."""
        if seed is None or isinstance(seed, int):
            seeds = [None if seed is None else seed + i for i in range(self.num_envs)]
        else:
            seeds = list(seed)
            if len(seeds) != self.num_envs:
                raise ValueError(f"seed has {len(seeds)} entries; expected num_envs = {self.num_envs}")
        observations, infos = [], {}
        for i, (env, s) in enumerate(zip(self.envs, seeds)):
            obs, info = env.reset(seed=s, options=options)
            self._episode_steps[i] = 0
            self._needs_reset[i] = False
            observations.append(obs)
            infos = self._add_info(infos, info, i)
        return np.stack(observations), infos

    def step(self, actions: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, dict[str, Any]]:
        """One throw in every environment; the simulation of all throws runs in parallel."""
        actions = np.asarray(actions)
        if actions.shape != self.action_space.shape:
            raise ValueError(f"actions must have shape {self.action_space.shape}, got {actions.shape}")
        throwing = [i for i in range(self.num_envs) if not self._needs_reset[i]]
        launches, velocities, plans = {}, {}, []
        for i in throwing:
            env = self.envs[i]
            velocities[i] = env.action_velocity(actions[i])
            assert env.thrower is not None
            launches[i] = env.thrower.position
            plans.append(env.sim.throw_plan(launches[i], velocities[i], fast=env.fast))
        checkpoints = [self.envs[i].sim.checkpoint() for i in throwing]
        try:
            results = dict(zip(throwing, drive([self.envs[i].sim for i in throwing], plans, self._workspace,
                                               names=[f"sub-environment {i}" for i in throwing])))
        except NetgymError as error:
            for i, checkpoint in zip(throwing, checkpoints):
                self.envs[i].sim.restore(checkpoint)
            raise type(error)(f"{error} (every sub-environment was left as before this step)") from error
        observations, rewards = [], np.zeros(self.num_envs)
        terminated = np.zeros(self.num_envs, dtype=bool)
        truncated = np.zeros(self.num_envs, dtype=bool)
        infos: dict[str, Any] = {}
        for i, env in enumerate(self.envs):
            if i not in results:  # NEXT_STEP: the episode ended last step; this step starts the next one
                obs, info = env.reset()
                self._episode_steps[i], self._needs_reset[i] = 0, False
                observations.append(obs)
                infos = self._add_info(infos, info, i)
                continue
            self._episode_steps[i] += 1
            obs, rewards[i], terminated[i], truncated[i], info = env.after_throw(launches[i], velocities[i], results[i])
            if self.max_episode_steps is not None and not terminated[i]:
                truncated[i] = self._episode_steps[i] >= self.max_episode_steps
            if (terminated[i] or truncated[i]) and self.autoreset_mode == AutoresetMode.NEXT_STEP:
                self._needs_reset[i] = True
            elif terminated[i] or truncated[i]:
                infos = self._add_info(infos, {"final_obs": obs, "final_info": info}, i)
                obs, _ = env.reset()
                self._episode_steps[i] = 0
            observations.append(obs)
            infos = self._add_info(infos, info, i)
        return np.stack(observations), rewards, terminated, truncated, infos

    def close_extras(self, **kwargs: Any) -> None:
        """Close the sub-environments."""
        for env in self.envs:
            env.close()
