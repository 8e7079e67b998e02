"""The baselines' tables and figures, from the result files under an output folder alone.

:func:`statistics` computes, with rliable (:mod:`agents.baselines.stats`): per (learner, task)
cell the interquartile mean (IQM) of the final capture rate over the cell's seeds with its 95%
stratified bootstrap interval; per common task set (:func:`task_sets`) each learner's IQM and
optimality gap of the normalised score (random 0, informed oracle 1); per task the probability
that its leader improves on the runner-up and on every learner whose interval overlaps its; on
the tasks with feedback the IQM of each throw index. At rliable's 50000 resamples they take
minutes, so :func:`write_report` stores them beside the result files (:data:`STATS_FILE`, with
the digest of the records they come from) and :func:`load_cells` hands them on for as long as
the records are those. The references (random, blind, informed oracle) are one run each: their
intervals are Wilson's over their throws.

Tables fit the docs' content column (about 700 px at a page width of 1280 px): at most
:data:`COLUMNS_A_TABLE` columns of intervals beside the key column, one line each, and ids that
never break at their hyphens (:func:`nowrap`). Figures: the learning curves of each group of tasks
and the performance profiles of each common task set (:func:`write_figures`).
"""

from __future__ import annotations

import functools
import hashlib
import importlib.metadata
import json
from collections import Counter, defaultdict
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np
from rliable import metrics

import netgym
from agents.baselines.grid import ALGORITHMS, BUDGETS, REFERENCES, TRAIN_SEED_STRIDE
from agents.baselines.stats import (DEFAULT_REPS, IMPROVEMENT_REPS, PROFILE_REPS, SEED, Estimate, aggregate_intervals,
                                    improvement_intervals, iqm_intervals, normalise, profile_bands, wilson)
from agents.model_env import vector_counterpart
from netgym.bench.results import read_results

Cells = dict[tuple[str, str], list[dict[str, Any]]]
Stats = dict[str, Any]
"""What :func:`statistics` computes, as JSON reads it back."""
STATS_FILE = "stats.json"
"""The statistics of an output folder's result files, stored beside them by :func:`write_report`."""
COLUMNS_A_TABLE = 3
"""Columns of intervals a table shows beside its key column: with an id there, about 650 px, within
the docs' content column (about 700 px at a page width of 1280 px)."""
FIGURE_WIDTH, FIGURE_DPI, FONT_PT = 7.6, 105, 10
"""Figures 800 px wide (shown about 1:1 in the docs' content column), their text at 10 pt."""
PANEL_HEIGHT = 2.5
"""Inches of one row of panels."""
LEGEND_COLUMNS = 7
"""Most entries in a row of a figure's legend (below its panels)."""
REFERENCE_STYLES = {"random": ":", "blind": "--", "oracle": "-."}
"""The reference runs' lines (black) in the learning curves."""
_STORED: dict[tuple[str, int], Stats] = {}
"""Statistics already computed or read, by the digest of their records and their resamples."""


def load_cells(out: Path) -> Cells:
    """Every complete result under ``out``, grouped by (algorithm, env id), seeds in order; the
    statistics stored in ``out/stats.json`` are taken up if they are of these very records."""
    cells: Cells = defaultdict(list)
    for path in sorted(out.glob("*/*/seed_*.json")):
        record = read_results(path)["figures"]
        cells[record["algorithm"], record["env_id"]].append(record)
    cells = {key: sorted(records, key=lambda r: r["seed"]) for key, records in cells.items()}
    stored = out / STATS_FILE
    if stored.is_file():
        stats = json.loads(stored.read_text())
        if stats.get("digest") == digest(cells):
            _STORED[stats["digest"], stats["reps"]] = stats
    return cells


def digest(cells: Cells) -> str:
    """SHA-256 of every record of ``cells`` (canonical JSON): what their statistics depend on."""
    records = [cells[key] for key in sorted(cells)]
    return hashlib.sha256(json.dumps(records, sort_keys=True).encode()).hexdigest()


def nowrap(text: str) -> str:
    """``text`` that a table never breaks (ids break at their hyphens otherwise); copied, it
    stays plain ASCII."""
    return f'<span style="white-space:nowrap">{text}</span>'


@functools.cache
def is_pixels(env_id: str) -> bool:
    """Whether ``env_id`` observes images (its episodes run with vector observations elsewhere)."""
    return vector_counterpart(env_id)[0] != env_id


def has_feedback(env_id: str) -> bool:
    """Whether ``env_id``'s observations carry the feedback of the episode's earlier throws."""
    entry = netgym.ENVIRONMENTS.get(env_id)
    return bool(entry and entry.kwargs.get("feedback"))


def _rates(records: list[dict[str, Any]]) -> np.ndarray:
    """The runs' final capture rates."""
    return np.array([record["final"]["rate"] for record in records])


def learners(cells: Cells) -> list[str]:
    """The algorithms of ``cells`` that learn (references left out), in the grid's order."""
    return [algo for algo in ALGORITHMS if algo not in REFERENCES and any(a == algo for a, _ in cells)]


def table_ids(cells: Cells) -> list[str]:
    """The env ids of ``cells`` that some learner ran on, in the grid's order."""
    return [env_id for env_id in BUDGETS if any(e == env_id and a not in REFERENCES for a, e in cells)]


def bounds(cells: Cells, env_id: str) -> tuple[float, float] | None:
    """The rates of ``env_id``'s random policy and informed oracle (a normalised 0 and 1), if both ran."""
    if ("random", env_id) in cells and ("oracle", env_id) in cells:
        return float(_rates(cells["random", env_id])[0]), float(_rates(cells["oracle", env_id])[0])
    return None


def cell_key(algo: str, env_id: str) -> str:
    """A cell's key in the statistics: ``algo/env_id``."""
    return f"{algo}/{env_id}"


# ---------------------------------------------------------------- which learners, which tasks


def _rank_key(cells: Cells, algo: str, env_id: str) -> tuple[float, int, float]:
    """What ranks a learner on ``env_id``: its IQM capture rate over its seeds (rliable's), then
    how many seeds, then the mean rate."""
    rates = _rates(cells[algo, env_id])
    return float(metrics.aggregate_iqm(rates)), len(rates), float(np.mean(rates))


def ranking(cells: Cells, env_id: str) -> list[str]:
    """The learners on ``env_id`` from the highest IQM capture rate over their seeds down (ties:
    more seeds first, then the higher mean, then the grid's order)."""
    ran = [algo for algo in learners(cells) if (algo, env_id) in cells]
    return sorted(ran, key=lambda algo: tuple(-value for value in _rank_key(cells, algo, env_id)))


def best_learners(cells: Cells) -> dict[str, list[str]]:
    """Per env id, the learners with the highest IQM capture rate over their seeds (ties: more
    seeds, then the higher mean; learners equal in all three are all named, in the grid's order)."""
    best = {}
    for env_id in table_ids(cells):
        ranked = ranking(cells, env_id)
        top = _rank_key(cells, ranked[0], env_id)
        best[env_id] = [algo for algo in ranked if _rank_key(cells, algo, env_id) == top]
    return best


def task_sets(cells: Cells) -> list[tuple[str, ...]]:
    """The common task sets of the aggregates: each learner's tasks that have both references
    (pixel and vector tasks apart), each set once; vector sets first, larger sets first."""
    found: list[tuple[str, ...]] = []
    for algo in learners(cells):
        tasks = [env_id for env_id in table_ids(cells) if (algo, env_id) in cells and bounds(cells, env_id)]
        for pixels in (False, True):
            part = tuple(env_id for env_id in tasks if is_pixels(env_id) == pixels)
            if part and part not in found:
                found.append(part)
    return sorted(found, key=lambda tasks: (is_pixels(tasks[0]), -len(tasks)))


def set_name(tasks: tuple[str, ...] | list[str]) -> str:
    """A task set's name: its id if it has one task, else how many and of what kind."""
    if len(tasks) == 1:
        return tasks[0]
    kind = "pixel" if is_pixels(tasks[0]) else "feedback" if all(map(has_feedback, tasks)) else "vector"
    return f"{len(tasks)} {kind} tasks"


def set_scores(cells: Cells, tasks: tuple[str, ...]) -> dict[str, tuple[list[int], np.ndarray]]:
    """Per learner that ran every task of ``tasks``: the seeds all of them have and its normalised
    scores on them, a rectangular (seeds, tasks) matrix."""
    scores = {}
    for algo in learners(cells):
        if not all((algo, env_id) in cells for env_id in tasks):
            continue
        seeds = sorted(set.intersection(*({r["seed"] for r in cells[algo, env_id]} for env_id in tasks)))
        if seeds:
            columns = [normalise([r["final"]["rate"] for r in cells[algo, env_id] if r["seed"] in seeds],
                                 *bounds(cells, env_id)) for env_id in tasks]
            scores[algo] = (seeds, np.stack(columns, axis=1))
    return scores


def _throw_counts(final: dict[str, Any]) -> list[int] | None:
    """A run's captures by throw index: its counts, or counted from its episodes' outcomes; None
    for a run that recorded neither."""
    if final.get("by_throw"):
        return list(final["by_throw"])
    if final.get("outcomes"):
        return [sum(episode[k] == "1" for episode in final["outcomes"]) for k in range(len(final["outcomes"][0]))]
    return None


def _throw_tallies(final: dict[str, Any]) -> list[tuple[int, int]] | None:
    """A run's captures and throws on each throw index, then on every throw but the first (those
    that can use the feedback of the ones before); None where the run did not count them or throws
    once an episode."""
    counts = _throw_counts(final)
    if counts is None or len(counts) < 2:
        return None
    episodes = final["episodes"]
    return [*((count, episodes) for count in counts), (sum(counts[1:]), episodes * (len(counts) - 1))]


def _throw_rates(final: dict[str, Any]) -> np.ndarray | None:
    """A run's capture rates of :func:`_throw_tallies`."""
    tallies = _throw_tallies(final)
    return None if tallies is None else np.array([captured / throws for captured, throws in tallies])


# ---------------------------------------------------------------- the statistics (rliable)


def statistics(cells: Cells, reps: int | None = None) -> Stats:
    """Every interval the tables show, computed once per set of records: ``reps`` resamples a
    bootstrap (default rliable's, :data:`~agents.baselines.stats.DEFAULT_REPS`; improvements
    take at most :data:`~agents.baselines.stats.IMPROVEMENT_REPS`)."""
    reps = reps or DEFAULT_REPS
    key = (digest(cells), reps)
    if key not in _STORED:
        per_cell = iqm_intervals({cell_key(a, e): _rates(records) for (a, e), records in cells.items()
                                  if a not in REFERENCES}, reps)
        stats = {"digest": key[0], "reps": reps, "improvement_reps": min(reps, IMPROVEMENT_REPS), "seed": SEED,
                 "rliable": importlib.metadata.version("rliable"), "cells": per_cell,
                 "sets": _set_statistics(cells, reps),
                 "improvement": _improvements(cells, per_cell, min(reps, IMPROVEMENT_REPS)),
                 "by_throw": {env_id: _throw_statistics(cells, env_id, reps)
                              for env_id in table_ids(cells) if has_feedback(env_id)}}
        _STORED[key] = json.loads(json.dumps(stats))  # as the stored file reads back
    return _STORED[key]


def _set_statistics(cells: Cells, reps: int) -> list[dict[str, Any]]:
    """Per common task set, each member's seeds, normalised IQM and optimality gap."""
    found = []
    for tasks in task_sets(cells):
        scores = set_scores(cells, tasks)
        estimates = aggregate_intervals({algo: matrix for algo, (_, matrix) in scores.items()}, reps)
        found.append({"tasks": list(tasks), "learners": {
            algo: {"seeds": seeds, "iqm": estimates[algo][0], "gap": estimates[algo][1]}
            for algo, (seeds, _) in scores.items()}})
    return found


def _overlaps(a: Estimate, b: Estimate) -> bool:
    """Whether two estimates' intervals (a point where there is none) overlap."""
    low_a, high_a = (a[1], a[2]) if a[1] is not None else (a[0], a[0])
    low_b, high_b = (b[1], b[2]) if b[1] is not None else (b[0], b[0])
    return low_a <= high_b and low_b <= high_a


def _improvements(cells: Cells, per_cell: dict[str, Estimate], reps: int) -> dict[str, list[dict[str, Any]]]:
    """Per task with two learners or more: the probability that its leader (:func:`ranking`)
    improves on the runner-up, then on each other learner whose interval overlaps the leader's."""
    pairs = {}
    for env_id in table_ids(cells):
        ranked = ranking(cells, env_id)
        leader = ranked[0]
        for other in ranked[1:]:
            if other == ranked[1] or _overlaps(per_cell[cell_key(leader, env_id)], per_cell[cell_key(other, env_id)]):
                pairs[env_id, leader, other] = (_rates(cells[leader, env_id])[:, None],
                                                _rates(cells[other, env_id])[:, None])
    estimates = improvement_intervals(pairs, reps)
    found: dict[str, list[dict[str, Any]]] = defaultdict(list)
    for (env_id, leader, other), estimate in estimates.items():
        found[env_id].append({"leader": leader, "other": other, "p": estimate})
    return dict(found)


def _throw_statistics(cells: Cells, env_id: str, reps: int) -> dict[str, dict[str, Any]]:
    """Per learner on ``env_id``: how many of its runs counted their captures by throw, and the
    IQM over them of each throw's rate and of the later throws' (:func:`_throw_rates`)."""
    counted = {}
    for algo in learners(cells):
        rows = [rates for r in cells.get((algo, env_id), []) if (rates := _throw_rates(r["final"])) is not None]
        if rows:
            counted[algo] = np.array(rows)
    estimates = iqm_intervals({(algo, k): rows[:, k] for algo, rows in counted.items()
                               for k in range(rows.shape[1])}, reps)
    return {algo: {"runs": len(rows), "rates": [estimates[algo, k] for k in range(rows.shape[1])]}
            for algo, rows in counted.items()}


def _clear(probability: Estimate | list) -> bool:
    """Whether a probability of improvement's 95% interval lies above one half."""
    return probability[1] is not None and probability[1] > 0.5


def clear_winners(stats: Stats) -> dict[str, str]:
    """Per task, its leader where the 95% interval of the probability that it improves on the
    runner-up lies above one half."""
    return {env_id: pairs[0]["leader"] for env_id, pairs in stats["improvement"].items() if _clear(pairs[0]["p"])}


# ---------------------------------------------------------------- text


def _estimate(estimate: Estimate | list, scale: float = 100.0, digits: int = 1) -> str:
    """``point [low, high]`` (rates in percent to 0.1 by default); the point alone where there is
    no interval."""
    point, low, high = (None if value is None else scale * value for value in estimate)
    if low is None:
        return f"{point:.{digits}f}"
    return f"{point:.{digits}f} [{low:.{digits}f}, {high:.{digits}f}]"


def _seeds_text(seeds: list[int]) -> str:
    """``0-4`` for a run of consecutive seeds, else the seeds listed."""
    seeds = sorted(seeds)
    if len(seeds) > 2 and seeds == list(range(seeds[0], seeds[-1] + 1)):
        return f"{seeds[0]}-{seeds[-1]}"
    return ", ".join(map(str, seeds))


def _tables(corner: str, rows: list[tuple[str, Any]], columns: list[tuple[str, Callable[[Any], str | None]]]) -> str:
    """Markdown tables of ``rows`` (label, key) by ``columns`` (header, cell of a key or None),
    :data:`COLUMNS_A_TABLE` columns a table; a table has the rows that have a cell in it ('-'
    where a column has none)."""
    tables = []
    for start in range(0, len(columns), COLUMNS_A_TABLE):
        chunk = columns[start:start + COLUMNS_A_TABLE]
        lines = [f"| {corner} | " + " | ".join(header for header, _ in chunk) + " |", "|---|" + "---:|" * len(chunk)]
        for label, key in rows:
            texts = [cell(key) for _, cell in chunk]
            if any(text is not None for text in texts):
                lines.append(f"| {label} | " + " | ".join("-" if text is None else text for text in texts) + " |")
        tables.append("\n".join(lines))
    return "\n\n".join(tables)


def _final_wilson(final: dict[str, Any]) -> Estimate:
    """A final evaluation's capture rate and its Wilson interval over its throws."""
    return wilson(final["captured"], final["throws"])


def _usual(values: dict[Any, Any]) -> tuple[Any, dict[Any, list[Any]]]:
    """The most frequent of ``values`` (of equals, the first), and the keys of each other value."""
    usual = Counter(values.values()).most_common(1)[0][0]
    others: dict[Any, list[Any]] = defaultdict(list)
    for key, value in values.items():
        if value != usual:
            others[value].append(key)
    return usual, dict(others)


def _grouped(pairs: list[tuple[str, str]], joint: str) -> str:
    """``(name, place)`` pairs as ``a, b{joint}place``, one group a place, in order."""
    places: dict[str, list[str]] = defaultdict(list)
    for name, place in pairs:
        places[place].append(name)
    return "; ".join(f"{', '.join(names)}{joint}{place}" for place, names in places.items())


def _seed_caption(cells: Cells) -> str:
    """How many seeds the learners' cells have: the usual seeds, and the cells with others."""
    usual, others = _usual({(algo, nowrap(env_id)): tuple(r["seed"] for r in cells[algo, env_id])
                            for env_id in table_ids(cells) for algo in learners(cells) if (algo, env_id) in cells})
    return (f"{len(usual)} seeds a cell ({_seeds_text(list(usual))})"
            + "".join(f"; {len(s)} ({_seeds_text(list(s))}): {_grouped(keys, ' on ')}" for s, keys in others.items()))


def _references(cells: Cells) -> str:
    """The references' table: tasks by reference, each run's rate with its Wilson interval."""
    runs = {key: records[0]["final"] for key, records in cells.items() if key[0] in REFERENCES}
    columns = [(f"*{name}*", lambda env_id, name=name: _estimate(_final_wilson(runs[name, env_id]))
                if (name, env_id) in runs else None) for name in REFERENCES if any(n == name for n, _ in runs)]
    return _tables("task (rate in %)", [(nowrap(env_id), env_id) for env_id in table_ids(cells)], columns)


def matrix(cells: Cells, stats: Stats | None = None) -> str:
    """The tables a reader looks at first: tasks by learner, each cell the IQM capture rate over
    the cell's seeds with its 95% interval, a task's leader in bold where it is clear of the
    runner-up (:func:`clear_winners`); then the references' rates with their Wilson intervals."""
    stats = stats or statistics(cells)
    winners = clear_winners(stats)

    def cell(algo: str) -> Callable[[str], str | None]:
        def text(env_id: str) -> str | None:
            estimate = stats["cells"].get(cell_key(algo, env_id))
            if estimate is None:
                return None
            return f"**{_estimate(estimate)}**" if winners.get(env_id) == algo else _estimate(estimate)
        return text

    episodes = sorted({r["final"]["episodes"] for records in cells.values() for r in records})
    caption = (f"Capture rate (%) on {' / '.join(map(str, episodes))} held-out episodes, IQM over seeds "
               f"[95% stratified bootstrap CI], {_seed_caption(cells)}. Bold: the task's leader, where the "
               "95% interval of the probability that it beats the runner-up lies above 0.5.")
    learner_tables = _tables("task (rate in %)", [(nowrap(env_id), env_id) for env_id in table_ids(cells)],
                             [(algo, cell(algo)) for algo in learners(cells)])
    reference_caption = ("References, one run each (they do not learn) on the same episodes; "
                         "95% Wilson interval over the run's throws:")
    return f"{caption}\n\n{learner_tables}\n\n{reference_caption}\n\n{_references(cells)}"


def improvement(cells: Cells, stats: Stats | None = None) -> str:
    """The table of the probabilities of improvement: per task its leader against the runner-up
    and every learner whose interval overlaps the leader's, bold where the interval lies above
    one half."""
    stats = stats or statistics(cells)
    lines = ["| task | leader | against | P(leader > other) [95% CI] |", "|---|---|---|---:|"]
    for env_id, pairs in stats["improvement"].items():
        for pair in pairs:
            text = _estimate(pair["p"], 1.0, 2)
            lines.append(f"| {nowrap(env_id)} | {pair['leader']} | {pair['other']} | "
                         f"{f'**{text}**' if _clear(pair['p']) else text} |")
    alone = [nowrap(env_id) for env_id in table_ids(cells) if env_id not in stats["improvement"]]
    caption = (f"rliable's probability of improvement from the seeds' capture rates (every seed of both cells), "
               f"95% interval over {stats['improvement_reps']:,} bootstrap resamples of each cell's seeds.")
    return caption + "\n\n" + "\n".join(lines) + (f"\n\nOne learner only: {', '.join(alone)}." if alone else "")


def aggregates(cells: Cells, stats: Stats | None = None) -> str:
    """Each learner's normalised IQM and optimality gap over each common task set, with 95%
    intervals (every learner with a normalised score appears); which tasks and seeds a set has."""
    stats = stats or statistics(cells)
    sets = stats["sets"]
    rows = [(algo, algo) for algo in learners(cells) if any(algo in s["learners"] for s in sets)]

    def columns(metric: str) -> list[tuple[str, Callable[[str], str | None]]]:
        return [(nowrap(set_name(s["tasks"])), lambda algo, s=s: _estimate(s["learners"][algo][metric], 1.0, 2)
                 if algo in s["learners"] else None) for s in sets]

    legend = "".join(f"{set_name(s['tasks'])}: {', '.join(map(nowrap, s['tasks']))}. " for s in sets
                     if len(s["tasks"]) > 1)
    return (f"Normalised score (random 0, informed oracle 1 on each task), IQM over the runs of every task of a "
            f"set [95% stratified bootstrap CI]; a learner appears in a set's column when it ran every task of it. "
            f"{legend}{_set_seeds_caption(stats)}\n\n{_tables('learner', rows, columns('iqm'))}\n\n"
            f"Optimality gap (γ = 1: how far the mean normalised score, each capped at 1, falls short of 1; "
            f"lower is better) [95% CI]:\n\n{_tables('learner', rows, columns('gap'))}")


def _set_seeds_caption(stats: Stats) -> str:
    """Which seeds the sets take: the usual ones, and the learners of a set with others."""
    usual, others = _usual({(algo, nowrap(set_name(s["tasks"]))): tuple(member["seeds"])
                            for s in stats["sets"] for algo, member in s["learners"].items()})
    return (f"Each set takes the seeds all its tasks have: {_seeds_text(list(usual))}"
            + "".join(f"; {_seeds_text(list(found))} of {_grouped(keys, ' on ')}" for found, keys in others.items())
            + " (a cell with more seeds than the set's other tasks gives the set only the seeds they share).")


def table(cells: Cells, stats: Stats | None = None) -> str:
    """The table of every cell: per task and learner its seeds, IQM capture rate and normalised
    IQM with 95% intervals and the median minutes a run; then the references (one run, Wilson)."""
    stats = stats or statistics(cells)
    lines = ["| task | learner (seeds) | capture rate (%), IQM [95% CI] | normalised IQM [95% CI] | "
             "minutes a run (median) |", "|---|---|---:|---:|---:|"]
    rows = [(env_id, algo) for env_id in table_ids(cells) for algo in [*learners(cells), *REFERENCES]
            if (algo, env_id) in cells]
    for env_id, algo in rows:
        records = cells[algo, env_id]
        wall = np.median([record["wall_s"] for record in records]) / 60
        if algo in REFERENCES:
            name, rate, scaled = f"*{algo}* (1 run)", _estimate(_final_wilson(records[0]["final"])), "-"
        else:
            estimate, scale = stats["cells"][cell_key(algo, env_id)], bounds(cells, env_id)
            name, rate = f"{algo} ({len(records)})", _estimate(estimate)
            scaled = "-" if scale is None else _estimate(
                [None if value is None else float(normalise(value, *scale)) for value in estimate], 1.0, 2)
        lines.append(f"| {nowrap(env_id)} | {name} | {rate} | {scaled} | {wall:.1f} |")
    return "\n".join(lines)


def by_throw(cells: Cells, env_id: str, stats: Stats | None = None) -> str:
    """``env_id``'s capture rate by throw index: per learner (``n``: its runs that counted them)
    the IQM over its runs of each throw's rate and of the later throws' rate, with 95% intervals;
    the references' with Wilson intervals over their episodes."""
    stats = stats or statistics(cells)
    counted = stats["by_throw"].get(env_id, {})
    references = {name: tallies for name in REFERENCES if (name, env_id) in cells
                  and (tallies := _throw_tallies(cells[name, env_id][0]["final"])) is not None}
    if not counted and not references:
        return f"No run on {env_id} counted its captures by throw yet."
    throws = len(next(iter(counted.values()))["rates"] if counted else next(iter(references.values()))) - 1
    rows = [(f"throw {k + 1}", k) for k in range(throws)] + [(f"throws 2-{throws}", throws)]
    learner_columns = [(f"{algo} (n={found['runs']})", lambda k, found=found: _estimate(found["rates"][k]))
                       for algo, found in counted.items()]
    reference_columns = [(f"*{name}*", lambda k, tallies=tallies: _estimate(wilson(*tallies[k])))
                         for name, tallies in references.items()]
    missing = [algo for algo in learners(cells) if (algo, env_id) in cells and algo not in counted]
    caption = (f"Capture rate (%) by throw index, IQM over the runs [95% CI] (n: runs that counted their throws; "
               f"throws 2-{throws}: each run's rate over those throws); references: Wilson 95% interval over the "
               "episodes." + (f" Not counted (runs from before the count was recorded): {', '.join(missing)}."
                              if missing else ""))
    return "\n\n".join(part for part in (caption, _tables("rate in %", rows, learner_columns) if counted else "",
                                         _tables("rate in %", rows, reference_columns) if references else "") if part)


def shipped(results: Path, models: dict[str, str]) -> str:
    """The markdown table of the shipped models ``models`` (file name -> run, as
    :data:`agents.policies.SHIPPED_BASELINES`), each with its run and final evaluation from its
    result file under ``results``: the capture rate with its Wilson interval over the evaluation's
    throws and, where the run counted them, throw 1 and the later throws."""
    lines = ["| agents/pretrained/ | run | capture rate (%) [95% CI] | throw 1 (%) | later throws (%) |",
             "|---|---|---:|---:|---:|"]
    records = {name: read_results(results / f"{run}.json")["figures"] for name, run in models.items()}
    for name, record in records.items():
        final, rates = record["final"], _throw_rates(record["final"])
        first, later = ("-", "-") if rates is None else (f"{100 * rates[0]:.1f}", f"{100 * rates[-1]:.1f}")
        lines.append(f"| `{name}` | {nowrap(record['env_id'])}, {record['algorithm']} seed {record['seed']}, "
                     f"{record['budget']:,} steps | {_estimate(_final_wilson(final))} | {first} | {later} |")
    episodes = sorted({record["final"]["episodes"] for record in records.values()})
    return ("\n".join(lines) + f"\n\nOn {' / '.join(map(str, episodes))} held-out episodes; 95% Wilson interval over "
            "the evaluation's throws.")


def best_line(cells: Cells, env_id: str) -> str:
    """One sentence naming ``env_id``'s best learner(s): the IQM capture rate, interval, seeds and
    budget; or that no learner has run on it."""
    best = best_learners(cells).get(env_id)
    if best is None:
        return "none trained yet"
    records = cells[best[0], env_id]
    point, low, high = statistics(cells)["cells"][cell_key(best[0], env_id)]
    interval = "" if low is None else f" [{100 * low:.1f}, {100 * high:.1f}]"
    return (f"{', '.join(best)}{' (tied)' if len(best) > 1 else ''}: {100 * point:.1f}%{interval} IQM over "
            f"{len(records)} seeds at {records[0]['budget']:,} steps")


def _distinct(values: list[Any]) -> str:
    """The distinct values, most frequent first; each with its count where there are several."""
    counted = Counter(values).most_common()
    return str(counted[0][0]) if len(counted) == 1 else ", ".join(f"{value} ({n})" for value, n in counted)


def _protocol_rows(cells: Cells) -> list[str]:
    """Per task: the learners' budget(s), seeds, final evaluation and learning curve."""
    lines = ["| task | budget (env steps) | seeds | final evaluation (deterministic) | learning curve |",
             "|---|---:|---|---|---|"]
    for env_id in table_ids(cells):
        runs = {algo: cells[algo, env_id] for algo in learners(cells) if (algo, env_id) in cells}
        usual, others = _usual({algo: records[0]["budget"] for algo, records in runs.items()})
        budget = f"{usual:,}" + "".join(f"; {', '.join(algos)}: {b:,}" for b, algos in others.items())
        usual, others = _usual({algo: tuple(r["seed"] for r in records) for algo, records in runs.items()})
        seed_text = _seeds_text(list(usual)) + "".join(f"; {', '.join(algos)}: {_seeds_text(list(found))}"
                                                       for found, algos in others.items())
        finals = [r["final"] for records in cells.values() for r in records if r["env_id"] == env_id]
        evaluation = _distinct([f"{f['episodes']} episodes seeded from {f['seed']:,}" for f in finals])
        curves = [r["curve"] for records in runs.values() for r in records]
        curve = _distinct([f"{len(c['points'])} points of {c['episodes']} episodes"
                           + (f" seeded from {c['seed']:,}" if "seed" in c else "") for c in curves])
        lines.append(f"| {nowrap(env_id)} | {budget} | {seed_text} | {evaluation} | {curve} |")
    return lines


def _provenance(cells: Cells) -> list[str]:
    """The runs' training seeds, commits (with a warning line where there are several, or a tree
    with changes), machines, dates, compute and package versions."""
    records = [record for runs in cells.values() for record in runs]
    learning = [r for r in records if r["algorithm"] not in REFERENCES]
    seeded = [r for r in learning if "env_seeds" in r]
    stride = TRAIN_SEED_STRIDE
    as_planned = [r for r in seeded if all(stride * r["seed"] <= s < stride * (r["seed"] + 1) for s in r["env_seeds"])
                  and r["env_seeds"][:r["hyperparams"].get("n_envs", 1)]
                  == [stride * r["seed"] + i for i in range(r["hyperparams"].get("n_envs", 1))]]
    lines = ["Training env seeds: not recorded by these runs." if not seeded else
             f"Training envs: worker i of run seed k seeded {stride} k + i (a resumed run's next workers the next "
             f"ones of its block of {stride}) in {len(as_planned)} of the {len(seeded)} learner runs that record them"
             + ("" if len(seeded) == len(learning) else f" ({len(learning)} learner runs)")
             + ("." if len(as_planned) == len(seeded) else "; **Warning:** the others were seeded otherwise.")]
    commits = Counter(str(r["versions"].get("commit"))[:10] for r in records)
    if len(commits) == 1:
        lines.append(f"Commit: `{next(iter(commits))}` (every run).")
    else:
        shown = commits.most_common(3)
        lines.append(f"**Warning:** the runs come from {len(commits)} commits, not one: "
                     + ", ".join(f"`{commit}` ({n} runs)" for commit, n in shown)
                     + (f" and {len(commits) - len(shown)} more." if len(commits) > len(shown) else "."))
    dirty = sum(r["versions"].get("tree_clean") is False for r in records)
    unknown = sum(r["versions"].get("tree_clean") is None for r in records)
    if dirty:
        lines.append(f"**Warning:** {dirty} runs ran on a tree with uncommitted changes: their commit does not say "
                     f"what ran.")
    if unknown:
        lines.append(f"{unknown} runs did not record whether their tree had uncommitted changes.")
    started = sorted(r["started"] for r in records)
    cpu_hours, wall_hours = (sum(r[key] for r in records) / 3600 for key in ("cpu_s", "wall_s"))
    lines.append(f"{len(records)} runs ({len(learning)} learning), one process and one torch thread each, CPU only, on "
                 f"{_distinct([r['machine'] for r in records])}; started {started[0][:16].replace('T', ' ')} to "
                 f"{started[-1][:16].replace('T', ' ')} UTC. Compute: {cpu_hours:.1f} CPU hours, {wall_hours:.1f} "
                 "hours of runs' wall-clock.")
    names = dict.fromkeys(name for r in records for name in r["versions"] if name not in ("commit", "tree_clean"))
    lines.append("Versions: " + ", ".join(
        f"{name} {_distinct([str(r['versions'][name]) for r in records if r['versions'].get(name)])}"
        for name in names) + ".")
    return lines


def protocol(cells: Cells, stats: Stats | None = None) -> str:
    """The protocol as the result files record it: per task the budgets, seeds, held-out
    evaluation and learning curve; the runs' training seeds, commits, machines, compute and
    versions; the statistics' resamples."""
    stats = stats or statistics(cells)
    return "\n".join(_protocol_rows(cells)) + "\n\n" + "\n\n".join([*_provenance(cells), (
        f"Statistics: rliable {stats['rliable']}, stratified bootstrap 95% percentile intervals from "
        f"{stats['reps']:,} resamples (probabilities of improvement: {stats['improvement_reps']:,}; the figures' "
        f"bands: {min(stats['reps'], PROFILE_REPS):,}), numpy's global generator seeded {stats['seed']} for each.")])


# ---------------------------------------------------------------- figures


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
                    ax.axhline(100 * _rates(cells[name, env_id])[0], color="black", linewidth=1,
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


def write_report(out: Path, reps: int | None = None) -> Path:
    """Write ``out/report.md`` (every table), ``out/stats.json`` (the statistics, for the docs'
    quoted tables) and the figures from the result files under ``out``; returns the report's
    path. ``reps``: the bootstraps' resamples (default rliable's)."""
    cells = load_cells(out)
    stats = statistics(cells, reps)
    (out / STATS_FILE).write_text(json.dumps(stats, indent=1) + "\n")
    figures = write_figures(cells, out, reps)
    images = "\n\n".join(f"![{name.removesuffix('.png')}]({name})" for name in figures)
    throws = "".join(f"### {env_id}\n\n{by_throw(cells, env_id, stats)}\n\n" for env_id in stats["by_throw"])
    report = out / "report.md"
    report.write_text(f"# Baselines\n\n## Capture rate\n\n{matrix(cells, stats)}\n\n## Probability of improvement\n\n"
                      f"{improvement(cells, stats)}\n\n## Figures\n\n{images}\n\n## Aggregates\n\n"
                      f"{aggregates(cells, stats)}\n\n## Every cell\n\n{table(cells, stats)}\n\n## By throw\n\n{throws}"
                      f"## Protocol\n\n{protocol(cells, stats)}\n")
    return report
