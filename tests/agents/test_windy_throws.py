"""Capture rates by throw index (agents/evaluation.py's ``by_throw``) and the windy per-throw
study (agents/windy_throws.py, scripts/windy_per_throw.py): the counts against episodes run by
hand, the policies' rates by index against what they know, the aims of the first-throw search,
the search against the blind oracle, and the script's --quick run."""

from __future__ import annotations

import math
import subprocess
import sys
from pathlib import Path

import gymnasium as gym
import numpy as np
import pytest

from agents.evaluation import evaluate
from agents.oracle import AdaptiveOracle, BallisticOracle, InformedOracle
from agents.random_agent import RandomAgent
from agents.windy_throws import (BLIND_AIM, WINDY, AimedOracle, FirstThrowAim, SearchPlan, first_throw_rate,
                                 search_first_throw, windy_policies)
from netgym.bench.results import read_results
from netgym.envs import ObservationIndex

ROOT = Path(__file__).resolve().parents[2]


def _blind(env):
    return BallisticOracle(env.scene)


def test_by_throw_counts_the_captures_of_each_throw_index_as_episodes_run_by_hand() -> None:
    result = evaluate(_blind, 3, seed=40, env_id=WINDY)
    env = gym.make(WINDY, disable_env_checker=True)
    oracle = BallisticOracle(env.unwrapped.scene)
    by_hand = np.zeros(5, dtype=int)
    for episode in range(3):
        obs, _ = env.reset(seed=40 + episode)
        for k in range(5):
            obs, _, _, _, info = env.step(oracle.predict(obs)[0])
            by_hand[k] += int(info["captured"])
    assert list(result.by_throw) == by_hand.tolist()
    assert sum(result.by_throw) == result.captured and result.episodes == 3 and result.throws == 15
    assert result.rate_by_throw == pytest.approx(by_hand / 3)


def test_the_first_throw_fast_path_throws_the_first_throws_of_whole_episodes() -> None:
    whole = evaluate(_blind, 12, seed=60, env_id=WINDY)
    first = first_throw_rate(BLIND_AIM, 12, seed=60)
    assert first.by_throw == whole.by_throw[:1] and first.throws == first.episodes == 12


@pytest.mark.slow
def test_rates_by_throw_follow_what_each_policy_knows() -> None:
    informed = evaluate(InformedOracle, 10, seed=70, env_id=WINDY)
    random = evaluate(RandomAgent(0), 10, seed=70, env_id=WINDY)
    assert min(informed.rate_by_throw) > max(random.rate_by_throw), (informed, random)
    blind = evaluate(_blind, 20, seed=70, env_id=WINDY)
    adaptive = evaluate(lambda env: AdaptiveOracle(env.scene), 20, seed=70, env_id=WINDY)
    assert adaptive.by_throw[0] == blind.by_throw[0]  # nothing to adapt to yet: the blind oracle's throw
    later = sum(adaptive.by_throw[1:]) / (4 * adaptive.episodes)
    assert later > adaptive.rate_by_throw[0], adaptive  # the feedback of the throws before helps


@pytest.mark.parametrize("aim", [FirstThrowAim(60.0, 40.0, 0.4, -0.3), FirstThrowAim(50.0, 50.0, -0.25, 0.2)])
def test_an_aimed_oracle_crosses_the_opening_at_its_moved_aim_point_without_wind(aim: FirstThrowAim) -> None:
    env = gym.make(WINDY, disable_env_checker=True, wind=(0.0, 0.0), balls_per_episode=1)
    oracle = AimedOracle(env.unwrapped.scene, aim)
    for seed in range(3):
        obs, _ = env.reset(seed=seed)
        facing = math.atan2(-obs[ObservationIndex.BEARING_SIN], -obs[ObservationIndex.BEARING_COS])
        crossed, *_ = env.step(oracle.predict(obs)[0])
        offset = crossed[[ObservationIndex.LAST_OFFSET_U, ObservationIndex.LAST_OFFSET_W]]
        along = offset @ [math.cos(facing), math.sin(facing)]
        across = offset @ [-math.sin(facing), math.cos(facing)]
        assert (along, across) == pytest.approx((aim.along, aim.across), abs=0.02)


def test_the_blind_aim_is_the_blind_oracles() -> None:
    env = gym.make(WINDY, disable_env_checker=True)
    blind, aimed = BallisticOracle(env.unwrapped.scene), AimedOracle(env.unwrapped.scene, BLIND_AIM)
    for seed in range(3):
        obs, _ = env.reset(seed=seed)
        assert np.array_equal(blind.predict(obs)[0], aimed.predict(obs)[0])


@pytest.mark.slow
def test_the_search_finds_an_aim_at_least_as_good_as_the_blind_oracles_first_throw() -> None:
    plan = SearchPlan(episodes=30, seed=5, elevations=(45.0, 75.0), rounds=1)
    search = search_first_throw(plan, progress=False)
    blind = evaluate(_blind, plan.episodes, seed=plan.seed, env_id=WINDY).by_throw[0]
    assert search.tried[search.best] == max(search.tried.values()) >= blind
    assert first_throw_rate(search.best, plan.episodes, plan.seed).captured == search.tried[search.best]
    assert len(search.tried) <= plan.trials


@pytest.mark.slow
def test_windy_per_throw_quick_prints_the_table_and_writes_the_result_file(tmp_path: Path) -> None:
    results = tmp_path / "windy.json"
    done = subprocess.run([sys.executable, "scripts/windy_per_throw.py", "--quick", "--results", str(results)],
                          cwd=ROOT, capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stderr
    rows = [line.split("|")[1:-1] for line in done.stdout.splitlines() if line.startswith("| ")]
    assert [cell.strip() for cell in rows[0]] == ["policy", *(f"throw {k}" for k in range(1, 6)), "throws 2-5", "all"]
    record = read_results(results)
    figures = record["figures"]
    assert "windy_per_throw.py --quick" in record["command"]
    assert len(rows) == 1 + len(figures["rows"]) == 2 + len(windy_policies())  # header, policies, best fixed throw
    assert any(row["policy"].startswith("sac_asym sac_asym_windy.zip") for row in figures["rows"])
    assert all(sum(row["by_throw"]) == row["captured"] for row in figures["rows"])
    assert [cell.strip() for cell in rows[-1][2:]] == ["-"] * 6  # the best fixed first throw: throw 1 only
    assert figures["first_throw_search"]["best_captured"] >= figures["first_throw_search"]["blind_captured"]
