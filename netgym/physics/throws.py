"""Throws: plans that simulate one ball until its outcome is decided (the fast path).

A throw starts from a net at rest. Its fast path models only what the scene needs: the ball
flies in closed form while it is clear of the net, poles and other balls (the net, at rest,
is not integrated then), to whole steps after the launch; once it comes near, everything is
integrated with the scene's integrator, so on the very steps the full simulation takes; the
throw ends as soon as its outcome is decided: the ball flies away from
everything, cannot reach the opening any more, nor before the time limit (energy bounds), is
at rest, or (``line`` rule) is wholly over the opening's line. ``fast=False`` integrates
everything from launch to the time limit instead, as a reference.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from netgym.arguments import vector_argument
from netgym.errors import SimulationDivergedError
from netgym.physics import air, contacts, flight, stepping
from netgym.physics.frames import FrameClock
from netgym.physics.kinds import Contact
from netgym.physics.plans import CHUNK_SECONDS, Integrate, Plan, Tick, integrate_until_stops
from netgym.physics.surroundings import still_since, survey

if TYPE_CHECKING:
    from netgym.physics.simulator import Simulator

REST_WINDOW = 0.1             # s during which a ball and its surroundings must stay slow to be "at rest"
REST_REACH = 0.2              # m around a ball within which moving bodies keep it from being at rest
CLEARANCE = 0.02              # m: closer than this to anything, a ball is simulated, not flown
AWAKE_MARGIN = 0.5            # m the moving net may reach beyond its current bounding box
TIME_EPSILON = 1e-9          # s: instants closer than this are the same
AIR_PIECE = 0.1              # s: longest piece of a flight through air between two clearance checks
MISS_FILMED_AFTER_LANDING = 0.5  # s of a missed ball's flight filmed after it first lands
LINE_TIME_TOLERANCE = 1e-4    # s: a flown ball's line decision comes at most this late
LINE_FILMED = 0.5             # s of a ball filmed on after the line rule decided it (a goal running into the net)
LINE_REASONS = ("crossed_line", "out_of_play")  # the line rule's decisions: a goal, a ball out of play
SLEEP_SPEED = 1e-2            # m/s: a net (and balls in it) slower than this may stop being integrated


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
    :param reason: ``"flies_away"``, ``"cannot_reach_opening"``, ``"at_rest"``, ``"crossed_line"``
        (a goal under ``line``), ``"out_of_play"`` (wholly over the line beside the frame, under
        ``line``) or ``"time_limit"``.
    :param settle_substeps: integration substeps spent bringing the net to rest before the launch.
    :param settle_time: simulated seconds of that settling.
    """

    captured: bool
    entered: bool
    final_position: np.ndarray
    final_velocity: np.ndarray
    time: float
    substeps: int
    reason: str
    settle_substeps: int = 0
    settle_time: float = 0.0


class Throw:
    """One throw into a simulator's scene, as a plan: launch a ball and simulate until its
    outcome is decided. Uses only the simulator's public API.

    :param sim: the :class:`~netgym.physics.simulator.Simulator` to throw into.
    :param position: release point (m).
    :param velocity: launch velocity (m/s).
    :param fast: take the fast path; False integrates everything to the time limit (the reference).
    :param frames: when given, the plan stops at every instant of this clock (integration
        chunks end at the substep nearest it; a :class:`~netgym.physics.plans.Tick` while the
        ball flies in closed form), from the launch on, and a miss decided in closed form is
        flown on to its landing for the frames, a goal filmed on into the net (then put back as decided).
    :param settle_frames: also film the settling of the net before the launch (with ``frames``).
    """

    def __init__(self, sim: "Simulator", position: Any, velocity: Any, fast: bool = True,
                 frames: FrameClock | None = None, settle_frames: bool = False) -> None:
        self.sim = sim
        self.position = vector_argument(position, "position")  # fail on bad input before any work
        self.velocity = vector_argument(velocity, "velocity")
        self.fast = fast
        self.frames = frames
        self.settle_frames = settle_frames
        m = sim.model
        self.launched = 0.0  # simulated time of the launch: the origin of the full simulation's step grid
        self.ground = flight.Ground(m.ball_radius, m.gravity, m.contact[Contact.BALL_GROUND, 0],
                                    m.contact[Contact.BALL_GROUND, 1], m.restitution_threshold)

    def plan(self) -> Plan:
        """The throw as a plan; it returns the :class:`ThrowResult`. The net is first brought to
        rest if it still moves. A ball captured under ``held`` stays in the scene; a missed one,
        or a goal under ``line``, is removed."""
        sim = self.sim
        settled = yield from sim.pause_plan(self.frames, self.settle_frames)
        start = sim.state.copy()
        ball = sim.launch_ball(self.position, self.velocity)
        if self.frames is not None:
            if not self.settle_frames:
                self.frames.restart(sim.state.time)
            yield Tick()  # the launch
        try:
            result = yield from self._steps(ball)
        except SimulationDivergedError:
            sim.state.restore(start)
            raise
        if self.frames is not None and result.reason == "flies_away":
            yield from self._film_miss(sim.model.n_net + ball, t_limit=start.time + sim.config.simulation.time_limit)
        if self.frames is not None and result.reason in LINE_REASONS:
            yield from self._film_on()
        if not result.captured or sim.config.capture_rule == "line":
            self._take_out(ball)
        return dataclasses.replace(result, **settled)

    def _take_out(self, ball: int) -> None:
        """Remove the ball once its throw is decided: a miss, or a goal under the ``line`` rule
        (as after a goal in the sport, the next throw meets an empty goal). A ball still flying
        clear of a sleeping scene leaves it asleep (nothing there moved); else it settles again."""
        sim = self.sim
        awake = sim.awake
        sim.remove_ball(ball)
        sim.awake = awake

    def _clearance(self, row: int) -> float:
        """Distance the ball in ``row`` can travel before it could touch the net, a pole or
        another ball (the net held still)."""
        m = self.sim.model
        return contacts.clearance(self.sim.state.x, m.n_net, row, m.ball_radius, m.segments, m.poles)

    def _survey(self, row: int, margin: float) -> tuple[float, np.ndarray, np.ndarray]:
        """``(others, lo, hi)``: the largest velocity component of every body but the ball in
        ``row``, and the bounding box of the net particles, the poles' axes and the other balls'
        centres, grown by the ball radius + the largest radius about those (a pole's, another
        ball's) + ``margin``: outside it the ball is more than ``margin`` from everything."""
        m, s = self.sim.model, self.sim.state
        box = np.empty(6)
        others = survey(s.x, s.v, row, m.poles, box)
        about = max(float(m.poles[:, 6].max(initial=0.0)), m.ball_radius if self.sim.n_balls > 1 else 0.0)
        grow = m.ball_radius + about + margin
        return others, box[:3] - grow, box[3:] + grow

    def _steps(self, ball: int) -> Plan:
        sim, fast = self.sim, self.fast
        m, s, cfg = sim.model, sim.state, sim.config.simulation
        row = m.n_net + ball
        t0, substeps0 = s.time, sim.substeps
        self.launched = t0
        deadline = t0 + cfg.time_limit
        chunk = max(1, round(CHUNK_SECONDS / cfg.dt))
        reference_energy = self._potential_without(row, sim.energy())
        recent: list[tuple[float, np.ndarray]] = []  # (time, positions) at the checks of the last REST_WINDOW
        line = sim.config.capture_rule == "line"
        from_front = sim.opening.depth(s.x[row]) <= 0.0  # launched before the line: it can go out of play
        decided: str | None = None  # under line: one of LINE_REASONS, once the ball is wholly over the line
        while True:
            if fast and not sim.awake:
                reason = yield from self._fly(row, ball, deadline, from_front)
                if reason is not None:
                    decided = reason if reason in LINE_REASONS else None
                    break
                sim.awake = True
                if self._clearance(row) < 0.0:
                    continue  # launched overlapping something: let the contacts act before deciding
            elif round((deadline - s.time) / cfg.dt) > 0:
                sim.awake = True  # integration wakes the scene (full simulation integrates from the launch on)
                request = Integrate(min(chunk, round((deadline - s.time) / cfg.dt)), sim.integrator, cfg.dt)
                yield from integrate_until_stops(s, request, self.frames)
            if line and decided is None:
                decided = self._line_reason(s.x[row], bool(s.entered[ball]), from_front)
            if fast and decided is not None:
                reason = decided
                break
            if deadline - s.time < 0.5 * cfg.dt:
                reason = "time_limit"
                break
            if not fast:
                continue
            others, lo, hi = self._survey(row, AWAKE_MARGIN)
            recent.append((s.time, s.x.copy()))
            while len(recent) > 1 and recent[1][0] <= s.time - REST_WINDOW + TIME_EPSILON:
                recent.pop(0)
            reason = self._decided(row, reference_energy, self._at_rest(row, recent), lo, hi, deadline)
            if reason is not None:
                break
            if others < SLEEP_SPEED and self._flight_time(row, deadline) > 0.0:
                sim.sleep(keep=row)
        entered = bool(s.entered[ball])
        captured = decided == "crossed_line" if line else entered and sim.opening.contains(s.x[row])
        return ThrowResult(captured=captured, entered=entered,
                           final_position=s.x[row].copy(), final_velocity=s.v[row].copy(),
                           time=s.time - t0, substeps=sim.substeps - substeps0, reason=reason)

    def _line_reason(self, position: np.ndarray, entered: bool, from_front: bool) -> str | None:
        """The ``line`` rule's decision on a ball at ``position``: once the whole ball is past the
        opening's plane, ``"crossed_line"`` (a goal) if it came in through the frame
        (``entered``), ``"out_of_play"`` if it crossed beside it (as over the bar or wide of a
        post in the sport; only for a ball launched ``from_front`` of the line); None before."""
        if self.sim.opening.depth(position) < self.sim.model.ball_radius:
            return None
        if entered:
            return "crossed_line"
        return "out_of_play" if from_front else None

    def _fly(self, row: int, ball: int, deadline: float, from_front: bool) -> Plan:
        """Move the ball on its free flight (closed form; through air, RK4) while it is clear of
        everything. Returns a decision reason, or None when the ball came close enough to need
        simulating."""
        sim = self.sim
        s = sim.state
        _, lo, hi = self._survey(row, CLEARANCE)
        parabola = sim.model.ball_drag == 0.0
        line = sim.config.capture_rule == "line"
        if parabola:  # whether and when it comes into the box is one answer along the whole flight
            entry = flight.entry_time(s.x[row], s.v[row], lo, hi, self.ground, deadline - s.time)
            if entry is None:
                return "flies_away"
            entry = self._on_step_grid(entry)
            if entry > 0.0:  # until then it is clear of everything and cannot cross the opening (inside the box)
                if line:  # but it may pass the line beside the frame, out of play
                    entry = self._line_instant(row, ball, entry, from_front, through_opening=False)
                yield from self._move(row, entry, through_opening=False)
                reason = self._flown_to(row, ball, deadline, from_front)
                if reason is not None:
                    return reason
        while True:
            if self._never_enters(row, lo, hi, deadline - s.time):  # it left the box, for good
                return "flies_away"
            if parabola and flight.lies_still(s.x[row], s.v[row], self.ground):
                return "at_rest"  # beside the sleeping scene, nothing can move it any more
            tau = self._flight_time(row, deadline)
            if tau <= 0.0:
                return None  # near something: integrate from here (on the full simulation's step grid)
            if line:
                tau = self._line_instant(row, ball, tau, from_front, through_opening=True)
            yield from self._move(row, tau, through_opening=True)
            reason = self._flown_to(row, ball, deadline, from_front)
            if reason is not None:
                return reason

    def _flown_to(self, row: int, ball: int, deadline: float, from_front: bool) -> str | None:
        """The decision at the end of a piece of flight: the ``line`` rule's (see
        :meth:`_line_reason`), the time limit, or None."""
        sim = self.sim
        s = sim.state
        if sim.config.capture_rule == "line":
            reason = self._line_reason(s.x[row], bool(s.entered[ball]), from_front)
            if reason is not None:
                return reason
        return "time_limit" if deadline - s.time < 0.5 * sim.dt else None

    def _move(self, row: int, tau: float, through_opening: bool) -> Plan:
        """Fly the ball in ``row`` for ``tau`` (filmed if there are frames); if it may pass
        ``through_opening``, book its crossing along the chord of the flight (a conservative
        step's chord stays, like its arc, within the clearance about its start)."""
        sim = self.sim
        s, n_net = sim.state, sim.model.n_net
        before = s.x[n_net:].copy()
        start = s.x[row].copy(), s.v[row].copy(), s.time
        if self.frames is not None:
            yield from self._film_flight(row, *start, start[2] + tau)
        s.x[row], s.v[row] = self._flight(start[0], start[1], tau)
        if through_opening:
            stepping.update_entered(s.x, before, n_net, s.entered, sim.kernel_model.opening)
        s.time = start[2] + tau
        if self.frames is not None:
            yield Tick()  # an instant within half a step after the flight's end: here is its nearest substep

    def _line_instant(self, row: int, ball: int, tau: float, from_front: bool, through_opening: bool) -> float:
        """``tau``, or, if the ball in ``row`` flying for ``tau`` ends wholly over the line (see
        :meth:`_line_reason`; its crossing booked only if it may pass ``through_opening``), the
        first instant it is (within LINE_TIME_TOLERANCE after it): the line rule's decision."""
        sim = self.sim
        s, n_net = sim.state, sim.model.n_net
        start, before = (s.x[row].copy(), s.v[row].copy()), s.x[n_net:].copy()

        def over(t: float) -> bool:
            x, entered = s.x.copy(), s.entered.copy()
            x[row] = self._flight(*start, t)[0]
            if through_opening:
                stepping.update_entered(x, before, n_net, entered, sim.kernel_model.opening)
            return self._line_reason(x[row], bool(entered[ball]), from_front) is not None

        if not over(tau):
            return tau
        lo, hi = 0.0, tau
        while hi - lo > LINE_TIME_TOLERANCE:
            mid = 0.5 * (lo + hi)
            lo, hi = (lo, mid) if over(mid) else (mid, hi)
        return hi

    def _flight(self, x: np.ndarray, v: np.ndarray, tau: float) -> tuple[np.ndarray, np.ndarray]:
        """Where a lone ball starting at ``x``, ``v`` is after ``tau``: closed form without air,
        RK4 steps through air."""
        m = self.sim.model
        if m.ball_drag == 0.0:
            return flight.advance(x, v, tau, self.ground)
        p, u = np.array(x, dtype=np.float64), np.array(v, dtype=np.float64)
        g = self.ground
        air.fly(p, u, tau, m.gravity, m.ball_drag, m.wind, g.radius, g.restitution, g.friction, g.threshold,
                air.MAX_FLIGHT_STEP)
        return p, u

    def _flight_time(self, row: int, deadline: float) -> float:
        """How long the ball in ``row`` can fly in closed form from now, clear of everything and
        at most to ``deadline``, ending on the full simulation's step grid; 0.0 if it cannot fly
        to the next step there, and must be simulated."""
        gap = self._clearance(row)
        if gap <= CLEARANCE:
            return 0.0
        return self._on_step_grid(min(self._safe_time(row, gap), deadline - self.sim.state.time))

    def _on_step_grid(self, tau: float) -> float:
        """The longest flight of at most ``tau`` from now that ends on the step grid of the full
        simulation (the launch plus whole steps of the scene's dt), or 0.0: where the fast path
        integrates, it then takes the steps the full simulation takes there."""
        dt, now = self.sim.config.simulation.dt, self.sim.state.time
        steps = math.floor((now + tau - self.launched) / dt + 1e-9)
        return max(0.0, self.launched + steps * dt - now)

    def _never_enters(self, row: int, lo: np.ndarray, hi: np.ndarray, horizon: float) -> bool:
        """The ball in ``row`` cannot come into the box ``lo``..``hi`` within ``horizon``: its
        parabola (with bounces) misses it; through air, it lies outside, held by friction."""
        s, m, g = self.sim.state, self.sim.model, self.ground
        p, v = s.x[row], s.v[row]
        if not (np.any(p < lo) or np.any(p > hi)):
            return False  # inside it already
        if m.ball_drag == 0.0:
            return flight.entry_time(p, v, lo, hi, g, horizon) is None
        return air.held_by_friction(v, m.gravity, m.ball_drag, m.wind, g.radius, g.friction, p)

    def _safe_time(self, row: int, gap: float) -> float:
        """A time within which the ball in ``row`` cannot travel ``gap``."""
        m, v = self.sim.model, self.sim.state.v[row]
        speed = float(np.linalg.norm(v))
        if m.ball_drag == 0.0:
            g = abs(m.gravity)
        else:  # bound the acceleration over at most AIR_PIECE, with the speed it could gain
            g0 = air.max_acceleration(speed, m.gravity, m.ball_drag, m.wind)
            g = air.max_acceleration(speed + g0 * AIR_PIECE, m.gravity, m.ball_drag, m.wind)
        tau = gap / speed if g == 0.0 else (-speed + math.sqrt(speed * speed + 4.0 * g * gap)) / (2.0 * g)
        return tau if m.ball_drag == 0.0 else min(tau, AIR_PIECE)

    def _film_flight(self, row: int, x: np.ndarray, v: np.ndarray, t: float, end: float) -> Plan:
        """Put the ball in ``row``, flying in closed form from ``x``, ``v`` at time ``t``, where it
        is at each frame instant before ``end``, and stop there (a Tick). The flight itself is
        computed apart, so that filming changes nothing."""
        assert self.frames is not None
        s = self.sim.state
        while (instant := self.frames.next_instant(s.time, TIME_EPSILON)) < end - TIME_EPSILON:
            s.x[row], s.v[row] = self._flight(x, v, instant - t)
            s.time = instant
            yield Tick()

    def _film_miss(self, row: int, t_limit: float) -> Plan:
        """Film a missed ball's closed-form flight on until MISS_FILMED_AFTER_LANDING after it
        first lands (or ``t_limit``); then put the ball and the time back as decided."""
        s = self.sim.state
        kept = s.x[row].copy(), s.v[row].copy(), s.time
        end = min(t_limit, s.time + flight.ground_time(s.x[row], s.v[row], self.ground) + MISS_FILMED_AFTER_LANDING)
        yield from self._film_flight(row, *kept, end)
        s.x[row], s.v[row], s.time = kept

    def _film_on(self) -> Plan:
        """Film a ball decided over the line on for LINE_FILMED seconds, everything integrated (a
        goal runs into the net, a ball out of play onto it or past it), then put the scene, its
        time and its work counters back as decided."""
        sim = self.sim
        kept = sim.checkpoint()
        cfg = sim.config.simulation
        sim.awake = True
        yield from integrate_until_stops(sim.state, Integrate(round(LINE_FILMED / cfg.dt), sim.integrator, cfg.dt),
                                         self.frames)
        sim.restore(kept)

    def _potential_without(self, row: int, energy: Any) -> float:
        """Potential energy of everything but the ball in ``row`` (``energy``: the current one)."""
        s = self.sim.state
        return energy.spring + energy.gravity + self.sim.model.gravity / s.inv_mass[row] * s.x[row, 2]

    def _at_rest(self, row: int, recent: list[tuple[float, np.ndarray]]) -> bool:
        """The ball in ``row`` and the bodies near it (centres within twice its radius plus
        REST_REACH of its centre) moved no coordinate more than ``rest_speed`` x REST_WINDOW between
        any check of the last REST_WINDOW (``recent``, oldest first, covering it) and now.
        Positions, not velocities: a light net under a resting ball keeps a velocity jitter of
        the order of its acceleration x dt (2.8 cm/s on the goal's roof at 0.5 ms) while nothing
        moves."""
        s, m = self.sim.state, self.sim.model
        if s.time - recent[0][0] < REST_WINDOW - TIME_EPSILON:
            return False
        reach, bound = 2.0 * m.ball_radius + REST_REACH, self.sim.config.simulation.rest_speed * REST_WINDOW
        return all(still_since(s.x, x, row, reach, bound) for _, x in recent[:-1])

    def _decided(self, row: int, reference_energy: float, at_rest: bool,
                 lo: np.ndarray, hi: np.ndarray, deadline: float) -> str | None:
        """The reason the throw's outcome is decided now, or None (``lo``, ``hi``: the region
        from :meth:`_survey` with AWAKE_MARGIN). The energy bound counts, besides the energy
        free now, all the wind could still feed the balls before ``deadline``."""
        sim = self.sim
        s, m = sim.state, sim.model
        p = s.x[row]
        if self._never_enters(row, lo, hi, math.inf):
            return "flies_away"
        if at_rest:
            return "at_rest"
        energy = sim.energy()  # one evaluation per check: kinetic and potential together
        free = energy.kinetic + max(0.0, self._potential_without(row, energy) - reference_energy)
        free += sim.n_balls * air.wind_power_bound(m.ball_mass, m.ball_drag, m.wind) * max(0.0, deadline - s.time)
        reach = p[2] + free * s.inv_mass[row] / abs(m.gravity) if m.gravity != 0.0 else math.inf
        if reach < sim.opening.lowest_z:
            return "cannot_reach_opening"
        # nor can it get to the opening before the deadline, at the speed all that energy and
        # its own fall to the ground could give it (a vertical mouth has no height to climb)
        fall = abs(m.gravity) * max(0.0, p[2] - m.ball_radius) / s.inv_mass[row]
        top_speed = math.sqrt(2.0 * (free + fall) * s.inv_mass[row])
        if top_speed * (deadline - s.time) < float(sim.opening.distance(p[None])[0]):
            return "cannot_reach_opening"
        return None
