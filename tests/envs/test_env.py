"""NetCatch-v0: registration, the env checkers, seeding, spaces, bad input, rewards, pickling."""

from __future__ import annotations

import pickle
import subprocess
import sys
import warnings

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env as gym_check_env

import netgym  # noqa: F401  (registers NetCatch-v0)
from netgym.aim import BallisticAim
from netgym.envs import NetCatchEnv
from netgym.envs.observation import aim_at_centre
from netgym.errors import ConfigError, UnstableTimeStepError


def test_make_after_import_and_with_module_prefix() -> None:
    env = gym.make("NetCatch-v0")
    assert isinstance(env.unwrapped, NetCatchEnv) and env.unwrapped.scene.name == "basket"
    code = "import gymnasium as gym; env = gym.make('netgym:NetCatch-v0', scene='goal'); print(env.unwrapped.scene.name)"
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip().endswith("goal")


@pytest.mark.parametrize("scene", ["basket", "goal"])
def test_gymnasium_env_checker_passes_without_warnings(scene: str) -> None:
    env = gym.make("NetCatch-v0", scene=scene, render_mode="rgb_array").unwrapped
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        gym_check_env(env)


def test_stable_baselines3_env_checker_passes_without_warnings() -> None:
    from stable_baselines3.common.env_checker import check_env as sb3_check_env

    env = gym.make("NetCatch-v0").unwrapped
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        sb3_check_env(env, warn=True)


def _rollout(env: NetCatchEnv, seed: int, actions: np.ndarray):
    obs, _ = env.reset(seed=seed)
    out = [obs]
    for a in actions:
        obs, reward, terminated, truncated, info = env.step(a)
        out.append((obs, reward, terminated, info["captured"], info["substeps"]))
        if terminated:
            obs, _ = env.reset()
            out.append(obs)
    return out


def test_reset_seed_makes_episodes_deterministic() -> None:
    actions = np.random.default_rng(0).uniform(-1, 1, (7, 3)).astype(np.float32)
    a = _rollout(gym.make("NetCatch-v0").unwrapped, 11, actions)
    b = _rollout(gym.make("NetCatch-v0").unwrapped, 11, actions)
    assert len(a) == len(b)
    for x, y in zip(a, b):
        assert str(x) == str(y)
    c = _rollout(gym.make("NetCatch-v0").unwrapped, 12, actions)
    assert str(a[0]) != str(c[0])


@pytest.mark.parametrize("scene", ["basket", "goal"])
def test_observations_stay_inside_their_space(scene: str) -> None:
    env = gym.make("NetCatch-v0", scene=scene).unwrapped
    aim = BallisticAim(env.scene)
    rng = np.random.default_rng(1)
    obs, _ = env.reset(seed=3)
    for k in range(12):
        assert env.observation_space.contains(obs), obs
        action = aim_at_centre(aim, obs) if k % 2 else rng.uniform(-1, 1, 3).astype(np.float32)
        obs, reward, terminated, truncated, info = env.step(action)
        assert reward in (0.0, 1.0) and not truncated
        assert reward == float(info["captured"])
        if terminated:
            obs, _ = env.reset()


def test_episode_holds_balls_per_episode_throws_and_keeps_caught_balls() -> None:
    env = gym.make("NetCatch-v0", balls_per_episode=3).unwrapped
    aim = BallisticAim(env.scene)
    obs, _ = env.reset(seed=5)
    ends = []
    for _ in range(3):
        obs, reward, terminated, truncated, info = env.step(aim_at_centre(aim, obs))
        ends.append(terminated)
    assert ends == [False, False, True]
    assert env.sim.n_balls == 3  # all caught, all still in the net
    assert obs[4] == pytest.approx(1.0) and obs[5] == pytest.approx(0.0)


@pytest.mark.parametrize(("action", "message"), [
    (np.zeros(2, dtype=np.float32), r"action must have shape \(3,\)"),
    (np.array([0.0, np.nan, 0.0], dtype=np.float32), "action must be finite"),
])
def test_bad_actions_get_a_clear_error(action: np.ndarray, message: str) -> None:
    env = gym.make("NetCatch-v0").unwrapped
    env.reset(seed=0)
    before = env.sim.state.copy()
    with pytest.raises(ValueError, match=message):
        env.step(action)
    assert np.array_equal(env.sim.state.x, before.x)


def test_bad_arguments_get_named_errors() -> None:
    with pytest.raises(ValueError, match="reward_mode = 'dense'"):
        NetCatchEnv(reward_mode="dense")
    with pytest.raises(ValueError, match="render_mode = 'ascii'"):
        NetCatchEnv(render_mode="ascii")
    with pytest.raises(ValueError, match="balls_per_episode = 0"):
        NetCatchEnv(balls_per_episode=0)
    with pytest.raises(ConfigError, match="simulation.integrator = 'leapfrog' is not allowed"):
        NetCatchEnv(integrator="leapfrog")
    with pytest.raises(UnstableTimeStepError, match="simulation.dt = 0.002 s is beyond"):
        NetCatchEnv(integrator="symplectic_euler", dt=0.002)
    with pytest.raises(RuntimeError, match="reset"):
        NetCatchEnv().step(np.zeros(3, dtype=np.float32))


def test_shaped_reward_is_bounded_and_rewards_near_misses_more() -> None:
    env = gym.make("NetCatch-v0", reward_mode="shaped").unwrapped
    aim = BallisticAim(env.scene)
    obs, _ = env.reset(seed=2)
    good = aim_at_centre(aim, obs)
    _, capture_reward, _, _, info = env.step(good)
    assert info["captured"] and capture_reward == 1.0
    rewards = []
    for offset in (0.3, 0.6, 1.2):  # ever weaker throws: further from the opening
        env.reset(seed=2)
        miss = good.copy()
        miss[0] = np.clip(good[0] - offset, -1, 1)
        _, reward, _, _, info = env.step(miss)
        assert not info["captured"]
        assert 0.0 <= reward <= 0.5
        rewards.append(reward)
    assert rewards[0] > rewards[1] > rewards[2]


def test_pickle_round_trip_and_double_close() -> None:
    env = gym.make("NetCatch-v0").unwrapped
    env.reset(seed=4)
    copy = pickle.loads(pickle.dumps(env))
    action = np.array([0.2, 0.3, 0.0], dtype=np.float32)
    assert str(env.step(action)[:4]) == str(copy.step(action)[:4])
    env.close()
    env.close()


def test_metadata_declares_render_fps_and_modes() -> None:
    assert NetCatchEnv.metadata["render_fps"] > 0
    assert set(NetCatchEnv.metadata["render_modes"]) == {"human", "rgb_array", "rgb_array_list", "replay_list"}


@pytest.mark.slow
def test_works_in_stable_baselines3_subprocess_vec_env() -> None:
    from stable_baselines3.common.env_util import make_vec_env
    from stable_baselines3.common.vec_env import SubprocVecEnv

    vec = make_vec_env("netgym:NetCatch-v0", n_envs=2, seed=0, vec_env_cls=SubprocVecEnv)
    try:
        obs = vec.reset()
        assert obs.shape == (2, 7)
        obs, rewards, dones, infos = vec.step(np.zeros((2, 3), dtype=np.float32))
        assert obs.shape == (2, 7) and rewards.shape == (2,) and "captured" in infos[0]
    finally:
        vec.close()


@pytest.mark.parametrize(("env_id", "scene", "balls", "threshold"), [
    ("NetCatch-v0", "basket", 3, 2.9), ("NetCatchGoal-v0", "goal", 3, 2.9),
    ("NetCatchLongEpisode-v0", "basket", 10, 9.7)])
def test_registered_variants_make_pass_the_checker_and_state_their_threshold(env_id: str, scene: str, balls: int,
                                                                             threshold: float) -> None:
    env = gym.make(env_id)
    assert env.spec.reward_threshold == threshold
    assert env.unwrapped.scene.name == scene and env.unwrapped.balls_per_episode == balls
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        gym_check_env(env.unwrapped)
    vec = gym.make_vec(env_id, num_envs=2, vectorization_mode="sync")
    assert vec.unwrapped.envs[0].unwrapped.scene.name == scene
