"""The fast path (closed-form flight, sleeping net, early decisions) against full simulation
from launch to the time limit, on seeded throws into both scenes under both capture rules.

Simulating the 1,120 throws fully takes about 8 minutes on 2 cores, so the full simulation's
results are stored in ``tests/golden/full_simulation.json``: the fast path runs on every throw
each time and is held to them, and a sample of the throws is simulated fully again each time and
must reproduce its stored result bit for bit (outcome, reason, time, final position), so that no
change to the physics leaves a stale reference behind. After a change that is meant to alter
results, regenerate the file deliberately and say so in the commit::

    NETGYM_WRITE_GOLDEN=1 python -m pytest tests/physics/test_fast_path.py
"""

from __future__ import annotations

import dataclasses
import json
import os
from pathlib import Path

import numpy as np
import pytest

from netgym.bench.accuracy.fast_path import Throw, compare, summarise, throw_each
from netgym.bench.throws import sample_throws
from netgym.physics.simulator import Simulator
from netgym.physics.throw import ThrowResult, throw

STORED = Path(__file__).parents[1] / "golden" / "full_simulation.json"
WRITE = os.environ.get("NETGYM_WRITE_GOLDEN") == "1"

# name: (scene, overrides, throws, seed, least agreement, throws simulated fully again each run)
CASES = {
    "basket": ("basket", None, 1000, 2024, 0.995, 8),
    "goal-line": ("goal", {"capture_rule": "line"}, 60, 5, 0.99, 1),
    "goal-held": ("goal", {"capture_rule": "held"}, 60, 5, 0.99, 1),
}


def _throw_record(throw: Throw) -> list[str]:
    return [float(c).hex() for part in throw for c in part]


def _result_record(result: ThrowResult) -> dict:
    """What is stored of a full simulation: exact text of its floats (``float.hex``)."""
    return {"captured": bool(result.captured), "reason": str(result.reason), "time": float(result.time).hex(),
            "final_position": [float(c).hex() for c in result.final_position]}


def _stored(name: str) -> dict:
    if WRITE:
        scene, overrides, count, seed, _, _ = CASES[name]
        throws = sample_throws(scene, count, seed)
        case = {"throws": [_throw_record(t) for t in throws],
                "full": [_result_record(r) for r in throw_each(scene, throws, 2, overrides, fast=False)]}
        stored = json.loads(STORED.read_text()) if STORED.exists() else {}
        STORED.write_text(json.dumps({**stored, name: case}, indent=0) + "\n")
    return json.loads(STORED.read_text())[name]


Case = tuple[str, list[Throw], dict, list[bool]]


@pytest.fixture(scope="module", params=list(CASES))
def case(request: pytest.FixtureRequest) -> Case:
    """A case's name, its throws (checked against the stored ones), its stored record and the
    fast path's outcome of each throw (run once for the tests of the case)."""
    name = request.param
    scene, overrides, count, seed, _, _ = CASES[name]
    throws = sample_throws(scene, count, seed)
    stored = _stored(name)
    assert [_throw_record(t) for t in throws] == stored["throws"], (
        f"sample_throws({scene!r}, {count}, seed={seed}) no longer draws the stored throws; regenerate "
        f"{STORED.name} (see this module's docstring)")
    return name, throws, stored, [r.captured for r in throw_each(scene, throws, 1, overrides)]


def test_fast_path_agrees_with_the_full_simulation(case: Case) -> None:
    name, _, stored, fast = case
    least = CASES[name][4]
    full = [r["captured"] for r in stored["full"]]
    captured = sum(full) / len(full)
    agreement = sum(f == g for f, g in zip(fast, full)) / len(full)
    print(f"{name}: {len(full)} throws, {captured:.1%} captured, agreement {agreement:.2%}")
    assert 0.2 < captured < 0.9  # the sample mixes captures and misses
    assert agreement >= least


@pytest.mark.slow
def test_the_stored_full_simulation_is_reproduced(case: Case) -> None:
    """Evenly spaced throws, and every throw on which the fast path disagrees, simulated fully
    again: each must reproduce its stored result exactly."""
    name, throws, stored, fast = case
    scene, overrides, count, _, _, again = CASES[name]
    chosen = sorted(set(range(0, count, count // again))
                    | {k for k, captured in enumerate(fast) if captured != stored["full"][k]["captured"]})
    results = throw_each(scene, [throws[k] for k in chosen], 2, overrides, fast=False)
    for k, result in zip(chosen, results):
        assert _result_record(result) == stored["full"][k], (
            f"{name} throw {k}: the full simulation no longer gives the stored result; if that is meant, "
            f"regenerate {STORED.name} (see this module's docstring)")


def test_a_changed_result_is_caught() -> None:
    """The record compared above holds every float exactly: one ulp of the final position differs."""
    result = throw(Simulator("basket"), *sample_throws("basket", 1, seed=2024)[0])
    nudged = dataclasses.replace(result, final_position=np.nextafter(result.final_position, np.inf))
    assert _result_record(nudged) != _result_record(result)


@pytest.mark.slow
def test_a_reference_at_the_scenes_own_step_is_the_full_simulation_throw_for_throw() -> None:
    """The reference runs the same scene, overrides included (here the ``held`` rule: the fifth
    throw is a goal under ``line`` but comes back out, a miss under ``held``), only at its own
    step: at the scene's step it must be the full simulation itself."""
    throws = sample_throws("goal", 5, seed=3)
    outcomes = compare("goal", throws, overrides={"capture_rule": "held"}, reference_dt=0.0005)
    assert [o.reference_captured for o in outcomes] == [o.full_captured for o in outcomes]
    assert any(o.full_captured for o in outcomes) and not outcomes[4].full_captured
    summary = summarise(outcomes)
    assert summary["full_vs_reference"] == 1.0 and summary["fast_vs_reference"] == summary["agreement"]
    assert "fast_vs_reference" not in summarise(compare("goal", throws[:1]))  # no reference asked for
