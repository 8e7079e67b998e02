"""The hot loop: many integration steps, with contacts and opening crossings, in one numba call."""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np
from numba.extending import overload

from netgym.kinds import ContactModel
from netgym.physics.compliant.step import compliant_step
from netgym.physics.compliant.system import new_work
from netgym.physics.kernels.jit import inline_kernel, kernel

from netgym.physics.kernels.air import rk4_step
from netgym.physics.kernels.impulse_contacts import (Bodies, resolve_ball_contacts, resolve_ball_ground, resolve_ground,
                                             resolve_lone_ball)
from netgym.physics.kernels.smooth_forces import kinetic_energy
from netgym.physics.kernels.integrators import START_SLOT, smooth_step
from netgym.physics.kernels.rows import copy_row, copy_rows
from netgym.physics.kernels.surroundings import alone_for_a_step

OK, DIVERGED = 0, 1
COUNTERS = np.dtype([("substeps", np.int64), ("cg_iterations", np.int64)])
"""The work counters :func:`advance` adds to: a one-record array of this type."""


def new_counters() -> np.ndarray:
    """A zeroed one-record array of :data:`COUNTERS`."""
    return np.zeros(1, dtype=COUNTERS)


@kernel
def _finite_and_below(v, limit):
    """True if every velocity is finite and no speed exceeds ``limit``."""
    for k in range(v.shape[0]):
        s2 = v[k, 0] * v[k, 0] + v[k, 1] * v[k, 1] + v[k, 2] * v[k, 2]
        if not s2 <= limit * limit:
            return False
    return True


@kernel
def _closing_speed(x, v, n_net, radius, dt, speeds):
    """Largest speed of a ball plus that of any net particle that could reach it within dt:
    the relative speed the substeps must resolve (``speeds``: scratch for the net's speeds)."""
    for k in range(n_net):
        speeds[k] = math.sqrt(v[k, 0] ** 2 + v[k, 1] ** 2 + v[k, 2] ** 2)
    worst = 0.0
    for b in range(n_net, x.shape[0]):
        ball = math.sqrt(v[b, 0] ** 2 + v[b, 1] ** 2 + v[b, 2] ** 2)
        near = 0.0
        for k in range(n_net):
            speed = speeds[k]
            reach = radius + (ball + speed) * dt
            if (abs(x[k, 0] - x[b, 0]) < reach and abs(x[k, 1] - x[b, 1]) < reach
                    and abs(x[k, 2] - x[b, 2]) < reach):
                near = max(near, speed)
        worst = max(worst, ball + near)
    return worst


@kernel
def _substeps(x, v, n_net, radius, dt, travel, speeds):
    """Substeps of ``dt`` such that no ball moves more than ``travel`` (m) in one relative to a
    net particle that could reach it (see :func:`_closing_speed`). When the fastest ball and
    the fastest particle together stay within one substep, that bound answers (the closing speed
    never exceeds it, so the count is the same) without the search for near particles."""
    fastest_net, fastest_ball = 0.0, 0.0
    for k in range(n_net):
        fastest_net = max(fastest_net, v[k, 0] ** 2 + v[k, 1] ** 2 + v[k, 2] ** 2)
    for b in range(n_net, x.shape[0]):
        fastest_ball = max(fastest_ball, v[b, 0] ** 2 + v[b, 1] ** 2 + v[b, 2] ** 2)
    if (math.sqrt(fastest_ball) + math.sqrt(fastest_net)) * dt / travel <= 1.0:
        return 1
    return max(1, int(math.ceil(_closing_speed(x, v, n_net, radius, dt, speeds) * dt / travel)))


@kernel
def net_box(x, n_net, box):
    """Write into ``box`` (6,) the bounding box of the net's particles: min x, y, z, max x, y, z."""
    for c in range(3):
        box[c] = math.inf
        box[c + 3] = -math.inf
    for k in range(n_net):
        for c in range(3):
            box[c] = min(box[c], x[k, c])
            box[c + 3] = max(box[c + 3], x[k, c])


@kernel
def _free_ball_flight(x, v, before, before_v, n_net, gravity, h, ball_drag, wind):
    """Balls feel only gravity (and air, when ``ball_drag`` > 0) between contacts: give them
    their free flight over ``h`` from the substep's start, whatever the integrator: the exact
    parabola without air (no time-discretisation error), an RK4 step through air."""
    for b in range(before.shape[0]):
        _fly_ball(x, v, n_net + b, before, before_v, b, gravity, h, ball_drag, wind)


@inline_kernel
def _fly_ball(x, v, k, before, before_v, b, gravity, h, ball_drag, wind):
    """The free flight over ``h`` of the ball in row ``k`` of ``x``, ``v`` from its position and
    velocity in row ``b`` of ``before``, ``before_v`` (see :func:`_free_ball_flight`)."""
    if ball_drag > 0.0:
        copy_row(x, k, before, b)
        copy_row(v, k, before_v, b)
        rk4_step(x[k], v[k], h, gravity, ball_drag, wind)
        return
    for c in range(3):
        x[k, c] = before[b, c] + h * before_v[b, c]
        v[k, c] = before_v[b, c]
    x[k, 2] += 0.5 * gravity * h * h
    v[k, 2] += gravity * h


@kernel
def update_entered(x, before, n_net, entered, opening):
    """Set a ball's flag when its centre crosses the opening (an
    :class:`~netgym.physics.model.opening.OpeningRecord`) inwards inside the rectangle, clear it when
    it crosses outwards."""
    axis, sign, plane, u, w = opening.axis, opening.sign, opening.plane, opening.u, opening.w
    for b in range(entered.shape[0]):
        k = n_net + b
        h0 = sign * (before[b, axis] - plane)
        h1 = sign * (x[k, axis] - plane)
        if (h0 >= 0.0) == (h1 >= 0.0):
            continue
        s = h0 / (h0 - h1)
        cu = before[b, u] + s * (x[k, u] - before[b, u])
        cw = before[b, w] + s * (x[k, w] - before[b, w])
        if opening.u_lo <= cu <= opening.u_hi and opening.w_lo <= cw <= opening.w_hi:
            entered[b] = 1 if h1 < 0.0 else 0


@kernel
def _step_buffers(x, n_net):
    """The scratch of :func:`_step` for a state of ``x.shape[0]`` bodies: the balls' velocities
    at a substep's start, the net's bounding box, the net particles' speeds and the indices of
    the particles near a ball."""
    return np.empty((x.shape[0] - n_net, 3)), np.empty(6), np.empty(n_net), np.empty(n_net, dtype=np.int64)


def substep(settings, bodies, entered, model, net_gravity, h, scratch, stats, buffers, work):
    """The motion and contacts of one substep of ``h`` of :func:`_step`, by the contact model of
    ``settings``: the smooth forces, the balls' free flight and then the contacts' projections
    and impulses, or :func:`~netgym.physics.compliant.step.compliant_step` (``work``: its
    scratch, from :func:`contact_work`; the parts it splits the substep into booked as
    substeps). For numba kernels only: the model is chosen when the calling kernel compiles."""
    raise TypeError("substep runs inside numba kernels only")


def _compliant(settings) -> bool:
    """Whether the numba type of ``settings`` is of a compliant contact model's class."""
    return getattr(settings.instance_class, "CONTACT_MODEL", ContactModel.IMPULSE) == ContactModel.COMPLIANT


@overload(substep, jit_options={"error_model": "numpy"})
def _substep(settings, bodies, entered, model, net_gravity, h, scratch, stats, buffers, work):
    """The implementation of :func:`substep` for the contact model of ``settings``' type."""
    if _compliant(settings):
        def step(settings, bodies, entered, model, net_gravity, h, scratch, stats, buffers, work):
            parts = compliant_step(settings, bodies.x, bodies.v, bodies.inv_mass, model, net_gravity, h, scratch, work)
            stats[0].substeps += parts - 1  # the caller books one
        return step

    def impulse_step(settings, bodies, entered, model, net_gravity, h, scratch, stats, buffers, work):
        x, v, inv_mass = bodies.x, bodies.v, bodies.inv_mass
        before_v, box, _, near = buffers
        n_net = model.n_net
        before = bodies.start[n_net:]
        for b in range(x.shape[0] - n_net):
            copy_row(before_v, b, v, n_net + b)
        smooth_step(settings, x, v, inv_mass, model, net_gravity, h, scratch, stats)
        if entered is not None:
            if x.shape[0] > n_net:
                _free_ball_flight(x, v, before, before_v, n_net, model.gravity, h, model.ball_drag, model.wind)
                net_box(x, n_net, box)
            resolve_ball_contacts(bodies, model, box, near)
        resolve_ground(bodies, model)
    return impulse_step


def contact_work(settings, x, model, scratch):
    """The scratch :func:`substep` needs besides the integrators': None for impulses,
    :func:`~netgym.physics.compliant.system.new_work`'s for the compliant model, its grips kept
    in ``scratch.anchors``. For numba kernels only."""
    raise TypeError("contact_work runs inside numba kernels only")


@overload(contact_work, jit_options={"error_model": "numpy"})
def _contact_work(settings, x, model, scratch):
    """The implementation of :func:`contact_work` for the contact model of ``settings``' type."""
    if _compliant(settings):
        return lambda settings, x, model, scratch: new_work(x, model, scratch.anchors)
    return lambda settings, x, model, scratch: None


@kernel
def _step(bodies, entered, model, settings, scratch, stats, buffers, net_gravity, work):
    """One step of ``settings.dt`` (see :func:`advance`) of ``bodies`` (their ``start``: every
    body's position at the start of the substep), in substeps where balls move fast: the passes
    of a substep in order, each handed the :class:`~netgym.physics.model.model.KernelModel` or
    the parts of it it needs; ``buffers`` from :func:`_step_buffers`; ``net_gravity``: the
    acceleration gravity gives the net (``model.gravity`` but in a relaxation with inertia);
    ``entered``: the balls' flags, or None for a net without balls, whose kernels numba then
    compiles without the balls' passes (it prunes the branches on ``entered is not None``)."""
    speeds = buffers[2]
    n_net, radius, dt = model.n_net, model.ball_radius, settings.dt
    x, v, start = bodies.x, bodies.v, bodies.start
    before = start[n_net:]
    n_balls = x.shape[0] - n_net
    substeps = 1
    if entered is not None and n_balls > 0:
        substeps = _substeps(x, v, n_net, radius, dt, settings.max_travel * radius, speeds)
    h = dt / substeps
    for _sub in range(substeps):
        copy_rows(start, x)
        substep(settings, bodies, entered, model, net_gravity, h, scratch, stats, buffers, work)
        if entered is not None:
            update_entered(x, before, n_net, entered, model.opening)
        stats[0].substeps += 1


@kernel
def advance(x, v, inv_mass, entered, model, settings, n_steps, scratch, stats):
    """Advance the state by ``n_steps`` steps of ``settings.dt``, in place.

    Balls move on their exact free-flight parabola between contacts, or through air (RK4) when
    the scene has some (net particles feel linear air drag). A step is split into equal substeps when a ball could otherwise move
    more than ``max_travel * radius`` relative to the net particles near it in one. Each substep:

    1. the smooth forces (springs, dampers, gravity, drag) with the chosen integrator;
    2. the balls' free flight over the substep;
    3. contacts, in one deterministic pass;
    4. the balls' ``entered`` flags (crossings of the opening).

    ``scratch`` is an :class:`~netgym.physics.kernels.integrators.Scratch` for this many bodies;
    ``stats`` a :data:`COUNTERS` record array. Returns OK, or DIVERGED as soon as a velocity is
    non-finite or above ``divergence_speed`` (the state is then invalid and the caller restores
    its copy).
    """
    buffers = _step_buffers(x, model.n_net)
    work = contact_work(settings, x, model, scratch)
    bodies = Bodies(x, v, inv_mass, scratch.work[START_SLOT])  # a slot the integrators leave alone
    for _ in range(n_steps):
        if not _finite_and_below(v, settings.divergence_speed):
            return DIVERGED
        _step(bodies, entered, model, settings, scratch, stats, buffers, model.gravity, work)
    return OK if _finite_and_below(v, settings.divergence_speed) else DIVERGED


@kernel
def advance_alone(x, v, inv_mass, entered, model, settings, n_steps, row, stats):
    """Advance the ball in ``row`` by up to ``n_steps`` steps of ``settings.dt``, everything else
    held still (a sleeping scene), in place, while it can touch nothing that moves within the
    next step (:func:`~netgym.physics.kernels.surroundings.alone_for_a_step`): the steps
    :func:`advance` takes when nothing but that ball moves and it touches only what cannot (poles,
    pinned particles, the ground), with the same arithmetic. Returns (OK, the steps taken), or
    (DIVERGED, 0) as :func:`advance` diverges."""
    n_net, radius, dt = model.n_net, model.ball_radius, settings.dt
    start = x.copy()  # only the ball's row changes
    before, before_v, b = start[n_net:], np.empty((x.shape[0] - n_net, 3)), row - n_net
    box, near = np.empty(6), np.empty(n_net, dtype=np.int64)
    net_box(x, n_net, box)
    bodies = Bodies(x, v, inv_mass, start)
    ball = v[row:row + 1]
    travel = settings.max_travel * radius
    for taken in range(n_steps):
        if not _finite_and_below(ball, settings.divergence_speed):
            return DIVERGED, 0
        if not alone_for_a_step(x, v, inv_mass, model, row, dt):
            return OK, taken
        speed = math.sqrt(ball[0, 0] ** 2 + ball[0, 1] ** 2 + ball[0, 2] ** 2)
        substeps = max(1, int(math.ceil(speed * dt / travel)))  # :func:`_substeps` with all else still
        h = dt / substeps
        for _sub in range(substeps):
            copy_row(start, row, x, row)
            copy_row(before_v, b, v, row)
            _fly_ball(x, v, row, before, before_v, b, model.gravity, h, model.ball_drag, model.wind)
            resolve_lone_ball(bodies, row, model, box, near)
            resolve_ball_ground(bodies, row, radius, model.materials.ball_ground, model.restitution_threshold)
            update_entered(x, before, n_net, entered, model.opening)
            stats[0].substeps += 1
    return (OK, n_steps) if _finite_and_below(ball, settings.divergence_speed) else (DIVERGED, 0)


@kernel
def _largest_displacement(x, earlier):
    """Largest coordinate difference between ``x`` and ``earlier``."""
    worst = 0.0
    for k in range(x.shape[0]):
        for c in range(3):
            worst = max(worst, abs(x[k, c] - earlier[k, c]))
    return worst


class RestRecord(NamedTuple):
    """What :func:`relax` carries across calls: ``history`` (window, n_bodies, 3), the positions
    of the last steps; ``memory``, a one-record array of :data:`REST_MEMORY`; the rest test's
    ``displacement`` (m), whether the net is kinetically ``damped``, and the net's ``inertia``
    as a multiple of its mass (see :func:`relax`)."""

    history: np.ndarray
    memory: np.ndarray
    displacement: float
    damped: bool
    inertia: float


REST_MEMORY = np.dtype([("recorded", np.int64), ("kinetic", np.float64), ("steps", np.int64), ("at_rest", np.bool_)])
"""What a relaxation remembers besides its history: the steps recorded in it, the net's last
kinetic energy, the steps taken by the last :func:`relax` call, and whether it came to rest."""


def new_rest_memory() -> np.ndarray:
    """A one-record array of :data:`REST_MEMORY` for a relaxation that has not begun."""
    memory = np.zeros(1, dtype=REST_MEMORY)
    memory[0]["kinetic"] = np.inf
    return memory


@kernel
def relax(x, v, inv_mass, entered, model, settings, n_steps, scratch, stats, rest):
    """Dynamic relaxation: :func:`advance` for at most ``n_steps`` steps, with kinetic damping of
    the net when ``rest.damped`` (every net particle's velocity is zeroed after a step whose net
    kinetic energy fell, i.e. just past a peak), until no coordinate moved more than
    ``rest.displacement`` over the last ``rest.history.shape[0]`` steps. Balls keep their own
    dynamics (friction and restitution settle them): zeroing them too would hold a collapsing
    pile back step by step, so that it passed the rest test while still falling.

    With ``rest.inertia`` > 1 the net's inertia is that many times its mass while its weight
    stays (dynamic relaxation with a fictitious mass): the equilibrium is the same, the net's
    frequencies are sqrt(inertia) lower, so that the relaxation may step that much longer, and
    in contacts the net yields to a ball less. IMEX Euler's damper shares, computed for those
    masses, are marked stale after the call.

    ``rest`` is a :class:`RestRecord`; its history and memory carry the relaxation across
    calls. Returns OK or DIVERGED as :func:`advance` does.
    """
    weighted = rest.inertia != 1.0
    inv_inertia = _inertial(inv_mass, model.n_net, rest.inertia) if weighted else inv_mass
    if weighted:
        scratch.coef_dt[0] = 0.0
    status = _relax_steps(x, v, inv_inertia, entered, model, settings, n_steps, scratch, stats, rest)
    if weighted:
        scratch.coef_dt[0] = 0.0
    return status


@kernel
def _inertial(inv_mass, n_net, inertia):
    """``inv_mass`` with the net particles' divided by ``inertia``."""
    scaled = inv_mass.copy()
    for k in range(n_net):
        scaled[k] = inv_mass[k] / inertia
    return scaled


@kernel
def _relax_steps(x, v, inv_mass, entered, model, settings, n_steps, scratch, stats, rest):
    """The steps of :func:`relax`, with ``inv_mass`` its inertia's."""
    history, memory = rest.history, rest.memory[0]
    window = history.shape[0]
    buffers = _step_buffers(x, model.n_net)
    work = contact_work(settings, x, model, scratch)
    net_gravity = model.gravity / rest.inertia
    bodies = Bodies(x, v, inv_mass, scratch.work[START_SLOT])  # a slot the integrators leave alone
    memory.steps = 0
    memory.at_rest = False
    for i in range(n_steps):
        if not _finite_and_below(v, settings.divergence_speed):
            return DIVERGED
        _step(bodies, entered, model, settings, scratch, stats, buffers, net_gravity, work)
        memory.steps = i + 1
        if rest.damped:
            kinetic = kinetic_energy(v[:model.n_net], inv_mass[:model.n_net])
            if kinetic < memory.kinetic:
                v[:model.n_net] = 0.0
                kinetic = 0.0
            memory.kinetic = kinetic
        recorded = memory.recorded
        slot = recorded % window
        if recorded >= window and _largest_displacement(x, history[slot]) < rest.displacement:
            memory.at_rest = True
            return OK
        copy_rows(history[slot], x)
        memory.recorded = recorded + 1
    return OK if _finite_and_below(v, settings.divergence_speed) else DIVERGED
