"""Speed against error: the project's benchmark report -> docs/BENCHMARKS.md + docs/figures/.

Sections 1-9 are measured in one full run, on one core unless stated, and their figures kept in
docs/results/report.json; sections 10-12 quote the result files of their own scripts:

1. work-precision: every integrator over a sweep of dt, error against a fine RK4 reference
   versus wall time per simulated second, on the default scene with a ball striking the net;
2. outcome accuracy: per (integrator, dt), the fraction of seeded throws whose capture outcome
   matches the reference, against throws per second;
3. stability limits: the largest stable dt of each integrator by bisection, on the default and
   a stiff scene, beside the linear-stability estimate;
4. throughput: substeps/s, ns per spring per substep, throws/s with and without the fast path,
   8 environments in a Gymnasium SyncVectorEnv and in SB3's SubprocVecEnv;
5. peers: the same net in a NumPy vectorised implementation, same dt, same reference;
6. what the design buys, as ratios of the above, and the alternatives rejected;
7. whole episodes (step times, the pause booked);
8. episode agreement: the default pipeline against the stored reference episodes;
9. the pause against a fine relaxation of the same loaded nets, and how far balls at rest in
   piles still move;
10. the spring pass against its roofline; 11. every id's speed; 12. convergence through contact.

Usage::

    python scripts/report.py            # full run (about 16 minutes): docs/results/report.json, the page, figures
    python scripts/report.py --render   # rewrite docs/BENCHMARKS.md from the result files, measuring nothing
    python scripts/report.py --quick    # small sweeps, prints to stdout, writes nothing
"""

from __future__ import annotations

import argparse
from pathlib import Path

from netgym.bench.plots import plot_outcomes, plot_work_precision
from agents.bench.report import load, measure, save, to_markdown


def main() -> None:
    """Run every section and write the result file, docs/BENCHMARKS.md and figures (print only,
    with --quick); or, with --render, write docs/BENCHMARKS.md from the result file."""
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    mode = parser.add_mutually_exclusive_group()
    mode.add_argument("--quick", action="store_true")
    mode.add_argument("--render", action="store_true", help="measure nothing: render the page from the result file")
    parser.add_argument("--throws", type=int, default=1000, help="throws for the outcome-accuracy section")
    parser.add_argument("--docs", type=Path, default=Path("docs"))
    args = parser.parse_args()
    results = args.docs / "results" / "report.json"
    if args.render:
        (args.docs / "BENCHMARKS.md").write_text(to_markdown(*load(results)))
        print(f"rendered {args.docs / 'BENCHMARKS.md'} from {results}")
        return
    report = measure(args.quick, 4 if args.quick else args.throws, args.docs / "figures" / "episode_reference.json")
    if args.quick:
        print(to_markdown(report))
        return
    text = to_markdown(report, save(report, results))
    (args.docs / "figures").mkdir(parents=True, exist_ok=True)
    plot_work_precision(report.work_precision, args.docs / "figures" / "work_precision.png")
    plot_outcomes(report.outcomes, args.docs / "figures" / "outcome_accuracy.png")
    (args.docs / "BENCHMARKS.md").write_text(text)
    print(text)


if __name__ == "__main__":
    main()
