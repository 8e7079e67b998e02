"""The asymmetric actor-critic (agents/asymmetric.py): the policy acts on the image, or on the
observation, alone; the critics read the state alone; the training envs return both; the target
entropy falls as asked; a saved model acts in NetCatchPixels-v0 as the table's other models do."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import gymnasium as gym
import numpy as np
import pytest
import torch
from gymnasium.utils.env_checker import check_env
from stable_baselines3.common.callbacks import BaseCallback

import netgym  # noqa: F401
from agents.asymmetric import AsymmetricSAC, AsymmetricSACPolicy, acting_kwargs
from agents.evaluation import evaluate
from agents.model_env import record_env
from agents.policies import load_policy, policy_in_env, saved_algorithm
from netgym.bench.results import read_results
from netgym.errors import InvalidArgumentError
from netgym.wrappers import HiddenState, acting_key, thrower_view_env

TRAINING_ENVS = {"pixels": lambda: gym.make("NetCatchPixels-v0", with_state=True),
                 "observation": lambda: HiddenState(gym.make("NetCatchWindy-v0"))}
POLICIES = {"pixels": "AsymmetricCnnPolicy", "observation": "AsymmetricMlpPolicy"}
ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="module")
def training_env() -> gym.Env:
    return TRAINING_ENVS["pixels"]()


@pytest.fixture(scope="module")
def model(training_env: gym.Env) -> AsymmetricSAC:
    return AsymmetricSAC("AsymmetricCnnPolicy", training_env, seed=0, buffer_size=64, learning_starts=8,
                         batch_size=8, policy_kwargs=dict(net_arch=[32, 32]), device="cpu")


@pytest.fixture(scope="module", params=sorted(TRAINING_ENVS))
def env_and_model(request: pytest.FixtureRequest) -> tuple[gym.Env, AsymmetricSAC]:
    env = TRAINING_ENVS[request.param]()
    return env, AsymmetricSAC(POLICIES[request.param], env, seed=0, buffer_size=64, learning_starts=8, batch_size=8,
                              policy_kwargs=dict(net_arch=[32, 32]), device="cpu")


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


def test_the_policy_acts_on_what_the_env_shows_alone(env_and_model: tuple[gym.Env, AsymmetricSAC]) -> None:
    env, model = env_and_model
    key = acting_key(env.observation_space)
    obs, _ = env.reset(seed=5)
    action, _ = model.predict(obs, deterministic=True)
    other_state = {key: obs[key], "state": np.random.default_rng(0).normal(size=obs["state"].shape)}
    assert np.array_equal(model.predict(other_state, deterministic=True)[0], action)
    assert np.array_equal(model.predict(obs[key], deterministic=True)[0], action)
    other, _ = env.reset(seed=6)
    assert not np.array_equal(model.predict(other[key], deterministic=True)[0], action)


def test_the_critics_read_the_state_alone(env_and_model: tuple[gym.Env, AsymmetricSAC]) -> None:
    env, model = env_and_model
    key = acting_key(env.observation_space)
    obs, _ = env.reset(seed=5)
    other, _ = env.reset(seed=6)
    action = torch.zeros((1, 3))

    def values(seen: np.ndarray, state: np.ndarray) -> torch.Tensor:
        tensors, _ = model.policy.obs_to_tensor({key: seen, "state": state})
        return torch.cat(model.critic(tensors, action))

    assert torch.equal(values(obs[key], obs["state"]), values(other[key], obs["state"]))
    assert not torch.equal(values(obs[key], obs["state"]), values(obs[key], other["state"]))


@pytest.mark.parametrize("env_id", ["NetCatchWindy-v0", "NetCatchRandomized-v1", "NetCatch-v0"])
def test_hidden_state_puts_what_the_episode_hides_beside_the_observation(env_id: str) -> None:
    env = HiddenState(gym.make(env_id))
    plain = gym.make(env_id)
    both, info = env.reset(seed=4)
    assert np.array_equal(both["observation"], plain.reset(seed=4)[0])
    base = env.unwrapped
    size = plain.observation_space.shape[0]
    assert np.array_equal(both["state"][:size], both["observation"])
    hidden = both["state"][size:]
    wind = hidden[:2] * base.wind_range.high if base.wind_range is not None else np.zeros(2)
    np.testing.assert_allclose(wind, info["wind"][:2], rtol=1e-6)
    ranges = base.randomize.ranges if base.randomize is not None else ()
    draws = hidden[len(hidden) - len(ranges):]
    assert np.all(np.abs(draws) <= 1.0)
    np.testing.assert_allclose([low + (d + 1.0) / 2.0 * (high - low) for d, (_, low, high) in zip(draws, ranges)],
                               [info["scene_draws"][field] for field, _, _ in ranges], rtol=1e-5)
    assert len(hidden) == (2 if base.wind_range is not None else 0) + len(ranges)
    stepped, *_, info = env.step(env.action_space.sample())
    assert np.array_equal(stepped["state"][size:], hidden) and env.observation_space.contains(stepped)


@pytest.mark.filterwarnings("ignore:.*is different from the unwrapped version")
def test_hidden_state_passes_the_checker_and_refuses_images() -> None:
    check_env(HiddenState(gym.make("NetCatchWindy-v0").unwrapped))
    with pytest.raises(InvalidArgumentError, match="vector observations"):
        HiddenState(gym.make("NetCatchPixels-v0"))


def test_the_target_entropy_holds_falls_over_the_middle_third_and_holds() -> None:
    seen = []

    class Record(BaseCallback):
        def _on_step(self) -> bool:
            seen.append((self.num_timesteps, self.model.target_entropy))
            return True

    env = HiddenState(gym.make("NetCatchWindy-v0"))
    model = AsymmetricSAC("AsymmetricMlpPolicy", env, seed=0, buffer_size=128, learning_starts=0, batch_size=8,
                          target_entropy_end=-12.0, policy_kwargs=dict(net_arch=[16, 16]), device="cpu")
    model.learn(90, callback=Record())
    by_step = dict(seen)  # the target an env step starts with: the last gradient step's
    assert by_step[1] == by_step[30] == -3.0 and model.target_entropy == -12.0
    middle = [by_step[t] for t in range(32, 61)]
    assert all(a > b for a, b in zip(middle, middle[1:])) and -12.0 < min(middle) and max(middle) < -3.0
    assert by_step[62] == by_step[90] == -12.0


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


def test_a_windy_run_trains_on_the_hidden_wind_and_acts_on_stacked_observations(tmp_path: Path) -> None:
    """The table's runner with sac_asym.yml's windy settings: trained on HiddenState's Dicts of 5
    stacked observations, saved with its frame stack, evaluated on NetCatchWindy-v0's own episodes."""
    from agents.baselines.grid import FINAL_SEED, MODELS, Run
    from agents.baselines.runs import execute
    from agents.policies import FrameStackPolicy

    run = Run("sac_asym", "NetCatchWindy-v0", 0, 64, final_episodes=2, curve_episodes=1)
    record = execute(run, tmp_path)
    assert record["env_steps"] == 64 and record["final"]["throws"] == 10 and len(record["final"]["by_throw"]) == 5
    saved = tmp_path / MODELS / f"{run.name}.zip"
    model = load_policy(saved)
    spaces = model.observation_space
    assert spaces["observation"].shape == (5 * 11,) and spaces["state"].shape == (5 * 13,)
    env_id, policy = policy_in_env(saved)
    assert env_id == "NetCatchWindy-v0" and isinstance(policy, FrameStackPolicy) and policy.n_stack == 5
    assert tuple(evaluate(policy, 2, seed=FINAL_SEED, env_id=env_id).by_throw) == tuple(record["final"]["by_throw"])
    results = tmp_path / "seeds.json"
    command = ["scripts/seed_rates.py", "sac_asym", "NetCatchWindy-v0", "--out", str(tmp_path), "--episodes", "2",
               "--results", str(results)]
    done = subprocess.run([sys.executable, *command], cwd=ROOT, capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    (row,) = read_results(results)["figures"]["rows"]
    assert row["policy"] == "sac_asym seed 0" and tuple(row["by_throw"]) == tuple(record["final"]["by_throw"])
