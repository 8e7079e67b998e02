"""The progress guarantee of a simulation plan's loop: it cannot go round without advancing
simulated time.

A plan (a throw, the pause between throws, the settling of a new net) works in pieces: a flight,
a chunk of integration, a relaxation request. A piece may legitimately take no time (a flight
that finds the ball near something hands over to integration at once), but never many in a
row: :class:`ProgressGuard` allows at most :data:`MAX_STILL_PIECES` such pieces after each
other, and at most :meth:`ProgressGuard.bound` pieces in all between a start and an end time,
and raises :class:`~netgym.errors.NoProgressError` past either, naming the plan and the state,
instead of spinning.
"""

from __future__ import annotations

import math
from collections.abc import Callable

from netgym.errors import NoProgressError

MAX_STILL_PIECES = 4
"""Pieces in a row that may leave the simulated time where it was. The longest such run a throw
takes on purpose is three: a flight that hands over at once, a ball that cannot be stepped
alone after all, and the waking of the scene, before the integration that moves time on."""


class ProgressGuard:
    """Counts a plan's pieces from ``start`` (s of simulated time) to ``end`` with steps of
    ``dt``; ``describe()`` says what the plan does and where it stands, for the error.

    A piece that moves time on by anything takes at least a step, or ends its plan, but for
    one flight cut short at an instant the capture rule decides (then the next piece is back on
    the step grid): so at most ``2 * ceil((end - start) / dt) + 2`` pieces move time on, each
    followed by at most :data:`MAX_STILL_PIECES` that do not.
    """

    def __init__(self, start: float, end: float, dt: float, describe: Callable[[], str]) -> None:
        self.time, self.describe = start, describe
        self.still = 0
        self.pieces = 0
        self.most = self.bound(start, end, dt)

    @staticmethod
    def bound(start: float, end: float, dt: float) -> int:
        """The most pieces a plan from ``start`` to ``end`` with steps of ``dt`` may take."""
        return (MAX_STILL_PIECES + 1) * (2 * math.ceil(max(end - start, 0.0) / dt - 1e-9) + 2)

    def piece(self, time: float) -> None:
        """Book a piece that ended at ``time``; raise :class:`~netgym.errors.NoProgressError` if
        it is one too many without progress, or one too many in all."""
        self.pieces += 1
        if time > self.time:
            self.time, self.still = time, 0
        else:
            self.still += 1
        if self.still > MAX_STILL_PIECES:
            raise NoProgressError(f"{self.describe()}: {self.still} pieces in a row left the simulated time at "
                                  f"{time!r} s (at most {MAX_STILL_PIECES} may); this is a bug in netgym, "
                                  f"please report it with this message")
        if self.pieces > self.most:
            raise NoProgressError(f"{self.describe()}: {self.pieces} pieces, more than the {self.most} its "
                                  f"span of simulated time allows; this is a bug in netgym, please report it "
                                  f"with this message")
