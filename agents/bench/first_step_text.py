"""The paragraph the README and the docs quote from the first-step result file
(``scripts/first_step_time.py --results docs/results/first_step.json``): the ranges measured."""

from __future__ import annotations

from pathlib import Path

from agents.bench.first_step import latest_runs
from netgym.bench.results import RESULTS, read_results

TEMPLATE = RESULTS.parent / "_templates" / "first_step.md"
"""The paragraph's prose, its figures named placeholders."""


def _span(values: list[float]) -> str:
    """``low-high`` of ``values`` to 0.1, or the one value when they agree."""
    low, high = f"{min(values):.1f}", f"{max(values):.1f}"
    return low if low == high else f"{low}-{high}"


def block(path: Path) -> str:
    """What a first run waits for while the kernels compile and what later runs wait for, as the
    runs of the label written last in the result file at ``path`` measured them."""
    record = read_results(path)
    figures = record["figures"]
    runs = latest_runs(figures)

    def span(cache: str, key: str) -> str:
        return _span([run[cache][key] for run in runs])

    return TEMPLATE.read_text().strip().format(
        env=figures["env"], cold_seconds=span("cold", "seconds"), cold_aimed_seconds=span("cold", "aimed_seconds"),
        warm_seconds=span("warm", "seconds"), file=path.name, runs=len(runs),
        load=_span([run["load_1min"] for run in runs]), cpus=figures["cpus"], machine=record["machine"],
        command=record["command"])
