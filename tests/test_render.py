"""Rendering in every mode: shapes, dtypes, that the picture shows the scene, the GIF script."""

from __future__ import annotations

import os

import gymnasium as gym
import numpy as np
import pytest

import netgym  # noqa: F401
from agents.oracle import BallisticOracle


@pytest.mark.parametrize("scene", ["basket", "goal"])
def test_rgb_array_frame(scene: str) -> None:
    env = gym.make("NetCatch-v0", scene=scene, render_mode="rgb_array")
    env.reset(seed=0)
    frame = env.render()
    h, w = frame.shape[:2]
    assert frame.shape == (360, 480, 3) and frame.dtype == np.uint8
    # the net is drawn in white and the poles in red over the sky/ground background
    assert np.sum(np.all(frame == 245, axis=-1)) > 500
    assert np.sum(np.all(frame == [200, 40, 40], axis=-1)) > 100
    empty = frame.copy()
    env.unwrapped.sim.launch_ball(env.unwrapped.sim.model.geometry.positions.mean(axis=0), [0.0, 0.0, 0.0])
    with_ball = env.render()
    assert np.sum(np.any(with_ball != empty, axis=-1)) > 50  # the ball shows
    assert (h, w) == (360, 480)
    env.close()


def test_rgb_array_list_holds_the_frames_of_a_throw() -> None:
    env = gym.make("NetCatch-v0", render_mode="rgb_array_list").unwrapped
    obs, _ = env.reset(seed=1)
    oracle = BallisticOracle(env.scene)
    _, _, _, _, info = env.step(oracle.predict(obs)[0])
    frames = env.render()
    expected = info["sim_time"] * env.metadata["render_fps"]
    assert len(frames) >= 0.8 * expected
    assert all(f.shape == (360, 480, 3) and f.dtype == np.uint8 for f in frames)
    assert env.render() == []  # frames are handed out once


def test_human_mode_runs_headless() -> None:
    pytest.importorskip("pygame")
    os.environ.setdefault("SDL_VIDEODRIVER", "dummy")
    env = gym.make("NetCatch-v0", render_mode="human")
    env.unwrapped.metadata = dict(env.unwrapped.metadata, render_fps=1000)  # do not wait in tests
    env.reset(seed=0)
    assert env.render() is None
    env.step(np.zeros(3, dtype=np.float32))
    env.close()
    env.close()
