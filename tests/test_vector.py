"""NetCatchVectorEnv: the vector entry point, equivalence with single environments, autoreset,
and the Stable-Baselines3 adapter."""

from __future__ import annotations

import gymnasium as gym
import numpy as np
import pytest

import netgym  # noqa: F401
from agents.oracle import BallisticOracle
from netgym.envs import NetCatchEnv
from netgym.envs.vector import NetCatchVectorEnv


def test_make_vec_uses_the_vector_entry_point() -> None:
    env = gym.make_vec("NetCatch-v0", num_envs=3, vectorization_mode="vector_entry_point")
    assert isinstance(env, NetCatchVectorEnv)
    obs, _ = env.reset(seed=0)
    assert obs.shape == (3, 7) and env.observation_space.contains(obs)
    env.close()


@pytest.mark.parametrize("scene", ["basket", "goal"])
def test_vector_env_equals_single_envs_with_the_same_seeds(scene: str) -> None:
    n = 4
    vector = NetCatchVectorEnv(num_envs=n, scene=scene, balls_per_episode=2)
    singles = [NetCatchEnv(scene=scene, balls_per_episode=2) for _ in range(n)]
    obs, _ = vector.reset(seed=100)
    single_obs = np.stack([env.reset(seed=100 + i)[0] for i, env in enumerate(singles)])
    assert np.array_equal(obs, single_obs)
    oracle = BallisticOracle(singles[0].scene)
    rng = np.random.default_rng(0)
    finals = 0
    for _ in range(5):
        actions = np.clip(oracle.predict(obs)[0] + rng.normal(0, 0.2, (n, 3)), -1, 1).astype(np.float32)
        obs, rewards, terminated, truncated, infos = vector.step(actions)
        for i, env in enumerate(singles):
            o, r, te, tr, info = env.step(actions[i])
            assert r == rewards[i] and te == terminated[i] and tr == truncated[i]
            assert info["substeps"] == infos["substeps"][i]
            assert np.array_equal(info["final_position"], infos["final_position"][i])
            if te:
                assert np.array_equal(o, infos["final_obs"][i])  # same-step autoreset
                o, _ = env.reset()
                finals += 1
            assert np.array_equal(o, obs[i])
            assert np.array_equal(env.sim.state.x, vector.envs[i].sim.state.x)
    assert finals > 0


def test_vector_env_rejects_bad_actions() -> None:
    vector = NetCatchVectorEnv(num_envs=2)
    vector.reset(seed=0)
    with pytest.raises(ValueError, match=r"actions must have shape \(2, 3\)"):
        vector.step(np.zeros((3, 3), dtype=np.float32))
    with pytest.raises(ValueError, match="action must be finite"):
        vector.step(np.full((2, 3), np.nan, dtype=np.float32))


def test_sb3_adapter_steps_and_reports_terminal_observations() -> None:
    from stable_baselines3.common.vec_env import VecMonitor

    from netgym.envs.sb3 import NetCatchSB3VecEnv

    env = VecMonitor(NetCatchSB3VecEnv(num_envs=2, balls_per_episode=1))
    env.seed(3)
    obs = env.reset()
    assert obs.shape == (2, 7)
    obs, rewards, dones, infos = env.step(np.zeros((2, 3), dtype=np.float32))
    assert dones.all()  # one ball per episode
    for info in infos:
        assert info["terminal_observation"].shape == (7,)
        assert "episode" in info and "captured" in info
    assert env.get_attr("balls_per_episode") == [1, 1]
    env.close()


def test_next_step_autoreset_matches_gymnasium_sync_vector_env_and_its_wrappers() -> None:
    import gymnasium as gym
    from gymnasium.vector import AutoresetMode, SyncVectorEnv
    from gymnasium.wrappers.vector import NormalizeObservation

    native = NetCatchVectorEnv(num_envs=2, balls_per_episode=2, autoreset_mode="next_step")
    assert native.metadata["autoreset_mode"] == AutoresetMode.NEXT_STEP
    sync = SyncVectorEnv([lambda: NetCatchEnv(balls_per_episode=2) for _ in range(2)],
                         autoreset_mode=AutoresetMode.NEXT_STEP)
    a, _ = native.reset(seed=4)
    b, _ = sync.reset(seed=4)
    assert np.array_equal(a, b)
    rng = np.random.default_rng(0)
    ended = 0
    for _ in range(5):  # crosses two episode ends and the resets that follow them
        actions = rng.uniform(-1, 1, (2, 3)).astype(np.float32)
        a_out, b_out = native.step(actions), sync.step(actions)
        for x, y in zip(a_out[:4], b_out[:4]):
            assert np.array_equal(x, y)
        ended += int(a_out[2].sum())
    assert ended >= 2
    wrapped = NormalizeObservation(NetCatchVectorEnv(num_envs=2, autoreset_mode=AutoresetMode.NEXT_STEP))
    wrapped.reset(seed=0)
    wrapped.step(np.zeros((2, 3), dtype=np.float32))
    with pytest.raises(ValueError, match="autoreset_mode = 'sometimes'"):
        NetCatchVectorEnv(num_envs=1, autoreset_mode="sometimes")
    gym.make_vec("NetCatch-v0", num_envs=2, vectorization_mode="vector_entry_point", autoreset_mode="next_step").close()
