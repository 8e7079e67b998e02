"""Integration of one or many states of a scene: the one Python entry to the stepping kernels.

:func:`integrate` owns the bookkeeping around :func:`~netgym.physics.stepping.advance`: a copy
of each state before, the simulated time after, and on divergence the restored state and a
:class:`~netgym.errors.SimulationDivergedError`. One state is integrated in place; many are
integrated in one parallel numba call over padded copies, with identical results.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Protocol

import numpy as np

from netgym.errors import SimulationDivergedError
from netgym.physics import stepping
from netgym.physics.integrators import Scratch
from netgym.physics.kinds import Integrator
from netgym.physics.model import KernelModel, Settings, State


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

    def scratch(self, n_bodies: int, n_springs: int) -> Scratch:
        """Integrator scratch for one state of this size."""
        work, coef = Scratch.shapes(n_bodies, n_springs)
        return Scratch(self.array("work", work), self.array("coef", coef))


def integrate(targets: Sequence[Integrand], model: KernelModel, settings: Settings, n_steps: Sequence[int],
              workspace: Workspace) -> list[SimulationDivergedError | None]:
    """Advance ``targets[i].state`` by ``n_steps[i]`` steps (none when 0), in place, and add the
    work to its counters. Returns one entry per target: None, or the error of a target whose
    integration diverged (its state is then restored as it was before the call)."""
    befores = [t.state.copy() for t in targets]
    if len(targets) == 1:
        s = targets[0].state
        status = [stepping.advance(s.x, s.v, s.inv_mass, s.entered, model, settings, n_steps[0],
                                   workspace.scratch(s.x.shape[0], model.springs.shape[0]), targets[0].counters)]
    else:
        status = _advance_padded(targets, model, settings, n_steps, workspace)
    errors: list[SimulationDivergedError | None] = []
    for target, before, steps, code in zip(targets, befores, n_steps, status):
        if code == stepping.OK:
            target.state.time += steps * settings.dt
            errors.append(None)
            continue
        target.state.restore(before)
        errors.append(SimulationDivergedError(
            f"{Integrator(settings.integrator).label} at dt = {settings.dt:g} s diverged (a speed exceeded "
            f"{settings.divergence_speed:g} m/s or became non-finite) within {steps} steps from "
            f"t = {before.time:g} s; the state was restored. {target.divergence_advice(settings.integrator)}"))
    return errors


def _advance_padded(targets: Sequence[Integrand], model: KernelModel, settings: Settings, n_steps: Sequence[int],
                    workspace: Workspace) -> list[int]:
    """Many states in one parallel call, over copies padded to the largest of them."""
    count, n_net = len(targets), model.n_net
    n_bodies = np.array([t.state.x.shape[0] for t in targets], dtype=np.int64)
    rows = int(n_bodies.max())
    x = workspace.array("x", (count, rows, 3))
    v = workspace.array("v", (count, rows, 3))
    inv_mass = workspace.array("inv_mass", (count, rows))
    entered = workspace.array("entered", (count, rows - n_net), np.int8)
    work_shape, coef_shape = Scratch.shapes(rows, model.springs.shape[0])
    work = workspace.array("batch_work", (count, *work_shape))
    coef = workspace.array("batch_coef", (count, *coef_shape))
    stats = np.concatenate([t.counters for t in targets])
    for e, t in enumerate(targets):
        n = n_bodies[e]
        x[e, :n], v[e, :n], inv_mass[e, :n] = t.state.x, t.state.v, t.state.inv_mass
        entered[e, :n - n_net] = t.state.entered
    status = np.zeros(count, dtype=np.int64)
    stepping.advance_batch(x, v, inv_mass, entered, n_bodies, np.asarray(n_steps, dtype=np.int64), model, settings,
                           work, coef, stats, status)
    for e, t in enumerate(targets):
        n = n_bodies[e]
        t.state.x[:], t.state.v[:] = x[e, :n], v[e, :n]
        t.state.entered[:] = entered[e, :n - n_net]
        t.counters[:] = stats[e]
    return status.tolist()
