"""An RLlib checkpoint (``scripts/train_rllib.py``) as a policy with Stable-Baselines3's
``predict``: its RL module, restored in this process without starting Ray, acting as RLlib's env
runners act (the action distribution's deterministic action, unsquashed or clipped to the
action space as the checkpoint's config says).

Needs the ``rllib`` extra; ``ray`` is imported only when a checkpoint is loaded.
"""

from __future__ import annotations

import pickle
from pathlib import Path
from typing import Any

import numpy as np

from agents.model_env import record_env

RLLIB_EXTRA = 'Ray RLlib and torch: pip install torch==2.13.0 && pip install -e ".[rllib]"'
"""What an RLlib checkpoint needs, and how to install it."""
ENV_PREFIX = "netgym/"
"""How scripts/train_rllib.py names a registered NetCatch id for ``register_env``."""
MODULE_PATH = Path("learner_group") / "learner" / "rl_module" / "default_policy"
"""Where an algorithm checkpoint keeps its (single-agent) RL module."""


def is_rllib_checkpoint(path: str | Path) -> bool:
    """Whether ``path`` is the folder of an RLlib algorithm checkpoint."""
    return (Path(path) / "rllib_checkpoint.json").is_file()


class RLlibPolicy:
    """The policy of an RLlib algorithm checkpoint at ``path``, acting in one env."""

    def __init__(self, path: str | Path) -> None:
        path = Path(path)
        if not is_rllib_checkpoint(path):
            raise FileNotFoundError(f"{str(path)!r} is not an RLlib checkpoint folder (no rllib_checkpoint.json)")
        if not (path / MODULE_PATH).is_dir():
            raise FileNotFoundError(f"the RLlib checkpoint {str(path)!r} has no single-agent module at {MODULE_PATH}")
        try:
            import torch
            from ray.rllib.core.rl_module.rl_module import RLModule
            from ray.rllib.utils.spaces.space_utils import unsquash_action
        except ImportError as missing:
            raise ImportError(f"loading the RLlib checkpoint {str(path)!r} needs {RLLIB_EXTRA}") from missing
        self._torch, self._unsquash = torch, unsquash_action
        self.module = RLModule.from_checkpoint(str(path / MODULE_PATH))
        self.observation_space, self.action_space = self.module.observation_space, self.module.action_space
        with open(path / "class_and_ctor_args.pkl", "rb") as file:
            config = pickle.load(file)["ctor_args_and_kwargs"][0][0]
        self.normalize_actions, self.clip_actions = bool(config["normalize_actions"]), bool(config["clip_actions"])
        if isinstance(config.get("env"), str) and config["env"].startswith(ENV_PREFIX):
            record_env(self, config["env"][len(ENV_PREFIX):])  # the env it trained on, as SB3 models record it

    def predict(self, observation: np.ndarray, state: Any = None, episode_start: Any = None,
                deterministic: bool = True) -> tuple[np.ndarray, Any]:
        """The module's action for one observation: the distribution's mode when
        ``deterministic``, else a sample; in the env's action space."""
        obs = self._torch.as_tensor(np.asarray(observation, dtype=np.float32).reshape(1, -1))
        with self._torch.no_grad():
            out = self.module.forward_inference({"obs": obs})
        dist = self.module.get_inference_action_dist_cls().from_logits(out["action_dist_inputs"])
        action = (dist.to_deterministic() if deterministic else dist).sample()[0].numpy()
        if self.normalize_actions:
            action = self._unsquash(action, self.action_space)
        elif self.clip_actions:
            action = np.clip(action, self.action_space.low, self.action_space.high)
        return action, state
