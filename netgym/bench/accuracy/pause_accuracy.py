"""How near the pause between throws comes to the equilibrium a fine relaxation finds.

Seeded loaded nets: 1-10 balls dropped one after another into the basket (each from above the
opening, with a small horizontal speed, each throw decided as usual and the net paused between
them as usual); the pause after the last ball starts from the state the throw left (balls may
still bounce). From that one state each pause runs: the default, variants, and reference relaxations
(the same kinetic damping at a fine step, ended at 3 mm/s; at 1 mm/s piles of balls often do
not come to rest within a minute: they creep). The error of a pause is the largest
distance of a ball to its place in the reference and the RMS distance of the net particles; its
drift, the largest distance a ball moves when the scene is simulated on for a second after it.
Comparing the finer reference with the reference tells how well defined the equilibrium is:
friction makes where balls come to rest depend on the path there.
"""

from __future__ import annotations

import time
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from tqdm import tqdm

from netgym.arguments import describe_overrides
from netgym.errors import NetNotAtRestError
from netgym.physics.simulator import Simulator
from netgym.physics.throw import throw

REFERENCE = {"dt": 5e-4, "settle_speed": 3e-3, "max_time": 20.0}
PAUSES = {  # label: arguments of Simulator.relax_plan (none: the default pause)
    "default (IMEX Euler, 26.9 ms, net inertia 4x, to 0.1 m/s)": {},
    "11.5 ms steps, net's own inertia, to 0.1 m/s": {"dt": 0.0115},
    "2 ms steps, to 0.1 m/s": {"dt": 2e-3},
    "6 ms steps, to 0.1 m/s": {"dt": 6e-3},
    "default pause to 0.01 m/s": {"settle_speed": 1e-2},
    "finer reference (0.25 ms, to 3 mm/s)": {"dt": 2.5e-4, "settle_speed": 3e-3, "max_time": 20.0},
}
DROP_HEIGHT = 3.6             # m, above the basket's opening at z = 3
DROP_SPREAD = 0.7             # m, drops land within +-this of the opening's centre in x and y
DROP_SPEED = 1.0              # m/s, most horizontal speed of a drop along x and y
DRIFT_TIME = 1.0              # s simulated on after a pause, at the scene's dt, to see how far the balls still move


@dataclass(frozen=True)
class PauseResult:
    """One pause from one loaded net: where its balls and net particles ended, its cost, and the
    largest distance a ball moved in DRIFT_TIME simulated on after it (the scene's dynamics)."""

    balls: np.ndarray
    net: np.ndarray
    wall_seconds: float
    simulated_seconds: float
    drift: float


def loaded_net(sim: Simulator, seed: int) -> int:
    """Reset ``sim`` and drop 1-10 balls (drawn from ``seed``) into it; returns how many. The
    scene is left as the last throw decided it, before its pause."""
    rng = np.random.default_rng(seed)
    sim.reset()
    count = int(rng.integers(1, 11))
    for _ in range(count):
        x, y = rng.uniform(-DROP_SPREAD, DROP_SPREAD, 2)
        vx, vy = rng.uniform(-DROP_SPEED, DROP_SPEED, 2)
        throw(sim, [x, y, DROP_HEIGHT], [vx, vy, 0.0])
    return count


def largest_move(sim: Simulator, seconds: float) -> float:
    """Simulate ``sim`` on for ``seconds``; the largest distance a ball moved meanwhile (m)."""
    before = sim.ball_positions
    sim.step(round(seconds / sim.dt))
    return float(np.linalg.norm(sim.ball_positions - before, axis=1).max(initial=0.0))


def pause(sim: Simulator, **relaxation: Any) -> PauseResult:
    """Run the pause (``relaxation``: arguments of ``relax_plan``; none for the default one),
    then simulate on for DRIFT_TIME."""
    start, time0 = time.perf_counter(), sim.state.time
    sim.run(sim.relax_plan(**relaxation))
    wall, n = time.perf_counter() - start, sim.model.n_net
    balls, net, simulated = sim.ball_positions, sim.state.x[:n].copy(), sim.state.time - time0
    return PauseResult(balls, net, wall, simulated, largest_move(sim, DRIFT_TIME))


def errors(result: PauseResult, reference: PauseResult) -> tuple[float, float]:
    """(largest ball distance, RMS net particle distance) of ``result`` from ``reference`` (m)."""
    ball = float(np.linalg.norm(result.balls - reference.balls, axis=1).max(initial=0.0))
    net = float(np.sqrt(np.mean(np.sum((result.net - reference.net) ** 2, axis=1))))
    return ball, net


def pause_accuracy(nets: int, seed: int = 0, progress: bool = True,
                   candidates: Sequence[Mapping[str, Any]] = ()) -> list[dict]:
    """Per loaded net: the ball count and, per pause of PAUSES, its errors from the reference
    and its wall and simulated seconds (``"pauses"`` is ``None`` where the reference did not come
    to rest, a pause's entry ``None`` where that pause did not). Each of ``candidates`` (scene
    overrides) adds the default pause of a basket with them, from the same loaded nets."""
    sim = Simulator("basket")
    loaded_net(sim, seed)
    pause(sim)  # compile the kernels outside the timed pauses
    runs = [(label, sim, relaxation) for label, relaxation in PAUSES.items()]
    runs += [(candidate_label(c), Simulator("basket", c), {}) for c in candidates]
    rows = []
    for k in tqdm(range(nets), desc="loaded nets", unit="net", disable=not progress):
        row: dict[str, Any] = {"balls": loaded_net(sim, seed + k), "pauses": None}
        rows.append(row)
        start = sim.checkpoint()
        try:
            reference = pause(sim, **REFERENCE)
        except NetNotAtRestError:  # did not come to rest within max_time: the net is left out
            continue
        row["pauses"] = {}
        for label, simulator, relaxation in runs:
            simulator.restore(start)
            try:
                result = pause(simulator, **relaxation)
            except NetNotAtRestError:
                row["pauses"][label] = None
                continue
            ball, net = errors(result, reference)
            row["pauses"][label] = {"ball": ball, "net": net, "wall": result.wall_seconds,
                                    "simulated": result.simulated_seconds, "drift": result.drift}
    return rows


def candidate_label(overrides: Mapping[str, Any]) -> str:
    """The row label of the default pause with ``overrides``."""
    return "default with " + describe_overrides(overrides)


BALL_GROUPS = ((1, 1), (2, 4), (5, 10))  # loaded nets by their ball count: a lone ball, small piles, large piles
GROUPED_PAUSES = (list(PAUSES)[0], list(PAUSES)[-1])  # the default pause and the finer reference


def to_markdown(rows: list[dict]) -> str:
    """The tables: per pause, p50 / p90 / max of the errors, the share within 5 mm (balls) and
    2 mm RMS (net), the drift after it, and the cost; then the errors of the default pause and of
    the finer reference by the number of balls in the net (a lone ball against piles)."""
    settled = [r for r in rows if r["pauses"] is not None]
    lines = [f"{len(rows) - len(settled)} of {len(rows)} loaded nets left out: the reference did not come to rest "
             f"within {REFERENCE['max_time']:g} s.", "",
             "| pause | loaded nets at rest | not at rest | ball error p50 / p90 / max (mm) | balls within 5 mm | "
             "net RMS error p50 / p90 / max (mm) | net within 2 mm | ball drift in the next second p50 / p90 / max (mm) | "
             "wall ms p50 / p99 / max | simulated s p50 |",
             "|---|---:|---:|---|---:|---|---:|---|---|---:|"]
    labels = list(settled[0]["pauses"]) if settled else list(PAUSES)
    for label in labels:
        done = [r["pauses"][label] for r in settled if r["pauses"][label] is not None]
        if not done:
            lines.append(f"| {label} | 0 | {len(settled)} | - | - | - | - | - | - | - |")
            continue
        wall, simulated, drift = (np.array([p[key] for p in done]) for key in ("wall", "simulated", "drift"))
        wall, drift = 1e3 * wall, 1e3 * drift
        lines.append(f"| {label} | {len(done)} | {len(settled) - len(done)} | {_errors(done)} | {_spread(drift)} | "
                     f"{np.median(wall):.1f} / {np.percentile(wall, 99):.1f} / {wall.max():.1f} | "
                     f"{np.median(simulated):.2f} |")
    lines += ["", "By the number of balls in the net:", "",
              "| balls | pause | loaded nets at rest | ball error p50 / p90 / max (mm) | balls within 5 mm | "
              "net RMS error p50 / p90 / max (mm) | net within 2 mm |",
              "|---|---|---:|---|---:|---|---:|"]
    for low, high in BALL_GROUPS:
        group = [r for r in settled if low <= r["balls"] <= high]
        for label in GROUPED_PAUSES:
            done = [r["pauses"][label] for r in group if r["pauses"][label] is not None]
            balls = str(low) if low == high else f"{low}-{high}"
            lines.append(f"| {balls} | {label} | {len(done)} | {_errors(done) if done else '- | - | - | -'} |")
    return "\n".join(lines)


def _errors(done: list[dict]) -> str:
    """The error columns of pauses ``done``: ball error spread and share within 5 mm, net RMS
    error spread and share within 2 mm."""
    ball, net = (1e3 * np.array([p[key] for p in done]) for key in ("ball", "net"))
    return (f"{_spread(ball)} | {100 * np.mean(ball <= 5.0):.0f}% | "
            f"{_spread(net)} | {100 * np.mean(net <= 2.0):.0f}%")


def _spread(values: np.ndarray) -> str:
    return f"{np.median(values):.1f} / {np.percentile(values, 90):.1f} / {values.max():.1f}"
