"""``python -m netgym``: one throw into the default basket, its outcome and the speed."""

from __future__ import annotations

import argparse
import time

from netgym.physics.simulator import Simulator
from netgym.physics.throw import throw


def main() -> None:
    """Simulate one lobbed throw into a scene and print what happened and how fast."""
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--scene", default="basket", help="built-in scene name or TOML path")
    args = parser.parse_args()
    sim = Simulator(args.scene)
    throw(sim, [5.0, 0.0, 1.8], [-5.0, 0.0, 6.1])  # compiles the kernels outside the timed region
    sim.reset()
    start = time.perf_counter()
    result = throw(sim, [5.0, 0.0, 1.8], [-5.0, 0.0, 6.1])
    wall = time.perf_counter() - start
    cfg = sim.config.simulation
    print(f"scene {sim.config.name}: {sim.model.n_net} particles, {sim.model.n_springs} springs, "
          f"{cfg.integrator} at dt = {cfg.dt:g} s")
    print(f"throw from (5, 0, 1.8) m at (-5, 0, 6.1) m/s: {'CAPTURED' if result.captured else 'missed'} "
          f"({result.reason}) after {result.time:.3f} s simulated")
    print(f"{result.substeps} substeps in {wall * 1e3:.1f} ms wall: {result.time / wall:.0f}x real time")


if __name__ == "__main__":
    main()
