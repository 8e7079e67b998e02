"""Contacts, resolved after each integration substep by projection and impulses.

Every contact removes the overlap (split by inverse mass, so momentum is conserved) and, if
the bodies approach, applies a normal impulse with restitution (none below the restitution
threshold, so resting contacts stay still) and a Coulomb friction impulse bounded by
``friction * normal impulse``. Contacts of a ball also hold static friction on positions (as in
position-based dynamics): when the contact's tangential slip over the substep is within
``friction * overlap`` it is undone, so a ball at rest on a slope flatter than the friction
angle stays put instead of creeping downhill by ``g sin(slope) dt`` per second. Kinds handled:

- ball / net particle and ball / structural spring segment (interior points of the segment,
  the impulse shared by its two particles by barycentric weight): springs cannot sink into
  a ball;
- ball / pole capsule and ball / ground: static, infinitely heavy obstacles;
- ball / ball, every pair (no pass when there is a single ball);
- net particle / ground.

Tunnelling is prevented by the caller, which splits steps so that no ball moves more than a
fraction of its radius relative to the net in one substep.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from netgym.physics.kernels.jit import inline_kernel, kernel
from netgym.physics.kernels.rows import add_scaled


COINCIDENT = 1e-24   # m^2: squared distances below this leave no direction between two centres
NEAR_MARGIN = 0.05   # m: slack of the segment broad phase (see _ball_net)


class Bodies(NamedTuple):
    """The arrays contacts act on: positions ``x`` and velocities ``v`` (n, 3), ``inv_mass``
    (n,), and ``start``, every body's position at the start of the substep."""

    x: np.ndarray
    v: np.ndarray
    inv_mass: np.ndarray
    start: np.ndarray


class Touch(NamedTuple):
    """Where two bodies touch: the unit normal (nx, ny, nz) and the ``depth`` of the overlap along it."""

    nx: float
    ny: float
    nz: float
    depth: float


@kernel
def _direction(dx, dy, dz, dist2, ex, ey, ez):
    """(unit vector along (dx, dy, dz), its length), the squared length being ``dist2``. When the
    two centres coincide, a defined direction instead: perpendicular to the feature's axis
    (ex, ey, ez) (zero for a point) along the coordinate axis least aligned with it, or +z for a
    point."""
    dist = math.sqrt(dist2)
    if dist2 >= COINCIDENT:
        return dx / dist, dy / dist, dz / dist, dist
    if ex == 0.0 and ey == 0.0 and ez == 0.0:
        return 0.0, 0.0, 1.0, dist
    ax, ay, az = abs(ex), abs(ey), abs(ez)
    px, py, pz = 0.0, 0.0, 0.0
    if az <= ax and az <= ay:
        pz = 1.0
    elif ay <= ax:
        py = 1.0
    else:
        px = 1.0
    len2 = ex * ex + ey * ey + ez * ez
    along = (px * ex + py * ey + pz * ez) / len2
    nx, ny, nz = px - along * ex, py - along * ey, pz - along * ez
    norm = math.sqrt(nx * nx + ny * ny + nz * nz)
    return nx / norm, ny / norm, nz / norm, dist


@kernel
def _static_slip(sx, sy, sz, nx, ny, nz, bound):
    """Static friction on positions (as in position-based dynamics): the tangential part of a
    contact's slip (sx, sy, sz) over one substep when it is within the Coulomb bound
    ``friction * depth`` (it is then undone), else zero (the velocity impulse handles sliding)."""
    along = sx * nx + sy * ny + sz * nz
    tx, ty, tz = sx - along * nx, sy - along * ny, sz - along * nz
    if tx * tx + ty * ty + tz * tz > bound * bound:
        return 0.0, 0.0, 0.0
    return tx, ty, tz


@kernel
def _pair_response(bodies, a, i, j, t, touch, material, threshold):
    """Resolve a contact between body ``a`` and the point ``(1-t) x_i + t x_j`` of
    :class:`Bodies`, of a :class:`~netgym.physics.model.contact_tables.Material`.

    The :class:`Touch`'s normal ``n`` points from ``a`` to the point; its ``depth`` is the
    overlap along it. A single body as the second side is ``i == j`` with ``t = 0``. A resting
    contact (approaching no faster than ``threshold``) also holds static friction on positions
    (on the slip since the substep's ``start``). Returns a bound on how far it moved any body (m).
    """
    (x, v, inv_mass, start), (nx, ny, nz, depth), (restitution, friction) = bodies, touch, material
    wa = inv_mass[a]
    wi = (1.0 - t) * inv_mass[i]
    wj = t * inv_mass[j] if j != i else 0.0
    w_point = (1.0 - t) * wi + t * wj
    total = wa + w_point
    if total <= 0.0:
        return 0.0
    moved = max(wa, wi, wj) / total * depth * (1.0 + friction)  # the overlap's share, then the slip undone
    # position: remove the overlap
    lam = depth / total
    add_scaled(x, a, -(wa * lam), nx, ny, nz)
    add_scaled(x, i, wi * lam, nx, ny, nz)
    if j != i:
        add_scaled(x, j, wj * lam, nx, ny, nz)
    # velocity of the point relative to a
    rx = (1.0 - t) * v[i, 0] + t * v[j, 0] - v[a, 0]
    ry = (1.0 - t) * v[i, 1] + t * v[j, 1] - v[a, 1]
    rz = (1.0 - t) * v[i, 2] + t * v[j, 2] - v[a, 2]
    closing = rx * nx + ry * ny + rz * nz
    if -closing <= threshold:
        # a resting contact: static friction on positions, on the point's slip relative to a
        sx = (1.0 - t) * (x[i, 0] - start[i, 0]) + t * (x[j, 0] - start[j, 0]) - (x[a, 0] - start[a, 0])
        sy = (1.0 - t) * (x[i, 1] - start[i, 1]) + t * (x[j, 1] - start[j, 1]) - (x[a, 1] - start[a, 1])
        sz = (1.0 - t) * (x[i, 2] - start[i, 2]) + t * (x[j, 2] - start[j, 2]) - (x[a, 2] - start[a, 2])
        sx, sy, sz = _static_slip(sx, sy, sz, nx, ny, nz, friction * depth)
        add_scaled(x, a, wa / total, sx, sy, sz)
        add_scaled(x, i, -(wi / total), sx, sy, sz)
        if j != i:
            add_scaled(x, j, -(wj / total), sx, sy, sz)
    if closing >= 0.0:
        return moved
    e = restitution if -closing > threshold else 0.0
    jn = -(1.0 + e) * closing / total
    tx = rx - closing * nx
    ty = ry - closing * ny
    tz = rz - closing * nz
    slip = math.sqrt(tx * tx + ty * ty + tz * tz)
    jt = 0.0
    if slip > 1e-12:
        jt = min(friction * jn, slip / total) / slip
    # impulse on the point is +jn n - jt t_vec; on a the opposite
    px = jn * nx - jt * tx
    py = jn * ny - jt * ty
    pz = jn * nz - jt * tz
    add_scaled(v, a, -wa, px, py, pz)
    add_scaled(v, i, wi, px, py, pz)
    if j != i:
        add_scaled(v, j, wj, px, py, pz)
    return moved


@kernel
def _static_response(bodies, k, touch, material, threshold, hold):
    """Resolve a contact of body ``k`` with an immovable obstacle; the :class:`Touch`'s normal
    points out of the obstacle towards ``k``. ``hold``: a resting contact holds static friction
    on positions, as in :func:`_pair_response` (balls; net particles on the ground do not)."""
    x, v, start = bodies.x, bodies.v, bodies.start
    nx, ny, nz, depth = touch
    restitution, friction = material
    add_scaled(x, k, depth, nx, ny, nz)
    closing = v[k, 0] * nx + v[k, 1] * ny + v[k, 2] * nz
    if hold and -closing <= threshold:  # a resting contact: static friction on positions
        sx, sy, sz = _static_slip(start[k, 0] - x[k, 0], start[k, 1] - x[k, 1], start[k, 2] - x[k, 2],
                                  nx, ny, nz, friction * depth)
        add_scaled(x, k, 1.0, sx, sy, sz)
    if closing >= 0.0:
        return
    e = restitution if -closing > threshold else 0.0
    jn = -(1.0 + e) * closing
    tx = v[k, 0] - closing * nx
    ty = v[k, 1] - closing * ny
    tz = v[k, 2] - closing * nz
    slip = math.sqrt(tx * tx + ty * ty + tz * tz)
    scale = 0.0
    if slip > 1e-12:
        scale = min(friction * jn, slip) / slip
    v[k, 0] += jn * nx - scale * tx
    v[k, 1] += jn * ny - scale * ty
    v[k, 2] += jn * nz - scale * tz


@kernel
def _ball_poles(bodies, b, radius, poles, material, threshold):
    """Resolve ball ``b`` (of ``radius``) against every one of the :class:`~netgym.physics.model.contact_tables.Poles`."""
    x = bodies.x
    for p in range(poles.radius.shape[0]):
        ax, ay, az = poles.start[p, 0], poles.start[p, 1], poles.start[p, 2]
        ex, ey, ez = poles.end[p, 0] - ax, poles.end[p, 1] - ay, poles.end[p, 2] - az
        reach = radius + poles.radius[p]
        t = ((x[b, 0] - ax) * ex + (x[b, 1] - ay) * ey + (x[b, 2] - az) * ez) / (ex * ex + ey * ey + ez * ez)
        t = min(max(t, 0.0), 1.0)
        dx = x[b, 0] - (ax + t * ex)
        dy = x[b, 1] - (ay + t * ey)
        dz = x[b, 2] - (az + t * ez)
        dist2 = dx * dx + dy * dy + dz * dz
        if dist2 >= reach * reach:
            continue
        nx, ny, nz, dist = _direction(dx, dy, dz, dist2, ex, ey, ez)
        _static_response(bodies, b, Touch(nx, ny, nz, reach - dist), material, threshold, True)


@kernel
def _segment_extent(x, segments):
    """Largest extent of a segment along any axis (m); one running maximum per axis, three
    independent chains."""
    rx, ry, rz = 0.0, 0.0, 0.0
    for s in range(segments.shape[0]):
        i = segments[s, 0]
        j = segments[s, 1]
        rx = max(rx, abs(x[j, 0] - x[i, 0]))
        ry = max(ry, abs(x[j, 1] - x[i, 1]))
        rz = max(rz, abs(x[j, 2] - x[i, 2]))
    return max(rx, ry, rz)


@kernel
def _ball_net(bodies, b, model, extent, near):
    """Resolve ball ``b`` against every net particle, then every segment's interior, in index
    order (``model``: the :class:`~netgym.physics.model.model.KernelModel`). Returns how far that
    moved any body (a bound, m).

    Broad phase for the segments: a segment touches the ball's bounding cube only if its first
    particle lies within ``radius`` + its extent of the ball's centre along every axis. The
    particle pass lists (in ``near``) the particles within ``radius + extent + NEAR_MARGIN``
    (``extent``: a bound on every segment's extent when the ball's turn began), and only their
    segments (``segments`` sorted by first particle, those of particle k at ``segment_start[k]``
    on) are tested, in the order all of them would be. The list stays exact while this ball's
    contacts have moved no body farther than NEAR_MARGIN / 4 in all; beyond, every remaining
    segment is tested.
    """
    radius, material, threshold = model.ball_radius, model.materials.ball_net, model.restitution_threshold
    count, moved = _ball_particles(bodies, b, radius, model.n_net, material, threshold, extent, near)
    return _ball_segments(bodies, b, radius, model.segments, model.segment_start, material, threshold, near[:count],
                          moved)


@inline_kernel
def _ball_particles(bodies, b, radius, n_net, material, threshold, extent, near):
    """Resolve ball ``b`` (of ``radius``) against every net particle, in index order, and list
    in ``near`` the particles within ``radius + extent + NEAR_MARGIN`` of it (see
    :func:`_ball_net`). Returns (how many were listed, how far the contacts moved any body)."""
    x = bodies.x
    r2 = radius * radius
    listed = radius + extent + NEAR_MARGIN
    count = 0
    moved = 0.0
    for k in range(n_net):
        dx = x[k, 0] - x[b, 0]
        if abs(dx) >= listed:
            continue
        dy = x[k, 1] - x[b, 1]
        dz = x[k, 2] - x[b, 2]
        if abs(dy) < listed and abs(dz) < listed:
            near[count] = k
            count += 1
        if abs(dx) >= radius or abs(dy) >= radius:
            continue
        dist2 = dx * dx + dy * dy + dz * dz
        if dist2 >= r2:
            continue
        nx, ny, nz, dist = _direction(-dx, -dy, -dz, dist2, 0.0, 0.0, 0.0)  # out of the particle, towards the ball
        moved += _pair_response(bodies, b, k, k, 0.0, Touch(-nx, -ny, -nz, radius - dist), material, threshold)
    return count, moved


@inline_kernel
def _ball_segments(bodies, b, radius, segments, segment_start, material, threshold, near, moved):
    """Resolve ball ``b`` against the interior of the segments of the ``near`` particles, in
    segment order, while the contacts moved no body farther than NEAR_MARGIN / 4 in all
    (``moved`` so far), then against every remaining segment (see :func:`_ball_net`). Returns
    how far the ball's net contacts moved any body (a bound, m)."""
    x = bodies.x
    r2 = radius * radius
    from_list = 4.0 * moved <= NEAR_MARGIN  # else every segment, in order
    n, s, end = 0, 0, 0  # next listed particle; next segment; end of the listed particle's segments
    while True:
        if from_list:
            while s >= end and n < near.shape[0]:
                s, end = segment_start[near[n]], segment_start[near[n] + 1]
                n += 1
            if s >= end:
                break
        elif s >= segments.shape[0]:
            break
        i = segments[s, 0]
        j = segments[s, 1]
        s += 1
        cx, cy, cz = x[b, 0], x[b, 1], x[b, 2]
        if (min(x[i, 0], x[j, 0]) >= cx + radius or max(x[i, 0], x[j, 0]) <= cx - radius
                or min(x[i, 1], x[j, 1]) >= cy + radius or max(x[i, 1], x[j, 1]) <= cy - radius
                or min(x[i, 2], x[j, 2]) >= cz + radius or max(x[i, 2], x[j, 2]) <= cz - radius):
            continue
        ex = x[j, 0] - x[i, 0]
        ey = x[j, 1] - x[i, 1]
        ez = x[j, 2] - x[i, 2]
        len2 = ex * ex + ey * ey + ez * ez
        if len2 < COINCIDENT:
            continue
        t = ((cx - x[i, 0]) * ex + (cy - x[i, 1]) * ey + (cz - x[i, 2]) * ez) / len2
        if t <= 0.0 or t >= 1.0:
            continue  # end points are particles, handled above
        dx = x[i, 0] + t * ex - cx
        dy = x[i, 1] + t * ey - cy
        dz = x[i, 2] + t * ez - cz
        dist2 = dx * dx + dy * dy + dz * dz
        if dist2 >= r2:
            continue
        nx, ny, nz, dist = _direction(-dx, -dy, -dz, dist2, ex, ey, ez)  # out of the segment, towards the ball
        moved += _pair_response(bodies, b, i, j, t, Touch(-nx, -ny, -nz, radius - dist), material, threshold)
        from_list = from_list and 4.0 * moved <= NEAR_MARGIN  # the segments after this one, all of them
    return moved


@kernel
def resolve_ball_contacts(bodies, model, net_box, near):
    """Resolve the balls' contacts of :class:`Bodies` once, in a fixed order (deterministic
    Gauss-Seidel pass): ball/ball pairs first, then each ball's poles and net; :func:`resolve_ground`
    follows. A pair's projection pushes its balls along the line between them, partly along their
    supports; the supports' static friction, resolved after it, holds that push as it holds
    gravity's. (Resolved after the supports, the pushes escaped their friction and piles crept on
    for good.)

    ``net_box`` = (xmin, ymin, zmin, xmax, ymax, zmax) of the net particles: a ball whose
    sphere does not overlap it skips the particle and segment tests (broad phase); the others
    test only the segments near them (see :func:`_ball_net`; ``model``: the
    :class:`~netgym.physics.model.model.KernelModel`, ``near``: scratch for ``n_net`` particle indices).
    """
    x = bodies.x
    n_net, radius, threshold = model.n_net, model.ball_radius, model.restitution_threshold
    n = x.shape[0]
    reach = 2.0 * radius
    for b in range(n_net, n):
        for c in range(b + 1, n):
            dx = x[c, 0] - x[b, 0]
            dy = x[c, 1] - x[b, 1]
            dz = x[c, 2] - x[b, 2]
            dist2 = dx * dx + dy * dy + dz * dz
            if dist2 >= reach * reach:
                continue
            nx, ny, nz, dist = _direction(dx, dy, dz, dist2, 0.0, 0.0, 0.0)
            _pair_response(bodies, b, c, c, 0.0, Touch(nx, ny, nz, reach - dist), model.materials.ball_ball, threshold)
    extent = -1.0  # the segments' largest extent, measured when a ball first meets the net
    moved = 0.0  # how far the net contacts since may have moved a particle, which stretches a segment as much
    for b in range(n_net, n):
        extent, moved = _ball_poles_and_net(bodies, b, model, net_box, near, extent, moved)


@kernel
def resolve_lone_ball(bodies, b, model, net_box, near):
    """Resolve ball ``b``'s contacts with the poles and the net once, as :func:`resolve_ball_contacts`
    does, the other balls left out (a ball moving alone, clear of them)."""
    _ball_poles_and_net(bodies, b, model, net_box, near, -1.0, 0.0)


@inline_kernel
def _ball_poles_and_net(bodies, b, model, net_box, near, extent, moved):
    """Resolve ball ``b`` against the poles, then the net if it overlaps ``net_box``; returns
    (``extent``, ``moved``) carried on (see :func:`resolve_ball_contacts`: the segments' largest
    extent, measured when a ball first meets the net, or -1.0; how far the net contacts since may
    have moved a particle, which stretches a segment as much)."""
    x, radius = bodies.x, model.ball_radius
    _ball_poles(bodies, b, radius, model.poles, model.materials.ball_pole, model.restitution_threshold)
    if (x[b, 0] + radius > net_box[0] and x[b, 0] - radius < net_box[3]
            and x[b, 1] + radius > net_box[1] and x[b, 1] - radius < net_box[4]
            and x[b, 2] + radius > net_box[2] and x[b, 2] - radius < net_box[5]):
        if extent < 0.0:
            extent = _segment_extent(x, model.segments)
        moved += _ball_net(bodies, b, model, extent + 2.0 * moved, near)
    return extent, moved


@kernel
def resolve_ground(bodies, model):
    """Resolve every body's contact with the ground once, after :func:`resolve_ball_contacts` (a net
    without balls needs only this pass, so that its relaxation compiles without the balls'): a net
    particle's point, then each ball's sphere. The records are unpacked once, outside the loops:
    read per particle, they cost the net's step half its speed."""
    x, inv_mass, threshold = bodies.x, bodies.inv_mass, model.restitution_threshold
    n_net, materials = model.n_net, model.materials
    net_ground = materials.net_ground
    for k in range(n_net):
        if x[k, 2] < 0.0 and inv_mass[k] > 0.0:
            _static_response(bodies, k, Touch(0.0, 0.0, 1.0, 0.0 - x[k, 2]), net_ground, threshold, False)
    for k in range(n_net, x.shape[0]):
        resolve_ball_ground(bodies, k, model.ball_radius, materials.ball_ground, threshold)


@inline_kernel
def resolve_ball_ground(bodies, k, radius, material, threshold):
    """Resolve the contact of the ball in row ``k`` (of ``radius``) with the ground, of
    ``material`` and restitution ``threshold``."""
    if bodies.x[k, 2] < radius and bodies.inv_mass[k] > 0.0:
        _static_response(bodies, k, Touch(0.0, 0.0, 1.0, radius - bodies.x[k, 2]), material, threshold, True)
