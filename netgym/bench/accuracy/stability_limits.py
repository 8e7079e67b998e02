"""Stability limits: the largest stable dt of each integrator by bisection, on the default and a
stiff scene, beside the linear-stability estimate."""

from __future__ import annotations

import math

import numpy as np

from netgym.config import INTEGRATORS
from netgym.errors import SimulationDivergedError
from netgym.physics.stability import stable_dt
from netgym.physics.simulator import Simulator


def _stable(integrator: str, dt: float, overrides: dict, seconds: float, sim_cache: dict) -> bool:
    key = tuple(sorted(overrides.items()))
    if key not in sim_cache:
        sim_cache[key] = Simulator("basket", {**overrides, "simulation.integrator": "implicit_euler",
                                              "simulation.dt": 5e-3})
    sim = sim_cache[key]
    sim.reset()
    rng = np.random.default_rng(0)
    sim.state.x[:] += rng.normal(0.0, 0.01, sim.state.x.shape) * (sim.state.inv_mass > 0)[:, None]
    try:
        sim.step(max(1, round(seconds / dt)), integrator=integrator, dt=dt)
    except SimulationDivergedError:
        return False
    return True


def stability_limits(quick: bool) -> list[dict]:
    """Largest stable dt per integrator by bisection (log scale), next to the linear estimate."""
    scenes = {"default (ks 1500, kd 50)": {},
              "stiff (ks 15000, kd 50)": {f"springs.{k}.ks": 15000.0 for k in ("structural", "shear", "bending")}}
    rows, cache = [], {}
    for label, overrides in scenes.items():
        modes = Simulator("basket", {**overrides, "simulation.integrator": "implicit_euler"}).modes
        for code, integrator in enumerate(INTEGRATORS):
            lo, hi = 1e-5, 5e-2
            if _stable(integrator, hi, overrides, 1.0, cache):
                found = hi
            else:
                for _ in range(5 if quick else 12):
                    mid = math.sqrt(lo * hi)
                    lo, hi = (mid, hi) if _stable(integrator, mid, overrides, 1.0, cache) else (lo, mid)
                found = lo
            rows.append({"scene": label, "integrator": integrator, "bisection": found,
                         "linear": stable_dt(code, modes), "omega": modes.omega, "damping": modes.damping})
    return rows
