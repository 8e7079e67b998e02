"""The baselines' runner (agents/baselines, scripts/baselines.py): the grid and its hyperparameter
files, and a runner killed and started again (the statistics and the report:
test_baselines_report.py)."""

from __future__ import annotations

import inspect
import importlib
import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from agents.baselines import grid as grid_module
from agents.baselines.grid import ALGORITHMS, BUDGETS, LEFT_OUT, REFERENCES, TRAIN_SEED_STRIDE, grid, table_budget
from agents.baselines.runner import done, missing
from agents.baselines.tables import nowrap
from agents.hyperparams import action_noise, algorithm_kwargs, env_ids, load, yml
from agents.policies import policy_in_env, saved_algorithm
from netgym.bench.results import read_results, write_results
from netgym.errors import InvalidArgumentError

ROOT = Path(__file__).resolve().parents[2]


@pytest.mark.parametrize("algorithm", sorted(ALGORITHMS))
def test_every_algorithms_settings_are_arguments_of_its_class(algorithm: str) -> None:
    """Each yml has settings for ids of the grid only, each setting is rl_zoo3's or an argument
    of the algorithm's class, and its noise makes SB3 action noise."""
    module, name = ALGORITHMS[algorithm]
    parameters = {}
    for cls in getattr(importlib.import_module(module), name).__mro__:  # a subclass passes **kwargs on to its base
        own = inspect.signature(cls).parameters
        parameters.update(own)
        if not any(p.kind is inspect.Parameter.VAR_KEYWORD for p in own.values()):
            break
    assert env_ids(yml(algorithm)) and set(env_ids(yml(algorithm))) <= set(BUDGETS)
    for env_id in env_ids(yml(algorithm)):
        settings = load(yml(algorithm), env_id)
        assert set(algorithm_kwargs(settings)) <= set(parameters)
        noise = action_noise(settings, 3)
        assert (noise is None) == ("noise_type" not in settings) and ("action_noise" in parameters or noise is None)


def test_grid_gives_every_algorithm_its_ids_budget_and_each_id_its_references() -> None:
    runs = grid()
    learners = [run for run in runs if run.algorithm not in REFERENCES]
    assert {run.algorithm for run in learners} == set(ALGORITHMS) - set(LEFT_OUT)
    assert all(run.budget == table_budget(run.env_id) and run.env_id in env_ids(yml(run.algorithm))
               for run in learners)
    ids = {run.env_id for run in runs}
    assert {(run.algorithm, run.env_id) for run in runs if run.algorithm in REFERENCES} == \
        {(reference, env_id) for reference in REFERENCES for env_id in ids}
    assert len({run.path(Path("out")) for run in runs}) == len(runs)
    for run in learners:  # PPO's rollouts end on the budget
        settings = load(yml(run.algorithm), run.env_id)
        assert run.budget % (settings.get("n_envs", 1) * settings.get("n_steps", 1)) == 0


def test_grid_refuses_unknown_names() -> None:
    with pytest.raises(InvalidArgumentError, match="algorithm"):
        grid(["dqn"])
    with pytest.raises(InvalidArgumentError, match="env id"):
        grid(ids=["CartPole-v1"])


def test_a_budget_replaces_the_ids_and_a_runs_command_repeats_it() -> None:
    longer = grid(["sac"], ["NetCatchWindy-v0"], [3], budget=40_960)
    learner = next(run for run in longer if run.algorithm == "sac")
    assert learner.budget == 40_960 and all(run.budget == 0 for run in longer if run.algorithm in REFERENCES)
    assert learner.command(Path("out"))[-2:] == ["--budget", "40960"]
    table_run = next(run for run in grid(["sac"], ["NetCatchWindy-v0"], [3]) if run.algorithm == "sac")
    assert "--budget" not in table_run.command(Path("out"))
    for wrong in (0, -512, 1.5):
        with pytest.raises(InvalidArgumentError, match="budget"):
            grid(["sac"], budget=wrong)


def test_evaluating_a_cells_saved_models_names_the_folder_that_has_none(tmp_path: Path) -> None:
    from agents.baselines.runner import evaluate_saved

    with pytest.raises(InvalidArgumentError, match="no saved models under .*models/sac/NetCatch-v0"):
        evaluate_saved(tmp_path, "sac", "NetCatch-v0", 1, 0)


def test_an_env_wrapper_setting_names_a_training_wrapper() -> None:
    from agents.hyperparams import env_wrapper
    from netgym.wrappers import HiddenState

    assert env_wrapper({}) is None and env_wrapper({"env_wrapper": "netgym.wrappers.HiddenState"}) is HiddenState
    with pytest.raises(InvalidArgumentError, match="env_wrapper"):
        env_wrapper({"env_wrapper": "os.system"})


def test_a_run_is_done_only_with_a_complete_result_file_of_its_protocol(tmp_path: Path) -> None:
    run = grid(quick=True)[0]
    assert missing([run], tmp_path) == [run]
    run.path(tmp_path).parent.mkdir(parents=True)
    run.path(tmp_path).write_text('{"figures": {"fin')  # cut short: never what write_results leaves
    assert not done(run, tmp_path)
    final = {"rate": 1.0, "episodes": run.final_episodes, "seed": grid_module.FINAL_SEED}
    for other, wrong in (({"budget": run.budget + 512}, f"{run.budget + 512} steps"),
                         ({"final": {**final, "episodes": 100}}, "100 final episodes"),
                         ({"final": {**final, "seed": 10_000}}, "seeded from 10000")):
        write_results(run.path(tmp_path), {"budget": run.budget, "final": final, **other})  # another protocol's
        with pytest.raises(InvalidArgumentError, match=f"another protocol \\(.*{wrong}.*\\), not .*--out"):
            done(run, tmp_path)  # refused, never overwritten
    write_results(run.path(tmp_path), {"budget": run.budget, "final": final})
    assert done(run, tmp_path) and missing([run], tmp_path) == []


def test_no_two_runs_share_a_training_episode_stream_and_none_meets_the_evaluations() -> None:
    from agents.baselines.runs import RESUME_STRIDE

    streams = {}
    for run in grid():
        if run.budget:
            n_envs = load(yml(run.algorithm), run.env_id).get("n_envs", 1)
            assert n_envs <= RESUME_STRIDE
            first = TRAIN_SEED_STRIDE * run.seed
            streams[run.name] = set(range(first, first + TRAIN_SEED_STRIDE))  # with every resumption's
    by_cell: dict[tuple[str, str], list[set[int]]] = {}
    for name, seeds in streams.items():
        algorithm, env_id, _ = name.split("/")
        by_cell.setdefault((algorithm, env_id), []).append(seeds)
    for blocks in by_cell.values():
        assert sum(map(len, blocks)) == len(set().union(*blocks))
    everything = set().union(*streams.values())
    assert max(everything) < min(grid_module.FINAL_SEED, grid_module.CURVE_SEED)
    assert grid_module.FINAL_SEED + grid_module.FINAL_EPISODES <= grid_module.CURVE_SEED
    with pytest.raises(InvalidArgumentError, match="seeds \\[1000\\]"):
        grid(["sac"], ["NetCatch-v0"], [1000])


def test_a_result_records_each_episodes_outcome_its_commit_and_a_relative_command(tmp_path: Path) -> None:
    from agents.baselines.runs import execute

    reference = next(run for run in grid(["sac"], ["NetCatchWindy-v0"], quick=True) if run.algorithm == "blind")
    record = execute(reference)
    final = record["final"]
    assert len(final["outcomes"]) == final["episodes"] == reference.final_episodes
    assert all(len(episode) == 5 and set(episode) <= {"0", "1"} for episode in final["outcomes"])
    assert final["captured"] == sum(episode.count("1") for episode in final["outcomes"])
    assert list(final["by_throw"]) == [sum(episode[k] == "1" for episode in final["outcomes"]) for k in range(5)]
    versions = record["versions"]
    assert len(versions["commit"]) == 40 and isinstance(versions["tree_clean"], bool) and versions["numba"]
    out = ROOT / "runs" / "some-table"
    assert reference.command(out)[:3] == ["scripts/baselines.py", "--out", "runs/some-table"]
    assert not any(part.startswith("/") for part in reference.command(tmp_path))


@pytest.mark.slow
def test_a_learner_killed_mid_training_resumes_from_its_checkpoint(tmp_path: Path, monkeypatch) -> None:
    """A checkpoint at every rollout; the run dies after its third: run again, it goes on from
    the third's steps (its curve kept, new episode streams), ends on its budget, and its
    checkpoint is gone once its result is in."""
    from agents.baselines import checkpoints
    from agents.baselines.runs import execute

    run = next(run for run in grid(["sac"], ["NetCatch-v0"], quick=True) if run.algorithm == "sac")
    monkeypatch.setattr(checkpoints, "EVERY_S", 0.0)
    written, write = [], checkpoints.Checkpointer.write

    def write_then_die(self) -> None:
        write(self)
        written.append(self.model.num_timesteps)
        if len(written) == 3:
            raise KeyboardInterrupt("killed")

    monkeypatch.setattr(checkpoints.Checkpointer, "write", write_then_die)
    with pytest.raises(KeyboardInterrupt):
        execute(run, tmp_path)
    folder = checkpoints.checkpoint_folder(tmp_path, run.name)
    state = checkpoints.load_state(folder)
    assert state["steps"] == written[-1] > 0 and state["resumed_at"] == []
    monkeypatch.setattr(checkpoints.Checkpointer, "write", write)
    monkeypatch.setattr(checkpoints, "EVERY_S", 1e9)
    record = execute(run, tmp_path)
    assert record["resumed_at"] == [written[-1]] and record["env_steps"] == run.budget
    assert record["env_seeds"] == [TRAIN_SEED_STRIDE * run.seed, TRAIN_SEED_STRIDE * run.seed + 8]
    steps = [point[0] for point in record["curve"]["points"]]
    assert steps == sorted(set(steps)) and steps[0] == 0 and steps[-1] == run.budget
    kept = state["curve"]["points"]
    assert [list(point) for point in record["curve"]["points"][:len(kept)]] == kept
    assert record["cpu_s"] >= state["spent"]["cpu_s"] and not folder.exists()
    assert (tmp_path / "models" / f"{run.name}.zip").is_file()


def test_a_failed_run_is_reported_and_the_others_are_written(tmp_path: Path, monkeypatch) -> None:
    from agents.baselines import runner

    failing, passing = grid(quick=True)[:2]
    final = {"rate": 1.0, "episodes": passing.final_episodes, "seed": grid_module.FINAL_SEED}
    outcomes = [(failing, ValueError("boom")), (passing, {"budget": passing.budget, "final": final, "wall_s": 1.0})]
    monkeypatch.setattr(runner, "_local", lambda runs, workers, out: iter(outcomes))
    lines: list[str] = []
    with pytest.raises(RuntimeError, match=failing.name):
        runner.run_missing([failing, passing], tmp_path, report=lines.append)
    assert done(passing, tmp_path) and not done(failing, tmp_path)
    assert any("FAILED" in line and "boom" in line for line in lines)


def _children(pid: int) -> list[int]:
    """Process ids whose parent is ``pid``."""
    found = []
    for stat in Path("/proc").glob("[0-9]*/stat"):
        try:
            fields = stat.read_text().rsplit(")", 1)[1].split()
        except OSError:
            continue
        if int(fields[1]) == pid:
            found.append(int(stat.parent.name))
    return found


def _results(out: Path) -> dict[Path, bytes]:
    return {path: path.read_bytes() for path in sorted(out.rglob("seed_*.json")) if "checkpoints" not in path.parts}


@pytest.mark.slow
def test_runner_killed_and_started_again_runs_only_the_missing_runs(tmp_path: Path) -> None:
    """SIGKILL the runner once its first result lands: its workers end with it, every result
    file left is complete, and the runner started again runs exactly the missing runs, leaving
    those files as they were, and writes the report."""
    out = tmp_path / "out"
    command = [sys.executable, "scripts/baselines.py", "--quick", "--out", str(out), "--algos", "ppo", "sac",
               "--ids", "NetCatch-v0", "--workers", "2"]
    runs = grid(["ppo", "sac"], ["NetCatch-v0"], quick=True)
    first = subprocess.Popen(command, cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
    deadline = time.monotonic() + 300
    while not _results(out) and time.monotonic() < deadline and first.poll() is None:
        time.sleep(0.2)
    workers = _children(first.pid)
    first.send_signal(signal.SIGKILL)
    first.wait()
    before = _results(out)
    assert 1 <= len(before) < len(runs), "the first runner ended before it was killed"
    assert all("final" in json.loads(text)["figures"] for text in before.values())
    deadline = time.monotonic() + 30
    while any(Path(f"/proc/{pid}").exists() for pid in workers) and time.monotonic() < deadline:
        time.sleep(0.2)
    assert not any(Path(f"/proc/{pid}").exists() for pid in workers), "a worker outlived the killed runner"
    after = subprocess.run(command, cwd=ROOT, capture_output=True, text=True, timeout=600)
    assert after.returncode == 0, after.stderr[-3000:]
    assert f"{len(before)} of {len(runs)} runs done" in after.stdout
    assert after.stdout.count("% captured") == len(runs) - len(before)
    results = _results(out)
    assert {path: results[path] for path in before} == before  # none rerun
    assert set(results) == {run.path(out) for run in runs}  # none lost
    for run in runs:
        record = read_results(run.path(out))
        figures = record["figures"]
        assert record["command"].split()[1:] == run.command(out)
        assert figures["seed"] == run.seed and figures["budget"] == run.budget and figures["versions"]["torch"]
        assert figures["final"]["episodes"] == run.final_episodes and figures["final"]["deterministic"]
        assert figures["env_steps"] >= run.budget and (len(figures["curve"]["points"]) >= 2) == (run.budget > 0)
    assert f"| {nowrap('NetCatch-v0')} | ppo (1) |" in (out / "report.md").read_text()
    assert (out / "curves-vector.png").stat().st_size > 0


@pytest.mark.slow
def test_quick_mode_runs_the_quick_grid_end_to_end(tmp_path: Path) -> None:
    """``--quick``, as CI runs it: every run of the quick grid, the table and the figure."""
    done_ = subprocess.run([sys.executable, "scripts/baselines.py", "--quick", "--out", str(tmp_path)], cwd=ROOT,
                           capture_output=True, text=True, timeout=600)
    assert done_.returncode == 0, done_.stderr[-3000:]
    runs = grid(quick=True)
    assert all(done(run, tmp_path) for run in runs)
    report = (tmp_path / "report.md").read_text()
    names = {run: f"*{run.algorithm}* (1 run)" if run.budget == 0 else f"{run.algorithm} (1)" for run in runs}
    assert all(f"| {nowrap(run.env_id)} | {names[run]} |" in report for run in runs)
    assert len(grid_module.QUICK_IDS) == len({run.env_id for run in runs})
    for run in (run for run in runs if run.algorithm not in REFERENCES):  # each model loads with no other argument
        model = tmp_path / "models" / f"{run.name}.zip"
        assert saved_algorithm(model) == ALGORITHMS[run.algorithm][1]
        env_id, policy = policy_in_env(model)
        assert env_id == run.env_id and type(policy).__name__ == ALGORITHMS[run.algorithm][1]


@pytest.mark.slow
def test_runs_go_to_a_ray_cluster_as_tasks_with_address(tmp_path: Path) -> None:
    """``--address``: the same runs as Ray tasks on a local two-node cluster (in a network
    namespace of its own, as tests/agents/test_rllib_cluster.py starts it), their results written here."""
    from test_rllib_cluster import _needs_cluster

    _needs_cluster()
    command = [sys.executable, "scripts/local_cluster.py", "--", sys.executable, "scripts/baselines.py", "--quick",
               "--out", str(tmp_path), "--algos", "ppo", "--ids", "NetCatch-v0", "--address", "127.0.0.1:6380"]
    finished = subprocess.run(command, cwd=ROOT, capture_output=True, text=True, timeout=600)
    assert finished.returncode == 0, finished.stdout[-3000:] + finished.stderr[-3000:]
    runs = grid(["ppo"], ["NetCatch-v0"], quick=True)
    assert f"{len(runs)} to run on the Ray cluster" in finished.stdout
    assert all(done(run, tmp_path) for run in runs)


def test_every_shipped_baseline_model_is_its_runs_algorithm_on_its_runs_task() -> None:
    """Each file named in SHIPPED_BASELINES is in agents/pretrained/, saved by its run's algorithm,
    and evaluated on its run's task by default (the file records it); its run's result exists."""
    from agents.policies import SHIPPED_BASELINES

    for name, run in SHIPPED_BASELINES.items():
        folder, algorithm, env_id, seed = run.split("/")
        path = ROOT / "agents" / "pretrained" / name
        assert path.is_file(), name
        assert saved_algorithm(path) == ALGORITHMS[algorithm][1], name
        assert policy_in_env(path)[0] == env_id, name
        assert folder in ("baselines", "baselines_long"), name
        assert read_results(ROOT / "docs" / "results" / f"{run}.json")["figures"]["seed"] == int(seed[5:])


@pytest.mark.slow
def test_every_shipped_baseline_model_catches_more_than_random_actions() -> None:
    """On 5 fresh episodes of its task, each shipped model catches more than uniform random actions."""
    from agents.evaluation import evaluate
    from agents.policies import SHIPPED_BASELINES, load_policy

    for name in SHIPPED_BASELINES:
        env_id, policy = policy_in_env(ROOT / "agents" / "pretrained" / name)
        model = evaluate(policy, episodes=5, seed=60_000, env_id=env_id)
        random = evaluate(load_policy("random"), episodes=5, seed=60_000, env_id=env_id)
        assert model.rate > random.rate + 0.3, (name, str(model), str(random))


def test_every_algorithm_says_where_it_was_tuned_and_the_page_shows_it() -> None:
    from agents.baselines.tables import tuning
    from agents.hyperparams import TUNING

    assert set(TUNING) == set(ALGORITHMS) and all(TUNING.values())
    page = (ROOT / "docs" / "baselines.md").read_text()
    assert tuning() in page
    for algorithm in ALGORITHMS:
        assert f"| {algorithm} | `agents/hyperparams/{algorithm}.yml` |" in tuning()
