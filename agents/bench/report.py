"""The benchmark report, speed against error: every section measured in one run
(:func:`measure`), its figures kept in a result file (:func:`save`, :func:`load`) and its
markdown text (:func:`to_markdown`), as ``scripts/report.py`` writes it to docs/BENCHMARKS.md."""

from __future__ import annotations

import dataclasses
import math
import platform
from dataclasses import dataclass
from pathlib import Path

from tqdm import tqdm

from agents.bench import episode_agreement, episodes
from agents.bench.env_throughput import SETUPS, env_throughput
from agents.bench.outcomes import outcome_accuracy
from agents.bench.report_text import (
    AGREEMENT_NOTES,
    AGREEMENT_TEXT,
    COMPLIANT_CONVERGENCE_NOTES,
    COMPLIANT_CONVERGENCE_TEXT,
    CONTACT_CONVERGENCE_NOTES,
    CONTACT_CONVERGENCE_TEXT,
    CREEP_NOTES,
    CREEP_TEXT,
    DESIGN_ITEMS,
    DESIGN_TEXT,
    ENV_THROUGHPUT_TEXT,
    EPISODES_NOTES,
    EPISODES_TEXT,
    HELD_GOAL_TEXT,
    INTRO_TEXT,
    LOAD_TEXT,
    OUTCOMES_NOTES,
    PAUSE_ACCURACY_NOTES,
    PAUSE_ACCURACY_TEXT,
    PEERS_TEXT,
    REJECTED_ITEMS,
    REJECTED_TEXT,
    ROOFLINE_TEXT,
    SIM_THROUGHPUT_TEXT,
    VARIANT_SPEED_NOTES,
    VARIANT_SPEED_TEXT,
)
from netgym.bench.accuracy import convergence_table, creep, model_agreement, pause_accuracy
from netgym.bench.accuracy.contact_convergence import RESULT_FILES
from netgym.bench.accuracy.fast_path import CASES, compare, summarise
from netgym.bench.accuracy.stability_limits import stability_limits
from netgym.bench.accuracy.work_precision import SAMPLE, STRIKE, STRIKE_SECONDS, work_precision
from netgym.bench.results import RESULTS, read_results, write_results
from netgym.bench.settings import DEFAULT, PEER_SETTING, QUICK_REFERENCE, REFERENCE
from netgym.bench.speed import roofline, sim_throughput, speed_table
from netgym.bench.speed.peers import peers
from netgym.bench.throws import sample_throws

REPORT_RESULTS = RESULTS / "report.json"
"""Where a full run keeps the figures of sections 1-9, which ``scripts/report.py --render`` renders."""


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


def save(report: Report, path: Path = REPORT_RESULTS) -> dict:
    """Write ``report``'s figures to the result file ``path``; returns the record written (the
    figures, the command, when and where it ran)."""
    return read_results(write_results(path, dataclasses.asdict(report)))


def load(path: Path = REPORT_RESULTS) -> tuple[Report, dict]:
    """The report a full run kept at ``path``, and its record."""
    record = read_results(path)
    return Report(**{**record["figures"], "reference": tuple(record["figures"]["reference"])}), record


def _row(rows: list[dict], setting: tuple[str, float]) -> dict | None:
    """The row of ``rows`` for ``setting`` (integrator, dt), if it was measured."""
    return next((r for r in rows if (r["integrator"], r["dt"]) == setting), None)


def _header(record: dict | None) -> list[str]:
    """The title, what the page is, and where and how its figures were measured (``record``: the
    result file's; None for a quick run, which writes nothing)."""
    if record is None:
        run = (f"A quick run (small sweeps, few throws) on {platform.machine()}, Python {platform.python_version()}, "
               "that writes nothing.")
    else:
        run = f"Sections 1-9: one run of `{record['command']}`, {record['written']}, {record['machine']}."
    return ["# Benchmarks: speed against error", "", INTRO_TEXT, "", f"{run} {LOAD_TEXT}"]


def _work_precision(report: Report) -> list[str]:
    """Section 1: error against wall time of every integrator over its dt sweep."""
    out = ["## 1. Work-precision", "",
           f"The error of every integrator over a sweep of dt, against its cost (`netgym/bench/accuracy/work_precision.py`). "
           f"The default basket at rest; a ball launched from {STRIKE[0].tolist()} m at {STRIKE[1].tolist()} m/s "
           f"strikes the bottom of the net; {STRIKE_SECONDS} s simulated, against {report.reference[0]} at dt = "
           f"{report.reference[1]:g} s. Ball error: RMS over the strike (sampled every {SAMPLE} s) of the distance to "
           "the reference's ball; net error: RMS distance of the net's particles to the reference's at the end; "
           "cost: wall seconds per simulated second.",
           "", "![work-precision](figures/work_precision.png)", "",
           "| integrator | dt (ms) | ball error (m) | net error (m) | wall s per simulated s |",
           "|---|---:|---:|---:|---:|"]
    for r in report.work_precision:
        if r["diverged"]:
            out.append(f"| {r['integrator']} | {r['dt'] * 1e3:g} | diverged | diverged | - |")
        else:
            out.append(f"| {r['integrator']} | {r['dt'] * 1e3:g} | {r['ball_error']:.2e} | {r['net_error']:.2e} | "
                       f"{r['wall_per_sim_s']:.3f} |")
    meaning = ("Contacts are resolved after each step, as impulses and position projections, so once the ball "
               "touches the net every integrator is first order (section 12 splits the error by phase): a higher "
               "order buys no accuracy here, only cost.")
    default = _row(report.work_precision, DEFAULT)
    if default is not None and not default["diverged"]:
        meaning += (f" The default, {DEFAULT[0]} at {DEFAULT[1] * 1e3:g} ms, leaves {default['ball_error']:.1e} m on "
                    f"the ball at {default['wall_per_sim_s']:.3f} wall s per simulated second; section 2 shows what "
                    "that error does to outcomes.")
    return [*out, "", meaning]


def _outcomes(report: Report) -> list[str]:
    """Section 2: outcome agreement with a fine reference against throws per second."""
    out = ["## 2. Outcome accuracy", "",
           "Whether a throw's outcome, caught or not, is the one a converged simulation gives, and how many throws a "
           f"second each setting decides (`agents/bench/outcomes.py`): {report.count} seeded throws (seed 99; half "
           "uniform-random actions, half the ballistic oracle's plus noise), each into the empty basket and decided "
           "by the fast path, against the outcomes of rk4 at dt = 0.1 ms. `diverged` counts the throws a setting "
           f"could not simulate. The default setting is {DEFAULT[0]} at {DEFAULT[1] * 1e3:g} ms.",
           "", "![outcome accuracy](figures/outcome_accuracy.png)", "",
           "| integrator | dt (ms) | outcome agreement | throws/s | diverged |", "|---|---:|---:|---:|---:|"]
    for r in report.outcomes:
        mark = " **(default)**" if (r["integrator"], r["dt"]) == DEFAULT else ""
        out.append(f"| {r['integrator']}{mark} | {r['dt'] * 1e3:g} | {100 * r['agreement']:.1f}% | "
                   f"{r['throws_per_s']:.1f} | {r['diverged']} |")
    lowest, default = min(report.outcomes, key=lambda r: r["agreement"]), _row(report.outcomes, DEFAULT)
    return [*out, "",
            f"Every setting agrees with the reference on at least {100 * lowest['agreement']:.1f}% of the throws "
            f"({lowest['integrator']} at {lowest['dt'] * 1e3:g} ms), the default on {100 * default['agreement']:.1f}% "
            f"at {default['throws_per_s']:.1f} throws/s. {OUTCOMES_NOTES}"]


def _stability(report: Report) -> list[str]:
    """Section 3: the largest stable dt by bisection beside the linear estimate."""
    out = ["## 3. Stability limits", "",
           "The largest dt at which 1 s of the net (perturbed by 1 cm noise from rest, no ball) stays below the "
           "divergence speed, by bisection on a log scale between 0.01 ms and 50 ms "
           "(`netgym/bench/accuracy/stability_limits.py`), beside the linear estimate: the spectral radius of each method's "
           "step on the net's fastest mode, found by power iteration; for imex_euler, whose dampers are a Gauss-Seidel sweep rather than a force, the "
           "linearised step on the whole net, its sweep included: stable while lambda_max(h^2 F K F^T - 2 F F^T + "
           "2 I) < 2 + 2 / keep, F the forward damper pass (`netgym/physics/stability.py`).",
           "", "| scene | integrator | bisection | linear estimate |", "|---|---|---:|---:|"]
    for r in report.stability:
        found = ">= 50 ms (largest tried)" if r["bisection"] >= 5e-2 else f"{r['bisection'] * 1e3:.3g} ms"
        linear = "unconditional" if math.isinf(r["linear"]) else f"{r['linear'] * 1e3:.3g} ms"
        out.append(f"| {r['scene']} | {r['integrator']} | {found} | {linear} |")
    bounded = [r for r in report.stability if math.isfinite(r["linear"]) and r["bisection"] < 5e-2]
    gap = max(abs(r["bisection"] / r["linear"] - 1) for r in bounded)
    scene = report.stability[0]["scene"]
    limits = {r["integrator"]: r["linear"] for r in report.stability if r["scene"] == scene}
    return [*out, "",
            f"The linear estimate is within {100 * gap:.0f}% of the bisection wherever there is a limit, so netgym "
            "computes it instead of simulating: to refuse a `dt` beyond it, and to step the pause between throws at "
            f"90% of it. Implicit Euler is unconditionally stable; IMEX Euler, implicit in its dampers and drag, is "
            f"stable to {limits['imex_euler'] * 1e3:.3g} ms on the {scene} net, "
            f"{limits['imex_euler'] / limits['explicit_euler']:.0f}x explicit Euler."]


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


def _throughput(report: Report) -> list[str]:
    """Section 4: the simulator's and the environment's throughput."""
    basket, envs = report.fast_path["basket"], report.vector_envs
    lowest = min(s["agreement"] for s in report.fast_path.values())
    return ["## 4. Throughput", "", SIM_THROUGHPUT_TEXT, "", report.sim_table, "", ENV_THROUGHPUT_TEXT, "",
            _env_table(report), "",
            f"The fast path and the full simulation agree on at least {100 * lowest:.1f}% of the throws in every case, "
            "so what the fast path saves (section 6) costs no outcomes. A throw that touches the net costs more (on "
            f"the basket {basket['fast_touching_throws_per_s']:.1f} against {basket['fast_throws_per_s']:.1f} "
            "throws/s): the net is then integrated until the outcome is known. For 8 environments SB3's "
            f"`SubprocVecEnv` steps {envs['subproc'] / envs['sync']:.1f}x the env steps/s of a Gymnasium "
            "`SyncVectorEnv` in one process, on 2 cores.", "", HELD_GOAL_TEXT]


def _peers(report: Report) -> list[str]:
    """Section 5: the same net in other implementations."""
    ours = report.peers[0]["steps_per_s"]
    rows = [f"| {r['system']} | {r['steps_per_s']:,.0f} | {r['error']:.2e} | {ours / r['steps_per_s']:.1f}x |"
            for r in report.peers]
    return ["## 5. Peers", "", f"{PEERS_TEXT} Every system steps {PEER_SETTING[1] * 1e3:g} ms.", "",
            "| system | steps/s | RMS error vs reference (m) | speed-up of netgym |", "|---|---:|---:|---:|", *rows,
            "", "The NumPy version runs the same method as netgym and errs the same, so its speed-up is what the "
            "compiled kernels buy; MuJoCo's Euler with implicit dampers is another method, with an error of its own."]


def _design(report: Report) -> list[str]:
    """Section 6: what the shortcuts and kernels buy, and the alternatives measured and rejected."""
    basket, peer_rows = report.fast_path["basket"], report.peers
    default, explicit = _row(report.outcomes, DEFAULT), _row(report.outcomes, PEER_SETTING)
    return [
        "## 6. What the optimisations bought", "", DESIGN_TEXT, "",
        f"- The fast path (closed-form flight, sleeping net, early decision) over full simulation to the time limit: "
        f"{basket['fast_throws_per_s'] / basket['full_throws_per_s']:.0f}x throws/s on the basket "
        f"({100 * basket['agreement']:.1f}% outcome agreement, section 4).",
        f"- numba kernels (fused spring loop, contacts with a bounding-box broad phase) over vectorised NumPy: "
        f"{peer_rows[0]['steps_per_s'] / peer_rows[1]['steps_per_s']:.0f}x steps/s at the same error (section 5).",
        f"- IMEX Euler (elastic forces explicit, dampers and drag implicit): the default at {DEFAULT[1] * 1e3:g} ms "
        f"decides {default['throws_per_s'] / explicit['throws_per_s']:.1f}x the throws/s of {PEER_SETTING[0]} at "
        f"{PEER_SETTING[1] * 1e3:g} ms, {100 * default['agreement']:.1f}% against {100 * explicit['agreement']:.1f}% "
        "outcome agreement (section 2).",
        *DESIGN_ITEMS, "", REJECTED_TEXT, "", *REJECTED_ITEMS]


def to_markdown(report: Report, record: dict | None = None) -> str:
    """The report's text (docs/BENCHMARKS.md); ``record``: the result file that keeps ``report``
    (None for a quick run)."""
    out = [*_header(record), "", *_work_precision(report), "", *_outcomes(report), "", *_stability(report), "",
           *_throughput(report), "", *_peers(report), "", *_design(report)]
    out += ["", "## 7. Episodes", "", EPISODES_TEXT, "", report.episodes, "", EPISODES_NOTES]
    out += ["", "## 8. Do the shortcuts change episodes?", "", AGREEMENT_TEXT, "", report.agreement, "",
            AGREEMENT_NOTES]
    out += ["", "## 9. How near the pause comes to the equilibrium", "", PAUSE_ACCURACY_TEXT, "", report.pause, "",
            PAUSE_ACCURACY_NOTES, "", CREEP_TEXT, "", report.creep, "", CREEP_NOTES]
    out += ["", "## 10. The spring pass against its roofline", "", ROOFLINE_TEXT, "", "<!-- quote:roofline -->",
            _roofline_table(), "<!-- /quote:roofline -->"]
    out += ["", "## 11. Every id's speed", "", VARIANT_SPEED_TEXT, "", "<!-- quote:variant-speed -->",
            speed_table.block(RESULTS / "variant_speed.json"), "<!-- /quote:variant-speed -->", "", VARIANT_SPEED_NOTES]
    out += ["", "## 12. Convergence through contact", "", CONTACT_CONVERGENCE_TEXT, "",
            "![contact convergence](figures/contact_convergence.png)", "", "<!-- quote:contact-convergence -->",
            contact_convergence("impulse"), "<!-- /quote:contact-convergence -->", "",
            CONTACT_CONVERGENCE_NOTES, "", "### The compliant contact model", "", COMPLIANT_CONVERGENCE_TEXT, "",
            "<!-- quote:compliant-convergence -->", contact_convergence("compliant"),
            "<!-- /quote:compliant-convergence -->", "", COMPLIANT_CONVERGENCE_NOTES, "",
            "<!-- quote:model-agreement -->", model_agreement_quote(), "<!-- /quote:model-agreement -->"]
    return "\n".join(out) + "\n"


def contact_convergence(contact_model: str) -> str:
    """Section 12's tables of one contact model (``"impulse"``, ``"compliant"``), from its result file."""
    flags = "" if contact_model == "impulse" else f"--contact-model {contact_model} "
    return convergence_table.block(RESULTS / RESULT_FILES[contact_model], flags)


def model_agreement_quote() -> str:
    """Section 12's line on the two contact models' outcomes, from its result file."""
    return model_agreement.block(RESULTS / "model_agreement.json")


def _roofline_table() -> str:
    """Section 10's table, from the roofline's result file (written by ``scripts/roofline.py``)."""
    path = RESULTS / "roofline.json"
    if not path.is_file():
        return "No roofline measured yet: `python scripts/roofline.py --results docs/results/roofline.json`."
    return roofline.to_markdown(read_results(path))
