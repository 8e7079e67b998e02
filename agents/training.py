"""PPO training on NetCatch-v0 with Stable-Baselines3: environments, callbacks, the curve plot.

Used by ``scripts/train_ppo.py`` and by ``python -m agents`` (which trains when no pretrained
model is present).
"""

from __future__ import annotations

import os
import sys
import time
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

import gymnasium as gym
import numpy as np
import torch
from stable_baselines3 import PPO
from stable_baselines3.common.callbacks import BaseCallback, CallbackList
from stable_baselines3.common.env_util import make_vec_env
from stable_baselines3.common.vec_env import SubprocVecEnv, VecEnv, VecFrameStack

from agents.evaluation import evaluate
from agents.hyperparams import ENV_KWARGS, POLICY, PPO_PARAMS  # from agents/hyperparams/ppo.yml
from agents.model_env import record_env
from agents.policies import acting_policy
from agents.run_progress import RunProgress
from agents.warm_up import compile_kernels

EVAL_SEED = 20_000   # evaluation episodes during training use seeds 20000, 20001, ... (not the final test's)
TRAINER_THREADS = 1
"""torch threads of the training process. Its forward passes and updates are small (a 64x64 MLP,
batches of 128); a second thread gains nothing there and, spinning between them, takes a core from
the environment workers: on 2 cores, 8 workers, from scratch, 357-409 env steps/s with 2 threads
against 558-650 with 1 (2026-12-02)."""


@contextmanager
def torch_threads(n: int) -> Iterator[None]:
    """Run the block with ``n`` torch threads, restoring the number it had after."""
    before = torch.get_num_threads()
    torch.set_num_threads(n)
    try:
        yield
    finally:
        torch.set_num_threads(before)


class ReadyLine:
    """Says on stderr that a worker's environment is made (the last step of ``make_vec_env``'s
    factory in the worker: its ``wrapper_class``), with the seconds since ``started`` (epoch
    seconds, from the process that starts the workers). Returns the environment as it is."""

    def __init__(self, started: float) -> None:
        self.started = started

    def __call__(self, env: gym.Env) -> gym.Env:
        sys.stderr.write(f"environment worker {os.getpid()} ready after {time.time() - self.started:.0f} s\n")
        sys.stderr.flush()
        return env


def make_training_env(n_envs: int, seed: int, env_id: str = "NetCatch-v0", frame_stack: int = 1) -> VecEnv:
    """The vectorised training environment: ``make_vec_env`` with ``SubprocVecEnv`` (one
    process per environment), observations stacked over the last ``frame_stack`` steps
    (``VecFrameStack``) when it is above 1. Starting the workers takes a while (each imports
    torch and netgym and settles its net): it says so on stderr, and each worker when it is ready."""
    compile_kernels(env_id, **ENV_KWARGS)  # once, before the workers start
    sys.stderr.write(f"starting {n_envs} environment workers (each imports torch and netgym, then makes {env_id} "
                     "and settles its net) ...\n")
    sys.stderr.flush()
    env = make_vec_env(f"netgym:{env_id}", n_envs=n_envs, seed=seed, vec_env_cls=SubprocVecEnv,
                       env_kwargs=dict(ENV_KWARGS), wrapper_class=ReadyLine(time.time()))
    return VecFrameStack(env, frame_stack) if frame_stack > 1 else env


Point = tuple[int, float, float]
"""A point of a learning curve: (environment steps, capture rate, wall seconds of training)."""


class CaptureCurve(BaseCallback):
    """Evaluate the deterministic policy on the same seeded episodes at the start, every
    ``eval_every`` environment steps and at the end; record (steps, capture rate, wall seconds
    of training, evaluations excluded), save the best model (unless ``best_path`` is None), stop
    when the wall-clock budget is spent. The episodes are ``env_id``'s with ``env_kwargs``
    (default: ppo.yml's)."""

    def __init__(self, eval_every: int, episodes: int, budget_s: float, best_path: Path | None, seed: int = EVAL_SEED,
                 env_id: str = "NetCatch-v0", frame_stack: int = 1, env_kwargs: dict | None = None) -> None:
        super().__init__()
        self.eval_every, self.episodes, self.budget_s, self.env_id = eval_every, episodes, budget_s, env_id
        self.frame_stack = frame_stack
        self.env_kwargs = ENV_KWARGS if env_kwargs is None else env_kwargs
        self.best_path, self.seed = best_path, seed
        self.points: list[Point] = []
        self._best = -1.0
        self._spent = 0.0          # wall seconds of training so far, evaluations excluded
        self._resumed = 0.0
        self._next = 0

    def _evaluate(self) -> None:
        self._spent += time.perf_counter() - self._resumed
        rate = evaluate(acting_policy(self.model, self.frame_stack), self.episodes, seed=self.seed,
                        env_id=self.env_id, **self.env_kwargs).rate  # captures
        self.points.append((self.num_timesteps, rate, self._spent))
        self.logger.record("eval/capture_rate", rate)
        if rate > self._best and self.best_path is not None:
            self._best = rate
            self.model.save(self.best_path)
        self._next = self.num_timesteps + self.eval_every
        self._resumed = time.perf_counter()

    def _on_training_start(self) -> None:
        self._resumed = time.perf_counter()
        if not self.points:  # a resumed curve (restore) has its start already
            self._evaluate()

    def state(self) -> dict:
        """What :meth:`restore` needs to go on with this curve in a resumed run."""
        return {"points": self.points, "best": self._best, "spent": self.training_seconds(), "next": self._next}

    def restore(self, state: dict) -> None:
        """Go on with the curve whose :meth:`state` was ``state``."""
        self.points = [tuple(point) for point in state["points"]]
        self._best, self._spent, self._next = state["best"], state["spent"], state["next"]

    def latest_rate(self) -> float | None:
        """The capture rate of the latest evaluation, None before the first."""
        return self.points[-1][1] if self.points else None

    def training_seconds(self) -> float:
        """Wall seconds of training so far, evaluations excluded (what the budget counts)."""
        return self._spent + time.perf_counter() - self._resumed

    def _on_step(self) -> bool:
        if self.num_timesteps >= self._next:
            self._evaluate()
        return self.training_seconds() < self.budget_s

    def _on_training_end(self) -> None:
        if self.points[-1][0] != self.num_timesteps:
            self._evaluate()


def plot_curves(curves: list[list[Point]], oracle: float, random: float, path: Path,
                title: str = "PPO on NetCatch-v0 (basket)") -> None:
    """Capture rate against environment steps and against wall-clock minutes: each seed's
    curve, their mean and min-max spread (several seeds), the oracle and random rates."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 2, figsize=(10.0, 4.0), sharey=True)
    for ax, column, label in ((axes[0], 0, "environment steps (throws)"), (axes[1], 2, "wall-clock minutes of training")):
        scale = 1.0 if column == 0 else 1.0 / 60.0
        for k, points in enumerate(curves):
            ax.plot([p[column] * scale for p in points], [100 * p[1] for p in points], marker="o", markersize=3,
                    alpha=0.5 if len(curves) > 1 else 1.0, label=f"PPO seed {k}" if len(curves) > 1 else "PPO")
        if len(curves) > 1 and column == 0:
            grid, mean, low, high = _spread(curves)
            ax.plot(grid, mean, color="black", label=f"mean of {len(curves)} seeds")
            ax.fill_between(grid, low, high, color="gray", alpha=0.25, label="min-max over seeds")
        ax.axhline(100 * oracle, color="green", linestyle="--", label=f"ballistic oracle ({100 * oracle:.0f}%)")
        ax.axhline(100 * random, color="gray", linestyle=":", label=f"random ({100 * random:.0f}%)")
        ax.set_xlabel(label)
        ax.grid(alpha=0.3)
    axes[0].set_ylabel("capture rate (%), deterministic policy")
    axes[0].set_ylim(0, 105)
    axes[0].legend(loc="lower right", fontsize=8)
    fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def _spread(curves: list[list[Point]]) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Mean, min and max capture rate (%) of several curves on the steps they all reached."""
    last = min(points[-1][0] for points in curves)
    grid = np.linspace(0, last, 50)
    rates = np.array([np.interp(grid, [p[0] for p in points], [100 * p[1] for p in points]) for points in curves])
    return grid, rates.mean(axis=0), rates.min(axis=0), rates.max(axis=0)


def train(out: Path, minutes: float = 20.0, timesteps: int = 200_000, n_envs: int = 8,
          eval_every: int = 4096, eval_episodes: int = 40, seed: int = 0,
          progress_bar: bool = True, env_id: str = "NetCatch-v0", frame_stack: int = 1) -> tuple[PPO, list[Point]]:
    """Train PPO within a wall-clock budget; saves ``model.zip`` and ``best_model.zip`` in
    ``out`` and logs to TensorBoard under ``out/tb``. Returns the model and its capture curve
    (from step 0 to the end; see :class:`CaptureCurve`). ``progress_bar``: a bar of steps whose
    ETA is for the budget or the step cap, whichever ends the run first (:class:`RunProgress`);
    ``env_id``: the registered NetCatch id to train on; ``frame_stack``: observations stacked
    over that many steps (act with :func:`~agents.policies.acting_policy`). Both are saved
    with the models (:func:`~agents.model_env.record_env`)."""
    out.mkdir(parents=True, exist_ok=True)
    env = make_training_env(n_envs, seed, env_id, frame_stack)
    curve = CaptureCurve(eval_every, eval_episodes, 60.0 * minutes, out / "best_model", env_id=env_id,
                         frame_stack=frame_stack)
    model = PPO(POLICY, env, seed=seed, tensorboard_log=str(out / "tb"), verbose=0, **PPO_PARAMS)
    record_env(model, env_id, frame_stack)
    callbacks = [curve, RunProgress(curve.budget_s, curve.training_seconds, latest_rate=curve.latest_rate)] if progress_bar else [curve]
    with torch_threads(TRAINER_THREADS):
        model.learn(timesteps, callback=CallbackList(callbacks))
    model.save(out / "model")
    env.close()
    return model, curve.points
