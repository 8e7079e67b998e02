"""The frame clock: the simulated instants at which frames of a simulation are taken.

Frames are ``period`` simulated seconds apart from an anchor. Plans that are given a clock end
their integration chunks at the substep nearest each instant (and move closed-form flights to
the instants exactly), so that a video played at ``1 / period`` frames per second runs at the
simulation's own pace; a :class:`Film`, the observer that records the frames, asks
:meth:`FrameClock.take` whether now is an instant.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

from netgym.arguments import is_real
from netgym.errors import InvalidArgumentError


class FrameClock:
    """Frame instants ``anchor + k * period`` (k = 0, 1, ...), each taken at most once.

    :param period: simulated seconds between frames (> 0).
    :param anchor: simulated time of the first instant.
    """

    def __init__(self, period: float, anchor: float = 0.0) -> None:
        if not is_real(period) or not math.isfinite(period) or period <= 0.0:
            raise InvalidArgumentError(f"period = {period!r}; allowed: a finite number of seconds > 0")
        self.period = float(period)
        self.restart(anchor)

    def restart(self, anchor: float) -> None:
        """Start the instants afresh at ``anchor`` (after a jump in time that was not filmed)."""
        self.anchor = float(anchor)
        self._taken = -1
        self.paused = False

    def pause(self) -> None:
        """Take no frames until the next :meth:`restart` (time that is not filmed)."""
        self.paused = True

    def next_instant(self, time: float, slack: float = 0.0) -> float:
        """The first instant later than ``time + slack``."""
        k = math.floor((time + slack - self.anchor) / self.period) + 1
        return self.anchor + k * self.period

    def steps_to_next(self, time: float, dt: float) -> int:
        """Substeps of ``dt`` from ``time`` to the one nearest the next instant (at least 1)."""
        return max(1, round((self.next_instant(time, 0.5 * dt) - time) / dt))

    def take(self, time: float, slack: float) -> bool:
        """True, once, when ``time`` is within ``slack`` of an instant not yet taken."""
        if self.paused:
            return False
        k = round((time - self.anchor) / self.period)
        if k <= self._taken or abs(time - (self.anchor + k * self.period)) > slack:
            return False
        self._taken = k
        return True


class Film:
    """An observer that films a simulation: ``record(sim)`` once at each instant of ``clock``
    (within half a step). Handed to :meth:`~netgym.physics.simulator.Simulator.run`, it makes
    the plans stop at the clock's instants (integration at the substep nearest each, closed-form
    flights at the instant itself).

    :param clock: the frame instants.
    :param record: takes a frame of the simulator.
    :param settling: also film the pauses between throws (else the clock pauses over them).
    """

    def __init__(self, clock: FrameClock, record: Callable[[Any], None], settling: bool = False) -> None:
        self.clock = clock
        self.record = record
        self.settling = settling

    def __call__(self, sim: Any, step: float | None = None) -> None:
        """Record ``sim`` if now is an instant of the clock not yet taken (within half the
        ``step`` just taken: the scene's dt unless given, the pause's in a relaxation)."""
        if self.clock.take(sim.state.time, 0.5 * (sim.dt if step is None else step) + 1e-9):
            self.record(sim)
