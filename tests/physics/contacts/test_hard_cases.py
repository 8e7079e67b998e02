"""The seed's failures as tests: tunnelling, springs sinking into balls, sticking to poles,
blow-ups, piles of balls, stiff and badly damped nets."""

from __future__ import annotations

import numpy as np
import pytest

from netgym.errors import SimulationDivergedError, UnstableTimeStepError
from netgym.physics.simulator import Simulator


def _track(sim: Simulator, seconds: float, every: int = 1):
    """Step for ``seconds``; yield after every ``every`` steps."""
    for _ in range(round(seconds / sim.config.simulation.dt / every)):
        sim.step(every)
        yield


def _assert_enveloped(sim: Simulator, seconds: float, axis: int, sign: float) -> None:
    """While the ball is on the inner side of the opening, it never gets beyond the net along
    ``sign * axis``: the net wraps around it (a ball bounced back out of the mouth is free)."""
    n_net = sim.model.n_net
    opening = sim.opening
    for _ in _track(sim, seconds):
        centre = sim.state.x[n_net]
        assert np.all(np.isfinite(sim.state.x))
        if opening.sign * (centre[opening.axis] - opening.plane) < 0.0:
            assert sign * centre[axis] <= (sign * sim.state.x[:n_net, axis]).max()


@pytest.mark.parametrize("contact_model", ["impulse", "compliant"])
@pytest.mark.parametrize(("start", "velocity", "axis", "sign"), [
    ([0.0, 0.0, 2.0], [0.0, 0.0, -40.0], 2, -1.0),   # down into the bottom
    ([0.0, 0.0, 1.5], [40.0, 0.0, 0.0], 0, 1.0),     # into the +x wall
    ([0.2, -0.3, 1.5], [0.0, -40.0, 0.0], 1, -1.0),  # into the -y wall
])
def test_basket_40ms_from_inside_stays_inside(contact_model: str, start, velocity, axis, sign) -> None:
    """With either contact model (the compliant one's springs yield, but its segments' line
    penalty holds the ball as the projections do)."""
    basket = Simulator("basket", {"simulation.contact_model": contact_model})
    basket.launch_ball(start, velocity)
    _assert_enveloped(basket, 1.0, axis, sign)
    for _ in _track(basket, 2.0, every=100):
        pass
    p = basket.ball_positions[0]
    assert np.all(np.abs(p[:2]) < 1.0) and p[2] < 3.0
    assert basket.state.entered[0] == 1


@pytest.mark.parametrize(("start", "velocity", "axis", "sign"), [
    ([0.2, 0.0, 1.0], [40.0, 0.0, 0.0], 0, 1.0),     # into the back net
    ([0.5, 0.0, 1.0], [0.0, 0.0, 40.0], 2, 1.0),     # into the roof
    ([0.5, 0.5, 1.0], [0.0, 40.0, 0.0], 1, 1.0),     # into a side
])
def test_goal_40ms_from_inside_never_passes_through(goal: Simulator, start, velocity, axis, sign) -> None:
    goal.launch_ball(start, velocity)
    _assert_enveloped(goal, 1.0, axis, sign)


def test_goal_40ms_shot_into_the_back_net_stays_inside(goal: Simulator) -> None:
    goal.launch_ball([0.2, 0.0, 1.0], [40.0, 0.0, 0.0])
    _assert_enveloped(goal, 1.5, 0, 1.0)
    p = goal.ball_positions[0]
    assert 0.0 < p[0] < 1.0 and abs(p[1]) < 1.5 and p[2] < 2.0
    assert goal.state.entered[0] == 1


@pytest.mark.parametrize(("target", "name"), [
    ([1 / 9, 1 / 9], "particle"),
    ([0.0, 1 / 9], "spring midpoint"),
    ([0.0, 0.0], "cell centre"),
    ([0.85, 0.85], "net corner"),
])
def test_basket_ball_aimed_at_bottom_features(basket: Simulator, target, name) -> None:
    basket.launch_ball([target[0], target[1], 2.6], [0.0, 0.0, -25.0])
    _assert_enveloped(basket, 1.5, 2, -1.0)
    p = basket.ball_positions[0]
    assert np.all(np.abs(p[:2]) < 1.0), name
    assert p[2] > basket.model.ball_radius - 1e-9, name


@pytest.mark.parametrize(("target", "name"), [
    ([0.0, 1.0], "particle"),
    ([0.0625, 1.0], "spring midpoint"),
    ([0.0625, 1.0625], "cell centre"),
    ([1.5 - 0.1, 2.0 - 0.1], "net corner"),
])
def test_goal_ball_aimed_at_back_net_features(goal: Simulator, target, name) -> None:
    goal.launch_ball([0.15, target[0], target[1]], [25.0, 0.0, 0.0])
    _assert_enveloped(goal, 1.0, 0, 1.0)


_DIAGONAL = np.array([-1.0, -1.0, 0.0]) / np.sqrt(2)


@pytest.mark.parametrize(("scene", "start", "velocity", "pole"), [
    ("basket", np.array([1.0, 1.0, 2.0]) - 2.0 * _DIAGONAL, 25.0 * _DIAGONAL, 7),  # a corner pole
    ("basket", [0.0, 2.0, 3.0], [0.0, -25.0, 0.0], 1),                              # the rim
    ("goal", [-2.0, -1.5, 1.0], [25.0, 0.0, 0.0], 1),                               # a post
    ("goal", [-2.0, 0.3, 2.0], [25.0, 0.0, 0.0], 0),                                # the crossbar
], ids=["basket-corner-pole", "basket-rim", "goal-post", "goal-crossbar"])
def test_ball_bounces_off_poles_without_sinking_or_sticking(scene: str, start, velocity, pole: int) -> None:
    """Never closer than contact distance, leaves with about ``restitution`` times its approach
    speed, and does not stay stuck (the seed's problem 6)."""
    sim = Simulator(scene)
    poles = sim.model.poles
    a, b, pole_radius = poles.start[pole], poles.end[pole], poles.radius[pole]
    reach = sim.model.ball_radius + pole_radius

    def distance() -> float:
        c = sim.ball_positions[0]
        t = np.clip(np.dot(c - a, b - a) / np.dot(b - a, b - a), 0.0, 1.0)
        return float(np.linalg.norm(c - (a + t * (b - a))))

    sim.launch_ball(start, velocity)
    closest = np.inf
    for _ in _track(sim, 0.3):
        closest = min(closest, distance())
    assert reach - 1e-9 <= closest < reach + 0.05  # it hit, and never sank in
    assert distance() > reach + 0.5  # it left
    speed_in, speed_out = np.linalg.norm(velocity), np.linalg.norm(sim.state.v[sim.model.n_net])
    restitution = sim.model.contact[1, 0]
    assert 0.5 * restitution * speed_in < speed_out < 1.1 * speed_in


def test_seed_parameters_with_explicit_euler_at_1ms_raise_named_errors() -> None:
    seed = {"simulation.integrator": "explicit_euler", "simulation.dt": 0.001}
    with pytest.raises(UnstableTimeStepError, match=r"simulation\.dt = 0\.001 s is beyond the linear stability limit"):
        Simulator("basket", seed)
    sim = Simulator("basket", seed, check_stability=False)
    sim.launch_ball([0.0, 0.0, 3.5], [0.0, 0.0, -5.0])
    before = sim.state.copy()
    with pytest.raises(SimulationDivergedError, match="explicit_euler at dt = 0.001 s diverged"):
        sim.step(3000)
    assert np.array_equal(sim.state.x, before.x) and sim.state.time == before.time


def test_ten_balls_pile_up_in_the_basket(basket: Simulator) -> None:
    for k in range(10):
        basket.launch_ball([-0.5 + 0.33 * (k % 4), -0.4 + 0.4 * (k // 4), 3.6 + 0.7 * k], [0.0, 0.0, 0.0])
    for _ in _track(basket, 4.0, every=200):
        p = basket.ball_positions
        gaps = np.linalg.norm(p[:, None] - p[None], axis=2) + np.eye(10) * 9.0
        assert gaps.min() >= 2 * basket.model.ball_radius - 0.02
    p = basket.ball_positions
    assert np.all(np.abs(p[:, :2]) < 1.0) and np.all(p[:, 2] < 3.0)
    assert np.all(basket.state.entered == 1)
    assert basket.energy().kinetic < 0.05


def test_stiff_net_with_implicit_euler_at_10ms_stays_finite() -> None:
    stiff = {f"springs.{k}.ks": 150000.0 for k in ("structural", "shear", "bending")}
    sim = Simulator("basket", {**stiff, "simulation.integrator": "implicit_euler", "simulation.dt": 0.01})
    sim.launch_ball([0.0, 0.0, 3.5], [0.0, 0.0, -10.0])
    sim.step(300)
    assert np.all(np.isfinite(sim.state.x)) and np.all(np.isfinite(sim.state.v))
    assert 0.0 < sim.ball_positions[0, 2] < 3.0


@pytest.mark.slow
@pytest.mark.parametrize(("integrator", "dt"), [
    ("explicit_euler", 1e-3), ("symplectic_euler", 5e-4), ("rk4", 1e-3), ("implicit_euler", 1e-2),
    ("imex_euler", 5e-3)])
def test_low_ks_high_kd_runs_or_raises_the_named_error(integrator: str, dt: float) -> None:
    soft = {f"springs.{k}.ks": 50.0 for k in ("structural", "shear", "bending")}
    damped = {f"springs.{k}.kd": 200.0 for k in ("structural", "shear", "bending")}
    overrides = {**soft, **damped, "simulation.integrator": integrator, "simulation.dt": dt}
    try:
        sim = Simulator("basket", overrides, check_stability=False)
        sim.launch_ball([0.0, 0.0, 3.5], [0.0, 0.0, -10.0])
        sim.step(round(2.0 / dt))
    except SimulationDivergedError as error:
        assert integrator in str(error) and "dt" in str(error)
        assert np.all(np.isfinite(sim.state.x))
    else:
        assert np.all(np.isfinite(sim.state.x)) and np.all(np.isfinite(sim.state.v))
        assert integrator == "implicit_euler" or dt <= sim.stable_dt


def test_the_substep_count_is_the_closing_speed_rule_whatever_the_shortcut() -> None:
    """Substeps keep every ball within ``max_ball_travel`` radii of travel relative to the net
    particles that could reach it; when the fastest ball and the fastest particle together stay
    within one substep, that bound answers without the search for near particles. On random
    states, from slow to fast, the count is the rule's own."""
    import math

    from netgym.physics import stepping

    sim = Simulator("basket")
    m, rng = sim.model, np.random.default_rng(5)
    dt, travel = sim.dt, sim.config.simulation.max_ball_travel * m.ball_radius
    for scale in (0.01, 0.1, 1.0, 10.0, 40.0):
        for _ in range(20):
            x = np.vstack([sim.state.x, rng.uniform([-1.0, -1.0, 0.5], [1.0, 1.0, 3.0], (3, 3))])
            v = rng.normal(0.0, scale, x.shape)
            speeds = np.empty(m.n_net)
            rule = max(1, int(math.ceil(stepping._closing_speed(x, v, m.n_net, m.ball_radius, dt, speeds)
                                        * dt / travel)))
            assert stepping._substeps(x, v, m.n_net, m.ball_radius, dt, travel, speeds) == rule
