"""Throws: plans that simulate one ball until its outcome is decided (the fast path).

A throw starts from a net at rest. Its fast path models only what the scene needs: the ball
flies in closed form while it is clear of the net, poles and other balls (the net, at rest,
is not integrated then), to whole steps after the launch; once it comes near, everything is
integrated with the scene's integrator, so on the very steps the full simulation takes; the
throw ends as soon as its outcome is decided (a :class:`~netgym.physics.outcomes.Reason`): the
ball flies away from everything, cannot reach the opening any more, nor before the time limit
(energy bounds), is at rest, or its scene's capture rule decided it (``line``: the ball is
wholly over the opening's line). ``fast=False`` integrates everything from launch to the time
limit instead, as a reference.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, NamedTuple

import numpy as np

from netgym.arguments import vector_argument
from netgym.errors import SimulationDivergedError
from netgym.physics import air, approach, contacts, flight, reach, stepping
from netgym.physics.outcomes import Reason
from netgym.physics.plans import CHUNK_SECONDS, Integrate, Plan, Tick, Watched
from netgym.physics.surroundings import survey
from netgym.physics.watch import RestWindow, Watch, near_check

if TYPE_CHECKING:
    from netgym.physics.frames import Film
    from netgym.physics.simulator import Simulator


@dataclass(frozen=True)
class FastPathTuning:
    """The fast path's tuning: how near is near, how still is at rest, how long a decided throw
    is filmed on. These trade work for nothing the outcome depends on (the tests compare the
    fast path with the full simulation); change them with the agreement tests at hand."""

    rest_window: float = 0.1      # s during which a ball and its surroundings must stay slow to be "at rest"
    rest_reach: float = 0.2       # m around a ball within which moving bodies keep it from being at rest
    clearance: float = 0.02       # m: closer than this to anything, a ball is simulated, not flown
    awake_margin: float = 0.5     # m the moving net may reach beyond its current bounding box
    time_epsilon: float = 1e-9    # s: instants closer than this are the same
    air_piece: float = 0.1        # s: longest piece of a flight through air between two clearance checks
    sleep_speed: float = 5e-2     # m/s: a net (and balls in it) slower than this may stop being integrated
                                  # (half the pause's settle speed; 1 cm/s kept a jittering net awake)
    line_time_tolerance: float = 1e-4  # s: a flown ball's capture-rule decision comes at most this late
    miss_filmed_after_landing: float = 0.5  # s of a missed ball's flight filmed after it first lands
    rule_filmed: float = 0.5      # s filmed on after the capture rule decided (a goal running into the net)


TUNING = FastPathTuning()


@dataclass(frozen=True)
class ThrowResult:
    """Outcome of one throw.

    :param captured: caught by the scene's ``capture_rule``: ``"held"``, the ball came in through
        the opening and is inside the net; ``"line"``, the whole ball crossed the opening's plane
        inside the frame (it is out of play, a miss, once wholly over it beside the frame).
    :param entered: the ball's centre crossed the opening inwards (and did not leave through it).
    :param final_position: ball centre when the outcome was decided (m).
    :param final_velocity: ball velocity then (m/s).
    :param time: simulated seconds from launch to the decision.
    :param substeps: integration substeps spent on the throw (0 when decided in closed form).
    :param reason: why it was decided then, a :class:`~netgym.physics.outcomes.Reason` of this
        outcome (equal to its string value, as ``info["reason"]`` reports it).
    :param settle_substeps: integration substeps spent bringing the net to rest before the launch.
    :param settle_time: simulated seconds of that settling.
    """

    captured: bool
    entered: bool
    final_position: np.ndarray
    final_velocity: np.ndarray
    time: float
    substeps: int
    reason: Reason
    settle_substeps: int = 0
    settle_time: float = 0.0


class Ball(NamedTuple):
    """The thrown ball: its ``index`` among the balls, its ``row`` among the bodies."""

    index: int
    row: int


@dataclass
class Course:
    """What a throw keeps from its launch to its decision."""

    launched: float               # simulated time of the launch: the origin of the full simulation's step grid
    deadline: float               # the launch plus the time limit
    substeps: int                 # the simulator's substeps at the launch
    about: float                  # the ball's radius + the largest radius about the other bodies (a pole's, a ball's)
    from_front: bool              # launched in front of the opening's plane: it can go out of play
    watch: Watch                  # what the checks after each chunk look at (the energy bound, the rest window)
    decision: Reason | None = None  # the capture rule's, once it decided


class Throw:
    """One throw into a simulator's scene, as a plan: launch a ball and simulate until its
    outcome is decided. Uses only the simulator's public API.

    :param sim: the :class:`~netgym.physics.simulator.Simulator` to throw into.
    :param position: release point (m).
    :param velocity: launch velocity (m/s).
    :param fast: take the fast path; False integrates everything to the time limit (the reference).

    When the plan runs with a :class:`~netgym.physics.frames.Film` (``Simulator.run``), it
    stops at every instant of its clock from the launch on (integration at the substep nearest
    it, a :class:`~netgym.physics.plans.Tick` while the ball flies in closed form), a miss
    decided in closed form is flown on to its landing for the frames and a ball decided by the
    capture rule filmed on (then put back as decided).
    """

    def __init__(self, sim: "Simulator", position: Any, velocity: Any, fast: bool = True) -> None:
        self.sim = sim
        self.position = vector_argument(position, "position")  # fail on bad input before any work
        self.velocity = vector_argument(velocity, "velocity")
        self.fast = fast
        self.rule = sim.capture_rule
        self.film: Film | None = None  # the simulator's, while the plan runs
        m, ground = sim.model, sim.kernel_model.materials.ball_ground
        self.ground = flight.Ground(m.ball_radius, m.gravity, ground.restitution, ground.friction,
                                    m.restitution_threshold)
        self.ball = Ball(-1, -1)
        self.course: Course | None = None

    # ------------------------------------------------------------------ the recipe
    def plan(self) -> Plan:
        """The throw as a plan; it returns the :class:`ThrowResult`. Its phases:

        1. the pause: the net is brought to rest if it still moves (``Simulator.pause_plan``);
        2. :meth:`_launch` the ball;
        3. :meth:`_until_decided`: fly it in closed form while it is clear of everything
           (:meth:`_fly_clear`), integrate everything while it is near (:meth:`_integrate_near`),
           and after each piece :meth:`_decide`;
        4. :meth:`_film_after` the decision, when filmed;
        5. take the ball out, unless the capture rule keeps it (a ball captured under ``held``
           stays in the scene; a miss, or a goal under ``line``, is removed).
        """
        sim = self.sim
        self.film = sim.film
        settled = yield from sim.pause_plan()
        start = sim.state.copy()
        yield from self._launch()
        try:
            reason = yield from self._until_decided()
        except SimulationDivergedError:
            sim.state.restore(start)
            raise
        result = self._result(reason)
        yield from self._film_after(reason, t_limit=start.time + sim.config.simulation.time_limit)
        if not (result.captured and self.rule.keeps_captured):
            self._take_out()
        return dataclasses.replace(result, **settled)

    def _launch(self) -> Plan:
        """Put the ball in the scene at its release, and start the :class:`Course` of the throw
        (its clock, time limit and the energy it is measured against); a frame of the launch."""
        sim = self.sim
        s = sim.state
        index = sim.launch_ball(self.position, self.velocity)
        self.ball = Ball(index, sim.model.n_net + index)
        if self.film is not None:
            if not self.film.settling:
                self.film.clock.restart(s.time)
            yield Tick()  # the launch
        m = sim.model
        about = m.ball_radius + max(float(m.poles.radius.max(initial=0.0)), m.ball_radius if sim.n_balls > 1 else 0.0)
        deadline = s.time + sim.config.simulation.time_limit
        self.course = Course(launched=s.time, deadline=deadline, substeps=sim.substeps, about=about,
                             from_front=sim.opening.depth(s.x[self.ball.row]) <= 0.0,
                             watch=self._watch(deadline, about))

    def _watch(self, deadline: float, about: float) -> Watch:
        """The :class:`~netgym.physics.watch.Watch` of a throw launched now, with the ball's
        ``deadline`` and ``about`` (see :class:`Course`): its energy budget measured now."""
        sim, row = self.sim, self.ball.row
        s, m, km, cfg = sim.state, sim.model, sim.kernel_model, sim.config.simulation
        budget = reach.Budget(reach.potential_without_ball(s.x, s.v, s.inv_mass, row, km.gravity, km.springs.pairs,
                                                           km.springs.params),
                              sim.n_balls * air.wind_power_bound(m.ball_mass, m.ball_drag, m.wind), km.gravity,
                              m.ball_radius, sim.opening.lowest_z)
        rest = RestWindow.sized(s.x.shape[0], cfg.dt, TUNING.rest_window, TUNING.time_epsilon,
                                2.0 * m.ball_radius + TUNING.rest_reach, cfg.rest_speed * TUNING.rest_window)
        return Watch(row, s.time, deadline, cfg.dt, max(1, round(CHUNK_SECONDS / cfg.dt)), TUNING.clearance,
                     about + TUNING.awake_margin, self.rule.decision_depth(m.ball_radius), TUNING.sleep_speed, budget,
                     rest, np.empty(6))

    def _until_decided(self) -> Plan:
        """Simulate the ball until its outcome is decided; returns the :class:`Reason`.

        While the scene sleeps (the fast path), the ball flies in closed form, and the flight
        itself may decide the throw. Once it comes near something, the scene wakes and is
        integrated chunk by chunk, with a decision after each; when nothing but the ball moves
        any more and it is clear of everything, the scene sleeps again and the ball flies on.
        """
        sim = self.sim
        while True:
            if self.fast and not sim.awake:
                reason = yield from self._fly_clear()
                if reason is not None:
                    return reason
                sim.awake = True
                if self._clearance() < 0.0:
                    continue  # launched overlapping something: let the contacts act before deciding
            else:
                yield from self._integrate_near()
            reason = self._decide()
            if reason is not None:
                return reason

    def _integrate_near(self) -> Plan:
        """Integrate everything for one chunk of CHUNK_SECONDS (less before the time limit; none
        at it): the ball is near something, or this is the full simulation. On the fast path,
        unfilmed, chunk after chunk in one request, for as long as the checks after them see
        nothing that could be decided (:class:`~netgym.physics.plans.Watched`): the decision
        after it is the one after the last of those chunks. Integration wakes the scene; each
        chunk ends on the full simulation's step grid, as every flight does."""
        sim, watch = self.sim, self.course.watch
        dt = sim.config.simulation.dt
        left = round((self.course.deadline - sim.state.time) / dt)
        if left > 0:
            sim.awake = True
            if self.fast and self.film is None:
                yield Watched(sim.integrator, dt, watch)
            else:
                yield Integrate(min(watch.chunk, left), sim.integrator, dt)

    def _decide(self) -> Reason | None:
        """The decision after a piece of the throw, or None to go on: the capture rule's (the
        full simulation notes it and goes on to the time limit), the time limit, then the fast
        path's own decisions (:meth:`_fast_decision`)."""
        course, s = self.course, self.sim.state
        if course.decision is None:
            course.decision = self._rule_decision(s.x[self.ball.row], bool(s.entered[self.ball.index]))
        if self.fast and course.decision is not None:
            return course.decision
        if course.deadline - s.time < 0.5 * self.sim.dt:
            return Reason.TIME_LIMIT
        if not self.fast:
            return None
        return self._fast_decision()

    def _fast_decision(self) -> Reason | None:
        """The fast path's decision on the integrated scene (see :meth:`_decided`: the ball flies
        away, is at rest, or cannot reach the opening), or None; when nothing but the ball moves
        (slower than ``sleep_speed``) and it could fly clear for a step, the scene goes to sleep,
        so that the ball flies in closed form again."""
        s, km, watch = self.sim.state, self.sim.kernel_model, self.course.watch
        others, _, at_rest, unreachable = near_check(s.x, s.v, s.inv_mass, s.time, km.springs.pairs, km.springs.params,
                                                     km.opening, km.poles, watch)
        reason = self._decided(at_rest, unreachable, watch.box[:3].copy(), watch.box[3:].copy())
        if reason is None and others < watch.sleep_speed and self._flight_time() > 0.0:
            self.sim.sleep(keep=self.ball.row)
        return reason

    def _result(self, reason: Reason) -> ThrowResult:
        """The :class:`ThrowResult` of a throw decided now for ``reason``."""
        sim, course = self.sim, self.course
        s, (index, row) = sim.state, self.ball
        entered = bool(s.entered[index])
        captured = self.rule.captured(course.decision, entered, sim.opening.contains(s.x[row]))
        return ThrowResult(captured=captured, entered=entered,
                           final_position=s.x[row].copy(), final_velocity=s.v[row].copy(),
                           time=s.time - course.launched, substeps=sim.substeps - course.substeps,
                           reason=reason.for_outcome(captured))

    def _film_after(self, reason: Reason, t_limit: float) -> Plan:
        """When filmed: a miss decided in closed form flown on to its landing, a ball the capture
        rule decided filmed on; both put back as decided."""
        if self.film is None:
            return
        if reason is Reason.FLIES_AWAY:
            yield from self._film_miss(t_limit)
        if reason is self.course.decision:
            yield from self._film_on()

    def _take_out(self) -> None:
        """Remove the ball once its throw is decided: a miss, or a goal under the ``line`` rule
        (as after a goal in the sport, the next throw meets an empty goal). A ball still flying
        clear of a sleeping scene leaves it asleep (nothing there moved); else it settles again."""
        sim = self.sim
        awake = sim.awake
        sim.remove_ball(self.ball.index)
        sim.awake = awake

    # ------------------------------------------------------------------ flying clear
    def _fly_clear(self) -> Plan:
        """Move the ball on its free flight (closed form; through air, RK4) while it is clear of
        everything. Returns a decision reason, or None when the ball came close enough to need
        simulating."""
        s, course = self.sim.state, self.course
        row = self.ball.row
        _, lo, hi = self._survey(TUNING.clearance)
        parabola = self.sim.model.ball_drag == 0.0
        if parabola:  # whether and when it comes into the box is one answer along the whole flight
            entry = flight.entry_time(s.x[row], s.v[row], lo, hi, self.ground, course.deadline - s.time)
            if entry is None:
                return Reason.FLIES_AWAY
            entry = self._on_step_grid(entry)
            if entry > 0.0:  # until then it is clear of everything and cannot cross the opening (inside the box)
                entry = self._decision_instant(entry, through_opening=False)  # it may pass the line beside the frame
                yield from self._move(entry, through_opening=False)
                reason = self._flown_to()
                if reason is not None:
                    return reason
        box, km = np.concatenate((lo, hi)), self.sim.kernel_model
        while True:
            if self.film is None:  # the pieces that certainly end undecided, in one kernel call
                s.time = (approach.approach(s.x, s.v, s.entered, km, self.ground, course.watch, box, s.time) if parabola
                          else approach.approach_through_air(s.x, s.v, s.entered, km, self.ground, course.watch, box,
                                                             s.time, TUNING.air_piece))
            if self._never_enters(lo, hi, course.deadline - s.time):  # it left the box, for good
                return Reason.FLIES_AWAY
            if parabola and flight.lies_still(s.x[row], s.v[row], self.ground):
                return Reason.AT_REST  # beside the sleeping scene, nothing can move it any more
            tau = self._flight_time()
            if tau <= 0.0:
                return None  # near something: integrate from here (on the full simulation's step grid)
            tau = self._decision_instant(tau, through_opening=True)
            yield from self._move(tau, through_opening=True)
            reason = self._flown_to()
            if reason is not None:
                return reason

    def _rule_decision(self, position: np.ndarray, entered: bool) -> Reason | None:
        """The capture rule's decision on the ball at ``position`` (``entered``: through the opening)."""
        return self.rule.decision(self.sim.opening, self.sim.model.ball_radius, position, entered,
                                  self.course.from_front)

    def _flown_to(self) -> Reason | None:
        """The decision at the end of a piece of flight: the capture rule's (noted in the
        course), the time limit, or None."""
        s, course, (index, row) = self.sim.state, self.course, self.ball
        decision = self._rule_decision(s.x[row], bool(s.entered[index]))
        if decision is not None:
            course.decision = decision
            return decision
        return Reason.TIME_LIMIT if course.deadline - s.time < 0.5 * self.sim.dt else None

    def _move(self, tau: float, through_opening: bool) -> Plan:
        """Fly the ball for ``tau`` (filmed if there is a film); if it may pass
        ``through_opening``, book its crossing along the chord of the flight (a conservative
        step's chord stays, like its arc, within the clearance about its start)."""
        sim = self.sim
        s, n_net, row = sim.state, sim.model.n_net, self.ball.row
        before = s.x[n_net:].copy()
        start = s.x[row].copy(), s.v[row].copy(), s.time
        if self.film is not None:
            yield from self._film_flight(*start, start[2] + tau)
        s.x[row], s.v[row] = self._flight(start[0], start[1], tau)
        if through_opening:
            stepping.update_entered(s.x, before, n_net, s.entered, sim.kernel_model.opening)
        s.time = start[2] + tau
        if self.film is not None:
            yield Tick()  # an instant within half a step after the flight's end: here is its nearest substep

    def _decision_instant(self, tau: float, through_opening: bool) -> float:
        """``tau``, or, if the capture rule decides the ball flying for ``tau`` (its crossing
        booked only if it may pass ``through_opening``), the first instant it does (within
        ``line_time_tolerance`` after it)."""
        sim = self.sim
        s, n_net, (index, row) = sim.state, sim.model.n_net, self.ball
        start, before = (s.x[row].copy(), s.v[row].copy()), s.x[n_net:].copy()

        def decided_at(t: float) -> bool:
            x, entered = s.x.copy(), s.entered.copy()
            x[row] = self._flight(*start, t)[0]
            if through_opening:
                stepping.update_entered(x, before, n_net, entered, sim.kernel_model.opening)
            return self._rule_decision(x[row], bool(entered[index])) is not None

        return self.rule.decision_instant(tau, decided_at, TUNING.line_time_tolerance)

    def _flight(self, x: np.ndarray, v: np.ndarray, tau: float) -> tuple[np.ndarray, np.ndarray]:
        """Where a lone ball starting at ``x``, ``v`` is after ``tau``: closed form without air,
        RK4 steps through air."""
        m = self.sim.model
        if m.ball_drag == 0.0:
            return flight.advance(x, v, tau, self.ground)
        p, u = np.array(x, dtype=np.float64), np.array(v, dtype=np.float64)
        air.fly(p, u, tau, m.ball_drag, m.wind, self.ground, air.MAX_FLIGHT_STEP)
        return p, u

    def _flight_time(self) -> float:
        """How long the ball can fly in closed form from now, clear of everything and at most to
        the deadline, ending on the full simulation's step grid; 0.0 if it cannot fly to the
        next step there, and must be simulated."""
        gap = self._clearance()
        if gap <= TUNING.clearance:
            return 0.0
        return self._on_step_grid(min(self._safe_time(gap), self.course.deadline - self.sim.state.time))

    def _on_step_grid(self, tau: float) -> float:
        """The longest flight of at most ``tau`` from now that ends on the step grid of the full
        simulation (the launch plus whole steps of the scene's dt), or 0.0: where the fast path
        integrates, it then takes the steps the full simulation takes there."""
        return approach.on_step_grid(self.sim.state.time, tau, self.course.launched, self.sim.config.simulation.dt)

    def _clearance(self) -> float:
        """Distance the ball can travel before it could touch the net, a pole or another ball
        (the net held still)."""
        m = self.sim.model
        return contacts.clearance(self.sim.state.x, m.n_net, self.ball.row, m.ball_radius, m.segments, m.poles)

    def _survey(self, margin: float) -> tuple[float, np.ndarray, np.ndarray]:
        """``(others, lo, hi)``: the largest velocity component of every body but the ball, and
        the bounding box of the net particles, the poles' axes and the other balls' centres,
        grown by the ball radius + the largest radius about those (a pole's, another ball's) +
        ``margin``: outside it the ball is more than ``margin`` from everything."""
        s = self.sim.state
        box = np.empty(6)
        others = survey(s.x, s.v, self.ball.row, self.sim.model.poles, box)
        grow = self.course.about + margin
        return others, box[:3] - grow, box[3:] + grow

    def _never_enters(self, lo: np.ndarray, hi: np.ndarray, horizon: float) -> bool:
        """The ball cannot come into the box ``lo``..``hi`` within ``horizon``: its parabola
        (with bounces) misses it; through air, it lies outside, held by friction, or too far to
        come back within ``horizon`` (:func:`~netgym.physics.air.cannot_reach`)."""
        s, m, g = self.sim.state, self.sim.model, self.ground
        p, v = s.x[self.ball.row], s.v[self.ball.row]
        if not ((p < lo).any() or (p > hi).any()):
            return False  # inside it already
        if m.ball_drag == 0.0:
            return flight.entry_time(p, v, lo, hi, g, horizon) is None
        return (air.held_by_friction(v, m.gravity, m.ball_drag, m.wind, g.radius, g.friction, p)
                or air.cannot_reach(p, v, m.wind, np.concatenate((lo, hi)), horizon))

    def _safe_time(self, gap: float) -> float:
        """A time within which the ball cannot travel ``gap``."""
        m, v = self.sim.model, self.sim.state.v[self.ball.row]
        speed = approach.speed(v)
        if m.ball_drag == 0.0:
            return approach.travel_time(speed, abs(m.gravity), gap)
        return approach.air_safe_time(speed, gap, m.gravity, m.ball_drag, m.wind, TUNING.air_piece)

    # ------------------------------------------------------------------ filming
    def _film_flight(self, x: np.ndarray, v: np.ndarray, t: float, end: float) -> Plan:
        """Put the ball, flying in closed form from ``x``, ``v`` at time ``t``, where it is at
        each frame instant before ``end``, and stop there (a Tick). The flight itself is
        computed apart, so that filming changes nothing."""
        assert self.film is not None
        s, row, eps = self.sim.state, self.ball.row, TUNING.time_epsilon
        while (instant := self.film.clock.next_instant(s.time, eps)) < end - eps:
            s.x[row], s.v[row] = self._flight(x, v, instant - t)
            s.time = instant
            yield Tick()

    def _film_miss(self, t_limit: float) -> Plan:
        """Film a missed ball's closed-form flight on until ``miss_filmed_after_landing`` after it
        first lands (or ``t_limit``); then put the ball and the time back as decided."""
        s, row = self.sim.state, self.ball.row
        kept = s.x[row].copy(), s.v[row].copy(), s.time
        landing = flight.ground_time(s.x[row], s.v[row], self.ground)
        end = min(t_limit, s.time + landing + TUNING.miss_filmed_after_landing)
        yield from self._film_flight(*kept, end)
        s.x[row], s.v[row], s.time = kept

    def _film_on(self) -> Plan:
        """Film a ball the capture rule decided on for ``rule_filmed`` seconds, everything
        integrated (a goal runs into the net, a ball out of play onto it or past it), then put
        the scene, its time and its work counters back as decided."""
        sim = self.sim
        kept = sim.checkpoint()
        cfg = sim.config.simulation
        sim.awake = True
        yield Integrate(round(TUNING.rule_filmed / cfg.dt), sim.integrator, cfg.dt)
        sim.restore(kept)

    # ------------------------------------------------------------------ the fast path's decisions
    def _decided(self, at_rest: bool, unreachable: bool, lo: np.ndarray, hi: np.ndarray) -> Reason | None:
        """The reason the throw's outcome is decided now, or None, from the check after a chunk
        (:func:`~netgym.physics.watch.near_check`): the ball flies away (it cannot come back into
        the box ``lo``..``hi`` around everything else), it is ``at_rest``, or it can no longer
        reach the opening (``unreachable``: the energy bound, which counts, besides the energy
        free now, all the wind could still feed the balls before the deadline)."""
        through_air = self.sim.model.ball_drag != 0.0  # then the time left bounds how far it can come back
        if self._never_enters(lo, hi, self.course.deadline - self.sim.state.time if through_air else math.inf):
            return Reason.FLIES_AWAY
        if at_rest:
            return Reason.AT_REST
        if unreachable:
            return Reason.CANNOT_REACH_OPENING
        return None
