"""Convergence through contact (netgym/bench/accuracy/contact_convergence.py): the work-precision strike
measured by phase (before the first contact, its first 10 ms, the rest) for every integrator
over a ladder of halving steps, against an RK4 reference validated against itself at half its
step; then an ensemble of strikes launched within 3 cm of it, with median and 90th-percentile
errors and fitted slopes. Resumable: every strike's result is kept in the result file the moment
it is done, and a run started again with the same settings measures only the missing ones.

Usage::

    python scripts/contact_convergence.py --results docs/results/contact_convergence.json \
        --plot docs/figures/contact_convergence.png
    python scripts/contact_convergence.py --contact-model compliant --strikes 8 \
        --results docs/results/contact_convergence_compliant.json
    python scripts/contact_convergence.py --quick --results /tmp/convergence.json   # a smoke test
"""

from __future__ import annotations

import argparse
from pathlib import Path

from tqdm import tqdm

from netgym.bench.accuracy.contact_convergence import (ENSEMBLE_OFFSET, REFERENCE_DT, SAMPLE, ensemble_launches,
                                                       ladders_of, measure_strike, summary, warm_up)
from netgym.bench.accuracy.convergence_table import block
from netgym.bench.plots import plot_contact_convergence
from netgym.bench.results import read_results, write_results
from netgym.bench.accuracy.work_precision import STRIKE, STRIKE_SECONDS
from netgym.physics.simulator import Simulator


def main() -> None:
    """Parse arguments, measure what is missing strike by strike, write the result file after each."""
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--strikes", type=int, default=32, help="strikes of the ensemble")
    parser.add_argument("--quick", action="store_true", help="0.3 s strikes, two steps each, 2 strikes")
    parser.add_argument("--results", type=Path, required=True, help="the result file (JSON), resumed if it exists")
    parser.add_argument("--plot", type=Path, help="also draw the ensemble's errors by phase to this PNG")
    parser.add_argument("--contact-model", choices=("impulse", "compliant"), default="impulse")
    args = parser.parse_args()
    ladders = ladders_of(args.contact_model, args.quick)
    seconds, reference_dt = (0.3, REFERENCE_DT * 32) if args.quick else (STRIKE_SECONDS, REFERENCE_DT)
    count = 2 if args.quick else args.strikes
    settings = {"ladders": {k: list(v) for k, v in ladders.items()}, "strike_seconds": seconds, "sample": SAMPLE,
                "reference_dt": reference_dt, "offset": ENSEMBLE_OFFSET, "ensemble_size": count}
    settings.update({"contact_model": args.contact_model} if args.contact_model != "impulse" else {})
    kept = _resumable(args.results, settings)
    launches = [STRIKE, *ensemble_launches(count)]
    sim = Simulator("basket", {"simulation.contact_model": args.contact_model}, check_stability=False)
    warm_up(sim, ladders)
    runs_per_strike = 2 + sum(len(v) for v in ladders.values())
    bar = tqdm(total=runs_per_strike * (len(launches) - len(kept)), desc="runs of every strike", unit="run")
    for i in range(len(kept), len(launches)):
        kept.append(measure_strike(sim, launches[i], ladders, seconds, reference_dt, progress=bar.update))
        figures = {**settings, "strike": kept[0], "ensemble": kept[1:], "complete": len(kept) == len(launches)}
        write_results(args.results, figures)
    bar.close()
    print(block(args.results))
    if args.plot is not None:
        figures = read_results(args.results)["figures"]
        plot_contact_convergence(summary(figures["ensemble"] or [figures["strike"]]), args.plot)


def _resumable(path: Path, settings: dict) -> list[dict]:
    """The strikes already measured in the result file at ``path`` with the same ``settings``."""
    if not path.is_file():
        return []
    figures = read_results(path)["figures"]
    if any(figures.get(key) != value for key, value in settings.items()):
        return []
    return [figures["strike"], *figures["ensemble"]]


if __name__ == "__main__":
    main()
