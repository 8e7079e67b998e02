"""Train PPO (Stable-Baselines3) on NetCatch-v0 and plot its learning curve.

The training environments are SB3's ``make_vec_env`` with ``SubprocVecEnv`` (one process per
environment). Training uses the documented ``shaped`` reward; evaluation counts captures on the
sparse reward. Writes, under ``--out``:

- ``model.zip``: the final model; ``best_model.zip``: the best evaluated one (with several
  ``--seeds``, under ``seed_<k>/`` for each);
- ``curve.csv`` and ``learning_curve.png``: capture rate, evaluated at step 0, every
  ``--eval-every`` steps and at the end, against environment steps and wall-clock minutes (with
  several seeds: each curve, their mean and spread), with the ballistic oracle's and the random
  policy's rates as reference lines;
- TensorBoard logs under ``tb/``.

Usage::

    python scripts/train_ppo.py --minutes 20 --out runs/ppo                 # full run
    python scripts/train_ppo.py --minutes 6 --seeds 0 1 2 --out runs/seeds  # several seeds, one after another
    python scripts/train_ppo.py --env NetCatchWindy-v0 --frame-stack 5 --out runs/windy_stack5  # memory of the episode
    python scripts/train_ppo.py --quick --out /tmp/ppo                      # seconds, for CI
"""

from __future__ import annotations

import argparse
import csv
from pathlib import Path

from agents.evaluation import evaluate
from agents.policies import acting_policy, policy_in_env
from agents.training import plot_curves, train


def main() -> None:
    """Parse arguments, train, evaluate, plot."""
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--out", type=Path, default=Path("runs/ppo"))
    parser.add_argument("--minutes", type=float, default=20.0, help="wall-clock training budget")
    parser.add_argument("--timesteps", type=int, default=200_000, help="upper bound on environment steps")
    parser.add_argument("--n-envs", type=int, default=8)
    parser.add_argument("--eval-every", type=int, default=4096, help="environment steps between evaluations")
    parser.add_argument("--eval-episodes", type=int, default=40)
    parser.add_argument("--seeds", type=int, nargs="+", default=[0], help="one run per seed, one after another")
    parser.add_argument("--env", default="NetCatch-v0", help="the registered NetCatch id to train on")
    parser.add_argument("--frame-stack", type=int, default=1,
                        help="stack each observation with the previous ones of the episode (SB3's VecFrameStack)")
    parser.add_argument("--quick", action="store_true", help="tiny budget for smoke tests")
    args = parser.parse_args()
    if args.quick:
        args.timesteps, args.n_envs, args.eval_every, args.eval_episodes = 256, 2, 128, 2
    curves, models = [], []
    for seed in args.seeds:
        out = args.out if len(args.seeds) == 1 else args.out / f"seed_{seed}"
        print(f"seed {seed}: training for up to {args.minutes:g} min or {args.timesteps} steps ...")
        model, points = train(out, args.minutes, args.timesteps, args.n_envs, args.eval_every, args.eval_episodes,
                              seed, progress_bar=True, env_id=args.env, frame_stack=args.frame_stack)
        curves.append(points)
        models.append(model)
        print(f"seed {seed}: trained {model.num_timesteps} steps in {points[-1][2] / 60:.1f} min of training; "
              f"evaluations {', '.join(f'{100 * p[1]:.0f}%' for p in points)}; best {100 * max(p[1] for p in points):.1f}%")
    episodes = 4 if args.quick else 100
    oracle = evaluate(policy_in_env("oracle", args.env)[1], episodes, seed=10_000, env_id=args.env)
    random = evaluate(policy_in_env("random", args.env)[1], episodes, seed=10_000, env_id=args.env)
    with open(args.out / "curve.csv", "w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(["seed", "env_steps", "capture_rate", "wall_seconds"])
        writer.writerows((seed, *p) for seed, points in zip(args.seeds, curves) for p in points)
    stacked = f", the last {args.frame_stack} observations stacked" if args.frame_stack > 1 else ""
    plot_curves(curves, oracle.rate, random.rate, args.out / "learning_curve.png", f"PPO on {args.env}{stacked}")
    for seed, model in zip(args.seeds, models):
        print(f"seed {seed}: capture rate over {episodes} test episodes: PPO "
              f"{evaluate(acting_policy(model, args.frame_stack), episodes, seed=10_000, env_id=args.env)}")
    print(f"oracle {oracle}; random {random}; wrote {args.out / 'learning_curve.png'}")


if __name__ == "__main__":
    main()
