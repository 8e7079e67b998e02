"""A watchdog for a run of plans that must end (an environment step): a generous bound of
requests and of wall seconds, past which it stops the run with a named error that says what
the run was doing, so that a training job stops with a message instead of hanging a worker.

Every plan of the simulator already guarantees progress (:mod:`netgym.physics.progress_guard`);
the watchdog is the last line behind that guarantee. It is a plan observer (see
:meth:`~netgym.physics.simulator.Simulator.run`): it checks after every request, and leaves
the seconds numba spends compiling kernels out of the wall time it measures.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from typing import Any

from netgym.errors import StepTimeoutError
from netgym.physics.compile_notice import compile_seconds

MAX_REQUESTS = 200_000
"""Requests a watched run may carry out: a throw's plan takes at most a few thousand, and the
pause after it at most a few hundred."""
MAX_SECONDS = 120.0
"""Wall seconds a watched run may take, compiling left out: a step takes milliseconds."""


class Watchdog:
    """Bounds a run to ``max_requests`` requests and ``max_seconds`` wall seconds (compiling
    left out; by default :data:`MAX_REQUESTS` and :data:`MAX_SECONDS`) from its creation;
    ``describe()`` names the run for the error (e.g. the throw's launch), called only then.
    Call it after every request (pass it as a plan's observer); it raises
    :class:`~netgym.errors.StepTimeoutError` past either bound."""

    def __init__(self, describe: Callable[[], str], max_requests: int | None = None, max_seconds: float | None = None,
                 clock: Callable[[], float] = time.perf_counter,
                 compiling: Callable[[], float] = compile_seconds) -> None:
        self.describe = describe
        self.max_requests = MAX_REQUESTS if max_requests is None else max_requests
        self.max_seconds = MAX_SECONDS if max_seconds is None else max_seconds
        self.clock, self.compiling = clock, compiling
        self.started = clock() - compiling()
        self.requests = 0

    def seconds(self) -> float:
        """Wall seconds since the start, compiling left out."""
        return self.clock() - self.compiling() - self.started

    def __call__(self, sim: Any) -> None:
        self.requests += 1
        seconds = self.seconds()
        if self.requests > self.max_requests or seconds > self.max_seconds:
            raise StepTimeoutError(
                f"{self.describe()} was stopped by its watchdog after {self.requests} requests and {seconds:.1f} s "
                f"(bounds: {self.max_requests} requests, {self.max_seconds:g} s, compiling left out), at simulated "
                f"time {sim.state.time!r} s; this is a bug in netgym, please report it with this message")
