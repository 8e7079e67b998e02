"""The baselines' table and figures, from the result files under the output folder alone:
per algorithm and id the interquartile mean of the final capture rate over seeds with its 95%
stratified bootstrap interval, raw and normalised (random 0, informed oracle 1); per algorithm the
normalised IQM over all its ids; learning curves (IQM and interval against environment steps)
and a performance profile."""

from __future__ import annotations

from collections import defaultdict
from pathlib import Path
from typing import Any

import numpy as np

from agents.baselines.grid import ALGORITHMS, BUDGETS, REFERENCES
from agents.baselines.stats import bootstrap_ci, iqm, normalise, performance_profile
from netgym.bench.results import read_results

Cells = dict[tuple[str, str], list[dict[str, Any]]]
PANELS_A_ROW = 4
"""Columns of the figure's grid of panels (one an id, then the performance profile)."""
REFERENCE_COLOURS = {"random": "gray", "blind": "black", "oracle": "green"}
"""The reference runs' lines in every panel."""
FEEDBACK_IDS = ("NetCatchWindy-v0", "NetCatchRandomized-v1")
"""The tasks whose later throws can use the feedback of the earlier ones: their rates by throw."""


def load_cells(out: Path) -> Cells:
    """Every complete result under ``out``, grouped by (algorithm, env id), seeds in order."""
    cells: Cells = defaultdict(list)
    for path in sorted(out.glob("*/*/seed_*.json")):
        record = read_results(path)["figures"]
        cells[record["algorithm"], record["env_id"]].append(record)
    return {key: sorted(records, key=lambda r: r["seed"]) for key, records in cells.items()}


def _rates(records: list[dict[str, Any]]) -> np.ndarray:
    return np.array([record["final"]["rate"] for record in records])


def normalised(cells: Cells) -> dict[tuple[str, str], np.ndarray]:
    """The learners' final capture rates of each cell, normalised by the id's references."""
    refs = {(algo, env_id): _rates(records)[0] for (algo, env_id), records in cells.items() if algo in REFERENCES}
    return {(algo, env_id): normalise(_rates(records), refs["random", env_id], refs["oracle", env_id])
            for (algo, env_id), records in cells.items()
            if algo not in REFERENCES and ("random", env_id) in refs and ("oracle", env_id) in refs}


def _interval(scores: np.ndarray, scale: float = 100.0, unit: str = "%") -> str:
    """IQM and 95% interval: rates in percent to 0.1, normalised scores (no unit) to 0.01."""
    low, high = bootstrap_ci(scores)
    digits = 1 if unit else 2
    return f"{scale * iqm(scores):.{digits}f}{unit} [{scale * low:.{digits}f}, {scale * high:.{digits}f}]"


def table(cells: Cells) -> str:
    """The markdown table: one row per (algorithm, id) with its budget, seeds, IQM capture rate
    and normalised IQM with 95% intervals, and the median wall-clock of a run; then the
    references, then each algorithm's normalised IQM over its ids (stratified over ids)."""
    scaled = normalised(cells)
    lines = ["| algorithm | env id | budget (steps) | seeds | capture rate, IQM [95% CI] | normalised IQM [95% CI] "
             "| minutes a run (median) |", "|---|---|---:|---:|---:|---:|---:|"]
    for (algo, env_id), records in sorted(cells.items(), key=lambda item: (item[0][0] in REFERENCES, item[0])):
        norm = _interval(scaled[algo, env_id], 1.0, "") if (algo, env_id) in scaled else "-"
        wall = np.median([record["wall_s"] for record in records]) / 60
        lines.append(f"| {algo} | {env_id} | {records[0]['budget']:,} | {len(records)} | "
                     f"{_interval(_rates(records))} | {norm} | {wall:.1f} |")
    by_algo: dict[str, list[np.ndarray]] = defaultdict(list)
    for (algo, _), scores in sorted(scaled.items()):
        by_algo[algo].append(scores)
    lines += ["", "| algorithm | ids | normalised IQM over ids [95% stratified CI] |", "|---|---:|---:|"]
    for algo, columns in by_algo.items():
        if len({len(c) for c in columns}) == 1:  # stratified resampling needs a seed count common to the ids
            lines.append(f"| {algo} | {len(columns)} | {_interval(np.stack(columns, axis=1), 1.0, '')} |")
    return "\n".join(lines)


def learners(cells: Cells) -> list[str]:
    """The algorithms of ``cells`` that learn (references left out), in the grid's order."""
    return [algo for algo in ALGORITHMS if any(a == algo for a, _ in cells)]


def table_ids(cells: Cells) -> list[str]:
    """The env ids of ``cells`` that some learner ran on, in the grid's order."""
    return [env_id for env_id in BUDGETS if any(e == env_id and a not in REFERENCES for a, e in cells)]


def matrix(cells: Cells) -> str:
    """The markdown table a reader looks at first: one row per algorithm, one column per id, each
    cell the IQM capture rate over seeds with its 95% interval and the number of seeds (the best
    of each id, and any tied with it, in bold); then the references' rates (one run each: they do
    not learn)."""
    ids = table_ids(cells)
    best = best_learners(cells)
    lines = ["| algorithm | " + " | ".join(ids) + " |", "|---|" + "---:|" * len(ids)]
    for algo in learners(cells):
        row = []
        for env_id in ids:
            records = cells.get((algo, env_id))
            text = f"{_interval(_rates(records))} (n={len(records)})" if records else "-"
            row.append(f"**{text}**" if algo in best.get(env_id, ()) else text)
        lines.append(f"| {algo} | " + " | ".join(row) + " |")
    for reference in REFERENCES:
        rates = [cells.get((reference, env_id)) for env_id in ids]
        lines.append(f"| *{reference}* | " + " | ".join(f"{100 * _rates(r)[0]:.1f}%" if r else "-" for r in rates)
                     + " |")
    return "\n".join(lines)


def by_throw(cells: Cells, env_id: str) -> str:
    """The markdown table of ``env_id``'s capture rate by throw index within the episode: per
    algorithm (then reference) whose runs counted it, the IQM over those runs of each throw's
    rate, and of the rate over every throw but the first (the throws that can use the feedback
    of the ones before). Runs from before the count was recorded are left out (``n`` says how
    many count)."""
    counted = {}
    for algo in [*learners(cells), *REFERENCES]:
        finals = [r["final"] for r in cells.get((algo, env_id), []) if r["final"].get("by_throw")]
        if finals:
            counted[algo] = np.array([_throw_rates(final) for final in finals])  # (runs, throws)
    if not counted:
        return f"No run on {env_id} counted its captures by throw yet."
    throws = min(rates.shape[1] for rates in counted.values())
    lines = ["| algorithm | n | " + " | ".join(f"throw {k + 1}" for k in range(throws)) + f" | throws 2-{throws} |",
             "|---|---:|" + "---:|" * (throws + 1)]
    for algo, rates in counted.items():
        per_throw = " | ".join(f"{100 * iqm(rates[:, k]):.1f}%" for k in range(throws))
        lines.append(f"| {algo} | {len(rates)} | {per_throw} | {100 * iqm(rates[:, 1:throws].mean(axis=1)):.1f}% |")
    return "\n".join(lines)


def _throw_rates(final: dict[str, Any]) -> np.ndarray:
    """A run's capture rate by throw index, from its final evaluation's counts (empty if it has
    none)."""
    return np.asarray(final.get("by_throw") or [], dtype=np.float64) / final["episodes"]


def shipped(results: Path, models: dict[str, str]) -> str:
    """The markdown table of the shipped models ``models`` (file name -> run, as
    :data:`agents.policies.SHIPPED_BASELINES`), each with its run's budget and final evaluation
    from its result file under ``results``: the capture rate and, on tasks with feedback, throw 1
    and the rest."""
    lines = ["| agents/pretrained/ | env id | algorithm, seed | budget (steps) | capture rate (held-out episodes) "
             "| throw 1 | later throws |", "|---|---|---|---:|---:|---:|---:|"]
    for name, run in models.items():
        record = read_results(results / f"{run}.json")["figures"]
        final, rates = record["final"], _throw_rates(record["final"])
        first, later = ("-", "-") if len(rates) < 2 else (f"{100 * rates[0]:.1f}%", f"{100 * rates[1:].mean():.1f}%")
        lines.append(f"| `{name}` | {record['env_id']} | {record['algorithm']}, seed {record['seed']} | "
                     f"{record['budget']:,} | {100 * final['rate']:.1f}% | {first} | {later} |")
    return "\n".join(lines)


def best_learners(cells: Cells) -> dict[str, list[str]]:
    """Per env id, the learners with the highest IQM capture rate over their seeds (ties: more
    seeds, then the higher mean; learners equal in all three are all named, in the grid's order)."""
    scores: dict[str, dict[str, tuple]] = defaultdict(dict)
    for (algo, env_id), records in cells.items():
        if algo not in REFERENCES:
            rates = _rates(records)
            scores[env_id][algo] = (iqm(rates), len(records), float(np.mean(rates)))
    return {env_id: [algo for algo in ALGORITHMS if by_algo.get(algo) == max(by_algo.values())]
            for env_id, by_algo in scores.items()}


def best_line(cells: Cells, env_id: str) -> str:
    """One sentence naming ``env_id``'s best learner(s): the IQM capture rate, interval, seeds and
    budget; or that no learner has run on it."""
    best = best_learners(cells).get(env_id)
    if best is None:
        return "none trained yet"
    records = cells[best[0], env_id]
    return (f"{', '.join(best)}{' (tied)' if len(best) > 1 else ''}: {_interval(_rates(records))} IQM over "
            f"{len(records)} seeds at {records[0]['budget']:,} steps")


def protocol(cells: Cells) -> str:
    """The protocol as the result files record it: per id the budget, the learners' seeds and the
    held-out evaluation; then the runs' machines, package versions and the compute they cost."""
    ids = table_ids(cells)
    lines = ["| env id | budget (env steps) | seeds a learner | final evaluation (deterministic) | "
             "learning curve |", "|---|---:|---:|---|---|"]
    for env_id in ids:
        runs = [records for (algo, e), records in cells.items() if e == env_id and algo not in REFERENCES]
        first = runs[0][0]
        fewest, most = min(len(records) for records in runs), max(len(records) for records in runs)
        lines.append(f"| {env_id} | {first['budget']:,} | {most if fewest == most else f'{fewest}-{most}'} | "
                     f"{first['final']['episodes']} episodes seeded from {first['final']['seed']} | "
                     f"{len(first['curve']['points'])} points, {first['curve']['episodes']} episodes each |")
    records = [record for runs in cells.values() for record in runs]
    versions = {name: sorted({str(r["versions"].get(name)) for r in records})
                for name in ("stable-baselines3", "sb3-contrib", "torch", "gymnasium", "numba")}
    started = sorted(r["started"] for r in records)
    machines = sorted({r["machine"] for r in records})
    lines += ["", f"{len(records)} runs ({sum(len(r) for a, r in cells.items() if a[0] not in REFERENCES)} "
              f"learning), one process and one torch thread each, CPU only, on {' / '.join(machines)}; started "
              f"{started[0][:16].replace('T', ' ')} to {started[-1][:16].replace('T', ' ')} UTC. "
              f"Compute: {sum(r['cpu_s'] for r in records) / 3600:.1f} CPU hours, "
              f"{sum(r['wall_s'] for r in records) / 3600:.1f} hours of runs' wall-clock. Versions: "
              + ", ".join(f"{name} {' / '.join(found)}" for name, found in versions.items()) + "."]
    return "\n".join(lines)


def _curve(records: list[dict[str, Any]]) -> tuple[np.ndarray, np.ndarray]:
    """The seeds' curves on the first seed's evaluation steps: steps, rates (seeds x steps)."""
    steps = np.array([point[0] for point in records[0]["curve"]["points"]])
    rates = np.array([np.interp(steps, *np.array(r["curve"]["points"])[:, :2].T) for r in records])
    return steps, rates


def plot(cells: Cells, path: Path) -> None:
    """Learning curves (IQM over seeds and its 95% interval against environment steps), one panel
    an id, with the references as lines; the performance profile of the normalised scores."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    ids = sorted({env_id for algo, env_id in cells if algo not in REFERENCES})
    columns = min(PANELS_A_ROW, len(ids) + 1)
    rows = -(-(len(ids) + 1) // columns)
    fig, axes = plt.subplots(rows, columns, figsize=(4.0 * columns, 3.6 * rows), squeeze=False)
    panels = list(axes.flat)
    colours = {algo: f"C{k}" for k, algo in enumerate(ALGORITHMS)}
    for ax, env_id in zip(panels, ids):
        for (algo, cell_id), records in sorted(cells.items()):
            if cell_id != env_id:
                continue
            if algo in REFERENCES:
                ax.axhline(100 * _rates(records)[0], linestyle=":", color=REFERENCE_COLOURS[algo],
                           label=algo)
                continue
            steps, rates = _curve(records)
            bands = np.array([bootstrap_ci(rates[:, k], reps=500) for k in range(len(steps))])
            ax.plot(steps, 100 * iqm(rates, axis=0), color=colours[algo], label=f"{algo} (n={len(records)})")
            ax.fill_between(steps, 100 * bands[:, 0], 100 * bands[:, 1], color=colours[algo], alpha=0.2)
        ax.set(title=env_id, xlabel="environment steps", ylim=(0, 105))
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7, loc="lower right")
    for row in axes:
        row[0].set_ylabel("capture rate (%), IQM over seeds")
    profile = panels[len(ids)]
    for unused in panels[len(ids) + 1:]:
        unused.set_axis_off()
    thresholds = np.linspace(0.0, 1.05, 106)
    scaled = normalised(cells)
    for algo in sorted({algo for algo, _ in scaled}):
        scores = np.concatenate([s for (a, _), s in sorted(scaled.items()) if a == algo])
        profile.plot(thresholds, performance_profile(scores, thresholds), color=colours[algo], label=algo)
    profile.set(title="performance profile", xlabel="normalised score τ", ylabel="fraction of runs with score > τ",
                ylim=(0, 1.05))
    profile.grid(alpha=0.3)
    profile.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def write_report(out: Path) -> Path:
    """Write ``out/report.md`` (the table) and ``out/curves.png`` from the result files; returns
    the report's path."""
    cells = load_cells(out)
    plot(cells, out / "curves.png")
    report = out / "report.md"
    report.write_text(f"# Baselines\n\n{matrix(cells)}\n\n![learning curves and performance profile](curves.png)\n\n"
                      f"{table(cells)}\n\n## By throw\n\n"
                      + "".join(f"{env_id}:\n\n{by_throw(cells, env_id)}\n\n" for env_id in FEEDBACK_IDS)
                      + f"## Protocol\n\n{protocol(cells)}\n")
    return report
