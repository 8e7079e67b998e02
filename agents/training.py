"""PPO training on NetCatch-v0 with Stable-Baselines3: environments, callbacks, the curve plot.

Used by ``scripts/train_ppo.py`` and by ``python -m agents`` (which trains when no pretrained
model is present).
"""

from __future__ import annotations

import time
import warnings
from pathlib import Path

from stable_baselines3 import PPO
from stable_baselines3.common.callbacks import BaseCallback, CallbackList, EvalCallback
from stable_baselines3.common.env_util import make_vec_env
from stable_baselines3.common.monitor import Monitor
from stable_baselines3.common.vec_env import SubprocVecEnv, VecEnv

from agents.hyperparams import ENV_KWARGS, POLICY, PPO_PARAMS  # from agents/hyperparams/ppo.yml
from netgym.envs import NetCatchEnv


def make_training_env(n_envs: int, seed: int) -> VecEnv:
    """The vectorised training environment: ``make_vec_env`` with ``SubprocVecEnv`` (one
    process per environment)."""
    NetCatchEnv()  # compile the kernels once before the workers start
    return make_vec_env("netgym:NetCatch-v0", n_envs=n_envs, seed=seed, vec_env_cls=SubprocVecEnv,
                        env_kwargs=dict(ENV_KWARGS))


class CaptureCurve(BaseCallback):
    """After each evaluation: record the capture rate (mean sparse return / balls per episode)
    against environment steps, and stop once the wall-clock budget is spent."""

    def __init__(self, balls_per_episode: int, budget_s: float) -> None:
        super().__init__()
        self.balls = balls_per_episode
        self.budget_s, self.start = budget_s, time.perf_counter()
        self.points: list[tuple[int, float, float]] = []

    def _on_step(self) -> bool:
        assert isinstance(self.parent, EvalCallback)
        rate = self.parent.last_mean_reward / self.balls
        elapsed = time.perf_counter() - self.start
        self.points.append((self.num_timesteps, rate, elapsed))
        self.logger.record("eval/capture_rate", rate)
        return True

    def out_of_time(self) -> bool:
        """True once the wall-clock budget is spent."""
        return time.perf_counter() - self.start > self.budget_s


class WallClockStop(BaseCallback):
    """Stops training when its :class:`CaptureCurve` says the budget is spent."""

    def __init__(self, curve: CaptureCurve) -> None:
        super().__init__()
        self.curve = curve

    def _on_step(self) -> bool:
        return not self.curve.out_of_time()


def plot_curve(points: list[tuple[int, float, float]], oracle: float, random: float, path: Path) -> None:
    """Capture rate against environment steps, with the oracle and random rates."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    steps = [p[0] for p in points]
    fig, ax = plt.subplots(figsize=(6.4, 4.0))
    ax.plot(steps, [100 * p[1] for p in points], marker="o", label="PPO (deterministic policy)")
    ax.axhline(100 * oracle, color="green", linestyle="--", label=f"ballistic oracle ({100 * oracle:.0f}%)")
    ax.axhline(100 * random, color="gray", linestyle=":", label=f"random ({100 * random:.0f}%)")
    ax.set_xlabel("environment steps (throws)")
    ax.set_ylabel("capture rate (%)")
    ax.set_ylim(0, 105)
    ax.set_title("PPO on NetCatch-v0 (basket)")
    ax.grid(alpha=0.3)
    ax.legend(loc="lower right")
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def train(out: Path, minutes: float = 20.0, timesteps: int = 200_000, n_envs: int = 8,
          eval_every: int = 4096, eval_episodes: int = 40, seed: int = 0) -> tuple[PPO, list[tuple[int, float, float]]]:
    """Train PPO within a wall-clock budget; saves ``model.zip`` and ``best_model.zip`` in
    ``out`` and logs to TensorBoard under ``out/tb``. Returns the model and its capture curve
    (environment steps, capture rate, wall seconds)."""
    out.mkdir(parents=True, exist_ok=True)
    warnings.filterwarnings("ignore", message="Training and eval env are not of the same type")
    env = make_training_env(n_envs, seed)
    eval_env = Monitor(NetCatchEnv())
    curve = CaptureCurve(eval_env.unwrapped.balls_per_episode, 60.0 * minutes)
    eval_callback = EvalCallback(eval_env, n_eval_episodes=eval_episodes, deterministic=True,
                                 eval_freq=max(1, eval_every // n_envs), best_model_save_path=str(out),
                                 callback_after_eval=curve, verbose=0)
    model = PPO(POLICY, env, seed=seed, tensorboard_log=str(out / "tb"), verbose=0, **PPO_PARAMS)
    model.learn(timesteps, callback=CallbackList([eval_callback, WallClockStop(curve)]))
    model.save(out / "model")
    env.close()
    eval_env.close()
    return model, curve.points
