"""Simulator throughput on one thread: substeps per second and ns per spring per substep, per
integrator and scene, for the settled net alone (``net``) and for a ball driven into the net at
10 m/s and then resting in it (``impact``, all contacts live). Each figure is the best of
several timed runs, after a warm-up run that compiles the kernels."""

from __future__ import annotations

import time

from netgym.physics.simulator import Simulator

SETTINGS = {  # integrator -> dt used for the benchmark
    "explicit_euler": 5e-4,
    "symplectic_euler": 5e-4,
    "rk4": 1e-3,
    "implicit_euler": 5e-3,
    "imex_euler": 2e-3,
}
IMPACT = {  # scene -> (ball start, velocity): straight into the net bottom / back net
    "basket": ([0.0, 0.0, 2.0], [0.0, 0.0, -10.0]),
    "goal": ([0.2, 0.0, 1.0], [10.0, 0.0, 0.0]),
}


def _measure(sim: Simulator, seconds: float, repeats: int, with_ball: bool) -> tuple[float, float]:
    """Best (substeps per second, CG iterations per substep) over ``repeats`` runs."""
    steps = max(1, round(seconds / sim.config.simulation.dt))
    best, cg = 0.0, 0.0
    for _ in range(repeats):
        sim.reset()
        if with_ball:
            sim.launch_ball(*IMPACT[sim.config.name])
        substeps, iterations = sim.substeps, sim.cg_iterations
        start = time.perf_counter()
        sim.step(steps)
        wall = time.perf_counter() - start
        done = sim.substeps - substeps
        if done / wall > best:
            best, cg = done / wall, (sim.cg_iterations - iterations) / done
    return best, cg


def run(quick: bool) -> list[dict]:
    """Measure every (scene, integrator, workload); returns rows of figures."""
    seconds, repeats = (0.05, 1) if quick else (1.0, 3)
    rows = []
    for scene in ("basket", "goal"):
        for integrator, dt in SETTINGS.items():
            sim = Simulator(scene, {"simulation.integrator": integrator, "simulation.dt": dt})
            _measure(sim, 0.02, 1, True)  # warm-up: compile outside the timed region
            for workload in ("net", "impact"):
                rate, cg = _measure(sim, seconds, repeats, workload == "impact")
                rows.append({"scene": scene, "integrator": integrator, "dt": dt, "workload": workload,
                             "springs": sim.model.n_springs, "particles": sim.model.n_net,
                             "substeps_per_s": rate, "ns_per_spring": 1e9 / rate / sim.model.n_springs,
                             "cg_per_substep": cg})
    return rows


def to_markdown(rows: list[dict]) -> str:
    """The rows as a markdown table."""
    lines = ["| scene | integrator | dt (s) | workload | substeps/s | ns/spring/substep | CG it./substep |",
             "|---|---|---|---|---:|---:|---:|"]
    for r in rows:
        cg = f"{r['cg_per_substep']:.1f}" if r["integrator"] == "implicit_euler" else "-"
        lines.append(f"| {r['scene']} ({r['particles']} p, {r['springs']} s) | {r['integrator']} | {r['dt']:g} | "
                     f"{r['workload']} | {r['substeps_per_s']:,.0f} | {r['ns_per_spring']:.1f} | {cg} |")
    return "\n".join(lines)
