"""Progress of long simulation work (the settling of a large net), shown on stderr.

Quiet for work that ends within ``quiet`` wall seconds; after that, one line rewritten in place
about every ``every`` seconds, with the simulated time done, its bound and the wall time spent.
"""

from __future__ import annotations

import sys
import time
from typing import Any, TextIO


class Progress:
    """A plan observer (see :meth:`Simulator.run`) that reports ``what`` while it lasts.

    :param what: what is being done, e.g. ``"settling the net"``.
    :param bound: the most simulated seconds the work can take.
    """

    def __init__(self, what: str, bound: float, quiet: float = 2.0, every: float = 1.0,
                 stream: TextIO | None = None) -> None:
        self.what, self.bound, self.quiet, self.every = what, bound, quiet, every
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
        self.stream.write(f"\r{self.what}: {done:.2f} of at most {self.bound:g} s simulated, "
                          f"{now - self.started:.0f} s so far ({rate:.2f} simulated s per s)")
        self.stream.flush()

    def close(self) -> None:
        """End the line, if anything was shown."""
        if self.shown_at is not None:
            self.stream.write("\n")
            self.stream.flush()
