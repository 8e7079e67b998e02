"""Shared fixtures: simulators are cached per configuration, tests get fresh copies of state.

When the suite runs on several processes (pytest-xdist, the default), the controller first
compiles the kernels an episode of each scene uses (or loads them from numba's cache), so that
the workers load them from the cache instead of each compiling them at once. Tests marked
``slow`` are handed out first, so that no long test starts last while the other workers idle.
The suite draws headless: SDL's dummy video driver unless the caller chose one (human mode with no
display and no driver is an error, tested on its own with the variables removed).
"""

from __future__ import annotations

import os

import pytest
from hypothesis import settings

from netgym.physics.simulator import Simulator

os.environ.setdefault("SDL_VIDEODRIVER", "dummy")

settings.register_profile("ci", max_examples=25, deadline=None, derandomize=True)
settings.register_profile("thorough", max_examples=300, deadline=None)
settings.register_profile("domain", deadline=None)  # tests/physics/test_throw_domain.py's long run
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "ci"))

WARM_UP_ENVIRONMENTS = ("NetCatch-v0", "NetCatchGoal-v0")
"""One oracle episode of each compiles the throw's and the pause's kernels of both scenes."""


def pytest_configure(config: pytest.Config) -> None:
    """In the controller of a parallel run only: compile the kernels before the workers start."""
    workers = getattr(config.option, "numprocesses", None)
    if not workers or hasattr(config, "workerinput") or config.option.collectonly:
        return
    from agents.warm_up import compile_kernels

    for env_id in WARM_UP_ENVIRONMENTS:
        compile_kernels(env_id)


def pytest_collection_modifyitems(items: list[pytest.Item]) -> None:
    """Run the tests marked ``slow`` first (each group keeps its order)."""
    items.sort(key=lambda item: item.get_closest_marker("slow") is None)


@pytest.fixture
def basket() -> Simulator:
    """The default scene at rest, no balls."""
    return Simulator("basket")


@pytest.fixture
def goal() -> Simulator:
    """The goal scene at rest, no balls."""
    return Simulator("goal")
