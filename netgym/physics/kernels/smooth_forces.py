"""Smooth forces: springs with dampers along them, and gravity. numba kernels over flat arrays.

Each spring pushes its ends by :mod:`~netgym.physics.kernels.spring_law`; air drag ``-drag * m * v``
acts on every free body.
"""

from __future__ import annotations

import math

from netgym.physics.kernels import spring_law
from netgym.physics.kernels.jit import inline_kernel, kernel
from netgym.physics.kernels.springs import EXISTS, ON_FIRST, ON_SECOND, POSITIONS, REST, TOTALS, VELOCITIES


@inline_kernel
def spring_axis(x, i, j):
    """Length of the spring i-j and its unit direction from j to i (zero if degenerate)."""
    dx = x[i, 0] - x[j, 0]
    dy = x[i, 1] - x[j, 1]
    dz = x[i, 2] - x[j, 2]
    length = math.sqrt(dx * dx + dy * dy + dz * dz)
    inv = 1.0 / length if length > 1e-12 else 0.0
    return length, dx * inv, dy * inv, dz * inv


@inline_kernel
def _to_columns(rows, columns, n):
    """Copy the first ``n`` rows of the C-contiguous ``rows`` (at least n, 3) into the first n
    places of the three rows of ``columns``. Read as a flat array with a constant stride, the
    copy is vectorised (the compiler interleaves the loads); indexed by row and column it is not."""
    flat = rows.reshape(-1)
    for k in range(n):
        columns[0, k] = flat[3 * k]
        columns[1, k] = flat[3 * k + 1]
        columns[2, k] = flat[3 * k + 2]


@inline_kernel
def _from_columns(columns, rows, n):
    """Copy the first ``n`` places of ``columns``' three rows back into the first n rows of the
    C-contiguous ``rows``, vectorised likewise."""
    flat = rows.reshape(-1)
    for k in range(n):
        flat[3 * k] = columns[0, k]
        flat[3 * k + 1] = columns[1, k]
        flat[3 * k + 2] = columns[2, k]


@inline_kernel
def _dense_group_forces(positions, velocities, params, forces, offset, first, length, start, ks, kd):
    """Forces of the dense group (offset, first, length, start), of stiffness ``ks`` and damping
    ``kd``, into ``forces`` (a :class:`~netgym.physics.kernels.springs.Springs`' ``dense_forces``:
    planes ON_FIRST and ON_SECOND), -0.0 (which adds nothing, bitwise) where a spring is missing
    or degenerate; ``params``: its ``dense_params`` (rows REST, EXISTS). Contiguous columns and
    unsigned indices: the compiler vectorises this loop."""
    rest, present = params[REST], params[EXISTS]
    on_first, on_second = forces[ON_FIRST], forces[ON_SECOND]
    for t in range(length):
        i = first + t
        j = i + offset
        s = start + t
        dx = positions[0, i] - positions[0, j]
        dy = positions[1, i] - positions[1, j]
        dz = positions[2, i] - positions[2, j]
        length_ij = math.sqrt(dx * dx + dy * dy + dz * dz)
        inv = 1.0 / length_ij
        ux = dx * inv
        uy = dy * inv
        uz = dz * inv
        closing = ((velocities[0, i] - velocities[0, j]) * ux + (velocities[1, i] - velocities[1, j]) * uy
                   + (velocities[2, i] - velocities[2, j]) * uz)
        mag = spring_law.tension(length_ij, rest[s], ks, kd, closing)
        exists = (present[s] != 0.0) & (length_ij > 1e-12)
        fx = mag * ux
        fy = mag * uy
        fz = mag * uz
        on_first[0, s] = fx if exists else -0.0
        on_first[1, s] = fy if exists else -0.0
        on_first[2, s] = fz if exists else -0.0
        on_second[0, s] = -fx if exists else -0.0
        on_second[1, s] = -fy if exists else -0.0
        on_second[2, s] = -fz if exists else -0.0


@inline_kernel
def _add_dense_group(totals, forces, first, length, start):
    """Add a dense group's ``forces`` (a plane of ``dense_forces``) to the force columns
    ``totals`` of the particles ``first .. first + length - 1``."""
    for c in range(3):
        for t in range(length):
            totals[c, first + t] += forces[c, start + t]


@kernel
def spring_forces(x, v, springs, f):
    """Add every spring's force to ``f`` (n, 3); ``springs``: a
    :class:`~netgym.physics.kernels.springs.Springs`. Bitwise the sum of a loop over the springs sorted
    by particle pair: on the second particles group by group in decreasing offset, then on the
    first particles in increasing offset (the :mod:`~netgym.physics.kernels.springs` module says why).
    The sparse groups' loops stay in this body: as an inlined kernel they ran slower."""
    groups, sparse, scratch = springs.groups, springs.sparse, springs.sparse_forces
    columns = springs.columns
    positions, velocities, totals = columns[POSITIONS], columns[VELOCITIES], columns[TOTALS]
    n = springs.n_particles
    _to_columns(x, positions, n)
    _to_columns(v, velocities, n)
    _to_columns(f, totals, n)
    n_groups = groups.shape[0]
    for h in range(n_groups):
        group = groups[n_groups - 1 - h]
        offset, first, length, start = group.offset, group.first, group.length, group.start
        if group.dense:
            _dense_group_forces(positions, velocities, springs.dense_params, springs.dense_forces, offset, first,
                                length, start, group.ks, group.kd)
            _add_dense_group(totals, springs.dense_forces[ON_SECOND], first + offset, length, start)
            continue
        for s in range(start, start + length):
            spring, force = sparse[s], scratch[s]
            i = spring.i
            j = spring.j
            length_ij, ux, uy, uz = spring_axis(positions.T, i, j)
            force.exists = 0.0
            if length_ij <= 1e-12:
                continue
            closing = ((velocities[0, i] - velocities[0, j]) * ux + (velocities[1, i] - velocities[1, j]) * uy
                       + (velocities[2, i] - velocities[2, j]) * uz)
            mag = spring_law.tension(length_ij, spring.rest, spring.ks, spring.kd, closing)
            force.x, force.y, force.z, force.exists = mag * ux, mag * uy, mag * uz, 1.0
            totals[0, j] -= force.x
            totals[1, j] -= force.y
            totals[2, j] -= force.z
    for g in range(n_groups):
        group = groups[g]
        first, length, start = group.first, group.length, group.start
        if group.dense:
            _add_dense_group(totals, springs.dense_forces[ON_FIRST], first, length, start)
            continue
        for s in range(start, start + length):
            force = scratch[s]
            if force.exists != 0.0:
                i = sparse[s].i
                totals[0, i] += force.x
                totals[1, i] += force.y
                totals[2, i] += force.z
    _from_columns(totals, f, n)


@kernel
def accelerations(x, v, inv_mass, gravity, drag, springs, a):
    """Write into ``a`` the accelerations of all bodies (zero for fixed ones): springs (a
    :class:`~netgym.physics.kernels.springs.Springs`), gravity and linear air drag ``-drag * v``."""
    a[:] = 0.0
    spring_forces(x, v, springs, a)
    for k in range(x.shape[0]):
        w = inv_mass[k]
        if w > 0.0:
            a[k, 0] = a[k, 0] * w - drag * v[k, 0]
            a[k, 1] = a[k, 1] * w - drag * v[k, 1]
            a[k, 2] = a[k, 2] * w - drag * v[k, 2] + gravity
        else:
            a[k, 0] = 0.0
            a[k, 1] = 0.0
            a[k, 2] = 0.0


@kernel
def kinetic_energy(v, inv_mass):
    """Kinetic energy of the free bodies (rows of ``v`` with ``inv_mass`` > 0), in joules."""
    kinetic = 0.0
    for k in range(v.shape[0]):
        w = inv_mass[k]
        if w > 0.0:
            kinetic += 0.5 * (1.0 / w) * (v[k, 0] ** 2 + v[k, 1] ** 2 + v[k, 2] ** 2)
    return kinetic


@kernel
def energies(x, v, inv_mass, gravity, springs, params):
    """(kinetic, spring potential, gravitational potential) of all free bodies, in joules."""
    kinetic = kinetic_energy(v, inv_mass)
    potential_g = 0.0
    for k in range(x.shape[0]):
        w = inv_mass[k]
        if w > 0.0:
            potential_g -= (1.0 / w) * gravity * x[k, 2]
    potential_s = 0.0
    for s in range(springs.shape[0]):
        i = springs[s, 0]
        j = springs[s, 1]
        length = math.sqrt((x[i, 0] - x[j, 0]) ** 2 + (x[i, 1] - x[j, 1]) ** 2 + (x[i, 2] - x[j, 2]) ** 2)
        potential_s += spring_law.energy(length, params[s, 0], params[s, 1])
    return kinetic, potential_s, potential_g
