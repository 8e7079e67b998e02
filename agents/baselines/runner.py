"""Run the baseline runs whose result files are missing: in local worker processes (the default)
or as Ray tasks on a cluster. Each result is written the moment its run ends, atomically, and a
learner keeps checkpoints while it trains (:mod:`~agents.baselines.checkpoints`), so a runner
killed at any point and started again runs only what is missing, each run from its latest
checkpoint. An output folder holds the runs of one budget protocol: a run whose result there has
another budget is refused, never overwritten."""

from __future__ import annotations

import ctypes
import functools
import json
import multiprocessing
import signal
import time
from collections.abc import Callable, Iterator
from concurrent.futures import ProcessPoolExecutor, as_completed
from pathlib import Path
from typing import Any

from agents.baselines.grid import FINAL_SEED, MODELS, Run
from agents.baselines.runs import execute
from agents.evaluation import CaptureRate, evaluate
from agents.policies import policy_in_env
from agents.warm_up import compile_kernels
from netgym.bench.results import read_results, write_results
from netgym.errors import InvalidArgumentError

PR_SET_PDEATHSIG = 1


def evaluate_saved(out: Path, algorithm: str, env_id: str, episodes: int, seed: int) -> dict[Path, CaptureRate]:
    """Each model the runs of ``algorithm`` on ``env_id`` saved under ``out`` (by seed), evaluated
    deterministically on ``episodes`` episodes of ``env_id`` seeded from ``seed``, as it acts (its
    frame stack too); InvalidArgumentError when there is none."""
    models = sorted((out / MODELS / algorithm / env_id).glob("seed_*.zip"),
                    key=lambda path: int(path.stem.removeprefix("seed_")))
    if not models:
        raise InvalidArgumentError(f"no saved models under {out / MODELS / algorithm / env_id}")
    return {path: evaluate(policy_in_env(path, env_id)[1], episodes, seed=seed, progress=path.stem, env_id=env_id)
            for path in models}


def done(run: Run, out: Path) -> bool:
    """Whether ``run``'s result file under ``out`` is there and complete; InvalidArgumentError
    when it is the result of another protocol (another budget, or another final evaluation):
    runs of another protocol go to a folder of their own."""
    try:
        figures = read_results(run.path(out))["figures"]
    except (FileNotFoundError, InvalidArgumentError, json.JSONDecodeError):
        return False
    if "final" not in figures:
        return False
    theirs = (figures.get("budget"), figures["final"].get("episodes"), figures["final"].get("seed"))
    ours = (run.budget, run.final_episodes, FINAL_SEED)
    if theirs != ours:
        raise InvalidArgumentError(
            f"{run.path(out)} holds a run of another protocol ({_protocol(*theirs)}), not {_protocol(*ours)}: write "
            f"runs of another protocol to a folder of their own (--out), so that no result of one is overwritten")
    return True


def _protocol(budget: int | None, episodes: int | None, seed: int | None) -> str:
    return f"{budget} steps, {episodes} final episodes seeded from {seed}"


def missing(runs: list[Run], out: Path) -> list[Run]:
    """The runs of ``runs`` without a complete result file under ``out``."""
    return [run for run in runs if not done(run, out)]


def _die_with_parent() -> None:
    """Worker initializer: end with the runner (SIGKILL when it dies, whatever kills it), so
    that no orphaned worker writes a result the next runner also runs."""
    ctypes.CDLL(None).prctl(PR_SET_PDEATHSIG, signal.SIGKILL)


def _compile(ids: list[str]) -> None:
    """Compile (or load from numba's cache) the kernels of every id in ``ids``."""
    for env_id in ids:
        compile_kernels(env_id)


Outcome = tuple[Run, "dict[str, Any] | Exception"]
"""A run and its record, or the exception that ended it."""


def _local(runs: list[Run], workers: int, out: Path) -> Iterator[Outcome]:
    """Each run's outcome as it ends, from ``workers`` processes started fresh (spawn) after the
    kernels of the runs' ids are compiled once here; checkpoints and models under ``out``."""
    _compile(list(dict.fromkeys(run.env_id for run in runs)))
    context = multiprocessing.get_context("spawn")
    with ProcessPoolExecutor(workers, mp_context=context, initializer=_die_with_parent) as pool:
        futures = {pool.submit(execute, run, out): run for run in runs}
        for future in as_completed(futures):
            yield futures[future], future.exception() or future.result()


def _ray(runs: list[Run], address: str, out: Path) -> Iterator[Outcome]:
    """Each run's outcome as it ends, from Ray tasks (one CPU each) on the cluster at
    ``address``; the kernels are compiled first on every node, one task each; checkpoints and
    models are kept under ``out`` on the node that trains the run."""
    import ray
    from ray.util.scheduling_strategies import NodeAffinitySchedulingStrategy

    ray.init(address=address)
    warm = ray.remote(num_cpus=1)(_compile)
    ids = list(dict.fromkeys(run.env_id for run in runs))
    nodes = [node["NodeID"] for node in ray.nodes() if node["Alive"] and node["Resources"].get("CPU", 0) >= 1]
    ray.get([warm.options(scheduling_strategy=NodeAffinitySchedulingStrategy(node, soft=False)).remote(ids)
             for node in nodes])
    task = ray.remote(num_cpus=1)(execute)
    pending = {task.remote(run, out): run for run in runs}
    while pending:
        ready, _ = ray.wait(list(pending), num_returns=1)
        run = pending.pop(ready[0])
        try:
            yield run, ray.get(ready[0])
        except ray.exceptions.RayError as error:
            yield run, error


def run_missing(runs: list[Run], out: Path, workers: int = 2, address: str | None = None,
                report: Callable[[str], None] = functools.partial(print, flush=True)) -> list[Run]:
    """Run those of ``runs`` not done under ``out``, the costliest first, each result file
    written as its run ends (``--out``'s layout: ``ALGORITHM/ENV_ID/seed_K.json``, the learners'
    models under :data:`MODELS`); ``report``
    gets a line per run with the progress and the estimated time left. A run that fails is
    reported and the others go on; then RuntimeError names the failed runs. Returns the runs
    it ran."""
    todo = sorted(missing(runs, out), key=lambda run: -run.cost)
    report(f"{len(runs) - len(todo)} of {len(runs)} runs done under {out}; {len(todo)} to run "
           + (f"on the Ray cluster at {address}" if address else f"in {workers} local processes"))
    if not todo:
        return []
    total, spent, start = sum(run.cost for run in todo), 0, time.perf_counter()
    records = _ray(todo, address, out) if address else _local(todo, workers, out)
    failed = []
    for k, (run, record) in enumerate(records, start=1):
        spent += run.cost
        elapsed = time.perf_counter() - start
        left = f"elapsed {elapsed / 60:.1f} min, left ~{elapsed / spent * (total - spent) / 60:.1f} min"
        if isinstance(record, Exception):
            failed.append(run.name)
            report(f"[{k}/{len(todo)}] {run.name} FAILED: {record!r}; {left}")
            continue
        write_results(run.path(out), record, command=run.command(out))
        report(f"[{k}/{len(todo)}] {run.name}: {100 * record['final']['rate']:.1f}% captured, "
               f"{record['wall_s']:.0f} s; {left}")
    if failed:
        raise RuntimeError(f"{len(failed)} run(s) failed (run again to retry them): {', '.join(failed)}")
    return todo
