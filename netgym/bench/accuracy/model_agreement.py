"""The two contact models on the same throws: the compliant model's full simulation against
the impulse model's default (the fast path) and its own full simulation, each throw from the
settled empty basket."""

from __future__ import annotations

import time
from pathlib import Path
from typing import Any

from netgym.bench.accuracy.fast_path import Throw, throw_each
from netgym.bench.results import read_results

COMPLIANT = {"simulation.contact_model": "compliant"}


def model_agreement(throws: list[Throw], workers: int = 1) -> dict[str, Any]:
    """Outcomes of ``throws`` by the impulse model's fast path and full simulation and by the
    compliant model's full simulation: the catches of each, the shares of equal outcomes, the
    seconds a throw each took and the throws whose outcomes differ between the models."""
    runs, seconds = {}, {}
    for label, overrides, fast in (("impulse_fast", None, True), ("impulse_full", None, False),
                                   ("compliant_full", COMPLIANT, False)):
        throw_each("basket", throws[:1], 1, overrides, fast)  # compile before the clock starts
        start = time.perf_counter()
        runs[label] = [r.captured for r in throw_each("basket", throws, workers, overrides, fast)]
        seconds[label] = (time.perf_counter() - start) * workers / len(throws)

    def agree(a: str, b: str) -> float:
        return sum(x == y for x, y in zip(runs[a], runs[b])) / len(throws)

    return {"throws": len(throws), "captured": {label: sum(r) for label, r in runs.items()},
            "agreement": {"compliant vs impulse fast": agree("compliant_full", "impulse_fast"),
                          "compliant vs impulse full": agree("compliant_full", "impulse_full"),
                          "impulse fast vs impulse full": agree("impulse_fast", "impulse_full")},
            "seconds_per_throw": seconds,
            "differ": [i for i, (a, b) in enumerate(zip(runs["compliant_full"], runs["impulse_full"])) if a != b]}


def block(path: Path) -> str:
    """The report's sentence on the two models' outcomes, from the result file at ``path``, or
    how to make it."""
    if not path.is_file():
        return f"Not measured yet: `python scripts/model_agreement.py --results docs/results/{path.name}`."
    record = read_results(path)
    f = record["figures"]
    agreement, captured, seconds = f["agreement"], f["captured"], f["seconds_per_throw"]
    return (f"Outcomes of {f['throws']} sampled basket throws, each from the settled empty net: the compliant "
            f"model's full simulation caught {captured['compliant_full']}, the impulse model's fast path "
            f"{captured['impulse_fast']} and its full simulation {captured['impulse_full']}; the compliant outcome "
            f"equals the impulse default's on {100 * agreement['compliant vs impulse fast']:.1f}% of them (the "
            f"impulse fast path its own full simulation's on {100 * agreement['impulse fast vs impulse full']:.1f}%). "
            f"A throw took {seconds['compliant_full']:.2f} s simulated fully with the compliant model, "
            f"{seconds['impulse_full']:.2f} s with the impulse model and {seconds['impulse_fast']:.3f} s by its fast "
            f"path, one core. Source: `docs/results/{path.name}`, written by `{record['command']}` "
            f"({record['written']}, {record['machine']}).")
