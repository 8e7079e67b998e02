"""SAC from pixels alone, in the spirit of DrQ (Kostrikov et al., 2021, "Image Augmentation Is All
You Need") and DrQ-v2 (Yarats et al., 2022): one image encoder, trained by the critics' loss only;
the actor reads its features detached; every image of a training batch is shifted at random by up
to 4 pixels (padded by its edge pixels), so the critics cannot fit one throw's exact pixels.

Nothing privileged: actor, critics and encoder see the 84 x 84 image of ``NetCatchPixels-v0`` and
nothing else, in training as in acting (unlike :mod:`agents.asymmetric`, whose critics read the
state). Acting (``predict``) and collecting are in eval mode: unshifted images.

The encoder is most of the cost on a CPU, so a gradient step passes each batch through it once
(:meth:`DrQSAC.train`: the critics' features, detached for the actor and its loss) where SB3's
SAC would pass it four times, and the next images only where a discount makes the target need
them; its convolutions are NatureCNN's with 32 channels each.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import torch
from gymnasium import spaces
from stable_baselines3 import SAC
from stable_baselines3.common.torch_layers import BaseFeaturesExtractor
from stable_baselines3.common.utils import polyak_update
from stable_baselines3.sac.policies import LOG_STD_MAX, LOG_STD_MIN, Actor, SACPolicy
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
    """NatureCNN's three convolutions (8x8 stride 4, 4x4 stride 2, 3x3) with ``channels`` channels
    each, then a linear layer to ``features_dim`` features with layer normalisation and tanh
    (DrQ's head); in training mode each image is shifted first (:func:`random_shift`)."""

    def __init__(self, observation_space: spaces.Box, features_dim: int = 50, channels: int = 32) -> None:
        super().__init__(observation_space, features_dim)
        self.convolutions = nn.Sequential(
            nn.Conv2d(observation_space.shape[0], channels, 8, stride=4), nn.ReLU(),
            nn.Conv2d(channels, channels, 4, stride=2), nn.ReLU(),
            nn.Conv2d(channels, channels, 3, stride=1), nn.ReLU(), nn.Flatten())
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
    """Stable-Baselines3's SAC with the policy ``"DrQCnnPolicy"`` (:class:`CriticEncoderPolicy`)
    and a gradient step that passes each batch through the encoder once (:meth:`train`)."""

    policy_aliases = {**SAC.policy_aliases, "DrQCnnPolicy": CriticEncoderPolicy}

    def _actions(self, features: torch.Tensor) -> tuple[torch.Tensor, torch.Tensor]:
        """The actor's sampled actions and their log-probabilities, from encoder features."""
        latent = self.actor.latent_pi(features)
        log_std = torch.clamp(self.actor.log_std(latent), LOG_STD_MIN, LOG_STD_MAX)
        actions, log_prob = self.actor.action_dist.log_prob_from_params(self.actor.mu(latent), log_std)
        return actions, log_prob.reshape(-1, 1)

    def _q_values(self, critic: Any, features: torch.Tensor, actions: torch.Tensor) -> list[torch.Tensor]:
        """Each of ``critic``'s Q-networks on encoder features and actions."""
        return [q_net(torch.cat([features, actions], dim=1)) for q_net in critic.q_networks]

    def _target(self, data: Any, ent_coef: torch.Tensor) -> torch.Tensor:
        """The critics' target: the reward, plus the discounted soft value of the next images
        (their features from the online encoder for the actor, the target encoder for the target
        critics) where the discount is not 0."""
        if self.gamma == 0.0:
            return data.rewards
        with torch.no_grad():
            next_actions, next_log_prob = self._actions(
                self.critic.extract_features(data.next_observations, self.critic.features_extractor))
            target_features = self.critic_target.extract_features(data.next_observations,
                                                                  self.critic_target.features_extractor)
            next_q = torch.min(torch.cat(self._q_values(self.critic_target, target_features, next_actions), dim=1),
                               dim=1, keepdim=True)[0] - ent_coef * next_log_prob
            return data.rewards + (1 - data.dones) * self.gamma * next_q

    def train(self, gradient_steps: int, batch_size: int = 64) -> None:
        """SAC's gradient steps (its entropy coefficient, critic and actor updates and Polyak
        averaging), the batch's images encoded once, shifted: the critics' loss trains the
        encoder, the actor reads the same features detached."""
        if self.use_sde:
            raise ValueError("DrQSAC does not support gSDE (use_sde=True)")
        self.policy.set_training_mode(True)
        optimizers = [self.actor.optimizer, self.critic.optimizer]
        if self.ent_coef_optimizer is not None:
            optimizers.append(self.ent_coef_optimizer)
        self._update_learning_rate(optimizers)
        losses: dict[str, list[float]] = {"actor_loss": [], "critic_loss": [], "ent_coef": []}
        for gradient_step in range(gradient_steps):
            data = self.replay_buffer.sample(batch_size, env=self._vec_normalize_env)
            features = self.critic.extract_features(data.observations, self.critic.features_extractor)
            actions_pi, log_prob = self._actions(features.detach())
            ent_coef = self._entropy_coefficient(log_prob)
            target = self._target(data, ent_coef)
            critic_loss = 0.5 * sum(functional.mse_loss(q, target) for q in self._q_values(self.critic, features,
                                                                                         data.actions))
            self.critic.optimizer.zero_grad()
            critic_loss.backward()
            self.critic.optimizer.step()
            q_pi = torch.cat(self._q_values(self.critic, features.detach(), actions_pi), dim=1)
            actor_loss = (ent_coef * log_prob - torch.min(q_pi, dim=1, keepdim=True)[0]).mean()
            self.actor.optimizer.zero_grad()
            actor_loss.backward()
            self.actor.optimizer.step()
            if gradient_step % self.target_update_interval == 0:
                polyak_update(self.critic.parameters(), self.critic_target.parameters(), self.tau)
            for name, value in (("actor_loss", actor_loss), ("critic_loss", critic_loss), ("ent_coef", ent_coef)):
                losses[name].append(float(value.item()))
        self._n_updates += gradient_steps
        self.logger.record("train/n_updates", self._n_updates, exclude="tensorboard")
        for name, values in losses.items():
            self.logger.record(f"train/{name}", float(np.mean(values)))

    def _entropy_coefficient(self, log_prob: torch.Tensor) -> torch.Tensor:
        """SAC's entropy coefficient for this step, after its own update where it is learned."""
        if self.ent_coef_optimizer is None or self.log_ent_coef is None:
            return self.ent_coef_tensor
        ent_coef = torch.exp(self.log_ent_coef.detach())
        loss = -(self.log_ent_coef * (log_prob + self.target_entropy).detach()).mean()
        self.ent_coef_optimizer.zero_grad()
        loss.backward()
        self.ent_coef_optimizer.step()
        return ent_coef
