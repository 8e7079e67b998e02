"""What each entry of a NetCatch observation vector is: its position, meaning and unit; and
what an observation tells an aim: the thrower it describes, the launch through the opening's
centre."""

from __future__ import annotations

import math
from enum import IntEnum

import numpy as np

from netgym.aim import BallisticAim
from netgym.launch import Thrower


class ObservationIndex(IntEnum):
    """Where each quantity sits in a NetCatch observation (``env.observation_structure`` maps
    the lower-case names to these positions); each member's ``meaning`` and ``unit`` say what it
    is. The ``LAST_*`` entries are there only with ``feedback=True``."""

    meaning: str
    unit: str

    def __new__(cls, index: int, meaning: str, unit: str) -> ObservationIndex:
        member = int.__new__(cls, index)
        member._value_ = index
        member.meaning, member.unit = meaning, unit
        return member

    DISTANCE = 0, "horizontal distance from the thrower to the opening's centre", "m"
    HEIGHT = 1, "release height minus the opening centre's height", "m"
    BEARING_COS = 2, "cosine of the thrower's bearing around the net", "-"
    BEARING_SIN = 3, "sine of the thrower's bearing", "-"
    CAUGHT = 4, "balls caught so far / balls per episode", "-"
    THROWS_LEFT = 5, "throws left / balls per episode", "-"
    PILE_HEIGHT = 6, ("height of the highest caught ball, at rest, minus the opening centre's height (the net's "
                      "lowest point when none)"), "m"
    LAST_CAUGHT = 7, "the previous throw was caught (0 or 1; 0 before the first)", "-"
    LAST_OFFSET_U = 8, ("where the previous throw's free flight crossed the opening's plane, minus its centre, along "
                        "the plane's first axis (world x for the basket, y for the goal)"), "m"
    LAST_OFFSET_W = 9, "the same along the plane's second axis (world y for the basket, z for the goal)", "m"
    LAST_SHORT = 10, "how far short of the opening's plane that flight stayed (0 when it crossed)", "m"


def thrower_of(observation: np.ndarray, centre: np.ndarray) -> Thrower:
    """The thrower an observation describes, around the opening's ``centre``."""
    bearing = math.degrees(math.atan2(observation[ObservationIndex.BEARING_SIN],
                                      observation[ObservationIndex.BEARING_COS]))
    return Thrower(distance=float(observation[ObservationIndex.DISTANCE]), bearing=bearing,
                   height=float(observation[ObservationIndex.HEIGHT]) + float(centre[2]),
                   centre=(float(centre[0]), float(centre[1])))


def aim_at_centre(aim: BallisticAim, observation: np.ndarray) -> np.ndarray:
    """The action of ``aim`` through the opening's centre for one observation: the parabola of
    the observed distance and height, or, with air, the aim through air from the thrower the
    observation describes."""
    if aim.drag == 0.0:
        return aim.action(float(observation[ObservationIndex.DISTANCE]), float(observation[ObservationIndex.HEIGHT]))
    return aim.aim(thrower_of(observation, aim.opening.centre), aim.opening.centre)
