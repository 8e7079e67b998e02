"""Train PPO on NetCatch-v0 with Ray RLlib: the path for users who outgrow one machine.

The environment is registered with ``register_env`` and sampled by ``--env-runners`` RLlib env
runners, one process each, in parallel. Requires the ``rllib`` extra: ``pip install -e ".[rllib]"``.

On a Ray cluster the same script spreads the env runners over the machines: install netgym on
every node (the same ``pip install -e ".[rllib]"``), start the cluster (``ray start --head`` on
one node, ``ray start --address=HEAD_IP:6379`` on the others, or a cluster launcher), then run
the script on a node of the cluster with ``--address auto`` and as many ``--env-runners`` as
the cluster has CPUs to spare (one learner CPU stays on the head).

Usage::

    python scripts/train_rllib.py --iterations 50 --env-runners 2           # this machine
    python scripts/train_rllib.py --address auto --env-runners 64           # a running Ray cluster
    python scripts/train_rllib.py --quick                                   # smoke test: 2 env runners
"""

from __future__ import annotations

import argparse
from pathlib import Path

import ray
from ray.rllib.algorithms.ppo import PPOConfig
from ray.tune.registry import register_env

from agents.hyperparams import ENV_KWARGS, PPO_PARAMS, rllib_training  # from agents/hyperparams/ppo.yml
from netgym.envs import NetCatchEnv

ENV_NAME = "netgym/NetCatch-v0"


def make_env(env_config: dict) -> NetCatchEnv:
    """RLlib env creator: NetCatch-v0 with ``env_config`` as keyword arguments."""
    return NetCatchEnv(**env_config)


def build(env_runners: int, batch: int, minibatch: int, epochs: int):
    """The PPO algorithm on NetCatch-v0, with the training environment's arguments and the
    settings RLlib shares with SB3 (learning rate, gamma, lambda, entropy coefficient) from
    agents/hyperparams/ppo.yml; ``epochs`` overrides its ``n_epochs``."""
    register_env(ENV_NAME, make_env)
    config = (
        PPOConfig()
        .environment(ENV_NAME, env_config=dict(ENV_KWARGS))
        .env_runners(num_env_runners=env_runners, num_envs_per_env_runner=1)
        .training(**{**rllib_training(), "num_epochs": epochs}, train_batch_size_per_learner=batch,
                  minibatch_size=minibatch)
    )
    return config.build_algo()


def main() -> None:
    """Parse arguments, train, report, save a checkpoint."""
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--iterations", type=int, default=50)
    parser.add_argument("--env-runners", type=int, default=2)
    parser.add_argument("--batch", type=int, default=1024)
    parser.add_argument("--address", default=None,
                        help="a running Ray cluster to join ('auto': the one this node belongs to); default: a local Ray")
    parser.add_argument("--out", type=Path, default=Path("runs/rllib"))
    parser.add_argument("--quick", action="store_true", help="one tiny iteration, for smoke tests")
    args = parser.parse_args()
    if args.quick:
        args.iterations, args.env_runners, args.batch = 1, 2, 64
    NetCatchEnv()  # compile the numba kernels once, before the env runner processes start
    if args.address is None:
        ray.init(num_cpus=args.env_runners + 1, include_dashboard=False, log_to_driver=False)
    else:
        ray.init(address=args.address, log_to_driver=False)
    print(f"Ray: {ray.cluster_resources().get('CPU', 0):g} CPUs; {args.env_runners} env runners")
    try:
        algo = build(args.env_runners, args.batch, min(args.batch, 256), 2 if args.quick else PPO_PARAMS["n_epochs"])
        for i in range(args.iterations):
            result = algo.train()
            runners = result.get("env_runners", {})
            print(f"iteration {i + 1}: env steps {runners.get('num_env_steps_sampled_lifetime')}, "
                  f"mean episode return {runners.get('episode_return_mean')}, "
                  f"env runners healthy {algo.env_runner_group.num_healthy_remote_workers()}")
        path = algo.save(str(args.out.resolve()))
        print(f"checkpoint: {getattr(path, 'checkpoint', path)}")
        algo.stop()
    finally:
        ray.shutdown()


if __name__ == "__main__":
    main()
