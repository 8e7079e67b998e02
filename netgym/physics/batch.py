"""Carry out the plans of many simulators of one scene together.

Each simulator's plan (:meth:`Simulator.throw_plan`) keeps its own decisions; whenever plans
ask for integration, all the requests are integrated in one parallel numba call
(:func:`netgym.physics.stepping.advance_batch`) over padded copies of the states. Results are
identical to running each plan alone with :meth:`Simulator.run`.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from netgym.errors import SimulationDivergedError
from netgym.physics import stepping
from netgym.physics.integrators import WORK_SLOTS
from netgym.physics.simulator import Plan, Simulator


class BatchRunner:
    """Runs plans of simulators sharing one scene, integrating their requests in parallel."""

    def __init__(self) -> None:
        self._buffers: dict[str, np.ndarray] = {}

    def _buffer(self, name: str, shape: tuple[int, ...], dtype: type = np.float64) -> np.ndarray:
        buf = self._buffers.get(name)
        if buf is None or buf.shape != shape:
            buf = self._buffers[name] = np.zeros(shape, dtype=dtype)
        return buf

    def run(self, sims: list[Simulator], plans: list[Plan]) -> list[Any]:
        """Drive ``plans[i]`` on ``sims[i]`` until all are done; returns their results."""
        results: list[Any] = [None] * len(plans)
        requests: dict[int, tuple[int, int, float]] = {}
        for i, plan in enumerate(plans):
            self._resume(i, plan, None, requests, results)
        while requests:
            pending = [i for i, (n, _, _) in requests.items() if n > 0]
            failures = self._integrate([sims[i] for i in pending], [requests[i] for i in pending]) if pending else {}
            for i in list(requests):
                error = failures.get(pending.index(i)) if i in pending else None
                self._resume(i, plans[i], error, requests, results)
        return results

    @staticmethod
    def _resume(i: int, plan: Plan, error: Exception | None, requests: dict, results: list) -> None:
        try:
            requests[i] = plan.throw(error) if error is not None else next(plan)
        except StopIteration as stop:
            requests.pop(i, None)
            results[i] = stop.value

    def _integrate(self, sims: list[Simulator], requests: list[tuple[int, int, float]]) -> dict[int, Exception]:
        """Integrate each simulator's request in one parallel call; returns errors by position."""
        integrator, dt = requests[0][1], requests[0][2]
        if any((r[1], r[2]) != (integrator, dt) for r in requests):
            raise ValueError("batched simulators must share one integrator and dt")
        model, sim_cfg = sims[0].model, sims[0].config.simulation
        count = len(sims)
        n_bodies = np.array([s.state.x.shape[0] for s in sims], dtype=np.int64)
        rows = int(n_bodies.max())
        x = self._buffer("x", (count, rows, 3))
        v = self._buffer("v", (count, rows, 3))
        inv_mass = self._buffer("inv_mass", (count, rows))
        entered = self._buffer("entered", (count, rows - model.n_net), np.int8)
        work = self._buffer("work", (count, WORK_SLOTS, rows, 3))
        coef = self._buffer("coef", (count, max(model.n_springs, 1), 5))
        stats = np.array([s.stats for s in sims])
        befores = []
        for e, s in enumerate(sims):
            befores.append(s.begin_advance())
            n = n_bodies[e]
            x[e, :n], v[e, :n], inv_mass[e, :n] = s.state.x, s.state.v, s.state.inv_mass
            entered[e, :n - model.n_net] = s.state.entered
        status = np.zeros(count, dtype=np.int64)
        steps = np.array([r[0] for r in requests], dtype=np.int64)
        stepping.advance_batch(
            x, v, inv_mass, entered, n_bodies, steps, model.n_net, model.springs, model.spring_params,
            model.segments, model.poles, model.contact, model.restitution_threshold, model.gravity,
            model.drag, model.ball_radius, model.opening, integrator, dt, sim_cfg.max_ball_travel,
            sim_cfg.cg_tolerance, sim_cfg.cg_max_iterations, sim_cfg.divergence_speed, work, coef, stats, status)
        failures: dict[int, Exception] = {}
        for e, s in enumerate(sims):
            n = n_bodies[e]
            s.state.x[:], s.state.v[:] = x[e, :n], v[e, :n]
            s.state.entered[:] = entered[e, :n - model.n_net]
            s.stats[:] = stats[e]
            try:
                s.end_advance(int(status[e]), befores[e], int(steps[e]), integrator, dt)
            except SimulationDivergedError as error:
                failures[e] = error
        return failures
