"""NetCatch-v0: throw balls into a goal net."""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path
from typing import Any

import gymnasium as gym
import numpy as np
from gymnasium import spaces

from netgym.arguments import is_integer
from netgym.config import SceneConfig, load_scene
from netgym.errors import EpisodeEndedError, InvalidArgumentError
from netgym.envs.booking import ThrowBooking
from netgym.envs.observation import ObservationIndex
from netgym.envs.rendering import EnvRendering
from netgym.envs.reset_options import checked_reset_options
from netgym.envs.variation import FEEDBACK_LIMIT, FEEDBACK_SIZE, LaunchNoise, SceneRanges, WindRange
from netgym.launch import Thrower, action_to_launch, launch_velocity, sample_thrower
from netgym.physics.film import Film, FrameClock
from netgym.physics.net_family import NetFamily, family_of
from netgym.physics.simulator import Simulator
from netgym.physics.pause import Pause, pause
from netgym.physics.watchdog import Watchdog
from netgym.physics.throw import throw
from netgym.view.replay import Scenery, Snapshot

REWARD_MODES = ("sparse", "shaped")
FILMED_MODES = ("human", "rgb_array_list", "replay_list")   # render modes that take every frame of a throw


def _observation_space(scene: SceneConfig, centre: np.ndarray, floor: float, feedback: bool) -> spaces.Box:
    """The observation bounds of ``scene`` (opening ``centre``, lowest net point ``floor``),
    with the feedback entries when ``feedback``."""
    t, cz = scene.throw, float(centre[2])
    top = scene.net.upper[2] + scene.ball.radius - cz
    low = [t.distance[0], t.height[0] - cz, -1, -1, 0, 0, -cz]
    high = [t.distance[1], t.height[1] - cz, 1, 1, 1, 1, max(top, floor - cz)]
    if feedback:
        low += [0, -FEEDBACK_LIMIT, -FEEDBACK_LIMIT, 0]
        high += [1, FEEDBACK_LIMIT, FEEDBACK_LIMIT, FEEDBACK_LIMIT]
    return spaces.Box(np.array(low, dtype=np.float32), np.array(high, dtype=np.float32), dtype=np.float32)


def _check_arguments(render_modes: list[str], render_mode: str | None, reward_mode: str, balls_per_episode: Any,
                     flags: dict[str, Any]) -> None:
    """Refuse a ``render_mode`` not among ``render_modes``, a ``reward_mode`` not among
    :data:`REWARD_MODES`, a ``balls_per_episode`` outside [1, 50], and ``flags`` (by name)
    that are not True or False."""
    if render_mode is not None and render_mode not in render_modes:
        raise InvalidArgumentError(f"render_mode = {render_mode!r} is not one of {render_modes}")
    if reward_mode not in REWARD_MODES:
        raise InvalidArgumentError(f"reward_mode = {reward_mode!r} is not one of {list(REWARD_MODES)}")
    if not is_integer(balls_per_episode) or not 1 <= balls_per_episode <= 50:
        raise InvalidArgumentError(f"balls_per_episode = {balls_per_episode!r}; allowed: an integer in [1, 50]")
    for name, flag in flags.items():
        if not isinstance(flag, (bool, np.bool_)):
            raise InvalidArgumentError(f"{name} = {flag!r}; allowed: True or False")


def _scene_changes(overrides: dict[str, Any] | None, integrator: str | None, dt: float | None,
                   capture_rule: str | None, contact_model: str | None) -> dict[str, Any]:
    """``overrides`` and the scene fields that ``make``'s own arguments set, those given."""
    changes = dict(overrides or {})
    for dotted, value in (("simulation.integrator", integrator), ("simulation.dt", dt),
                          ("capture_rule", capture_rule), ("simulation.contact_model", contact_model)):
        if value is not None:
            changes[dotted] = value
    return changes


class NetCatchEnv(ThrowBooking, EnvRendering, gym.Env[np.ndarray, np.ndarray]):
    """Throw balls so that a mass-spring goal net catches them.

    A thrower stands at a random place around the net (default scene ``basket``: an open-top
    box net, 2 x 2 m opening at 3 m). Each step is one throw: the agent chooses the
    launch speed, elevation and azimuth of a ball, and the simulator runs the throw until its
    outcome is decided. An episode is a sequence of throws into the same net; under the ``held``
    capture rule (the basket's) caught balls stay in it, so later throws meet a loaded, deformed
    net and other balls; under ``line`` (the goal's) a goal is taken out once scored.

    ## Action space

    Three numbers in [-1, 1] (float32), each mapped linearly onto its range in the scene's
    ``[throw]`` table (values outside [-1, 1] are clipped): the launch speed, the elevation above
    the horizon and the azimuth offset from the direction to the opening's centre
    (:data:`~netgym.launch.LAUNCH_ENTRIES`).

    ## Observation space

    Numbers (float32) on the thrower, the balls caught and left and the pile in the net, and with
    ``feedback=True`` on the previous throw: :class:`~netgym.envs.ObservationIndex` (also
    ``env.observation_structure``) names each position and says what it is.

    ## Rewards

    ``sparse`` (default): +1 for a captured ball, 0 otherwise. ``shaped``: a miss also earns
    ``0.5 * exp(-d / 1 m)``, where ``d`` is the closest distance between the ball's free flight
    (the launch parabola; through the air and wind when the scene has air) and the opening
    rectangle (bounded in [0, 0.5], so a capture is always better).

    ## Starting state

    The net at rest under gravity without balls; the thrower drawn uniformly from the scene's
    distance, bearing and height ranges with ``np_random``. Each throw draws a new thrower.
    With ``wind``, the episode's wind is drawn too (never observed: ``info["wind"]`` reports it).

    ## Episode end

    Terminated after ``balls_per_episode`` throws. Never truncated. ``step`` on an ended episode
    raises :class:`~netgym.errors.EpisodeEndedError` (no reward is ever paid beyond the episode).

    ## Info

    ``captured`` (bool, by the scene's ``capture_rule``), ``reason`` (how the outcome was
    decided, each reason of one outcome: a miss ``"flies_away"``, the ball left the net's
    surroundings for good, ``"at_rest"`` outside the net, ``"cannot_reach_opening"``, no energy
    left to get it in, ``"out_of_play"`` under ``line``, ``"time_limit"``; caught
    ``"at_rest_in_net"``, ``"cannot_leave"``, no energy left to get it back out,
    ``"crossed_line"`` under ``line``, ``"time_limit_in_net"``), ``final_position`` of the ball,
    ``sim_time`` (simulated seconds of the throw), ``substeps`` (every integration substep the
    step took), split into ``throw_substeps`` and ``settle_substeps`` (bringing the net and the
    balls in it to rest after this throw, for the next one: the pause between throws, none after
    an episode's last throw; ``settle_time`` simulated seconds), ``launch_position`` and
    ``launch_velocity``.

    ## Arguments

    | argument | default | meaning |
    |---|---|---|
    | ``scene`` | ``"basket"`` | built-in scene name (``"basket"``, ``"goal"``), TOML path or :class:`SceneConfig` |
    | ``integrator`` | scene's | ``explicit_euler``, ``symplectic_euler``, ``rk4``, ``implicit_euler``, ``imex_euler`` |
    | ``dt`` | scene's | integration step (s) |
    | ``balls_per_episode`` | 3 | throws per episode |
    | ``reward_mode`` | ``"sparse"`` | ``"sparse"`` or ``"shaped"`` |
    | ``render_mode`` | None | ``"human"``, ``"rgb_array"``, ``"rgb_array_list"``, ``"replay_list"`` (3D positions instead of pixels: :mod:`netgym.view.replay`) |
    | ``fast`` | True | decide throws early and skip what does not matter (False: full simulation to the time limit) |
    | ``overrides`` | None | more scene fields, e.g. ``{"simulation.time_limit": 4.0}`` |
    | ``render_settling`` | False | ``rgb_array_list``/``human``: also film the net settling between throws |
    | ``wind`` | None | ``(low, high)`` m/s: a hidden horizontal wind drawn per episode (speed uniform, any direction; needs ``air.density`` > 0), in ``info["wind"]`` |
    | ``launch_noise`` | None | ``(speed, elevation, azimuth)`` standard deviations (m/s, degrees) of Gaussian noise on each release; ``info["aimed_velocity"]`` is the intended one |
    | ``feedback`` | False | append the previous throw's outcome and where it passed the opening to the observation |
    | ``randomize`` | None | domain randomisation: ``{scene field: (low, high)}`` drawn uniformly per episode (``info["scene_draws"]``; fields that change the spaces are refused at reset) |
    | ``contact_model`` | scene's | ``"impulse"`` or ``"compliant"`` (Hunt-Crossley contact forces inside the integrator, which converge at its order; not with ``implicit_euler``) |
    | ``capture_rule`` | scene's | ``"held"`` (basket: in the net at rest or at the time limit; caught balls stay) or ``"line"`` (goal: the whole ball crossed the mouth inside the frame; wholly over the line beside it, out of play; the ball is then taken out) |

    ## Registered ids

    Every id in :data:`netgym.ENVIRONMENTS` (the defaults above, or a variant's arguments); each
    has its card in the docs, generated from this docstring, the id's registration and the env
    it makes.

    ## Version History

    - v0 (netgym 0.1, not yet released; changes made within v0 before the first release):
      the default integrator became IMEX Euler at 2 ms (was symplectic Euler at 0.5 ms; the
      shipped PPO model was trained on the old default and scores the same on the new one);
      resting contacts hold static friction (balls no longer creep on the settled net); the
      goal scene counts a goal by the ``line`` rule, and takes the ball out once it is scored;
      ``info`` books the settling pause; the basket's pause relaxes the net with four times
      its inertia (``simulation.settle_inertia``): the same outcomes, the balls at rest
      elsewhere (BENCHMARKS section 9).
      Options added without changing v0's dynamics: ``reset(options=...)``, ``render_settling``,
      and the variation arguments ``wind``, ``launch_noise``, ``feedback`` (off by default).
      ``info["reason"]`` labels one outcome each: a caught ball decided at rest, out of energy
      or at the time limit is ``"at_rest_in_net"``, ``"cannot_leave"`` or
      ``"time_limit_in_net"`` (it shared ``"at_rest"``, ``"cannot_reach_opening"`` and
      ``"time_limit"`` with misses); the dynamics are unchanged.
    - ``NetCatchWindy-v0``, ``NetCatchNoisy-v0``, ``NetCatchRandomized-v0`` and
      ``NetCatchPixels-v0``: new in netgym 0.1.
    - ``NetCatchRandomized-v1`` (netgym 0.1): v0 drew only what changes how the net answers, so
      an oracle blind to the draws caught every throw and it separated no algorithms.
      v1 also draws the ball's drag coefficient (0-1, in air of 1.2 kg/m^3) beside its mass, so
      the flight, and the aim, change per episode; 5 throws with the previous throw's feedback,
      so that an agent can identify them. v0 stays registered (``gymnasium.make`` says that v1
      exists).
    """

    metadata = {"render_modes": ["human", "rgb_array", "rgb_array_list", "replay_list"], "render_fps": 30}

    def __init__(self, scene: str | Path | SceneConfig = "basket", integrator: str | None = None,
                 dt: float | None = None, balls_per_episode: int = 3, reward_mode: str = "sparse",
                 render_mode: str | None = None, fast: bool = True,
                 overrides: dict[str, Any] | None = None, capture_rule: str | None = None,
                 render_settling: bool = False, wind: tuple[float, float] | None = None,
                 launch_noise: tuple[float, float, float] | None = None, feedback: bool = False,
                 randomize: dict[str, tuple[float, float]] | None = None, contact_model: str | None = None) -> None:
        _check_arguments(self.metadata["render_modes"], render_mode, reward_mode, balls_per_episode,
                         {"fast": fast, "render_settling": render_settling, "feedback": feedback})
        config = scene if isinstance(scene, SceneConfig) else load_scene(scene)
        changes = _scene_changes(overrides, integrator, dt, capture_rule, contact_model)
        self.wind_range = None if wind is None else WindRange.parse(wind)
        self.launch_noise = None if launch_noise is None else LaunchNoise.parse(launch_noise)
        self.feedback = bool(feedback)
        self.sim = Simulator(config.replace(changes) if changes else config)
        if self.wind_range is not None and self.sim.model.ball_drag == 0.0:
            raise InvalidArgumentError("wind needs air: the scene's air.density is 0 "
                                       "(pass overrides={'air.density': 1.2})")
        self.scene = self.sim.config
        self._base_scene = self.scene
        self.randomize = None if randomize is None else SceneRanges.parse(randomize, self.scene)
        self._overrides: dict[str, Any] = {}
        self._draws: dict[str, float] = {}
        self.balls_per_episode = int(balls_per_episode)
        self.reward_mode = reward_mode
        self.render_mode = render_mode
        self.fast = bool(fast)
        self.render_settling = bool(render_settling)
        self._film = (Film(FrameClock(1.0 / self.metadata["render_fps"]), self._record_frame, self.render_settling)
                      if render_mode in FILMED_MODES else None)
        self._centre = self.sim.opening.centre
        self._floor = float(self.sim.state.x[:, 2].min())
        self.action_space = spaces.Box(-1.0, 1.0, (3,), np.float32)
        self.observation_space = _observation_space(self.scene, self._centre, self._floor, self.feedback)
        self.observation_structure = {index.name.lower(): int(index) for index in ObservationIndex
                                      if index < self.observation_space.shape[0]}
        self._last_throw = np.zeros(FEEDBACK_SIZE)
        self.thrower: Thrower | None = None
        self._ended = False
        self._throws_done = 0
        self._caught = 0
        self._renderer = None
        self._scenery: Scenery | None = None
        self._flight: np.ndarray | None = None   # launch velocity of the throw being simulated
        self._frames: list[np.ndarray] | list[Snapshot] = []

    # ------------------------------------------------------------------ spaces
    def _observation(self) -> np.ndarray:
        assert self.thrower is not None
        cz = float(self._centre[2])
        balls = self.sim.ball_positions
        pile = float(balls[:, 2].max()) if len(balls) else self._floor
        bearing = math.radians(self.thrower.bearing)
        obs = np.empty(self.observation_space.shape[0], dtype=np.float32)
        obs[ObservationIndex.DISTANCE] = self.thrower.distance
        obs[ObservationIndex.HEIGHT] = self.thrower.height - cz
        obs[ObservationIndex.BEARING_COS] = math.cos(bearing)
        obs[ObservationIndex.BEARING_SIN] = math.sin(bearing)
        obs[ObservationIndex.CAUGHT] = self._caught / self.balls_per_episode
        obs[ObservationIndex.THROWS_LEFT] = (self.balls_per_episode - self._throws_done) / self.balls_per_episode
        obs[ObservationIndex.PILE_HEIGHT] = pile - cz
        if self.feedback:
            obs[ObservationIndex.LAST_CAUGHT:] = self._last_throw
        return np.clip(obs, self.observation_space.low, self.observation_space.high)

    # ------------------------------------------------------------------ gym API
    def reset(self, *, seed: int | None = None, options: dict[str, Any] | None = None) -> tuple[np.ndarray, dict]:
        """Start an episode: the net at rest and empty, a new thrower.

        ``options`` (all optional):

        - ``"overrides"``: scene fields for this and the following episodes, as in ``make``'s
          ``overrides`` (e.g. ``{"ball.mass": 0.5, "contact.ball_net.friction": 0.5}``), applied to
          the scene the env was made with. Fields that change the spaces (the ``throw`` ranges)
          are refused: make a new env for those.
        - ``"thrower"``: the first thrower of the episode, a dict with any of ``distance`` (m),
          ``bearing`` (degrees), ``height`` (m) inside the scene's ``throw`` ranges; what is left
          out is drawn as usual.

        Bad options raise a ValueError (or ConfigError) and leave the env as it was.
        """
        options = checked_reset_options(options, self.scene.throw)
        overrides = dict(options.get("overrides", self._overrides))
        scene = self._base_scene.replace(overrides) if overrides else self._base_scene  # bad overrides fail here
        super().reset(seed=seed)
        self._draws = {} if self.randomize is None else self.randomize.draw(self.np_random)
        drawn: dict[str, Any] = dict(self._draws)
        if self.wind_range is not None:
            drawn["air.wind"] = self.wind_range.draw(self.np_random).tolist()
        family = None if self.randomize is None else family_of(scene, self.randomize.ranges)
        self._set_scene(scene.replace(drawn) if drawn else scene, family)
        self._overrides = overrides
        self.sim.reset()
        self._last_throw = np.zeros(FEEDBACK_SIZE)
        self._throws_done = 0
        self._caught = 0
        self._ended = False
        self.thrower = sample_thrower(self.scene.throw, self.sim.opening, self.np_random)
        if "thrower" in options:
            self.thrower = dataclasses.replace(self.thrower, **options["thrower"])
        self._frames = []
        self._flight = None
        if self._film is not None:
            self._film.clock.restart(self.sim.state.time)
            self._film(self.sim)
        return self._observation(), {"wind": self.sim.model.wind.copy(), "scene_draws": dict(self._draws)}

    def _set_scene(self, config: SceneConfig, family: NetFamily | None = None) -> None:
        """Simulate ``config`` from now on (a member of ``family``, nets drawn per episode, if
        given); refused (nothing changed) if the spaces would change."""
        if config == self.scene:
            return
        sim = Simulator(config, like=self.sim) if family is None else family.simulator(config, like=self.sim)
        centre, floor = sim.opening.centre, float(sim.state.x[:, 2].min())
        if _observation_space(config, centre, floor, self.feedback) != self.observation_space:
            raise InvalidArgumentError("these overrides change the observation space's bounds (the net's geometry "
                                       "or the ball radius); make a new env with them instead")
        self.sim, self.scene, self._centre, self._floor = sim, config, centre, floor
        self._scenery = None
        self.close()  # the renderer's camera and frames belong to the old scene

    def step(self, action: np.ndarray) -> tuple[np.ndarray, float, bool, bool, dict]:
        """Throw one ball with launch ``action`` and simulate until its outcome is decided."""
        if self.thrower is None:
            raise EpisodeEndedError("call reset() before step()")
        if self._ended:
            raise EpisodeEndedError(f"the episode ended after its {self.balls_per_episode} throws "
                                    f"(balls_per_episode); call reset() before step()")
        intended = self._intended_launch(action)
        aimed = launch_velocity(*intended, self.thrower)
        velocity = aimed if self.launch_noise is None else \
            launch_velocity(*self.launch_noise.apply(*intended, self.np_random), self.thrower)
        launch = self.thrower.position
        self._flight = velocity
        step = self._throws_done + 1
        watchdog = Watchdog(lambda: f"{self.spec.id if self.spec else type(self).__name__} step {step} (the throw from "
                                    f"{launch.tolist()} m at {velocity.tolist()} m/s, then the pause)")
        result = throw(self.sim, launch, velocity, fast=self.fast, film=self._film, observer=watchdog)
        settled = Pause()
        if self._throws_done + 1 < self.balls_per_episode:  # the net settles for the next throw (none after the last)
            settled = pause(self.sim, self._film, watchdog)
        return self.after_throw(launch, velocity, result, aimed, settled)

    def _intended_launch(self, action: np.ndarray) -> tuple[float, float, float]:
        """Validate an action; its (speed, elevation, azimuth offset), values clipped to [-1, 1]."""
        a = np.asarray(action)
        if a.dtype.kind not in "fiu":
            raise InvalidArgumentError(f"action must be an array of real numbers, got {a.dtype} values: {action!r}")
        a = a.astype(np.float64)
        if a.shape != (3,):
            raise InvalidArgumentError(f"action must have shape (3,), got {a.shape}")
        if not np.all(np.isfinite(a)):
            raise InvalidArgumentError(f"action must be finite, got {a.tolist()}")
        return action_to_launch(np.clip(a, -1.0, 1.0), self.scene.throw)
