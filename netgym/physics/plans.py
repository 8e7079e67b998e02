"""Plans and their driver.

A plan is a generator that holds all the decisions of a piece of simulation (a throw, the
relaxation of the net) and yields typed requests: :class:`Integrate` (integrate this many
steps) or :class:`Tick` (time moved in closed form: a moment to observe, e.g. record a frame).
It returns its result. :func:`drive` is the only code that resumes plans: it carries out the
requests of one or many simulators, integrating all pending requests of one kind in one call
(parallel across simulators), and throws a divergence back into the plan whose state failed.
"""

from __future__ import annotations

from collections.abc import Callable, Generator, Sequence
from dataclasses import dataclass
from typing import Any, Protocol, Union

from netgym.errors import NetgymError
from netgym.physics.integration import Integrand, Workspace, integrate
from netgym.physics.model import KernelModel, Settings

CHUNK_SECONDS = 0.01          # simulated time between two checks of a plan's decisions


@dataclass(frozen=True)
class Integrate:
    """Request: integrate ``n_steps`` steps of ``dt`` with ``integrator`` (an Integrator code)."""

    n_steps: int
    integrator: int
    dt: float


@dataclass(frozen=True)
class Tick:
    """Request: nothing to integrate; the plan moved time itself (a moment to observe)."""


Request = Union[Integrate, Tick]
Plan = Generator[Request, None, Any]
"""A simulation plan: yields :data:`Request` objects, returns its result."""


class Drivable(Integrand, Protocol):
    """What :func:`drive` needs of a simulator: :class:`Integrand` and its kernel records."""

    @property
    def kernel_model(self) -> KernelModel:
        """The scene as the kernels take it."""

    def settings(self, integrator: int, dt: float) -> Settings:
        """Kernel settings for this integrator and dt."""


def drive(sims: Sequence[Drivable], plans: Sequence[Plan], workspace: Workspace,
          observer: Callable[[Any], None] | None = None, names: Sequence[str] | None = None) -> list[Any]:
    """Carry out ``plans[i]`` on ``sims[i]`` until every plan has returned; returns their results.

    Each round integrates all pending :class:`Integrate` requests that share an integrator and
    dt in one :func:`~netgym.physics.integration.integrate` call, then resumes every plan (with
    the divergence error of its own integration, if any). ``observer(sim)`` is called after
    every request carried out without error, for example to record frames. A netgym error
    raised by plan ``i`` propagates, its message prefixed with ``names[i]`` when names are given.
    """
    results: list[Any] = [None] * len(plans)
    pending: dict[int, Request] = {}

    def resume(i: int, error: Exception | None) -> None:
        try:
            pending[i] = plans[i].throw(error) if error is not None else next(plans[i])
        except StopIteration as stop:
            pending.pop(i, None)
            results[i] = stop.value
        except NetgymError as failure:
            if names is None:
                raise
            raise type(failure)(f"{names[i]}: {failure}") from failure

    for i in range(len(plans)):
        resume(i, None)
    while pending:
        errors: dict[int, Exception] = {}
        groups: dict[tuple[int, float], list[int]] = {}
        for i, request in pending.items():
            if isinstance(request, Integrate):
                groups.setdefault((request.integrator, request.dt), []).append(i)
        for (integrator, dt), members in groups.items():
            targets = [sims[i] for i in members]
            failures = integrate(targets, targets[0].kernel_model, targets[0].settings(integrator, dt),
                                 [pending[i].n_steps for i in members], workspace)
            errors.update((i, e) for i, e in zip(members, failures) if e is not None)
        for i in list(pending):
            if observer is not None and i not in errors:
                observer(sims[i])
            resume(i, errors.get(i))
    return results
