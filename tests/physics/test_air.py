"""Air on balls: quadratic drag towards the wind, in the fast path's flight (netgym.physics.kernels.air)
and in the kernels, against analytic solutions, limits, symmetry and the full simulation."""

from __future__ import annotations

import math

import numpy as np
import pytest

from netgym.bench.accuracy.fast_path import compare, summarise
from netgym.bench.throws import sample_throws
from netgym.config import ConfigError, load_scene
from netgym.physics.kernels import air
from netgym.physics.fast_path import flight
from netgym.physics.model.model import ball_drag_constant
from netgym.physics.fast_path.flight import Ground
from netgym.physics.simulator import Simulator
from netgym.physics.throw import FreeFlight

GROUND = dict(radius=0.3, restitution=0.5, friction=0.3, threshold=0.2)
CALM = np.zeros(3)


def _fly(p, v, tau, gravity=-9.81, k=0.05, wind=CALM, step=air.MAX_FLIGHT_STEP):
    p, v = np.array(p, dtype=float), np.array(v, dtype=float)
    air.fly(p, v, tau, k, np.asarray(wind, dtype=float), flight.Ground(gravity=gravity, **GROUND), step)
    return p, v


def test_drag_constant_is_half_rho_cd_area_over_mass() -> None:
    scene = load_scene("basket").replace({"air.density": 1.2, "air.drag_coefficient": 0.5})
    assert ball_drag_constant(scene) == pytest.approx(0.5 * 1.2 * 0.5 * math.pi * 0.3 ** 2 / 1.0)
    assert ball_drag_constant(load_scene("basket")) == 0.0  # no air by default: NetCatch-v0 unchanged


def test_horizontal_flight_without_gravity_matches_the_analytic_solution() -> None:
    """v' = -k v^2: v(t) = v0 / (1 + k v0 t), x(t) = ln(1 + k v0 t) / k."""
    k, v0, t = 0.05, 12.0, 2.0
    p, v = _fly([0.0, 0.0, 100.0], [v0, 0.0, 0.0], t, gravity=0.0, k=k)
    assert p[0] == pytest.approx(math.log1p(k * v0 * t) / k, rel=1e-10)
    assert v[0] == pytest.approx(v0 / (1.0 + k * v0 * t), rel=1e-10)


def test_a_long_fall_reaches_the_terminal_speed() -> None:
    k = 0.05
    _, v = _fly([0.0, 0.0, 1e4], [0.0, 0.0, 0.0], 30.0, k=k)
    assert -v[2] == pytest.approx(math.sqrt(9.81 / k), rel=1e-9)


def test_fourth_order_convergence() -> None:
    start = ([0.0, 0.0, 50.0], [8.0, 1.0, 6.0])
    reference, _ = _fly(*start, 2.0, wind=[2.0, -1.0, 0.0], step=1e-4)
    errors = [np.linalg.norm(_fly(*start, 2.0, wind=[2.0, -1.0, 0.0], step=h)[0] - reference) for h in (0.08, 0.04, 0.02)]
    orders = [math.log2(a / b) for a, b in zip(errors, errors[1:])]
    assert all(3.7 < q < 4.3 for q in orders), orders


def test_without_drag_the_flight_is_the_parabola_with_its_bounces() -> None:
    ground = flight.Ground(gravity=-9.81, **GROUND)
    for v0 in ([6.0, 2.0, 7.0], [3.0, 0.0, -2.0]):
        want_p, want_v = flight.advance(np.array([0.0, 0.0, 2.0]), np.array(v0), 1.5, ground)
        got_p, got_v = _fly([0.0, 0.0, 2.0], v0, 1.5, k=0.0)
        assert np.allclose(got_p, want_p, atol=1e-9) and np.allclose(got_v, want_v, atol=1e-9)


def test_mirrored_wind_gives_the_mirrored_flight() -> None:
    left, _ = _fly([0.0, 0.0, 2.0], [7.0, 0.0, 6.0], 2.5, wind=[1.0, 3.0, 0.0])
    right, _ = _fly([0.0, 0.0, 2.0], [7.0, 0.0, 6.0], 2.5, wind=[1.0, -3.0, 0.0])
    assert left[1] > 0.5 and np.allclose(right, left * [1.0, -1.0, 1.0], atol=1e-12)


def test_friction_holds_a_ball_against_a_breeze_but_not_a_gale() -> None:
    k, grip = 0.05, 0.3 * 9.81
    breeze = np.array([math.sqrt(grip / k) * 0.9, 0.0, 0.0])   # drag 0.81 of friction
    gale = breeze / 0.9 * 1.2
    rest = ([5.0, 0.0, 0.3], [0.0, 0.0, 0.0])
    assert air.held_by_friction(np.zeros(3), -9.81, k, breeze, 0.3, 0.3, np.array(rest[0]))
    assert not air.held_by_friction(np.zeros(3), -9.81, k, gale, 0.3, 0.3, np.array(rest[0]))
    assert np.array_equal(_fly(*rest, 1.0, k=k, wind=breeze)[0], rest[0])
    pushed, _ = _fly(*rest, 1.0, k=k, wind=gale)
    assert pushed[0] > 5.0 + 0.1 and pushed[2] == 0.3


def test_kernel_free_flight_through_air_matches_the_fine_flight() -> None:
    """In the full simulation a ball far from the net flies by one RK4 step per substep."""
    sim = Simulator("basket", {"air.density": 1.2, "air.wind": [2.0, -3.0, 0.0]})
    m = sim.model
    sim.launch_ball([-30.0, 0.0, 20.0], [-3.0, 1.0, 4.0])
    sim.step(250)  # 0.5 s at 2 ms
    want, _ = _fly([-30.0, 0.0, 20.0], [-3.0, 1.0, 4.0], 0.5, k=m.ball_drag, wind=m.wind, step=1e-4)
    assert np.linalg.norm(sim.ball_positions[0] - want) < 1e-7


@pytest.mark.slow
@pytest.mark.parametrize("wind", [[0.0, 0.0, 0.0], [3.0, -2.0, 0.0]])
def test_fast_path_through_air_agrees_with_full_simulation(wind: list[float]) -> None:
    """The fast path's RK4 flight, its decisions (no energy bound when the wind can feed the
    ball) and the full simulation give the same outcome on every one of 40 seeded throws."""
    outcomes = compare("basket", sample_throws("basket", 40, seed=3), 1, {"air.density": 1.2, "air.wind": wind})
    assert summarise(outcomes)["agreement"] == 1.0
    assert 0 < sum(o.fast_captured for o in outcomes) < len(outcomes)


def test_bad_air_is_refused() -> None:
    with pytest.raises(ConfigError, match="air.density"):
        load_scene("basket").replace({"air.density": -1.0})
    with pytest.raises(ConfigError, match="air.wind"):
        load_scene("basket").replace({"air.wind": [1.0, 2.0]})


def test_flight_path_without_drag_is_the_parabola_until_it_lands() -> None:
    p0, v0, g, step = np.array([0.0, 0.0, 1.8]), np.array([5.0, 1.0, 6.0]), -9.81, 5e-3
    points = air.flight_path(p0, v0, g, 0.0, CALM, 0.3, step, 10.0)
    t = step * np.arange(len(points))[:, None]
    assert np.abs(points - (p0 + v0 * t + 0.5 * np.array([0.0, 0.0, g]) * t * t)).max() < 1e-9
    assert points[-1, 2] < 0.3 <= points[-2, 2]  # stops at the first sample under the ball radius


def test_shaped_reward_distance_follows_the_air_and_the_wind() -> None:
    """A throw that falls short of the opening in still air comes closer with a tailwind, and
    further with a headwind; without air the distance is the parabola's, found in closed form
    (it lands short of the opening's near edge: the distance from its landing point's height)."""
    sim = Simulator("basket")
    opening, r, g = sim.opening, sim.model.ball_radius, sim.model.gravity
    position, velocity = np.array([-5.0, 0.0, 1.8]), np.array([3.0, 0.0, 6.0])  # lands about 1 m short

    def miss(drag: float, wind: tuple[float, float, float] = (0.0, 0.0, 0.0)) -> float:
        flight = FreeFlight(Ground(r, g, 0.0, 0.0, 0.0), drag, np.array(wind))
        return flight.miss_distance(opening, position, velocity, 10.0)

    t = np.linspace(0.0, 2.0, 200_001)[:, None]  # the parabola, densely, until well past its landing
    points = position + velocity * t + 0.5 * np.array([0.0, 0.0, g]) * t * t
    landed = np.argmax(points[:, 2] < r)
    exact = opening.distance(points[:landed + 1]).min()
    parabola, still = miss(0.0), miss(0.05)
    assert parabola == pytest.approx(exact, abs=0.02)  # sampled every MEASURE_STEP, to its first point under r
    assert parabola < still and miss(0.05, (3.0, 0.0, 0.0)) < still < miss(0.05, (-3.0, 0.0, 0.0))


def test_wind_power_bound_holds_for_any_velocity() -> None:
    """The drag force's power F.v never exceeds air.wind_power_bound (random velocities, winds)."""
    rng = np.random.default_rng(1)
    k, mass = 0.08, 1.3
    for _ in range(20000):
        wind, v = rng.normal(0, 3, 3), rng.normal(0, 3, 3) * rng.uniform(0, 2)
        u = v - wind
        power = -mass * k * np.linalg.norm(u) * u @ v
        assert power <= air.wind_power_bound(mass, k, wind) + 1e-12
    assert air.wind_power_bound(mass, k, CALM) == 0.0 and air.wind_power_bound(mass, 0.0, np.ones(3)) == 0.0


def test_a_ball_ruled_out_never_comes_back() -> None:
    """air.cannot_reach is sound: of random balls outside a box (random velocities, horizontal
    winds up to 3 m/s, strong drag, the ground's bounces and friction), none it rules out comes
    within the box's horizontal extent before the horizon (checked every 10 ms); it rules out
    most of those that stay away, and some it keeps do come in (the check can see an entry)."""
    rng = np.random.default_rng(7)
    box = np.array([-1.0, -1.5, 0.0, 1.0, 1.5, 2.5])
    ground = flight.Ground(gravity=-9.81, **GROUND)
    ruled_out, stayed_away, came_back = 0, 0, 0
    for _ in range(300):
        p = np.array([rng.uniform(-6.0, 6.0), rng.uniform(-6.0, 6.0), rng.uniform(0.3, 4.0)])
        if box[0] <= p[0] <= box[3] and box[1] <= p[1] <= box[4]:
            continue
        v, wind = rng.normal(0.0, 5.0, 3), np.append(rng.uniform(-3.0, 3.0, 2), 0.0)
        horizon = rng.uniform(0.5, 6.0)
        out = air.cannot_reach(p, v, wind, box, horizon)
        entered = False
        for _ in range(round(horizon / 0.01)):
            air.fly(p, v, 0.01, 0.2, wind, ground, air.MAX_FLIGHT_STEP)
            entered = entered or bool(box[0] <= p[0] <= box[3] and box[1] <= p[1] <= box[4])
        assert not (out and entered)
        ruled_out += out
        stayed_away += not entered
        came_back += entered
    assert came_back > 10 and ruled_out > 0.5 * stayed_away
