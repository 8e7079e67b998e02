"""Bad arguments and actions get clear errors naming what is wrong, and change nothing; a
divergence's error says what to change."""

from __future__ import annotations

import numpy as np
import pytest

from agents.oracle import BallisticOracle
from netgym.envs import NetCatchEnv
from netgym.errors import EpisodeEndedError, SimulationDivergedError
from netgym.physics.simulator import Simulator


def test_stepping_an_ended_episode_raises_and_pays_nothing() -> None:
    env = NetCatchEnv(balls_per_episode=1)
    obs, _ = env.reset(seed=0)
    _, _, terminated, _, _ = env.step(BallisticOracle(env.scene).predict(obs)[0])
    assert terminated
    with pytest.raises(EpisodeEndedError, match="call reset"):
        env.step(np.zeros(3, dtype=np.float32))
    assert env.sim.n_balls <= 1
    env.reset(seed=1)
    env.step(np.zeros(3, dtype=np.float32))


@pytest.mark.parametrize(("kwargs", "message"), [
    ({"fast": "no"}, "fast = 'no'"),
    ({"balls_per_episode": True}, "balls_per_episode = True"),
])
def test_loosely_typed_env_arguments_are_refused(kwargs: dict, message: str) -> None:
    with pytest.raises(ValueError, match=message):
        NetCatchEnv(**kwargs)


@pytest.mark.parametrize("action", [np.array([True, False, True]), np.array([1j, 0, 0]), "abc",
                                    ["0.1", "0.2", "0.3"]])
def test_non_real_actions_are_refused_with_a_clear_error(action: object) -> None:
    env = NetCatchEnv()
    env.reset(seed=0)
    with pytest.raises(ValueError, match="action must be an array of real numbers"):
        env.step(action)
    assert env.sim.n_balls == 0


@pytest.mark.parametrize(("options", "message"), [("fast", "options must be a dict"),
                                                  ({"thrower": 3}, r"options\['thrower'\] must be a dict")])
def test_reset_options_are_checked(options: object, message: str) -> None:
    with pytest.raises(ValueError, match=message):
        NetCatchEnv().reset(seed=0, options=options)


@pytest.mark.parametrize(("args", "message"), [
    ({"n_steps": -5}, "n_steps = -5"), ({"n_steps": 2.5}, "n_steps = 2.5"), ({"n_steps": True}, "n_steps = True"),
    ({"dt": -1e-3}, "dt = -0.001"), ({"dt": float("nan")}, "dt = nan"),
    ({"integrator": "verlet"}, r"integrator = 'verlet' is not one of \['explicit_euler'"),
])
def test_simulator_step_refuses_bad_arguments_and_changes_nothing(basket: Simulator, args: dict, message: str) -> None:
    before = basket.state.copy()
    with pytest.raises(ValueError, match=message):
        basket.step(**args)
    assert basket.state.time == before.time and np.array_equal(basket.state.x, before.x)


def test_launch_speed_error_prints_enough_digits(basket: Simulator) -> None:
    with pytest.raises(ValueError, match=r"speed 100\.00000000000001 m/s"):
        basket.launch_ball([0.0, 0.0, 5.0], [100.00000000000001, 0.0, 0.0])


def test_divergence_advice_never_suggests_the_integrator_that_diverged() -> None:
    sim = Simulator("basket", {"simulation.divergence_speed": 15.5})
    sim.launch_ball([0.0, 0.0, 2.0], [0.0, 0.0, -16.0])
    with pytest.raises(SimulationDivergedError) as failure:
        sim.step(1)
    message = str(failure.value)
    assert message.startswith("imex_euler at dt = 0.002 s diverged")
    assert 'integrator = "implicit_euler"' in message and '"imex_euler"' not in message
