"""The variants: a hidden wind per episode, launch noise, the feedback of each throw; their
registered ids pass Gymnasium's checker (how oracles and the shipped models fare on them:
tests/agents/test_variant_agents.py)."""

from __future__ import annotations

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env

import netgym  # noqa: F401
from netgym.aim import BallisticAim
from netgym.config import ConfigError
from netgym.envs import NetCatchEnv
from netgym.envs.net_catch import ObservationIndex
from netgym.envs.observation import aim_at_centre
from netgym.envs.variation import LaunchNoise, WindRange
from netgym.wrappers import thrower_view_env

WINDY = {"balls_per_episode": 5, "overrides": {"air.density": 1.2}, "wind": (0.0, 3.0), "feedback": True}


@pytest.mark.parametrize("env_id", ["NetCatchWindy-v0", "NetCatchNoisy-v0", "NetCatchRandomized-v0",
                                    "NetCatchRandomized-v1", "NetCatchPixels-v0"])
@pytest.mark.filterwarnings("ignore:.*is different from the unwrapped version")  # ThrowerView is a wrapper
@pytest.mark.filterwarnings("ignore:.*NetCatchRandomized-v0 is out of date")  # v0 is checked as long as it is kept
def test_variants_pass_the_env_checker(env_id: str) -> None:
    env = thrower_view_env() if env_id == "NetCatchPixels-v0" else gym.make(env_id).unwrapped
    check_env(env, skip_render_check=True)
    env.close()


def test_pixel_observations_show_the_net_from_the_thrower() -> None:
    env = gym.make("NetCatchPixels-v0")
    near, _ = env.reset(seed=0, options={"thrower": {"distance": 3.0}})
    far, _ = env.reset(seed=0, options={"thrower": {"distance": 8.0}})
    assert near.shape == far.shape == (84, 84, 3) and near.dtype == np.uint8
    rgb = near.astype(int)
    red = (rgb[..., 0] > 150) & (rgb[..., 1] < 100)                 # the poles and rim
    grey = (rgb.min(axis=-1) > 150) & (np.ptp(rgb, axis=-1) < 25)   # the net
    assert red.sum() > 50 and grey.sum() > 50
    assert red.sum() > ((far[..., 0] > 150) & (far[..., 1] < 100)).sum()  # nearer: the frame looks bigger


def test_wind_is_drawn_per_episode_from_the_seed_and_hidden() -> None:
    env = NetCatchEnv(**WINDY)
    winds = [env.reset(seed=seed)[1]["wind"] for seed in (1, 2, 1)]
    assert np.array_equal(winds[0], winds[2]) and not np.array_equal(winds[0], winds[1])
    assert np.array_equal(env.sim.model.wind, winds[2])                         # the physics blows it
    assert env.observation_space.shape == (len(ObservationIndex),)              # not an entry of its own
    draws = np.array([WindRange(0.0, 3.0).draw(np.random.default_rng(k)) for k in range(2000)])
    speeds = np.linalg.norm(draws, axis=1)
    assert speeds.min() >= 0.0 and speeds.max() <= 3.0 and np.all(draws[:, 2] == 0.0)
    assert abs(speeds.mean() - 1.5) < 0.05                                     # uniform speed
    assert np.linalg.norm((draws[:, :2] / speeds[:, None]).mean(axis=0)) < 0.05  # any direction


def test_domain_randomisation_is_drawn_per_episode_from_the_seed() -> None:
    ranges = {"ball.mass": (0.5, 2.0), "springs.structural.ks": (1000.0, 3000.0)}
    env = NetCatchEnv(randomize=ranges)
    draws = [env.reset(seed=seed)[1]["scene_draws"] for seed in (4, 5, 4)]
    assert draws[0] == draws[2] and draws[0] != draws[1]
    for field, (low, high) in ranges.items():
        assert all(low <= d[field] <= high for d in draws)
    assert env.sim.config.ball.mass == draws[2]["ball.mass"]                    # the physics uses them
    assert env.sim.config.springs.structural.ks == draws[2]["springs.structural.ks"]
    _, _, _, _, info = env.step(np.zeros(3, dtype=np.float32))
    assert info["scene_draws"] == draws[2]
    with pytest.raises(ConfigError, match="ball.mass"):
        NetCatchEnv(randomize={"ball.mass": (-1.0, 2.0)})
    with pytest.raises(ConfigError, match="unknown field 'ball.colour'"):
        NetCatchEnv(randomize={"ball.colour": (0.0, 1.0)})
    with pytest.raises(ValueError, match="randomize"):
        NetCatchEnv(randomize={"ball.mass": (2.0, 1.0)})


def test_launch_noise_has_the_stated_statistics() -> None:
    noise, rng = LaunchNoise(0.3, 1.5, 2.0), np.random.default_rng(0)
    released = np.array([noise.apply(10.0, 45.0, 0.0, rng) for _ in range(20000)])
    assert np.allclose(released.mean(axis=0), [10.0, 45.0, 0.0], atol=0.05)
    assert np.allclose(released.std(axis=0), [0.3, 1.5, 2.0], rtol=0.03)
    env = NetCatchEnv(launch_noise=(0.3, 1.5, 1.5))
    env.reset(seed=0)
    _, _, _, _, info = env.step(np.zeros(3, dtype=np.float32))
    assert not np.allclose(info["launch_velocity"], info["aimed_velocity"])


def test_feedback_says_where_a_throw_crossed_the_opening() -> None:
    """Through the centre: offsets ~ 0; a throw 2 m long: offset ~ 2 m along its direction;
    one that never rises to the opening: short > 0."""
    env = NetCatchEnv(feedback=True)
    obs, _ = env.reset(seed=3, options={"thrower": {"bearing": 180.0}})  # thrower on the -x side
    assert not np.any(obs[ObservationIndex.LAST_CAUGHT:])
    aim = BallisticAim(env.scene)
    obs, _, _, _, info = env.step(aim_at_centre(aim, obs))
    assert obs[ObservationIndex.LAST_CAUGHT] == float(info["captured"]) == 1.0
    assert np.abs(obs[ObservationIndex.LAST_OFFSET_U:ObservationIndex.LAST_SHORT + 1]).max() < 0.02
    env.reset(seed=3, options={"thrower": {"bearing": 180.0}})
    action = aim.aim(env.thrower, env.sim.opening.centre + [2.0, 0.0, 0.0])
    obs, *_ = env.step(action)
    assert obs[ObservationIndex.LAST_OFFSET_U] == pytest.approx(2.0, abs=0.02)
    assert obs[ObservationIndex.LAST_CAUGHT] == 0.0
    env.reset(seed=3)
    obs, *_ = env.step(np.array([-1.0, -1.0, 0.0], dtype=np.float32))         # 4 m/s at 20 degrees
    assert obs[ObservationIndex.LAST_SHORT] > 0.5


def test_wind_needs_air_and_bad_variation_arguments_are_refused() -> None:
    with pytest.raises(ValueError, match="wind needs air"):
        NetCatchEnv(wind=(0.0, 3.0))
    with pytest.raises(ValueError, match="wind = "):
        NetCatchEnv(overrides={"air.density": 1.2}, wind=(3.0, 1.0))
    with pytest.raises(ValueError, match="launch_noise = "):
        NetCatchEnv(launch_noise=(0.3, -1.0, 1.0))
    with pytest.raises(ValueError, match="feedback = "):
        NetCatchEnv(feedback=1)
