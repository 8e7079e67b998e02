"""Aggregate statistics of baseline scores (Agarwal et al. 2021, "Deep RL at the edge of the
statistical precipice", as rliable computes them): the interquartile mean, its stratified
bootstrap confidence interval, scores normalised between two references, performance profiles.

Scores are arrays of shape (runs, tasks): one row per seed, one column per env id.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np
from scipy import stats

Statistic = Callable[..., Any]
"""A statistic of all scores (``axis=None``) or of each row of a 2-d array (``axis=1``)."""


def iqm(scores: np.ndarray, axis: int | None = None) -> Any:
    """Interquartile mean: the mean of the middle 50% (scipy's ``trim_mean`` with a quarter cut
    from each end, as rliable's ``aggregate_iqm``), of all ``scores`` (a float) or along ``axis``."""
    if axis is None:
        return float(stats.trim_mean(np.ravel(scores), 0.25))
    return stats.trim_mean(scores, 0.25, axis=axis)


def normalise(score: np.ndarray | float, low: float, high: float) -> np.ndarray:
    """``score`` on the scale where ``low`` (the random policy) is 0 and ``high`` (the informed
    ceiling) is 1."""
    return (np.asarray(score, dtype=float) - low) / (high - low)


def bootstrap_ci(scores: np.ndarray, statistic: Statistic = iqm, confidence: float = 0.95, reps: int = 2000,
                 seed: int = 0) -> tuple[float, float]:
    """Percentile interval of ``statistic`` over ``reps`` stratified bootstrap resamples of
    ``scores`` (runs x tasks, or one task's runs): each resample draws, for every task on its
    own, as many runs as it has, with replacement."""
    scores = np.asarray(scores, dtype=float)
    scores = scores[:, None] if scores.ndim == 1 else scores
    runs, tasks = scores.shape
    rows = np.random.default_rng(seed).integers(0, runs, size=(reps, runs, tasks))
    resampled = scores[rows, np.arange(tasks)]
    values = statistic(resampled.reshape(reps, runs * tasks), axis=1)
    tail = 100 * (1 - confidence) / 2
    low, high = np.percentile(values, [tail, 100 - tail])
    return float(low), float(high)


def performance_profile(scores: np.ndarray, thresholds: np.ndarray) -> np.ndarray:
    """The fraction of all runs (every task's) whose score is above each threshold."""
    flat = np.ravel(scores)
    return np.array([float(np.mean(flat > tau)) for tau in np.asarray(thresholds)])
