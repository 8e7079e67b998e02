"""Progress of long simulation work (the settling of a large net), shown on stderr.

Quiet for work that ends within ``quiet`` wall seconds; after that, one line rewritten in place
about every ``every`` seconds, with the simulated time done, its bound and the wall time spent.
In a worker process (``multiprocessing``: vectorised environments), whose siblings write to the
same stderr, whole lines named by the process id instead, at most every :data:`WORKER_EVERY` s.
"""

from __future__ import annotations

import multiprocessing
import os
import sys
import time
from typing import Any, TextIO

WORKER_EVERY = 10.0
"""Seconds between the progress lines of a worker process."""


class Progress:
    """A plan observer (see :meth:`Simulator.run`) that reports ``what`` while it lasts.

    :param what: what is being done, e.g. ``"settling the net"``.
    :param bound: the most simulated seconds the work can take.
    :param worker: write whole lines named by the process id (default: in a ``multiprocessing``
        child process).
    """

    def __init__(self, what: str, bound: float, quiet: float = 2.0, every: float = 1.0,
                 stream: TextIO | None = None, worker: bool | None = None) -> None:
        self.worker = multiprocessing.parent_process() is not None if worker is None else worker
        self.what, self.bound, self.quiet = what, bound, quiet
        self.every = max(every, WORKER_EVERY) if self.worker else every
        self.stream = sys.stderr if stream is None else stream
        self.started = time.perf_counter()  # restarted at the first observation
        self.shown_at: float | None = None
        self.sim_start: float | None = None

    def __call__(self, sim: Any) -> None:
        now = time.perf_counter()
        if self.sim_start is None:  # the first request is done: the kernels are compiled, time from here
            self.sim_start, self.started = sim.state.time, now
            return
        if now - self.started < self.quiet or (self.shown_at is not None and now - self.shown_at < self.every):
            return
        self.shown_at = now
        done = sim.state.time - self.sim_start
        rate = done / (now - self.started)
        line = (f"{self.what}: {done:.2f} of at most {self.bound:g} s simulated, "
                f"{now - self.started:.0f} s so far ({rate:.2f} simulated s per s)")
        self.stream.write(f"process {os.getpid()}, {line}\n" if self.worker else f"\r{line}")
        self.stream.flush()

    def close(self) -> None:
        """End the line, if anything was shown in place."""
        if self.shown_at is not None and not self.worker:
            self.stream.write("\n")
            self.stream.flush()
