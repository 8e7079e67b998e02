"""Nets drawn per episode without settling each from scratch: the interpolated equilibrium
against a net settled from scratch with the same draw, the family's modes against each draw's
own, refilled springs against springs built anew, and a new wind sharing the net."""

import numpy as np
import pytest

import netgym  # noqa: F401  (registers the ids)
from netgym import ENVIRONMENTS
from netgym.config import load_scene
from netgym.envs import NetCatchEnv
from netgym.physics.kernels.smooth_forces import spring_forces
from netgym.physics.model.model import Model
from netgym.physics.net_family import NetFamily, family_of, field_value
from netgym.physics.new_net import NEW_NET_REST_SPEED, NEW_NET_WINDOW
from netgym.physics.simulator import Simulator
from netgym.physics.kernels.springs import Springs
from netgym.physics.stability import net_modes

RANGES = tuple((field, float(lo), float(hi)) for field, (lo, hi)
               in ENVIRONMENTS["NetCatchRandomized-v0"].kwargs["randomize"].items())
DRAWS = [{"springs.structural.ks": 1234.5, "springs.structural.kd": 71.0, "ball.mass": 1.7},
         {"springs.structural.ks": 2877.0, "springs.structural.kd": 23.0, "contact.ball_net.friction": 0.15}]
REST_TOLERANCE = NEW_NET_REST_SPEED * NEW_NET_WINDOW   # m: what a new net may still move by when settled


@pytest.fixture(scope="module")
def family() -> NetFamily:
    return family_of(load_scene("basket"), RANGES)


@pytest.mark.slow
@pytest.mark.parametrize("draw", DRAWS)
def test_interpolated_net_within_the_rest_tolerance_of_one_settled_from_scratch(family, draw):
    config = family.scene.replace(draw)
    assert family.serves(config)
    from_scratch = Simulator(config).state.x
    served = family.simulator(config).state.x
    gap = float(np.abs(served - from_scratch).max())
    assert gap <= REST_TOLERANCE, f"interpolated net {gap:.2e} m from the one settled from scratch"


@pytest.mark.slow
@pytest.mark.parametrize("draw", DRAWS)
def test_family_modes_are_no_more_stable_than_a_draws_own(family, draw):
    config = family.scene.replace(draw)
    m = Model.from_config(config)
    modes, settle_modes = family.modes()
    for inertia, bound in ((1.0, modes), (config.simulation.settle_inertia, settle_modes)):
        own = net_modes(m.geometry.positions, m.net_inv_mass / inertia, m.springs, m.spring_params, m.drag)
        assert bound.omega2 >= own.omega2 and bound.damping >= own.damping
        assert bound.imex_limit <= own.imex_limit


def test_family_serves_only_its_draws(family):
    scene = family.scene
    assert family.serves(scene.replace({"ball.mass": 0.6, "air.density": 1.2}))
    assert not family.serves(scene.replace({"net.particle_mass": 0.3}))
    assert not NetFamily(scene, [("springs.structural.ks", 1e3, 2e3), ("springs.shear.ks", 1e3, 2e3)]).serves(scene)
    assert not NetFamily(scene, [("net.particle_mass", 0.1, 0.3)]).serves(scene)


def test_refilled_springs_give_the_forces_of_springs_built_anew():
    nominal = Model.from_config(load_scene("basket"))
    rng = np.random.default_rng(7)
    for draw in DRAWS:
        model = Model.from_config(nominal.config.replace(draw), like=nominal)
        assert model.spring_layout[1] is model.layout_hint, "the layout of the nominal net serves a draw"
        anew = Springs.of(model.springs, model.spring_params, model.n_net)
        x = model.geometry.positions + 0.01 * rng.standard_normal(model.geometry.positions.shape)
        v = rng.standard_normal(x.shape)
        refilled_forces, anew_forces = np.zeros_like(x), np.zeros_like(x)
        spring_forces(x, v, model.kernel.springs, refilled_forces)
        spring_forces(x, v, anew, anew_forces)
        assert np.array_equal(refilled_forces, anew_forces)


def test_refill_refuses_a_dense_group_that_no_longer_shares_its_stiffness():
    model = Model.from_config(load_scene("basket"))
    layout = model.spring_layout[1]
    params = model.spring_params.copy()
    params[layout.dense_members[0], 1] *= 2.0   # one spring of a dense group stiffer than the others
    assert layout.refill(params) is None


def test_a_new_wind_shares_the_net_and_its_kernel_arrays():
    env = NetCatchEnv(balls_per_episode=2, overrides={"air.density": 1.2}, wind=(1.0, 3.0))
    env.reset(seed=1)
    before = env.sim
    env.reset(seed=2)
    assert not np.array_equal(env.sim.model.wind, before.model.wind)
    assert env.sim.model.geometry is before.model.geometry
    assert env.sim.kernel_model.springs is before.kernel_model.springs
    assert np.array_equal(env.sim.kernel_model.wind, env.sim.model.wind)


def test_a_randomized_reset_takes_its_net_from_the_family():
    env = NetCatchEnv(randomize=dict(ENVIRONMENTS["NetCatchRandomized-v0"].kwargs["randomize"]))
    _, info = env.reset(seed=3)
    config = env.sim.config
    assert all(field_value(config, field) == value for field, value in info["scene_draws"].items())
    family = family_of(env._base_scene, env.randomize.ranges)
    assert np.array_equal(env.sim.state.x, family.equilibrium(config))


def test_prepare_net_is_what_a_new_simulator_starts_from() -> None:
    """prepare_net settles a scene once (the same record asked again) and a simulator handed it
    starts where one that settles its own net starts, bitwise; a scene differing only in its air
    shares it."""
    from netgym.physics.simulator import prepare_net

    config = Simulator("basket").config
    prepared = prepare_net(config)
    assert prepare_net(config) is prepared
    assert prepare_net(config.replace({"air.density": 1.2})) is prepared
    own, handed = Simulator(config), Simulator(config, prepared=prepared)
    assert np.array_equal(own.state.x, handed.state.x) and np.array_equal(own.state.v, handed.state.v)
    assert own.modes == handed.modes and own.settle_dt == handed.settle_dt
