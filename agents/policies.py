"""Load a policy by name: a saved Stable-Baselines3 model, ``oracle`` or ``random``."""

from __future__ import annotations

from pathlib import Path

from agents.evaluation import Policy
from agents.oracle import BallisticOracle
from agents.random_agent import RandomAgent

PRETRAINED = Path(__file__).resolve().parent / "pretrained" / "ppo_netcatch.zip"
PRETRAINED_WINDY = Path(__file__).resolve().parent / "pretrained" / "ppo_windy.zip"  # trained on NetCatchWindy-v0


SB3_ALGORITHMS = ("PPO", "A2C", "SAC", "TD3", "DDPG")


def load_policy(name: str | Path, scene: str = "basket", algorithm: str = "PPO") -> Policy:
    """``"oracle"``, ``"random"`` or the path of a model saved by Stable-Baselines3's
    ``algorithm`` (one of SB3_ALGORITHMS)."""
    if str(name) == "oracle":
        return BallisticOracle.from_scene(scene)
    if str(name) == "random":
        return RandomAgent(0)
    if algorithm.upper() not in SB3_ALGORITHMS:
        raise ValueError(f"algorithm = {algorithm!r} is not one of {list(SB3_ALGORITHMS)}")
    if not Path(name).is_file():
        raise FileNotFoundError(f"policy {str(name)!r} is neither 'oracle', 'random' nor a saved model file")
    import stable_baselines3

    return getattr(stable_baselines3, algorithm.upper()).load(str(name), device="cpu")
