"""Integration of one state of a scene: the one Python entry to the stepping kernels.

:func:`integrate`, :func:`integrate_watched` and :func:`relax` own the bookkeeping around
:func:`~netgym.physics.stepping.advance`, :func:`~netgym.physics.fast_path.watch.integrate_watched` and
:func:`~netgym.physics.stepping.relax`: a copy of the state before, the simulated time after,
and on divergence the restored state and a :class:`~netgym.errors.SimulationDivergedError`.
The state is integrated in place.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Protocol

import numpy as np

from netgym.errors import SimulationDivergedError
from netgym.physics import stepping
from netgym.physics.kernels.integrators import Scratch
from netgym.kinds import Integrator
from netgym.physics.model.model import KernelModel, Settings, State
from netgym.physics.fast_path.watch import Watch
from netgym.physics.fast_path.watch import integrate_watched as integrate_kernel
from netgym.physics.fast_path.watch import roll_watched


class Integrand(Protocol):
    """What :func:`integrate` needs of a simulator."""

    state: State
    counters: np.ndarray

    def divergence_advice(self, integrator: int) -> str:
        """What to change when ``integrator`` diverged."""


class Workspace:
    """Scratch arrays of the kernels, kept between calls and re-sized to the states they meet."""

    def __init__(self) -> None:
        self._arrays: dict[str, np.ndarray] = {}

    def array(self, name: str, shape: tuple[int, ...], dtype: type = np.float64) -> np.ndarray:
        """The array called ``name``, zeroed anew whenever ``shape`` changes."""
        array = self._arrays.get(name)
        if array is None or array.shape != shape:
            array = self._arrays[name] = np.zeros(shape, dtype=dtype)
        return array

    def scratch(self, state: State, model: KernelModel) -> Scratch:
        """Integrator scratch for ``state``'s bodies and ``model``'s springs, with its anchors."""
        work, coef, coef_dt = Scratch.shapes(state.x.shape[0], model.springs.pairs.shape[0])
        return Scratch(self.array("work", work), self.array("coef", coef), self.array("coef_dt", coef_dt),
                       state.anchors)


class RestTest:
    """What a relaxation remembers between kernel calls: the positions of its last ``window``
    steps, its last kinetic energy, and whether no coordinate moved more than ``displacement``
    (m) over the window; ``damped``: the net is kinetically damped meanwhile, ``inertia``: the
    net's inertia as a multiple of its mass meanwhile (see :func:`~netgym.physics.stepping.relax`)."""

    def __init__(self, shape: tuple[int, int], window: int, displacement: float, damped: bool = True,
                 inertia: float = 1.0) -> None:
        self.record = stepping.RestRecord(np.zeros((max(1, window), *shape)), stepping.new_rest_memory(),
                                          float(displacement), bool(damped), float(inertia))

    @property
    def steps(self) -> int:
        """Steps taken by the last kernel call."""
        return int(self.record.memory[0]["steps"])

    @property
    def at_rest(self) -> bool:
        """True once the rest test has passed."""
        return bool(self.record.memory[0]["at_rest"])


def integrate(target: Integrand, model: KernelModel, settings: Settings, n_steps: int,
              workspace: Workspace, alone: int = -1) -> SimulationDivergedError | None:
    """Advance ``target.state`` by ``n_steps`` steps (none when 0), in place, and add the work
    to its counters; ``alone``: the row of a ball stepped alone, everything else asleep, for as
    many of them as it can touch nothing that moves
    (:func:`~netgym.physics.stepping.advance_alone`), or -1. Returns None, or the error
    when the integration diverged (the state is then restored as it was before the call)."""
    s = target.state
    if alone >= 0:
        def alone_kernel() -> tuple[int, float]:
            status, taken = stepping.advance_alone(s.x, s.v, s.inv_mass, s.entered, model, settings, n_steps, alone,
                                                   target.counters)
            return status, s.time + taken * settings.dt
        return _guarded(target, settings, n_steps, alone_kernel)
    return _guarded(target, settings, n_steps, lambda: (stepping.advance(
        s.x, s.v, s.inv_mass, s.entered, model, settings, n_steps,
        workspace.scratch(s, model), target.counters), s.time + n_steps * settings.dt))


def integrate_watched(target: Integrand, model: KernelModel, settings: Settings, workspace: Workspace,
                      watch: Watch, alone: bool = False) -> SimulationDivergedError | None:
    """Integrate ``target.state`` chunk after chunk until ``watch`` sees something that could
    be decided (see :func:`~netgym.physics.fast_path.watch.integrate_watched`; ``alone``: the
    watch's ball alone, everything else asleep, :func:`~netgym.physics.fast_path.watch.roll_watched`);
    returns as :func:`integrate` does."""
    s = target.state
    if alone:
        return _guarded(target, settings, round((watch.deadline - s.time) / settings.dt), lambda: roll_watched(
            s.x, s.v, s.inv_mass, s.entered, model, settings, target.counters, watch, s.time))
    return _guarded(target, settings, round((watch.deadline - s.time) / settings.dt), lambda: integrate_kernel(
        s.x, s.v, s.inv_mass, s.entered, model, settings, workspace.scratch(s, model),
        target.counters, watch, s.time))


def relax(target: Integrand, model: KernelModel, settings: Settings, n_steps: int, workspace: Workspace,
          rest: RestTest) -> SimulationDivergedError | None:
    """Relax ``target.state`` for at most ``n_steps`` steps, until ``rest`` passes (see
    :func:`~netgym.physics.stepping.relax`); returns as :func:`integrate` does. A net without
    balls (a new net settling) is relaxed by the kernels compiled without the balls' passes."""
    s = target.state
    return _guarded(target, settings, n_steps, lambda: (stepping.relax(
        s.x, s.v, s.inv_mass, s.entered if s.entered.size else None, model, settings, n_steps,
        workspace.scratch(s, model), target.counters, rest.record),
        s.time + rest.steps * settings.dt))


def _guarded(target: Integrand, settings: Settings, n_steps: int,
             kernel: Callable[[], tuple[int, float]]) -> SimulationDivergedError | None:
    """Run ``kernel()`` (returning its status and the time it reached) on a copy-guarded state:
    the time moves on to that reached, or the state is restored and the error returned
    (``n_steps``: the most steps the call could take, for the error)."""
    s = target.state
    before = s.copy()
    status, time = kernel()
    if status == stepping.OK:
        s.time = time
        return None
    s.restore(before)
    return SimulationDivergedError(
        f"{Integrator(settings.integrator).label} at dt = {settings.dt:g} s diverged (a speed exceeded "
        f"{settings.divergence_speed:g} m/s or became non-finite) within {n_steps} steps from "
        f"t = {before.time:g} s; the state was restored. {target.divergence_advice(settings.integrator)}")
