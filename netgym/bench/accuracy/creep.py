"""Do balls at rest stay at rest? How far the balls of a pile move when the basket is simulated
on after they came to rest: arranged piles dropped onto the bottom (balls side by side, a ball on
two others) and seeded loaded nets (2-10 balls, each throw decided and paused as between throws),
at the scene's integrator and several dt."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from tqdm import tqdm

from netgym.bench.accuracy.pause_accuracy import largest_move, loaded_net
from netgym.physics.simulator import Simulator

ARRANGED = {  # label: drop positions (m), released at rest above the basket's bottom
    "2 side by side": ((0.25, 0.0, 1.2), (-0.25, 0.0, 1.2)),
    "3 side by side": ((0.3, 0.0, 1.2), (-0.15, 0.26, 1.2), (-0.15, -0.26, 1.2)),
    "4 side by side": ((0.3, 0.3, 1.2), (-0.3, 0.3, 1.2), (0.3, -0.3, 1.2), (-0.3, -0.3, 1.2)),
    "1 on 2 others": ((0.3, 0.0, 1.2), (-0.3, 0.0, 1.2), (0.0, 0.0, 2.2)),
}
SETTLE_TIME = 6.0    # s simulated after an arranged pile is dropped, before measuring
AFTER_PAUSE = 1.0    # s simulated after a loaded net's pause, before measuring (a pile still collapsing)
MEASURED = 2.0       # s over which the balls' movement is measured
DTS, NETS = (2e-3, 1e-3, 5e-4), 48        # the basket's integrator at these steps; seeded loaded nets per step
QUICK_DTS, QUICK_NETS = (2e-3,), 3        # the same, for smoke tests


@dataclass(frozen=True)
class CreepRow:
    """The creep at one dt: per arranged pile, and over the loaded nets, the largest distance a
    ball moved in MEASURED seconds (m)."""

    dt: float
    arranged: dict[str, float]
    loaded: list[float]   # one per loaded net of 2 balls or more


def arranged_creep(sim: Simulator, positions: Sequence[Sequence[float]]) -> float:
    """Drop balls at ``positions`` into the reset ``sim``, let them settle for SETTLE_TIME, then
    measure their largest move over MEASURED."""
    sim.reset()
    for position in positions:
        sim.launch_ball(position, [0.0, 0.0, 0.0])
    sim.step(round(SETTLE_TIME / sim.dt))
    return largest_move(sim, MEASURED)


def loaded_creep(sim: Simulator, seed: int) -> float | None:
    """A seeded loaded net (None if it holds a single ball), paused as between throws and
    simulated on for AFTER_PAUSE: the largest move of its balls over MEASURED."""
    if loaded_net(sim, seed) < 2:
        return None
    sim.run(sim.relax_plan())
    sim.step(round(AFTER_PAUSE / sim.dt))
    return largest_move(sim, MEASURED)


def creep(dts: Sequence[float], nets: int, seed: int = 0, progress: bool = True) -> list[CreepRow]:
    """One row per dt (the basket's own integrator): the arranged piles and the loaded nets of
    seeds ``seed`` .. ``seed + nets - 1`` that hold 2 balls or more."""
    rows = []
    for dt in dts:
        sim = Simulator("basket", {"simulation.dt": dt})
        arranged = {label: arranged_creep(sim, positions) for label, positions in ARRANGED.items()}
        moves = (loaded_creep(sim, seed + k) for k in tqdm(range(nets), desc=f"loaded nets at {dt * 1e3:g} ms",
                                                           unit="net", disable=not progress))
        rows.append(CreepRow(dt, arranged, [m for m in moves if m is not None]))
    return rows


def to_markdown(rows: list[CreepRow]) -> str:
    """The table: per dt, the arranged piles' moves and the loaded nets' p50 / p90 / max (mm)."""
    lines = ["| dt (ms) | " + " | ".join(f"{label} (mm)" for label in ARRANGED)
             + " | loaded nets | largest move per loaded net p50 / p90 / max (mm) |",
             "|---:|" + "---:|" * len(ARRANGED) + "---:|---|"]
    for r in rows:
        loaded = 1e3 * np.array(r.loaded) if r.loaded else None
        spread = "-" if loaded is None else (f"{np.median(loaded):.1f} / {np.percentile(loaded, 90):.1f} / "
                                             f"{loaded.max():.1f}")
        lines.append(f"| {r.dt * 1e3:g} | " + " | ".join(f"{1e3 * r.arranged[label]:.2f}" for label in ARRANGED)
                     + f" | {len(r.loaded)} | {spread} |")
    return "\n".join(lines)
