"""Shared fixtures: simulators are cached per configuration, tests get fresh copies of state."""

from __future__ import annotations

import os

import pytest
from hypothesis import settings

from netgym.physics.simulator import Simulator

settings.register_profile("ci", max_examples=25, deadline=None, derandomize=True)
settings.register_profile("thorough", max_examples=300, deadline=None)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "ci"))


@pytest.fixture
def basket() -> Simulator:
    """The default scene at rest, no balls."""
    return Simulator("basket")


@pytest.fixture
def goal() -> Simulator:
    """The goal scene at rest, no balls."""
    return Simulator("goal")
