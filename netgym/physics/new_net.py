"""A new net's settling: the shape a net built for a scene comes to rest in under gravity, and
what a :class:`~netgym.physics.simulator.Simulator` keeps of that work (:class:`PreparedNet`,
which :func:`~netgym.physics.simulator.prepare_net` caches per scene)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from netgym.errors import NetNotAtRestError, SimulationDivergedError
from netgym.kinds import ContactModel, Integrator
from netgym.physics.model.model import State
from netgym.physics.progress import Progress
from netgym.physics.stability import NetModes

RELAX_IMPLICIT_DT = 0.01      # s, step of the fallback relaxation (implicit Euler; IMEX with compliant contacts)
SETTLE_TIME = 60.0            # s: the most simulated time the settling of a new net may take
NEW_NET_SETTLE_SPEED = 0.01   # m/s: a new net settles (once per scene) until nothing moves faster (or settle_speed)
NEW_NET_REST_SPEED = 1e-3     # m/s: then, on the scene's own integrator and dt, undamped, until nothing moves faster
NEW_NET_WINDOW = 1.0          # s over which it must have moved nothing faster: from rest a creeping net gathers
                              # speed slowly, and passed a 0.1 s window while still sagging


@dataclass(frozen=True)
class PreparedNet:
    """What a simulator would otherwise work out for its net: its settled ``positions`` and the
    ``modes`` of the net at its own inertia and ``settle_modes`` at the pause's (for nets drawn
    per episode, see :mod:`~netgym.physics.net_family`)."""

    positions: np.ndarray
    modes: NetModes
    settle_modes: NetModes


def settled_positions(sim: Any) -> np.ndarray:
    """The positions the net of ``sim`` (a :class:`~netgym.physics.simulator.Simulator` whose
    net has its built shape) comes to rest at: kinetically damped near the equilibrium, then on
    the scene's own dynamics until it stays. Where those dynamics cannot hold the net still (an
    unstable dt, allowed with check_stability=False), the damped equilibrium; where the damped
    relaxation diverges, the equilibrium found with implicit Euler (IMEX Euler for compliant
    contacts, which have no implicit Euler step) from the built shape."""
    progress = Progress(f"settling the net of {sim.model.n_net} particles", SETTLE_TIME)
    speed = min(NEW_NET_SETTLE_SPEED, sim.config.simulation.settle_speed)
    try:
        sim.run(sim.relax_plan(SETTLE_TIME, settle_speed=speed), observer=progress)
        damped = sim.checkpoint()
        try:
            sim.run(sim.relax_plan(SETTLE_TIME, sim.integrator, sim.dt, settle_speed=NEW_NET_REST_SPEED,
                                   damped=False, window=NEW_NET_WINDOW), observer=progress)
        except NetNotAtRestError:
            sim.sleep()  # a heavily overdamped net creeps on for minutes: as settled as SETTLE_TIME gets it
        except SimulationDivergedError:
            sim.restore(damped)
    except SimulationDivergedError:
        sim.state = State.at_rest(sim.model)
        fallback = Integrator.IMEX_EULER if sim.contact_model == ContactModel.COMPLIANT else Integrator.IMPLICIT_EULER
        sim.run(sim.relax_plan(SETTLE_TIME, fallback, RELAX_IMPLICIT_DT, settle_speed=speed), observer=progress)
    finally:
        progress.close()
    return sim.state.x.copy()
