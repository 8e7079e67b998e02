"""The baselines' statistics and report (agents/baselines/: stats.py, cells.py, analysis.py,
tables.py, report.py) against known answers: result files written with known outcomes, read back
as the report reads them. The bootstraps run on few resamples here (``REPS``); the report itself
takes rliable's defaults."""

from __future__ import annotations

import json
import re
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

from agents.baselines import analysis, report, stats, tables
from agents.baselines.cells import Cells, best_learners, digest, learners, ranking, set_scores, task_sets, throw_rates
from agents.baselines.grid import REFERENCES
from agents.evaluation import wilson_interval
from netgym.bench.results import write_results

REPS = 200
"""Bootstrap resamples in these tests."""
WINDY, RANDOMIZED, PIXELS = "NetCatchWindy-v0", "NetCatchRandomized-v1", "NetCatchPixels-v0"
ID = re.compile(r"NetCatch\w*-v\d")


def _outcomes(captured: int, episodes: int, throws: int) -> list[str]:
    """``episodes`` outcomes of ``throws`` throws each, ``captured`` of them caught, filled
    throw index by throw index (all first throws before any second one)."""
    grid = np.zeros((throws, episodes), dtype=int)
    grid.flat[:captured] = 1
    return ["".join(map(str, grid[:, e])) for e in range(episodes)]


def _record(algorithm: str, env_id: str, seed: int, outcomes: list[str] | None = None, *,
            by_throw: list[int] | None = None, episodes: int | None = None, commit: str = "a" * 40,
            tree_clean: bool | None = True) -> dict:
    """A result record as scripts/baselines.py writes it, with these episode outcomes (or, as the
    older runs recorded, captures by throw index alone, or neither)."""
    if outcomes is not None:
        episodes = len(outcomes)
        by_throw = [sum(episode[k] == "1" for episode in outcomes) for k in range(len(outcomes[0]))]
    captured, throws = sum(by_throw), episodes * len(by_throw)
    low, high = wilson_interval(captured, throws)
    reference = algorithm in REFERENCES
    budget = 0 if reference else 512
    final = {"episodes": episodes, "seed": 1_000_000, "deterministic": True, "rate": captured / throws,
             "captured": captured, "throws": throws, "low": low, "high": high, "by_throw": by_throw,
             **({"outcomes": outcomes} if outcomes is not None else {})}
    return {"algorithm": algorithm, "env_id": env_id, "seed": seed, "budget": budget, "final_episodes": episodes,
            "versions": {"python": "3.11.7", "torch": "2.13.0", "commit": commit, "tree_clean": tree_clean},
            "machine": "x86_64, test", "started": f"2026-12-08T0{seed % 10}:00:00+00:00", "wall_s": 120.0,
            "cpu_s": 110.0, "env_steps": budget, "hyperparams": {} if reference else {"n_envs": 2},
            **({} if reference else {"env_seeds": [1000 * seed, 1000 * seed + 1]}),
            "curve": {"episodes": 0 if reference else 2, "seed": 2_000_000,
                      "points": [] if reference else [[0, 0.0, 0.0], [256, captured / throws / 2, 1.0],
                                                      [512, captured / throws, 2.0]]},
            "final": final}


def _write(out: Path, record: dict) -> None:
    write_results(out / record["algorithm"] / record["env_id"] / f"seed_{record['seed']}.json", record,
                  command=["scripts/baselines.py"])


def _cell(out: Path, algorithm: str, env_id: str, captured: list[int], episodes: int = 100, throws: int = 1) -> None:
    """One run per seed 0, 1, ... with these captures."""
    for seed, caught in enumerate(captured):
        _write(out, _record(algorithm, env_id, seed, _outcomes(caught, episodes, throws)))


def _references(out: Path, env_id: str, random: int = 5, blind: int = 50, oracle: int = 100, episodes: int = 100,
                throws: int = 1) -> None:
    for name, caught in (("random", random), ("blind", blind), ("oracle", oracle)):
        _write(out, _record(name, env_id, 0, _outcomes(caught * throws, episodes, throws)))


@pytest.fixture
def table(tmp_path: Path) -> Path:
    """A small table: sac clearly ahead of ppo on NetCatch-v0, ppo and sac a coin flip on
    NetCatchGoal-v0; on the windy task (5 throws) those two and rppo, sac_asym (10 seeds);
    rppo also on NetCatchRandomized-v1, sac_asym also on pixels, with sac_drq."""
    _cell(tmp_path, "sac", "NetCatch-v0", [95, 96, 97, 98, 99])
    _cell(tmp_path, "ppo", "NetCatch-v0", [50, 52, 55, 58, 60])
    _cell(tmp_path, "sac", "NetCatchGoal-v0", [90, 92, 94, 96, 98])
    _cell(tmp_path, "ppo", "NetCatchGoal-v0", [91, 93, 95, 97, 99])
    for algorithm, captured in (("ppo", [80, 82, 84, 86, 88]), ("sac", [85, 86, 87, 88, 89]),
                                ("rppo", [88, 89, 90, 91, 92]), ("sac_asym", [90 + k % 5 for k in range(10)])):
        _cell(tmp_path, algorithm, WINDY, [5 * c for c in captured], episodes=100, throws=5)
    _cell(tmp_path, "rppo", RANDOMIZED, [300, 310, 320, 330, 340], episodes=100, throws=5)
    _cell(tmp_path, "sac_asym", PIXELS, [100] * 5)
    _cell(tmp_path, "sac_drq", PIXELS, [60, 70, 80, 90, 95])
    for env_id, throws in (("NetCatch-v0", 1), ("NetCatchGoal-v0", 1), (WINDY, 5), (RANDOMIZED, 5), (PIXELS, 1)):
        _references(tmp_path, env_id, throws=throws)
    return tmp_path


def _statistics(out: Path) -> tuple[Cells, analysis.Stats]:
    cells = analysis.load_cells(out)
    return cells, analysis.statistics(cells, REPS)


def _blocks(cells: Cells, found: analysis.Stats) -> list[str]:
    return [tables.matrix(cells, found), tables.improvement(cells, found), tables.aggregates(cells, found),
            tables.table(cells, found), tables.protocol(cells, found),
            *(tables.by_throw(cells, env_id, found) for env_id in (WINDY, RANDOMIZED))]


def _row(text: str, label: str) -> list[str]:
    """The cells of the first table row of ``text`` whose first cell contains ``label``."""
    for line in text.splitlines():
        cells = [cell.strip() for cell in line.strip().strip("|").split("|")]
        if line.startswith("|") and label in cells[0]:
            return cells
    raise AssertionError(f"no row {label!r} in\n{text}")


def test_a_references_interval_is_wilsons_over_its_throws(table: Path) -> None:
    """The windy blind oracle caught 250 of 500 throws: its cell is 50.0 with the Wilson interval
    of 250/500 (about 45.6-54.4), not a bootstrap of its one run (a zero-width interval)."""
    cells, found = _statistics(table)
    low, high = wilson_interval(250, 500)
    expected = f"50.0 [{100 * low:.1f}, {100 * high:.1f}]"
    assert high - low > 0.08
    references = tables.matrix(cells, found).split("References")[1]
    assert _row(references, WINDY)[2] == expected
    assert f"{WINDY}</span> | *blind* (1 run) | {expected} |" in tables.table(cells, found)


def test_the_aggregate_tables_have_every_learner_in_each_common_task_set_it_ran(table: Path) -> None:
    """Sets: the vector tasks ppo and sac ran, the two feedback tasks (rppo), the windy task
    (sac_asym's vector part) and pixels (sac_asym, sac_drq); a learner is in a set's column when
    it ran every task of the set, and every learner has a row."""
    cells, found = _statistics(table)
    assert task_sets(cells) == [("NetCatch-v0", "NetCatchGoal-v0", WINDY), (WINDY, RANDOMIZED), (WINDY,),
                                (PIXELS,)]
    text = tables.aggregates(cells, found)
    iqm, gap = text.split("Optimality gap")
    for part in (iqm, gap):
        assert [_row(part, algo)[0] for algo in learners(cells)] == ["ppo", "sac", "rppo", "sac_asym", "sac_drq"]
    members = {algo: [cell != "-" for cell in _row(iqm, algo)[1:]] for algo in learners(cells)}
    assert members["ppo"] == members["sac"] == [True, False, True]
    assert members["rppo"] == [False, True, True] and members["sac_asym"] == [False, False, True]
    assert "sac_drq" in gap.split("|---|")[-1] and _row(gap.split(PIXELS)[-1], "sac_drq")[1] != "-"


def test_an_aggregate_takes_the_seeds_every_task_of_its_set_has(table: Path) -> None:
    """sac_asym has 10 windy seeds and 5 pixel ones: alone on the windy task it brings all 10, and
    each set's matrix is rectangular; the caption names the exception."""
    cells, found = _statistics(table)
    seeds = {tuple(s["tasks"]): {algo: m["seeds"] for algo, m in s["learners"].items()} for s in found["sets"]}
    assert seeds[WINDY,]["sac_asym"] == list(range(10)) and seeds[WINDY,]["ppo"] == list(range(5))
    scores = set_scores(cells, ("NetCatch-v0", "NetCatchGoal-v0", WINDY))
    assert {algo: matrix.shape for algo, (_, matrix) in scores.items()} == {"ppo": (5, 3), "sac": (5, 3)}
    assert "0-9 of sac_asym" in tables.aggregates(cells, found)


def test_a_clear_leader_is_bold_and_a_coin_flip_is_not(table: Path) -> None:
    """On NetCatch-v0 every sac seed beats every ppo seed: P(sac > ppo) = 1 [1, 1], sac in bold.
    On NetCatchGoal-v0 ppo's seeds interleave sac's (P = 15/25 = 0.6, its interval holds 0.5):
    neither is bold, and the probability table says why."""
    cells, found = _statistics(table)
    winners = analysis.clear_winners(found)
    assert winners["NetCatch-v0"] == "sac" and "NetCatchGoal-v0" not in winners
    matrix = tables.matrix(cells, found)
    assert _row(matrix, "NetCatch-v0</span>")[2].startswith("**97.0 [")
    assert not any("**" in cell for cell in _row(matrix, "NetCatchGoal-v0"))
    improvement = tables.improvement(cells, found)
    assert _row(improvement, "NetCatch-v0</span>")[1:] == ["sac", "ppo", "**1.00 [1.00, 1.00]**"]
    goal = _row(improvement, "NetCatchGoal-v0")
    assert goal[1:3] == ["ppo", "sac"] and goal[3].startswith("0.60 [") and float(goal[3][6:10]) <= 0.5


def test_the_probability_of_improvement_of_identical_scores_is_one_half() -> None:
    same = np.array([[0.5], [0.7], [0.9], [0.6]])
    better = same + 1.0
    found = stats.improvement_intervals({"same": (same, same), "better": (better, same)}, reps=REPS)
    assert found["same"][0] == 0.5 and found["same"][1] <= 0.5 <= found["same"][2]
    assert found["better"] == (1.0, 1.0, 1.0)


def test_the_iqm_and_its_interval_are_rliables(table: Path) -> None:
    """Of 1..8 the IQM is the mean of 3..6 (4.5); a constant's interval is that constant; the
    normalised interval is rliable's interval of the normalised scores (the same resamples)."""
    found = stats.iqm_intervals({"ramp": np.arange(1.0, 9.0), "flat": np.full(8, 0.7)}, reps=REPS)
    assert found["ramp"][0] == pytest.approx(4.5) and found["ramp"][1] < 4.5 < found["ramp"][2]
    assert found["flat"] == pytest.approx((0.7, 0.7, 0.7))
    raw = np.array([0.55, 0.61, 0.58, 0.7, 0.52])
    scaled = stats.iqm_intervals({"x": stats.normalise(raw, 0.1, 0.9)}, reps=REPS)["x"]
    assert scaled == pytest.approx(tuple(stats.normalise(stats.iqm_intervals({"x": raw}, reps=REPS)["x"], 0.1, 0.9)))
    assert stats.iqm_intervals({"one": np.array([0.3])}, reps=REPS)["one"] == (0.3, None, None)


def test_rates_by_throw_are_iqms_over_the_runs_that_counted_them(tmp_path: Path) -> None:
    """Four windy runs of 10 episodes caught throw 1 in 5, 6, 7, 8 of them (one counted from its
    outcomes alone, as the newer runs record them) and every later throw: IQM 65.0 on throw 1, 100
    on the others. A fifth run that counted nothing is left out (n=4)."""
    for seed, first in enumerate((8, 5, 7)):
        _write(tmp_path, _record("sac", WINDY, seed, by_throw=[first, 10, 10, 10, 10], episodes=10))
    _write(tmp_path, _record("sac", WINDY, 3, ["11111"] * 6 + ["01111"] * 4))
    old = _record("sac", WINDY, 4, by_throw=[9, 9, 9, 9, 9], episodes=10)
    del old["final"]["by_throw"]
    _write(tmp_path, old)
    _references(tmp_path, WINDY, throws=5, episodes=10)
    cells, found = _statistics(tmp_path)
    text = tables.by_throw(cells, WINDY, found)
    assert _row(text, "rate in %")[1] == "sac (n=4)"
    first = _row(text, "throw 1")[1]
    assert first.startswith("65.0 [") and float(first[6:10]) < 65.0 < float(first.split(", ")[1][:-1])
    assert _row(text, "throw 2")[1] == "100.0 [100.0, 100.0]" and _row(text, "throws 2-5")[1].startswith("100.0")
    low, high = wilson_interval(5, 10)  # random: 25 catches of 50, throw index by throw index: 10, 10, 5, 0, 0
    assert _row(text.split("*random*")[1], "throw 3")[1] == f"50.0 [{100 * low:.1f}, {100 * high:.1f}]"
    assert "No run on NetCatch-v0" in tables.by_throw(cells, "NetCatch-v0", found)


def test_every_id_in_a_table_never_breaks_at_its_hyphens(table: Path) -> None:
    cells, found = _statistics(table)
    lines = [line for block in _blocks(cells, found) for line in block.splitlines() if line.startswith("|")]
    assert sum(len(ID.findall(line)) for line in lines) > 40
    for line in lines:
        bare = ID.findall(re.sub(r'<span style="white-space:nowrap">[^<]*</span>', "", line))
        assert bare == [], line


def test_protocol_names_its_commit_or_warns_of_several_and_of_changed_trees(table: Path) -> None:
    cells, found = _statistics(table)
    text = tables.protocol(cells, found)
    assert f"Commit: `{'a' * 10}` (every run)." in text and "Warning" not in text
    learning = sum(len(records) for (algo, _), records in cells.items() if algo not in REFERENCES)
    assert f"seeded 1000 k + i (a resumed run's next workers the next ones of its block of 1000) in {learning} of " \
           f"the {learning} learner runs that record them." in text
    assert "sac_drq" not in _row(text, PIXELS)[1]
    _write(table, _record("sac_drq", PIXELS, 5, _outcomes(90, 100, 1), commit="b" * 40, tree_clean=False))
    cells = analysis.load_cells(table)
    text = tables.protocol(cells, analysis.statistics(cells, REPS))
    assert "**Warning:** the runs come from 2 commits, not one" in text
    assert "**Warning:** 1 runs ran on a tree with uncommitted changes" in text
    assert _row(text, PIXELS)[2] == "0-4; sac_drq: 0-5"


def test_a_shipped_models_rate_comes_with_its_wilson_interval(tmp_path: Path) -> None:
    _write(tmp_path / "baselines", _record("rppo", RANDOMIZED, 0, _outcomes(400, 100, 5)))
    text = tables.shipped(tmp_path, {"rppo_randomized_v1.zip": f"baselines/rppo/{RANDOMIZED}/seed_0"})
    low, high = wilson_interval(400, 500)
    assert _row(text, "rppo_randomized_v1.zip")[2:] == [f"80.0 [{100 * low:.1f}, {100 * high:.1f}]", "100.0", "75.0"]


def test_the_report_writes_its_tables_statistics_and_figures_at_page_width(table: Path) -> None:
    written = report.write_report(table, reps=30)
    text = written.read_text()
    names = ["curves-vector.png", "curves-feedback.png", "curves-pixels.png", "profiles.png"]
    for name in names:
        assert f"]({name})" in text
        width, height = Image.open(table / name).size
        assert 700 <= width <= 800 and height < 900
    assert json.loads((table / analysis.STATS_FILE).read_text())["digest"] == digest(analysis.load_cells(table))
    assert "## Probability of improvement" in text and "Optimality gap" in text


def test_stored_statistics_serve_only_the_records_they_were_computed_from(table: Path, monkeypatch) -> None:
    """The statistics written beside the results are read back instead of computed while the
    records are those; one record changed, they are computed again."""
    report.write_report(table, reps=30)
    stored = json.loads((table / analysis.STATS_FILE).read_text())
    analysis._STORED.clear()

    def refuse(*args, **kwargs):
        raise AssertionError("computed again")

    monkeypatch.setattr(analysis, "iqm_intervals", refuse)
    assert analysis.statistics(analysis.load_cells(table), 30) == stored
    _write(table, _record("sac", "NetCatch-v0", 0, _outcomes(90, 100, 1)))
    with pytest.raises(AssertionError, match="computed again"):
        analysis.statistics(analysis.load_cells(table), 30)


def _runs(algorithm: str, env_id: str, rates: list[float]) -> list[dict]:
    """Result records of one cell with these final rates (seeds 0, 1, ...)."""
    return [{"algorithm": algorithm, "env_id": env_id, "seed": seed, "budget": 512, "final": {"rate": rate}}
            for seed, rate in enumerate(rates)]


def test_the_best_learner_has_the_highest_iqm_and_ties_go_to_more_seeds_then_the_mean(monkeypatch) -> None:
    monkeypatch.setattr(analysis, "DEFAULT_REPS", REPS)
    cells = {("ppo", "NetCatch-v0"): _runs("ppo", "NetCatch-v0", [0.1, 0.9, 0.9, 0.9, 0.9]),
             ("sac", "NetCatch-v0"): _runs("sac", "NetCatch-v0", [0.9, 0.9, 0.9, 0.9, 0.95]),
             ("td3", "NetCatch-v0"): _runs("td3", "NetCatch-v0", [0.9, 0.9, 0.9]),
             ("ppo", "NetCatchGoal-v0"): _runs("ppo", "NetCatchGoal-v0", [0.5, 0.6, 0.7, 0.8]),
             ("random", "NetCatch-v0"): _runs("random", "NetCatch-v0", [1.0])}
    assert best_learners(cells) == {"NetCatch-v0": ["sac"], "NetCatchGoal-v0": ["ppo"]}  # not the reference
    tied = {**cells, ("tqc", "NetCatch-v0"): _runs("tqc", "NetCatch-v0", [0.9, 0.9, 0.9, 0.9, 0.95])}
    assert best_learners(tied)["NetCatch-v0"] == ["sac", "tqc"]
    assert ranking(tied, "NetCatch-v0") == ["sac", "tqc", "ppo", "td3"]
    assert tables.best_line(tied, "NetCatch-v0").startswith("sac, tqc (tied): 90.0% [90.0, ")
    assert tables.best_line(cells, "NetCatchGoal-v0").startswith("ppo: 65.0% [") and "over 4 seeds at 512" in \
        tables.best_line(cells, "NetCatchGoal-v0")
    assert tables.best_line(cells, "NetCatchPixels-v0") == "none trained yet"


def test_the_baselines_pages_words_hold_in_the_committed_results() -> None:
    """docs/baselines.md says in words that the long windy runs trained longer than the table's,
    and that at the table's budget sac_asym has the highest IQM of the windy task's throws 2-5."""
    from rliable import metrics

    root = Path(__file__).resolve().parents[2]
    results = root / "docs" / "results"
    text = " ".join((root / "docs" / "baselines.md").read_text().split())
    assert "`sac_asym` already has the highest IQM of the windy task's throws 2-5" in text
    assert "trained longer" in text
    table, long = analysis.load_cells(results / "baselines"), analysis.load_cells(results / "baselines_long")
    later = {algo: metrics.aggregate_iqm([rates[-1] for r in table[algo, WINDY]
                                          if (rates := throw_rates(r["final"])) is not None])
             for algo in learners(table) if (algo, WINDY) in table
             and any(throw_rates(r["final"]) is not None for r in table[algo, WINDY])}
    assert max(later, key=later.get) == "sac_asym" and len(later) > 1
    assert long["sac_asym", WINDY][0]["budget"] > table["sac_asym", WINDY][0]["budget"]
