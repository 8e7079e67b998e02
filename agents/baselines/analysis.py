"""The statistics of the baselines' cells, with rliable (:mod:`agents.baselines.stats`), and their cache.

:func:`statistics` computes: per (learner, task) cell the interquartile mean (IQM) of the final
capture rate over the cell's seeds with its 95% stratified bootstrap interval; per common task set
(:func:`~agents.baselines.cells.task_sets`) each learner's IQM and optimality gap of the normalised
score (random 0, informed oracle 1); per task the probability that its leader improves on the
runner-up and on every learner whose interval overlaps its; on the tasks with feedback the IQM of
each throw index. At rliable's 50000 resamples they take minutes, so
:func:`~agents.baselines.report.write_report` stores them beside the result files
(:data:`STATS_FILE`, with the digest of the records they come from, :func:`write_statistics`) and
:func:`load_cells` hands them on for as long as the records are those.
"""

from __future__ import annotations

import importlib.metadata
import json
from collections import defaultdict
from pathlib import Path
from typing import Any

import numpy as np

from agents.baselines.cells import (Cells, cell_key, digest, final_rates, has_feedback, learners, ranking, read_cells,
                                    set_scores, table_ids, task_sets, throw_rates)
from agents.baselines.grid import REFERENCES
from agents.baselines.stats import (DEFAULT_REPS, IMPROVEMENT_REPS, SEED, Estimate, aggregate_intervals,
                                    improvement_intervals, iqm_intervals)

Stats = dict[str, Any]
"""What :func:`statistics` computes, as JSON reads it back."""
STATS_FILE = "stats.json"
"""The statistics of an output folder's result files, stored beside them by :func:`write_statistics`."""
_STORED: dict[tuple[str, int], Stats] = {}
"""Statistics already computed or read, by the digest of their records and their resamples."""


def load_cells(out: Path) -> Cells:
    """Every complete result under ``out``, grouped by (algorithm, env id), seeds in order
    (:func:`~agents.baselines.cells.read_cells`); the statistics stored in ``out/stats.json`` are
    taken up if they are of these very records."""
    cells = read_cells(out)
    stored = out / STATS_FILE
    if stored.is_file():
        stats = json.loads(stored.read_text())
        if stats.get("digest") == digest(cells):
            _STORED[stats["digest"], stats["reps"]] = stats
    return cells


def write_statistics(out: Path, stats: Stats) -> Path:
    """Store ``stats`` as ``out/stats.json`` (:data:`STATS_FILE`), where :func:`load_cells` takes
    them up again; returns its path."""
    path = out / STATS_FILE
    path.write_text(json.dumps(stats, indent=1) + "\n")
    return path


def statistics(cells: Cells, reps: int | None = None) -> Stats:
    """Every interval the tables show, computed once per set of records: ``reps`` resamples a
    bootstrap (default rliable's, :data:`~agents.baselines.stats.DEFAULT_REPS`; improvements
    take at most :data:`~agents.baselines.stats.IMPROVEMENT_REPS`)."""
    reps = reps or DEFAULT_REPS
    key = (digest(cells), reps)
    if key not in _STORED:
        per_cell = iqm_intervals({cell_key(a, e): final_rates(records) for (a, e), records in cells.items()
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
    """Per task with two learners or more: the probability that its leader
    (:func:`~agents.baselines.cells.ranking`) improves on the runner-up, then on each other learner
    whose interval overlaps the leader's."""
    pairs = {}
    for env_id in table_ids(cells):
        ranked = ranking(cells, env_id)
        leader = ranked[0]
        for other in ranked[1:]:
            if other == ranked[1] or _overlaps(per_cell[cell_key(leader, env_id)], per_cell[cell_key(other, env_id)]):
                pairs[env_id, leader, other] = (final_rates(cells[leader, env_id])[:, None],
                                                final_rates(cells[other, env_id])[:, None])
    estimates = improvement_intervals(pairs, reps)
    found: dict[str, list[dict[str, Any]]] = defaultdict(list)
    for (env_id, leader, other), estimate in estimates.items():
        found[env_id].append({"leader": leader, "other": other, "p": estimate})
    return dict(found)


def _throw_statistics(cells: Cells, env_id: str, reps: int) -> dict[str, dict[str, Any]]:
    """Per learner on ``env_id``: how many of its runs counted their captures by throw, and the
    IQM over them of each throw's rate and of the later throws'
    (:func:`~agents.baselines.cells.throw_rates`)."""
    counted = {}
    for algo in learners(cells):
        rows = [rates for r in cells.get((algo, env_id), []) if (rates := throw_rates(r["final"])) is not None]
        if rows:
            counted[algo] = np.array(rows)
    estimates = iqm_intervals({(algo, k): rows[:, k] for algo, rows in counted.items()
                               for k in range(rows.shape[1])}, reps)
    return {algo: {"runs": len(rows), "rates": [estimates[algo, k] for k in range(rows.shape[1])]}
            for algo, rows in counted.items()}


def is_clear(probability: Estimate | list) -> bool:
    """Whether a probability of improvement's 95% interval lies above one half."""
    return probability[1] is not None and probability[1] > 0.5


def clear_winners(stats: Stats) -> dict[str, str]:
    """Per task, its leader where the 95% interval of the probability that it improves on the
    runner-up lies above one half."""
    return {env_id: pairs[0]["leader"] for env_id, pairs in stats["improvement"].items() if is_clear(pairs[0]["p"])}
