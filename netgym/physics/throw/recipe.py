"""A throw as a plan: launch a ball and simulate until its outcome is decided (the fast path).

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
from typing import TYPE_CHECKING, Any

import numpy as np

from netgym.arguments import vector_argument
from netgym.kinds import ContactModel
from netgym.errors import SimulationDivergedError
from netgym.physics.compliant import contacts as compliant_contacts
from netgym.physics.kernels import air
from netgym.physics.fast_path import reach
from netgym.physics.film import Film
from netgym.physics.outcomes import Reason
from netgym.physics.pause import pause_plan
from netgym.physics.plans import CHUNK_SECONDS, Integrate, Plan, Tick, Watched
from netgym.physics.progress_guard import ProgressGuard
from netgym.physics.throw import decisions
from netgym.physics.throw.clear_flight import fly_clear
from netgym.physics.throw.clearance import can_roll_alone, clearance
from netgym.physics.throw.filming import film_after
from netgym.physics.throw.free_flight import FreeFlight
from netgym.physics.throw.records import TUNING, Ball, Course, ThrowContext, ThrowResult
from netgym.physics.kernels.surroundings import LoneBall
from netgym.physics.fast_path.watch import RestWindow, Watch

if TYPE_CHECKING:
    from netgym.physics.simulator import Simulator


class Throw:
    """One throw into a simulator's scene, as a plan: launch a ball and simulate until its
    outcome is decided. Uses only the simulator's public API.

    :param sim: the :class:`~netgym.physics.simulator.Simulator` to throw into.
    :param position: release point (m).
    :param velocity: launch velocity (m/s).
    :param fast: take the fast path; False integrates everything to the time limit (the reference).
    :param film: a :class:`~netgym.physics.film.Film` to film the throw with (run the plan with
        the same film): the plan then stops at every instant of its clock from the launch on
        (integration at the substep nearest it, a :class:`~netgym.physics.plans.Tick` while the
        ball flies in closed form), a miss decided in closed form is flown on to its landing for
        the frames and a ball decided by the capture rule filmed on (then put back as decided).
    """

    def __init__(self, sim: "Simulator", position: Any, velocity: Any, fast: bool = True,
                 film: Film | None = None) -> None:
        self.position = vector_argument(position, "position")  # fail on bad input before any work
        self.velocity = vector_argument(velocity, "velocity")
        self.context = ThrowContext(sim, fast, sim.capture_rule, film, FreeFlight.of(sim.model),
                                    LoneBall.of(sim.kernel_model))

    def plan(self) -> Plan:
        """The throw as a plan; it returns the :class:`ThrowResult`. Its phases:

        1. the pause: the net is brought to rest if it still moves (:func:`~netgym.physics.pause.pause_plan`);
        2. :meth:`_launch` the ball;
        3. :meth:`_until_decided`: fly it in closed form while it is clear of everything
           (:func:`~netgym.physics.throw.clear_flight.fly_clear`), integrate everything while it
           is near (:meth:`_integrate_near`), and after each piece decide
           (:func:`~netgym.physics.throw.decisions.after_piece`);
        4. film on after the decision, when filmed (:func:`~netgym.physics.throw.filming.film_after`);
        5. take the ball out, unless the capture rule keeps it (a ball captured under ``held``
           stays in the scene; a miss, or a goal under ``line``, is removed).
        """
        throw = self.context
        sim = throw.sim
        settled = yield from pause_plan(sim, throw.film)
        start = sim.state.copy()
        yield from self._launch()
        try:
            reason = yield from self._until_decided()
        except SimulationDivergedError:
            sim.state.restore(start)
            raise
        result = self._result(reason)
        yield from film_after(throw, reason, t_limit=start.time + sim.config.simulation.time_limit)
        if not (result.captured and throw.rule.keeps_captured):
            # a ball flown clear of a sleeping scene leaves it asleep (nothing there moved); else it settles again
            sim.remove_ball(throw.ball.index, wake=False)
        return dataclasses.replace(result, settle_substeps=settled.substeps, settle_time=settled.time)

    def _launch(self) -> Plan:
        """Put the ball in the scene at its release, and start the :class:`Course` of the throw
        (its clock, time limit and the energy it is measured against); a frame of the launch."""
        throw = self.context
        sim = throw.sim
        s = sim.state
        index = sim.launch_ball(self.position, self.velocity)
        throw.ball = Ball(index, sim.model.n_net + index)
        if throw.film is not None:
            if not throw.film.settling:
                throw.film.clock.restart(s.time)
            yield Tick()  # the launch
        m = sim.model
        about = m.ball_radius + max(float(m.poles.radius.max(initial=0.0)), m.ball_radius if sim.n_balls > 1 else 0.0)
        deadline = s.time + sim.config.simulation.time_limit
        throw.course = Course(launched=s.time, deadline=deadline, substeps=sim.substeps, about=about,
                              from_front=sim.opening.depth(s.x[throw.ball.row]) <= 0.0,
                              watch=self._watch(deadline, about))

    def _watch(self, deadline: float, about: float) -> Watch:
        """The :class:`~netgym.physics.fast_path.watch.Watch` of a throw launched now, with the ball's
        ``deadline`` and ``about`` (see :class:`Course`): its energy budget measured now."""
        throw = self.context
        sim, row = throw.sim, throw.ball.row
        s, m, km, cfg = sim.state, sim.model, sim.kernel_model, sim.config.simulation
        compliant = sim.contact_model == ContactModel.COMPLIANT
        budget = reach.Budget(reach.potential_without_ball(s.x, s.v, s.inv_mass, row, km.gravity, km.springs.pairs,
                                                           km.springs.params),
                              sim.n_balls * air.wind_power_bound(m.ball_mass, m.ball_drag, m.wind), km.gravity,
                              m.ball_radius, sim.opening.lowest_z, cfg.contact_stiffness if compliant else 0.0)
        rest = RestWindow.sized(s.x.shape[0], cfg.dt, TUNING.rest_window, TUNING.time_epsilon,
                                2.0 * m.ball_radius + TUNING.rest_reach, cfg.rest_speed * TUNING.rest_window)
        return Watch(row, s.time, deadline, cfg.dt, max(1, round(CHUNK_SECONDS / cfg.dt)), TUNING.clearance,
                     about + TUNING.awake_margin, throw.rule.decision_depth(m.ball_radius), TUNING.sleep_speed,
                     TUNING.far_clearance, TUNING.far_sleep_speed, budget, rest, np.empty(6),
                     compliant_contacts.new_list(s.x, km) if compliant else compliant_contacts.NO_CONTACTS)

    def _until_decided(self) -> Plan:
        """Simulate the ball until its outcome is decided; returns the :class:`Reason`.

        While the scene sleeps (the fast path), the ball flies in closed form, and the flight
        itself may decide the throw. Once it comes near something, it is stepped alone while it
        can touch nothing that moves (poles, pinned particles, the ground only: the scene sleeps
        on), else the scene wakes and is integrated chunk by chunk, with a decision after each;
        when nothing but the ball moves any more and it could fly clear or move alone, or the rest
        moves slowly and the ball is far from it (a net swaying after the ball left it off the
        rim), the scene sleeps again. The ball alone flies again only once it is clear of
        everything, where the compiled loop of its chunks hands back
        (:func:`~netgym.physics.fast_path.watch.roll_watched`).

        Every piece is booked with a :class:`~netgym.physics.progress_guard.ProgressGuard`: a
        loop that stopped moving simulated time on raises
        :class:`~netgym.errors.NoProgressError`, naming the launch and the state, instead of
        spinning.
        """
        throw = self.context
        sim = throw.sim
        guard = ProgressGuard(throw.course.launched, throw.course.deadline, sim.dt, self._where)
        alone = False  # the ball is near only what cannot move, the scene asleep: step it alone next
        while True:
            guard.piece(sim.state.time)
            rolled = near_fixed = False
            if throw.fast and not sim.awake:
                if alone:
                    yield from self._roll_alone()
                    rolled = True
                else:
                    reason = yield from fly_clear(throw)
                    if reason is not None:
                        return reason
                    near_fixed = can_roll_alone(throw)
                    if not near_fixed:
                        sim.wake()
                        if clearance(throw) < 0.0:
                            continue  # launched overlapping something: let the contacts act before deciding
            else:
                yield from self._integrate_near()
            verdict = decisions.after_piece(throw)
            if verdict.reason is not None:
                return verdict.reason
            if verdict.quiet:
                sim.sleep(keep=throw.ball.row)
            alone = near_fixed or (rolled and clearance(throw) <= TUNING.clearance and can_roll_alone(throw))

    def _where(self) -> str:
        """The throw and where it stands, for an error."""
        sim, row = self.context.sim, self.context.ball.row
        s = sim.state
        return (f"the throw from {self.position.tolist()} m at {self.velocity.tolist()} m/s into the "
                f"{sim.config.name} scene ({sim.integrator.label}, dt {sim.dt:g} s, {sim.contact_model.label} "
                f"contacts, {'fast path' if self.context.fast else 'full simulation'}), now at {s.time!r} s with "
                f"the ball at {s.x[row].tolist()} m moving {s.v[row].tolist()} m/s, the scene "
                f"{'awake' if sim.awake else 'asleep'}")

    def _integrate_near(self) -> Plan:
        """Integrate everything for one chunk of CHUNK_SECONDS (less before the time limit; none
        at it): the ball is near something, or this is the full simulation. On the fast path,
        unfilmed, chunk after chunk in one request, for as long as the checks after them see
        nothing that could be decided (:class:`~netgym.physics.plans.Watched`): the decision
        after it is the one after the last of those chunks. Integration wakes the scene; each
        chunk ends on the full simulation's step grid, as every flight does."""
        throw = self.context
        sim, watch = throw.sim, throw.course.watch
        dt = sim.config.simulation.dt
        left = round((throw.course.deadline - sim.state.time) / dt)
        if left > 0:
            sim.wake()
            if throw.fast and throw.film is None:
                yield Watched(sim.integrator, dt, watch)
            else:
                yield Integrate(min(watch.chunk, left), sim.integrator, dt)

    def _roll_alone(self) -> Plan:
        """Step the ball alone for one chunk, everything else asleep (unfilmed, chunk after chunk
        in one request, while nothing could be decided and it stays near nothing that moves:
        :func:`~netgym.physics.fast_path.watch.roll_watched`): it touches only poles, pinned
        particles and the ground, on the steps the full simulation takes, with its arithmetic,
        while the net's residual motion (below ``sleep_speed``) is left out as in a flight."""
        throw = self.context
        sim, watch = throw.sim, throw.course.watch
        dt = sim.config.simulation.dt
        if throw.film is None:
            yield Watched(sim.integrator, dt, watch, alone=True)
        else:
            left = round((throw.course.deadline - sim.state.time) / dt)
            yield Integrate(min(watch.chunk, left), sim.integrator, dt, alone=throw.ball.row)

    def _result(self, reason: Reason) -> ThrowResult:
        """The :class:`ThrowResult` of a throw decided now for ``reason``."""
        throw = self.context
        sim, course = throw.sim, throw.course
        s, (index, row) = sim.state, throw.ball
        entered = bool(s.entered[index])
        captured = throw.rule.captured(course.decision, entered, sim.opening.contains(s.x[row]))
        return ThrowResult(captured=captured, entered=entered,
                           final_position=s.x[row].copy(), final_velocity=s.v[row].copy(),
                           time=s.time - course.launched, substeps=sim.substeps - course.substeps,
                           reason=reason.for_outcome(captured))


def throw_plan(sim: "Simulator", position: Any, velocity: Any, fast: bool = True, film: Film | None = None) -> Plan:
    """:func:`throw` as a plan (see :meth:`~netgym.physics.simulator.Simulator.run`); it returns
    the :class:`ThrowResult`."""
    return Throw(sim, position, velocity, fast, film).plan()


def throw(sim: "Simulator", position: Any, velocity: Any, fast: bool = True, film: Film | None = None,
          observer: Any = None) -> ThrowResult:
    """Launch a ball from ``position`` (m) at ``velocity`` (m/s) into ``sim``'s scene and simulate
    until its outcome is decided (see :class:`Throw`).

    The net is first brought to rest if it still moves. A ball captured under the ``held`` rule
    stays in the scene; a missed one, or a goal under ``line``, is removed. With ``fast=False``
    everything is integrated from launch to the time limit (the reference the fast path is tested
    against). A ``film`` films the throw; ``observer(sim)`` is called after every request.
    """
    return sim.run(throw_plan(sim, position, velocity, fast, film), film, observer)
