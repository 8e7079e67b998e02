"""The variants' speed table (agents/variant_speed.py): what its policies act on."""

from __future__ import annotations

import gymnasium as gym

import netgym  # noqa: F401
from agents.variant_speed import _Timing


def test_the_blind_oracle_aims_with_the_registered_scene_not_an_episodes_draw() -> None:
    timing = _Timing("NetCatchRandomized-v1", "oracle")   # has run its warm-up episode, which drew a scene
    registered = gym.make("NetCatchRandomized-v1").unwrapped.scene
    assert timing.env.unwrapped.scene != registered and timing.scene == registered
