"""Label placement of the outcome-accuracy figure."""

from __future__ import annotations

import math

import numpy as np

from netgym.bench.plots import LABEL_HALF_WIDTH, LABEL_OFFSETS, _label_levels


def test_labels_on_one_level_never_overlap_and_spread_points_share_the_first() -> None:
    rng = np.random.default_rng(0)
    for _ in range(200):
        speeds = list(10.0 ** rng.uniform(1.0, 3.0, int(rng.integers(1, 5))))
        levels = _label_levels(speeds)
        assert all(0 <= level < len(LABEL_OFFSETS) for level in levels)
        for level in set(levels):
            xs = sorted(math.log10(s) for s, n in zip(speeds, levels) if n == level)
            assert all(b - a >= 2 * LABEL_HALF_WIDTH - 1e-12 for a, b in zip(xs, xs[1:]))
    assert _label_levels([10.0, 100.0, 1000.0]) == [0, 0, 0]
    assert _label_levels([100.0, 105.0, 110.0]) == [0, 1, 2]
