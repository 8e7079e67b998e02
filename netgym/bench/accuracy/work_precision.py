"""Work-precision: every integrator over a sweep of dt, error against a fine RK4 reference
versus wall time per simulated second, on the default scene with a ball striking the net."""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from netgym.bench.settings import REFERENCE, SWEEPS
from netgym.errors import InvalidArgumentError, SimulationDivergedError
from netgym.physics.simulator import Simulator

STRIKE = (np.array([0.3, 0.2, 2.4]), np.array([1.0, 0.5, -9.0]))  # a ball driven into the basket's bottom
STRIKE_SECONDS = 0.5
SAMPLE = 0.01  # s between ball samples (every dt of SWEEPS divides it)


@dataclass(frozen=True)
class Run:
    """A strike simulated with one (integrator, dt)."""

    integrator: str
    dt: float
    ball: np.ndarray      # (samples, 3) ball positions every SAMPLE seconds
    net: np.ndarray       # (n_net, 3) final net positions
    wall_per_sim_s: float


def strike(integrator: str, dt: float, seconds: float = STRIKE_SECONDS,
           launch: tuple[np.ndarray, np.ndarray] = STRIKE, sample: float = SAMPLE) -> Run:
    """Simulate the strike scenario (the ball from ``launch``, position and velocity), its ball
    sampled every ``sample`` seconds; time only the stepping (kernels compiled before)."""
    sim = Simulator("basket", {"simulation.integrator": integrator, "simulation.dt": dt}, check_stability=False)
    sim.step(1)  # compile outside the timed region
    sim.reset()
    sim.launch_ball(*launch)
    per_sample = round(sample / dt)
    if abs(per_sample * dt - sample) > 1e-9 * sample:
        raise InvalidArgumentError(f"dt = {dt:g} s does not divide the sampling interval {sample:g} s")
    samples, wall = [], 0.0
    for _ in range(round(seconds / sample)):
        start = time.perf_counter()
        sim.step(per_sample)
        wall += time.perf_counter() - start
        samples.append(sim.ball_positions[0])
    return Run(integrator, dt, np.array(samples), sim.state.x[: sim.model.n_net].copy(), wall / seconds)


def errors(run: Run, reference: Run) -> tuple[float, float]:
    """(RMS ball-position error over the throw, RMS net-position error at the end), metres."""
    ball = float(np.sqrt(np.mean(np.sum((run.ball - reference.ball) ** 2, axis=1))))
    net = float(np.sqrt(np.mean(np.sum((run.net - reference.net) ** 2, axis=1))))
    return ball, net


def work_precision(quick: bool, reference_setting: tuple[str, float] = REFERENCE) -> list[dict]:
    """Every integrator and dt of the sweep (its two largest dt and a tenth of the strike when
    ``quick``) against the reference (integrator, dt)."""
    reference = strike(*reference_setting, seconds=0.1 if quick else STRIKE_SECONDS)
    rows = []
    for integrator, dts in SWEEPS.items():
        for dt in (dts[-2:] if quick else dts):
            try:
                run = strike(integrator, dt, seconds=0.1 if quick else STRIKE_SECONDS)
            except SimulationDivergedError:
                rows.append({"integrator": integrator, "dt": dt, "diverged": True})
                continue
            ball, net = errors(run, reference)
            rows.append({"integrator": integrator, "dt": dt, "diverged": False, "ball_error": ball,
                         "net_error": net, "wall_per_sim_s": run.wall_per_sim_s})
    return rows

