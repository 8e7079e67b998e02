"""The baselines' figures: the learning curves of each group of tasks and the performance profiles
of each common task set (:func:`write_figures`), 800 px wide, their bands rliable's.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from agents.baselines.cells import (Cells, final_rates, has_feedback, is_pixels, learners, set_name, set_scores,
                                    table_ids, task_sets)
from agents.baselines.grid import ALGORITHMS, REFERENCES
from agents.baselines.stats import PROFILE_REPS, iqm_intervals, profile_bands

FIGURE_WIDTH, FIGURE_DPI, FONT_PT = 7.6, 105, 10
"""Figures 800 px wide (shown about 1:1 in the docs' content column), their text at 10 pt."""
PANEL_HEIGHT = 2.5
"""Inches of one row of panels."""
LEGEND_COLUMNS = 7
"""Most entries in a row of a figure's legend (below its panels)."""
REFERENCE_STYLES = {"random": ":", "blind": "--", "oracle": "-."}
"""The reference runs' lines (black) in the learning curves."""


def curve_groups(cells: Cells) -> dict[str, list[str]]:
    """The tasks of each learning-curve figure: vector tasks without feedback, with feedback, on
    pixels (groups without a task left out)."""
    ids = table_ids(cells)
    groups = {"vector": [e for e in ids if not is_pixels(e) and not has_feedback(e)],
              "feedback": [e for e in ids if not is_pixels(e) and has_feedback(e)],
              "pixels": [e for e in ids if is_pixels(e)]}
    return {name: tasks for name, tasks in groups.items() if tasks}


def _curve(records: list[dict[str, Any]]) -> tuple[np.ndarray, np.ndarray]:
    """The seeds' curves on the first seed's evaluation steps: steps, rates (seeds x steps)."""
    steps = np.array([point[0] for point in records[0]["curve"]["points"]])
    rates = np.array([np.interp(steps, *np.array(r["curve"]["points"])[:, :2].T) for r in records])
    return steps, rates


def _colours() -> dict[str, str]:
    """Each algorithm's colour, the same in every figure."""
    return {algo: f"C{k}" for k, algo in enumerate(ALGORITHMS)}


def _figure(panels: int, legend_rows: int) -> tuple[Any, list[Any]]:
    """A figure :data:`FIGURE_WIDTH` wide with ``panels`` panels, two a row, room below for the legend."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    columns = min(2, panels)
    rows = -(-panels // columns)
    fig, axes = plt.subplots(rows, columns, figsize=(FIGURE_WIDTH, PANEL_HEIGHT * rows + 0.35 * legend_rows + 0.3),
                             squeeze=False, layout="constrained")
    for unused in list(axes.flat)[panels:]:
        unused.set_axis_off()
    return fig, list(axes.flat)[:panels]


def _save(fig: Any, path: Path) -> None:
    """The figure's legend below its panels (never over a curve), saved at :data:`FIGURE_DPI`."""
    import matplotlib.pyplot as plt

    handles: dict[str, Any] = {}
    for ax in fig.axes:
        for handle, label in zip(*ax.get_legend_handles_labels()):
            handles.setdefault(label, handle)
    if handles:
        rows = -(-len(handles) // LEGEND_COLUMNS)
        fig.legend(handles.values(), handles.keys(), loc="outside lower center", ncols=-(-len(handles) // rows),
                   frameon=False)
    fig.savefig(path, dpi=FIGURE_DPI)
    plt.close(fig)


def plot_curves(cells: Cells, tasks: list[str], path: Path, reps: int = PROFILE_REPS) -> None:
    """Learning curves of ``tasks``, a panel each: per learner the IQM capture rate over its seeds
    against environment steps with its 95% band (rliable, ``reps`` resamples), the references as
    black lines."""
    import matplotlib.pyplot as plt

    with plt.rc_context({"font.size": FONT_PT}):
        learned = {(a, e): _curve(records) for (a, e), records in cells.items()
                   if e in tasks and a not in REFERENCES and records[0]["curve"]["points"]}
        bands = iqm_intervals({(a, e, k): rates[:, k] for (a, e), (steps, rates) in learned.items()
                               for k in range(len(steps))}, reps)
        references = [name for name in REFERENCES if any((name, e) in cells for e in tasks)]
        fig, panels = _figure(len(tasks), -(-len({a for a, _ in learned} | set(references)) // LEGEND_COLUMNS))
        for ax, env_id in zip(panels, tasks):
            for algo in learners(cells):
                if (algo, env_id) not in learned:
                    continue
                steps, _ = learned[algo, env_id]
                estimates = np.array([[np.nan if v is None else 100 * v for v in bands[algo, env_id, k]]
                                      for k in range(len(steps))])
                ax.plot(steps, estimates[:, 0], color=_colours()[algo], label=algo)
                ax.fill_between(steps, estimates[:, 1], estimates[:, 2], color=_colours()[algo], alpha=0.2)
            for name in references:
                if (name, env_id) in cells:
                    ax.axhline(100 * final_rates(cells[name, env_id])[0], color="black", linewidth=1,
                               linestyle=REFERENCE_STYLES[name], label=name)
            ax.set(title=env_id, ylim=(0, 103), xlabel="environment steps")
            ax.xaxis.set_major_formatter(lambda value, _: f"{value / 1000:g}k" if value else "0")
            ax.grid(alpha=0.3)
        for ax in panels[::2]:
            ax.set_ylabel("capture rate (%)")
        _save(fig, path)


def plot_profiles(cells: Cells, path: Path, reps: int = PROFILE_REPS) -> None:
    """Performance profiles, a panel per common task set: per learner the fraction of its runs
    (every task of the set) whose normalised score is above each threshold, with rliable's 95%
    bands (``reps`` resamples)."""
    import matplotlib.pyplot as plt

    sets = task_sets(cells)
    scores = {(tasks, algo): matrix for tasks in sets for algo, (_, matrix) in set_scores(cells, tasks).items()}
    top = max(1.0, max(float(matrix.max()) for matrix in scores.values())) + 0.05
    thresholds = np.linspace(0.0, top, 106)
    profiles = profile_bands(scores, thresholds, reps)
    with plt.rc_context({"font.size": FONT_PT}):
        fig, panels = _figure(len(sets), -(-len({algo for _, algo in scores}) // LEGEND_COLUMNS))
        for ax, tasks in zip(panels, sets):
            for algo in learners(cells):
                if (tasks, algo) in profiles:
                    profile, low, high = profiles[tasks, algo]
                    ax.plot(thresholds, profile, color=_colours()[algo], label=algo)
                    ax.fill_between(thresholds, low, high, color=_colours()[algo], alpha=0.2)
            ax.set(title=set_name(tasks), ylim=(0, 1.03), xlabel="normalised score τ")
            ax.grid(alpha=0.3)
        for ax in panels[::2]:
            ax.set_ylabel("fraction of runs > τ")
        _save(fig, path)


def write_figures(cells: Cells, out: Path, reps: int | None = None) -> list[str]:
    """The learning curves of each group of tasks (``curves-GROUP.png``) and the performance
    profiles (``profiles.png``) under ``out``; returns their file names."""
    reps = min(reps or PROFILE_REPS, PROFILE_REPS)
    names = []
    for group, tasks in curve_groups(cells).items():
        plot_curves(cells, tasks, out / f"curves-{group}.png", reps)
        names.append(f"curves-{group}.png")
    if task_sets(cells):
        plot_profiles(cells, out / "profiles.png", reps)
        names.append("profiles.png")
    return names
