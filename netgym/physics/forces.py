"""Smooth forces: springs with dampers along them, and gravity. numba kernels over flat arrays.

A spring between particles i and j with ``d = x_i - x_j``, ``l = |d|``, ``u = d / l`` pushes i
with ``-(ks (l - L) + kd (v_i - v_j) . u) u`` and j with the opposite force. Air drag
``-drag * m * v`` acts on every free body.
"""

from __future__ import annotations

import math

from netgym.physics.jit import inline_kernel, kernel

from netgym.physics.rows import add_pair_force


@inline_kernel
def spring_axis(x, i, j):
    """Length of the spring i-j and its unit direction from j to i (zero if degenerate)."""
    dx = x[i, 0] - x[j, 0]
    dy = x[i, 1] - x[j, 1]
    dz = x[i, 2] - x[j, 2]
    length = math.sqrt(dx * dx + dy * dy + dz * dz)
    inv = 1.0 / length if length > 1e-12 else 0.0
    return length, dx * inv, dy * inv, dz * inv


@kernel
def spring_forces(x, v, springs, params, f):
    """Add every spring's force to ``f`` (n, 3)."""
    for s in range(springs.shape[0]):
        i = springs[s, 0]
        j = springs[s, 1]
        length, ux, uy, uz = spring_axis(x, i, j)
        if length <= 1e-12:
            continue
        closing = (v[i, 0] - v[j, 0]) * ux + (v[i, 1] - v[j, 1]) * uy + (v[i, 2] - v[j, 2]) * uz
        mag = -params[s, 1] * (length - params[s, 0]) - params[s, 2] * closing
        add_pair_force(f, i, j, mag * ux, mag * uy, mag * uz)


@kernel
def accelerations(x, v, inv_mass, gravity, drag, springs, params, a):
    """Write into ``a`` the accelerations of all bodies (zero for fixed ones): springs,
    gravity and linear air drag ``-drag * v``."""
    a[:] = 0.0
    spring_forces(x, v, springs, params, a)
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
        potential_s += 0.5 * params[s, 1] * (length - params[s, 0]) ** 2
    return kinetic, potential_s, potential_g
