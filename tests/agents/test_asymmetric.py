"""The asymmetric actor-critic for pixels (agents/asymmetric.py): the policy acts on the image
alone, the critics read the state alone, the training env returns both, and a saved model acts in
NetCatchPixels-v0 as the table's other models do."""

from __future__ import annotations

from pathlib import Path

import gymnasium as gym
import numpy as np
import pytest
import torch
from gymnasium.utils.env_checker import check_env

import netgym  # noqa: F401
from agents.asymmetric import AsymmetricSAC, AsymmetricSACPolicy, acting_kwargs
from agents.evaluation import evaluate
from agents.model_env import record_env
from agents.policies import load_policy, policy_in_env, saved_algorithm
from netgym.errors import InvalidArgumentError
from netgym.wrappers import thrower_view_env


@pytest.fixture(scope="module")
def training_env() -> gym.Env:
    return gym.make("NetCatchPixels-v0", with_state=True)


@pytest.fixture(scope="module")
def model(training_env: gym.Env) -> AsymmetricSAC:
    return AsymmetricSAC("AsymmetricCnnPolicy", training_env, seed=0, buffer_size=64, learning_starts=8,
                         batch_size=8, policy_kwargs=dict(net_arch=[32, 32]), device="cpu")


@pytest.mark.filterwarnings("ignore:.*is different from the unwrapped version")  # ThrowerView is a wrapper
def test_the_training_env_returns_the_image_and_the_vector_of_the_same_episode(training_env: gym.Env) -> None:
    both, _ = training_env.reset(seed=3)
    image, _ = gym.make("NetCatchPixels-v0").reset(seed=3)
    vector, _ = gym.make("NetCatch-v0").reset(seed=3)
    assert np.array_equal(both["pixels"], image) and np.array_equal(both["state"], vector)
    assert training_env.observation_space["pixels"].contains(both["pixels"])
    check_env(thrower_view_env(with_state=True), skip_render_check=True)


def test_with_state_must_be_a_flag() -> None:
    with pytest.raises(InvalidArgumentError, match="with_state"):
        thrower_view_env(with_state="yes")


def test_the_policy_acts_on_the_image_alone(model: AsymmetricSAC, training_env: gym.Env) -> None:
    obs, _ = training_env.reset(seed=5)
    action, _ = model.predict(obs, deterministic=True)
    other_state = {"pixels": obs["pixels"], "state": np.random.default_rng(0).normal(size=obs["state"].shape)}
    assert np.array_equal(model.predict(other_state, deterministic=True)[0], action)
    assert np.array_equal(model.predict(obs["pixels"], deterministic=True)[0], action)
    other_image, _ = training_env.reset(seed=6)
    assert not np.array_equal(model.predict(other_image["pixels"], deterministic=True)[0], action)


def test_the_critics_read_the_state_alone(model: AsymmetricSAC, training_env: gym.Env) -> None:
    obs, _ = training_env.reset(seed=5)
    other, _ = training_env.reset(seed=6)
    action = torch.zeros((1, 3))

    def values(pixels: np.ndarray, state: np.ndarray) -> torch.Tensor:
        tensors, _ = model.policy.obs_to_tensor({"pixels": pixels, "state": state})
        return torch.cat(model.critic(tensors, action))

    assert torch.equal(values(obs["pixels"], obs["state"]), values(other["pixels"], obs["state"]))
    assert not torch.equal(values(obs["pixels"], obs["state"]), values(obs["pixels"], other["state"]))


def test_actor_and_critics_cannot_share_a_features_extractor(training_env: gym.Env) -> None:
    with pytest.raises(InvalidArgumentError, match="share_features_extractor"):
        AsymmetricSAC("AsymmetricCnnPolicy", training_env, buffer_size=8,
                      policy_kwargs=dict(share_features_extractor=True))
    assert AsymmetricSAC.policy_aliases["AsymmetricCnnPolicy"] is AsymmetricSACPolicy


def test_evaluation_drops_the_training_only_arguments() -> None:
    assert acting_kwargs({"reward_mode": "shaped", "with_state": True}) == {"reward_mode": "shaped"}


def test_a_saved_model_loads_by_its_name_and_acts_in_the_pixel_env(model: AsymmetricSAC, tmp_path: Path) -> None:
    model.learn(16)
    record_env(model, "NetCatchPixels-v0")
    model.save(tmp_path / "asym.zip")
    assert saved_algorithm(tmp_path / "asym.zip") == "AsymmetricSAC"
    env_id, policy = policy_in_env(tmp_path / "asym.zip")
    assert env_id == "NetCatchPixels-v0" and isinstance(policy, AsymmetricSAC)
    image, _ = gym.make(env_id).reset(seed=5)
    assert np.array_equal(policy.predict(image, deterministic=True)[0], model.predict(image, deterministic=True)[0])
    assert evaluate(load_policy(tmp_path / "asym.zip"), 1, env_id=env_id).throws == 3


def test_for_acting_drops_what_only_training_reads_and_keeps_the_actions(training_env: gym.Env,
                                                                        tmp_path: Path) -> None:
    from agents.policies import for_acting

    trained = AsymmetricSAC("AsymmetricCnnPolicy", training_env, seed=1, buffer_size=64, learning_starts=8,
                            batch_size=8, policy_kwargs=dict(net_arch=[32, 32]), device="cpu")
    trained.learn(24)
    record_env(trained, "NetCatchPixels-v0")
    image, _ = gym.make("NetCatchPixels-v0").reset(seed=5)
    action = trained.predict(image, deterministic=True)[0]
    trained.save(tmp_path / "full.zip")
    for_acting(trained)
    trained.save(tmp_path / "acting.zip")
    assert (tmp_path / "acting.zip").stat().st_size < (tmp_path / "full.zip").stat().st_size
    reloaded = load_policy(tmp_path / "acting.zip")
    assert np.array_equal(reloaded.predict(image, deterministic=True)[0], action)
    assert not reloaded.actor.optimizer.state_dict()["state"] and not reloaded.critic.optimizer.state_dict()["state"]
    assert all(torch.equal(target, online) for target, online in
               zip(reloaded.critic_target.parameters(), reloaded.critic.parameters()))
