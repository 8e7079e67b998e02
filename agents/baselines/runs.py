"""One baseline run: train an algorithm on an env id for its budget of environment steps, with a
learning curve and checkpoints (a killed run resumes from its latest), then evaluate the
deterministic policy on the held-out episodes, keeping every episode's outcome; or evaluate a
reference policy. The result is a JSON-ready record (the runner writes it)."""

from __future__ import annotations

import dataclasses
import datetime
import importlib
import importlib.metadata
import platform
import subprocess
import time
from pathlib import Path
from typing import Any

from stable_baselines3.common.env_util import make_vec_env
from stable_baselines3.common.vec_env import DummyVecEnv, VecFrameStack

import netgym  # registers the ids make_vec_env makes
from agents.asymmetric import acting_kwargs
from agents.baselines.checkpoints import Checkpointer, checkpoint_folder, load_state, remove, resume
from agents.baselines.grid import (ALGORITHMS, CURVE_POINTS, CURVE_SEED, FINAL_SEED, MODELS, ROOT, TRAIN_SEED_STRIDE,
                                   Run)
from agents.evaluation import capture_rate, episode_outcomes
from agents.hyperparams import action_noise, algorithm_kwargs, env_wrapper, load, yml
from agents.model_env import record_env, vector_counterpart
from agents.oracle import BallisticOracle, InformedOracle
from agents.policies import acting_policy
from agents.random_agent import RandomAgent
from agents.training import TRAINER_THREADS, CaptureCurve, torch_threads

PACKAGES = ("netgym", "stable-baselines3", "sb3-contrib", "torch", "numpy", "gymnasium", "numba", "scipy")
RESUME_STRIDE = 8
"""Env seeds a (re)start of a run takes from its block of :data:`TRAIN_SEED_STRIDE`: one a worker."""


def versions() -> dict[str, str | bool | None]:
    """The versions of Python, the packages a run depends on and the source tree's git commit,
    and whether the tree had changes beside it (``tree_clean``: False means the commit does not
    say what ran)."""
    found: dict[str, str | bool | None] = {"python": platform.python_version()}
    for package in PACKAGES:
        try:
            found[package] = importlib.metadata.version(package)
        except importlib.metadata.PackageNotFoundError:
            found[package] = None
    git = subprocess.run(["git", "rev-parse", "HEAD"], cwd=ROOT, capture_output=True, text=True)
    found["commit"] = git.stdout.strip() if git.returncode == 0 else None
    changes = subprocess.run(["git", "status", "--porcelain", "--untracked-files=no"], cwd=ROOT, capture_output=True,
                             text=True)
    found["tree_clean"] = changes.returncode == 0 and not changes.stdout.strip()
    return found


def execute(run: Run, out: Path | None = None) -> dict[str, Any]:
    """Train and evaluate ``run`` on one torch thread; with an output folder ``out``, keep
    checkpoints under it while training (and resume from one left there) and save a learner's
    final model as ``out/models/ALGORITHM/ENV_ID/seed_K.zip``. Its record: the run's fields,
    versions, machine, start time, wall and CPU seconds (of every segment of a resumed run; the
    CPU's do not count time lost to other processes), steps trained, hyperparameters, learning
    curve (``[steps, capture rate, training seconds]`` points) and the final evaluation with every
    episode's outcome."""
    if not Path(netgym.__file__).resolve().is_relative_to(ROOT):
        raise RuntimeError(f"netgym is imported from {netgym.__file__}, not from this tree ({ROOT}), whose commit the "
                           f"run would record: install that tree (pip install -e .) or put it first (PYTHONPATH)")
    started, clock, cpu = datetime.datetime.now(datetime.timezone.utc), time.perf_counter(), time.process_time()
    with torch_threads(TRAINER_THREADS):
        trained = _reference(run) if run.budget == 0 else _learner(run, out)
    before = trained.pop("spent_before", {"wall_s": 0.0, "cpu_s": 0.0})
    return {**dataclasses.asdict(run), "versions": versions(), "machine": f"{platform.machine()}, {platform.node()}",
            "started": started.isoformat(timespec="seconds"), "wall_s": before["wall_s"] + time.perf_counter() - clock,
            "cpu_s": before["cpu_s"] + time.process_time() - cpu, **trained}


def _final(outcomes: list[str]) -> dict[str, Any]:
    """The final evaluation's record: its rate, Wilson interval, captures by throw and outcomes."""
    rate = capture_rate(outcomes)
    return {"episodes": len(outcomes), "seed": FINAL_SEED, "deterministic": True, "rate": rate.rate,
            **dataclasses.asdict(rate), "outcomes": outcomes}


def _reference(run: Run) -> dict[str, Any]:
    """A reference policy on the held-out episodes (of the vector counterpart, for pixels)."""
    policies = {"random": RandomAgent(run.seed), "blind": lambda env: BallisticOracle(env.scene),
                "oracle": InformedOracle}
    env_id, env_kwargs = vector_counterpart(run.env_id)
    outcomes = episode_outcomes(policies[run.algorithm], run.final_episodes, seed=FINAL_SEED, env_id=env_id,
                                **env_kwargs)
    return {"env_steps": 0, "hyperparams": {}, "curve": {"episodes": 0, "points": []},
            "final": {**_final(outcomes), "evaluated_on": env_id}}


def _learner(run: Run, out: Path | None) -> dict[str, Any]:
    """Train the algorithm with its yml's settings for the id (its ``env_wrapper`` and
    ``frame_stack`` too), recording the curve, from the run's checkpoint under ``out`` if there is
    one; save the model under ``out`` (if given); evaluate (without the training-only env
    arguments and wrapper)."""
    settings = load(yml(run.algorithm), run.env_id)
    module, name = ALGORITHMS[run.algorithm]
    algorithm = getattr(importlib.import_module(module), name)
    env_kwargs, frames, n_envs = settings.get("env_kwargs", {}), settings.get("frame_stack", 1), settings.get("n_envs", 1)
    folder = checkpoint_folder(out, run.name) if out is not None else None
    saved = load_state(folder) if folder is not None else None
    resumed = saved["resumed_at"] + [saved["steps"]] if saved else []
    env = make_vec_env(run.env_id, n_envs=n_envs, seed=TRAIN_SEED_STRIDE * run.seed + RESUME_STRIDE * len(resumed),
                       vec_env_cls=DummyVecEnv, env_kwargs=env_kwargs, wrapper_class=env_wrapper(settings))
    env = VecFrameStack(env, frames) if frames > 1 else env
    if saved:
        model = resume(folder, algorithm, env)
        model.set_random_seed(TRAIN_SEED_STRIDE * run.seed + RESUME_STRIDE * len(resumed))
    else:
        noise = action_noise(settings, env.action_space.shape[0])
        model = algorithm(settings["policy"], env, seed=run.seed, device="cpu", verbose=0,
                          **({"action_noise": noise} if noise is not None else {}), **algorithm_kwargs(settings))
        record_env(model, run.env_id, frames)
    acting = acting_kwargs(env_kwargs)
    curve = CaptureCurve(max(1, run.budget // CURVE_POINTS), run.curve_episodes, float("inf"), None,
                         env_id=run.env_id, frame_stack=frames, env_kwargs=acting, seed=CURVE_SEED)
    before = saved["spent"] if saved else {"wall_s": 0.0, "cpu_s": 0.0}
    if saved:
        curve.restore(saved["curve"])
    clock, cpu = time.perf_counter(), time.process_time()
    callbacks = [curve] if folder is None else [curve, Checkpointer(folder, lambda: {
        "curve": curve.state(), "resumed_at": resumed,
        "spent": {"wall_s": before["wall_s"] + time.perf_counter() - clock,
                  "cpu_s": before["cpu_s"] + time.process_time() - cpu}})]
    model.learn(run.budget - model.num_timesteps, callback=callbacks, reset_num_timesteps=not saved)
    env.close()
    if out is not None:
        (out / MODELS / run.name).parent.mkdir(parents=True, exist_ok=True)
        model.save(out / MODELS / f"{run.name}.zip")
    outcomes = episode_outcomes(acting_policy(model, frames), run.final_episodes, seed=FINAL_SEED, env_id=run.env_id,
                                **acting)
    if folder is not None:
        remove(folder)
    return {"env_steps": model.num_timesteps, "hyperparams": settings, "train_s": curve.points[-1][2],
            "curve": {"episodes": run.curve_episodes, "seed": curve.seed, "points": curve.points},
            "env_seeds": [TRAIN_SEED_STRIDE * run.seed + RESUME_STRIDE * r + i for r in range(len(resumed) + 1)
                          for i in range(n_envs)],
            "resumed_at": resumed, "final": _final(outcomes), "spent_before": before}
