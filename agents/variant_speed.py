"""Every registered id's speed as a user pays it: whole episodes, resets included, under the
ballistic oracle, random actions and the model shipped for the id (the models users train:
:data:`~agents.policies.SHIPPED_FOR_ID`), and PPO training's environment steps per second.

One process, one numba thread. The ids run interleaved, round after round, each round on
episode seeds of its own, so that a slow spell of a shared machine falls on all of them alike;
each id is compared with NetCatch-v0 under the same policy, as a ratio of throws per second
measured in the same run. Only ``reset`` and ``step`` are timed (not the policy choosing its
action), each once per call, so the tails (p99, max) are those a training loop meets. A call
during which numba compiled a kernel (a path the warm-up episode did not take, met first in a
timed one) is left out and counted: it times the compiler, once per machine, not the env.
"""

from __future__ import annotations

import cProfile
import pstats
import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import gymnasium as gym
import numba
import numpy as np
from numba.core import event
from tqdm import tqdm

import netgym
from agents.oracle import BallisticOracle
from agents.policies import policy_in_env, shipped_model
from netgym.bench.speed.speed_table import BASE_ID
from netgym.config import SceneConfig

SHIPPED = "shipped model"
POLICIES = ("oracle", "random", SHIPPED)
VECTOR_IDS = tuple(env_id for env_id in netgym.ENVIRONMENTS if env_id != "NetCatchPixels-v0")
"""The ids with a vector observation (the pixel id renders every step: a different workload)."""


class _Compilations(event.Listener):
    """How many numba compilations have started in this process since it was registered."""

    def __init__(self) -> None:
        self.count = 0

    def on_start(self, ev: event.Event) -> None:
        self.count += 1

    def on_end(self, ev: event.Event) -> None:
        pass


COMPILATIONS = _Compilations()
event.register("numba:compile", COMPILATIONS)


@dataclass(frozen=True)
class SpeedRow:
    """One id under one policy: ``throws`` steps of ``episodes`` episodes, their rate with the
    resets counted, p50/p99/max of a step and of a reset (ms), the capture rate, and the ratio
    of its throws per second to NetCatch-v0's under the same policy; ``left_out``: the calls
    left out because numba compiled during them."""

    env_id: str
    policy: str
    episodes: int
    throws: int
    throws_per_s: float
    step_ms: tuple[float, float, float]
    reset_ms: tuple[float, float, float]
    capture_rate: float
    ratio: float
    left_out: int = 0
    model: str = ""  # the shipped model's file, for that policy


def _chooser(policy: str, model: Any, scene: SceneConfig, seed: int) -> Callable[[np.ndarray, bool], np.ndarray]:
    """The action for an observation (the second argument: the first of its episode): the
    ballistic oracle of ``scene``, random actions, or the shipped ``model`` (its recurrent state
    or frame stack given back, as SB3's ``evaluate_policy`` does)."""
    if policy == "oracle":
        oracle = BallisticOracle(scene)
        return lambda obs, first: oracle.predict(obs)[0]
    if policy == "random":
        rng = np.random.default_rng(seed)
        return lambda obs, first: rng.uniform(-1.0, 1.0, 3).astype(np.float32)
    state: list[Any] = [None]

    def act(obs: np.ndarray, first: bool) -> np.ndarray:
        action, state[0] = model.predict(obs, state=None if first else state[0], episode_start=np.array([first]),
                                         deterministic=True)
        return action

    return act


class _Timing:
    """The timed calls of one (id, policy) pair over every round."""

    def __init__(self, env_id: str, policy: str) -> None:
        self.env_id, self.policy = env_id, policy
        self.env = gym.make(env_id, disable_env_checker=True)
        self.scene = self.env.unwrapped.scene   # as registered: the oracle is blind to each episode's draws
        self.model = policy_in_env(shipped_model(env_id), env_id)[1] if policy == SHIPPED else None
        self.steps: list[float] = []
        self.resets: list[float] = []
        self.caught = 0
        self.episodes = 0
        self.left_out = 0
        self.run_episodes(1, seed=10**6, timed=False)   # compiles, builds the net family; not timed

    def run_episodes(self, episodes: int, seed: int, timed: bool = True) -> None:
        """Run ``episodes`` episodes seeded ``seed, seed + 1, ...``, timing each call."""
        choose = _chooser(self.policy, self.model, self.scene, seed)
        for episode in range(episodes):
            compiled, start = COMPILATIONS.count, time.perf_counter()
            obs, _ = self.env.reset(seed=seed + episode)
            resets = [time.perf_counter() - start] if COMPILATIONS.count == compiled else []
            done, steps, caught, left_out, first = False, [], 0, 1 - len(resets), True
            while not done:
                action, first = choose(obs, first), False
                compiled, start = COMPILATIONS.count, time.perf_counter()
                obs, _, terminated, truncated, info = self.env.step(action)
                if COMPILATIONS.count == compiled:
                    steps.append(time.perf_counter() - start)
                    caught += int(info["captured"])
                else:
                    left_out += 1
                done = terminated or truncated
            if timed:
                self.resets.extend(resets)
                self.steps.extend(steps)
                self.caught += caught
                self.left_out += left_out
                self.episodes += 1

    def row(self, base_rate: float | None) -> SpeedRow:
        """The figures of every timed call (``base_rate``: NetCatch-v0's throws/s, None for itself)."""
        rate = len(self.steps) / (sum(self.steps) + sum(self.resets))
        return SpeedRow(self.env_id, self.policy, self.episodes, len(self.steps), rate, _tails(self.steps),
                        _tails(self.resets), self.caught / len(self.steps), rate / (base_rate or rate), self.left_out,
                        shipped_model(self.env_id).name if self.policy == SHIPPED else "")


def _tails(seconds: list[float]) -> tuple[float, float, float]:
    ms = 1e3 * np.asarray(seconds)
    return float(np.median(ms)), float(np.percentile(ms, 99)), float(ms.max())


def measure(episodes: int, rounds: int = 3, ids: tuple[str, ...] = VECTOR_IDS, seed: int = 0,
            progress: bool = True) -> list[SpeedRow]:
    """Every id of ``ids`` (NetCatch-v0 first) under each policy: ``episodes`` episodes a round,
    ``rounds`` rounds interleaved, round ``r`` on seeds ``seed + 1000 r + ...``."""
    numba.set_num_threads(1)
    ids = (BASE_ID, *[i for i in ids if i != BASE_ID])
    timings = [_Timing(env_id, policy) for env_id in ids for policy in POLICIES]
    bar = tqdm(total=rounds * len(timings), desc="episodes of every id", unit="batch", disable=not progress)
    for r in range(rounds):
        for timing in timings:
            timing.run_episodes(episodes, seed + 1000 * r)
            bar.update()
    bar.close()
    base = {t.policy: t.row(None).throws_per_s for t in timings if t.env_id == BASE_ID}
    return [t.row(None if t.env_id == BASE_ID else base[t.policy]) for t in timings]


PHASES = {  # phase: the functions (file suffix, name) whose cumulative time it is
    "reset": [("envs/net_catch.py", "reset")],
    "integration near the net": [("physics/integration.py", "integrate_watched"), ("physics/integration.py", "integrate")],
    "the pause": [("physics/integration.py", "relax")],
    "flight clear of everything": [("physics/throw/clear_flight.py", "fly_clear")],
    "decision checks": [("physics/throw/decisions.py", "after_piece")],
}


def profile(env_id: str, policy: str, episodes: int, seed: int = 50_000) -> dict[str, float]:
    """Where an id's episodes spend their time (cProfile over ``episodes`` episodes, the policy's
    own time left out): each of :data:`PHASES` as a share of the env's time, and ``"other"``."""
    timing = _Timing(env_id, policy)
    profiler = cProfile.Profile()
    profiler.enable()
    timing.run_episodes(episodes, seed)
    profiler.disable()
    stats = pstats.Stats(profiler).stats  # (file, line, name) -> (calls, primitive, own, cumulative, callers)
    env_time = sum(timing.steps) + sum(timing.resets)
    shares = {phase: sum(ct for (path, _, name), (_, _, _, ct, _) in stats.items()
                         if any(path.endswith(suffix) and name == fn for suffix, fn in functions)) / env_time
              for phase, functions in PHASES.items()}
    shares["other"] = max(0.0, 1.0 - sum(shares.values()))
    return shares


def training_steps_per_s(env_ids: tuple[str, ...] = (BASE_ID, "NetCatchWindy-v0"), steps: int = 4096,
                         warm_up: int = 512, n_envs: int = 8, rounds: int = 1) -> dict[str, list[float]]:
    """PPO training's environment steps per second on each id, as ``agents.training.train`` runs
    it (SB3, ``n_envs`` SubprocVecEnv workers, one torch thread): ``steps`` timed after
    ``warm_up``, from scratch, the ids interleaved over ``rounds``."""
    from stable_baselines3 import PPO

    from agents.hyperparams import POLICY, PPO_PARAMS
    from agents.training import TRAINER_THREADS, make_training_env, torch_threads

    rates: dict[str, list[float]] = {env_id: [] for env_id in env_ids}
    for _ in range(rounds):
        for env_id in env_ids:
            env = make_training_env(n_envs, seed=0, env_id=env_id)
            model = PPO(POLICY, env, device="cpu", seed=0, **PPO_PARAMS)
            with torch_threads(TRAINER_THREADS):
                model.learn(warm_up)
                start, before = time.perf_counter(), model.num_timesteps
                model.learn(steps, reset_num_timesteps=False)
                rates[env_id].append((model.num_timesteps - before) / (time.perf_counter() - start))
            env.close()
    return rates
