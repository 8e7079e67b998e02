"""Train PPO on NetCatch-v0 with Ray RLlib: the path for users who outgrow one machine.

The environment is registered with ``register_env`` and sampled by ``--env-runners`` RLlib env
runners, one process each, in parallel. Requires the ``rllib`` extra: ``pip install -e ".[rllib]"``.

On a Ray cluster the same script spreads the env runners over the machines: install netgym on
every node (the same ``pip install -e ".[rllib]"``), start the cluster (``ray start --head`` on
one node, ``ray start --address=HEAD_IP:6379`` on the others, or a cluster launcher), then run
the script on a node of the cluster with ``--address auto`` and as many ``--env-runners`` as
the cluster has CPUs to spare (one learner CPU stays on the head). Recipes for a real cluster:
``deploy/ray-cluster.yaml`` (Ray's cluster launcher) and ``deploy/rayjob.yaml`` (KubeRay).

RLlib's fault tolerance is on: an env runner lost with its node (or its process) is restarted
as soon as the cluster has a CPU for it, and training goes on with the healthy ones meanwhile.
The script prints, each iteration, its seconds, the capture rate of the episodes its env runners
finished (by default the training return is the shaped reward of ``agents/hyperparams/ppo.yml``,
which pays near misses too; ``--reward-mode sparse`` pays captures alone), the healthy env runners,
and where the env runners run; ``--summary`` writes the same as JSON. The checkpoint is a policy
that ``scripts/evaluate.py`` evaluates like a saved SB3 model.

Usage::

    python scripts/train_rllib.py --iterations 50 --env-runners 2           # this machine
    python scripts/train_rllib.py --address auto --env-runners 64           # a running Ray cluster
    python scripts/train_rllib.py --quick                                   # smoke test: 2 env runners
"""

from __future__ import annotations

import json

from agents.rllib_training import build_parser, train


def main() -> None:
    """Parse arguments, train, report, save a checkpoint."""
    args = build_parser(__doc__).parse_args()
    summary = train(args.iterations, args.env_runners, args.batch, args.address, args.out, args.reward_mode, args.quick)
    if args.summary is not None:
        args.summary.write_text(json.dumps(summary, indent=1) + "\n")


if __name__ == "__main__":
    main()
