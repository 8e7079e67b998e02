"""SAC from pixels alone (agents/drq.py): the random shift against cropping by hand, the encoder
trained by the critics' loss and not the actor's, nothing but the image read."""

from __future__ import annotations

import gymnasium as gym
import numpy as np
import pytest
import torch

import netgym  # noqa: F401  (registers the ids)
from agents.drq import SHIFT_PIXELS, DrQSAC, ShiftedNatureEncoder, random_shift


def test_random_shift_moves_each_image_by_whole_pixels_within_the_pad() -> None:
    torch.manual_seed(0)
    images = torch.rand(16, 3, 84, 84)
    shifted = random_shift(images)
    padded = torch.nn.functional.pad(images, (SHIFT_PIXELS,) * 4, mode="replicate")
    span = range(2 * SHIFT_PIXELS + 1)
    offsets = []
    for k in range(len(images)):
        matches = [(dy, dx) for dy in span for dx in span
                   if torch.allclose(shifted[k], padded[k, :, dy:dy + 84, dx:dx + 84], atol=1e-4)]  # float32 sampling; crops differ by ~0.5
        assert len(matches) == 1, f"image {k} is no crop of its padded self"
        offsets.append(matches[0])
    assert len(set(offsets)) > 1  # drawn per image
    with pytest.raises(ValueError, match="square"):
        random_shift(torch.rand(1, 3, 84, 80))


def _model(steps: int = 0, gamma: float = 0.0) -> DrQSAC:
    env = gym.make("NetCatchPixels-v0")
    model = DrQSAC("DrQCnnPolicy", env, seed=0, device="cpu", learning_starts=8, batch_size=8, buffer_size=64,
                   gamma=gamma, train_freq=4, policy_kwargs=dict(net_arch=[32, 32]))
    if steps:
        model.learn(steps)
    return model


@pytest.mark.slow
@pytest.mark.parametrize(("gamma", "passes"), [(0.0, 1), (0.5, 2)])
def test_a_gradient_step_encodes_the_batch_once_and_only_the_critics_move_the_encoder(gamma: float, passes: int,
                                                                                     monkeypatch) -> None:
    """One pass of the online encoder a gradient step (two where a discount needs the next
    images); with the critics' optimiser stopped, the actor's and entropy's steps leave the
    encoder as it was, and the critics' step moves it."""
    model = _model(gamma=gamma)
    model.learning_starts = 10_000
    model.learn(16)  # fills the buffer, no gradient step
    encoder = model.policy.critic.features_extractor
    calls = []
    encoder.register_forward_hook(lambda *_: calls.append(1))
    before = [p.detach().clone() for p in encoder.parameters()]
    actor_before = [p.detach().clone() for p in model.policy.actor.latent_pi.parameters()]
    monkeypatch.setattr(model.critic.optimizer, "step", lambda *args, **kwargs: None)
    model.train(gradient_steps=1, batch_size=8)
    assert len(calls) == passes
    assert all(torch.equal(a, b) for a, b in zip(encoder.parameters(), before))
    assert any(not torch.equal(a, b) for a, b in zip(model.policy.actor.latent_pi.parameters(), actor_before))
    monkeypatch.undo()
    model.train(gradient_steps=1, batch_size=8)
    assert any(not torch.equal(a, b) for a, b in zip(encoder.parameters(), before))


def test_the_critics_own_and_train_the_encoder_and_the_actor_reads_it_detached() -> None:
    model = _model()
    policy = model.policy
    encoder = policy.critic.features_extractor
    assert isinstance(encoder, ShiftedNatureEncoder) and policy.actor.features_extractor is encoder
    assert policy.critic_target.features_extractor is not encoder
    in_actor_optimiser = {id(p) for group in policy.actor.optimizer.param_groups for p in group["params"]}
    in_critic_optimiser = {id(p) for group in policy.critic.optimizer.param_groups for p in group["params"]}
    assert not in_actor_optimiser & {id(p) for p in encoder.parameters()}
    assert {id(p) for p in encoder.parameters()} <= in_critic_optimiser
    images = torch.as_tensor(np.stack([model.observation_space.sample() for _ in range(4)]))
    policy.set_training_mode(True)
    mean, _, _ = policy.actor.get_action_dist_params(images)
    mean.sum().backward()
    assert all(p.grad is None for p in encoder.parameters())  # the actor's loss does not reach it
    q_values = policy.critic(images, torch.zeros(4, 3))
    q_values[0].sum().backward()
    assert all(p.grad is not None and p.grad.abs().sum() > 0 for p in encoder.parameters())


def test_acting_is_unshifted_and_training_shifts() -> None:
    model = _model()
    encoder = model.policy.critic.features_extractor
    images = torch.rand(2, 3, 84, 84)
    encoder.eval()
    assert torch.equal(encoder(images), encoder(images))
    encoder.train()
    torch.manual_seed(1)
    assert not torch.equal(encoder(images), encoder(images))
    observation = model.observation_space.sample()
    assert np.array_equal(model.predict(observation, deterministic=True)[0], model.predict(observation, deterministic=True)[0])


@pytest.mark.slow
def test_training_moves_the_encoder_and_the_model_reloads_as_it_acts(tmp_path) -> None:
    from agents.policies import load_policy

    model = _model()
    before = [p.detach().clone() for p in model.policy.critic.features_extractor.parameters()]
    model.learn(32)
    after = list(model.policy.critic.features_extractor.parameters())
    assert any(not torch.equal(a, b) for a, b in zip(after, before))
    model.save(tmp_path / "drq.zip")
    loaded = load_policy(tmp_path / "drq.zip", algorithm="DrQSAC")
    observation = model.observation_space.sample()
    assert np.allclose(loaded.predict(observation, deterministic=True)[0], model.predict(observation, deterministic=True)[0])
