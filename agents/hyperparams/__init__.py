"""Hyperparameters in rl_zoo3's format, one file an algorithm in this folder (``ppo.yml``,
``sac.yml``, ...; ``python -m rl_zoo3.train --conf-file agents/hyperparams/ppo.yml`` reads them as
they are): :func:`load` reads an env id's settings, :func:`algorithm_kwargs` and
:func:`action_noise` turn them into keyword arguments of the algorithm's class. The PPO settings
of NetCatch-v0:

- :data:`PPO_PARAMS`: keyword arguments of Stable-Baselines3's ``PPO`` (``agents/training.py``);
- :data:`POLICY`, :data:`ENV_KWARGS`: the policy class name and the training environment's
  keyword arguments;
- :func:`rllib_training`: the settings that RLlib's ``PPOConfig.training`` shares, under its
  names (``scripts/train_rllib.py``).
"""

from __future__ import annotations

import ast
from pathlib import Path
from typing import Any

import numpy as np
import yaml

from netgym.errors import InvalidArgumentError
from netgym.wrappers import HiddenState

HERE = Path(__file__).resolve().parent
PPO_YML = HERE / "ppo.yml"
ENV_ID = "NetCatch-v0"
ZOO_ONLY = ("n_envs", "n_timesteps", "policy", "env_kwargs", "env_wrapper", "frame_stack")  # rl_zoo3's run settings
NOISE = ("noise_type", "noise_std")  # rl_zoo3's action noise of off-policy algorithms, see action_noise
# SB3 name -> RLlib PPOConfig.training name. Not mapped: clip_range, batch sizes and net_arch
# (train_rllib.py has always run with RLlib's own clip_param, its --batch option and RLlib's
# default model; taking them from here would change its training).
RLLIB_NAMES = {"learning_rate": "lr", "gamma": "gamma", "gae_lambda": "lambda_", "n_epochs": "num_epochs",
               "ent_coef": "entropy_coeff"}


def parse_policy_kwargs(text: str) -> dict[str, Any]:
    """rl_zoo3's ``policy_kwargs`` string, ``dict(name=literal, ...)``, as a dict, without
    evaluating it: anything but literal values (names, calls, attributes) raises
    InvalidArgumentError."""
    node = ast.parse(text, mode="eval").body
    if not (isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id == "dict"
            and not node.args and all(k.arg is not None for k in node.keywords)):
        raise InvalidArgumentError(f"policy_kwargs must read dict(name=literal, ...), not {text!r}")
    return {k.arg: ast.literal_eval(k.value) for k in node.keywords}


def yml(algorithm: str) -> Path:
    """The hyperparameter file of ``algorithm`` (its file name without ``.yml``, e.g. ``"sac"``)."""
    return HERE / f"{algorithm}.yml"


def env_ids(path: Path) -> list[str]:
    """The env ids the yml has settings for."""
    return list(yaml.safe_load(path.read_text()))


def load(path: Path = PPO_YML, env_id: str = ENV_ID) -> dict[str, Any]:
    """The yml's settings for ``env_id``, with ``policy_kwargs`` parsed into a dict."""
    settings = dict(yaml.safe_load(path.read_text())[env_id])
    if isinstance(settings.get("policy_kwargs"), str):
        settings["policy_kwargs"] = parse_policy_kwargs(settings["policy_kwargs"])
    return settings


def algorithm_kwargs(settings: dict[str, Any]) -> dict[str, Any]:
    """The settings that are keyword arguments of the algorithm's class (all but rl_zoo3's run
    settings and its action noise)."""
    return {key: value for key, value in settings.items() if key not in ZOO_ONLY + NOISE}


def action_noise(settings: dict[str, Any], n_actions: int) -> Any:
    """Stable-Baselines3's action noise that rl_zoo3 makes of ``noise_type`` (``normal`` or
    ``ornstein-uhlenbeck``) and ``noise_std``, or None when the settings have none."""
    from stable_baselines3.common.noise import NormalActionNoise, OrnsteinUhlenbeckActionNoise

    kinds = {"normal": NormalActionNoise, "ornstein-uhlenbeck": OrnsteinUhlenbeckActionNoise}
    kind = settings.get("noise_type")
    if kind is None:
        return None
    if kind not in kinds:
        raise InvalidArgumentError(f"noise_type = {kind!r} is not one of {list(kinds)}")
    return kinds[kind](mean=np.zeros(n_actions), sigma=settings["noise_std"] * np.ones(n_actions))


TRAINING_WRAPPERS = {"netgym.wrappers.HiddenState": HiddenState}
"""The wrappers an ``env_wrapper`` setting may name: they show training what acting does not
see, so a trained policy is evaluated without them."""


def env_wrapper(settings: dict[str, Any]) -> type[HiddenState] | None:
    """The training wrapper that rl_zoo3's ``env_wrapper`` setting names (its dotted class name,
    one of :data:`TRAINING_WRAPPERS`), or None when the settings have none."""
    name = settings.get("env_wrapper")
    if name is None:
        return None
    if name not in TRAINING_WRAPPERS:
        raise InvalidArgumentError(f"env_wrapper = {name!r} is not one of {list(TRAINING_WRAPPERS)}")
    return TRAINING_WRAPPERS[name]


TUNING: dict[str, str] = {
    "ppo": "on NetCatch-v0, then given to every vector id alike (docs/AGENTS.md)",
    "sac": "on NetCatch-v0, seeds 0-3, then given to every vector id alike",
    "td3": "on NetCatch-v0, seeds 0-3, then given to every vector id alike",
    "tqc": "none: sac.yml's settings, checked on NetCatch-v0 seeds 0-3; every vector id alike",
    "rppo": "none: ppo.yml's settings with an LSTM of 64 units",
    "ppo_cnn": "on NetCatchPixels-v0, seed 0",
    "sac_asym": "on each of its ids itself, seed 0: the state in the critics and a CNN actor on pixels; "
                "on NetCatchWindy-v0 the wind in the critics, 5 stacked observations, 256-unit critics, "
                "a falling target entropy and a 200k buffer",
    "sac_sym": "none: sac_asym's NetCatchWindy-v0 settings, its critics reading what the actor reads",
    "sac_drq": "on NetCatchPixels-v0, one run of seed 99 (not a table seed)",
}
"""Where each algorithm's settings were tuned, as its yml's header records it (the baselines page
shows this table: tuning on a task is an advantage there)."""

SETTINGS = load()
PPO_PARAMS: dict[str, Any] = algorithm_kwargs(SETTINGS)
POLICY: str = SETTINGS["policy"]
ENV_KWARGS: dict[str, Any] = SETTINGS["env_kwargs"]


def rllib_training() -> dict[str, Any]:
    """Keyword arguments of RLlib's ``PPOConfig.training`` for the settings it shares with SB3."""
    return {RLLIB_NAMES[key]: PPO_PARAMS[key] for key in RLLIB_NAMES}
