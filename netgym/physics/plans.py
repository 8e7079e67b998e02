"""Plans and their driver.

A plan is a generator that holds all the decisions of a piece of simulation (a throw, the
relaxation of the net) and yields typed requests: :class:`Integrate` (integrate this many
steps), :class:`Relax` (relax for at most this many steps, until a rest test passes) or
:class:`Tick` (time moved in closed form: a moment to observe, e.g. record a frame).
It returns its result. :func:`drive` is the only code that resumes plans: it carries out the
requests of a simulator's plan, one integration call per :class:`Integrate`, and throws a
divergence back into the plan.
"""

from __future__ import annotations

from collections.abc import Callable, Generator
from dataclasses import dataclass
from typing import Any, Protocol, Union

from netgym.physics.integration import Integrand, RestTest, Workspace, integrate, relax
from netgym.physics.model import KernelModel, Settings, State

CHUNK_SECONDS = 0.01          # simulated time between two checks of a plan's decisions


@dataclass(frozen=True)
class Integrate:
    """Request: integrate ``n_steps`` steps of ``dt`` with ``integrator`` (an Integrator code)."""

    n_steps: int
    integrator: int
    dt: float


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


Request = Union[Integrate, Relax, Tick]
Plan = Generator[Request, None, Any]
"""A simulation plan: yields :data:`Request` objects, returns its result."""


class Clock(Protocol):
    """Where integration must stop for an observer (a :class:`~netgym.physics.frames.FrameClock`)."""

    def steps_to_next(self, time: float, dt: float) -> int:
        """Substeps of ``dt`` from ``time`` to the next stop (at least 1)."""


def integrate_until_stops(state: State, request: Integrate, clock: Clock | None) -> Plan:
    """Carry out ``request`` on ``state``, in pieces that end at the stops of ``clock`` when one
    is given. The pieces take the same substeps as the whole and the time ends as the whole's
    would, so a plan that decides between whole requests decides the same with or without it."""
    if clock is None:
        yield request
        return
    end, left = state.time + request.n_steps * request.dt, request.n_steps
    while left > 0:
        n = min(left, clock.steps_to_next(state.time, request.dt))
        yield Integrate(n, request.integrator, request.dt)
        left -= n
    state.time = end


class Drivable(Integrand, Protocol):
    """What :func:`drive` needs of a simulator: :class:`Integrand` and its kernel records."""

    @property
    def kernel_model(self) -> KernelModel:
        """The scene as the kernels take it."""

    def settings(self, integrator: int, dt: float) -> Settings:
        """Kernel settings for this integrator and dt."""


def drive(sim: Drivable, plan: Plan, workspace: Workspace, observer: Callable[[Any], None] | None = None) -> Any:
    """Carry out ``plan`` on ``sim`` until it returns; returns its result.

    Each :class:`Integrate` request is one :func:`~netgym.physics.integration.integrate` call,
    each :class:`Relax` one :func:`~netgym.physics.integration.relax` call;
    the plan is then resumed, with the divergence error of that integration thrown into it if
    there was one. ``observer(sim)`` is called after every request carried out without error,
    for example to record frames.
    """
    error: Exception | None = None
    while True:
        try:
            request = plan.throw(error) if error is not None else next(plan)
        except StopIteration as stop:
            return stop.value
        error = None
        if isinstance(request, Integrate):
            error = integrate(sim, sim.kernel_model, sim.settings(request.integrator, request.dt), request.n_steps,
                              workspace)
        elif isinstance(request, Relax):
            error = relax(sim, sim.kernel_model, sim.settings(request.integrator, request.dt), request.n_steps,
                          workspace, request.rest)
        if error is None and observer is not None:
            observer(sim)
