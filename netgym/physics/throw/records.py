"""What a throw keeps and returns: its tuning, its course from launch to decision, its result."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, NamedTuple

import numpy as np

from netgym.physics.film import Film
from netgym.physics.outcomes import CaptureRule, Reason
from netgym.physics.throw.free_flight import FreeFlight
from netgym.physics.kernels.surroundings import LoneBall
from netgym.physics.fast_path.watch import Watch

if TYPE_CHECKING:
    from netgym.physics.simulator import Simulator


@dataclass(frozen=True)
class FastPathTuning:
    """The fast path's tuning: how near is near, how still is at rest, how long a decided throw
    is filmed on. These trade work for nothing the outcome depends on (the tests compare the
    fast path with the full simulation); change them with the agreement tests at hand."""

    rest_window: float = 0.1      # s during which a ball and its surroundings must stay slow to be "at rest"
    rest_reach: float = 0.2       # m around a ball within which moving bodies keep it from being at rest
    clearance: float = 0.02       # m: closer than this to anything, a ball is simulated, not flown
    awake_margin: float = 0.5     # m the moving net may reach beyond its current bounding box
    time_epsilon: float = 1e-9    # s: instants closer than this are the same
    air_piece: float = 0.1        # s: longest piece of a flight through air between two clearance checks
    sleep_speed: float = 5e-2     # m/s: a net (and balls in it) slower than this may stop being integrated
                                  # (half the pause's settle speed; 1 cm/s kept a jittering net awake)
    far_clearance: float = 0.15   # m: a ball this clear of everything may fly while a net slower than
    far_sleep_speed: float = 0.3  # m/s goes to sleep (a net swaying after a ball left it off the rim)
    line_time_tolerance: float = 1e-4  # s: a flown ball's capture-rule decision comes at most this late
    miss_filmed_after_landing: float = 0.5  # s of a missed ball's flight filmed after it first lands
    rule_filmed: float = 0.5      # s filmed on after the capture rule decided (a goal running into the net)


TUNING = FastPathTuning()


@dataclass(frozen=True)
class ThrowResult:
    """Outcome of one throw.

    :param captured: caught by the scene's ``capture_rule``: ``"held"``, the ball came in through
        the opening and is inside the net; ``"line"``, the whole ball crossed the opening's plane
        inside the frame (it is out of play, a miss, once wholly over it beside the frame).
    :param entered: the ball's centre crossed the opening inwards (and did not leave through it).
    :param final_position: ball centre when the outcome was decided (m).
    :param final_velocity: ball velocity then (m/s).
    :param time: simulated seconds from launch to the decision.
    :param substeps: integration substeps spent on the throw (0 when decided in closed form).
    :param reason: why it was decided then, a :class:`~netgym.physics.outcomes.Reason` of this
        outcome (equal to its string value, as ``info["reason"]`` reports it).
    :param settle_substeps: integration substeps spent bringing the net to rest before the launch.
    :param settle_time: simulated seconds of that settling.
    """

    captured: bool
    entered: bool
    final_position: np.ndarray
    final_velocity: np.ndarray
    time: float
    substeps: int
    reason: Reason
    settle_substeps: int = 0
    settle_time: float = 0.0


class Ball(NamedTuple):
    """The thrown ball: its ``index`` among the balls, its ``row`` among the bodies."""

    index: int
    row: int


@dataclass
class Course:
    """What a throw keeps from its launch to its decision."""

    launched: float               # simulated time of the launch: the origin of the full simulation's step grid
    deadline: float               # the launch plus the time limit
    substeps: int                 # the simulator's substeps at the launch
    about: float                  # the ball's radius + the largest radius about the other bodies (a pole's, a ball's)
    from_front: bool              # launched in front of the opening's plane: it can go out of play
    watch: Watch                  # what the checks after each chunk look at (the energy bound, the rest window)
    decision: Reason | None = None  # the capture rule's, once it decided


@dataclass
class ThrowContext:
    """One throw under way: the simulator ``sim`` it is thrown into, whether it takes the
    ``fast`` path, the scene's capture ``rule``, the ``film`` it is filmed with (or None), the
    ball's ``free_flight`` and its ``lone`` record (what a check of the ball alone reads), the
    thrown ``ball`` and its ``course`` (from the launch on)."""

    sim: "Simulator"
    fast: bool
    rule: CaptureRule
    film: Film | None
    free_flight: FreeFlight
    lone: LoneBall
    ball: Ball = Ball(-1, -1)
    course: Course | None = None
