"""The two contact models on the same throws, each from the settled empty basket: each model's
fast path against its own full simulation, and the compliant model's against the impulse
default; and what a step of each costs at the same integrator and dt."""

from __future__ import annotations

import statistics
import time
from pathlib import Path
from typing import Any

import numpy as np

from netgym.bench.accuracy.fast_path import Throw, throw_each
from netgym.bench.results import read_results
from netgym.physics.simulator import Simulator

COMPLIANT = {"simulation.contact_model": "compliant"}
STEP_COST_CASES = (("imex_euler", 2e-3), ("rk4", 1e-3), ("symplectic_euler", 5e-4))
"""The (integrator, dt) pairs whose step the two models are timed at: the default, and the
steps at which RK4 and symplectic Euler are run."""
CREEP_SECONDS = 2.0
"""Simulated seconds over which a resting ball's creep is measured."""


def step_costs(rounds: int = 5, seconds: float = 1.0) -> dict[str, dict[str, float]]:
    """Wall time (us) of a step of each contact model at each of :data:`STEP_COST_CASES`, a ball
    resting on the basket's bottom (a contact on every step, the compliant model's worst
    case): the medians of ``rounds`` interleaved rounds of ``seconds`` simulated, and the ratio
    compliant / impulse; and how far (mm) that ball crept over the first :data:`CREEP_SECONDS`
    of the rounds (the first test of ``tests/physics/contacts/test_resting_contact.py``)."""
    sims = {}
    for integrator, dt in STEP_COST_CASES:
        for model in ("impulse", "compliant"):
            sim = Simulator("basket", {"simulation.integrator": integrator, "simulation.dt": dt,
                                       "simulation.contact_model": model})
            sim.launch_ball([0.3, 0.2, 1.5], [0.0, 0.0, 0.0])
            sim.step(round(3.0 / dt))  # dropped, bounced and settled; compiled before the clock
            sims[(integrator, model)] = sim
    settled = {key: sim.ball_positions[0].copy() for key, sim in sims.items()}
    times: dict[tuple[str, str], list[float]] = {key: [] for key in sims}
    creep = {}
    for done in range(rounds):
        for key, sim in sims.items():
            steps = round(seconds / sim.config.simulation.dt)
            start = time.perf_counter()
            sim.step(steps)
            times[key].append((time.perf_counter() - start) / steps)
            if key not in creep and (done + 1) * seconds >= CREEP_SECONDS - 1e-9:
                creep[key] = 1e3 * float(np.linalg.norm(sim.ball_positions[0] - settled[key]))
    out = {}
    for integrator, dt in STEP_COST_CASES:
        impulse, compliant = (statistics.median(times[(integrator, m)]) for m in ("impulse", "compliant"))
        out[f"{integrator} {dt * 1e3:g} ms"] = {"impulse_us": 1e6 * impulse, "compliant_us": 1e6 * compliant,
                                               "ratio": compliant / impulse,
                                               "impulse_creep_mm": creep[(integrator, "impulse")],
                                               "compliant_creep_mm": creep[(integrator, "compliant")]}
    return out


def model_agreement(throws: list[Throw], workers: int = 1, cost_rounds: int = 5) -> dict[str, Any]:
    """Outcomes of ``throws`` by each model's fast path and full simulation: the catches of
    each, the shares of equal outcomes, the seconds a throw each took, the throws whose outcomes
    differ between the models' full simulations, and :func:`step_costs` over ``cost_rounds``."""
    runs, seconds = {}, {}
    for label, overrides, fast in (("impulse_fast", None, True), ("impulse_full", None, False),
                                   ("compliant_fast", COMPLIANT, True), ("compliant_full", COMPLIANT, False)):
        throw_each("basket", throws[:4], 1, overrides, fast)  # compile before the clock starts (random and aimed)
        start = time.perf_counter()
        runs[label] = [r.captured for r in throw_each("basket", throws, workers, overrides, fast)]
        seconds[label] = (time.perf_counter() - start) * workers / len(throws)

    def agree(a: str, b: str) -> float:
        return sum(x == y for x, y in zip(runs[a], runs[b])) / len(throws)

    return {"throws": len(throws), "captured": {label: sum(r) for label, r in runs.items()},
            "agreement": {"compliant vs impulse fast": agree("compliant_full", "impulse_fast"),
                          "compliant vs impulse full": agree("compliant_full", "impulse_full"),
                          "impulse fast vs impulse full": agree("impulse_fast", "impulse_full"),
                          "compliant fast vs compliant full": agree("compliant_fast", "compliant_full")},
            "seconds_per_throw": seconds,
            "differ": [i for i, (a, b) in enumerate(zip(runs["compliant_full"], runs["impulse_full"])) if a != b],
            "step_costs": step_costs(cost_rounds), "cost_rounds": cost_rounds}


def block(path: Path) -> str:
    """The report's sentence on the two models' outcomes, from the result file at ``path``, or
    how to make it."""
    if not path.is_file():
        return f"Not measured yet: `python scripts/model_agreement.py --results docs/results/{path.name}`."
    record = read_results(path)
    f = record["figures"]
    agreement, captured, seconds = f["agreement"], f["captured"], f["seconds_per_throw"]
    costs = "; ".join(f"{case} {c['compliant_us']:.0f} us against {c['impulse_us']:.0f} us, {c['ratio']:.2f}x"
                      for case, c in f["step_costs"].items())
    creep = "; ".join(f"{case} {c['compliant_creep_mm']:.2f} mm (impulse {c['impulse_creep_mm']:.3f} mm)"
                      for case, c in f["step_costs"].items())
    return (f"Outcomes of {f['throws']} sampled basket throws, each from the settled empty net: the compliant "
            f"model's full simulation caught {captured['compliant_full']}, its fast path "
            f"{captured['compliant_fast']}, the impulse model's fast path {captured['impulse_fast']} and its full "
            f"simulation {captured['impulse_full']}; the compliant outcome equals the impulse default's on "
            f"{100 * agreement['compliant vs impulse fast']:.1f}% of them; each model's fast path its own full "
            f"simulation's on {100 * agreement['compliant fast vs compliant full']:.1f}% (compliant) and "
            f"{100 * agreement['impulse fast vs impulse full']:.1f}% (impulse). A throw took "
            f"{seconds['compliant_full']:.2f} s simulated fully with the compliant model and "
            f"{seconds['compliant_fast']:.3f} s by its fast path, {seconds['impulse_full']:.2f} s and "
            f"{seconds['impulse_fast']:.3f} s with the impulse model, one core. A step with a ball resting on the "
            f"basket's bottom, compliant against impulse at the same integrator and dt (medians of "
            f"{f['cost_rounds']} interleaved rounds): {costs}. How far that ball crept over {CREEP_SECONDS:g} s, compliant: {creep}. "
            f"Source: `docs/results/{path.name}`, written by `{record['command']}` "
            f"({record['written']}, {record['machine']}).")
