"""The fast path (closed-form flight, sleeping net, early decisions) against full simulation
from launch to the time limit, on 1000 seeded throws into the default scene."""

from __future__ import annotations

import pytest

from netgym.bench.fast_path import compare, summarise
from netgym.bench.throws import sample_throws


@pytest.mark.slow
def test_fast_path_agrees_with_full_simulation_on_1000_throws() -> None:
    outcomes = compare("basket", sample_throws("basket", 1000, seed=2024), workers=2)
    summary = summarise(outcomes)
    print(summary)
    assert summary["throws"] == 1000
    assert 0.2 < summary["captured"] < 0.8  # the sample mixes captures and misses
    assert summary["agreement"] >= 0.995
    assert summary["fast_throws_per_s"] > summary["full_throws_per_s"]


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
