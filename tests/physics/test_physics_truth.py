"""Physics against truth: the analytic parabola, the analytic damped oscillator, observed
convergence orders against a fine reference, and energy behaviour."""

from __future__ import annotations

import math

import numpy as np
import pytest

from netgym.errors import UnstableTimeStepError
from netgym.physics.fast_path import flight
from netgym.physics import stepping
from netgym.physics.model.contact_tables import Materials, Poles
from netgym.physics.kernels.integrators import Scratch
from netgym.kinds import Contact, Integrator
from netgym.physics.model.model import KernelModel, Settings
from netgym.physics.model.opening import Opening
from netgym.physics.simulator import Simulator
from netgym.physics.kernels.springs import Springs

# a small net hung high above the ground: it swings under gravity without touching anything
LIFTED = {"net.particles": [5, 5, 6], "net.lower": [-1.0, -1.0, 5.0], "net.upper": [1.0, 1.0, 7.5]}


def lifted_net(integrator: str, dt: float, **extra: object) -> Simulator:
    """The small lifted net in its built (unsagged) shape, about to fall and swing."""
    sim = Simulator("basket", {**LIFTED, "simulation.integrator": integrator, "simulation.dt": dt, **extra})
    sim.state.x[:] = sim.model.geometry.positions
    sim.state.v[:] = 0.0
    return sim


@pytest.mark.parametrize("integrator", Integrator.labels())
def test_free_flight_matches_the_parabola(integrator: str) -> None:
    sim = Simulator("basket", {"simulation.integrator": integrator, "simulation.dt": 5e-4})
    p0, v0 = np.array([30.0, -20.0, 2.0]), np.array([-3.0, 4.0, 12.0])
    sim.launch_ball(p0, v0)
    steps = 1000
    sim.step(steps)
    t = steps * sim.config.simulation.dt
    exact = p0 + v0 * t + 0.5 * np.array([0.0, 0.0, sim.model.gravity]) * t * t
    assert np.abs(sim.ball_positions[0] - exact).max() < 1e-9
    assert np.abs(sim.state.v[sim.model.n_net] - (v0 + np.array([0, 0, sim.model.gravity]) * t)).max() < 1e-9


def test_closed_form_flight_matches_the_parabola_and_bounces() -> None:
    ground = flight.Ground(radius=0.3, gravity=-9.81, restitution=0.5, friction=0.3, threshold=0.2)
    p0, v0 = np.array([0.0, 0.0, 2.0]), np.array([5.0, 0.0, 3.0])
    p, v = flight.advance(p0, v0, 0.4, ground)
    assert np.allclose(p, p0 + v0 * 0.4 + [0, 0, -0.5 * 9.81 * 0.16], atol=1e-12)
    # first ground contact, then restitution on the normal and Coulomb friction on the slip
    t_hit = (3.0 + math.sqrt(9.0 + 2 * 9.81 * 1.7)) / 9.81
    p, v = flight.advance(p0, v0, t_hit + 1e-12, ground)
    vz_in = 3.0 - 9.81 * t_hit
    assert v[2] == pytest.approx(-0.5 * vz_in, rel=1e-6)
    assert v[0] == pytest.approx(5.0 - 0.3 * 1.5 * -vz_in, rel=1e-6)
    # a slip smaller than the friction bound stops entirely
    p, v = flight.advance(p0, [1.0, 0.0, 3.0], t_hit + 1e-12, ground)
    assert v[0] == 0.0


def _oscillator(integrator: int, dt: float, t_end: float, ks: float, kd: float, m: float, amp: float) -> float:
    """Position offset of a mass on a spring from a fixed anchor after t_end (no contacts)."""
    rest = 1.0
    x = np.array([[0.0, 0.0, 50.0], [rest + amp, 0.0, 50.0]])
    v = np.zeros_like(x)
    inv_mass = np.array([0.0, 1.0 / m])
    springs = np.array([[0, 1]])
    params = np.array([[rest, ks, kd]])
    far_away = Opening(axis=2, sign=1, plane=100.0, tangent_axes=(0, 1), tangent_lower=(-1.0, -1.0),
                       tangent_upper=(1.0, 1.0))
    model = KernelModel(n_net=2, springs=Springs.of(springs, params, 2), segments=np.zeros((0, 2), dtype=np.int64),
                        segment_start=np.zeros(3, dtype=np.int64), poles=Poles.none(),
                        materials=Materials.of_table(np.zeros((len(Contact), 2))), restitution_threshold=0.0,
                        gravity=0.0, drag=0.0, ball_radius=0.1, opening=far_away.kernel_record(), ball_drag=0.0,
                        wind=np.zeros(3))
    settings = Settings.make(integrator=integrator, dt=dt, max_travel=0.25, cg_tolerance=1e-13, cg_max_iterations=500,
                        divergence_speed=1e6)
    status = stepping.advance(x, v, inv_mass, np.zeros(0, dtype=np.int8), model, settings, round(t_end / dt),
                              Scratch.sized(2, 1), stepping.new_counters())
    assert status == stepping.OK
    return x[1, 0] - rest


def _oscillator_exact(t: float, ks: float, kd: float, m: float, amp: float) -> float:
    gamma = kd / (2 * m)
    wd = math.sqrt(ks / m - gamma * gamma)
    return math.exp(-gamma * t) * (amp * math.cos(wd * t) + gamma * amp / wd * math.sin(wd * t))


@pytest.mark.parametrize("integrator", list(Integrator))
def test_spring_mass_oscillator_matches_the_analytic_solution(integrator: Integrator) -> None:
    # t_end avoids 1.0 s, where the first-order error term of IMEX Euler happens to vanish
    ks, kd, m, amp, t_end = 400.0, 2.0, 1.0, 0.1, 0.83
    exact = _oscillator_exact(t_end, ks, kd, m, amp)
    dts = (1e-3, 5e-4)
    errors = [abs(_oscillator(integrator, dt, t_end, ks, kd, m, amp) - exact) for dt in dts]
    omega = math.sqrt(ks / m)
    if integrator == Integrator.RK4:
        # global error of order t * omega * (omega dt)^4 / 120 * amp
        assert errors[1] < t_end * omega * (omega * dts[1]) ** 4 / 120 * amp
        assert errors[0] / errors[1] == pytest.approx(16.0, rel=0.15)
    else:
        # first-order methods: amplitude error of order omega^2 dt t / 2 * amp
        assert errors[1] < omega ** 2 * dts[1] * t_end / 2 * amp
        assert errors[0] / errors[1] == pytest.approx(2.0, rel=0.15)


def _final_positions(sim: Simulator, t_end: float) -> np.ndarray:
    sim.step(round(t_end / sim.config.simulation.dt))
    return sim.state.x.copy()


@pytest.mark.slow
@pytest.mark.parametrize(("integrator", "order", "dts"), [
    ("explicit_euler", 1, [2e-4, 1e-4, 5e-5, 2.5e-5]),
    ("symplectic_euler", 1, [2e-4, 1e-4, 5e-5, 2.5e-5]),
    ("implicit_euler", 1, [2e-4, 1e-4, 5e-5, 2.5e-5]),
    ("imex_euler", 1, [2e-4, 1e-4, 5e-5, 2.5e-5]),
    ("rk4", 4, [4e-4, 2e-4, 1e-4]),
])
def test_observed_convergence_order_on_a_swinging_net(integrator: str, order: int, dts: list[float]) -> None:
    t_end = 0.1
    reference = _final_positions(lifted_net("rk4", 1e-5), t_end)
    errors = [np.abs(_final_positions(lifted_net(integrator, dt, **{"simulation.cg_tolerance": 1e-13}), t_end)
                     - reference).max() for dt in dts]
    slope = np.polyfit(np.log(dts), np.log(errors), 1)[0]
    assert abs(slope - order) <= 0.3, (slope, errors)


def test_undamped_net_keeps_bounded_energy_with_symplectic_euler() -> None:
    undamped = {f"springs.{k}.kd": 0.0 for k in ("structural", "shear", "bending")}
    sim = lifted_net("symplectic_euler", 2.5e-4, **undamped, **{"net.drag": 0.0})
    e0 = sim.energy().total
    swing = []
    for _ in range(200):  # 10 s
        sim.step(200)
        swing.append(sim.energy().total - e0)
    swing = np.array(swing)
    scale = sim.energy().kinetic + sim.energy().spring + 1.0
    assert np.abs(swing).max() < 0.02 * scale
    # no drift: the last second's mean energy error is no worse than the first's plus noise
    assert abs(swing[-20:].mean()) < abs(swing[:20].mean()) + 0.005 * scale


@pytest.mark.parametrize(("integrator", "dt"), [("rk4", 2e-4), ("implicit_euler", 1e-3), ("implicit_euler", 1e-2),
                                                  ("imex_euler", 2e-3)])
def test_damped_net_never_gains_energy(integrator: str, dt: float) -> None:
    sim = lifted_net(integrator, dt, **{"simulation.cg_tolerance": 1e-12})
    energy = [sim.energy().total]
    for _ in range(round(2.0 / dt)):
        sim.step(1)
        energy.append(sim.energy().total)
    gains = np.diff(energy)
    assert gains.max() <= 1e-9 * abs(energy[0])
    assert energy[-1] < energy[0]


def _random_spring_graph(rng: np.random.Generator, n: int = 12, n_springs: int = 30):
    x = rng.uniform(-1.0, 1.0, (n, 3))
    pairs = {tuple(sorted(rng.choice(n, 2, replace=False))) for _ in range(n_springs)}
    springs = np.array(sorted(pairs), dtype=np.int64)
    return x, springs


def test_imex_dampers_only_remove_kinetic_energy_and_keep_momentum() -> None:
    from netgym.physics.kernels.integrators import step_imex_euler

    rng = np.random.default_rng(3)
    for _ in range(20):
        x, springs = _random_spring_graph(rng)
        v = rng.normal(0.0, 1.0, x.shape)
        inv_mass = rng.uniform(0.5, 5.0, len(x))
        params = np.column_stack([np.zeros(len(springs)), np.zeros(len(springs)),  # no elastic force
                                  rng.uniform(1.0, 500.0, len(springs))])
        dt = 10.0 ** rng.uniform(-4, -1)
        kinetic = 0.5 * np.sum(v * v / inv_mass[:, None])
        momentum = np.sum(v / inv_mass[:, None], axis=0)
        step_imex_euler(x, v, inv_mass, 0.0, 0.0, Springs.of(springs, params, len(x)), dt,
                        Scratch.sized(len(x), len(springs)))
        assert 0.5 * np.sum(v * v / inv_mass[:, None]) < kinetic
        assert np.allclose(np.sum(v / inv_mass[:, None], axis=0), momentum, atol=1e-10)


def test_imex_shares_are_computed_again_for_another_step_and_after_implicit_euler() -> None:
    """IMEX Euler keeps its damper shares (which depend on dt alone) between steps of one size: a
    scratch that last stepped at another dt, or that implicit Euler used since, steps bitwise as
    a fresh one does."""
    from netgym.physics.kernels.integrators import step_imex_euler, step_implicit_euler

    rng = np.random.default_rng(5)
    x, springs = _random_spring_graph(rng)
    v = rng.normal(0.0, 1.0, x.shape)
    inv_mass = rng.uniform(0.5, 5.0, len(x))
    params = np.column_stack([np.ones(len(springs)), rng.uniform(10.0, 100.0, len(springs)),
                              rng.uniform(1.0, 50.0, len(springs))])
    record = Springs.of(springs, params, len(x))

    def imex(scratch: Scratch, dt: float) -> tuple[np.ndarray, np.ndarray]:
        xs, vs = x.copy(), v.copy()
        step_imex_euler(xs, vs, inv_mass, -9.81, 0.0, record, dt, scratch)
        return xs, vs

    fresh = imex(Scratch.sized(len(x), len(springs)), 2e-3)
    used = Scratch.sized(len(x), len(springs))
    imex(used, 5e-3)
    assert all(np.array_equal(a, b) for a, b in zip(imex(used, 2e-3), fresh))
    step_implicit_euler(x.copy(), v.copy(), inv_mass, -9.81, 0.0, record, 2e-3,
                        Settings.make(Integrator.IMPLICIT_EULER, 2e-3, 0.25, 1e-8, 200, 1e3), used)
    assert all(np.array_equal(a, b) for a, b in zip(imex(used, 2e-3), fresh))


def test_imex_damper_of_one_spring_is_two_backward_euler_half_steps() -> None:
    from netgym.physics.kernels.integrators import step_imex_euler

    x = np.array([[0.0, 0.0, 0.0], [0.6, 0.8, 0.0]])
    v = np.array([[0.3, -0.2, 0.5], [-1.0, 0.4, 0.1]])
    inv_mass, kd, dt = np.array([2.0, 0.5]), 40.0, 0.01
    axis = x[1] - x[0]
    before = np.dot(v[1] - v[0], axis)
    step_imex_euler(x, v, inv_mass, 0.0, 0.0, Springs.of([[0, 1]], [[1.0, 0.0, kd]], 2), dt, Scratch.sized(2, 1))
    assert np.dot(v[1] - v[0], axis) == pytest.approx(before / (1.0 + 0.5 * dt * kd * inv_mass.sum()) ** 2, rel=1e-12)


def test_imex_euler_is_stable_far_beyond_the_explicit_dampers_limit() -> None:
    """The seed's dampers limit explicit methods to < 1 ms on the basket; IMEX Euler runs the
    net at 5 ms and its energy decays."""
    with pytest.raises(UnstableTimeStepError):
        Simulator("basket", {"simulation.integrator": "symplectic_euler", "simulation.dt": 5e-3})
    sim = Simulator("basket", {"simulation.integrator": "imex_euler", "simulation.dt": 5e-3})
    assert sim.stable_dt > 5e-3
    rng = np.random.default_rng(0)
    sim.state.x[:] += rng.normal(0.0, 0.01, sim.state.x.shape) * (sim.state.inv_mass > 0)[:, None]
    start = sim.energy().total
    sim.step(400)  # 2 s
    assert sim.energy().total < start
    assert np.abs(sim.state.v).max() < 0.05


def _one_damped_spring(ks: float, kd: float, mass: float) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """A free particle hung at rest length from a fixed one (positions, inverse masses, springs,
    spring parameters)."""
    x = np.array([[0.0, 0.0, 0.0], [0.6, 0.0, 0.8]])
    return x, np.array([0.0, 1.0 / mass]), np.array([[0, 1]]), np.array([[1.0, ks, kd]])


def _spectral_radius_of_the_imex_step(x, inv_mass, springs, params, dt) -> float:
    """Spectral radius of the Jacobian of the IMEX Euler kernel's step (free particle's position
    and velocity) about rest, by central differences."""
    from netgym.physics.kernels.integrators import step_imex_euler

    def step(state: np.ndarray) -> np.ndarray:
        xs, vs = x.copy(), np.zeros_like(x)
        xs[1] += state[:3]
        vs[1] = state[3:]
        step_imex_euler(xs, vs, inv_mass, 0.0, 0.0, Springs.of(springs, params, 2), dt, Scratch.sized(2, 1))
        return np.concatenate([xs[1] - x[1], vs[1]])

    eps = 1e-7
    jacobian = np.column_stack([(step(eps * e) - step(-eps * e)) / (2 * eps) for e in np.eye(6)])
    return float(max(abs(np.linalg.eigvals(jacobian))))


def test_imex_stability_limit_of_one_damped_spring_is_analytic_and_the_kernels() -> None:
    """One spring, damper swept over two half steps: along the spring the step is stable while
    h^2 omega^2 g < 2 (1 + g), g = 1 / (1 + h kd w / 2)^2, a quadratic in h. The estimate finds
    its root, far beyond the elastic limit 2 / omega, and the kernel's own step matrix turns
    unstable there."""
    from netgym.physics.stability import net_modes

    ks, kd, mass = 1500.0, 50.0, 2.0
    x, inv_mass, springs, params = _one_damped_spring(ks, kd, mass)
    omega2, c = ks / mass, kd / mass
    a = omega2 - c * c / 2.0                      # h^2 (omega^2 - c^2 / 2) - 2 c h - 4 = 0
    analytic = (2.0 * c + math.sqrt(4.0 * c * c + 16.0 * a)) / (2.0 * a)
    limit = net_modes(x, inv_mass, springs, params).imex_limit
    assert limit == pytest.approx(analytic, rel=3e-3)
    assert limit > 2.0 * (2.0 / math.sqrt(omega2))
    assert _spectral_radius_of_the_imex_step(x, inv_mass, springs, params, 0.98 * analytic) <= 1.0 + 1e-6
    assert _spectral_radius_of_the_imex_step(x, inv_mass, springs, params, 1.02 * analytic) > 1.02


@pytest.mark.parametrize("ks", [1500.0, 15000.0])
def test_imex_stability_limit_on_the_net_is_where_the_net_diverges(ks: float) -> None:
    """On the basket (default and ten times stiffer springs), perturbed by 1 cm from rest, IMEX
    Euler keeps the net for 2 s just below its estimated limit and diverges just above it."""
    from netgym.errors import SimulationDivergedError

    sim = Simulator("basket", {f"springs.{k}.ks": ks for k in ("structural", "shear", "bending")})
    limit = sim.modes.imex_limit
    assert limit > 1.5 * 2.0 / sim.modes.omega

    def run(dt: float) -> None:
        sim.reset()
        rng = np.random.default_rng(0)
        sim.state.x[:] += rng.normal(0.0, 0.01, sim.state.x.shape) * (sim.state.inv_mass > 0)[:, None]
        sim.step(round(2.0 / dt), integrator="imex_euler", dt=dt)

    run(0.95 * limit)
    assert np.abs(sim.state.v).max() < 0.1
    with pytest.raises(SimulationDivergedError):
        run(1.15 * limit)
