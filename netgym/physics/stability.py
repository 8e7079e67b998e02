"""Linear stability of the integrators on a net.

Linearised about a state, the free particles obey ``M a = -K dx - D dv``. The fastest mode
has ``omega^2 = lambda_max(M^-1/2 K M^-1/2)`` and damping rate
``c = lambda_max(M^-1/2 D M^-1/2)`` (for springs with one kd/ks ratio both belong to the same
mode). An explicit integrator is stable on the test system ``x'' = -omega^2 x - c x'`` when the
spectral radius of its one-step matrix is at most one; :func:`stable_dt` finds the largest
such ``dt`` by bisection.

IMEX Euler's dampers are a symmetric Gauss-Seidel sweep, not a force, so its limit is found on
the net itself. In mass-scaled coordinates its linearised step is ``v+ = G (v - h K x)``,
``x+ = x + h v+``, with ``G = keep F^T F``: ``F`` the forward pass of per-spring damper solves
(each a symmetric contraction), ``F^T`` the backward pass, ``keep = 1 / (1 + h drag)``. So ``G``
is symmetric with ``0 < G <= I``, and the step's eigenvalues ``lambda`` solve
``(lambda - 1) lambda G^-1 phi - (lambda - 1) phi + h^2 lambda K phi = 0``. On the unit circle
that needs ``lambda = -1`` (or an undamped mode, stable below the elastic limit), so the step
is stable while ``2 G^-1 + 2 I - h^2 K`` is positive definite, i.e. (congruence by ``F``) while
``lambda_max(h^2 F K F^T - 2 F F^T + 2 I) < 2 + 2 / keep``. Below the elastic limit
``h = 2 / omega`` this holds for any dampers; :func:`imex_limit` searches upward from there.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from netgym.physics.kernels import spring_law
from netgym.physics.kernels.integrators import damper_share, sweep_dampers
from netgym.physics.kernels.jit import kernel
from netgym.config import SceneConfig
from netgym.kinds import Integrator
from netgym.physics.model.model import Model
from netgym.physics.recent import Recent

IMEX_SEARCH_GROWTH = 1.5     # the IMEX limit is bracketed by steps growing by this factor ...
IMEX_SEARCH_HALVINGS = 8     # ... then bisected this often (to 0.2%)
IMEX_SEARCH_HORIZON = 1.0    # s; larger steps are not sought
IMEX_TOLERANCE = 1e-6        # relative change of the largest eigenvalue at which its power iterations stop


@dataclass(frozen=True)
class NetModes:
    """Highest angular frequency squared (rad^2/s^2) and highest damping rate (1/s)."""

    omega2: float
    damping: float
    imex_limit: float = float("inf")   # s, IMEX Euler's stability limit with its damper sweep

    @property
    def omega(self) -> float:
        """Highest angular frequency (rad/s)."""
        return float(np.sqrt(self.omega2))


def _scatter(n: int, springs: np.ndarray, pair_force: np.ndarray) -> np.ndarray:
    out = np.zeros((n, 3))
    for c in range(3):
        out[:, c] = (np.bincount(springs[:, 0], pair_force[:, c], n)
                     - np.bincount(springs[:, 1], pair_force[:, c], n))
    return out


@kernel
def _stretches(length, rest, out):
    """Each spring's :func:`~netgym.physics.kernels.spring_law.stretch` into ``out``."""
    for s in range(length.shape[0]):
        out[s] = spring_law.stretch(length[s], rest[s])


@kernel
def _stiffness_product(y, springs, axes, tension, ks, scale, out):
    """``out = M^-1/2 K M^-1/2 y``: each spring's stiffness ``ks`` along its axis, and
    ``ks * tension`` (its tension per unit length over ks) across it."""
    out[:] = 0.0
    for s in range(springs.shape[0]):
        i = springs[s, 0]
        j = springs[s, 1]
        dx = y[i, 0] * scale[i] - y[j, 0] * scale[j]
        dy = y[i, 1] * scale[i] - y[j, 1] * scale[j]
        dz = y[i, 2] * scale[i] - y[j, 2] * scale[j]
        ux, uy, uz = axes[s, 0], axes[s, 1], axes[s, 2]
        along = (1.0 - tension[s]) * (dx * ux + dy * uy + dz * uz)
        fx = ks[s] * (tension[s] * dx + along * ux)
        fy = ks[s] * (tension[s] * dy + along * uy)
        fz = ks[s] * (tension[s] * dz + along * uz)
        out[i, 0] += fx * scale[i]
        out[i, 1] += fy * scale[i]
        out[i, 2] += fz * scale[i]
        out[j, 0] -= fx * scale[j]
        out[j, 1] -= fy * scale[j]
        out[j, 2] -= fz * scale[j]


def _power_iteration(product, start: np.ndarray, iterations: int, above: float = math.inf,
                     tolerance: float = 0.0) -> tuple[float, np.ndarray]:
    """Largest eigenvalue of a symmetric positive semi-definite ``product`` and its vector, by at
    most ``iterations`` power iterations. Their Rayleigh quotients only grow towards it, so they
    stop once one reaches ``above`` (the eigenvalue is at least that) or changes by less than
    ``tolerance`` relative."""
    y, value = start, 0.0
    for _ in range(iterations):
        norm = np.linalg.norm(y)
        if norm == 0.0:
            return 0.0, y  # the operator is zero (for example no damping at all)
        y = y / norm
        z = product(y)
        value, last = float(np.sum(y * z)), value
        y = z
        if value >= above or abs(value - last) <= tolerance * value:
            break
    return value, y


def net_modes(positions: np.ndarray, inv_mass: np.ndarray, springs: np.ndarray, params: np.ndarray,
              drag: float = 0.0, iterations: int = 300) -> NetModes:
    """Estimate the fastest mode of the net linearised at ``positions`` by power iteration
    (air ``drag`` adds to every mode's damping rate), and IMEX Euler's limit there."""
    n = len(positions)
    d = positions[springs[:, 0]] - positions[springs[:, 1]]
    length = np.linalg.norm(d, axis=1)
    u = d / length[:, None]
    tension = np.empty(len(length))
    _stretches(length, params[:, 0], tension)
    ks, kd = params[:, 1], params[:, 2]
    scale = np.sqrt(inv_mass)
    free = inv_mass > 0.0

    def stiffness(y: np.ndarray) -> np.ndarray:
        out = np.empty_like(y)
        _stiffness_product(np.ascontiguousarray(y), springs, u, tension, ks, scale, out)
        return out

    def damping(y: np.ndarray) -> np.ndarray:
        ys = y * scale[:, None]
        along = np.sum((ys[springs[:, 0]] - ys[springs[:, 1]]) * u, axis=1)
        return _scatter(n, springs, (kd * along)[:, None] * u) * scale[:, None]

    rng = np.random.default_rng(0)
    omega2, _ = _power_iteration(stiffness, rng.standard_normal((n, 3)) * free[:, None], iterations)
    rate, _ = _power_iteration(damping, rng.standard_normal((n, 3)) * free[:, None], iterations)
    limit = imex_limit(stiffness, omega2, inv_mass, springs, u, kd, drag, rng.standard_normal((n, 3)) * free[:, None],
                       iterations)
    return NetModes(omega2=omega2, damping=rate + drag, imex_limit=limit)


def imex_limit(stiffness, omega2: float, inv_mass: np.ndarray, springs: np.ndarray, axes: np.ndarray,
               kd: np.ndarray, drag: float, start: np.ndarray, iterations: int) -> float:
    """Largest ``h`` at which IMEX Euler's linearised step is stable (module docstring):
    ``stiffness`` applies the mass-scaled K, ``axes`` are the springs' unit axes, ``start`` a
    starting vector for the power iterations (each warm-started from the last)."""
    if omega2 <= 0.0:
        return float("inf")
    scale = np.sqrt(inv_mass)[:, None]
    unscale = np.divide(1.0, scale, out=np.zeros_like(scale), where=scale > 0.0)
    w_i, w_j = inv_mass[springs[:, 0]], inv_mass[springs[:, 1]]
    coef = np.empty((len(springs), 5))
    coef[:, :3] = axes
    vector = [start]

    def stable(h: float) -> bool:
        share = damper_share(h, kd, w_i, w_j)
        coef[:, 3], coef[:, 4] = share * w_i, share * w_j

        def sweep(y: np.ndarray, forward: bool) -> np.ndarray:
            v = np.ascontiguousarray(y * scale)
            sweep_dampers(v, springs, coef, forward)
            return v * unscale

        def product(y: np.ndarray) -> np.ndarray:  # (h^2 F K F^T - 2 F F^T + 2 I) y
            back = sweep(y, False)
            return h * h * sweep(stiffness(back), True) - 2.0 * sweep(back, True) + 2.0 * y

        bound = 2.0 + 2.0 * (1.0 + h * drag)
        value, vector[0] = _power_iteration(product, vector[0], iterations, above=bound, tolerance=IMEX_TOLERANCE)
        return value < bound

    lo = 2.0 / np.sqrt(omega2)  # the elastic limit: stable whatever the dampers do
    while stable(lo * IMEX_SEARCH_GROWTH):
        lo *= IMEX_SEARCH_GROWTH
        if lo > IMEX_SEARCH_HORIZON:
            return lo
    hi = lo * IMEX_SEARCH_GROWTH
    for _ in range(IMEX_SEARCH_HALVINGS):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if stable(mid) else (lo, mid)
    return lo


def _step_matrix(integrator: int, dt: float, omega2: float, damping: float) -> np.ndarray:
    """One-step matrix of ``integrator`` on (x, v) for x'' = -omega2 x - damping x'."""
    a = np.array([[0.0, 1.0], [-omega2, -damping]])
    if integrator == Integrator.EXPLICIT_EULER:
        return np.eye(2) + dt * a
    if integrator == Integrator.RK4:
        h = dt * a
        return np.eye(2) + h + h @ h / 2 + h @ h @ h / 6 + h @ h @ h @ h / 24
    if integrator == Integrator.SYMPLECTIC_EULER:
        v_row = np.array([-dt * omega2, 1.0 - dt * damping])
        return np.array([[1.0 + dt * v_row[0], dt * v_row[1]], v_row])
    raise ValueError(f"integrator code {integrator} has no explicit step matrix")


def stable_dt(integrator: int, modes: NetModes) -> float:
    """Largest dt at which ``integrator`` is linearly stable on ``modes`` (inf for implicit Euler)."""
    if integrator == Integrator.IMPLICIT_EULER:
        return float("inf")
    if integrator == Integrator.IMEX_EULER:
        return modes.imex_limit

    def stable(dt: float) -> bool:
        return max(abs(np.linalg.eigvals(_step_matrix(integrator, dt, modes.omega2, modes.damping)))) <= 1.0 + 1e-12

    lo, hi = 0.0, 1.0
    while stable(hi):
        hi *= 2.0
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if stable(mid) else (lo, mid)
    return lo


CACHED_MODES = 64
"""Net modes kept per process (one per net, springs and inertia)."""
_MODES: Recent = Recent(CACHED_MODES)


def net_modes_of(model: Model, config: SceneConfig, inertia: float = 1.0) -> NetModes:
    """Fastest mode of ``model``'s net (of scene ``config``) linearised about its built shape,
    its inertia ``inertia`` times its mass (cached per net, springs and inertia)."""
    key = (config.net, config.springs, inertia)
    if key not in _MODES:
        _MODES[key] = net_modes(model.geometry.positions, model.net_inv_mass / inertia, model.springs,
                                model.spring_params, model.drag)
    return _MODES[key]
