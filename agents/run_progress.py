"""The training's progress bar: environment steps, with an ETA for whichever limit ends the run
first, the step cap or the wall-clock budget, and the latest evaluation's capture rate."""

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


WARM_UP_S = 20.0
"""Training seconds after which the bar estimates its total once, from the rate so far."""


class RunProgress(BaseCallback):
    """A tqdm bar of environment steps whose total, and so its ETA, is :func:`projected_steps`,
    estimated once from the rate of the first :data:`WARM_UP_S` training seconds and then kept
    steady (estimated again only if the run overtakes it); beside it the capture rate of the
    latest evaluation, as soon as it is measured.

    :param budget_s: the run's budget of training seconds.
    :param training_seconds: the training seconds spent so far, as the budget counts them
        (e.g. :meth:`~agents.training.CaptureCurve.training_seconds`).
    :param stream: where the bar is drawn (stderr by default).
    :param latest_rate: the capture rate of the latest evaluation, None before the first (e.g.
        :meth:`~agents.training.CaptureCurve.latest_rate`).
    """

    def __init__(self, budget_s: float, training_seconds: Callable[[], float], stream: TextIO | None = None,
                 latest_rate: Callable[[], float | None] | None = None) -> None:
        super().__init__()
        self.budget_s, self.training_seconds, self.stream = budget_s, training_seconds, stream
        self.latest_rate = latest_rate
        self.bar: tqdm | None = None
        self._first = self._cap = 0
        self._estimated = False
        self._shown_rate: float | None = None

    def _on_training_start(self) -> None:
        self._first = self.model.num_timesteps
        self._cap = self.locals["total_timesteps"] - self._first
        self.bar = tqdm(total=self._cap, unit="step", unit_scale=True, file=self.stream)

    def _on_step(self) -> bool:
        steps, seconds = self.model.num_timesteps - self._first, self.training_seconds()
        if (not self._estimated and seconds >= WARM_UP_S) or steps > self.bar.total:
            self.bar.total, self._estimated = projected_steps(steps, self._cap, seconds, self.budget_s), True
        rate = None if self.latest_rate is None else self.latest_rate()
        if rate is not None and rate != self._shown_rate:
            self._shown_rate = rate
            self.bar.set_postfix_str(f"last evaluation: {100 * rate:.1f}% caught", refresh=False)
        self.bar.update(steps - self.bar.n)
        return True

    def _on_training_end(self) -> None:
        self.bar.total = self.bar.n  # the run ended here, whichever limit ended it
        self.bar.refresh()
        self.bar.close()
