"""Train PPO (Stable-Baselines3) on NetCatch-v0 and plot its learning curve.

The training environments are SB3's ``make_vec_env`` with ``SubprocVecEnv`` (one process per
environment). Training uses the documented ``shaped`` reward; evaluation counts captures on the
sparse reward. Writes, under ``--out``:

- ``model.zip``: the final model; ``best_model.zip``: the best evaluated one;
- ``curve.csv`` and ``learning_curve.png``: capture rate against environment steps, with
  the ballistic oracle's and the random policy's rates as reference lines;
- TensorBoard logs under ``tb/``.

Usage::

    python scripts/train_ppo.py --minutes 20 --out runs/ppo     # full run
    python scripts/train_ppo.py --quick --out /tmp/ppo          # seconds, for CI
"""

from __future__ import annotations

import argparse
import csv
from pathlib import Path

from agents.evaluation import evaluate
from agents.policies import load_policy
from agents.training import plot_curve, train


def main() -> None:
    """Parse arguments, train, evaluate, plot."""
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--out", type=Path, default=Path("runs/ppo"))
    parser.add_argument("--minutes", type=float, default=20.0, help="wall-clock training budget")
    parser.add_argument("--timesteps", type=int, default=200_000, help="upper bound on environment steps")
    parser.add_argument("--n-envs", type=int, default=8)
    parser.add_argument("--eval-every", type=int, default=4096, help="environment steps between evaluations")
    parser.add_argument("--eval-episodes", type=int, default=40)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--quick", action="store_true", help="tiny budget for smoke tests")
    args = parser.parse_args()
    if args.quick:
        args.timesteps, args.n_envs, args.eval_every, args.eval_episodes = 256, 2, 128, 2
    model, points = train(args.out, args.minutes, args.timesteps, args.n_envs, args.eval_every,
                          args.eval_episodes, args.seed)
    episodes = 4 if args.quick else 100
    final = evaluate(model, episodes, seed=10_000)
    oracle = evaluate(load_policy("oracle"), episodes, seed=10_000)
    random = evaluate(load_policy("random"), episodes, seed=10_000)
    with open(args.out / "curve.csv", "w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(["env_steps", "capture_rate", "wall_seconds"])
        writer.writerows(points)
    plot_curve(points or [(model.num_timesteps, final.rate, 0.0)], oracle.rate, random.rate,
               args.out / "learning_curve.png")
    minutes = (points[-1][2] if points else 0.0) / 60
    print(f"trained {model.num_timesteps} steps in about {minutes:.1f} min; wrote {args.out / 'model.zip'}")
    print(f"capture rate over {episodes} episodes: PPO {final}; oracle {oracle}; random {random}")
    print(f"best evaluation during training: {100 * max((p[1] for p in points), default=0.0):.1f}%")


if __name__ == "__main__":
    main()
