"""Plans and their driver.

A plan is a generator that holds all the decisions of a piece of simulation (a throw, the
relaxation of the net) and yields typed requests: :class:`Integrate` (integrate this many
steps, or step one ball alone), :class:`Watched` (integrate chunk after chunk until a throw's
watch sees something it could decide), :class:`Relax` (relax for at most this many steps,
until a rest test passes) or :class:`Tick` (time moved in closed form: a moment to observe,
e.g. record a frame).
It returns its result. :func:`drive` is the only code that resumes plans: it carries out the
requests of a simulator's plan, one integration call per :class:`Integrate` (one per piece
between frame instants when it films, with a :class:`~netgym.physics.film.Film`), and throws
a divergence back into the plan.
"""

from __future__ import annotations

from collections.abc import Callable, Generator
from dataclasses import dataclass
from typing import Any, Protocol, Union

from netgym.physics.film import Film

from netgym.physics.integration import Integrand, RestTest, Workspace, integrate, integrate_watched, relax
from netgym.physics.model.model import KernelModel, Settings
from netgym.physics.fast_path.watch import Watch

CHUNK_SECONDS = 0.01          # simulated time between two checks of a plan's decisions


@dataclass(frozen=True)
class Integrate:
    """Request: integrate ``n_steps`` steps of ``dt`` with ``integrator`` (an Integrator code);
    ``alone``: only the ball of this row moves, everything else asleep, for as many of the steps
    as it can touch nothing that moves (-1: everything, every step)."""

    n_steps: int
    integrator: int
    dt: float
    alone: int = -1


@dataclass(frozen=True)
class Watched:
    """Request: integrate chunk after chunk of ``watch.chunk`` steps of ``dt`` with
    ``integrator`` until the :class:`~netgym.physics.fast_path.watch.Watch` sees something that could be
    decided (not for a filmed plan: a film needs every chunk); ``alone``: only the watch's ball
    moves, everything else asleep."""

    integrator: int
    dt: float
    watch: Watch
    alone: bool = False


@dataclass(frozen=True)
class Relax:
    """Request: at most ``n_steps`` steps of dynamic relaxation, until ``rest`` passes (it
    then says so, and how many steps were taken)."""

    n_steps: int
    integrator: int
    dt: float
    rest: RestTest


@dataclass(frozen=True)
class Tick:
    """Request: nothing to integrate; the plan moved time itself (a moment to observe)."""


Request = Union[Integrate, Watched, Relax, Tick]
Plan = Generator[Request, None, Any]
"""A simulation plan: yields :data:`Request` objects, returns its result."""


class Drivable(Integrand, Protocol):
    """What :func:`drive` needs of a simulator: :class:`Integrand` and its kernel records."""

    @property
    def kernel_model(self) -> KernelModel:
        """The scene as the kernels take it."""

    def settings(self, integrator: int, dt: float) -> Settings:
        """Kernel settings for this integrator and dt."""


def drive(sim: Drivable, plan: Plan, workspace: Workspace, film: Film | None = None,
          observer: Callable[[Any], None] | None = None) -> Any:
    """Carry out ``plan`` on ``sim`` until it returns; returns its result.

    Each :class:`Integrate` request is one :func:`~netgym.physics.integration.integrate` call
    (with a ``film``, one per piece between its instants, each filmed: :func:`_integrate_filmed`),
    each :class:`Watched` one :func:`~netgym.physics.integration.integrate_watched` call (never
    filmed: a film needs every chunk), each :class:`Relax` one
    :func:`~netgym.physics.integration.relax` call; the plan is then resumed, with the
    divergence error of that integration thrown into it if there was one. After every request
    carried out without error the ``film`` films and ``observer(sim)`` is called.
    """
    error: Exception | None = None
    while True:
        try:
            request = plan.throw(error) if error is not None else next(plan)
        except StopIteration as stop:
            return stop.value
        error = None
        if isinstance(request, Integrate) and film is not None:
            error = _integrate_filmed(sim, request, workspace, film)
            continue  # filmed piece by piece
        if isinstance(request, Integrate):
            error = integrate(sim, sim.kernel_model, sim.settings(request.integrator, request.dt), request.n_steps,
                              workspace, request.alone)
        elif isinstance(request, Watched):
            if film is not None:
                raise TypeError("a filmed plan integrates chunk by chunk (Integrate requests), not Watched ones")
            error = integrate_watched(sim, sim.kernel_model, sim.settings(request.integrator, request.dt), workspace,
                                      request.watch, request.alone)
        elif isinstance(request, Relax):
            error = relax(sim, sim.kernel_model, sim.settings(request.integrator, request.dt), request.n_steps,
                          workspace, request.rest)
        if error is not None:
            continue
        if film is not None:
            film(sim, request.dt if isinstance(request, Relax) else None)
        if observer is not None:
            observer(sim)


def _integrate_filmed(sim: Drivable, request: Integrate, workspace: Workspace, film: Film) -> Exception | None:
    """Carry out ``request`` in pieces that end at the substeps nearest the instants of the
    film's clock, filming after each. The pieces
    take the same substeps as the whole and the time ends as the whole's would, so a plan that
    decides between whole requests decides the same, filmed or not. Returns the divergence
    error of a piece, if one diverged (the state is then as before that piece)."""
    state, settings = sim.state, sim.settings(request.integrator, request.dt)
    end, left = state.time + request.n_steps * request.dt, request.n_steps
    while left > 0:
        n = min(left, film.clock.steps_to_next(state.time, request.dt))
        piece_end = state.time + n * request.dt
        error = integrate(sim, sim.kernel_model, settings, n, workspace, request.alone)
        if error is not None:
            return error
        left -= n
        film(sim, request.dt)
        if state.time < piece_end - 0.5 * request.dt:
            return None  # a ball stepped alone stopped short: it could touch something that moves
    state.time = end
    return None
