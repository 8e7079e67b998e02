"""The baselines' report, from the result files under an output folder alone.

:func:`write_report` assembles it: the statistics (:mod:`agents.baselines.analysis`, computed
once per set of records with rliable and stored beside them as ``stats.json``), the figures
(:mod:`agents.baselines.figures`) and every table (:mod:`agents.baselines.tables`), in
``report.md``.
"""

from __future__ import annotations

from pathlib import Path

from agents.baselines.analysis import load_cells, statistics, write_statistics
from agents.baselines.figures import write_figures
from agents.baselines.tables import aggregates, by_throw, improvement, matrix, protocol, table


def write_report(out: Path, reps: int | None = None) -> Path:
    """Write ``out/report.md`` (every table), ``out/stats.json`` (the statistics, for the docs'
    quoted tables) and the figures from the result files under ``out``; returns the report's
    path. ``reps``: the bootstraps' resamples (default rliable's)."""
    cells = load_cells(out)
    stats = statistics(cells, reps)
    write_statistics(out, stats)
    figures = write_figures(cells, out, reps)
    images = "\n\n".join(f"![{name.removesuffix('.png')}]({name})" for name in figures)
    throws = "".join(f"### {env_id}\n\n{by_throw(cells, env_id, stats)}\n\n" for env_id in stats["by_throw"])
    report = out / "report.md"
    report.write_text(f"# Baselines\n\n## Capture rate\n\n{matrix(cells, stats)}\n\n## Probability of improvement\n\n"
                      f"{improvement(cells, stats)}\n\n## Figures\n\n{images}\n\n## Aggregates\n\n"
                      f"{aggregates(cells, stats)}\n\n## Every cell\n\n{table(cells, stats)}\n\n## By throw\n\n{throws}"
                      f"## Protocol\n\n{protocol(cells, stats)}\n")
    return report
