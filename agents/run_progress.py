"""The training's progress bar: environment steps, with an ETA for whichever limit ends the run
first, the step cap or the wall-clock budget."""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import TextIO

from stable_baselines3.common.callbacks import BaseCallback
from tqdm import tqdm


def projected_steps(steps: int, cap: int, seconds: float, budget_s: float) -> int:
    """The environment steps done when the run ends: ``cap``, or fewer when, at the rate of the
    ``steps`` done in ``seconds`` of training, the budget of ``budget_s`` seconds ends it first."""
    if steps <= 0 or seconds <= 0.0:
        return cap
    return min(cap, steps + math.ceil(steps / seconds * max(0.0, budget_s - seconds)))


class RunProgress(BaseCallback):
    """A tqdm bar of environment steps whose total, and so its ETA, is :func:`projected_steps`,
    re-estimated at every step from the rate so far.

    :param budget_s: the run's budget of training seconds.
    :param training_seconds: the training seconds spent so far, as the budget counts them
        (e.g. :meth:`~agents.training.CaptureCurve.training_seconds`).
    :param stream: where the bar is drawn (stderr by default).
    """

    def __init__(self, budget_s: float, training_seconds: Callable[[], float], stream: TextIO | None = None) -> None:
        super().__init__()
        self.budget_s, self.training_seconds, self.stream = budget_s, training_seconds, stream
        self.bar: tqdm | None = None
        self._first = self._cap = 0

    def _on_training_start(self) -> None:
        self._first = self.model.num_timesteps
        self._cap = self.locals["total_timesteps"] - self._first
        self.bar = tqdm(total=self._cap, unit="step", unit_scale=True, file=self.stream)

    def _on_step(self) -> bool:
        steps = self.model.num_timesteps - self._first
        self.bar.total = projected_steps(steps, self._cap, self.training_seconds(), self.budget_s)
        self.bar.update(steps - self.bar.n)
        return True

    def _on_training_end(self) -> None:
        self.bar.total = self.bar.n  # the run ended here, whichever limit ended it
        self.bar.refresh()
        self.bar.close()
