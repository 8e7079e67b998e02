"""One baseline run: train an algorithm on an env id for its budget of environment steps, with a
learning curve, then evaluate the deterministic policy on the held-out episodes; or evaluate a
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

import netgym  # noqa: F401  (registers the ids make_vec_env makes)
from agents.asymmetric import acting_kwargs
from agents.baselines.grid import ALGORITHMS, CURVE_POINTS, FINAL_SEED, Run
from agents.evaluation import CaptureRate, evaluate
from agents.hyperparams import action_noise, algorithm_kwargs, env_wrapper, load, yml
from agents.model_env import record_env, vector_counterpart
from agents.oracle import BallisticOracle, InformedOracle
from agents.policies import acting_policy
from agents.random_agent import RandomAgent
from agents.training import TRAINER_THREADS, CaptureCurve, torch_threads

PACKAGES = ("netgym", "stable-baselines3", "sb3-contrib", "torch", "numpy", "gymnasium", "numba")
ROOT = Path(__file__).resolve().parents[2]


def versions() -> dict[str, str | None]:
    """The versions of Python, the packages a run depends on and the source tree's git commit."""
    found: dict[str, str | None] = {"python": platform.python_version()}
    for package in PACKAGES:
        try:
            found[package] = importlib.metadata.version(package)
        except importlib.metadata.PackageNotFoundError:
            found[package] = None
    git = subprocess.run(["git", "rev-parse", "HEAD"], cwd=ROOT, capture_output=True, text=True)
    found["commit"] = git.stdout.strip() if git.returncode == 0 else None
    return found


def execute(run: Run, models: Path | None = None) -> dict[str, Any]:
    """Train and evaluate ``run`` on one torch thread, saving a learner's final model as
    ``models/ALGORITHM/ENV_ID/seed_K.zip`` if ``models`` is given; its record: the run's fields,
    versions, machine, start time, wall and CPU seconds (the CPU's do not count time lost to other
    processes), steps trained, hyperparameters, learning curve (``[steps, capture rate,
    training seconds]`` points) and the final evaluation."""
    started, clock, cpu = datetime.datetime.now(datetime.timezone.utc), time.perf_counter(), time.process_time()
    with torch_threads(TRAINER_THREADS):
        trained = _reference(run) if run.budget == 0 else _learner(run, models)
    return {**dataclasses.asdict(run), "versions": versions(), "machine": f"{platform.machine()}, {platform.node()}",
            "started": started.isoformat(timespec="seconds"), "wall_s": time.perf_counter() - clock,
            "cpu_s": time.process_time() - cpu, **trained}


def _final(rate: CaptureRate, episodes: int) -> dict[str, Any]:
    return {"episodes": episodes, "seed": FINAL_SEED, "deterministic": True, "rate": rate.rate,
            **dataclasses.asdict(rate)}


def _reference(run: Run) -> dict[str, Any]:
    """A reference policy on the held-out episodes (of the vector counterpart, for pixels)."""
    policies = {"random": RandomAgent(run.seed), "blind": lambda env: BallisticOracle(env.scene),
                "oracle": InformedOracle}
    env_id, env_kwargs = vector_counterpart(run.env_id)
    rate = evaluate(policies[run.algorithm], run.final_episodes, seed=FINAL_SEED, env_id=env_id, **env_kwargs)
    return {"env_steps": 0, "hyperparams": {}, "curve": {"episodes": 0, "points": []},
            "final": {**_final(rate, run.final_episodes), "evaluated_on": env_id}}


def _learner(run: Run, models: Path | None) -> dict[str, Any]:
    """Train the algorithm with its yml's settings for the id (its ``env_wrapper`` and
    ``frame_stack`` too), recording the curve; save the model under ``models`` (if given);
    evaluate (without the training-only env arguments and wrapper)."""
    settings = load(yml(run.algorithm), run.env_id)
    module, name = ALGORITHMS[run.algorithm]
    algorithm = getattr(importlib.import_module(module), name)
    env_kwargs, frames = settings.get("env_kwargs", {}), settings.get("frame_stack", 1)
    env = make_vec_env(run.env_id, n_envs=settings.get("n_envs", 1), seed=run.seed, vec_env_cls=DummyVecEnv,
                       env_kwargs=env_kwargs, wrapper_class=env_wrapper(settings))
    env = VecFrameStack(env, frames) if frames > 1 else env
    noise = action_noise(settings, env.action_space.shape[0])
    model = algorithm(settings["policy"], env, seed=run.seed, device="cpu", verbose=0,
                      **({"action_noise": noise} if noise is not None else {}), **algorithm_kwargs(settings))
    record_env(model, run.env_id, frames)
    acting = acting_kwargs(env_kwargs)
    curve = CaptureCurve(max(1, run.budget // CURVE_POINTS), run.curve_episodes, float("inf"), None,
                         env_id=run.env_id, frame_stack=frames, env_kwargs=acting)
    model.learn(run.budget, callback=curve)
    env.close()
    if models is not None:
        model.save(models / f"{run.name}.zip")
    rate = evaluate(acting_policy(model, frames), run.final_episodes, seed=FINAL_SEED, env_id=run.env_id, **acting)
    return {"env_steps": model.num_timesteps, "hyperparams": settings, "train_s": curve.points[-1][2],
            "curve": {"episodes": run.curve_episodes, "seed": curve.seed, "points": curve.points},
            "final": _final(rate, run.final_episodes)}
