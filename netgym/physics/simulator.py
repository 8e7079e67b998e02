"""The public simulator: a scene's net and balls, their state, stepping, relaxation, sleeping
and waking, and the running of plans.

It knows no throw: throws (:mod:`netgym.physics.throw`) and the pause between them
(:mod:`netgym.physics.pause`) are plans over its public API, which
:func:`~netgym.physics.plans.drive` carries out.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Mapping

import numpy as np

from netgym.arguments import integer_argument, is_real, vector_argument
from netgym.config import AirConfig, SceneConfig, load_scene
from netgym.errors import InvalidArgumentError, NetNotAtRestError, SimulationDivergedError, UnstableTimeStepError
from netgym.physics.kernels.smooth_forces import energies
from netgym.physics.integration import RestTest, Workspace
from netgym.kinds import ContactModel, Integrator
from netgym.physics.model.model import KernelModel, Model, Settings, State
from netgym.physics.model.opening import Opening
from netgym.physics.outcomes import CaptureRule, capture_rule
from netgym.physics.film import Film
from netgym.physics.plans import Integrate, Plan, Relax, drive
from netgym.physics.new_net import PreparedNet, settled_positions
from netgym.physics.progress_guard import ProgressGuard
from netgym.physics.recent import Recent
from netgym.physics.stability import net_modes_of, stable_dt
from netgym.physics.stepping import new_counters

SETTLE_STABILITY_SHARE = 0.9  # the pause steps at most this share of its integrator's linear stability limit
RELAX_REQUEST = 0.25          # s, the most simulated time one relaxation request covers (a moment to observe)
RELAX_WINDOW = 0.1            # s over which relaxation must have moved nothing faster than simulation.settle_speed
MAX_LAUNCH_SPEED = 100.0      # m/s


@dataclass(frozen=True)
class Energy:
    """Kinetic, spring and gravitational potential energy of all free bodies (J)."""

    kinetic: float
    spring: float
    gravity: float

    @property
    def total(self) -> float:
        """Sum of the three."""
        return self.kinetic + self.spring + self.gravity


@dataclass(frozen=True)
class Checkpoint:
    """A simulator's state, awake flag and work counters at one moment."""

    state: State
    awake: bool
    counters: np.ndarray


CACHED_NETS = 64              # prepared nets kept per process
_PREPARED: Recent = Recent(CACHED_NETS)


class Simulator:
    """Mass-spring net, poles and balls of one scene.

    :param scene: a :class:`SceneConfig`, a built-in scene name or a TOML path.
    :param overrides: dotted config fields to replace, e.g. ``{"simulation.dt": 1e-3}``.
    :param check_stability: refuse an explicit integrator whose ``dt`` is beyond the linear
        stability limit estimated for this net, linearised about its built shape (raises
        :class:`UnstableTimeStepError`).
    :param like: a simulator of a scene that may differ from this one's only in its air (a wind
        drawn per episode); where it does, its net and kernel arrays are shared, not built again.
    :param prepared: the settled net and its modes (a :class:`PreparedNet`); by default
        :func:`prepare_net`'s for the scene (the net settled from scratch, up to a minute of
        simulated time, once per scene and process). Pass ``prepare_net(config)`` to do that work
        where it is wanted (before forking workers, say), or a net family's drawn net.

    ``awake`` is False while the net and the balls in it are at rest (a throw then need not
    integrate them while its ball flies far from them): :meth:`wake` and :meth:`sleep` are the
    only writers. ``capture_rule`` is the scene's (:mod:`~netgym.physics.outcomes`).
    """

    def __init__(self, scene: SceneConfig | str | Path = "basket",
                 overrides: Mapping[str, Any] | None = None, check_stability: bool = True,
                 like: "Simulator | None" = None, prepared: PreparedNet | None = None) -> None:
        config = scene if isinstance(scene, SceneConfig) else load_scene(scene)
        if overrides:
            config = config.replace(overrides)
        self.config = config
        same_net = like is not None and _without_air(like.config) == _without_air(config)
        self.model = (like.model.with_air(config) if same_net
                      else Model.from_config(config, None if like is None else like.model))
        self.state = State.at_rest(self.model)
        self.counters = new_counters()
        self.workspace = Workspace()
        self.awake = False
        self.capture_rule: CaptureRule = capture_rule(config.capture_rule)
        self.modes = net_modes_of(self.model, config) if prepared is None else prepared.modes
        self.stable_dt = stable_dt(self.integrator, self.modes)
        if check_stability and self.dt > self.stable_dt:
            raise UnstableTimeStepError(
                f"simulation.dt = {self.dt:g} s is beyond the linear stability limit "
                f"{self.stable_dt:.3g} s of {self.integrator.label} on this net (highest frequency "
                f"{self.modes.omega:.0f} rad/s, damping rate {self.modes.damping:.0f} 1/s); use "
                f"dt <= {self.stable_dt:.3g} s, or integrator = {_stabler_than(self.integrator)}")
        self.settle_integrator = Integrator.parse(config.simulation.settle_integrator)
        self.settle_inertia = config.simulation.settle_inertia
        if prepared is None:
            prepared = prepare_net(config, self.model)
        self.settle_modes = prepared.settle_modes
        self.settle_dt = min(config.simulation.settle_dt,
                             SETTLE_STABILITY_SHARE * stable_dt(self.settle_integrator, self.settle_modes))
        self.state = State.at_rest(self.model, prepared.positions)
        self._rest_state = self.state.copy()

    # ------------------------------------------------------------------ scene and state access
    @property
    def dt(self) -> float:
        """The scene's integration step (s)."""
        return self.config.simulation.dt

    @property
    def integrator(self) -> Integrator:
        """The scene's integrator."""
        return self.model.integrator

    @property
    def contact_model(self) -> ContactModel:
        """The scene's contact model."""
        return ContactModel.parse(self.config.simulation.contact_model)

    @property
    def opening(self) -> Opening:
        """The net's opening."""
        return self.model.opening

    @property
    def kernel_model(self) -> KernelModel:
        """The scene in the form the kernels take."""
        return self.model.kernel

    def settings(self, integrator: int, dt: float) -> Settings:
        """Kernel settings for ``integrator`` and ``dt`` with this scene's safeguards."""
        return Settings.of(self.config.simulation, integrator, dt)

    @property
    def n_balls(self) -> int:
        """Number of balls in the scene."""
        return self.state.x.shape[0] - self.model.n_net

    @property
    def ball_positions(self) -> np.ndarray:
        """(n_balls, 3) ball centres (a copy)."""
        return self.state.x[self.model.n_net:].copy()

    @property
    def substeps(self) -> int:
        """Integration substeps taken since construction."""
        return int(self.counters[0]["substeps"])

    @property
    def cg_iterations(self) -> int:
        """Conjugate-gradient iterations taken by implicit Euler since construction."""
        return int(self.counters[0]["cg_iterations"])

    def energy(self) -> Energy:
        """Energy of the current state."""
        s = self.state
        return Energy(*energies(s.x, s.v, s.inv_mass, self.model.gravity, self.model.springs,
                                self.model.spring_params))

    # ------------------------------------------------------------------ editing
    def reset(self) -> None:
        """Back to the net at rest, without balls, at time 0."""
        self.state.restore(self._rest_state)
        self.awake = False

    def launch_ball(self, position: Any, velocity: Any) -> int:
        """Add a ball at ``position`` (m) with ``velocity`` (m/s); returns its ball index.

        A ball launched inside the net box counts as having entered it.
        """
        p = vector_argument(position, "position")
        v = vector_argument(velocity, "velocity")
        r = self.model.ball_radius
        if p[2] < r:
            raise InvalidArgumentError(f"position z = {p[2]:g} m puts the ball (radius {r:g} m) below the ground")
        speed = float(np.linalg.norm(v))
        if speed > MAX_LAUNCH_SPEED:
            raise InvalidArgumentError(f"velocity has speed {np.format_float_positional(speed, trim='-')} m/s; allowed: at most {MAX_LAUNCH_SPEED:g} m/s")
        s, before = self.state, self.n_balls
        s.x = np.vstack([s.x, p])
        s.v = np.vstack([s.v, v])
        s.inv_mass = np.append(s.inv_mass, 1.0 / self.model.ball_mass)
        s.entered = np.append(s.entered, np.int8(self.opening.contains(p)))
        s.relay_anchors(self.model, before, [*range(before), -1])
        return self.n_balls - 1

    def remove_ball(self, index: int, wake: bool = True) -> None:
        """Take ball ``index`` out of the scene; the scene wakes (the net may move once the
        ball's weight is gone) unless ``wake`` is False (a ball that never touched it)."""
        if not 0 <= index < self.n_balls:
            raise IndexError(f"ball index {index} out of range; the scene has {self.n_balls} balls")
        s, row, before = self.state, self.model.n_net + index, self.n_balls
        s.x, s.v = np.delete(s.x, row, axis=0), np.delete(s.v, row, axis=0)
        s.inv_mass, s.entered = np.delete(s.inv_mass, row), np.delete(s.entered, index)
        s.relay_anchors(self.model, before, [b for b in range(before) if b != index])
        if wake:
            self.wake()

    def wake(self) -> None:
        """Mark the scene as moving: it is integrated until it is put to sleep again."""
        self.awake = True

    def sleep(self, keep: int | None = None) -> None:
        """Put the scene to rest: zero every velocity but that of body row ``keep`` (a ball in
        flight), and mark the scene asleep, so that a throw need not integrate it."""
        kept = None if keep is None else self.state.v[keep].copy()
        self.state.v[:] = 0.0
        if keep is not None:
            self.state.v[keep] = kept
        self.awake = False

    def checkpoint(self) -> "Checkpoint":
        """Everything integration and throws change, to :meth:`restore` later."""
        return Checkpoint(self.state.copy(), self.awake, self.counters.copy())

    def restore(self, checkpoint: "Checkpoint") -> None:
        """Return to a :meth:`checkpoint`."""
        self.state.restore(checkpoint.state)
        self.awake = checkpoint.awake
        self.counters[:] = checkpoint.counters

    # ------------------------------------------------------------------ stepping
    def step(self, n_steps: int = 1, integrator: str | None = None, dt: float | None = None) -> None:
        """Integrate everything for ``n_steps`` steps (no shortcuts), with the scene's
        integrator and ``dt`` unless others are given (for convergence and stability studies)."""
        n_steps = integer_argument(n_steps, "n_steps", 0)
        dt = self.dt if dt is None else dt
        if not (is_real(dt) and math.isfinite(dt) and dt > 0.0):
            raise InvalidArgumentError(f"dt = {dt!r}; allowed: a finite number of seconds > 0")
        code = self.integrator if integrator is None else Integrator.parse(integrator)
        self.run(_request(Integrate(n_steps, code, float(dt))))
        self.wake()

    def relax(self, max_time: float = 60.0) -> None:
        """Bring the net and the balls in it to their equilibrium: the pause between two throws.

        Dynamic relaxation with kinetic damping of the net (its velocities are zeroed just past a
        peak of its kinetic energy; the balls settle by their own friction and restitution), with
        ``settle_integrator`` at :attr:`settle_dt` and the net's inertia ``settle_inertia`` times
        its mass (see :class:`~netgym.config.SimulationConfig`), until no body has
        moved more than ``simulation.settle_speed`` times RELAX_WINDOW over RELAX_WINDOW; if that
        diverges, again from where it started with the scene's integrator and ``dt``. Raises
        :class:`NetNotAtRestError` if it does not settle within ``max_time`` simulated seconds.
        """
        self.run(self.relax_plan(max_time))

    def relax_plan(self, max_time: float = 60.0, integrator: int | None = None, dt: float | None = None,
                   settle_speed: float | None = None, damped: bool = True, window: float = RELAX_WINDOW,
                   film: Film | None = None) -> Plan:
        """:meth:`relax` as a plan (see :meth:`run`); with a ``film`` that films the settling
        (run it with the same film), its requests end at the clock's instants too; ``integrator`` and ``dt`` replace
        the pause's own (then with no fallback; a ``dt`` given, with the net's true inertia),
        ``settle_speed`` the scene's ``simulation.settle_speed``; ``damped=False`` leaves out the
        kinetic damping (the net's own dynamics come to rest, or not), ``window`` is the time over
        which nothing may have moved faster than the settle speed."""
        if integrator is not None or dt is not None:
            integrator = self.settle_integrator if integrator is None else integrator
            yield from self._relaxation(max_time, integrator, self.settle_dt if dt is None else dt,
                                        settle_speed, damped, window, film, self.settle_inertia if dt is None else 1.0)
            return
        try:
            yield from self._relaxation(max_time, self.settle_integrator, self.settle_dt, settle_speed,
                                        damped, window, film, self.settle_inertia)
        except SimulationDivergedError:
            if (self.settle_integrator, self.settle_dt, self.settle_inertia) == (self.integrator, self.dt, 1.0):
                raise
            yield from self._relaxation(max_time, self.integrator, self.dt, settle_speed, damped, window, film)

    def _relaxation(self, max_time: float, integrator: int, dt: float, settle_speed: float | None, damped: bool,
                    window: float, film: Film | None, inertia: float = 1.0) -> Plan:
        """Dynamic relaxation with one integrator, dt and inertia of the net (see :meth:`relax_plan`);
        a request that took no step raises :class:`~netgym.errors.NoProgressError` rather than spin."""
        frames = film.clock if film is not None and film.settling else None
        speed = self.config.simulation.settle_speed if settle_speed is None else settle_speed
        rest = RestTest(self.state.x.shape, round(window / dt), speed * window, damped, inertia)
        started, taken = self.state.time, 0
        total, most = math.ceil(max_time / dt - 1e-9), max(1, round(RELAX_REQUEST / dt))
        guard = ProgressGuard(started, started + total * dt, dt, lambda: (
            f"the relaxation of the {self.config.name} scene with {self.n_balls} balls "
            f"({Integrator(integrator).label}, dt {dt:g} s) at {self.state.time!r} s, {taken} of {total} steps taken"))
        while taken < total:
            n = min(total - taken, most)
            if frames is not None:
                n = min(n, frames.steps_to_next(self.state.time, dt))
            yield Relax(n, integrator, dt, rest)
            taken += rest.steps
            self.state.time = started + taken * dt  # the same time however the requests were cut
            guard.piece(self.state.time)
            if rest.at_rest:
                self.sleep()
                return
        raise NetNotAtRestError(f"the net and the balls in it did not come to rest (nothing faster than "
                                f"{speed:g} m/s over {window:g} s) within {max_time:g} s of relaxation; "
                                f"the state is left where the relaxation ended")

    def rest_empty_net(self) -> None:
        """Put the net, with no ball in it, at rest in the shape every episode starts from (its
        equilibrium; where the net lies on the ground, as the goal's bottom does, friction could
        have held a disturbed net a little elsewhere), keeping the time."""
        time = self.state.time
        self.state.restore(self._rest_state)
        self.state.time = time
        self.awake = False

    def run(self, plan: Plan, film: Film | None = None, observer: Callable[["Simulator"], None] | None = None) -> Any:
        """Carry out a plan on this simulator (with :func:`~netgym.physics.plans.drive`) and
        return its result. A ``film`` (the one the plan was made with) films it: its integration
        requests stop at the film's instants; ``observer(sim)`` is called after every request."""
        return drive(self, plan, self.workspace, film, observer)

    def divergence_advice(self, integrator: int) -> str:
        """What to change after ``integrator`` diverged on this scene."""
        limit = stable_dt(integrator, self.modes)
        if not math.isfinite(limit):
            return "Use a smaller simulation.dt"
        return (f"Use a smaller simulation.dt (linear stability limit of {Integrator(integrator).label} here: "
                f"{limit:.3g} s), or integrator = {_stabler_than(integrator)}")


def prepare_net(config: SceneConfig, model: Model | None = None) -> PreparedNet:
    """The work a new :class:`Simulator` of scene ``config`` needs done first: its net settled
    under gravity from its built shape (:func:`~netgym.physics.new_net.settled_positions`: up to
    a minute of simulated time, with a progress bar when it takes a while) and its modes at its own inertia and the pause's.
    Cached per scene (air acts on balls only, so scenes that differ only in their air share it);
    ``model``: the scene's, if built already."""
    key = _without_air(config)
    if key not in _PREPARED:
        model = Model.from_config(config) if model is None else model
        built = PreparedNet(model.geometry.positions, net_modes_of(model, config),
                            net_modes_of(model, config, config.simulation.settle_inertia))
        settled = settled_positions(Simulator(config, check_stability=False, prepared=built))
        _PREPARED[key] = dataclasses.replace(built, positions=settled)
    return _PREPARED[key]


def _without_air(config: SceneConfig) -> SceneConfig:
    """``config`` with the default air: what the net, its settling and its springs depend on
    (air acts on balls only)."""
    return dataclasses.replace(config, air=AirConfig())


def _stabler_than(integrator: int) -> str:
    """The integrators to suggest instead of ``integrator`` when its dt is too large."""
    return " or ".join(f'"{i.label}"' for i in (Integrator.IMEX_EULER, Integrator.IMPLICIT_EULER) if i != integrator)


def _request(request: Integrate) -> Plan:
    """A plan of a single request."""
    yield request
