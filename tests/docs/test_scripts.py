"""Smoke tests of the scripts' --quick modes: they run end to end and print their figures."""

from __future__ import annotations

import json
import re
import subprocess
import sys
from pathlib import Path

import gymnasium as gym
import pytest

from agents.bench.env_throughput import SETUPS
from agents.bench.episodes import ROWS
from netgym.bench.results import RESULTS, read_results
from netgym.config import INTEGRATORS

ROOT = Path(__file__).resolve().parents[2]


def _run(*args: str) -> str:
    done = subprocess.run([sys.executable, *args], cwd=ROOT, capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stderr
    return done.stdout


@pytest.mark.slow
def test_bench_sim_quick_prints_every_integrator_and_scene() -> None:
    out = _run("scripts/bench_sim.py", "--quick")
    rows = [line for line in out.splitlines() if line.startswith("| basket") or line.startswith("| goal")]
    assert len(rows) == 2 * len(INTEGRATORS) * 2  # scenes x integrators x workloads


@pytest.mark.slow
def test_bench_episodes_quick_books_the_settling_and_runs_a_candidate_beside_each_row() -> None:
    out = _run("scripts/bench_episodes.py", "--quick", "--candidate", "simulation.settle_dt=0.002")
    rows = [line.split("|") for line in out.splitlines() if line.startswith("| basket") or line.startswith("| goal")]
    assert len(rows) == 2 * len(ROWS)  # every row, with and without the candidate
    assert [cell.strip() for cell in rows[-2][1:4]] == ["basket", "oracle", "1"]  # the best case, in the same run
    oracle_basket, candidate = rows[0], rows[1]
    assert [cell.strip() for cell in rows[2][1:4]] == ["basket", "shipped PPO", "3"]  # what a trained agent pays
    assert oracle_basket[1].strip() == "basket" and candidate[1].strip() == "basket (simulation.settle_dt=0.002)"
    assert oracle_basket[2].strip() == "oracle" and oracle_basket[5].strip() == "100.0%"
    assert float(oracle_basket[6]) > 0 and oracle_basket[8].split("/")[2].strip() != "0"  # pauses happened
    # the same episodes paused at 2 ms instead of 26.9 ms take more settling substeps
    assert float(candidate[8].split("/")[0]) > float(oracle_basket[8].split("/")[0])


def test_python_m_netgym_reports_a_throw() -> None:
    out = _run("-m", "netgym")
    assert "CAPTURED" in out and "substeps" in out


@pytest.mark.slow
def test_python_m_agents_evaluates_the_shipped_model_beside_oracle_and_random() -> None:
    """The main job of the README's first command, on 4 episodes: each policy's capture rate,
    its throughput timed apart from the loading of the kernels and the model."""
    out = _run("-m", "agents", "--episodes", "4")
    rows = {line.split("capture rate")[0].strip(): line for line in out.splitlines() if "capture rate" in line}
    assert list(rows) == ["PPO ppo_netcatch.zip", "oracle", "random"]
    assert "(12/12 throws" in rows["oracle"] and "loaded in" in rows["PPO ppo_netcatch.zip"]
    assert "simulator ready in" in out and all("throws/s" in line for line in rows.values())


@pytest.mark.slow
def test_bench_env_quick_reports_agreement_and_throughput() -> None:
    out = _run("scripts/bench_env.py", "--quick")
    rows = [line for line in out.splitlines() if line.startswith("| basket") or line.startswith("| goal")]
    assert [row.split("|")[1].strip() for row in rows] == ["basket", "goal", "goal, held"]
    for line in rows:
        assert float(line.split("|")[3].strip().rstrip("%")) >= 0.0
    rates = [line.split("|") for line in out.splitlines() if any(label in line for label in SETUPS.values())]
    assert len(rates) == len(SETUPS) and all(float(r[2]) > 0 for r in rates)


@pytest.mark.slow
def test_bench_env_quick_compares_one_case_with_a_finer_reference() -> None:
    out = _run("scripts/bench_env.py", "--quick", "--case", "goal, held", "--reference-dt", "0.00025")
    header, _, row = [line.split("|") for line in out.splitlines() if line.startswith("|")][:3]
    assert header[-3].strip() == "fast agrees with full at 0.00025 s" and row[1].strip() == "goal, held"
    for cell in row[-3:-1]:
        assert 0.0 <= float(cell.strip().rstrip("%")) <= 100.0
    assert "env steps/s" not in out  # one case asked for: the vector environments are left out


@pytest.mark.slow
def test_render_throw_writes_a_gif(tmp_path) -> None:
    from PIL import Image

    target = tmp_path / "throw.gif"
    out = _run("scripts/render_throw.py", "--throws", "1", "--output", str(target))
    assert "wrote" in out
    with Image.open(target) as gif:
        assert gif.n_frames > 10 and gif.size == (480, 360)


@pytest.mark.slow
def test_report_quick_covers_every_section() -> None:
    out = _run("scripts/report.py", "--quick")
    for heading in ("## 1. Work-precision", "## 2. Outcome accuracy", "## 3. Stability limits",
                    "## 4. Throughput", "## 5. Peers", "## 7. Episodes", "## 8. Do the shortcuts change episodes?",
                    "## 9. How near the pause comes to the equilibrium"):
        assert heading in out
    for integrator in INTEGRATORS:
        assert f"| {integrator} |" in out
    assert "NumPy vectorised" in out
    assert "against rk4 at dt = 0.0001 s." in out  # --quick settles its coarser reference in seconds
    assert "| default | 2..N | all | 4 |" in out  # two 3-ball episodes against a fresh reference
    assert "| default (IMEX Euler, 26.9 ms, net inertia 4x, to 0.1 m/s) |" in out


@pytest.mark.slow
def test_variants_table_quick_prints_every_agent() -> None:
    out = _run("scripts/variants_table.py", "--quick", "--workers", "1")
    rows = [line for line in out.splitlines() if line.startswith("| NetCatch")]
    assert len(rows) == 15 and all("% (" in row for row in rows)


def test_variant_rows_are_labelled_as_the_script_labels_them_and_speak_of_wind_only_with_wind() -> None:
    from agents import variants_table

    rows = [(row["variant"], row["agent"]) for name in ("variants.json", "variants_randomized_v1.json")
            for row in read_results(RESULTS / name)["figures"]["rows"]]
    assert rows == [(variant, variants_table.label(variant, agent))
                    for variant, agents in variants_table.VARIANTS.items() for agent in agents]
    for variant, agent in rows:
        assert "wind" not in agent or gym.spec(variant).kwargs.get("wind") is not None, (variant, agent)


@pytest.mark.slow
def test_episode_agreement_quick_compares_every_throw() -> None:
    out = _run("scripts/episode_agreement.py", "--quick", "--candidate", "simulation.settle_speed=0.02")
    rows = {tuple(cell.strip() for cell in line.split("|")[1:4]): line.split("|") for line in out.splitlines()
            if line.startswith("| default") or line.startswith("| simulation.settle_speed=0.02")}
    for pipeline in ("default", "simulation.settle_speed=0.02"):
        assert int(rows[(pipeline, "1", "all")][4]) == 2       # one first throw in each of the 2 episodes
        assert int(rows[(pipeline, "2..N", "all")][4]) == 4    # throws 2 and 3 of both
        assert float(rows[(pipeline, "2..N", "all")][7]) > 0   # throws/s
    assert "Reference: 2 basket episodes of 3 throws" in out


@pytest.mark.slow
def test_pause_accuracy_quick_measures_every_pause_and_a_candidate_from_the_same_nets() -> None:
    from netgym.bench.accuracy.pause_accuracy import PAUSES

    from netgym.physics.simulator import Simulator

    assert f"{Simulator('basket').settle_dt * 1e3:.1f} ms" in list(PAUSES)[0]  # the default's label says its step
    out = _run("scripts/pause_accuracy.py", "--quick", "--candidate",
               "simulation.settle_dt=0.006,simulation.settle_inertia=1")
    main, grouped = (block for block in out.split("\n\n") if block.startswith("| "))
    rows = [line.split("|") for line in main.splitlines() if "---" not in line][1:]
    candidate = "default with simulation.settle_dt=0.006, simulation.settle_inertia=1"
    assert [row[1].strip() for row in rows] == [*PAUSES, candidate]
    by_label = {row[1].strip(): row for row in rows}
    # the candidate's default pause is the 6 ms pause of the net's own inertia, from the same loaded nets: the same errors
    columns = (2, 3, 4, 6)  # nets at rest, not at rest, ball errors, net errors
    assert [by_label[candidate][k] for k in columns] == [by_label["6 ms steps, to 0.1 m/s"][k] for k in columns]
    left_out = int(out.split(" of 2 loaded nets")[0])
    for row in rows:
        assert int(row[2]) + int(row[3]) + left_out == 2  # every net measured, not at rest, or left out
        if int(row[2]) > 0:
            p50, p90, worst = (float(v) for v in row[4].split("/"))
            assert 0.0 <= p50 <= p90 <= worst
    # by ball count: the default pause and the finer reference, each net at rest in exactly one group
    groups = [line.split("|") for line in grouped.splitlines() if "---" not in line][1:]
    assert [row[1].strip() for row in groups] == ["1", "1", "2-4", "2-4", "5-10", "5-10"]
    for label in (list(PAUSES)[0], list(PAUSES)[-1]):
        assert sum(int(row[3]) for row in groups if row[2].strip() == label) == int(by_label[label][2])


@pytest.mark.slow
def test_pile_creep_quick_measures_every_arranged_pile_and_the_loaded_nets() -> None:
    from netgym.bench.accuracy.creep import ARRANGED

    out = _run("scripts/pile_creep.py", "--quick")
    rows = [line.split("|") for line in out.splitlines() if line.startswith("| ") and "---" not in line]
    header, row = rows
    assert [cell.strip() for cell in header[2:2 + len(ARRANGED)]] == [f"{label} (mm)" for label in ARRANGED]
    assert row[1].strip() == "2"
    assert all(float(cell) < 1.0 for cell in row[2:2 + len(ARRANGED)])  # piles at rest stay at rest
    loaded = int(row[2 + len(ARRANGED)])
    assert 1 <= loaded <= 3
    p50, p90, worst = (float(v) for v in row[3 + len(ARRANGED)].split("/"))
    assert 0.0 <= p50 <= p90 <= worst


@pytest.mark.slow
def test_held_goal_phases_quick_times_each_capture_before_its_decision() -> None:
    out = _run("scripts/held_goal_phases.py", "--quick").splitlines()
    captured = int(out[0].split()[0])
    assert captured >= 1 and out[0].endswith(")")  # seed 3's six throws hold captures, reasons counted
    figures = {line.split(":")[0]: [float(v) for v in re.findall(r"(?:p50|p90|max) ([0-9.]+)", line)]
               for line in out[1:]}
    assert len(figures) == 4
    for p50, p90, top in figures.values():
        assert 0.0 <= p50 <= p90 <= top
    decided = figures["decided after"]
    moving = next(v for k, v in figures.items() if k.startswith("ball's horizontal motion ended"))
    bouncing = figures["ball last off the floor (bouncing in place) at"]
    assert moving[2] <= decided[2] and bouncing[2] <= decided[2]  # nothing is sampled after the decision


@pytest.mark.slow
def test_evaluate_reads_the_env_saved_with_a_variant_model() -> None:
    """The windy model is evaluated on NetCatchWindy-v0 with no --env (5 throws an episode)."""
    out = _run("scripts/evaluate.py", "agents/pretrained/ppo_windy.zip", "--episodes", "2")
    assert "ppo_windy.zip on NetCatchWindy-v0: capture rate" in out and "/10 throws" in out


@pytest.mark.slow
def test_evaluate_names_both_envs_when_the_model_cannot_read_the_one_asked_for() -> None:
    done = subprocess.run([sys.executable, "scripts/evaluate.py", "agents/pretrained/ppo_windy.zip", "--env",
                           "NetCatch-v0", "--episodes", "1"], cwd=ROOT, capture_output=True, text=True, timeout=600)
    assert done.returncode == 2 and "Unexpected observation shape" not in done.stderr
    assert "error: agents/pretrained/ppo_windy.zip was trained on NetCatchWindy-v0" in done.stderr
    assert "NetCatch-v0's have shape (7,)" in done.stderr


@pytest.mark.slow
def test_contact_convergence_quick_writes_resumable_results(tmp_path: Path) -> None:
    """The quick run prints every table, writes its result file and draws its figure; started
    again with the same settings it measures nothing more and prints the same tables."""
    results, figure = tmp_path / "convergence.json", tmp_path / "convergence.png"
    out = _run("scripts/contact_convergence.py", "--quick", "--results", str(results), "--plot", str(figure))
    figures = read_results(results)["figures"]
    assert figures["complete"] and len(figures["ensemble"]) == figures["ensemble_size"] == 2
    assert "first 10 ms of contact" in out and "| rk4 |" in out
    assert figure.read_bytes().startswith(b"\x89PNG")
    assert _run("scripts/contact_convergence.py", "--quick", "--results", str(results)) == out


@pytest.mark.slow
def test_model_agreement_quick_runs_both_contact_models_on_the_same_throws() -> None:
    figures = json.loads(_run("scripts/model_agreement.py", "--quick"))
    assert figures["throws"] == 6
    assert set(figures["captured"]) == {"impulse_fast", "impulse_full", "compliant_fast", "compliant_full"}
    assert figures["agreement"]["impulse fast vs impulse full"] == 1.0
    assert 0.0 <= figures["agreement"]["compliant fast vs compliant full"] <= 1.0
    assert all(0.0 < s for s in figures["seconds_per_throw"].values())
    for cost in figures["step_costs"].values():
        assert cost["compliant_us"] > 0.0 and cost["impulse_us"] > 0.0 and cost["compliant_creep_mm"] >= 0.0
