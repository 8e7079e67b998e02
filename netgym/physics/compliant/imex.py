"""IMEX Euler through contact: the contacts' springs explicitly, their dampers and friction
implicitly (each contact's normal and then tangential velocity solved by backward Euler, in
list order, at the positions of the step's start), then the net's smooth forces as
:func:`~netgym.physics.kernels.integrators.step_imex_euler`. A gripping contact's anchor is a
spring and damper solved together by backward Euler; where the impulse that would hold it
leaves Coulomb's cone it breaks away and slides, as RK4's contacts do where the anchor's force
leaves it (holding it on the cone instead, a return mapping, is exact Coulomb friction: another
model than RK4's, which IMEX Euler then did not converge to, its errors stalling at 7 mm).
Its anchor moves by the sliding the step's final velocities did. The balls' own weight comes
first, so that the contacts hold what it adds (after them, a gripping anchor would have to
stretch beyond the load it holds by the backward Euler's damper share). Grips change at the
step's start otherwise."""

from __future__ import annotations

import math

from netgym.physics.compliant import contacts as cl
from netgym.physics.compliant import forces, grip, law
from netgym.physics.compliant.system import Z0, ball_acceleration, freeze
from netgym.physics.kernels.integrators import step_imex_euler
from netgym.physics.kernels.jit import inline_kernel, kernel
from netgym.physics.kernels.rows import copy_rows


@inline_kernel
def _impulse(v, inv_mass, a, ft, jx, jy, jz):
    """Apply the impulse (jx, jy, jz) to ``a`` and its reaction to the point's bodies."""
    for k, share in ((a, 1.0), (ft.at.i, -ft.at.wi), (ft.at.j, -ft.at.wj)):
        if k >= 0:
            w = inv_mass[k] * share
            v[k, 0] += w * jx
            v[k, 1] += w * jy
            v[k, 2] += w * jz


@inline_kernel
def _held(v, inv_mass, a, ft, h, w_eff, terms, limit, anchor, sliding):
    """Hold a gripping contact by its anchor over ``h`` (backward Euler): its anchor's
    stiffness and damping ``terms`` (:func:`~netgym.physics.compliant.grip.anchor_terms`), its
    anchor displacement ``anchor`` (its row of the anchors), its sliding velocity ``sliding``
    (tx, ty, tz); returns False, changing nothing, where the impulse that would hold it leaves
    Coulomb's cone ``h * limit`` (``limit``: friction times the normal force)."""
    k_t, c_t = terms
    tx, ty, tz = sliding
    zx, zy, zz = grip.tangential(anchor[0], anchor[1], anchor[2], ft.nx, ft.ny, ft.nz)
    scale = 1.0 / (1.0 + h * w_eff * (c_t + h * k_t))
    jx = ((tx - h * w_eff * k_t * zx) * scale - tx) / w_eff
    jy = ((ty - h * w_eff * k_t * zy) * scale - ty) / w_eff
    jz = ((tz - h * w_eff * k_t * zz) * scale - tz) / w_eff
    if math.sqrt(jx * jx + jy * jy + jz * jz) > h * limit:
        return False
    _impulse(v, inv_mass, a, ft, jx, jy, jz)
    return True


@kernel
def _move_anchors(start, v, model, contacts, h, z):
    """Move each gripping contact's anchor (``z``) by the sliding its bodies did over ``h`` at
    their velocities ``v`` after the step (those that moved them), across its normal at the
    positions ``start``."""
    for c in range(contacts.count[0]):
        if contacts.grip[c] != grip.STICK:
            continue
        a = contacts.a[c]
        ft = cl.feature(start, model, contacts.kind[c], a, contacts.b[c])
        ux, uy, uz, closing = cl.approach(v, a, ft)
        zx, zy, zz = grip.tangential(z[c, 0], z[c, 1], z[c, 2], ft.nx, ft.ny, ft.nz)
        z[c, 0], z[c, 1], z[c, 2] = zx + h * (ux + closing * ft.nx), zy + h * (uy + closing * ft.ny), \
            zz + h * (uz + closing * ft.nz)


@kernel
def _contact_impulses(x, v, inv_mass, model, h, contacts, stiffness, damping, z):
    """IMEX Euler's contacts over ``h``, at the positions of its start, in list order: the
    spring and the damper of each along its normal together by backward Euler on its closing
    rate (no pull), then its friction: a gripping contact's anchor (``z``), unless holding it
    would leave Coulomb's cone (it breaks away: SLOW), or sliding friction by backward Euler on
    its sliding velocity."""
    for c in range(contacts.count[0]):
        kind, a = contacts.kind[c], contacts.a[c]
        ft = cl.feature(x, model, kind, a, contacts.b[c])
        if ft.delta <= 0.0 or ft.at.weight == 0.0:
            continue
        w_eff = forces.inverse_effective_mass(inv_mass, a, ft)
        hk = h * stiffness * ft.at.weight * ft.delta
        d = damping[kind]
        _, _, _, closing = cl.approach(v, a, ft)
        after = (closing - w_eff * hk) / (1.0 + w_eff * hk * d)
        push = max(0.0, hk * (1.0 + d * after))
        _impulse(v, inv_mass, a, ft, push * ft.nx, push * ft.ny, push * ft.nz)
        friction = cl.material(model, kind)[1]
        if not (friction > 0.0 and push > 0.0 and w_eff > 0.0):
            continue
        ux, uy, uz, closing = cl.approach(v, a, ft)
        tx, ty, tz = ux + closing * ft.nx, uy + closing * ft.ny, uz + closing * ft.nz
        if contacts.grip[c] == grip.STICK:
            terms = grip.anchor_terms(stiffness, ft.at.weight, w_eff)
            if _held(v, inv_mass, a, ft, h, w_eff, terms, friction * push / h, z[c], (tx, ty, tz)):
                continue
            contacts.grip[c] = grip.SLOW
            z[c, 0], z[c, 1], z[c, 2] = 0.0, 0.0, 0.0
        if contacts.grip[c] == grip.SLOW:
            z[c, 0] += h   # its clock
        factor = law.friction_factor(friction, push / h, math.sqrt(tx * tx + ty * ty + tz * tz))
        keep = 1.0 / (1.0 + h * factor * w_eff)
        scale = -(1.0 - keep) / w_eff
        _impulse(v, inv_mass, a, ft, scale * tx, scale * ty, scale * tz)


@kernel
def imex(x, v, inv_mass, model, net_gravity, h, work, stiffness, scratch):
    """IMEX Euler over ``h`` (see the module), the grips frozen at its start and the anchors
    in ``work.anchor[Z0]``; the balls' own weight and air explicitly, before the contacts (which
    then hold what they add)."""
    rows = work.rows
    f, start = rows[0], rows[1]
    contacts, n_net, z = work.contacts, model.n_net, work.anchor[Z0]
    freeze(x, v, inv_mass, model, work, stiffness, z, False)
    copy_rows(start, x)
    f[:] = 0.0
    for c in range(contacts.count[0]):
        ft = cl.feature(x, model, contacts.kind[c], contacts.a[c], contacts.b[c])
        if ft.delta > 0.0 and ft.at.slope != 0.0:
            cl.segment_slope_force(f, x, contacts.a[c], ft, stiffness)
    for k in range(x.shape[0]):
        for c in range(3):
            v[k, c] += h * inv_mass[k] * f[k, c]
    for k in range(n_net, x.shape[0]):
        ax, ay, az = ball_acceleration(v, k, model)
        v[k, 0], v[k, 1], v[k, 2] = v[k, 0] + h * ax, v[k, 1] + h * ay, v[k, 2] + h * az
    _contact_impulses(x, v, inv_mass, model, h, contacts, stiffness, work.damping, z)
    balls = rows[2][n_net:]
    copy_rows(balls, v[n_net:])
    step_imex_euler(x, v, inv_mass, net_gravity, model.drag, model.springs, h, scratch)
    for k in range(n_net, x.shape[0]):
        for c in range(3):
            v[k, c] = balls[k - n_net, c]
            x[k, c] = start[k, c] + h * v[k, c]
    _move_anchors(start, v, model, contacts, h, z)
