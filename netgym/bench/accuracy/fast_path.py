"""The fast path (closed-form flight, sleeping net, early decision) against full simulation
from launch to the time limit: each throw starts from the empty net at rest and is simulated
both ways, with the outcomes and the wall time of each."""

from __future__ import annotations

import multiprocessing
import time
from collections.abc import Callable
from concurrent.futures import ProcessPoolExecutor
from dataclasses import dataclass

import numpy as np

from netgym.physics.simulator import Simulator
from netgym.physics.throw import ThrowResult, throw

Throw = tuple[np.ndarray, np.ndarray]  # (launch position, launch velocity)

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
    reference_captured: bool | None = None  # full simulation at the reference dt, when one was asked for


def _reference_overrides(overrides: dict | None, reference_dt: float) -> dict:
    """The reference's scene overrides: the comparison's own, at ``reference_dt``."""
    return {**(overrides or {}), "simulation.dt": reference_dt}


def _simulate(args: tuple[str, dict | None, float | None, list[Throw]]) -> list[Outcome]:
    scene, overrides, reference_dt, throws = args
    sim = Simulator(scene, overrides)
    fine = None if reference_dt is None else Simulator(scene, _reference_overrides(overrides, reference_dt))
    out = []
    for position, velocity in throws:
        sim.reset()
        start = time.perf_counter()
        fast = throw(sim, position, velocity)
        fast_seconds = time.perf_counter() - start
        sim.reset()
        start = time.perf_counter()
        full = throw(sim, position, velocity, fast=False)
        full_seconds = time.perf_counter() - start
        reference = None
        if fine is not None:
            fine.reset()
            reference = throw(fine, position, velocity, fast=False).captured
        out.append(Outcome(fast.captured, full.captured, fast_seconds, full_seconds, fast.substeps > 0, reference))
    return out


def _interleaved(work: Callable[[tuple], list], shared: tuple, throws: list[Throw], workers: int) -> list:
    """``work((*shared, throws))`` on ``workers`` processes (forked: compile and settle before),
    each taking every ``workers``-th throw; the results in the throws' order."""
    if workers == 1:
        return work((*shared, throws))
    chunks = [(*shared, throws[i::workers]) for i in range(workers)]
    with ProcessPoolExecutor(workers, mp_context=multiprocessing.get_context("fork")) as pool:
        parts = list(pool.map(work, chunks))
    ordered = [None] * len(throws)
    for i, part in enumerate(parts):
        ordered[i::workers] = part
    return ordered


def compare(scene: str, throws: list[Throw], workers: int = 1, overrides: dict | None = None,
            reference_dt: float | None = None) -> list[Outcome]:
    """Simulate every throw fast and fully, on ``workers`` processes (forked after compiling),
    in the scene with ``overrides`` (e.g. ``{"capture_rule": "held"}``); with ``reference_dt``,
    also fully at that (finer) step: how near the converged outcome each way comes."""
    throw(Simulator(scene, overrides), *throws[0])  # compile and settle before forking
    if reference_dt is not None:
        Simulator(scene, _reference_overrides(overrides, reference_dt))  # its net settles once, before forking
    return _interleaved(_simulate, (scene, overrides, reference_dt), throws, workers)


def _throw_each(args: tuple[str, dict | None, bool, list[Throw]]) -> list[ThrowResult]:
    scene, overrides, fast, throws = args
    sim = Simulator(scene, overrides)
    results = []
    for position, velocity in throws:
        sim.reset()
        results.append(throw(sim, position, velocity, fast))
    return results


def throw_each(scene: str, throws: list[Throw], workers: int = 1, overrides: dict | None = None,
               fast: bool = True) -> list[ThrowResult]:
    """Every throw from the settled empty net, by the fast path or (``fast=False``) simulated
    fully to the time limit, on ``workers`` processes."""
    throw(Simulator(scene, overrides), *throws[0], fast)  # compile and settle before forking
    return _interleaved(_throw_each, (scene, overrides, fast), throws, workers)


def summarise(outcomes: list[Outcome]) -> dict[str, float]:
    """Agreement and throughput figures of a comparison (with a reference: the fast path's and
    the full simulation's agreement with it too)."""
    n = len(outcomes)
    touched = [o for o in outcomes if o.touched]
    figures = {
        "throws": n,
        "agreement": sum(o.fast_captured == o.full_captured for o in outcomes) / n,
        "captured": sum(o.full_captured for o in outcomes) / n,
        "fast_throws_per_s": n / sum(o.fast_seconds for o in outcomes),
        "full_throws_per_s": n / sum(o.full_seconds for o in outcomes),
        "touching": len(touched),
        "fast_touching_throws_per_s": len(touched) / max(sum(o.fast_seconds for o in touched), 1e-12),
    }
    if all(o.reference_captured is not None for o in outcomes):
        figures["fast_vs_reference"] = sum(o.fast_captured == o.reference_captured for o in outcomes) / n
        figures["full_vs_reference"] = sum(o.full_captured == o.reference_captured for o in outcomes) / n
    return figures
