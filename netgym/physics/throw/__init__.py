"""Throws: one ball launched into a simulator's scene and simulated until its outcome is decided.

:func:`throw` (or :func:`throw_plan`, the same as a plan) is the entry point; the recipe is
:class:`~netgym.physics.throw.recipe.Throw`, its decisions are in
:mod:`~netgym.physics.throw.decisions`, the ball's free flight is
:class:`~netgym.physics.throw.free_flight.FreeFlight`.
"""

from __future__ import annotations

from netgym.physics.throw.free_flight import FreeFlight
from netgym.physics.throw.recipe import Throw, throw, throw_plan
from netgym.physics.throw.records import TUNING, FastPathTuning, ThrowResult

__all__ = ["TUNING", "FastPathTuning", "FreeFlight", "Throw", "ThrowResult", "throw", "throw_plan"]

