"""The registered NetCatch env a saved Stable-Baselines3 model acts in, and how many of its
observations the model sees stacked.

Training records both on the model (:func:`record_env`); SB3's ``save`` keeps the record in the
zip's ``data`` and ``load`` restores it. A model saved without one is matched to the registered
ids by the shape of its observation space.
"""

from __future__ import annotations

import functools
import warnings
from dataclasses import asdict, dataclass
from typing import Any

import gymnasium as gym
from gymnasium import spaces

import netgym
from netgym.errors import InvalidArgumentError
from netgym.wrappers import acting_key

DEFAULT_ENV = "NetCatch-v0"
SAVED_AS = "netgym_env"
"""The model attribute that holds the record (a dict, so SB3 saves it as plain JSON)."""


@dataclass(frozen=True)
class ModelEnv:
    """A registered env id, the number of its observations a model sees at once, and the
    algorithm that trained the model (its class name: PPO, SAC, TD3, TQC)."""

    env_id: str
    frame_stack: int = 1
    algorithm: str = "PPO"

    def __str__(self) -> str:
        return self.env_id + (f" with {self.frame_stack} observations stacked" if self.frame_stack > 1 else "")


class EnvMismatchError(InvalidArgumentError):
    """A model asked to act in an env whose observations it cannot read."""


def record_env(model: Any, env_id: str, frame_stack: int = 1) -> None:
    """Record on ``model`` the env it trains on and its algorithm, so that ``model.save`` keeps them."""
    setattr(model, SAVED_AS, asdict(ModelEnv(env_id, frame_stack, type(model).__name__)))


def saved_env(model: Any) -> ModelEnv | None:
    """The env recorded with ``model``, or None for a model saved without one."""
    record = getattr(model, SAVED_AS, None)
    return None if record is None else ModelEnv(**record)


def check_registered(env_id: str) -> None:
    """Raise InvalidArgumentError unless ``env_id`` is a registered NetCatch id."""
    if env_id not in netgym.ENVIRONMENTS:
        raise InvalidArgumentError(f"env {env_id!r} is not a registered NetCatch id; "
                                   f"one of {list(netgym.ENVIRONMENTS)}")


@functools.cache
def observation_space(env_id: str) -> spaces.Space:
    """The observation space of the registered ``env_id``."""
    check_registered(env_id)
    env = gym.make(env_id, disable_env_checker=True)
    env.close()
    return env.observation_space


def vector_counterpart(env_id: str, **env_kwargs: Any) -> tuple[str, dict[str, Any]]:
    """The id and arguments of the env with vector observations that runs the same episodes as
    ``env_id`` with ``env_kwargs``: itself, or for pixels NetCatch-v0 with the pixel id's
    arguments less the image size (the oracles read vector observations)."""
    if len(observation_space(env_id).shape) == 1:
        return env_id, env_kwargs
    env_kwargs = {**gym.spec(env_id).kwargs, **env_kwargs}
    env_kwargs.pop("size", None)
    return DEFAULT_ENV, env_kwargs


def acting_space(model_space: spaces.Space) -> spaces.Space:
    """What of a model's observations its policy acts on: the acting key of an asymmetric
    actor-critic's Dict (``"pixels"`` or ``"observation"``, :mod:`agents.asymmetric`; its critics
    alone read the ``"state"``), else the whole."""
    return model_space[acting_key(model_space)] if isinstance(model_space, spaces.Dict) else model_space


def frames_fitting(model_space: spaces.Space, env_space: spaces.Space) -> int | None:
    """How many of the env's observations make one of the model's (1 for the same shape, or an
    image SB3 turned channel-first; k for a vector k times as long), or None if they do not fit.
    A model's space is the one it acts on (:func:`acting_space`)."""
    model, env = acting_space(model_space).shape, env_space.shape
    if model == env or (len(env) == 3 and model == (env[2], env[0], env[1])):
        return 1
    if len(model) == len(env) == 1 and model[0] % env[0] == 0:
        return model[0] // env[0]
    return None


def model_env(model: Any, env_id: str | None = None, name: str = "the model") -> ModelEnv:
    """The env ``model`` (called ``name`` in messages) is to act in: ``env_id``, or by default
    the env recorded with it, or for a model without a record the registered id its
    observations fit (NetCatch-v0 where it fits). Raises :class:`EnvMismatchError` when the
    model cannot read that env's observations; warns when it was trained on another id whose
    observations it can read."""
    saved = saved_env(model)
    if env_id is None and saved is None:
        return _matching_env(model, name)
    target = env_id if env_id is not None else saved.env_id
    check_registered(target)
    frames = frames_fitting(model.observation_space, observation_space(target))
    if frames is None or (saved is not None and frames != saved.frame_stack):
        trained = f"trained on {saved}" if saved is not None else "saved without its env id"
        raise EnvMismatchError(
            f"{name} was {trained}: it reads observations of shape {acting_space(model.observation_space).shape}, and "
            f"{target}'s have shape {observation_space(target).shape}; "
            + (f"evaluate it on {saved.env_id}" if saved is not None else "pass an env it was trained on"))
    if saved is not None and saved.env_id != target:
        warnings.warn(f"{name} was trained on {saved.env_id}; acting in {target}", stacklevel=2)
    return ModelEnv(target, frames)


def _matching_env(model: Any, name: str) -> ModelEnv:
    fitting = [ModelEnv(env_id, frames) for env_id in netgym.ENVIRONMENTS
               if (frames := frames_fitting(model.observation_space, observation_space(env_id)))]
    default = [found for found in fitting if found.env_id == DEFAULT_ENV]
    if default or len(fitting) == 1:
        return (default or fitting)[0]
    raise EnvMismatchError(
        f"{name} was saved without its env id, and its observations of shape "
        f"{acting_space(model.observation_space).shape} "
        f"fit {', '.join(map(str, fitting)) or 'none of the registered NetCatch ids'}; name the env it was trained on")
