"""Time integrators for the smooth forces (springs, dampers, gravity); contacts come after.

Five methods, one numba kernel each; :func:`smooth_step` takes the one its
:class:`~netgym.physics.model.model.Settings` are made for, chosen when the calling kernel compiles:

====================  =====  ===============================================================
integrator            order  notes
====================  =====  ===============================================================
explicit_euler        1      the seed's method: x += dt v(t), v += dt a(t)
symplectic_euler      1      v += dt a(t), then x += dt v(t+dt); bounded energy error
rk4                   4      classical Runge-Kutta, four force evaluations per step
implicit_euler        1      linearised backward Euler (Baraff-Witkin), matrix-free
                             conjugate gradients; stable at large dt
imex_euler            1      symplectic Euler on elastic forces and gravity, dampers and air
                             drag implicit (a symmetric Gauss-Seidel sweep of exact per-spring
                             damper solves): the dampers no longer limit dt
====================  =====  ===============================================================

Every kernel takes a ``work`` array of shape (WORK_SLOTS, n, 3) and a ``coef`` array of
shape (n_springs, 5) as scratch space (with ``coef_dt``, together a :class:`Scratch`), so a step
allocates nothing.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numba.core.errors import NumbaTypeError
from numba.extending import overload

from netgym.physics.kernels import spring_law
from netgym.physics.kernels.smooth_forces import accelerations, spring_axis, spring_forces
from netgym.physics.kernels.jit import inline_kernel, kernel
from netgym.kinds import Integrator
from netgym.physics.kernels.rows import add_pair_force, add_scaled, copy_rows

WORK_SLOTS = 8
START_SLOT = 7   # the one slot the integrators leave alone: positions at the start of a substep


class Scratch(NamedTuple):
    """Scratch space of the integrators: ``work`` (WORK_SLOTS, n_bodies, 3), ``coef`` (n_springs, 5)
    and ``coef_dt`` (1,): the step for which ``coef``'s last two columns hold IMEX Euler's damper
    shares (they depend on the step and the masses, so :func:`step_imex_euler` computes them once
    per step size), 0 when they hold anything else or were computed for other masses (a
    relaxation with inertia sets it so). A scratch serves one net: its springs and masses.
    ``anchors``: the state's compliant contact grips
    (:mod:`~netgym.physics.compliant.grip`; none with impulses)."""

    work: np.ndarray
    coef: np.ndarray
    coef_dt: np.ndarray
    anchors: np.ndarray

    @staticmethod
    def shapes(n_bodies: int, n_springs: int) -> tuple[tuple[int, int, int], tuple[int, int], tuple[int]]:
        """The shapes of ``work``, ``coef`` and ``coef_dt`` for bodies and springs of this size."""
        return (WORK_SLOTS, n_bodies, 3), (max(n_springs, 1), 5), (1,)

    @classmethod
    def sized(cls, n_bodies: int, n_springs: int) -> "Scratch":
        """Zeroed scratch for bodies and springs of this size, with no anchors."""
        return cls(*(np.zeros(shape) for shape in cls.shapes(n_bodies, n_springs)), np.zeros((0, 4)))


@kernel
def step_euler(x, v, inv_mass, gravity, drag, springs, dt, work, symplectic):
    """One Euler step from a(x, v). Explicit: x += dt v(t), then v += dt a. Symplectic
    (semi-implicit): v += dt a first, then x += dt v(t+dt)."""
    a = work[0]
    accelerations(x, v, inv_mass, gravity, drag, springs, a)
    euler_update(x, v, a, dt, symplectic)


@inline_kernel
def euler_update(x, v, a, dt, symplectic):
    """Euler's update of (x, v) in place by the accelerations ``a`` of their start: explicit
    (x by the old velocity) or symplectic (x by the new)."""
    for k in range(x.shape[0]):
        for c in range(3):
            if symplectic:
                v[k, c] += dt * a[k, c]
                x[k, c] += dt * v[k, c]
            else:
                x[k, c] += dt * v[k, c]
                v[k, c] += dt * a[k, c]


@inline_kernel
def damper_share(dt, kd, w_i, w_j):
    """What one pass of the symmetric damper sweep (over ``dt / 2``, backward Euler along the
    spring) takes of a spring's closing speed, per unit inverse mass of each end; scalars in the
    kernels, arrays from the stability estimate."""
    hk = 0.5 * dt * kd
    return hk / (1.0 + hk * (w_i + w_j))


@inline_kernel
def sweep_dampers(v, pairs, coef, forward):
    """One Gauss-Seidel pass of per-spring damper solves over the springs, in order if
    ``forward`` else in reverse: spring s's closing speed c along its axis ``coef[s, :3]`` takes
    ``-c coef[s, 3]`` from its first particle and gives ``c coef[s, 4]`` to its second."""
    n_springs = pairs.shape[0]
    for t in range(n_springs):
        s = t if forward else n_springs - 1 - t
        i = pairs[s, 0]
        j = pairs[s, 1]
        ux, uy, uz = coef[s, 0], coef[s, 1], coef[s, 2]
        closing = (v[i, 0] - v[j, 0]) * ux + (v[i, 1] - v[j, 1]) * uy + (v[i, 2] - v[j, 2]) * uz
        add_scaled(v, i, -(closing * coef[s, 3]), ux, uy, uz)
        add_scaled(v, j, closing * coef[s, 4], ux, uy, uz)


@kernel
def step_imex_euler(x, v, inv_mass, gravity, drag, springs, dt, scratch):
    """Implicit-explicit Euler: v += dt (elastic + gravity) / m explicitly, then the dampers and
    air drag implicitly, then x += dt v (symplectic order). ``scratch``: a :class:`Scratch`.

    Air drag is solved exactly (``v /= 1 + dt drag``). The dampers are solved by a symmetric
    Gauss-Seidel sweep (the springs forwards, then backwards, each pass over dt/2) in which each
    spring's damper alone is integrated with backward Euler along its axis at the start of the
    step: its closing speed c becomes ``c / (1 + h kd (w_i + w_j))``. Every such update removes
    kinetic energy and the symmetric sweep is a symmetric contraction, so the dampers no longer
    limit the stable dt (the elastic frequencies do). The shares of that update depend on dt and
    the masses: they are computed again only when dt differs from ``scratch.coef_dt`` (which
    whoever changes the masses sets to 0).
    """
    a, coef = scratch.work[0], scratch.coef
    pairs, params = springs.pairs, springs.params
    a[:] = 0.0
    for s in range(pairs.shape[0]):
        i = pairs[s, 0]
        j = pairs[s, 1]
        length, ux, uy, uz = spring_axis(x, i, j)
        mag = spring_law.elastic_tension(length, params[s, 0], params[s, 1])
        add_pair_force(a, i, j, mag * ux, mag * uy, mag * uz)
        coef[s, 0], coef[s, 1], coef[s, 2] = ux, uy, uz
    if scratch.coef_dt[0] != dt:
        for s in range(pairs.shape[0]):
            i = pairs[s, 0]
            j = pairs[s, 1]
            share = damper_share(dt, params[s, 2], inv_mass[i], inv_mass[j])
            coef[s, 3], coef[s, 4] = share * inv_mass[i], share * inv_mass[j]
        scratch.coef_dt[0] = dt
    keep = 1.0 / (1.0 + dt * drag)
    for k in range(x.shape[0]):
        w = inv_mass[k]
        if w > 0.0:
            v[k, 0] = (v[k, 0] + dt * a[k, 0] * w) * keep
            v[k, 1] = (v[k, 1] + dt * a[k, 1] * w) * keep
            v[k, 2] = (v[k, 2] + dt * (a[k, 2] * w + gravity)) * keep
    sweep_dampers(v, pairs, coef, True)
    sweep_dampers(v, pairs, coef, False)
    for k in range(x.shape[0]):
        if inv_mass[k] > 0.0:
            add_scaled(x, k, dt, v[k, 0], v[k, 1], v[k, 2])


@kernel
def step_rk4(x, v, inv_mass, gravity, drag, springs, dt, work):
    """Classical fourth-order Runge-Kutta on (x, v)."""
    xs, vs, a, xsum, vsum = work[0], work[1], work[2], work[3], work[4]
    accelerations(x, v, inv_mass, gravity, drag, springs, a)
    copy_rows(xsum, v)
    copy_rows(vsum, a)
    for stage in range(3):
        rk4_stage_state(x, v, a, xs, vs, stage, dt)
        accelerations(xs, vs, inv_mass, gravity, drag, springs, a)
        rk4_accumulate(xsum, vsum, vs, a, stage)
    rk4_combine(x, v, xsum, vsum, dt, x, v)


@inline_kernel
def rk4_stage_state(x, v, a, xs, vs, stage, dt):
    """The state (xs, vs) at which RK4 evaluates its stage ``stage + 1`` from the step's start
    (x, v) and the last evaluation ``a``: half a step on (stages 0, 1), a whole one on (stage 2)."""
    h = dt if stage == 2 else 0.5 * dt
    for k in range(x.shape[0]):
        for c in range(3):
            vel = vs[k, c] if stage > 0 else v[k, c]
            xs[k, c] = x[k, c] + h * vel
            vs[k, c] = v[k, c] + h * a[k, c]


@inline_kernel
def rk4_accumulate(xsum, vsum, vs, a, stage):
    """Add the evaluation at the state of ``stage`` (see :func:`rk4_stage_state`) to RK4's sums,
    weighted 2 for the half-step stages and 1 for the last."""
    weight = 1.0 if stage == 2 else 2.0
    for k in range(xsum.shape[0]):
        for c in range(3):
            xsum[k, c] += weight * vs[k, c]
            vsum[k, c] += weight * a[k, c]


@inline_kernel
def rk4_combine(x, v, xsum, vsum, dt, x_out, v_out):
    """RK4's end of step from its start (x, v) and sums: into (x_out, v_out), which may be (x, v)."""
    for k in range(x.shape[0]):
        for c in range(3):
            x_out[k, c] = x[k, c] + dt / 6.0 * xsum[k, c]
            v_out[k, c] = v[k, c] + dt / 6.0 * vsum[k, c]


@kernel
def _system_product(y, inv_mass, mass_scale, pairs, coef, out):
    """out = (M - dt df/dv - dt^2 df/dx) y, with rows of fixed bodies zero; the drag part of
    df/dv is the factor ``mass_scale = 1 + dt * drag`` on M."""
    for k in range(y.shape[0]):
        w = inv_mass[k]
        m = mass_scale / w if w > 0.0 else 0.0
        out[k, 0] = m * y[k, 0]
        out[k, 1] = m * y[k, 1]
        out[k, 2] = m * y[k, 2]
    for s in range(pairs.shape[0]):
        i = pairs[s, 0]
        j = pairs[s, 1]
        dx = y[i, 0] - y[j, 0]
        dy = y[i, 1] - y[j, 1]
        dz = y[i, 2] - y[j, 2]
        ux, uy, uz, iso, axial = coef[s, 0], coef[s, 1], coef[s, 2], coef[s, 3], coef[s, 4]
        along = axial * (ux * dx + uy * dy + uz * dz)
        add_pair_force(out, i, j, iso * dx + along * ux, iso * dy + along * uy, iso * dz + along * uz)
    for k in range(y.shape[0]):
        if inv_mass[k] == 0.0:
            out[k, 0] = 0.0
            out[k, 1] = 0.0
            out[k, 2] = 0.0


@kernel
def _dot(a, b):
    total = 0.0
    for k in range(a.shape[0]):
        total += a[k, 0] * b[k, 0] + a[k, 1] * b[k, 1] + a[k, 2] * b[k, 2]
    return total


@kernel
def step_implicit_euler(x, v, inv_mass, gravity, drag, springs, dt, settings, scratch):
    """Linearised backward Euler (Baraff & Witkin 1998).

    Solves ``(M - dt D - dt^2 K) dv = dt (f + dt K v)`` by Jacobi-preconditioned conjugate
    gradients (to ``settings.cg_tolerance``, at most ``settings.cg_max_iterations``), where
    K = df/dx (with the transverse term clamped at zero under compression so the system stays
    positive definite) and D = df/dv; then v += dv, x += dt v. ``scratch``: a :class:`Scratch`.
    Returns the number of CG iterations used.
    """
    work, coef = scratch.work, scratch.coef
    scratch.coef_dt[0] = 0.0  # coef is about to hold this system's terms, not IMEX Euler's shares
    mass_scale = 1.0 + dt * drag
    _implicit_system(x, v, inv_mass, gravity, drag, springs, dt, work, coef)
    iterations = _conjugate_gradients(inv_mass, mass_scale, springs.pairs, dt, settings, scratch)
    dv = work[5]
    for k in range(x.shape[0]):
        for c in range(3):
            v[k, c] += dv[k, c]
            x[k, c] += dt * v[k, c]
    return iterations


@kernel
def _implicit_system(x, v, inv_mass, gravity, drag, springs, dt, work, coef):
    """Assemble implicit Euler's system: the forces plus ``dt K v`` in ``work[0]``, the
    diagonal of the system matrix (the preconditioner) in ``work[6]``, and each spring's axis
    and stiffness terms (ux, uy, uz, iso, axial) in ``coef`` for :func:`_system_product`."""
    f, diag = work[0], work[6]
    f[:] = 0.0
    spring_forces(x, v, springs, f)
    pairs, params = springs.pairs, springs.params
    mass_scale = 1.0 + dt * drag
    for k in range(x.shape[0]):
        w = inv_mass[k]
        m = 1.0 / w if w > 0.0 else 0.0
        for c in range(3):
            f[k, c] -= drag * m * v[k, c]
            diag[k, c] = mass_scale * m
        f[k, 2] += m * gravity
    for s in range(pairs.shape[0]):
        i = pairs[s, 0]
        j = pairs[s, 1]
        length, ux, uy, uz = spring_axis(x, i, j)
        ks, kd = params[s, 1], params[s, 2]
        iso = dt * dt * ks * spring_law.stretch(length, params[s, 0])
        axial = dt * dt * ks + dt * kd - iso
        coef[s, 0], coef[s, 1], coef[s, 2], coef[s, 3], coef[s, 4] = ux, uy, uz, iso, axial
        for c, uc in ((0, ux), (1, uy), (2, uz)):
            contribution = iso + axial * uc * uc
            diag[i, c] += contribution
            diag[j, c] += contribution
        # rhs term dt^2 K v (stiffness part only: iso and dt^2 ks along u)
        rx = v[i, 0] - v[j, 0]
        ry = v[i, 1] - v[j, 1]
        rz = v[i, 2] - v[j, 2]
        along = (dt * dt * ks - iso) * (ux * rx + uy * ry + uz * rz)
        add_pair_force(f, j, i, (iso * rx + along * ux) / dt, (iso * ry + along * uy) / dt,
                       (iso * rz + along * uz) / dt)


@kernel
def _conjugate_gradients(inv_mass, mass_scale, pairs, dt, settings, scratch):
    """Solve the system :func:`_implicit_system` assembled for ``dv`` (``work[5]``) by
    Jacobi-preconditioned conjugate gradients from dv = 0; returns the iterations taken."""
    work, coef = scratch.work, scratch.coef
    f, r, p, z, q, dv, diag = work[0], work[1], work[2], work[3], work[4], work[5], work[6]
    n = inv_mass.shape[0]
    # r = rhs - A dv with dv = 0 initially; rhs = dt * f (already holds f + dt K v)
    for k in range(n):
        free = inv_mass[k] > 0.0
        for c in range(3):
            dv[k, c] = 0.0
            r[k, c] = dt * f[k, c] if free else 0.0
            z[k, c] = r[k, c] / diag[k, c] if free else 0.0
            p[k, c] = z[k, c]
    rz_old = _dot(r, z)
    threshold = settings.cg_tolerance * settings.cg_tolerance * _dot(r, r)
    iterations = 0
    while iterations < settings.cg_max_iterations and _dot(r, r) > threshold and rz_old > 0.0:
        _system_product(p, inv_mass, mass_scale, pairs, coef, q)
        alpha = rz_old / _dot(p, q)
        for k in range(n):
            for c in range(3):
                dv[k, c] += alpha * p[k, c]
                r[k, c] -= alpha * q[k, c]
                z[k, c] = r[k, c] / diag[k, c] if inv_mass[k] > 0.0 else 0.0
        rz_new = _dot(r, z)
        beta = rz_new / rz_old
        rz_old = rz_new
        for k in range(n):
            for c in range(3):
                p[k, c] = z[k, c] + beta * p[k, c]
        iterations += 1
    return iterations


def smooth_step(settings, x, v, inv_mass, model, gravity, dt, scratch, stats):
    """One step of ``dt`` of the smooth forces of ``model`` (a
    :class:`~netgym.physics.model.model.KernelModel`: the net's drag, the springs) and ``gravity`` with the
    integrator ``settings`` are made for (their class, see
    :meth:`~netgym.physics.model.model.Settings.make`); ``scratch``: a :class:`Scratch`; implicit Euler
    adds its CG iterations to ``stats``. For numba kernels only: the integrator is chosen when
    the calling kernel compiles, so that it compiles that integrator alone."""
    raise TypeError("smooth_step runs inside numba kernels only")


@overload(smooth_step, jit_options={"error_model": "numpy"})
def _smooth_step(settings, x, v, inv_mass, model, gravity, dt, scratch, stats):
    """The implementation of :func:`smooth_step` for the integrator of ``settings``' type."""
    integrator = getattr(getattr(settings, "instance_class", None), "INTEGRATOR", None)
    if integrator is None:
        raise NumbaTypeError(f"smooth_step takes settings of one integrator (Settings.make or Settings.of), "
                             f"not {settings}")
    if integrator == Integrator.RK4:
        def step(settings, x, v, inv_mass, model, gravity, dt, scratch, stats):
            step_rk4(x, v, inv_mass, gravity, model.drag, model.springs, dt, scratch.work)
    elif integrator == Integrator.IMEX_EULER:
        def step(settings, x, v, inv_mass, model, gravity, dt, scratch, stats):
            step_imex_euler(x, v, inv_mass, gravity, model.drag, model.springs, dt, scratch)
    elif integrator == Integrator.IMPLICIT_EULER:
        def step(settings, x, v, inv_mass, model, gravity, dt, scratch, stats):
            stats[0].cg_iterations += step_implicit_euler(x, v, inv_mass, gravity, model.drag, model.springs, dt,
                                                          settings, scratch)
    else:
        symplectic = integrator == Integrator.SYMPLECTIC_EULER

        def step(settings, x, v, inv_mass, model, gravity, dt, scratch, stats):
            step_euler(x, v, inv_mass, gravity, model.drag, model.springs, dt, scratch.work, symplectic)
    return step
