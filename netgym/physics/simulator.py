"""The public simulator: a scene's net and balls, stepping, relaxation and plans.

Whole throws (the fast path and its decisions) come from :class:`~netgym.physics.throws.ThrowPlanning`.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Mapping

import numpy as np

from netgym.config import INTEGRATORS, SceneConfig, load_scene
from netgym.errors import SimulationDivergedError, UnstableTimeStepError
from netgym.physics import stepping
from netgym.physics.forces import energies
from netgym.physics.integrators import IMPLICIT_EULER, workspace
from netgym.physics.model import Model, State
from netgym.physics.stability import NetModes, net_modes, stable_dt
from netgym.physics.throws import CHUNK_SECONDS, Plan, ThrowPlanning, vector_argument

RELAX_IMPLICIT_DT = 0.01      # s, implicit Euler step of the fallback relaxation
RELAX_WINDOW = 0.1            # s over which relaxation must have moved nothing ...
RELAX_DISPLACEMENT = 1e-3     # m ... by more than this (1 cm/s: slow creep of balls on a sloped net is at rest)
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


_SETTLED: dict[SceneConfig, np.ndarray] = {}
_MODES: dict[tuple[Any, Any], NetModes] = {}


class Simulator(ThrowPlanning):
    """Mass-spring net, poles and balls of one scene.

    :param scene: a :class:`SceneConfig`, a built-in scene name or a TOML path.
    :param overrides: dotted config fields to replace, e.g. ``{"simulation.dt": 1e-3}``.
    :param check_stability: refuse an explicit integrator whose ``dt`` is beyond the linear
        stability limit estimated for this net, linearised about its built shape (raises
        :class:`UnstableTimeStepError`).
    """

    def __init__(self, scene: SceneConfig | str | Path = "basket",
                 overrides: Mapping[str, Any] | None = None, check_stability: bool = True) -> None:
        config = scene if isinstance(scene, SceneConfig) else load_scene(scene)
        if overrides:
            config = config.replace(overrides)
        self.config = config
        self.model = Model.from_config(config)
        self.state = State.at_rest(self.model)
        self.stats = np.zeros(2)  # counters: integration substeps, CG iterations
        self._work, self._coef = workspace(self.model.n_net, self.model.n_springs)
        self._awake = False
        sim = config.simulation
        self._dt, self._integrator = sim.dt, self.model.integrator_code
        self.modes = self._net_modes()
        self.stable_dt = stable_dt(self._integrator, self.modes)
        if check_stability and sim.dt > self.stable_dt:
            raise UnstableTimeStepError(
                f"simulation.dt = {sim.dt:g} s is beyond the linear stability limit "
                f"{self.stable_dt:.3g} s of {sim.integrator} on this net (highest frequency "
                f"{self.modes.omega:.0f} rad/s, damping rate {self.modes.damping:.0f} 1/s); use "
                f"dt <= {self.stable_dt:.3g} s, or integrator = \"imex_euler\" or \"implicit_euler\"")
        self.state = State.at_rest(self.model, self._settled_positions())
        self._rest_state = self.state.copy()

    # ------------------------------------------------------------------ state access
    @property
    def n_balls(self) -> int:
        """Number of balls in the scene."""
        return self.state.x.shape[0] - self.model.n_net

    @property
    def ball_positions(self) -> np.ndarray:
        """(n_balls, 3) ball centres (a copy)."""
        return self.state.x[self.model.n_net:].copy()

    @property
    def ball_velocities(self) -> np.ndarray:
        """(n_balls, 3) ball velocities (a copy)."""
        return self.state.v[self.model.n_net:].copy()

    @property
    def substeps(self) -> int:
        """Integration substeps taken since construction."""
        return int(self.stats[stepping.SUBSTEPS])

    @property
    def cg_iterations(self) -> int:
        """Conjugate-gradient iterations taken by implicit Euler since construction."""
        return int(self.stats[stepping.CG_ITERATIONS])

    def energy(self) -> Energy:
        """Energy of the current state."""
        s = self.state
        return Energy(*energies(s.x, s.v, s.inv_mass, self.model.gravity, self.model.springs,
                                self.model.spring_params))

    # ------------------------------------------------------------------ editing
    def reset(self) -> None:
        """Back to the net at rest, without balls, at time 0."""
        self.state.restore(self._rest_state)
        self._awake = False

    def launch_ball(self, position: Any, velocity: Any) -> int:
        """Add a ball at ``position`` (m) with ``velocity`` (m/s); returns its ball index.

        A ball launched inside the net box counts as having entered it.
        """
        p = vector_argument(position, "position")
        v = vector_argument(velocity, "velocity")
        r = self.model.ball_radius
        if p[2] < r:
            raise ValueError(f"position z = {p[2]:g} m puts the ball (radius {r:g} m) below the ground")
        speed = float(np.linalg.norm(v))
        if speed > MAX_LAUNCH_SPEED:
            raise ValueError(f"velocity has speed {speed:g} m/s; allowed: at most {MAX_LAUNCH_SPEED:g} m/s")
        s = self.state
        s.x = np.vstack([s.x, p])
        s.v = np.vstack([s.v, v])
        s.inv_mass = np.append(s.inv_mass, 1.0 / self.model.ball_mass)
        s.entered = np.append(s.entered, np.int8(self._inside_box(p)))
        return self.n_balls - 1

    def remove_ball(self, index: int) -> None:
        """Take ball ``index`` out of the scene."""
        if not 0 <= index < self.n_balls:
            raise IndexError(f"ball index {index} out of range; the scene has {self.n_balls} balls")
        s, row = self.state, self.model.n_net + index
        s.x, s.v = np.delete(s.x, row, axis=0), np.delete(s.v, row, axis=0)
        s.inv_mass, s.entered = np.delete(s.inv_mass, row), np.delete(s.entered, index)
        self._awake = True

    # ------------------------------------------------------------------ stepping
    def step(self, n_steps: int = 1, integrator: str | None = None, dt: float | None = None) -> None:
        """Integrate everything for ``n_steps`` steps (no shortcuts), with the scene's
        integrator and ``dt`` unless others are given (for convergence and stability studies)."""
        code = self._integrator if integrator is None else INTEGRATORS.index(integrator)
        self._advance(n_steps, code, self._dt if dt is None else dt)
        self._awake = True

    def relax(self, max_time: float = 60.0) -> None:
        """Bring the net and the balls in it to their equilibrium: the pause between two throws.

        Dynamic relaxation with the scene's own integrator and ``dt`` (so the result is an
        equilibrium of exactly the dynamics that follow): all velocities are zeroed whenever the
        kinetic energy has passed a peak, until no body moves more than RELAX_DISPLACEMENT over
        RELAX_WINDOW. Raises :class:`SimulationDivergedError` if it does not settle within
        ``max_time`` simulated seconds.
        """
        self.run(self.relax_plan(max_time))

    def relax_plan(self, max_time: float = 60.0, integrator: int | None = None, dt: float | None = None) -> Plan:
        """:meth:`relax` as a plan (see :meth:`run`)."""
        integrator = self._integrator if integrator is None else integrator
        dt = self._dt if dt is None else dt
        steps = max(1, round(CHUNK_SECONDS / dt))
        previous = math.inf
        started = self.state.time
        window_start, window_time = self.state.x.copy(), self.state.time
        while self.state.time - started < max_time:
            yield steps, integrator, dt
            kinetic = self.energy().kinetic
            if kinetic < previous:
                self.state.v[:] = 0.0
                kinetic = 0.0
            previous = kinetic
            if self.state.time - window_time >= RELAX_WINDOW - 1e-12:
                if float(np.abs(self.state.x - window_start).max(initial=0.0)) < RELAX_DISPLACEMENT:
                    self.state.v[:] = 0.0
                    self._awake = False
                    return
                window_start, window_time = self.state.x.copy(), self.state.time
        raise SimulationDivergedError(f"the net did not come to rest within {max_time:g} s of relaxation")

    def run(self, plan: Plan, observer: Callable[["Simulator"], None] | None = None) -> Any:
        """Carry out a plan on this simulator alone and return its result.

        A plan (from :meth:`throw_plan` or :meth:`relax_plan`) is a generator that yields
        ``(n_steps, integrator, dt)`` requests to integrate (``n_steps == 0``: time moved in
        closed form) and holds all the decisions; the driver only integrates, which lets a
        vector environment integrate many simulators' requests in one parallel call.
        ``observer(sim)`` is called after every request, for example to record frames.
        """
        try:
            request = next(plan)
            while True:
                n_steps, integrator, dt = request
                try:
                    if n_steps:
                        self._advance(n_steps, integrator, dt)
                except SimulationDivergedError as error:
                    request = plan.throw(error)
                    continue
                if observer is not None:
                    observer(self)
                request = next(plan)
        except StopIteration as stop:
            return stop.value

    def _advance(self, n_steps: int, integrator: int, dt: float) -> None:
        m, s = self.model, self.state
        sim = self.config.simulation
        before = self.begin_advance()
        status = stepping.advance(
            s.x, s.v, s.inv_mass, s.entered, m.n_net, m.springs, m.spring_params, m.segments,
            m.poles, m.contact, m.restitution_threshold, m.gravity, m.drag, m.ball_radius, m.opening,
            integrator, dt, n_steps, sim.max_ball_travel, sim.cg_tolerance, sim.cg_max_iterations,
            sim.divergence_speed, self._work, self._coef, self.stats)
        self.end_advance(status, before, n_steps, integrator, dt)

    def begin_advance(self) -> State:
        """Prepare scratch space for the current state; returns a copy to restore on failure."""
        if self._work.shape[1] != self.state.x.shape[0]:
            self._work, self._coef = workspace(self.state.x.shape[0], self.model.n_springs)
        return self.state.copy()

    def end_advance(self, status: int, before: State, n_steps: int, integrator: int, dt: float) -> None:
        """Book the time of an integration, or restore ``before`` and raise if it diverged."""
        s = self.state
        if status != stepping.OK:
            s.restore(before)
            raise SimulationDivergedError(
                f"{INTEGRATORS[integrator]} at dt = {dt:g} s diverged (a speed exceeded "
                f"{self.config.simulation.divergence_speed:g} m/s or became non-finite) within "
                f"{n_steps} steps from t = {before.time:g} s; the state was restored. Use a smaller "
                f"simulation.dt (linear stability limit of {INTEGRATORS[self._integrator]} here: "
                f"{self.stable_dt:.3g} s), or integrator = \"imex_euler\" or \"implicit_euler\"")
        s.time += n_steps * dt

    def _net_modes(self) -> NetModes:
        """Fastest mode of the net linearised about its built shape (cached per net and springs)."""
        key = (self.config.net, self.config.springs)
        if key not in _MODES:
            m = self.model
            _MODES[key] = net_modes(m.geometry.positions, m.net_inv_mass, m.springs, m.spring_params, m.drag)
        return _MODES[key]

    def _settled_positions(self) -> np.ndarray:
        """The net at rest under gravity (cached per scene config)."""
        key = self.config
        if key not in _SETTLED:
            try:
                self.relax()
            except SimulationDivergedError:
                # an unstable dt (allowed with check_stability=False) cannot hold the net still:
                # start it from the equilibrium found with implicit Euler instead
                self.state = State.at_rest(self.model)
                self.run(self.relax_plan(60.0, IMPLICIT_EULER, RELAX_IMPLICIT_DT))
            _SETTLED[key] = self.state.x.copy()
        return _SETTLED[key]

    # ------------------------------------------------------------------ geometry helpers
    def _inside_box(self, p: np.ndarray) -> bool:
        o = self.model.geometry.opening
        u, w = o.tangent_axes
        inner = o.sign * (p[o.axis] - o.plane) < 0.0
        return bool(inner and o.tangent_lower[0] <= p[u] <= o.tangent_upper[0]
                    and o.tangent_lower[1] <= p[w] <= o.tangent_upper[1])
