"""The compliant contact model: its integrators converge at their orders through contact (RK4
only because contact events are located inside its steps), its law returns the configured
restitution and keeps the energy of an elastic bounce, and the scene and env refuse what it
cannot do."""

from __future__ import annotations

import math

import gymnasium as gym
import numpy as np
import pytest

import netgym  # noqa: F401  (registers the ids)
from netgym.bench.accuracy.contact_convergence import fitted_slope
from netgym.errors import ConfigError, InvalidArgumentError
from netgym.bench.throws import sample_throws
from netgym.bench.accuracy.fast_path import throw_each
from netgym.bench.accuracy.model_agreement import COMPLIANT
from netgym.physics.compliant import contacts as compliant_contacts
from netgym.physics.compliant import law
from netgym.physics.fast_path import reach
from netgym.physics.simulator import Simulator
from netgym.physics.throw import throw

SMALL_NET = {"simulation.contact_model": "compliant", "simulation.integrator": "rk4", "simulation.dt": 1e-3,
             "net.particles": [3, 3, 3]}
BOUNCE = ([5.0, 5.0, 1.0], [1.0, 0.5, -3.0])     # onto the ground, sliding: friction acts
STRIKE = ([0.1, 0.2, 2.4], [0.5, 0.0, -6.0])     # into the small net's bottom: particles and segments
AGREEMENT_THROWS = 24


def _ball_path(sim: Simulator, launch: tuple, integrator: str, dt: float, seconds: float = 0.4) -> np.ndarray:
    """The ball's position every 10 ms of ``seconds`` from ``launch`` in the settled scene."""
    sim.reset()
    sim.launch_ball(*launch)
    path = []
    for _ in range(round(seconds / 0.01)):
        sim.step(round(0.01 / dt), integrator, dt)
        path.append(sim.ball_positions[0].copy())
    return np.array(path)


@pytest.fixture(scope="module")
def small_net() -> Simulator:
    return Simulator("basket", SMALL_NET)


BOUNCE_STEPS, STRIKE_STEPS = [5e-4, 2.5e-4, 1.25e-4], [1e-3, 5e-4, 2.5e-4, 1.25e-4]   # they divide 10 ms


@pytest.mark.parametrize(("launch", "dts"), [(BOUNCE, BOUNCE_STEPS), (STRIKE, STRIKE_STEPS)],
                         ids=["ground bounce", "net strike"])
def test_rk4_converges_at_fourth_order_through_contact(small_net: Simulator, launch: tuple, dts: list[float]) -> None:
    """Errors against RK4 at a 16th of the finest step fall with every halving, by at least
    2 orders' worth and by 3.5 at the finest (impulses, or contacts whose onsets, separations or
    grips a step did not locate, give about 1-2). The bounce: 3.6e-8, 6.7e-9, 4.4e-10 m (2.4,
    3.9); the strike 1.7e-6 .. 3.0e-10 m (4.2, 4.1, 4.1). Steps divide the 10 ms between
    samples; finer ones would meet the rounding of some 1e5 steps (about 5e-11 m)."""
    reference = _ball_path(small_net, launch, "rk4", dts[-1] / 16)
    errors = [np.abs(_ball_path(small_net, launch, "rk4", dt) - reference).max() for dt in dts]
    assert errors[0] > 1e-8  # the ball met something: there was an error to converge
    self_difference = np.abs(reference - _ball_path(small_net, launch, "rk4", dts[-1] / 32)).max()
    assert self_difference < 0.1 * errors[-1]  # the reference converged
    gains = [math.log2(coarse / fine) for coarse, fine in zip(errors, errors[1:])]
    assert min(gains) >= 2.0 and gains[-1] >= 3.5, errors


def test_rk4_locates_a_pole_contact_crossing_from_its_cap_to_its_side(small_net: Simulator) -> None:
    """A ball thrown up against the bottom end of a corner pole: the closest point of the pole's
    axis moves from its start cap onto its side while they touch, where the distance is only
    once differentiable. With the region frozen and the crossing located every halving gains
    at least 3 (not located: 5.6e-7, 5.2e-9, 2.5e-9 m, the last halving 1.1)."""
    launch = ([-1.45, -1.0, 0.31], [2.0, 0.0, 3.0])
    pole = small_net.kernel_model.poles
    axis = pole.end[4] - pole.start[4]
    reference = _ball_path(small_net, launch, "rk4", 1e-4 / 16, seconds=0.2)
    sides = (reference - pole.start[4]) @ axis / (axis @ axis)
    assert sides.min() < 0.0 < sides.max()  # its centre passes the end's height (touching, t -0.010 .. 0.004)
    dts = [4e-4, 2e-4, 1e-4]
    errors = [np.abs(_ball_path(small_net, launch, "rk4", dt, seconds=0.2) - reference).max() for dt in dts]
    self_difference = np.abs(reference - _ball_path(small_net, launch, "rk4", 1e-4 / 32, seconds=0.2)).max()
    assert self_difference < 0.1 * errors[-1]
    assert all(np.log2(coarse / fine) >= 3.0 for coarse, fine in zip(errors, errors[1:])), errors


@pytest.mark.parametrize("integrator", ["explicit_euler", "symplectic_euler", "imex_euler"])
def test_euler_methods_converge_at_first_order_through_contact(small_net: Simulator, integrator: str) -> None:
    reference = _ball_path(small_net, STRIKE, "rk4", 5e-5 / 8)
    dts = [2e-4, 1e-4, 5e-5]
    errors = [np.abs(_ball_path(small_net, STRIKE, integrator, dt) - reference).max() for dt in dts]
    assert all(fine < coarse for coarse, fine in zip(errors, errors[1:])), errors
    assert fitted_slope(dts, errors) >= 0.9, errors


def _bounce_speed(restitution: float, speed: float, friction: float = 0.0, gravity: float = 0.0) -> tuple[float, float]:
    """(rebound speed, total energy before and after: their difference) of a ball sent straight
    down onto the ground at ``speed`` (RK4 at 10 us)."""
    sim = Simulator("basket", {**SMALL_NET, "contact.ball_ground.restitution": restitution,
                               "contact.ball_ground.friction": friction, "simulation.gravity": gravity})
    radius, mass = sim.model.ball_radius, sim.model.ball_mass
    sim.launch_ball([5.0, 5.0, radius + 0.05], [0.0, 0.0, -speed])

    def energy() -> float:
        z, w = sim.ball_positions[0][2], sim.state.v[-1, 2]
        return 0.5 * mass * w * w - mass * gravity * z

    before = energy()
    sim.step(round(0.2 / 1e-5), "rk4", 1e-5)
    assert sim.ball_positions[0][2] > radius  # off the ground again
    return float(sim.state.v[-1, 2]), energy() - before


def test_a_contact_returns_its_restitution_at_the_reference_speed() -> None:
    rebound, _ = _bounce_speed(0.5, law.REFERENCE_SPEED)
    assert rebound == pytest.approx(0.5 * law.REFERENCE_SPEED, rel=1e-8)


def test_slower_approaches_bounce_more_as_hunt_crossley_says() -> None:
    """Restitution 1 - O(d v): the return ratio rises towards 1 as the approach slows."""
    ratios = [_bounce_speed(0.5, speed)[0] / speed for speed in (10.0, 5.0, 1.0)]
    assert ratios[0] < ratios[1] < ratios[2] < 1.0


def test_an_elastic_contact_keeps_the_energy_of_a_bounce_under_gravity() -> None:
    rebound, change = _bounce_speed(1.0, 4.0, gravity=-9.81)
    assert abs(change) < 1e-9
    assert rebound > 0.0


def test_dissipation_solves_the_restitution_relation() -> None:
    for e in (0.1, 0.5, 0.9):
        y = law.dissipation(e, 1.0)
        assert y - math.log1p(y) + e * y + math.log1p(-e * y) == pytest.approx(0.0, abs=1e-12)
    assert law.dissipation(1.0, 5.0) == 0.0


def test_a_compliant_full_simulation_catches_a_ball_dropped_into_the_basket() -> None:
    sim = Simulator("basket", {"simulation.contact_model": "compliant"})
    result = throw(sim, [0.2, 0.1, 3.6], [0.0, 0.0, -2.0], fast=False)
    assert result.captured
    assert 0.3 < result.final_position[2] < 1.0   # on the bottom, not through it


def test_the_scene_refuses_an_unknown_contact_model_and_implicit_euler_with_the_compliant_one() -> None:
    with pytest.raises(ConfigError, match="simulation.contact_model"):
        Simulator("basket", {"simulation.contact_model": "soft"})
    with pytest.raises(ConfigError, match="implicit_euler"):
        Simulator("basket", {"simulation.contact_model": "compliant", "simulation.integrator": "implicit_euler"})


def test_the_energy_bound_counts_what_the_contact_springs_hold() -> None:
    """A ball at rest pressed 6 cm into the ground holds k delta^2 / 2 = 36 J in its contact
    spring, enough to rise past the basket's rim (3 m): the compliant bound must not call the
    opening out of its reach; without the springs' energy (the impulse budget) it would."""
    sim = Simulator("basket", {"simulation.contact_model": "compliant"})
    sim.launch_ball([3.0, 0.0, 0.3], [0.0, 0.0, 0.0])
    s, km, row = sim.state, sim.kernel_model, sim.model.n_net
    s.x[row, 2] -= 0.06   # pressed in (a launch below the ground is refused)
    reference = reach.potential_without_ball(s.x, s.v, s.inv_mass, row, km.gravity, km.springs.pairs,
                                             km.springs.params)
    found = {}
    for stiffness in (sim.config.simulation.contact_stiffness, 0.0):
        budget = reach.Budget(reference, 0.0, km.gravity, sim.model.ball_radius, sim.opening.lowest_z, stiffness)
        found[stiffness] = reach.out_of_reach(s.x, s.v, s.inv_mass, row, km, budget, 5.0,
                                              compliant_contacts.new_list(s.x, km))
    assert found == {sim.config.simulation.contact_stiffness: False, 0.0: True}


def test_the_env_takes_the_compliant_model_on_its_fast_path() -> None:
    env = gym.make("NetCatch-v0", contact_model="compliant", balls_per_episode=1)
    env.reset(seed=0)
    _, _, terminated, _, info = env.step(env.action_space.sample())
    assert terminated and "captured" in info


@pytest.mark.slow
def test_the_compliant_fast_path_agrees_with_its_full_simulation() -> None:
    """Sampled basket throws (half random, half noisy aimed: rim and wall hits), each from
    the settled empty net, by the fast path and by full simulation, both compliant."""
    throws = sample_throws("basket", AGREEMENT_THROWS, seed=3)
    fast, full = (throw_each("basket", throws, 1, COMPLIANT, fast) for fast in (True, False))
    assert 0 < sum(r.captured for r in full) < len(throws)
    assert [r.captured for r in fast] == [r.captured for r in full]


def test_the_parts_a_stiff_contact_takes_are_booked_as_substeps() -> None:
    """IMEX Euler at 2 ms splits a step while a ball touches the net only where the contact
    springs' frequency bound asks for it: not at the default stiffness (h omega <= 1.5 for a
    ball resting on the bottom), into parts at ten times it; the counters say so."""
    counts = []
    for overrides in ({}, {"simulation.contact_model": "compliant"},
                      {"simulation.contact_model": "compliant", "simulation.contact_stiffness": 2e5}):
        sim = Simulator("basket", overrides)
        sim.launch_ball([0.3, 0.2, 0.9], [0.0, 0.0, 0.0])   # resting on the bottom within a few steps
        sim.step(200)
        before = sim.substeps
        sim.step(100)
        counts.append(sim.substeps - before)
    assert counts[0] == 100 and counts[1] == 100 and counts[2] >= 200
