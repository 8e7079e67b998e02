"""Agents: the oracle's capture rate, the confidence interval, PPO training smoke test, what
training says while it starts and runs, the shipped model, and the PPO settings' one source
(agents/hyperparams/ppo.yml)."""

from __future__ import annotations

import os
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

from agents.evaluation import evaluate, wilson_interval
from agents.model_env import EnvMismatchError, ModelEnv, model_env, saved_env
from agents.policies import PRETRAINED, PRETRAINED_WINDY_STACKED, FrameStackPolicy, load_policy, policy_in_env

ROOT = Path(__file__).resolve().parents[2]


@pytest.mark.parametrize("scene", ["basket", "goal"])
def test_oracle_captures_over_90_percent_of_a_few_hundred_throws(scene: str) -> None:
    result = evaluate(load_policy("oracle", scene), episodes=70, seed=500, scene=scene)
    assert result.throws == 210
    assert result.rate >= 0.9, str(result)


def test_random_policy_rarely_captures() -> None:
    result = evaluate(load_policy("random"), episodes=40, seed=500)
    assert result.rate < 0.2, str(result)


@pytest.mark.parametrize("single", [(7,), (84, 84, 3)])
def test_random_policy_gives_one_action_an_observation_and_one_a_row_of_a_batch(single: tuple[int, ...]) -> None:
    from agents.random_agent import RandomAgent

    agent = RandomAgent(0)
    assert agent.predict(np.zeros(single))[0].shape == (3,)
    assert agent.predict(np.zeros((5, *single)))[0].shape == (5, 3)


def test_wilson_interval_matches_known_values() -> None:
    low, high = wilson_interval(50, 100)
    assert low == pytest.approx(0.4038, abs=1e-4) and high == pytest.approx(0.5962, abs=1e-4)
    low, high = wilson_interval(0, 20)
    assert low == 0.0 and high == pytest.approx(0.1611, abs=1e-4)


def test_loading_a_model_without_stable_baselines3_names_the_extra(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setitem(sys.modules, "stable_baselines3", None)  # as if the [train] extra were not installed
    with pytest.raises(ImportError, match=r"needs Stable-Baselines3 and torch: .*\[train\]"):
        load_policy(PRETRAINED)


@pytest.mark.slow
def test_train_ppo_quick_writes_a_loadable_model(tmp_path: Path) -> None:
    done = subprocess.run([sys.executable, "scripts/train_ppo.py", "--quick", "--out", str(tmp_path)],
                          cwd=ROOT, capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stderr
    for name in ("model.zip", "best_model.zip", "curve.csv", "learning_curve.png"):
        assert (tmp_path / name).exists(), name
    model = load_policy(tmp_path / "model.zip")
    action, _ = model.predict([5.0, -1.2, 1.0, 0.0, 0.0, 1.0, -2.7], deterministic=True)
    assert action.shape == (3,)
    assert saved_env(model) == saved_env(load_policy(tmp_path / "best_model.zip")) == ModelEnv("NetCatch-v0", 1)
    _assert_trained_with_the_yml_settings(model)


def _assert_trained_with_the_yml_settings(model) -> None:
    """The saved model's hyperparameters are ppo.yml's (read here with yaml, not agents.hyperparams)."""
    import yaml

    from agents.hyperparams import parse_policy_kwargs

    zoo = yaml.safe_load((ROOT / "agents" / "hyperparams" / "ppo.yml").read_text())["NetCatch-v0"]
    assert type(model.policy).__name__ == "ActorCriticPolicy" and zoo["policy"] == "MlpPolicy"
    for key in ("n_steps", "batch_size", "n_epochs", "learning_rate", "gamma", "gae_lambda", "ent_coef", "clip_range"):
        got = getattr(model, key)
        assert (got(1.0) if callable(got) else got) == zoo[key], key
    assert model.policy_kwargs == parse_policy_kwargs(zoo["policy_kwargs"])


@pytest.mark.slow
def test_shipped_model_scores_well_above_random() -> None:
    assert PRETRAINED.exists(), "agents/pretrained/ppo_netcatch.zip is missing"
    ppo = evaluate(load_policy(PRETRAINED), episodes=20, seed=777)
    random = evaluate(load_policy("random"), episodes=20, seed=777)
    assert ppo.low > random.high, (str(ppo), str(random))
    assert ppo.rate >= 0.5, str(ppo)


def test_ppo_settings_have_one_source_the_rl_zoo_yml() -> None:
    import yaml

    from agents import hyperparams
    from agents.training import PPO_PARAMS

    zoo = yaml.safe_load(hyperparams.PPO_YML.read_text())[hyperparams.ENV_ID]
    assert PPO_PARAMS is hyperparams.PPO_PARAMS  # training uses the yml's settings, not a copy
    assert set(zoo) - set(hyperparams.ZOO_ONLY) == set(PPO_PARAMS)  # every yml setting is used or rl_zoo3's own
    assert {"n_envs", "n_timesteps", "policy", "env_kwargs"} <= set(zoo)
    for key, value in PPO_PARAMS.items():
        if key != "policy_kwargs":
            assert zoo[key] == value, key
    assert PPO_PARAMS["policy_kwargs"] == hyperparams.parse_policy_kwargs(zoo["policy_kwargs"])
    assert hyperparams.ENV_KWARGS == zoo["env_kwargs"] == {"reward_mode": "shaped"}
    assert hyperparams.POLICY == zoo["policy"]
    assert hyperparams.rllib_training() == {name: zoo[key] for key, name in hyperparams.RLLIB_NAMES.items()}


def test_ppo_settings_accepted_by_sb3_and_rllib() -> None:
    import inspect

    from stable_baselines3 import PPO

    from agents import hyperparams

    assert set(hyperparams.PPO_PARAMS) <= set(inspect.signature(PPO).parameters)
    text = (ROOT / "agents" / "rllib_training.py").read_text()
    assert "rllib_training()" in text and "ENV_KWARGS" in text
    try:
        from ray.rllib.algorithms.ppo import PPOConfig
    except ImportError:
        return  # the rllib extra is not installed
    config = PPOConfig().training(**hyperparams.rllib_training())
    for name, value in hyperparams.rllib_training().items():
        assert getattr(config, name) == value, name


@pytest.mark.parametrize("text", ["__import__('os').system('true')", "dict(net_arch=open('x'))",
                                  "dict(**{'a': 1})", "dict([64])", "list(net_arch=[64])"])
def test_policy_kwargs_are_parsed_not_evaluated(text: str) -> None:
    from agents.hyperparams import parse_policy_kwargs

    with pytest.raises(ValueError):
        parse_policy_kwargs(text)
    assert parse_policy_kwargs("dict(net_arch=[64, 64], log_std_init=-0.5)") == {"net_arch": [64, 64],
                                                                                  "log_std_init": -0.5}


def test_frame_stack_policy_sees_what_vec_frame_stack_gives_the_model() -> None:
    """Acting in one plain env, FrameStackPolicy hands the model exactly the stacked
    observations SB3's VecFrameStack gave it in training, across an episode boundary."""
    from stable_baselines3.common.vec_env import DummyVecEnv, VecFrameStack

    from agents.policies import FrameStackPolicy
    from netgym.envs import NetCatchEnv

    class Recorder:
        def __init__(self) -> None:
            self.seen: list[np.ndarray] = []

        def predict(self, observation, deterministic=True):
            self.seen.append(np.array(observation))
            return np.zeros(3, dtype=np.float32), None

    venv = VecFrameStack(DummyVecEnv([lambda: NetCatchEnv(balls_per_episode=2, feedback=True)]), 3)
    venv.seed(5)
    stacked = venv.reset()[0]
    env = NetCatchEnv(balls_per_episode=2, feedback=True)
    obs, _ = env.reset(seed=5)
    recorder = Recorder()
    policy, start, rng = FrameStackPolicy(recorder, 3), True, np.random.default_rng(0)
    for _ in range(4):  # two episodes
        action, _ = policy.predict(obs, episode_start=np.array([start]))
        assert np.array_equal(recorder.seen[-1], stacked)
        action = rng.uniform(-1, 1, 3).astype(np.float32)
        obs, _, done, _, _ = env.step(action)
        stacked = venv.step(action[None])[0][0]
        start = done
        if done:
            obs, _ = env.reset()
    assert np.count_nonzero(recorder.seen[2][:-obs.size]) == 0  # a new episode's stack starts from zeros


def test_shipped_models_say_which_env_they_act_in() -> None:
    env_id, policy = policy_in_env(PRETRAINED_WINDY_STACKED)
    assert env_id == "NetCatchWindy-v0" and isinstance(policy, FrameStackPolicy) and policy.n_stack == 5
    assert saved_env(load_policy(PRETRAINED)) == ModelEnv("NetCatch-v0", 1)
    with pytest.raises(EnvMismatchError, match=r"trained on NetCatchWindy-v0 with 5 observations stacked.*"
                                               r"NetCatchGoal-v0's have shape \(7,\)"):
        policy_in_env(PRETRAINED_WINDY_STACKED, "NetCatchGoal-v0")


@pytest.mark.parametrize(("size", "found"), [(7, ModelEnv("NetCatch-v0")), (14, ModelEnv("NetCatch-v0", 2)),
                                             (11, "NetCatchWindy-v0, NetCatchRandomized-v1"),
                                             (55, "NetCatchWindy-v0 with 5 observations stacked, "
                                                  "NetCatchRandomized-v1 with 5")])
def test_a_model_saved_without_its_env_is_matched_by_its_observations(size: int, found: ModelEnv | str) -> None:
    """The default env where it fits; ids whose observations it reads alike are named, not guessed."""
    from types import SimpleNamespace

    from gymnasium import spaces

    model = SimpleNamespace(observation_space=spaces.Box(-1.0, 1.0, (size,), np.float32))
    if isinstance(found, ModelEnv):
        assert model_env(model) == found
    else:
        with pytest.raises(EnvMismatchError, match=f"fit {found}.*name the env it was trained on"):
            model_env(model)
    with pytest.raises(EnvMismatchError, match="saved without its env id"):
        model_env(SimpleNamespace(observation_space=spaces.Box(-1.0, 1.0, (13,), np.float32)))


def test_training_progress_estimates_its_end_once_and_shows_the_latest_evaluation() -> None:
    """The bar's total (and so its ETA) is the steps the run will have made when it ends,
    estimated once after the warm-up and then kept: a 2-minute budget at 100 steps/s ends a
    200,000-step run at 12,000 steps; a run that overtakes the estimate is estimated again. The
    latest evaluation's capture rate shows as soon as it is measured."""
    import io
    from types import SimpleNamespace

    from agents.run_progress import WARM_UP_S, RunProgress

    clock, stream, rate = [0.0], io.StringIO(), [None]
    progress = RunProgress(budget_s=120.0, training_seconds=lambda: clock[0], stream=stream,
                           latest_rate=lambda: rate[0])
    progress.model = SimpleNamespace(num_timesteps=0)
    progress.on_training_start({"total_timesteps": 200_000}, {})
    progress.model.num_timesteps, clock[0] = 500, WARM_UP_S / 2  # warming up: nothing estimated yet
    progress.on_step()
    assert progress.bar.total == 200_000 and "caught" not in stream.getvalue()
    progress.model.num_timesteps, clock[0], rate[0] = 3_000, 30.0, 0.25
    progress.on_step()
    assert progress.bar.total == 12_000 and progress.bar.n == 3_000
    progress.model.num_timesteps, clock[0], rate[0] = 4_000, 45.0, 0.5  # slower now: the estimate stays
    progress.on_step()
    progress.bar.refresh()
    assert progress.bar.total == 12_000 and "last evaluation: 50.0% caught" in stream.getvalue()
    progress.model.num_timesteps, clock[0] = 150_000, 60.0  # past the estimate: estimated again
    progress.on_step()
    assert progress.bar.total == 200_000
    progress.on_training_end()
    assert progress.bar.total == progress.bar.n == 150_000 and "150k/150k" in stream.getvalue()


def test_a_training_worker_says_when_its_environment_is_ready(capsys: pytest.CaptureFixture) -> None:
    from agents.training import ReadyLine

    env = object()
    assert ReadyLine(time.time() - 12.4)(env) is env
    assert capsys.readouterr().err == f"environment worker {os.getpid()} ready after 12 s\n"


def test_a_recurrent_ppo_model_loads_by_the_name_it_was_saved_with_and_acts_with_its_memory(tmp_path: Path) -> None:
    """sb3-contrib's RecurrentPPO (the baselines' ``rppo``): saved with its env recorded, loaded
    with no other argument, and evaluated with its LSTM state carried through each episode."""
    from sb3_contrib import RecurrentPPO
    from stable_baselines3.common.env_util import make_vec_env

    from agents.model_env import record_env

    env = make_vec_env("NetCatchWindy-v0", n_envs=2, seed=0)
    model = RecurrentPPO("MlpLstmPolicy", env, n_steps=8, batch_size=16, seed=0, device="cpu",
                         policy_kwargs={"lstm_hidden_size": 8})
    record_env(model, "NetCatchWindy-v0")
    model.learn(16)
    model.save(tmp_path / "rppo.zip")
    env_id, policy = policy_in_env(tmp_path / "rppo.zip")
    assert env_id == "NetCatchWindy-v0" and type(policy).__name__ == "RecurrentPPO"
    rate = evaluate(policy, episodes=2, seed=0, env_id=env_id)
    assert rate.throws == 10 and len(rate.by_throw) == 5
