"""Golden episodes: whole multi-ball episodes on both scenes with all five integrators, a full
(no shortcut) episode and a rendered episode must reproduce, bit for bit, the results recorded
in ``tests/golden/episodes.json``: every observation, reward, outcome, simulated time, substep
count and a digest of the whole simulator state after each step.

The recorded actions are replayed, so the test needs no agent. After a change that is meant to
alter results, regenerate the file deliberately and say so in the commit::

    NETGYM_WRITE_GOLDEN=1 python -m pytest tests/envs/test_golden.py
"""

from __future__ import annotations

import hashlib
import json
import os
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from netgym.aim import BallisticAim
from netgym.envs import NetCatchEnv
from netgym.envs.observation import aim_at_centre

GOLDEN = Path(__file__).parents[1] / "golden" / "episodes.json"
WRITE = os.environ.get("NETGYM_WRITE_GOLDEN") == "1"
BALLS = 3

# (case name, env keyword arguments): both scenes, every integrator at a dt it is stable at
CASES = {
    f"{scene}-{integrator}": {"scene": scene, "integrator": integrator, "dt": dt}
    for scene in ("basket", "goal")
    for integrator, dt in (("imex_euler", 2e-3), ("symplectic_euler", 5e-4), ("explicit_euler", 5e-4),
                           ("rk4", 1e-3), ("implicit_euler", 5e-3))
}
CASES["basket-full"] = {"scene": "basket", "fast": False, "overrides": {"simulation.time_limit": 2.0}}
CASES["basket-frames"] = {"scene": "basket", "render_mode": "rgb_array_list"}


def _hex(values: Any) -> list[str]:
    """Exact text of float values (``float.hex``), so the comparison is bitwise."""
    return [float(x).hex() for x in np.ravel(np.asarray(values, dtype=np.float64))]


def _digest(*arrays: np.ndarray) -> str:
    h = hashlib.sha256()
    for a in arrays:
        h.update(np.ascontiguousarray(a).tobytes())
    return h.hexdigest()


def _state_digest(env: NetCatchEnv) -> str:
    s = env.sim.state
    return _digest(s.x, s.v, s.inv_mass, s.entered, np.array([s.time]))


def _step_record(obs: np.ndarray, reward: float, terminated: bool, info: dict, env: NetCatchEnv) -> dict:
    return {"obs": _hex(obs), "reward": float(reward).hex(), "terminated": bool(terminated),
            "captured": bool(info["captured"]), "reason": info["reason"], "sim_time": float(info["sim_time"]).hex(),
            "substeps": int(info["substeps"]), "final_position": _hex(info["final_position"]),
            "state": _state_digest(env)}


def _choose_actions(env: NetCatchEnv, obs: np.ndarray, rng: np.random.Generator, throw: int) -> np.ndarray:
    """Recording only: the ballistic aim's action through the opening's centre, with noise on
    the second throw and a random third, so that episodes load the net with caught balls and
    also miss."""
    if throw == BALLS - 1:
        return rng.uniform(-1, 1, 3).astype(np.float32)
    action = aim_at_centre(BallisticAim(env.scene), obs)
    if throw == 1:
        action = np.clip(action + rng.normal(0.0, 0.05, 3), -1, 1).astype(np.float32)
    return action


def _run_episode(kwargs: dict, actions: list[list[float]] | None) -> tuple[list[list[float]], list[dict]]:
    env = NetCatchEnv(balls_per_episode=BALLS, **kwargs)
    obs, _ = env.reset(seed=7)
    rng = np.random.default_rng(11)
    used, records = [], []
    for k in range(BALLS):
        action = _choose_actions(env, obs, rng, k) if actions is None else np.array(actions[k], dtype=np.float32)
        used.append([float(a) for a in action])
        obs, reward, terminated, _, info = env.step(action)
        record = _step_record(obs, reward, terminated, info, env)
        if env.render_mode == "rgb_array_list":
            frames = env.render()
            record["frames"] = len(frames)
            record["frames_digest"] = _digest(*frames)
        records.append(record)
    env.close()
    return used, records


def _golden() -> dict:
    if WRITE:
        return {}
    if not GOLDEN.is_file():
        pytest.fail(f"{GOLDEN} is missing; record it with NETGYM_WRITE_GOLDEN=1")
    return json.loads(GOLDEN.read_text())


def _store(name: str, entry: dict) -> None:
    data = json.loads(GOLDEN.read_text()) if GOLDEN.is_file() else {}
    data[name] = entry
    GOLDEN.parent.mkdir(exist_ok=True)
    GOLDEN.write_text(json.dumps(data, indent=1, sort_keys=True) + "\n")


def _compare(name: str, expected: list[dict], actual: list[dict]) -> None:
    assert len(actual) == len(expected)
    for k, (want, got) in enumerate(zip(expected, actual)):
        for key in want:
            assert got[key] == want[key], f"{name}, step {k}: {key} differs from the golden run"


@pytest.mark.parametrize("name", sorted(CASES))
def test_episode_is_bitwise_identical_to_the_golden_run(name: str) -> None:
    golden = _golden().get(name)
    if WRITE:
        actions, records = _run_episode(CASES[name], None)
        _store(name, {"actions": actions, "steps": records})
        return
    assert golden is not None, f"no golden record for {name}"
    _, records = _run_episode(CASES[name], golden["actions"])
    _compare(name, golden["steps"], records)


def test_golden_episodes_mix_captures_and_misses() -> None:
    """The recorded episodes exercise loaded nets: some throws are caught, some missed."""
    steps = [s for entry in _golden().values() for s in entry["steps"]]
    if WRITE:
        pytest.skip("recording")
    captured = sum(s["captured"] for s in steps)
    assert 0.3 * len(steps) < captured < len(steps)
