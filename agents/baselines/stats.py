"""Statistics of baseline scores as rliable computes them (Agarwal et al. 2021, "Deep RL at the
edge of the statistical precipice"): interquartile means (IQM) and optimality gaps with stratified
bootstrap 95% intervals, probabilities of improvement, performance profiles; and the binomial
(Wilson) interval of a reference's single run, which has no seeds to resample.

Scores are rliable's matrices of shape (runs, tasks). rliable's bootstrap draws from numpy's
global random generator; every function here seeds it with :data:`SEED` for its call (and puts
its state back after), so that the same scores always give the same intervals.
"""

from __future__ import annotations

import inspect
from collections import defaultdict
from collections.abc import Hashable, Iterator, Mapping
from contextlib import contextmanager
from typing import TypeVar

import numpy as np
import scipy.stats
from rliable import library, metrics

from agents.evaluation import wilson_interval

Key = TypeVar("Key", bound=Hashable)
Estimate = tuple[float, float | None, float | None]
"""A point estimate and its 95% interval (None, None where there is nothing to resample)."""

DEFAULT_REPS: int = inspect.signature(library.get_interval_estimates).parameters["reps"].default
"""rliable's default number of bootstrap resamples of an interval estimate (50000)."""
PROFILE_REPS: int = inspect.signature(library.create_performance_profile).parameters["reps"].default
"""rliable's default number of bootstrap resamples of a performance profile's bands (2000)."""
IMPROVEMENT_REPS = 2000
"""Resamples of a probability of improvement's interval, as rliable's README computes them (each
resample runs a Mann-Whitney U test)."""
SEED = 0
"""numpy's global seed for each bootstrap."""


@contextmanager
def seeded(seed: int = SEED) -> Iterator[None]:
    """numpy's global random generator seeded with ``seed`` inside the block, as it was after."""
    state = np.random.get_state()
    np.random.seed(seed)
    try:
        yield
    finally:
        np.random.set_state(state)


def normalise(score: np.ndarray | float, low: float, high: float) -> np.ndarray:
    """``score`` on the scale where ``low`` (the random policy) is 0 and ``high`` (the informed
    ceiling) is 1."""
    return (np.asarray(score, dtype=float) - low) / (high - low)


def column_iqms(scores: np.ndarray) -> np.ndarray:
    """rliable's ``aggregate_iqm`` of each column of ``scores`` on its own (scipy's ``trim_mean``
    with a quarter cut from each end, as ``aggregate_iqm`` calls it on the whole matrix)."""
    return scipy.stats.trim_mean(scores, 0.25, axis=0)


def iqm_intervals(columns: Mapping[Key, np.ndarray], reps: int = DEFAULT_REPS) -> dict[Key, Estimate]:
    """The IQM of each column of scores (one cell's runs) with its 95% stratified bootstrap
    interval: the columns with as many runs are the tasks of one rliable score matrix, whose
    bootstrap resamples each task's runs on its own, so each column's interval is its own
    bootstrap's. A column of one run has no interval."""
    by_runs: dict[int, list[Key]] = defaultdict(list)
    for key, scores in columns.items():
        by_runs[len(scores)].append(key)
    found: dict[Key, Estimate] = {}
    for runs, keys in by_runs.items():
        matrix = np.stack([np.asarray(columns[key], dtype=float) for key in keys], axis=1)
        if runs < 2:
            found.update({key: (float(matrix[0, k]), None, None) for k, key in enumerate(keys)})
            continue
        with seeded():
            points, intervals = library.get_interval_estimates({"cells": matrix}, column_iqms, reps=reps)
        found.update({key: (float(points["cells"][k]), float(intervals["cells"][0, k]), float(intervals["cells"][1, k]))
                      for k, key in enumerate(keys)})
    return {key: found[key] for key in columns}


def _aggregates(matrix: np.ndarray) -> np.ndarray:
    """rliable's IQM and optimality gap (gamma 1) of a score matrix."""
    return np.array([metrics.aggregate_iqm(matrix), metrics.aggregate_optimality_gap(matrix, 1)])


def aggregate_intervals(scores: Mapping[Key, np.ndarray], reps: int = DEFAULT_REPS
                        ) -> dict[Key, tuple[Estimate, Estimate]]:
    """Of each key's normalised score matrix (runs, tasks): rliable's IQM over all its runs and
    tasks and its optimality gap (gamma 1: how far the mean of the scores, each capped at 1, falls
    short of 1), each with its 95% stratified bootstrap interval (none for a single run)."""
    resampled = {key: matrix for key, matrix in scores.items() if len(matrix) > 1}
    with seeded():
        points, intervals = library.get_interval_estimates(resampled, _aggregates, reps=reps)
    found = {key: tuple((float(points[key][m]), float(intervals[key][0, m]), float(intervals[key][1, m]))
                        for m in range(2)) for key in resampled}
    found.update({key: tuple((float(value), None, None) for value in _aggregates(matrix))
                  for key, matrix in scores.items() if key not in resampled})
    return {key: found[key] for key in scores}


def improvement_intervals(pairs: Mapping[Key, tuple[np.ndarray, np.ndarray]], reps: int = IMPROVEMENT_REPS
                          ) -> dict[Key, Estimate]:
    """rliable's probability of improvement of each pair's X over its Y (score matrices (runs,
    tasks), as many tasks, any numbers of runs): the chance that a run of X scores more than a
    run of Y on a task, ties counting half, averaged over tasks; with its 95% interval over
    bootstraps that resample each algorithm's runs on their own (none where one has a single run)."""
    arrays = {key: [np.asarray(x, dtype=float), np.asarray(y, dtype=float)] for key, (x, y) in pairs.items()}
    resampled = {key: pair for key, pair in arrays.items() if min(len(pair[0]), len(pair[1])) > 1}
    with seeded():
        points, intervals = library.get_interval_estimates(resampled, metrics.probability_of_improvement, reps=reps)
    found: dict[Key, Estimate] = {key: (float(points[key]), *map(float, np.ravel(intervals[key])))
                                  for key in resampled}
    found.update({key: (float(metrics.probability_of_improvement(*pair)), None, None)
                  for key, pair in arrays.items() if key not in resampled})
    return {key: found[key] for key in pairs}


def profile_bands(scores: Mapping[Key, np.ndarray], thresholds: np.ndarray, reps: int = PROFILE_REPS
                  ) -> dict[Key, tuple[np.ndarray, np.ndarray, np.ndarray]]:
    """rliable's performance profile of each key's score matrix: the fraction of its runs (all
    tasks) that score above each threshold, and the 95% band of each fraction."""
    with seeded():
        profiles, bands = library.create_performance_profile(dict(scores), thresholds, reps=reps)
    return {key: (profiles[key], bands[key][0], bands[key][1]) for key in scores}


def wilson(captured: int, throws: int) -> Estimate:
    """A single run's capture rate and its Wilson 95% interval over its ``throws`` throws (a
    reference's: it learns nothing, so its only uncertainty is that of the episodes drawn)."""
    return (captured / throws, *wilson_interval(captured, throws))
