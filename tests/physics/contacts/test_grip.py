"""Static friction of compliant contacts (:mod:`netgym.physics.compliant.grip`): a resting ball
holds on the settled net and within Coulomb's cone, a sliding one stops where Coulomb says and
stays, RK4 keeps its order through the moment it grips, and grips persist between calls,
checkpoints and launches."""

from __future__ import annotations

import math

import numpy as np
import pytest

from netgym.bench.accuracy.contact_convergence import fitted_slope
from netgym.physics.compliant import grip, law
from netgym.physics.simulator import Simulator

COMPLIANT = {"simulation.contact_model": "compliant"}
SMALL_NET = {**COMPLIANT, "simulation.integrator": "rk4", "simulation.dt": 1e-3, "net.particles": [3, 3, 3]}
SPEED, FRICTION, GRAVITY = 1.0, 0.3, 9.81   # the slide: its launch speed, the ground's friction


@pytest.fixture(scope="module")
def small_net() -> Simulator:
    return Simulator("basket", SMALL_NET)


def _slide_path(sim: Simulator, integrator: str, dt: float, seconds: float = 0.5) -> np.ndarray:
    """The ball's position every 10 ms of ``seconds`` after it is set sliding along the ground
    at SPEED, far from the net, pressed into it as far as its weight presses it."""
    sim.reset()
    sim.launch_ball([5.0, 5.0, sim.model.ball_radius], [SPEED, 0.0, 0.0])
    sim.state.x[-1, 2] -= sim.model.ball_mass * GRAVITY / sim.config.simulation.contact_stiffness
    path = []
    for _ in range(round(seconds / 0.01)):
        sim.step(round(0.01 / dt), integrator, dt)
        path.append(sim.ball_positions[0].copy())
    return np.array(path)


@pytest.mark.parametrize(("integrator", "dt"), [("imex_euler", 2e-3), ("rk4", 1e-3), ("symplectic_euler", 5e-4)])
def test_a_ball_settled_on_the_basket_bottom_stays_put(integrator: str, dt: float) -> None:
    """Regularised friction alone let it creep 3.0 mm in these 2 s (RK4, symplectic Euler)."""
    sim = Simulator("basket", {**COMPLIANT, "simulation.integrator": integrator, "simulation.dt": dt})
    sim.launch_ball([0.3, 0.2, 1.5], [0.0, 0.0, 0.0])  # off centre: on the sloped part of the bottom
    sim.step(round(3.0 / dt))  # dropped, bounced and settled
    settled = sim.ball_positions[0]
    sim.step(round(2.0 / dt))
    assert np.linalg.norm(sim.ball_positions[0] - settled) < 1e-3


def _stop_distance(sim: Simulator) -> float:
    """Where the model stops the slide: sliding friction ``mu m g u / sqrt(u^2 + eps^2)`` from
    SPEED down to the speed at which it grips, ``int sqrt(u^2 + eps^2) du / (mu g)``, where its
    anchor holds it: Coulomb's ``v^2 / (2 mu g)`` = 0.1699 m and 0.8 mm. It grips where its
    anchor's damper ``c_t = 2 sqrt(k_t m)`` alone fits in the cone, below the grip speed."""
    eps, mass = law.SLIP_SPEED, sim.model.ball_mass
    damper = 2.0 * grip.STICK_DAMPING * math.sqrt(grip.STICK_SHARE * sim.config.simulation.contact_stiffness * mass)
    grips = min(grip.STICK_SPEED, FRICTION * mass * GRAVITY / damper)

    def area(u: float) -> float:
        return 0.5 * (u * math.hypot(u, eps) + eps * eps * math.asinh(u / eps))

    return (area(SPEED) - area(grips)) / (FRICTION * GRAVITY)


@pytest.mark.parametrize(("integrator", "dt", "tolerance"), [("rk4", 1e-3, 1e-4), ("imex_euler", 2e-3, 1e-2)])
def test_a_sliding_ball_stops_where_the_law_says_and_stays(small_net: Simulator, integrator: str, dt: float,
                                                            tolerance: float) -> None:
    path = _slide_path(small_net, integrator, dt, seconds=1.0)
    assert path[-1, 0] - 5.0 == pytest.approx(_stop_distance(small_net), rel=tolerance)
    assert np.abs(path[-1] - path[59]).max() < 1e-6   # still from 0.6 s on


def test_rk4_converges_at_fourth_order_through_a_slide_that_grips(small_net: Simulator) -> None:
    """The moment the slide slows below the grip speed is located inside RK4's step like a
    contact's onset: errors against RK4 at a 16th of the finest step fall with every halving
    at slope >= 3.5 (2.3e-9, 1.3e-10, 7.7e-12 m: 4.15; the grip changed at the next step's
    start instead: 2.0e-5, 8.5e-6, 2.4e-6 m, 1.5). Steps divide the 10 ms between samples."""
    reference = _slide_path(small_net, "rk4", 5e-4 / 16)
    dts = [2e-3, 1e-3, 5e-4]
    errors = [np.abs(_slide_path(small_net, "rk4", dt) - reference).max() for dt in dts]
    assert errors[0] > 1e-9
    self_difference = np.abs(reference - _slide_path(small_net, "rk4", 5e-4 / 32)).max()
    assert self_difference < 0.1 * errors[-1]
    assert all(fine < coarse for coarse, fine in zip(errors, errors[1:])), errors
    assert fitted_slope(dts, errors) >= 3.5, errors


def test_grips_persist_between_calls_and_checkpoints() -> None:
    """A resting ball stepped in one call or in a hundred lands bitwise on the same state (the
    anchors live in the state, not in a call's scratch), and a restored checkpoint goes on as
    the original did."""
    runs = []
    for calls in (1, 100):
        sim = Simulator("basket", COMPLIANT)
        sim.launch_ball([0.3, 0.2, 0.9], [0.0, 0.0, 0.0])
        sim.step(1500)   # settled: its contacts grip
        for _ in range(calls):
            sim.step(200 // calls)
        runs.append(sim)
    assert np.array_equal(runs[0].state.x, runs[1].state.x)
    assert (runs[0].state.anchors[:, 3] == grip.STICK).any()
    sim = runs[0]
    saved = sim.checkpoint()
    sim.step(100)
    onwards = sim.state.x.copy()
    sim.restore(saved)
    sim.step(100)
    assert np.array_equal(sim.state.x, onwards)


def test_a_launch_and_a_removal_keep_the_other_balls_grips() -> None:
    sim = Simulator("basket", COMPLIANT)
    sim.launch_ball([0.3, 0.2, 0.9], [0.0, 0.0, 0.0])
    sim.step(1500)
    held = sim.state.anchors[sim.state.anchors[:, 3] == grip.STICK].copy()
    assert len(held)
    sim.launch_ball([2.0, 2.0, 4.0], [0.0, 0.0, 0.0])
    sim.launch_ball([-2.0, 2.0, 4.0], [0.0, 0.0, 0.0])
    sim.remove_ball(1)
    assert np.array_equal(sim.state.anchors[sim.state.anchors[:, 3] == grip.STICK], held)
    sim.remove_ball(0)
    assert not (sim.state.anchors[:, 3] == grip.STICK).any()
