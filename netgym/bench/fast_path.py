"""The fast path (closed-form flight, sleeping net, early decision) against full simulation
from launch to the time limit: each throw starts from the empty net at rest and is simulated
both ways, with the outcomes and the wall time of each."""

from __future__ import annotations

import multiprocessing
import time
from concurrent.futures import ProcessPoolExecutor
from dataclasses import dataclass

from netgym.bench.throws import Throw
from netgym.physics.simulator import Simulator

CASES = {  # label: scene and overrides of the fast-path comparisons the benchmarks print
    "basket": ("basket", None),
    "goal": ("goal", None),
    "goal, held": ("goal", {"capture_rule": "held"}),
}


@dataclass(frozen=True)
class Outcome:
    """One throw simulated both ways."""

    fast_captured: bool
    full_captured: bool
    fast_seconds: float
    full_seconds: float
    touched: bool  # the fast path had to integrate (the ball came near the net or poles)


def _simulate(args: tuple[str, dict | None, list[Throw]]) -> list[Outcome]:
    scene, overrides, throws = args
    sim = Simulator(scene, overrides)
    out = []
    for position, velocity in throws:
        sim.reset()
        start = time.perf_counter()
        fast = sim.throw(position, velocity)
        fast_seconds = time.perf_counter() - start
        sim.reset()
        start = time.perf_counter()
        full = sim.throw(position, velocity, fast=False)
        out.append(Outcome(fast.captured, full.captured, fast_seconds, time.perf_counter() - start, fast.substeps > 0))
    return out


def compare(scene: str, throws: list[Throw], workers: int = 1, overrides: dict | None = None) -> list[Outcome]:
    """Simulate every throw fast and fully, on ``workers`` processes (forked after compiling),
    in the scene with ``overrides`` (e.g. ``{"capture_rule": "held"}``)."""
    Simulator(scene, overrides).throw(*throws[0])  # compile and settle before forking
    if workers == 1:
        return _simulate((scene, overrides, throws))
    chunks = [(scene, overrides, throws[i::workers]) for i in range(workers)]
    with ProcessPoolExecutor(workers, mp_context=multiprocessing.get_context("fork")) as pool:
        parts = list(pool.map(_simulate, chunks))
    return [o for part in parts for o in part]


def summarise(outcomes: list[Outcome]) -> dict[str, float]:
    """Agreement and throughput figures of a comparison."""
    n = len(outcomes)
    touched = [o for o in outcomes if o.touched]
    return {
        "throws": n,
        "agreement": sum(o.fast_captured == o.full_captured for o in outcomes) / n,
        "captured": sum(o.full_captured for o in outcomes) / n,
        "fast_throws_per_s": n / sum(o.fast_seconds for o in outcomes),
        "full_throws_per_s": n / sum(o.full_seconds for o in outcomes),
        "touching": len(touched),
        "fast_touching_throws_per_s": len(touched) / max(sum(o.fast_seconds for o in touched), 1e-12),
    }
