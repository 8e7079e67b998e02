"""The benchmark report, speed against error: every section measured in one run
(:func:`measure`) and its markdown text (:func:`to_markdown`), as ``scripts/report.py`` writes
it to docs/BENCHMARKS.md."""

from __future__ import annotations

import math
import platform
from dataclasses import dataclass
from pathlib import Path

from tqdm import tqdm

from netgym.bench import (
    convergence_table,
    creep,
    episode_agreement,
    episodes,
    pause_accuracy,
    roofline,
    sim_throughput,
    speed_table,
)
from netgym.bench.env_throughput import SETUPS, env_throughput
from netgym.bench.fast_path import CASES, compare, summarise
from netgym.bench.outcomes import outcome_accuracy
from netgym.bench.peers import peers
from netgym.bench.results import RESULTS, read_results
from netgym.bench.report_text import (
    AGREEMENT_NOTES,
    AGREEMENT_TEXT,
    ALIGNED_PASS_TEXT,
    BROAD_PHASE_TEXT,
    COMPILED_LOOPS_TEXT,
    CONTACT_CONVERGENCE_NOTES,
    CONTACT_CONVERGENCE_TEXT,
    CONTACT_ORDER_TEXT,
    CREEP_TEXT,
    DAMPER_SHARES_TEXT,
    DECIDED_EARLY_TEXT,
    EPISODES_NOTES,
    EPISODES_TEXT,
    ERROR_MODEL_TEXT,
    FAST_PATH_TEXT,
    FLIGHT_TEXT,
    HELD_AGREEMENT_TEXT,
    INERTIA_TEXT,
    NATIVE_VECTOR_ENV_TEXT,
    NOTHING_TO_SETTLE_TEXT,
    OFFSET_GROUPS_TEXT,
    OUT_OF_PLAY_TEXT,
    PAUSE_ACCURACY_NOTES,
    PAUSE_ACCURACY_TEXT,
    PAUSE_TEXT,
    PILE_FRICTION_TEXT,
    ROOFLINE_TEXT,
    VARIANT_SPEED_TEXT,
    STATIC_PAUSE_TEXT,
    STEP_LIMIT_TEXT,
    SUBSTEPS_TEXT,
    UNSIGNED_INDEX_TEXT,
    WAVEFRONT_TEXT,
)
from netgym.bench.settings import DEFAULT, PEER_SETTING, QUICK_REFERENCE, REFERENCE
from netgym.bench.stability_limits import stability_limits
from netgym.bench.throws import sample_throws
from netgym.bench.work_precision import SAMPLE, STRIKE, STRIKE_SECONDS, work_precision


@dataclass(frozen=True)
class Report:
    """The figures of every section, from one run."""

    count: int                              # throws of the outcome-accuracy section
    reference: tuple[str, float]            # (integrator, dt) of the work-precision reference
    work_precision: list[dict]
    outcomes: list[dict]
    stability: list[dict]
    peers: list[dict]
    sim_table: str                          # sim_throughput's markdown table
    fast_path: dict[str, dict[str, float]]  # scene -> fast_path.summarise figures
    vector_envs: dict[str, float]           # env_throughput.SETUPS key -> env steps/s
    episodes: str                           # episodes.to_markdown's table
    agreement: str                          # episode agreement table (default and the pause at 2 ms)
    pause: str                              # pause_accuracy.to_markdown's tables
    creep: str                              # creep.to_markdown's table


def _agreement(quick: bool, reference: Path | None) -> str:
    """Section 8: the default pipeline and the pause at the scene's own step (``settle_dt`` 2 ms)
    against the stored reference episodes (against two fresh 3-ball ones when ``quick`` or none is
    stored)."""
    if quick or reference is None or not reference.is_file():
        scene, ref = "basket", episode_agreement.reference("basket", 2, 3, workers=1)
    else:
        scene, ref = episode_agreement.load(reference)
    return episode_agreement.agreement_table(
        scene, ref, [("default", {}), ("simulation.settle_dt=0.002", {"simulation.settle_dt": 0.002})], workers=1)


def measure(quick: bool, count: int, reference: Path | None = None) -> Report:
    """Run every section (small sweeps and few throws with ``quick``); ``count`` throws for the
    outcome-accuracy section; ``reference``: the stored reference episodes of section 8. A
    progress bar on stderr counts the sections."""
    reference_setting = QUICK_REFERENCE if quick else REFERENCE
    sections = {
        "work-precision": lambda: work_precision(quick, reference_setting),
        "outcome accuracy": lambda: outcome_accuracy(count, quick),
        "stability limits": lambda: stability_limits(quick),
        "peers": lambda: peers(quick, reference_setting),
        "simulator throughput": lambda: sim_throughput.to_markdown(sim_throughput.run(quick)),
        "fast path": lambda: {label: summarise(compare(scene, sample_throws(scene, 2 if quick else 300), 1, overrides))
                              for label, (scene, overrides) in CASES.items()},
        "vector environments": lambda: env_throughput(8, 2 if quick else 30),
        "episodes": lambda: episodes.to_markdown(episodes.run_rows(2 if quick else 60, [None])),
        "episode agreement": lambda: _agreement(quick, reference),
        "pause accuracy": lambda: pause_accuracy.to_markdown(pause_accuracy.pause_accuracy(2 if quick else 200,
                                                                                           progress=False)),
        "pile creep": lambda: creep.to_markdown(creep.creep(creep.QUICK_DTS if quick else creep.DTS,
                                                            creep.QUICK_NETS if quick else creep.NETS,
                                                            progress=False)),
    }
    results = []
    with tqdm(sections.items(), desc="report", unit="section") as bar:
        for name, run in bar:
            bar.set_postfix_str(name)
            results.append(run())
    return Report(count, reference_setting, *results)


def _env_table(report: Report) -> str:
    """Section 4's environment tables."""
    env_rows = [f"| {scene} | {s['throws']} | {100 * s['agreement']:.1f}% | {s['fast_throws_per_s']:.1f} | "
                f"{s['full_throws_per_s']:.2f} | {s['touching']} | {s['fast_touching_throws_per_s']:.1f} |"
                for scene, s in report.fast_path.items()]
    return "\n".join(
        ["| scene | throws | fast/full agreement | fast throws/s | full throws/s | throws touching the net | "
         "fast throws/s on those |", "|---|---:|---:|---:|---:|---:|---:|", *env_rows, "",
         "| 8 environments, basket, noisy oracle actions | env steps/s |", "|---|---:|",
         *[f"| {SETUPS[kind]} | {rate:.1f} |" for kind, rate in report.vector_envs.items()]])


def _gains(report: Report) -> list[str]:
    """Section 6: what the optimisations bought, as ratios of the measured figures."""
    basket, peer_rows = report.fast_path["basket"], report.peers
    default = next(r for r in report.outcomes if (r["integrator"], r["dt"]) == DEFAULT)
    explicit = next(r for r in report.outcomes if (r["integrator"], r["dt"]) == PEER_SETTING)
    return [
        f"- Fast path (closed-form flight, sleeping net, early decision) over full simulation to the time limit: "
        f"{basket['fast_throws_per_s'] / basket['full_throws_per_s']:.0f}x throws/s on the basket "
        f"({100 * basket['agreement']:.1f}% outcome agreement).",
        f"- numba kernels (fused spring loop, contacts with a bounding-box broad phase) over vectorised NumPy: "
        f"{peer_rows[0]['steps_per_s'] / peer_rows[1]['steps_per_s']:.0f}x steps/s at the same error.",
        SUBSTEPS_TEXT,
        f"- IMEX Euler (elastic forces explicit, dampers and drag implicit), which the dampers no longer hold below "
        f"1 ms: the default at {DEFAULT[1] * 1e3:g} ms decides {default['throws_per_s'] / explicit['throws_per_s']:.1f}x "
        f"the throws/s of {PEER_SETTING[0]} at {PEER_SETTING[1] * 1e3:g} ms ({100 * default['agreement']:.1f}% vs "
        f"{100 * explicit['agreement']:.1f}% outcome agreement, section 2).",
        "- Exact ball-to-net clearance (distance to the spring segments instead of the nearest particle less half the "
        "longest spring) for closed-form flight and for putting the net back to sleep, with the per-check decision "
        "data (speeds near the ball, bounding box, sleep test) gathered in one numba pass instead of NumPy "
        "expressions: on 300 throws (seed 0) with symplectic Euler at 0.5 ms, substeps per touching throw 231 -> 116, "
        "Python time per touching throw 1.57 -> 0.66 ms, touching throws/s 130 -> 263 (measured before and after "
        "the change that introduced them, same machine).",
        WAVEFRONT_TEXT,
        ERROR_MODEL_TEXT,
        DAMPER_SHARES_TEXT,
        UNSIGNED_INDEX_TEXT,
        OFFSET_GROUPS_TEXT,
        ALIGNED_PASS_TEXT,
        NOTHING_TO_SETTLE_TEXT,
        PAUSE_TEXT,
        STEP_LIMIT_TEXT,
        INERTIA_TEXT,
        COMPILED_LOOPS_TEXT,
        FLIGHT_TEXT,
        NATIVE_VECTOR_ENV_TEXT,
        CONTACT_ORDER_TEXT,
        OUT_OF_PLAY_TEXT,
        BROAD_PHASE_TEXT,
        DECIDED_EARLY_TEXT,
        PILE_FRICTION_TEXT,
        ROOFLINE_TEXT,
        STATIC_PAUSE_TEXT,
    ]


def to_markdown(report: Report) -> str:
    """The report's text (docs/BENCHMARKS.md)."""
    wp, outcomes, stability, peer_rows = report.work_precision, report.outcomes, report.stability, report.peers
    sim_table, env_table, count, gains = report.sim_table, _env_table(report), report.count, _gains(report)
    out = [
        "# Benchmarks: speed against error",
        "",
        f"Generated by `python scripts/report.py` on {platform.machine()}, Python {platform.python_version()}, "
        "float64; every figure of a table comes from one run on one core of the project's 2-core machine "
        "(compare ratios within a table, not across machines).",
        "",
        "## 1. Work-precision",
        "",
        f"Scenario: the default basket at rest; a ball launched from {STRIKE[0].tolist()} m at "
        f"{STRIKE[1].tolist()} m/s strikes the bottom of the net; {STRIKE_SECONDS} s simulated. Reference: "
        f"{report.reference[0]} at dt = {report.reference[1]:g} s. Ball error: RMS over the strike (sampled every {SAMPLE} s) of "
        "the distance to the reference ball; net error: RMS distance of the particles to the reference at the end. "
        "Contacts are resolved after each step (non-smooth), which limits every integrator to first order "
        "once the ball touches the net.",
        "",
        "![work-precision](figures/work_precision.png)",
        "",
        "| integrator | dt (ms) | ball error (m) | net error (m) | wall s per simulated s |",
        "|---|---:|---:|---:|---:|",
    ]
    for r in wp:
        if r["diverged"]:
            out.append(f"| {r['integrator']} | {r['dt'] * 1e3:g} | diverged | diverged | - |")
        else:
            out.append(f"| {r['integrator']} | {r['dt'] * 1e3:g} | {r['ball_error']:.2e} | {r['net_error']:.2e} | "
                       f"{r['wall_per_sim_s']:.3f} |")
    out += [
        "",
        "## 2. Outcome accuracy",
        "",
        f"{count} seeded throws (half uniform-random actions, half the ballistic oracle's plus noise), each into "
        "the empty basket, each decided by the fast path. Reference outcomes: rk4 at dt = 0.1 ms. The default "
        f"setting is {DEFAULT[0]} at {DEFAULT[1] * 1e3:g} ms.",
        "",
        "![outcome accuracy](figures/outcome_accuracy.png)",
        "",
        "| integrator | dt (ms) | outcome agreement | throws/s | diverged |",
        "|---|---:|---:|---:|---:|",
    ]
    for r in outcomes:
        mark = " **(default)**" if (r["integrator"], r["dt"]) == DEFAULT else ""
        out.append(f"| {r['integrator']}{mark} | {r['dt'] * 1e3:g} | {100 * r['agreement']:.1f}% | "
                   f"{r['throws_per_s']:.1f} | {r['diverged']} |")
    out += [
        "",
        "## 3. Stability limits",
        "",
        "Largest dt at which 1 s of the net (perturbed by 1 cm noise from rest, no ball) stays below the "
        "divergence speed, by bisection on a log scale between 0.01 ms and 50 ms, beside the linear estimate "
        "(spectral radius of each method's step on the net's fastest mode, found by power iteration; for "
        "imex_euler, whose dampers are a Gauss-Seidel sweep rather than a force, the linearised step on the whole "
        "net, its sweep included: stable while lambda_max(h^2 F K F^T - 2 F F^T + 2 I) < 2 + 2 / keep, F the "
        "forward damper pass; `netgym/physics/stability.py`). The pause between throws steps at 90% of its "
        "integrator's estimate.",
        "",
        "| scene | integrator | bisection | linear estimate |",
        "|---|---|---:|---:|",
    ]
    for r in stability:
        found = ">= 50 ms (largest tried)" if r["bisection"] >= 5e-2 else f"{r['bisection'] * 1e3:.3g} ms"
        linear = "unconditional" if math.isinf(r["linear"]) else f"{r['linear'] * 1e3:.3g} ms"
        out.append(f"| {r['scene']} | {r['integrator']} | {found} | {linear} |")
    out += ["", "## 4. Throughput", "", "Simulator (`scripts/bench_sim.py`):", "", sim_table, "",
            "Environment (`scripts/bench_env.py`):", "", env_table, "", HELD_AGREEMENT_TEXT, "", FAST_PATH_TEXT, "",
            "## 5. Peers", "",
            "The same net (604 particles, 3250 springs, same masses, springs, dampers, drag and gravity), released "
            f"from its built shape, {PEER_SETTING[1] * 1e3:g} ms steps, error against the same rk4 reference after the "
            "same simulated time. The NumPy version is a straightforward vectorised implementation (gather, "
            "`np.add.at` scatter). MuJoCo (`pip install -e .[bench]`) models each free particle as a body with "
            "three slide joints (joint damping = air drag), each spring as a spatial tendon between two sites "
            "(stiffness ks, damping kd, spring length = rest length), fixed particles as world sites, contacts "
            "off, its Euler integrator (dampers implicit). None has contacts in this test (the net touches nothing).",
            "",
            "| system | steps/s | RMS error vs reference (m) | speed-up of netgym |", "|---|---:|---:|---:|"]
    ours = peer_rows[0]["steps_per_s"]
    for r in peer_rows:
        out.append(f"| {r['system']} | {r['steps_per_s']:,.0f} | {r['error']:.2e} | {ours / r['steps_per_s']:.1f}x |")
    out += ["", "## 6. What the optimisations bought (ratios of the figures above)", "", *gains]
    out += ["", "## 7. Episodes", "", EPISODES_TEXT, "", report.episodes, "", EPISODES_NOTES]
    out += ["", "## 8. Do the shortcuts change episodes?", "", AGREEMENT_TEXT, "", report.agreement, "", AGREEMENT_NOTES]
    out += ["", "## 9. How near the pause comes to the equilibrium", "", PAUSE_ACCURACY_TEXT, "", report.pause, "", PAUSE_ACCURACY_NOTES,
            "", CREEP_TEXT, "", report.creep]
    out += ["", "## 10. The spring pass against its roofline", "", ROOFLINE_TEXT, "", "<!-- quote:roofline -->",
            _roofline_table(), "<!-- /quote:roofline -->"]
    out += ["", "## 11. Every id's speed", "", VARIANT_SPEED_TEXT, "", "<!-- quote:variant-speed -->",
            speed_table.block(RESULTS / "variant_speed.json"), "<!-- /quote:variant-speed -->"]
    out += ["", "## 12. Convergence through contact", "", CONTACT_CONVERGENCE_TEXT, "",
            "![contact convergence](figures/contact_convergence.png)", "", "<!-- quote:contact-convergence -->", convergence_table.block(RESULTS / "contact_convergence.json"),
            "<!-- /quote:contact-convergence -->", "", CONTACT_CONVERGENCE_NOTES]
    return "\n".join(out) + "\n"


def _roofline_table() -> str:
    """Section 10's table, from the roofline's result file (written by ``scripts/roofline.py``)."""
    path = RESULTS / "roofline.json"
    if not path.is_file():
        return "No roofline measured yet: `python scripts/roofline.py --results docs/results/roofline.json`."
    return roofline.to_markdown(read_results(path))
