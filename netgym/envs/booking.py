"""NetCatchEnv's booking of a finished throw, term by term: its reward (the shaping of a miss
in ``shaped`` mode), the feedback the next observation carries, the episode's end, the next
thrower, and the step's ``info``."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from netgym.envs.variation import throw_feedback
from netgym.launch import sample_thrower
from netgym.physics.pause import Pause
from netgym.physics.throw import FreeFlight, ThrowResult

SHAPED_SCALE = 1.0   # m: a miss whose path passes this far from the opening earns 0.5 / e
SHAPED_MAX = 0.5     # largest reward of a miss in shaped mode


class ThrowBooking:
    """The booking methods of :class:`~netgym.envs.NetCatchEnv` (a mixin over its ``sim``,
    ``scene``, ``thrower``, its counts of throws and captures, ``reward_mode``, ``feedback``,
    ``render_mode``, ``np_random`` and its observation)."""

    def after_throw(self, launch: np.ndarray, velocity: np.ndarray, result: ThrowResult, aimed: np.ndarray,
                    settled: Pause) -> tuple[np.ndarray, float, bool, bool, dict]:
        """Book a finished throw, term by term: :meth:`_reward` (with :meth:`_shaping` for a
        miss), :meth:`_feedback`, :meth:`_terminated`, :meth:`_next_thrower`, then the observation
        and :meth:`_info` (``aimed``: the velocity the action meant, before launch noise;
        ``settled``: the :class:`~netgym.physics.pause.Pause` after the throw)."""
        self._throws_done += 1
        self._caught += int(result.captured)
        reward = self._reward(launch, velocity, result.captured)
        self._feedback(launch, velocity, result.captured)
        terminated = self._terminated()
        self._next_thrower(terminated)
        info = self._info(launch, velocity, result, aimed, settled)
        if self.render_mode == "human":
            self._renderer_show()
        return self._observation(), reward, terminated, False, info

    def _reward(self, launch: np.ndarray, velocity: np.ndarray, captured: bool) -> float:
        """1 for a capture; else 0, or the shaping of a miss in ``shaped`` mode."""
        if captured:
            return 1.0
        return self._shaping(launch, velocity) if self.reward_mode == "shaped" else 0.0

    def _shaping(self, launch: np.ndarray, velocity: np.ndarray) -> float:
        """A miss's reward in ``shaped`` mode: SHAPED_MAX x exp(-d / SHAPED_SCALE), ``d`` the
        closest distance between the ball's free flight and the opening."""
        miss = FreeFlight.of(self.sim.model).miss_distance(self.sim.opening, launch, velocity,
                                                           self.sim.config.simulation.time_limit)
        return SHAPED_MAX * math.exp(-miss / SHAPED_SCALE)

    def _feedback(self, launch: np.ndarray, velocity: np.ndarray, captured: bool) -> None:
        """With ``feedback``, note the throw's outcome for the next observation."""
        if self.feedback:
            self._last_throw = throw_feedback(self.sim, launch, velocity, captured)

    def _terminated(self) -> bool:
        """The episode ends after ``balls_per_episode`` throws (``step`` refuses to go on)."""
        self._ended = self._throws_done >= self.balls_per_episode
        return self._ended

    def _next_thrower(self, terminated: bool) -> None:
        """Draw the next throw's thrower, unless the episode ended; no throw is in flight."""
        if not terminated:
            self.thrower = sample_thrower(self.scene.throw, self.sim.opening, self.np_random)
        self._flight = None

    def _info(self, launch: np.ndarray, velocity: np.ndarray, result: ThrowResult, aimed: np.ndarray,
              settled: Pause) -> dict[str, Any]:
        """The step's info (see NetCatchEnv's docstring): the throw's outcome and its work, the
        settling before it and after it (``settled``), the launch, the wind and the scene's draws."""
        settle_substeps = result.settle_substeps + settled.substeps
        settle_time = result.settle_time + settled.time
        return {"captured": result.captured, "reason": result.reason,
                "final_position": result.final_position, "sim_time": result.time,
                "substeps": settle_substeps + result.substeps, "throw_substeps": result.substeps,
                "settle_substeps": settle_substeps, "settle_time": settle_time,
                "launch_position": launch, "launch_velocity": velocity, "aimed_velocity": aimed,
                "wind": self.sim.model.wind.copy(), "scene_draws": dict(self._draws)}
