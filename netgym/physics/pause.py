"""The pause between two throws: the net and the balls in it brought to rest for the next one.

:func:`pause_plan` is the one place the pause is decided; a throw runs it before its launch (a
no-op on a scene at rest) and the environment after each throw but an episode's last, and both
book its cost as a :class:`Pause`.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING

from netgym.physics.film import Film
from netgym.physics.plans import Plan

if TYPE_CHECKING:
    from netgym.physics.simulator import Simulator


@dataclass(frozen=True)
class Pause:
    """What a pause cost: integration ``substeps`` and simulated seconds ``time``."""

    substeps: int = 0
    time: float = 0.0


def pause_plan(sim: "Simulator", film: Film | None = None) -> Plan:
    """The pause as a plan (see :meth:`~netgym.physics.simulator.Simulator.run`); it returns
    the :class:`Pause`. If the scene still moves: a scene with balls relaxes
    (:meth:`~netgym.physics.simulator.Simulator.relax_plan`); an empty net is put back at its
    equilibrium, the settled net (filmed, it relaxes for the frames first, then is put back as
    unfilmed). Run with a ``film`` that films the settling, its requests end at the clock's
    instants; with one that does not, the clock is paused over it (restart it at the launch)."""
    substeps, time = sim.substeps, sim.state.time
    if sim.awake:
        if film is not None and not film.settling:
            film.clock.pause()
        if sim.n_balls > 0:
            yield from sim.relax_plan(film=film)
        else:
            if film is not None and film.settling:
                kept = sim.checkpoint()
                yield from sim.relax_plan(film=film)
                sim.restore(kept)
                film.clock.restart(time)
            sim.rest_empty_net()
    return Pause(sim.substeps - substeps, sim.state.time - time)


def pause(sim: "Simulator", film: Film | None = None, observer: Callable[["Simulator"], None] | None = None) -> Pause:
    """Run the pause on ``sim`` (see :func:`pause_plan`), filmed by ``film`` if given;
    ``observer(sim)`` is called after every request (e.g. a :class:`~netgym.physics.watchdog.Watchdog`)."""
    return sim.run(pause_plan(sim, film), film, observer)
