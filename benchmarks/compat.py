"""The few names the benchmarks need that moved between the trees they compare, and the
settings they share."""

from __future__ import annotations

from typing import Any, Callable

import numba
import numpy as np

numba.set_num_threads(1)  # every figure is of one thread

INTEGRATOR_DT = {  # integrator -> the dt its benchmarks step with (the docs' throughput table's)
    "explicit_euler": 5e-4,
    "symplectic_euler": 5e-4,
    "rk4": 1e-3,
    "implicit_euler": 5e-3,
    "imex_euler": 2e-3,
}
STEPS = 200
"""Steps a step benchmark takes in one timed call (a call of one step would time Python's
overhead, not the step)."""

IDS = ("NetCatch-v0", "NetCatchGoal-v0", "NetCatchLongEpisode-v0", "NetCatchWindy-v0", "NetCatchNoisy-v0",
       "NetCatchRandomized-v0", "NetCatchRandomized-v1", "NetCatchPixels-v0")
"""The registered ids (a static list: asv reads the parameters before it installs a tree)."""


def skip_unless(condition: bool, why: str) -> None:
    """Skip the benchmark on this tree (asv's convention: NotImplementedError in setup)."""
    if not condition:
        raise NotImplementedError(why)


def throw_function() -> Callable[..., Any]:
    """``throw(sim, position, velocity)``: netgym.physics.throw's, or the Simulator method of
    the trees before it."""
    try:
        from netgym.physics.throw import throw
    except ImportError:
        return lambda sim, position, velocity: sim.throw(position, velocity)
    return throw


def oracle_for(env: Any) -> Any:
    """The ballistic oracle of ``env``'s scene (anything with Stable-Baselines3's ``predict``)."""
    from agents.oracle import BallisticOracle

    return BallisticOracle(env.unwrapped.scene)


def shipped_policy(env_id: str) -> tuple[str, Any]:
    """The id to act in and the model shipped for ``env_id`` as a policy for one env of it (on
    trees that name no model per id, NetCatch-v0's PPO model, ``agents.policies.PRETRAINED``)."""
    try:
        from agents.policies import policy_in_env, shipped_model
    except ImportError as missing:
        if env_id != "NetCatch-v0":
            raise NotImplementedError(f"this tree names no shipped model per id: {missing}")
        from agents.policies import PRETRAINED, load_policy

        return env_id, load_policy(PRETRAINED)
    path = shipped_model(env_id)
    skip_unless(path.exists(), f"this tree ships no {path.name}")
    return policy_in_env(path, env_id)


def run_episode(env: Any, policy: Any, seed: int) -> int:
    """One episode of ``env`` seeded ``seed`` with ``policy`` (deterministic actions, its
    recurrent state given back as SB3's ``evaluate_policy`` does); returns its throws."""
    obs, _ = env.reset(seed=seed)
    done, throws, state = False, 0, None
    while not done:
        action, state = policy.predict(obs, state=state, episode_start=np.array([throws == 0]), deterministic=True)
        obs, _, terminated, truncated, _ = env.step(action)
        done, throws = terminated or truncated, throws + 1
    return throws
