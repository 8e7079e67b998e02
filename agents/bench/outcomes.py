"""Outcome accuracy: per (integrator, dt), the fraction of seeded throws whose capture outcome
matches a fine reference, against throws per second (fast path, one core)."""

from __future__ import annotations

import time

from netgym.bench.settings import outcome_sweeps
from netgym.bench.throws import sample_throws
from netgym.errors import SimulationDivergedError
from netgym.physics.simulator import Simulator
from netgym.physics.throw import throw


def outcome_accuracy(count: int, quick: bool = False) -> list[dict]:
    """Per (integrator, dt) of :func:`~netgym.bench.settings.outcome_sweeps`: agreement of
    capture outcomes with the reference, and throws/s."""
    throws = sample_throws("basket", count, seed=99)

    def outcomes(integrator: str, dt: float) -> tuple[list[bool], float]:
        sim = Simulator("basket", {"simulation.integrator": integrator, "simulation.dt": dt}, check_stability=False)
        throw(sim, *throws[0])
        captured, wall = [], 0.0
        for position, velocity in throws:
            sim.reset()
            start = time.perf_counter()
            try:
                captured.append(throw(sim, position, velocity).captured)
            except SimulationDivergedError:
                captured.append(None)
            wall += time.perf_counter() - start
        return captured, count / wall

    reference, _ = outcomes("rk4", 1e-4)
    rows = []
    for integrator, dts in outcome_sweeps(quick).items():
        for dt in dts:
            got, rate = outcomes(integrator, dt)
            agree = sum(g == r for g, r in zip(got, reference)) / count
            rows.append({"integrator": integrator, "dt": dt, "agreement": agree, "throws_per_s": rate,
                         "diverged": sum(g is None for g in got)})
    return rows
