"""PPO on NetCatch-v0 with Ray RLlib: the algorithm built from agents/hyperparams/ppo.yml, the
capture-counting callback, and a training run that reports each iteration (``scripts/train_rllib.py``
parses its options). Requires the ``rllib`` extra; ray is imported inside the functions."""

from __future__ import annotations

import argparse
import time
from pathlib import Path
from typing import Any

from agents.hyperparams import ENV_KWARGS, PPO_PARAMS, rllib_training  # from agents/hyperparams/ppo.yml
from netgym.envs import NetCatchEnv
from netgym.envs.net_catch import REWARD_MODES

ENV_NAME = "netgym/NetCatch-v0"
SB3_DEFAULTS = {"use_kl_loss": False, "vf_loss_coeff": 0.5, "grad_clip": 0.5}
"""Stable-Baselines3's PPO defaults (no KL penalty, value loss weight, gradient norm clip) where
RLlib's differ: the settings under which ppo.yml's values were tuned."""
HEAD_RESOURCE = "node:__internal_head__"
"""The resource Ray gives the head node alone."""
RESTART_DELAY_S = 1.0
"""Seconds between attempts to restart a lost env runner (RLlib's default is 60)."""


def make_env(env_config: dict) -> NetCatchEnv:
    """RLlib env creator: NetCatch-v0 with ``env_config`` as keyword arguments."""
    return NetCatchEnv(**env_config)


def capture_counter() -> type:
    """An RLlib callback class that counts, over the episodes the env runners finish, the throws
    and the captures (``info["captured"]``), as sums per training iteration (``throws`` and
    ``captures`` under the result's ``env_runners``); an episode cut into chunks counts once."""
    from ray.rllib.callbacks.callbacks import RLlibCallback

    class CaptureCounter(RLlibCallback):
        def on_episode_end(self, *, episode, prev_episode_chunks=None, metrics_logger=None, **kwargs) -> None:
            steps = [info for chunk in [*(prev_episode_chunks or []), episode] for info in chunk.get_infos()[1:]]
            metrics_logger.log_value("throws", len(steps), reduce="sum", clear_on_reduce=True)
            metrics_logger.log_value("captures", sum(bool(info.get("captured")) for info in steps), reduce="sum",
                                     clear_on_reduce=True)

    return CaptureCounter


def capture_rate(runners: dict) -> float | None:
    """The capture rate of an iteration's finished episodes (its result's ``env_runners``), or
    None when none finished."""
    throws = runners.get("throws") or 0
    return runners.get("captures", 0) / throws if throws else None


def build(env_runners: int, batch: int, minibatch: int, epochs: int, reward_mode: str | None = None):
    """The PPO algorithm on NetCatch-v0, with the training environment's arguments and the
    settings RLlib shares with SB3 (learning rate, gamma, lambda, entropy coefficient) from
    agents/hyperparams/ppo.yml; ``epochs`` overrides its ``n_epochs``, ``reward_mode`` (when
    given) its environment's ``reward_mode``."""
    from ray.rllib.algorithms.ppo import PPOConfig
    from ray.rllib.core.rl_module.default_model_config import DefaultModelConfig
    from ray.tune.registry import register_env

    register_env(ENV_NAME, make_env)
    config = (
        PPOConfig()
        .environment(ENV_NAME, env_config={**ENV_KWARGS, **({"reward_mode": reward_mode} if reward_mode else {})})
        .env_runners(num_env_runners=env_runners, num_envs_per_env_runner=1)
        .rl_module(model_config=DefaultModelConfig(fcnet_hiddens=PPO_PARAMS["policy_kwargs"]["net_arch"]))
        .training(**{**rllib_training(), "num_epochs": epochs}, train_batch_size_per_learner=batch,
                  minibatch_size=minibatch, clip_param=PPO_PARAMS["clip_range"], **SB3_DEFAULTS)
        .callbacks(capture_counter())
        .fault_tolerance(restart_failed_env_runners=True, delay_between_env_runner_restarts_s=RESTART_DELAY_S,
                         env_runner_health_probe_timeout_s=10.0)
    )
    return config.build_algo()


def env_runner_nodes(algo) -> list[str]:
    """The Ray node id of each healthy remote env runner, asked of the runners themselves."""
    import ray

    return algo.env_runner_group.foreach_env_runner(lambda runner: ray.get_runtime_context().get_node_id(),
                                                    local_env_runner=False)


def build_parser(description: str | None = None) -> argparse.ArgumentParser:
    """The command line of ``scripts/train_rllib.py`` (the recipes in deploy/ are checked against it)."""
    parser = argparse.ArgumentParser(description=description, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--iterations", type=int, default=50)
    parser.add_argument("--env-runners", type=int, default=2)
    parser.add_argument("--batch", type=int, default=1024)
    parser.add_argument("--address", default=None,
                        help="a running Ray cluster to join ('auto': the one this node belongs to); default: a local Ray")
    parser.add_argument("--out", type=Path, default=Path("runs/rllib"))
    parser.add_argument("--summary", type=Path, help="write the run's figures here as JSON")
    parser.add_argument("--reward-mode", choices=REWARD_MODES,
                        help=f"the environment's reward_mode (default: ppo.yml's, {ENV_KWARGS.get('reward_mode')!r})")
    parser.add_argument("--quick", action="store_true", help="one tiny iteration, for smoke tests")
    return parser


def train(iterations: int, env_runners: int, batch: int, address: str | None, out: Path,
          reward_mode: str | None = None, quick: bool = False) -> dict[str, Any]:
    """Train ``iterations`` PPO iterations on ``env_runners`` env runners (a local Ray, or the
    cluster at ``address``), printing each; save the checkpoint under ``out``; returns the run's
    summary (nodes, where the env runners ran, each iteration's figures, the checkpoint)."""
    import ray

    if quick:
        iterations, env_runners, batch = 1, 2, 64
    NetCatchEnv()  # compile the numba kernels once, before the env runner processes start
    if address is None:
        ray.init(num_cpus=env_runners + 1, include_dashboard=False, log_to_driver=False)
    else:
        ray.init(address=address, log_to_driver=False)
    nodes = [node["NodeID"] for node in ray.nodes() if node["Alive"]]
    head = next(node["NodeID"] for node in ray.nodes() if node["Alive"] and HEAD_RESOURCE in node["Resources"])
    print(f"Ray: {ray.cluster_resources().get('CPU', 0):g} CPUs on {len(nodes)} nodes; {env_runners} env runners")
    try:
        algo = build(env_runners, batch, min(batch, PPO_PARAMS["batch_size"]),
                     2 if quick else PPO_PARAMS["n_epochs"], reward_mode)
        placement = env_runner_nodes(algo)
        print(f"env runners on nodes: {placement}")
        records = []
        for i in range(iterations):
            start = time.time()
            result = algo.train()
            runners = result.get("env_runners", {})
            records.append({"end": time.time(), "seconds": time.time() - start,
                               "env_steps": runners.get("num_env_steps_sampled_lifetime"),
                               "episode_return_mean": runners.get("episode_return_mean"),
                               "capture_rate": capture_rate(runners),
                               "healthy": algo.env_runner_group.num_healthy_remote_workers()})
            print(f"iteration {i + 1}: {records[-1]['seconds']:.1f} s, env steps {records[-1]['env_steps']}, "
                  f"mean episode return {records[-1]['episode_return_mean']}, "
                  f"capture rate {records[-1]['capture_rate']}, "
                  f"env runners healthy {records[-1]['healthy']}", flush=True)
        checkpoint = algo.save_to_path(str(out.resolve()))
        print(f"checkpoint: {checkpoint}")
        summary = {"nodes": nodes, "head_node": head, "env_runner_nodes": placement,
                   "final_env_runner_nodes": env_runner_nodes(algo), "iterations": records, "checkpoint": checkpoint}
        algo.stop()
    finally:
        ray.shutdown()
    return summary
