"""Linear stability of the explicit integrators on a net.

Linearised about a state, the free particles obey ``M a = -K dx - D dv``. The fastest mode
has ``omega^2 = lambda_max(M^-1/2 K M^-1/2)`` and damping rate
``c = lambda_max(M^-1/2 D M^-1/2)`` (for springs with one kd/ks ratio both belong to the same
mode). An integrator is stable on the test system ``x'' = -omega^2 x - c x'`` when the
spectral radius of its one-step matrix is at most one; :func:`stable_dt` finds the largest
such ``dt`` by bisection. For IMEX Euler, whose implicit dampers do not limit dt, the estimate
is that of the elastic forces alone (c = 0).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from netgym.physics.kinds import Integrator


@dataclass(frozen=True)
class NetModes:
    """Highest angular frequency squared (rad^2/s^2) and highest damping rate (1/s)."""

    omega2: float
    damping: float

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


def _largest_eigenvalue(product, n: int, free: np.ndarray, iterations: int, rng: np.random.Generator) -> float:
    y = rng.standard_normal((n, 3)) * free[:, None]
    value = 0.0
    for _ in range(iterations):
        norm = np.linalg.norm(y)
        if norm == 0.0:
            return 0.0  # the operator is zero (for example no damping at all)
        y /= norm
        z = product(y)
        value = float(np.sum(y * z))
        y = z
    return value


def net_modes(positions: np.ndarray, inv_mass: np.ndarray, springs: np.ndarray, params: np.ndarray,
              drag: float = 0.0, iterations: int = 300) -> NetModes:
    """Estimate the fastest mode of the net linearised at ``positions`` by power iteration
    (air ``drag`` adds to every mode's damping rate)."""
    n = len(positions)
    d = positions[springs[:, 0]] - positions[springs[:, 1]]
    length = np.linalg.norm(d, axis=1)
    u = d / length[:, None]
    tension = np.maximum(1.0 - params[:, 0] / length, 0.0)
    ks, kd = params[:, 1], params[:, 2]
    scale = np.sqrt(inv_mass)
    free = inv_mass > 0.0

    def stiffness(y: np.ndarray) -> np.ndarray:
        ys = y * scale[:, None]
        diff = ys[springs[:, 0]] - ys[springs[:, 1]]
        along = np.sum(diff * u, axis=1)
        pair = ks[:, None] * (tension[:, None] * diff + ((1.0 - tension) * along)[:, None] * u)
        return _scatter(n, springs, pair) * scale[:, None]

    def damping(y: np.ndarray) -> np.ndarray:
        ys = y * scale[:, None]
        along = np.sum((ys[springs[:, 0]] - ys[springs[:, 1]]) * u, axis=1)
        return _scatter(n, springs, (kd * along)[:, None] * u) * scale[:, None]

    rng = np.random.default_rng(0)
    return NetModes(omega2=_largest_eigenvalue(stiffness, n, free, iterations, rng),
                    damping=_largest_eigenvalue(damping, n, free, iterations, rng) + drag)


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
    if integrator == Integrator.IMEX_EULER:
        # its dampers (a symmetric sweep of per-spring backward Euler solves) only remove energy;
        # the estimate is the elastic limit alone, that of undamped symplectic Euler
        return _step_matrix(Integrator.SYMPLECTIC_EULER, dt, omega2, 0.0)
    raise ValueError(f"integrator code {integrator} has no explicit step matrix")


def stable_dt(integrator: int, modes: NetModes) -> float:
    """Largest dt at which ``integrator`` is linearly stable on ``modes`` (inf for implicit Euler)."""
    if integrator == Integrator.IMPLICIT_EULER:
        return float("inf")

    def stable(dt: float) -> bool:
        return max(abs(np.linalg.eigvals(_step_matrix(integrator, dt, modes.omega2, modes.damping)))) <= 1.0 + 1e-12

    lo, hi = 0.0, 1.0
    while stable(hi):
        hi *= 2.0
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if stable(mid) else (lo, mid)
    return lo
