"""What a goal under the ``held`` rule waits for: for each captured throw, when the ball's
horizontal motion ends, when it last leaves the floor (bouncing in place), and when the fast
path decides the throw; with the speed of the net's fastest particle at those instants."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from netgym.bench.throws import sample_throws
from netgym.physics.simulator import Simulator
from netgym.physics.throw import throw

HORIZONTAL_SPEED = 0.05  # m/s: slower than this, the ball's horizontal motion has ended
FLOOR_GAP = 0.015        # m: a ball whose bottom is higher than this above the ground is off the floor


@dataclass(frozen=True)
class HeldCapture:
    """One captured throw, its instants in simulated seconds after the launch (sampled at the
    end of every integration request: 10 ms chunks)."""

    decided: float                # the fast path's decision
    reason: str                   # its reason
    moving_until: float           # last instant the ball's horizontal speed was above HORIZONTAL_SPEED
    bouncing_until: float         # last instant the ball was off the floor (its bottom above FLOOR_GAP)
    net_speed_when_still: float   # fastest net particle's largest velocity component then (m/s)


def held_captures(count: int, seed: int) -> list[HeldCapture]:
    """Throw ``count`` seeded throws (:func:`~netgym.bench.throws.sample_throws`) into the empty
    goal under ``held``, each from the net at rest, and return the captured ones."""
    sim = Simulator("goal", {"capture_rule": "held"})
    radius, n_net = sim.model.ball_radius, sim.model.n_net
    captures = []
    for position, velocity in sample_throws("goal", count, seed):
        sim.reset()
        start = sim.state.time
        samples: list[tuple[float, float, float, float]] = []  # time, horizontal speed, height, net speed

        def record(s: Simulator) -> None:
            if s.n_balls:
                x, v = s.state.x, s.state.v
                samples.append((s.state.time - start, float(np.hypot(*v[-1, :2])), float(x[-1, 2]),
                                float(np.abs(v[:n_net]).max())))

        result = throw(sim, position, velocity, observer=record)
        if not result.captured or not samples:
            continue
        t, horizontal, height, net_speed = np.array(samples).T
        moving = np.flatnonzero(horizontal > HORIZONTAL_SPEED)
        last_moving = moving[-1] if len(moving) else 0
        bouncing = np.flatnonzero(height - radius > FLOOR_GAP)
        captures.append(HeldCapture(result.time, result.reason, float(t[last_moving]),
                                    float(t[bouncing[-1]]) if len(bouncing) else 0.0,
                                    float(net_speed[min(last_moving + 1, len(t) - 1)])))
    return captures


def summary(captures: list[HeldCapture]) -> str:
    """The captures' instants as p50 / p90 / max lines."""
    if not captures:
        return "no captures"

    def spread(values: list[float], unit: str) -> str:
        p50, p90, top = np.percentile(values, [50, 90, 100])
        return f"p50 {p50:.2f} / p90 {p90:.2f} / max {top:.2f} {unit}"

    reasons = sorted({c.reason for c in captures})
    counts = ", ".join(f"{sum(c.reason == r for c in captures)} {r}" for r in reasons)
    rows = [("decided after", [c.decided for c in captures], "s"),
            (f"ball's horizontal motion ended (< {HORIZONTAL_SPEED} m/s) after",
             [c.moving_until for c in captures], "s"),
            ("ball last off the floor (bouncing in place) at", [c.bouncing_until for c in captures], "s"),
            ("net's fastest particle when the ball's motion ended", [c.net_speed_when_still for c in captures], "m/s")]
    width = max(len(label) for label, _, _ in rows) + 2
    return "\n".join([f"{len(captures)} captured throws ({counts})"]
                     + [(label + ":").ljust(width) + spread(values, unit) for label, values, unit in rows])
