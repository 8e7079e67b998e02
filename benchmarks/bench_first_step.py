"""The first step of NetCatch-v0 from an empty numba cache, in a fresh process: imports,
``gym.make``, ``reset`` and one ``step``, every kernel it needs compiled; then the next step,
aimed at the net (it compiles the balls' contacts). Slow: about a minute, measured once."""

from __future__ import annotations

import math
import tempfile


class FirstStepFromEmptyCache:
    """Wall seconds from an empty cache: to the first step, and the next one, aimed at the net."""


    unit = "s"
    timeout = 900

    def setup_cache(self) -> tuple[float, float]:
        try:
            from agents.bench.first_step import first_step
        except ImportError:
            return math.nan, math.nan  # this tree has no first-step timing (asv passes no None on to setup)
        with tempfile.TemporaryDirectory(prefix="netgym-asv-numba-") as cache:
            first = first_step("NetCatch-v0", cache)
        return first.seconds, first.aimed_seconds

    def setup(self, figures: tuple[float, float]) -> None:
        if math.isnan(figures[0]):
            raise NotImplementedError("this tree has no first-step timing (agents.bench.first_step)")

    def track_first_step_seconds(self, figures: tuple[float, float]) -> float:
        return figures[0]

    def track_next_aimed_step_seconds(self, figures: tuple[float, float]) -> float:
        return figures[1]
