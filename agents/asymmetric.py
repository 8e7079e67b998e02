"""SAC with an asymmetric actor-critic, for the pixel task: the actor, which is the policy, acts on
the image alone through a CNN; the critics, used only in training, read the env's vector state
(Pinto et al., 2018, "Asymmetric Actor Critic for Image-Based Robot Learning"). The critics then
learn the value of an aim from a handful of numbers instead of from pixels, and the actor learns
to read the image by following their gradient.

Train it on ``NetCatchPixels-v0`` made with ``with_state=True`` (a Dict of ``"pixels"`` and
``"state"``, :class:`~netgym.wrappers.ThrowerView`); the trained policy acts on
``NetCatchPixels-v0``'s images, or on the ``"pixels"`` of that Dict: acting never reads the state.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import torch
from gymnasium import spaces
from stable_baselines3 import SAC
from stable_baselines3.common.policies import ContinuousCritic
from stable_baselines3.common.torch_layers import BaseFeaturesExtractor, NatureCNN
from stable_baselines3.sac.policies import SACPolicy

from netgym.errors import InvalidArgumentError

TRAINING_ONLY = ("with_state",)
"""Env arguments of training alone: the policy is evaluated without them, on the images."""


def acting_kwargs(env_kwargs: dict[str, Any]) -> dict[str, Any]:
    """``env_kwargs`` less :data:`TRAINING_ONLY`: the env the trained policy acts in."""
    return {name: value for name, value in env_kwargs.items() if name not in TRAINING_ONLY}


class PixelFeatures(BaseFeaturesExtractor):
    """SB3's NatureCNN on the ``"pixels"`` of a Dict observation; nothing else is read."""

    def __init__(self, observation_space: spaces.Dict, features_dim: int = 256) -> None:
        super().__init__(observation_space, features_dim)
        self.cnn = NatureCNN(observation_space["pixels"], features_dim)

    def forward(self, observations: dict[str, torch.Tensor]) -> torch.Tensor:
        """The CNN's features of the images."""
        return self.cnn(observations["pixels"])


class StateFeatures(BaseFeaturesExtractor):
    """The ``"state"`` of a Dict observation, as it is."""

    def __init__(self, observation_space: spaces.Dict) -> None:
        super().__init__(observation_space, int(np.prod(observation_space["state"].shape)))

    def forward(self, observations: dict[str, torch.Tensor]) -> torch.Tensor:
        """The state vectors, flattened."""
        return torch.flatten(observations["state"], start_dim=1)


class AsymmetricSACPolicy(SACPolicy):
    """SAC's policy with an actor on the images (:class:`PixelFeatures`) and critics on the state
    (:class:`StateFeatures`); observations are Dicts of ``"pixels"`` and ``"state"``."""

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        if kwargs.get("share_features_extractor"):
            raise InvalidArgumentError("share_features_extractor = True; the actor reads the pixels and the critics "
                                       "the state, so they cannot share one")
        kwargs.setdefault("features_extractor_class", PixelFeatures)
        super().__init__(*args, **kwargs)

    def make_critic(self, features_extractor: BaseFeaturesExtractor | None = None) -> ContinuousCritic:
        """Critics on the state (a features extractor passed in is not used: it reads pixels)."""
        kwargs = self._update_features_extractor(self.critic_kwargs, StateFeatures(self.observation_space))
        return ContinuousCritic(**kwargs).to(self.device)

    def predict(self, observation: np.ndarray | dict[str, np.ndarray], state: Any = None, episode_start: Any = None,
                deterministic: bool = False) -> tuple[np.ndarray, Any]:
        """The actor's action for an image (H x W x 3, or a batch of them), or for the ``"pixels"``
        of a Dict observation: the state is dropped before the actor sees anything."""
        pixels = observation["pixels"] if isinstance(observation, dict) else observation
        return super().predict({"pixels": pixels}, state, episode_start, deterministic)


class AsymmetricSAC(SAC):
    """Stable-Baselines3's SAC, whose policy ``"AsymmetricCnnPolicy"`` is :class:`AsymmetricSACPolicy`."""

    policy_aliases = {**SAC.policy_aliases, "AsymmetricCnnPolicy": AsymmetricSACPolicy}
