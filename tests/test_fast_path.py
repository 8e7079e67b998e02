"""The fast path (closed-form flight, sleeping net, early decisions) against full simulation
from launch to the time limit, on 1000 seeded throws into the default scene."""

from __future__ import annotations

from netgym.bench.fast_path import compare, summarise
from netgym.bench.throws import sample_throws


def test_fast_path_agrees_with_full_simulation_on_1000_throws() -> None:
    outcomes = compare("basket", sample_throws("basket", 1000, seed=2024), workers=2)
    summary = summarise(outcomes)
    print(summary)
    assert summary["throws"] == 1000
    assert 0.2 < summary["captured"] < 0.8  # the sample mixes captures and misses
    assert summary["agreement"] >= 0.995
    assert summary["fast_throws_per_s"] > summary["full_throws_per_s"]
