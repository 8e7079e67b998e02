"""The tables of convergence through contact, from its result file
(``docs/results/contact_convergence.json``, written by ``scripts/contact_convergence.py``)."""

from __future__ import annotations

import math
from collections.abc import Mapping
from pathlib import Path
from typing import Any

from netgym.bench.accuracy.contact_convergence import PHASES, flagged, summary
from netgym.bench.results import read_results
from netgym.bench.settings import DEFAULT


def _error(value: float, mark: bool) -> str:
    if math.isnan(value):
        return "-"
    return f"{value:.1e}{' *' if mark else ''}"


def _slope(value: float) -> str:
    return "-" if math.isnan(value) else f"{value:.2f}"


def _monotone(slope: Mapping[str, Any]) -> str:
    if math.isnan(slope["slope"]):
        return "-"  # nothing the reference resolves
    return "yes" if slope["monotone"] else "no"


def strike_table(strike: Mapping[str, Any]) -> str:
    """The report's strike: each integrator and dt's largest ball error by phase (``*``: within
    ten times the reference's self-difference there) and its wall time."""
    lines = ["| integrator | dt (ms) | " + " | ".join(f"{p} (m)" for p in PHASES) + " | wall s per simulated s |",
             "|---|---:|" + "---:|" * (len(PHASES) + 1)]
    for row in strike["rows"]:
        if row["diverged"]:
            lines.append(f"| {row['integrator']} | {1e3 * row['dt']:.4g} | " + "diverged | " * len(PHASES) + "- |")
            continue
        cells = [_error(row["errors"][p], flagged(row["errors"][p], strike["self_difference"][p])) for p in PHASES]
        lines.append(f"| {row['integrator']} | {1e3 * row['dt']:.4g} | " + " | ".join(cells)
                     + f" | {row['wall_per_sim_s']:.3g} |")
    return "\n".join(lines)


def slope_table(one: Mapping[str, Any], many: Mapping[str, Any]) -> str:
    """Fitted slopes by integrator and phase (over the errors the reference resolves): on the
    report's strike (``one``) and on the ensemble's medians (``many``), over every dt and over
    the finest three; ``monotone``: the ensemble's medians fall with each halving."""
    lines = ["| integrator | phase | slope, the strike | slope, ensemble median | finest three, ensemble | "
             "monotone (ensemble) |", "|---|---|---:|---:|---:|---|"]
    for a, b in zip(one["slopes"], many["slopes"]):
        lines.append(f"| {a['integrator']} | {a['phase']} | {_slope(a['slope'])} | {_slope(b['slope'])} | "
                     f"{_slope(b['finest_three'])} | {_monotone(b)} |")
    return "\n".join(lines)


def ensemble_table(many: Mapping[str, Any]) -> str:
    """The ensemble's errors by phase: median / 90th percentile (m), with the share of strikes
    flagged where any is."""
    lines = ["| integrator | dt (ms) | strikes | " + " | ".join(f"{p}: median / p90 (m)" for p in PHASES) + " |",
             "|---|---:|---:|" + "---|" * len(PHASES)]
    for row in many["rows"]:
        cells = []
        for p in PHASES:
            cell = row[p]
            if cell is None:
                cells.append("diverged")
                continue
            share = f" ({100 * cell['flagged']:.0f}% *)" if cell["flagged"] else ""
            cells.append(f"{_error(cell['median'], False)} / {_error(cell['p90'], False)}{share}")
        lines.append(f"| {row['integrator']} | {1e3 * row['dt']:.4g} | {row['strikes']} | " + " | ".join(cells) + " |")
    return "\n".join(lines)


def default_cost(many: Mapping[str, Any]) -> str:
    """A sentence: the default setting's (:data:`~netgym.bench.settings.DEFAULT`) ensemble errors
    by phase and wall time, or an empty string if the ladders do not hold it."""
    found = [row for row in many["rows"] if (row["integrator"], row["dt"]) == DEFAULT and row["strikes"]]
    if not found:
        return ""
    row = found[0]
    phases = "; ".join(f"{p} {_error(row[p]['median'], False)} m (p90 {_error(row[p]['p90'], False)})" for p in PHASES)
    return (f"The default, {DEFAULT[0]} at {1e3 * DEFAULT[1]:g} ms, over the ensemble (median): {phases}; "
            f"{row['wall_per_sim_s']:.3g} wall s per simulated s.")


def block(path: Path, flags: str = "") -> str:
    """Every table of the result file at ``path`` with the reference's self-difference and the
    source line, or how to make the file (the script's ``flags`` before its ``--results``)."""
    if not path.is_file():
        return f"Not measured yet: `python scripts/contact_convergence.py {flags}--results docs/results/{path.name}`."
    record = read_results(path)
    figures = record["figures"]
    strike, many = figures["strike"], summary(figures["ensemble"] or [figures["strike"]])
    reference = ", ".join(f"{p} {strike['self_difference'][p]:.1e} m" for p in PHASES)
    spread = ", ".join(f"{p} {many['self_difference'][p]['median']:.1e} / {many['self_difference'][p]['max']:.1e} m"
                       for p in PHASES)
    done = "" if figures["complete"] else f" (partial: {many['strikes']} of {figures['ensemble_size']} done)"
    return "\n\n".join([
        f"The report's strike (first contact at {1e3 * strike['contact_time']:.0f} ms). Reference: RK4 at "
        f"{1e6 * strike['reference_dt']:.2f} us; against itself at half the step it differs by: {reference}. "
        "`*`: the error is within ten times that (it measures the reference as much as the method).",
        strike_table(strike),
        f"Fitted slopes (log error against log dt). Ensemble: {many['strikes']} strikes{done}, launch points "
        f"within {1e2 * figures['offset']:.0f} cm of the strike's; the reference's self-difference, median / max "
        f"over them: {spread}.",
        slope_table(summary([strike]), many),
        ensemble_table(many),
        *filter(None, [default_cost(many)]),
        f"Source: `docs/results/{path.name}`, written by `{record['command']}` ({record['written']}, "
        f"{record['machine']}; {figures['strike_seconds']} s simulated a strike, the ball sampled every "
        f"{1e3 * figures['sample']:g} ms)."])
