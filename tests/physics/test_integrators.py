"""The integrator kernels (``netgym/physics/kernels/integrators.py``) on a single undamped spring: a 1 kg
particle on a spring to a fixed anchor, along the spring's axis, is the harmonic oscillator
x(t) = L + A cos(w t), whose discretisations are known exactly: the order of each method's
error, the per-step energy factor of explicit and implicit Euler (1 + (w h)^2 and its inverse),
and the quantity symplectic Euler conserves."""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
import pytest

from netgym.physics.kernels import integrators
from netgym.physics.kernels.integrators import Scratch
from netgym.kinds import Integrator
from netgym.physics.model.model import Settings
from netgym.physics.kernels.springs import Springs

OMEGA = 2.0 * math.pi   # rad/s: a period of 1 s
REST = 1.0              # m, the spring's rest length
AMPLITUDE = 0.1         # m
SPRINGS = Springs.of([[1, 0]], [[REST, OMEGA ** 2, 0.0]], 2)  # the particle (row 1) on the anchor (row 0):
                                                               # rest length, ks (for 1 kg), no damper
INV_MASS = np.array([0.0, 1.0])

Step = Callable[[np.ndarray, np.ndarray, float, Scratch], None]


def euler(symplectic: bool) -> Step:
    return lambda x, v, h, s: integrators.step_euler(x, v, INV_MASS, 0.0, 0.0, SPRINGS, h, s.work, symplectic)


def rk4(x: np.ndarray, v: np.ndarray, h: float, s: Scratch) -> None:
    integrators.step_rk4(x, v, INV_MASS, 0.0, 0.0, SPRINGS, h, s.work)


def implicit_euler(x: np.ndarray, v: np.ndarray, h: float, s: Scratch) -> None:
    integrators.step_implicit_euler(x, v, INV_MASS, 0.0, 0.0, SPRINGS, h,
                                    Settings.make(Integrator.IMPLICIT_EULER, h, 0.25, 1e-14, 50, 1e3), s)


def imex_euler(x: np.ndarray, v: np.ndarray, h: float, s: Scratch) -> None:
    integrators.step_imex_euler(x, v, INV_MASS, 0.0, 0.0, SPRINGS, h, s)


METHODS = {"explicit_euler": euler(False), "symplectic_euler": euler(True), "rk4": rk4,
           "implicit_euler": implicit_euler, "imex_euler": imex_euler}


def released(amplitude: float = AMPLITUDE) -> tuple[np.ndarray, np.ndarray]:
    """The anchor at the origin and the particle stretched by ``amplitude``, at rest."""
    return np.array([[0.0, 0.0, 0.0], [REST + amplitude, 0.0, 0.0]]), np.zeros((2, 3))


def energy(x: np.ndarray, v: np.ndarray) -> float:
    """The oscillator's energy (J): kinetic plus the spring's."""
    return 0.5 * float(v[1] @ v[1]) + 0.5 * OMEGA ** 2 * (np.linalg.norm(x[1] - x[0]) - REST) ** 2


def error_after(step: Step, h: float, duration: float) -> float:
    """|x - x_exact| of the particle after ``duration`` in steps of ``h``."""
    x, v = released()
    scratch = Scratch.sized(2, 1)
    n = round(duration / h)
    for _ in range(n):
        step(x, v, h, scratch)
    assert not x[1, 1:].any() and not v[1, 1:].any()  # the motion stays on the spring's axis
    return abs(x[1, 0] - (REST + AMPLITUDE * math.cos(OMEGA * n * h)))


@pytest.mark.parametrize(("method", "order", "h"), [
    ("explicit_euler", 1, 1e-3), ("symplectic_euler", 1, 1e-3), ("implicit_euler", 1, 1e-3),
    ("imex_euler", 1, 1e-3), ("rk4", 4, 1e-2)])
def test_the_error_falls_with_the_step_at_the_methods_order(method: str, order: int, h: float) -> None:
    """Halving the step divides the error at t = 0.8 s by 2^order (observed order within 0.05)."""
    coarse, fine = error_after(METHODS[method], h, 0.8), error_after(METHODS[method], h / 2, 0.8)
    assert math.log2(coarse / fine) == pytest.approx(order, abs=0.05)


STATES = [(AMPLITUDE, 0.0), (0.0, 0.5), (-0.05, 0.3), (0.08, -0.2)]
"""(stretch m, speed m/s) of the particle: the states one step is taken from."""


def one_step(method: str, wh: float, stretch: float, speed: float) -> tuple[float, float]:
    """The energy before and after one step of ``method`` at w h = ``wh`` from this state."""
    x, v = released(stretch)
    v[1, 0] = speed
    before = energy(x, v)
    METHODS[method](x, v, wh / OMEGA, Scratch.sized(2, 1))
    return before, energy(x, v)


@pytest.mark.parametrize("wh", [0.01, 0.5, 3.0])
@pytest.mark.parametrize(("stretch", "speed"), STATES)
def test_explicit_euler_multiplies_the_energy_by_one_plus_wh_squared_every_step(wh: float, stretch: float,
                                                                              speed: float) -> None:
    """Explicit Euler grows the energy by 1 + (w h)^2 in every step, however small the step."""
    before, after = one_step("explicit_euler", wh, stretch, speed)
    assert after == pytest.approx(before * (1.0 + wh ** 2), rel=1e-12, abs=0.0)


@pytest.mark.parametrize("wh", [0.01, 10.0, 1000.0])
@pytest.mark.parametrize(("stretch", "speed"), STATES)
def test_implicit_euler_divides_the_energy_by_one_plus_wh_squared_at_any_step(wh: float, stretch: float,
                                                                             speed: float) -> None:
    """Unconditional damping: backward Euler on the linear spring shrinks the energy by
    1 / (1 + (w h)^2) in every step, far past any explicit method's stability limit (w h = 2).
    To 1e-9: the linear system's condition number is about (w h)^2, 1e6 at w h = 1000."""
    before, after = one_step("implicit_euler", wh, stretch, speed)
    assert after == pytest.approx(before / (1.0 + wh ** 2), rel=1e-9, abs=0.0)


def test_symplectic_euler_keeps_a_nearby_energy_exactly_and_never_drifts() -> None:
    """v += h a(x), then x += h v conserves H~ = E - (h w^2 / 2) q v exactly (q the stretch), so
    over 20 periods the energy never drifts: it stays within a factor 1 -+ w h / 2 of H~."""
    h = 1e-3
    x, v = released()
    scratch = Scratch.sized(2, 1)

    def shadow() -> float:
        return energy(x, v) - 0.5 * h * OMEGA ** 2 * (x[1, 0] - REST) * v[1, 0]

    conserved = shadow()
    for _ in range(20_000):
        METHODS["symplectic_euler"](x, v, h, scratch)
        assert conserved / (1 + OMEGA * h / 2) <= energy(x, v) <= conserved / (1 - OMEGA * h / 2)
    assert shadow() == pytest.approx(conserved, rel=1e-9)
