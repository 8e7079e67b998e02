"""Convergence through contact: the work-precision strike (section 1 of the report) measured by
phase, against a reference validated against itself, over one strike and an ensemble of them.

Every run starts from the same settled net (one :class:`Simulator`, stepped with each
integrator and dt), so its errors are the integration's alone. The ball is sampled every
:data:`SAMPLE` seconds; its error in a phase is the largest distance to the reference's ball
over the samples of that phase: before the first contact, the first :data:`FIRST_CONTACT`
seconds after it, and the rest. The reference (RK4 at :data:`REFERENCE_DT`) is run again at
half its step; its self-difference in a phase is the same largest distance between the two,
and a row whose error is less than ten times that is flagged (it measures the reference as
much as the method). The first contact is the first sample where the reference's ball has left
its free flight. Slopes are least-squares fits of log error against log dt over a ladder of
halvings.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Iterable

import numpy as np

from netgym.bench.accuracy.work_precision import STRIKE, STRIKE_SECONDS
from netgym.errors import SimulationDivergedError
from netgym.physics.simulator import Simulator

SAMPLE = 2e-3                    # s between ball samples (every dt of the ladders divides it)
FIRST_CONTACT = 0.01             # s after the first contact that make the second phase
PHASES = ("before contact", "first 10 ms of contact", "the rest")
REFERENCE_DT = 2e-3 / 2 ** 9     # 3.9 us: RK4's reference
LADDER = tuple(2e-3 / 2 ** k for k in range(8))   # 2 ms .. 15.6 us, halving
LADDERS = {
    "explicit_euler": LADDER[3:],
    "symplectic_euler": LADDER[3:],
    "rk4": LADDER[1:],
    "implicit_euler": LADDER[:7],
    "imex_euler": LADDER,
}
"""The dt of each integrator (its stable ones; implicit Euler's finest left out for its cost)."""
QUICK_LADDERS = {integrator: dts[:2] for integrator, dts in LADDERS.items()}
RESULT_FILES = {"impulse": "contact_convergence.json", "compliant": "contact_convergence_compliant.json"}
"""The result file of each contact model's measurement, in ``docs/results``."""


def ladders_of(contact_model: str, quick: bool = False) -> dict[str, tuple[float, ...]]:
    """The integrators and steps measured with ``contact_model``: :data:`LADDERS` (or the
    quick ones), less implicit Euler, which the compliant model does not take."""
    ladders = QUICK_LADDERS if quick else LADDERS
    return {k: v for k, v in ladders.items() if contact_model == "impulse" or k != "implicit_euler"}
ENSEMBLE_OFFSET = 0.03           # m: the ensemble's launch points lie within this of the strike's
FLAG_FACTOR = 10.0               # a row's error below this many self-differences is flagged
ROUND_OFF = 1e-10                # m: errors below this are round-off, no slope is fitted to them


class Strike:
    """One launch into the settled basket, run with any integrator and dt from the same state."""

    def __init__(self, sim: Simulator, launch: tuple[np.ndarray, np.ndarray], seconds: float) -> None:
        self.sim, self.launch, self.seconds = sim, launch, seconds

    def balls(self, integrator: str, dt: float) -> tuple[np.ndarray, float]:
        """The ball's position every :data:`SAMPLE` seconds (samples, 3) and the wall seconds
        per simulated second of the stepping; raises :class:`SimulationDivergedError` if the
        run diverges."""
        sim, per_sample = self.sim, round(SAMPLE / dt)
        sim.reset()
        sim.launch_ball(*self.launch)
        samples, wall = [], 0.0
        for _ in range(round(self.seconds / SAMPLE)):
            start = time.perf_counter()
            sim.step(per_sample, integrator, dt)
            wall += time.perf_counter() - start
            samples.append(sim.ball_positions[0])
        return np.array(samples), wall / self.seconds

    def contact_sample(self, reference: np.ndarray) -> int:
        """Index of the first sample at which the reference's ball has left its free flight."""
        p, v = self.launch
        g = np.array([0.0, 0.0, self.sim.model.gravity])
        t = SAMPLE * np.arange(1, reference.shape[0] + 1)[:, None]
        free = p + v * t + 0.5 * g * t * t
        left = np.flatnonzero(np.linalg.norm(reference - free, axis=1) > 1e-9)
        return int(left[0]) if left.size else reference.shape[0]


def phase_errors(balls: np.ndarray, reference: np.ndarray, contact: int) -> dict[str, float]:
    """The largest ball distance to ``reference`` in each of :data:`PHASES` (NaN for a phase
    with no sample), ``contact`` the first sample after the first contact."""
    distance = np.linalg.norm(balls - reference, axis=1)
    after = contact + round(FIRST_CONTACT / SAMPLE)
    parts = (distance[:contact], distance[contact:after], distance[after:])
    return {phase: float(part.max()) if part.size else math.nan for phase, part in zip(PHASES, parts)}


def measure_strike(sim: Simulator, launch: tuple[np.ndarray, np.ndarray], ladders: dict[str, Iterable[float]],
                   seconds: float = STRIKE_SECONDS, reference_dt: float = REFERENCE_DT,
                   progress: Callable[[], None] = lambda: None) -> dict:
    """Every integrator and dt of ``ladders`` on one strike: errors by phase against RK4 at
    ``reference_dt``, that reference's self-difference (against itself at half the step), the
    first contact's time and each run's wall time. ``progress`` is called after each run."""
    one = Strike(sim, launch, seconds)
    reference, _ = one.balls("rk4", reference_dt)
    progress()
    half, _ = one.balls("rk4", reference_dt / 2)
    progress()
    contact = one.contact_sample(reference)
    rows = []
    for integrator, dts in ladders.items():
        for dt in dts:
            try:
                balls, wall = one.balls(integrator, dt)
                rows.append({"integrator": integrator, "dt": dt, "diverged": False, "wall_per_sim_s": wall,
                             "errors": phase_errors(balls, reference, contact)})
            except SimulationDivergedError:
                rows.append({"integrator": integrator, "dt": dt, "diverged": True})
            progress()
    return {"launch": [list(map(float, part)) for part in launch], "contact_time": SAMPLE * contact,
            "reference_dt": reference_dt, "self_difference": phase_errors(half, reference, contact), "rows": rows}


def warm_up(sim: Simulator, ladders: dict[str, Iterable[float]]) -> None:
    """Compile every integrator of ``ladders`` (a step of each at its first dt, with a ball in the
    scene) before anything is timed; the scene is reset after."""
    sim.reset()
    sim.launch_ball(*STRIKE)
    for integrator, dts in ladders.items():
        sim.step(1, integrator, next(iter(dts)))
    sim.reset()


def ensemble_launches(count: int, seed: int = 0) -> list[tuple[np.ndarray, np.ndarray]]:
    """``count`` launches of the strike's velocity from points drawn uniformly within
    :data:`ENSEMBLE_OFFSET` of its launch point (seeded)."""
    rng = np.random.default_rng(seed)
    launches = []
    while len(launches) < count:
        offset = rng.uniform(-ENSEMBLE_OFFSET, ENSEMBLE_OFFSET, 3)
        if np.linalg.norm(offset) <= ENSEMBLE_OFFSET:
            launches.append((STRIKE[0] + offset, STRIKE[1].copy()))
    return launches


def fitted_slope(dts: list[float], errors: list[float], floor: float = ROUND_OFF) -> float:
    """Least-squares slope of log error against log dt over the errors above ``floor`` (at
    least round-off, :data:`ROUND_OFF`); NaN with fewer than two of them."""
    floor = max(floor, ROUND_OFF)
    points = [(math.log(d), math.log(e)) for d, e in zip(dts, errors) if e > floor and math.isfinite(e)]
    if len(points) < 2:
        return math.nan
    x, y = np.array(points).T
    return float(np.polyfit(x, y, 1)[0])


def flagged(error: float, self_difference: float) -> bool:
    """True if ``error`` is within :data:`FLAG_FACTOR` of the reference's own self-difference."""
    return error < FLAG_FACTOR * self_difference


def summary(strikes: list[dict]) -> dict:
    """Per integrator, dt and phase over ``strikes`` (results of :func:`measure_strike` with the
    same ladders): the median and 90th percentile of the errors, the share of strikes whose row
    is flagged, the median wall time; the reference's self-difference, median and max over the
    strikes; per integrator and phase, the slope fitted to the medians above ten times the
    median self-difference (all of them, and the finest three such) and whether the medians
    fall with each halving."""
    rows: list[dict] = []
    for i, first in enumerate(strikes[0]["rows"]):
        runs = [(s["rows"][i], s["self_difference"]) for s in strikes if not s["rows"][i]["diverged"]]
        cell: dict = {"integrator": first["integrator"], "dt": first["dt"], "strikes": len(runs),
                      "wall_per_sim_s": float(np.median([r["wall_per_sim_s"] for r, _ in runs])) if runs else None}
        for phase in PHASES:
            errors = np.array([r["errors"][phase] for r, _ in runs])
            cell[phase] = None if not runs else {
                "median": float(np.median(errors)), "p90": float(np.percentile(errors, 90)),
                "flagged": float(np.mean([flagged(r["errors"][phase], d[phase]) for r, d in runs]))}
        rows.append(cell)
    reference = {phase: {"median": float(np.median([s["self_difference"][phase] for s in strikes])),
                         "max": float(np.max([s["self_difference"][phase] for s in strikes]))} for phase in PHASES}
    slopes = []
    for integrator in dict.fromkeys(row["integrator"] for row in rows):
        usable = [row for row in rows if row["integrator"] == integrator and row["strikes"]]
        for phase in PHASES:
            floor = FLAG_FACTOR * reference[phase]["median"]
            points = [(row["dt"], row[phase]["median"]) for row in usable]
            resolved = [(dt, e) for dt, e in points if e > max(floor, ROUND_OFF)]
            slopes.append({"integrator": integrator, "phase": phase,
                           "slope": fitted_slope(*_columns(points), floor),
                           "finest_three": fitted_slope(*_columns(resolved[-3:]), floor),
                           "monotone": all(b[1] < a[1] for a, b in zip(points, points[1:]))})
    return {"strikes": len(strikes), "rows": rows, "slopes": slopes, "self_difference": reference}


def _columns(points: list[tuple[float, float]]) -> tuple[list[float], list[float]]:
    return [p[0] for p in points], [p[1] for p in points]
