"""Throws: one ball launched into a simulator's scene and simulated until its outcome is decided.

:func:`throw` (or :func:`throw_plan`, the same as a plan) is the entry point; the recipe is
:class:`~netgym.physics.throw.recipe.Throw`, its decisions are in
:mod:`~netgym.physics.throw.decisions`, the ball's free flight is
:class:`~netgym.physics.throw.free_flight.FreeFlight`.
"""

from __future__ import annotations

import functools
import warnings
from collections.abc import Callable
from typing import Any

from netgym.physics.film import Film
from netgym.physics.simulator import Simulator
from netgym.physics.throw.free_flight import FreeFlight
from netgym.physics.throw.recipe import Throw, throw, throw_plan
from netgym.physics.throw.records import TUNING, FastPathTuning, ThrowResult

__all__ = ["TUNING", "FastPathTuning", "FreeFlight", "Throw", "ThrowResult", "throw", "throw_plan"]


def _deprecated_method(function: Callable[..., Any]) -> Callable[..., Any]:
    """``Simulator.<name>`` as it was before throws left the simulator: ``function(sim, ...)``
    with a DeprecationWarning, a film passed as the old ``observer`` taken as the film."""

    @functools.wraps(function)
    def method(sim: Simulator, position: Any, velocity: Any, fast: bool = True, observer: Any = None) -> Any:
        warnings.warn(f"Simulator.{function.__name__} is deprecated; use netgym.physics.throw."
                      f"{function.__name__}(sim, position, velocity, fast, film)", DeprecationWarning, stacklevel=2)
        if function is throw_plan:
            return throw_plan(sim, position, velocity, fast)
        film = observer if isinstance(observer, Film) else None
        return throw(sim, position, velocity, fast, film, None if film is not None else observer)

    return method


Simulator.throw = _deprecated_method(throw)  # type: ignore[attr-defined]
Simulator.throw_plan = _deprecated_method(throw_plan)  # type: ignore[attr-defined]
