"""The agents on the variants: the windy one separates an oracle that knows the wind from one
that does not, with room for learning within an episode; randomized v1 rewards knowing the ball's
draws; the shipped windy models read the windy observations."""

from __future__ import annotations

import gymnasium as gym
import numpy as np
import pytest

import netgym
from agents.oracle import AdaptiveOracle, BallisticOracle, InformedOracle
from netgym.envs import NetCatchEnv

WINDY = netgym.ENVIRONMENTS["NetCatchWindy-v0"].kwargs


def _capture_rate(policy_of, episodes: int, **kwargs) -> float:
    env = NetCatchEnv(**(kwargs or WINDY))
    policy = policy_of(env)
    caught = throws = 0
    for episode in range(episodes):
        obs, _ = env.reset(seed=500 + episode)
        done = False
        while not done:
            obs, _, terminated, truncated, info = env.step(policy.predict(obs)[0])
            caught, throws, done = caught + info["captured"], throws + 1, terminated or truncated
    return caught / throws


def test_the_windy_variant_rewards_knowing_or_learning_the_wind() -> None:
    informed = _capture_rate(InformedOracle, 4)
    blind = _capture_rate(lambda env: BallisticOracle(env.scene), 4)
    adaptive = _capture_rate(lambda env: AdaptiveOracle(env.scene), 4)
    assert informed >= 0.9 and blind <= 0.6 and adaptive > blind


def test_randomized_v1_rewards_knowing_the_ball_and_v0_points_to_it() -> None:
    """The ball's drag and mass drawn per episode move the aim: an oracle blind to the draws loses
    at least 10 points against one told them (the issue's bar for a randomized task that tests
    aim), where on v0 the blind oracle catches everything; making v0 says that v1 exists."""
    v1 = netgym.ENVIRONMENTS["NetCatchRandomized-v1"].kwargs
    informed = _capture_rate(InformedOracle, 8, **v1)
    blind = _capture_rate(lambda env: BallisticOracle(env.scene), 8, **v1)
    assert informed >= 0.95 and blind <= informed - 0.10
    v0 = netgym.ENVIRONMENTS["NetCatchRandomized-v0"].kwargs
    assert _capture_rate(lambda env: BallisticOracle(env.scene), 4, **v0) == 1.0
    with pytest.warns(DeprecationWarning, match="NetCatchRandomized-v0 is out of date.*v1"):
        gym.make("NetCatchRandomized-v0").close()


def test_shipped_windy_model_loads_and_reads_the_windy_observation() -> None:
    pytest.importorskip("stable_baselines3")
    from agents.policies import PRETRAINED_WINDY, load_policy

    model = load_policy(PRETRAINED_WINDY)
    env = gym.make("NetCatchWindy-v0")
    obs, _ = env.reset(seed=0)
    assert model.observation_space == env.observation_space
    action, _ = model.predict(obs, deterministic=True)
    assert env.action_space.contains(action)


def test_shipped_frame_stacked_windy_model_acts_on_the_windy_observations() -> None:
    pytest.importorskip("stable_baselines3")
    from agents.policies import PRETRAINED_WINDY_STACKED, FrameStackPolicy, load_policy

    model = load_policy(PRETRAINED_WINDY_STACKED)
    env = gym.make("NetCatchWindy-v0")
    obs, _ = env.reset(seed=0)
    assert model.observation_space.shape == (5 * obs.size,)
    policy = FrameStackPolicy(model, 5)
    for start in (True, False):
        action, _ = policy.predict(obs, episode_start=np.array([start]))
        assert env.action_space.contains(action)
        obs, *_ = env.step(action)
