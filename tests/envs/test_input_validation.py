"""Bad arguments and actions get clear errors naming what is wrong, and change nothing; a
divergence's error says what to change."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import gymnasium as gym
import numpy as np
import pytest

from netgym.aim import BallisticAim
from netgym.envs import NetCatchEnv
from netgym.envs.observation import aim_at_centre
from netgym.errors import EpisodeEndedError, InvalidArgumentError, NetgymError, SimulationDivergedError
from netgym.physics.simulator import Simulator


def test_stepping_an_ended_episode_raises_and_pays_nothing() -> None:
    env = NetCatchEnv(balls_per_episode=1)
    obs, _ = env.reset(seed=0)
    _, _, terminated, _, _ = env.step(aim_at_centre(BallisticAim(env.scene), obs))
    assert terminated
    with pytest.raises(EpisodeEndedError, match="call reset"):
        env.step(np.zeros(3, dtype=np.float32))
    assert env.sim.n_balls <= 1
    env.reset(seed=1)
    env.step(np.zeros(3, dtype=np.float32))


MISTAKES = [
    pytest.param({"reward_mode": "dense"}, None, None, id="reward_mode"),
    pytest.param({"balls_per_episode": 0}, None, None, id="balls_per_episode"),
    pytest.param({"render_mode": "ascii"}, None, None, id="render_mode"),
    pytest.param({"fast": "no"}, None, None, id="fast"),
    pytest.param({"overrides": {"air.density": 1.2}, "wind": (3.0, 1.0)}, None, None, id="wind"),
    pytest.param({"launch_noise": (0.3, -1.0, 1.0)}, None, None, id="launch_noise"),
    pytest.param({"randomize": {"ball.mass": (2.0, 1.0)}}, None, None, id="randomize"),
    pytest.param({}, {"wind": 3.0}, None, id="reset option key"),
    pytest.param({}, {"thrower": {"distance": -1.0}}, None, id="reset thrower"),
    pytest.param({}, None, np.zeros(2, dtype=np.float32), id="action shape"),
    pytest.param({}, None, np.array([0.0, np.inf, 0.0], dtype=np.float32), id="action not finite"),
]
"""User mistakes: env arguments, reset options, an action (each None where not the mistake)."""

MAKERS: dict[str, Callable[..., Any]] = {"direct": NetCatchEnv,
                                         "gym.make": lambda **kwargs: gym.make("NetCatch-v0", **kwargs)}


@pytest.mark.parametrize("maker", list(MAKERS))
@pytest.mark.parametrize(("kwargs", "options", "action"), MISTAKES)
def test_user_mistakes_raise_a_netgym_error_that_is_a_value_error(maker: str, kwargs: dict, options: dict | None,
                                                                 action: np.ndarray | None) -> None:
    with pytest.raises(NetgymError) as failure:
        env = MAKERS[maker](**kwargs)
        env.reset(seed=0, options=options)
        if action is not None:
            env.step(action)
    assert isinstance(failure.value, ValueError) and isinstance(failure.value, InvalidArgumentError)


@pytest.mark.parametrize("mistake", [
    lambda sim: sim.step(n_steps=-1), lambda sim: sim.step(dt=float("nan")),
    lambda sim: sim.step(integrator="verlet"), lambda sim: sim.launch_ball([0.0, 0.0, -1.0], [1.0, 0.0, 0.0]),
    lambda sim: sim.launch_ball([0.0, 0.0], [1.0, 0.0, 0.0]), lambda sim: sim.launch_ball([0.0, 0.0, 5.0], [1e3, 0.0, 0.0]),
], ids=["n_steps", "dt", "integrator", "position below ground", "position shape", "velocity"])
def test_simulator_mistakes_raise_a_netgym_error_that_is_a_value_error(basket: Simulator,
                                                                       mistake: Callable[[Simulator], Any]) -> None:
    with pytest.raises(InvalidArgumentError) as failure:
        mistake(basket)
    assert isinstance(failure.value, NetgymError) and isinstance(failure.value, ValueError)


def test_step_before_reset_is_refused_by_gymnasium_first_through_make() -> None:
    with pytest.raises(EpisodeEndedError, match="call reset"):
        NetCatchEnv().step(np.zeros(3, dtype=np.float32))
    with pytest.raises(gym.error.ResetNeeded):
        gym.make("NetCatch-v0").step(np.zeros(3, dtype=np.float32))


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
