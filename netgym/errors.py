"""Named errors raised by netgym."""

from __future__ import annotations


class NetgymError(Exception):
    """Base class of every error netgym raises on purpose."""


class InvalidArgumentError(NetgymError, ValueError):
    """An argument, action or option passed to netgym is of the wrong type, shape or value; the
    message names it and what is allowed."""


class ConfigError(NetgymError, ValueError):
    """A scene field is missing, unknown, of the wrong type or out of its allowed range."""


class UnstableTimeStepError(NetgymError, ValueError):
    """The requested ``dt`` is beyond the linear stability limit of an explicit integrator."""


class SimulationDivergedError(NetgymError, FloatingPointError):
    """The state became non-finite or a body exceeded the divergence speed.

    The simulator restores the state it had before the failing call, so the object stays
    usable (for example with a smaller ``dt`` or the implicit integrator).
    """


class NetNotAtRestError(NetgymError, RuntimeError):
    """A relaxation (the pause between throws, the settling of a new net) did not pass its rest
    test within its time limit: for example a pile of balls that creeps on faster than a strict
    ``simulation.settle_speed`` allows. The state is left where the relaxation ended."""


class EpisodeEndedError(NetgymError, RuntimeError):
    """``step`` was called on an episode that has ended (or before the first ``reset``)."""


class NoProgressError(NetgymError, RuntimeError):
    """A simulation plan (a throw, the pause between throws, the settling of a new net) broke its
    progress guarantee: more pieces in a row than allowed left the simulated time where it was,
    or it took more pieces than its bound. The message names the plan (a throw's launch) and
    the state it stalled in. A bug in netgym, never a property of the input: please report it."""


class StepTimeoutError(NetgymError, RuntimeError):
    """A watched run (an environment step: a throw and the pause after it) exceeded its watchdog's
    bound of requests or of wall seconds (numba's compiling not counted). The message says what
    was thrown, so that a training run stops with it instead of hanging a worker."""
