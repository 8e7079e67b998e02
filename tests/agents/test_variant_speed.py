"""The variants' speed table (agents/variant_speed.py): what its policies act on."""

from __future__ import annotations

import gymnasium as gym
import pytest

import netgym  # noqa: F401
from agents.variant_speed import SHIPPED, _Timing


def test_the_blind_oracle_aims_with_the_registered_scene_not_an_episodes_draw() -> None:
    timing = _Timing("NetCatchRandomized-v1", "oracle")   # has run its warm-up episode, which drew a scene
    registered = gym.make("NetCatchRandomized-v1").unwrapped.scene
    assert timing.env.unwrapped.scene != registered and timing.scene == registered


def test_each_id_is_also_timed_with_the_model_shipped_for_it() -> None:
    """The model-driven rows: each id acts with the model its card names, its recurrent state
    given back as the evaluation gives it, so the same seeded episodes catch the same balls; the
    row names that model."""
    pytest.importorskip("stable_baselines3")
    from agents.evaluation import evaluate
    from agents.policies import SHIPPED_FOR_ID, policy_in_env, shipped_model

    env_id = "NetCatchRandomized-v1"  # a recurrent model
    timing = _Timing(env_id, SHIPPED)
    timing.run_episodes(6, seed=5)
    row = timing.row(None)
    assert row.model == SHIPPED_FOR_ID[env_id] == "rppo_randomized_v1.zip" and row.throws == 30
    evaluated = evaluate(policy_in_env(shipped_model(env_id), env_id)[1], 6, seed=5, env_id=env_id)
    assert timing.caught == evaluated.captured
