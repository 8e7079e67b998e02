"""The paragraph the README and the docs quote from the first-step result file
(``scripts/first_step_time.py --results docs/results/first_step.json``): the ranges measured."""

from __future__ import annotations

from pathlib import Path

from agents.bench.first_step import latest_runs
from netgym.bench.results import read_results


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

    return (f"The first run compiles the simulator's numba kernels as it needs them and says so on stderr, with a "
            f"count of the kernels compiled: from an empty cache, the first step of {figures['env']} (imports, "
            f"`gym.make`, `reset`, one `step`) took {span('cold', 'seconds')} s, and the first throw to reach the "
            f"net {span('cold', 'aimed_seconds')} s more (it compiles the balls' contacts); later runs load the "
            f"kernels from numba's cache: {span('warm', 'seconds')} s to the first step (`docs/results/{path.name}`: "
            f"{len(runs)} runs at load {_span([run['load_1min'] for run in runs])} on {figures['cpus']} cores, "
            f"{record['machine']}; `{record['command']}`).")
