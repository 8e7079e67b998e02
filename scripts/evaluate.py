"""Capture rate of a saved PPO model, an RLlib checkpoint, the ballistic oracle or the random
policy on a registered NetCatch env.

A saved model is evaluated on the env it was trained on (saved with it by
``scripts/train_ppo.py``; an RLlib checkpoint folder, ``scripts/train_rllib.py``'s, records it
too), with its stack of observations, unless ``--env`` names another whose observations it
reads; the oracle and the random policy on NetCatch-v0 unless ``--env`` says.

Usage::

    python scripts/evaluate.py agents/pretrained/ppo_netcatch.zip --episodes 1000
    python scripts/evaluate.py agents/pretrained/ppo_windy_stack5.zip      # on NetCatchWindy-v0
    python scripts/evaluate.py runs/rllib                                  # an RLlib checkpoint (extra rllib)
    python scripts/evaluate.py oracle --env NetCatchWindy-v0 --episodes 1000
    python scripts/evaluate.py random --scene goal
"""

from __future__ import annotations

import argparse
import time

from agents.evaluation import evaluate
from agents.policies import SB3_ALGORITHMS, policy_in_env


def main() -> None:
    """Parse arguments, evaluate, print the rate with its 95% confidence interval."""
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("policy", help="path of a saved SB3 model (.zip), an RLlib checkpoint folder, "
                        "'oracle' or 'random'")
    parser.add_argument("--env", help="registered NetCatch id (default: the model's own, else NetCatch-v0)")
    parser.add_argument("--episodes", type=int, default=100)
    parser.add_argument("--seed", type=int, default=10_000, help="episode i uses seed + i")
    parser.add_argument("--scene", help="scene in place of the env's own (e.g. goal)")
    parser.add_argument("--algorithm", choices=SB3_ALGORITHMS,
                        help="the algorithm of a saved model (default: the one it was saved with, else PPO)")
    args = parser.parse_args()
    try:
        env_id, policy = policy_in_env(args.policy, args.env, args.algorithm)
    except (ValueError, FileNotFoundError, ImportError) as error:  # EnvMismatchError is a ValueError
        parser.error(str(error))
    overrides = {} if args.scene is None else {"scene": args.scene}
    start = time.perf_counter()
    result = evaluate(policy, args.episodes, seed=args.seed, progress=str(args.policy), env_id=env_id, **overrides)
    seconds = time.perf_counter() - start
    where = env_id if args.scene is None else f"{env_id} (scene {args.scene})"
    print(f"{args.policy} on {where}: capture rate {result} over {args.episodes} episodes "
          f"(seeds {args.seed}..{args.seed + args.episodes - 1}; {result.throws / seconds:.1f} throws/s)")


if __name__ == "__main__":
    main()
