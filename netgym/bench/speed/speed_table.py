"""The table of every registered id's speed, from the rows of its result file
(``docs/results/variant_speed.json``, written by ``scripts/bench_variants.py``)."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from pathlib import Path
from statistics import median
from typing import Any

from netgym.bench.results import read_results

BASE_ID = "NetCatch-v0"


def _tails(values: Sequence[float]) -> str:
    return " / ".join(f"{v:.1f}" for v in values)


def to_markdown(rows: Sequence[Mapping[str, Any]], training: Mapping[str, Sequence[float]] | None = None,
                profile: Mapping[str, Mapping[str, Mapping[str, float]]] | None = None) -> str:
    """One line per id and policy (throws/s with resets, the ratio to NetCatch-v0 under the same
    policy, p50 / p99 / max of a step and of a reset), the rows of the models shipped for the ids
    (those with a ``model``) in a table of their own beside; under them, PPO training's env steps/s and
    where each id's time goes (``profile``: id -> policy -> phase -> share)."""
    lines = []
    for column, chosen in (("policy", [r for r in rows if not r.get("model")]),
                           ("shipped model", [r for r in rows if r.get("model")])):
        if not chosen:
            continue
        lines += [*([""] if lines else []), f"| id | {column} | throws | caught | throws/s | vs NetCatch-v0 | "
                  "step p50 / p99 / max (ms) | reset p50 / p99 / max (ms) |", "|---|---|---:|---:|---:|---:|---|---|"]
        lines += [f"| {r['env_id']} | {r.get('model') or r['policy']} | {r['throws']} | {100 * r['capture_rate']:.1f}% | "
                  f"{r['throws_per_s']:.1f} | {r['ratio']:.2f}x | {_tails(r['step_ms'])} | {_tails(r['reset_ms'])} |"
                  for r in chosen]
    if training:
        base = median(training[BASE_ID])
        lines += ["", "| PPO training (SB3, 8 SubprocVecEnv workers, from scratch) | env steps/s | vs NetCatch-v0 |",
                  "|---|---:|---:|"]
        lines += [f"| {env_id} | {median(rates):.0f} | {median(rates) / base:.2f}x |" for env_id, rates in training.items()]
    if profile:
        phases = list(next(iter(next(iter(profile.values())).values())))
        lines += ["", "| id | policy | " + " | ".join(phases) + " |", "|---|---|" + "---:|" * len(phases)]
        lines += [f"| {env_id} | {policy} | " + " | ".join(f"{100 * shares[p]:.0f}%" for p in phases) + " |"
                  for env_id, by_policy in profile.items() for policy, shares in by_policy.items()]
    return "\n".join(lines)


def block(path: Path) -> str:
    """The table of the result file at ``path`` with its source line, or how to make the file."""
    if not path.is_file():
        return f"Not measured yet: `python scripts/bench_variants.py --results {path.name}`."
    record = read_results(path)
    figures = record["figures"]
    left_out = sum(row.get("left_out", 0) for row in figures["rows"])
    return (to_markdown(figures["rows"], figures.get("training"), figures.get("profile")) + "\n\n"
            f"{figures['rounds']} rounds of {figures['episodes_per_round']} episodes per id and policy, one process, "
            f"one numba thread; {figures.get('profile_episodes', 0)} episodes of each profiled; {left_out} timed "
            f"calls left out (numba compiled a kernel during them). Source: `docs/results/{path.name}`, written by `{record['command']}` "
            f"({record['written']}, {record['machine']}).")
