"""SAC from pixels alone, in the spirit of DrQ (Kostrikov et al., 2021, "Image Augmentation Is All
You Need") and DrQ-v2 (Yarats et al., 2022): one image encoder, trained by the critics' loss only;
the actor reads its features detached; every image of a training batch is shifted at random by up
to 4 pixels (padded by its edge pixels), so the critics cannot fit one throw's exact pixels.

Nothing privileged: actor, critics and encoder see the 84 x 84 image of ``NetCatchPixels-v0`` and
nothing else, in training as in acting (unlike :mod:`agents.asymmetric`, whose critics read the
state). Acting (``predict``) and collecting are in eval mode: unshifted images.
"""

from __future__ import annotations

from typing import Any

import torch
from gymnasium import spaces
from stable_baselines3 import SAC
from stable_baselines3.common.torch_layers import BaseFeaturesExtractor, NatureCNN
from stable_baselines3.sac.policies import Actor, SACPolicy
from torch import nn
from torch.nn import functional

SHIFT_PIXELS = 4
"""The largest shift of the augmentation, DrQ's 4 pixels of an 84-pixel image."""


def random_shift(images: torch.Tensor, pad: int = SHIFT_PIXELS) -> torch.Tensor:
    """Each image of a batch (N, C, H, H) moved by a whole number of pixels drawn from
    ``-pad..pad`` in each direction, its edge pixels repeated into the uncovered border (DrQ-v2's
    bilinear sampling at integer offsets; torch's random generator, which SB3 seeds)."""
    n, _, height, width = images.shape
    if height != width:
        raise ValueError(f"random_shift takes square images, not {height} x {width}")
    padded = functional.pad(images, (pad, pad, pad, pad), mode="replicate")
    size = height + 2 * pad
    step = 1.0 / size
    ticks = torch.linspace(-1.0 + step, 1.0 - step, size, device=images.device, dtype=images.dtype)[:height]
    base = torch.stack(torch.meshgrid(ticks, ticks, indexing="xy"), dim=2).unsqueeze(0)
    shift = torch.randint(0, 2 * pad + 1, (n, 1, 1, 2), device=images.device).to(images.dtype) * (2.0 / size)
    return functional.grid_sample(padded, base + shift, padding_mode="zeros", align_corners=False)


class ShiftedNatureEncoder(BaseFeaturesExtractor):
    """NatureCNN's three convolutions, then a linear layer to ``features_dim`` features with layer
    normalisation and tanh (DrQ's head); in training mode each image is shifted first
    (:func:`random_shift`)."""

    def __init__(self, observation_space: spaces.Box, features_dim: int = 50) -> None:
        super().__init__(observation_space, features_dim)
        self.convolutions = NatureCNN(observation_space, normalized_image=False).cnn
        with torch.no_grad():
            flat = self.convolutions(torch.as_tensor(observation_space.sample()[None]).float()).shape[1]
        self.head = nn.Sequential(nn.Linear(flat, features_dim), nn.LayerNorm(features_dim), nn.Tanh())

    def forward(self, observations: torch.Tensor) -> torch.Tensor:
        """Features of a batch of images (already scaled to [0, 1] by SB3)."""
        seen = random_shift(observations) if self.training else observations
        return self.head(self.convolutions(seen))


class DetachedEncoderActor(Actor):
    """SAC's actor on the encoder's features, detached: the actor's loss does not train the encoder."""

    def extract_features(self, obs: Any, features_extractor: BaseFeaturesExtractor) -> torch.Tensor:
        """The encoder's features of ``obs``, cut from the graph."""
        return super().extract_features(obs, features_extractor).detach()


class CriticEncoderPolicy(SACPolicy):
    """SAC's policy with one encoder that the critics own and train; the actor reads it detached
    (:class:`DetachedEncoderActor`) and its optimiser leaves the encoder out. The target critics
    keep an encoder of their own, as in SAC."""

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        kwargs.setdefault("features_extractor_class", ShiftedNatureEncoder)
        kwargs["share_features_extractor"] = False  # the critics compute the encoder's gradient
        super().__init__(*args, **kwargs)

    def make_actor(self, features_extractor: BaseFeaturesExtractor | None = None) -> DetachedEncoderActor:
        """The actor, on ``features_extractor`` (the critics' encoder)."""
        actor_kwargs = self._update_features_extractor(self.actor_kwargs, features_extractor)
        return DetachedEncoderActor(**actor_kwargs).to(self.device)

    def _build(self, lr_schedule: Any) -> None:
        self.critic = self.make_critic(features_extractor=None)
        self.actor = self.make_actor(features_extractor=self.critic.features_extractor)
        own = [param for name, param in self.actor.named_parameters() if not name.startswith("features_extractor.")]
        self.actor.optimizer = self.optimizer_class(own, lr=lr_schedule(1), **self.optimizer_kwargs)
        self.critic_target = self.make_critic(features_extractor=None)
        self.critic_target.load_state_dict(self.critic.state_dict())
        self.critic.optimizer = self.optimizer_class(self.critic.parameters(), lr=lr_schedule(1),
                                                     **self.optimizer_kwargs)
        self.critic_target.set_training_mode(False)


class DrQSAC(SAC):
    """Stable-Baselines3's SAC with the policy ``"DrQCnnPolicy"`` (:class:`CriticEncoderPolicy`)."""

    policy_aliases = {**SAC.policy_aliases, "DrQCnnPolicy": CriticEncoderPolicy}
