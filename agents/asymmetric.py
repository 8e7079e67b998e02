"""SAC with an asymmetric actor-critic: the actor, which is the policy, acts on what the env
shows; the critics, used only in training, also read what it hides (Pinto et al., 2018,
"Asymmetric Actor Critic for Image-Based Robot Learning"). The critics then learn the value of an
aim from a handful of numbers, and the actor learns to act on what it sees by following them.

- Pixels: train on ``NetCatchPixels-v0`` made with ``with_state=True`` (a Dict of ``"pixels"``
  and ``"state"``, :class:`~netgym.wrappers.ThrowerView`): the actor is a CNN on the image, the
  critics read the vector state.
- Hidden wind or scene: train on a vector id wrapped in :class:`~netgym.wrappers.HiddenState`
  (a Dict of ``"observation"`` and ``"state"``, the observation followed by the episode's wind
  and randomised scene fields): the actor is an MLP on the observation.

The trained policy acts on the env's own observations (or on the acting key of such a Dict):
acting never reads the state.
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
from netgym.wrappers import STATE_KEY, acting_key

TRAINING_ONLY = ("with_state",)
"""Env arguments of training alone: the policy is evaluated without them, on the images."""


def acting_kwargs(env_kwargs: dict[str, Any]) -> dict[str, Any]:
    """``env_kwargs`` less :data:`TRAINING_ONLY`: the env the trained policy acts in."""
    return {name: value for name, value in env_kwargs.items() if name not in TRAINING_ONLY}


class KeyFeatures(BaseFeaturesExtractor):
    """One key of a Dict observation, flattened; the others are not read."""

    def __init__(self, observation_space: spaces.Dict, key: str) -> None:
        super().__init__(observation_space, int(np.prod(observation_space[key].shape)))
        self.key = key

    def forward(self, observations: dict[str, torch.Tensor]) -> torch.Tensor:
        """The key's vectors, flattened."""
        return torch.flatten(observations[self.key], start_dim=1)


class PixelFeatures(BaseFeaturesExtractor):
    """SB3's NatureCNN on the ``"pixels"`` of a Dict observation; nothing else is read."""

    def __init__(self, observation_space: spaces.Dict, features_dim: int = 256) -> None:
        super().__init__(observation_space, features_dim)
        self.cnn = NatureCNN(observation_space["pixels"], features_dim)

    def forward(self, observations: dict[str, torch.Tensor]) -> torch.Tensor:
        """The CNN's features of the images."""
        return self.cnn(observations["pixels"])


class ObservationFeatures(KeyFeatures):
    """The ``"observation"`` of a Dict observation, as it is."""

    def __init__(self, observation_space: spaces.Dict) -> None:
        super().__init__(observation_space, "observation")


class AsymmetricSACPolicy(SACPolicy):
    """SAC's policy with an actor on the Dict's acting key (:func:`acting_key`: a CNN on
    ``"pixels"``, or the ``"observation"`` as it is) and critics on its ``"state"``."""

    def __init__(self, observation_space: spaces.Dict, *args: Any, **kwargs: Any) -> None:
        if kwargs.get("share_features_extractor"):
            raise InvalidArgumentError("share_features_extractor = True; the actor and the critics read different "
                                       "parts of the observation, so they cannot share one")
        self.acting_key = acting_key(observation_space)
        kwargs.setdefault("features_extractor_class",
                          PixelFeatures if self.acting_key == "pixels" else ObservationFeatures)
        super().__init__(observation_space, *args, **kwargs)

    def make_critic(self, features_extractor: BaseFeaturesExtractor | None = None) -> ContinuousCritic:
        """Critics on the state (a features extractor passed in is not used: it is the actor's)."""
        state = KeyFeatures(self.observation_space, STATE_KEY)
        return ContinuousCritic(**self._update_features_extractor(self.critic_kwargs, state)).to(self.device)

    def predict(self, observation: np.ndarray | dict[str, np.ndarray], state: Any = None, episode_start: Any = None,
                deterministic: bool = False) -> tuple[np.ndarray, Any]:
        """The actor's action for what it acts on (an image or an observation vector, or a batch
        of them), or for the acting key of a Dict observation: the state is dropped before the
        actor sees anything."""
        seen = observation[self.acting_key] if isinstance(observation, dict) else observation
        return super().predict({self.acting_key: seen}, state, episode_start, deterministic)


class AsymmetricSAC(SAC):
    """Stable-Baselines3's SAC with the policies ``"AsymmetricCnnPolicy"`` and
    ``"AsymmetricMlpPolicy"`` (both :class:`AsymmetricSACPolicy`, whose actor follows the
    observation's keys), and a target entropy that can fall during training.

    :param target_entropy_end: None: SAC's fixed target entropy; a number: the target entropy
        holds at SAC's value for the first third of ``learn``'s steps, falls linearly to this value
        over the second third and holds there for the last. A lower target entropy shrinks the
        exploration noise, whose mean action is the best one for a noisy throw, not for an exact one.
    """

    policy_aliases = {**SAC.policy_aliases, "AsymmetricCnnPolicy": AsymmetricSACPolicy,
                      "AsymmetricMlpPolicy": AsymmetricSACPolicy}

    def __init__(self, *args: Any, target_entropy_end: float | None = None, **kwargs: Any) -> None:
        self.target_entropy_end = target_entropy_end
        super().__init__(*args, **kwargs)

    def _setup_model(self) -> None:
        super()._setup_model()
        if not hasattr(self, "target_entropy_start"):  # a loaded model has its own, and a fallen target
            self.target_entropy_start = float(self.target_entropy)

    def train(self, gradient_steps: int, batch_size: int = 64) -> None:
        """SAC's gradient steps, at the target entropy of this point of training."""
        if self.target_entropy_end is not None:
            done = 1.0 - self._current_progress_remaining
            fall = min(max(3.0 * done - 1.0, 0.0), 1.0)
            start, end = self.target_entropy_start, self.target_entropy_end
            self.target_entropy = start + fall * (end - start)
        super().train(gradient_steps, batch_size)
