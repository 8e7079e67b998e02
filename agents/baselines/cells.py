"""The baselines' result files as cells: every run's record, grouped by (algorithm, env id).

What the other modules ask of the cells: which learners and tasks they hold (:func:`learners`,
:func:`table_ids`), the references' bounds of a normalised score (:func:`bounds`), the order of
the learners on a task (:func:`ranking`, :func:`best_learners`), the common task sets of the
aggregates and their normalised scores (:func:`task_sets`, :func:`set_scores`), and the captures a
run counted by throw index (:func:`throw_tallies`, :func:`throw_rates`).
"""

from __future__ import annotations

import functools
import hashlib
import json
from collections import defaultdict
from pathlib import Path
from typing import Any

import numpy as np
from rliable import metrics

import netgym
from agents.baselines.grid import ALGORITHMS, BUDGETS, REFERENCES
from agents.baselines.stats import normalise
from agents.model_env import vector_counterpart
from netgym.bench.results import read_results

Cells = dict[tuple[str, str], list[dict[str, Any]]]
"""Result records by (algorithm, env id), seeds in order."""


def read_cells(out: Path) -> Cells:
    """Every complete result under ``out``, grouped by (algorithm, env id), seeds in order
    (:func:`agents.baselines.analysis.load_cells` also takes up the statistics stored beside them)."""
    cells: Cells = defaultdict(list)
    for path in sorted(out.glob("*/*/seed_*.json")):
        record = read_results(path)["figures"]
        cells[record["algorithm"], record["env_id"]].append(record)
    return {key: sorted(records, key=lambda r: r["seed"]) for key, records in cells.items()}


def digest(cells: Cells) -> str:
    """SHA-256 of every record of ``cells`` (canonical JSON): what their statistics depend on."""
    records = [cells[key] for key in sorted(cells)]
    return hashlib.sha256(json.dumps(records, sort_keys=True).encode()).hexdigest()


@functools.cache
def is_pixels(env_id: str) -> bool:
    """Whether ``env_id`` observes images (its episodes run with vector observations elsewhere)."""
    return vector_counterpart(env_id)[0] != env_id


def has_feedback(env_id: str) -> bool:
    """Whether ``env_id``'s observations carry the feedback of the episode's earlier throws."""
    entry = netgym.ENVIRONMENTS.get(env_id)
    return bool(entry and entry.kwargs.get("feedback"))


def final_rates(records: list[dict[str, Any]]) -> np.ndarray:
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
        return float(final_rates(cells["random", env_id])[0]), float(final_rates(cells["oracle", env_id])[0])
    return None


def cell_key(algo: str, env_id: str) -> str:
    """A cell's key in the statistics: ``algo/env_id``."""
    return f"{algo}/{env_id}"


def _rank_key(cells: Cells, algo: str, env_id: str) -> tuple[float, int, float]:
    """What ranks a learner on ``env_id``: its IQM capture rate over its seeds (rliable's), then
    how many seeds, then the mean rate."""
    rates = final_rates(cells[algo, env_id])
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


def throw_tallies(final: dict[str, Any]) -> list[tuple[int, int]] | None:
    """A run's captures and throws on each throw index, then on every throw but the first (those
    that can use the feedback of the ones before); None where the run did not count them or throws
    once an episode."""
    counts = _throw_counts(final)
    if counts is None or len(counts) < 2:
        return None
    episodes = final["episodes"]
    return [*((count, episodes) for count in counts), (sum(counts[1:]), episodes * (len(counts) - 1))]


def throw_rates(final: dict[str, Any]) -> np.ndarray | None:
    """A run's capture rates of :func:`throw_tallies`."""
    tallies = throw_tallies(final)
    return None if tallies is None else np.array([captured / throws for captured, throws in tallies])


# ---------------------------------------------------------------- the statistics (rliable)
