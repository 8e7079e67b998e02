"""Seeded test throws: half with uniform-random actions, half with the ballistic aim's action
through the opening's centre plus Gaussian noise, so that captures, rim hits and misses all
occur."""

from __future__ import annotations

import numpy as np

from netgym.aim import BallisticAim
from netgym.bench.accuracy.fast_path import Throw
from netgym.config import load_scene
from netgym.launch import action_to_launch, launch_velocity, sample_thrower
from netgym.physics.simulator import Simulator


def sample_throws(scene: str, count: int, seed: int = 0) -> list[Throw]:
    """``count`` (launch position, velocity) pairs, half random, half noisy aimed throws."""
    sim = Simulator(scene)
    opening = sim.opening
    aim = BallisticAim(load_scene(scene))
    centre_z = float(opening.centre[2])
    rng = np.random.default_rng(seed)
    throws = []
    for k in range(count):
        thrower = sample_thrower(sim.config.throw, opening, rng)
        if k % 2:
            action = aim.action(thrower.distance, thrower.height - centre_z) + rng.normal(0.0, 0.15, 3)
        else:
            action = rng.uniform(-1.0, 1.0, 3)
        throws.append((thrower.position, launch_velocity(*action_to_launch(np.clip(action, -1, 1), sim.config.throw), thrower)))
    return throws
