"""How a throw's outcome is decided: the reasons a throw ends, and the capture rules.

A :class:`Reason` says why a throw was decided when it was; its values are the strings of
``ThrowResult.reason`` and ``info["reason"]``. A capture rule (:class:`HeldRule`,
:class:`LineRule`; :func:`capture_rule` picks the scene's once) says what may decide a throw
besides the fast path's own reasons, what counts as a capture, and whether a captured ball
stays in the scene.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from enum import StrEnum

import numpy as np

from netgym.errors import InvalidArgumentError
from netgym.physics.model.opening import Opening

class Reason(StrEnum):
    """Why a throw's outcome was decided (equal to its string value). Each labels one outcome:
    a decision that can end either way (the ball at rest, out of energy, out of time) has a
    reason for a caught ball and one for a miss (:meth:`for_outcome`)."""

    FLIES_AWAY = "flies_away"                          # a miss: it left the net's surroundings for good
    AT_REST = "at_rest"                                # a miss: it and everything near it stopped moving
    AT_REST_IN_NET = "at_rest_in_net"                  # caught: it and everything near it stopped moving
    CANNOT_REACH_OPENING = "cannot_reach_opening"      # a miss: no energy left to get it to the opening
    CANNOT_LEAVE = "cannot_leave"                      # caught: no energy left to get it back out
    CROSSED_LINE = "crossed_line"                      # caught, ``line``: wholly over the line inside the frame
    OUT_OF_PLAY = "out_of_play"                        # a miss, ``line``: wholly over the line beside the frame
    TIME_LIMIT = "time_limit"                          # a miss: the scene's simulation.time_limit ran out
    TIME_LIMIT_IN_NET = "time_limit_in_net"            # caught: the time limit ran out with it in the net

    def for_outcome(self, captured: bool) -> "Reason":
        """The reason that says how a throw with this outcome (``captured``) was decided: the
        caught counterpart of a decision that can end either way, else this one."""
        return _CAUGHT.get(self, self) if captured else self


_CAUGHT = {Reason.AT_REST: Reason.AT_REST_IN_NET, Reason.CANNOT_REACH_OPENING: Reason.CANNOT_LEAVE,
           Reason.TIME_LIMIT: Reason.TIME_LIMIT_IN_NET}


class HeldRule:
    """``held`` (the basket's): a ball is caught if it came in through the opening and is inside
    the box when the throw is decided; nothing but the fast path's own reasons decides a throw,
    and a caught ball stays in the net."""

    keeps_captured = True

    def decision(self, opening: Opening, radius: float, position: np.ndarray, entered: bool,
                 from_front: bool) -> Reason | None:
        """The rule decides nothing by itself: always None."""
        return None

    def decision_depth(self, radius: float) -> float:
        """Past the opening's plane, the least depth at which the rule may decide a ball of
        ``radius``: never (inf)."""
        return math.inf

    def captured(self, decision: Reason | None, entered: bool, inside: bool) -> bool:
        """Caught: it ``entered`` through the opening and is ``inside`` the box."""
        return entered and inside

    def decision_instant(self, tau: float, decided_at: Callable[[float], bool], tolerance: float) -> float:
        """A flight of ``tau`` is never cut short by this rule: ``tau``."""
        return tau


class LineRule:
    """``line`` (the goal's): the throw is decided once the whole ball is past the opening's
    plane, a goal (:attr:`Reason.CROSSED_LINE`) if it came in through the frame, out of play
    (:attr:`Reason.OUT_OF_PLAY`) if it crossed beside it (as over the bar or wide of a post in
    the sport; only for a ball launched in front of the line). A goal is taken out of the scene,
    as after a goal in the sport."""

    keeps_captured = False

    def decision(self, opening: Opening, radius: float, position: np.ndarray, entered: bool,
                 from_front: bool) -> Reason | None:
        """The decision on a ball of ``radius`` at ``position`` (``entered``: it came in through
        the frame; ``from_front``: launched before the line); None while any of it is in front of
        the plane, or it is behind the line without having crossed it."""
        if opening.depth(position) < self.decision_depth(radius):
            return None
        if entered:
            return Reason.CROSSED_LINE
        return Reason.OUT_OF_PLAY if from_front else None

    def decision_depth(self, radius: float) -> float:
        """Past the opening's plane, the least depth at which the rule may decide a ball of
        ``radius``: its radius (the whole ball past the plane)."""
        return radius

    def captured(self, decision: Reason | None, entered: bool, inside: bool) -> bool:
        """Caught: the rule decided a goal."""
        return decision is Reason.CROSSED_LINE

    def decision_instant(self, tau: float, decided_at: Callable[[float], bool], tolerance: float) -> float:
        """``tau``, or, if the rule has decided by then (``decided_at(t)``: it has after a
        flight of ``t``), the first instant it has, found by bisection within
        ``tolerance`` after it."""
        if not decided_at(tau):
            return tau
        lo, hi = 0.0, tau
        while hi - lo > tolerance:
            mid = 0.5 * (lo + hi)
            lo, hi = (lo, mid) if decided_at(mid) else (mid, hi)
        return hi


CaptureRule = HeldRule | LineRule
_RULES: dict[str, CaptureRule] = {"held": HeldRule(), "line": LineRule()}


def capture_rule(name: str) -> CaptureRule:
    """The rule a scene's ``capture_rule`` names (``"held"`` or ``"line"``)."""
    if name not in _RULES:
        raise InvalidArgumentError(f"capture_rule = {name!r} is not one of {list(_RULES)}")
    return _RULES[name]
