"""reset(options=...): a scripted thrower and scene overrides for the next episodes; bad
options are refused by name and leave the env as it was."""

from __future__ import annotations

import math

import numpy as np
import pytest

from netgym.config import ConfigError
from netgym.envs import NetCatchEnv
from netgym.envs.net_catch import ObservationIndex


def test_thrower_option_places_the_first_thrower() -> None:
    env = NetCatchEnv()
    obs, _ = env.reset(seed=0, options={"thrower": {"distance": 5.0, "bearing": 90.0}})
    assert obs[ObservationIndex.DISTANCE] == pytest.approx(5.0)
    assert obs[ObservationIndex.BEARING_COS] == pytest.approx(0.0, abs=1e-6)
    assert obs[ObservationIndex.BEARING_SIN] == pytest.approx(1.0)
    drawn, _ = NetCatchEnv().reset(seed=0)
    assert obs[ObservationIndex.HEIGHT] == drawn[ObservationIndex.HEIGHT]  # left out: drawn as usual
    assert np.allclose(env.thrower.position[:2], [0.0, 5.0], atol=1e-9)


def test_overrides_option_changes_the_physics_of_this_and_later_episodes() -> None:
    env = NetCatchEnv()
    env.reset(seed=0, options={"overrides": {"ball.mass": 0.5, "contact.ball_net.friction": 0.5}})
    assert env.sim.config.ball.mass == 0.5 and env.sim.config.contact.ball_net.friction == 0.5
    env.reset(seed=1)
    assert env.sim.config.ball.mass == 0.5                       # kept for the following episodes
    env.reset(seed=2, options={"overrides": {}})
    assert env.sim.config.ball.mass == 1.0                       # relative to the scene the env was made with
    _, _, _, _, info = env.step(np.zeros(3, dtype=np.float32))
    assert math.isfinite(info["sim_time"])


@pytest.mark.parametrize("options, error, words", [
    ({"thrower": {"distance": 50.0}}, ValueError, "options['thrower']['distance'] = 50.0"),
    ({"thrower": {"spin": 1.0}}, ValueError, "unknown key 'spin'"),
    ({"thrower": [5.0]}, ValueError, "options['thrower'] must be a dict"),
    ({"overrides": {"throw.speed": [1.0, 2.0]}}, ValueError, "throw ranges"),
    ({"overrides": {"ball.radius": 0.2}}, ValueError, "observation space"),
    ({"overrides": {"ball.mass": -1.0}}, ConfigError, "ball.mass"),
    ({"wind": 3.0}, ValueError, "unknown reset option(s) ['wind']"),
])
def test_bad_options_are_refused_and_change_nothing(options: dict, error: type, words: str) -> None:
    env = NetCatchEnv()
    obs, _ = env.reset(seed=0)
    scene, thrower = env.sim.config, env.thrower
    with pytest.raises(error) as caught:
        env.reset(seed=1, options=options)
    assert words in str(caught.value)
    assert env.sim.config == scene and env.thrower == thrower
    env.step(np.zeros(3, dtype=np.float32))  # the episode goes on
