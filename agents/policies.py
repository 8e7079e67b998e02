"""Load a policy by name: a saved Stable-Baselines3 model, an RLlib checkpoint folder, ``oracle``
or ``random``."""

from __future__ import annotations

import importlib
import json
import zipfile
from collections.abc import Callable
from operator import attrgetter
from pathlib import Path
from typing import Any

import numpy as np

from agents.evaluation import Policy
from agents.model_env import DEFAULT_ENV, SAVED_AS, check_registered, model_env, observation_space
from agents.oracle import BallisticOracle
from agents.random_agent import RandomAgent
from agents.rllib_policy import RLlibPolicy, is_rllib_checkpoint
from netgym.envs import NetCatchEnv
from netgym.errors import InvalidArgumentError

PRETRAINED = Path(__file__).resolve().parent / "pretrained" / "ppo_netcatch.zip"
PRETRAINED_WINDY = Path(__file__).resolve().parent / "pretrained" / "ppo_windy.zip"  # trained on NetCatchWindy-v0
PRETRAINED_WINDY_STACKED = Path(__file__).resolve().parent / "pretrained" / "ppo_windy_stack5.zip"  # the same, 5 frames
SHIPPED_BASELINES = {"sac_goal.zip": "baselines/sac/NetCatchGoal-v0/seed_0",
                     "sac_noisy.zip": "baselines/sac/NetCatchNoisy-v0/seed_0",
                     "tqc_windy.zip": "baselines/tqc/NetCatchWindy-v0/seed_5",
                     "ppo_longepisode.zip": "baselines/ppo/NetCatchLongEpisode-v0/seed_4",
                     "rppo_randomized_v1.zip": "baselines/rppo/NetCatchRandomized-v1/seed_0",
                     "sac_asym_pixels.zip": "baselines/sac_asym/NetCatchPixels-v0/seed_0",
                     "sac_asym_windy.zip": "baselines_long/sac_asym/NetCatchWindy-v0/seed_1"}
"""The baselines' models shipped in ``agents/pretrained/``: each file's run, as its result file's
path under ``docs/results/`` less ``.json`` (``FOLDER/ALGORITHM/ENV_ID/seed_K``: the table's runs
in ``baselines/``, runs beyond its budget in ``baselines_long/``). NetCatch-v0's is
:data:`PRETRAINED`."""


SHIPPED_FOR_ID = {"NetCatch-v0": "ppo_netcatch.zip", "NetCatchGoal-v0": "sac_goal.zip",
                  "NetCatchLongEpisode-v0": "ppo_longepisode.zip", "NetCatchWindy-v0": "sac_asym_windy.zip",
                  "NetCatchNoisy-v0": "sac_noisy.zip", "NetCatchRandomized-v0": "ppo_netcatch.zip",
                  "NetCatchRandomized-v1": "rppo_randomized_v1.zip", "NetCatchPixels-v0": "sac_asym_pixels.zip"}
"""The model shipped in ``agents/pretrained/`` for each id, the one its card names (for
NetCatchRandomized-v0, trained on no draws of its own, NetCatch-v0's)."""


def shipped_model(env_id: str) -> Path:
    """The path of the model shipped for ``env_id`` (:data:`SHIPPED_FOR_ID`)."""
    return PRETRAINED.parent / SHIPPED_FOR_ID[env_id]


CONTRIB_ALGORITHMS = ("TQC", "RecurrentPPO")
"""The algorithms a saved model may come from that sb3-contrib implements."""
AGENTS_ALGORITHMS = {"AsymmetricSAC": "agents.asymmetric", "DrQSAC": "agents.drq"}
"""The algorithms a saved model may come from that this package implements, and their modules."""
SB3_ALGORITHMS = ("PPO", "A2C", "SAC", "TD3", "DDPG", *CONTRIB_ALGORITHMS, *AGENTS_ALGORITHMS)
"""The algorithms a saved model may come from: Stable-Baselines3's, :data:`CONTRIB_ALGORITHMS`
and :data:`AGENTS_ALGORITHMS` (built on Stable-Baselines3)."""
TRAIN_EXTRA = 'Stable-Baselines3 and torch: pip install torch==2.13.0 && pip install -e ".[train]"'
"""What a saved model or training needs beyond the environment, and how to install it."""


def saved_algorithm(path: str | Path) -> str:
    """The algorithm (one of SB3_ALGORITHMS) a model zip was saved by: the one its netgym record
    names (:func:`~agents.model_env.record_env`), else PPO (models saved before it named one)."""
    with zipfile.ZipFile(path) as archive:
        record = json.loads(archive.read("data")).get(SAVED_AS, {})
    return record.get("algorithm", "PPO")


def load_policy(name: str | Path, scene: str = "basket", algorithm: str | None = None) -> Policy:
    """``"oracle"``, ``"random"``, the folder of an RLlib checkpoint (``scripts/train_rllib.py``)
    or the path of a model saved by ``algorithm`` (one of SB3_ALGORITHMS; by default the one the
    model's zip names, :func:`saved_algorithm`)."""
    if str(name) == "oracle":
        return BallisticOracle.from_scene(scene)
    if str(name) == "random":
        return RandomAgent(0)
    if is_rllib_checkpoint(name):
        return RLlibPolicy(name)
    by_name = {known.upper(): known for known in SB3_ALGORITHMS}
    if algorithm is not None and algorithm.upper() not in by_name:
        raise InvalidArgumentError(f"algorithm = {algorithm!r} is not one of {list(SB3_ALGORITHMS)}")
    if not Path(name).is_file():
        raise FileNotFoundError(f"policy {str(name)!r} is neither 'oracle', 'random', a saved model file nor an RLlib "
                                f"checkpoint folder")
    algorithm = by_name[(algorithm or saved_algorithm(name)).upper()]
    contrib = algorithm in CONTRIB_ALGORITHMS
    module = "sb3_contrib" if contrib else AGENTS_ALGORITHMS.get(algorithm, "stable_baselines3")
    try:
        package = importlib.import_module(module)
    except ImportError as missing:
        extra = 'sb3-contrib: pip install -e ".[baselines]"' if contrib else TRAIN_EXTRA
        raise ImportError(f"loading the saved model {str(name)!r} needs {extra}") from missing
    return getattr(package, algorithm).load(str(name), device="cpu")


def for_acting(model: Any) -> None:
    """Drop from a Stable-Baselines3 ``model`` what only training reads, in place, its actions
    unchanged: its optimizers' state (Adam's moments are as large as the weights) and its target
    networks' own weights (each then shares the weights of the network it follows, as SB3 starts
    them), so that a shipped file holds little more than the policy."""
    for name in model.get_parameters():
        if name.endswith("optimizer"):
            attrgetter(name)(model).state.clear()
    for online in ("actor", "critic"):
        target = getattr(model.policy, f"{online}_target", None)
        if target is not None:
            for follower, leader in zip(target.parameters(), getattr(model.policy, online).parameters()):
                follower.data = leader.data


def policy_in_env(name: str | Path, env_id: str | None = None,
                  algorithm: str | None = None) -> tuple[str, Policy | Callable[[NetCatchEnv], Policy]]:
    """The registered env to act in and ``name``'s policy for one env of it (a policy, or a
    function of the env that makes one, as :func:`~agents.evaluation.evaluate` takes).
    ``env_id`` defaults to the one a saved model was trained on (see
    :func:`~agents.model_env.model_env`, which raises EnvMismatchError for an env the model
    cannot read), else NetCatch-v0; the oracle aims with that env's scene."""
    if str(name) not in ("oracle", "random"):
        model = load_policy(name, algorithm=algorithm)
        found = model_env(model, env_id, str(name))
        return found.env_id, acting_policy(model, found.frame_stack)
    env_id = DEFAULT_ENV if env_id is None else env_id
    check_registered(env_id)
    if len(observation_space(env_id).shape) != 1:
        raise InvalidArgumentError(f"the {name} policy acts on NetCatchEnv's vector observation; {env_id} observes "
                                   f"{observation_space(env_id).shape} images")
    return env_id, (lambda env: BallisticOracle(env.scene)) if str(name) == "oracle" else load_policy(name)


def acting_policy(model: Any, frame_stack: int = 1) -> Any:
    """``model`` as a policy for one unstacked env (wrapped in :class:`FrameStackPolicy` when it
    was trained on ``frame_stack`` > 1 stacked observations)."""
    return FrameStackPolicy(model, frame_stack) if frame_stack > 1 else model


class FrameStackPolicy:
    """A model trained on Stable-Baselines3's ``VecFrameStack(n_stack)`` observations, acting in
    one unstacked env: it keeps the episode's last ``n_stack`` observations, newest last and
    zeros before the first, as ``VecFrameStack`` does, and starts afresh at ``episode_start``."""

    def __init__(self, model: Any, n_stack: int) -> None:
        self.model, self.n_stack = model, n_stack
        self._stack: np.ndarray | None = None

    def predict(self, observation: np.ndarray, state: Any = None, episode_start: Any = None,
                deterministic: bool = True) -> tuple[np.ndarray, Any]:
        """The model's action for the stack that ends with ``observation`` (one env)."""
        obs = np.asarray(observation, dtype=np.float32).ravel()
        if self._stack is None or (episode_start is not None and bool(np.any(episode_start))):
            self._stack = np.zeros(self.n_stack * obs.size, dtype=np.float32)
        self._stack = np.concatenate([self._stack[obs.size:], obs])
        action, _ = self.model.predict(self._stack, deterministic=deterministic)
        return action, state
