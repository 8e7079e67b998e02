"""Load a policy by name: a saved SB3 PPO model, ``oracle`` or ``random``."""

from __future__ import annotations

from pathlib import Path

from agents.evaluation import Policy
from agents.oracle import BallisticOracle
from agents.random_agent import RandomAgent

PRETRAINED = Path(__file__).resolve().parent / "pretrained" / "ppo_netcatch.zip"


def load_policy(name: str | Path, scene: str = "basket") -> Policy:
    """``"oracle"``, ``"random"`` or the path of a saved Stable-Baselines3 PPO model."""
    if str(name) == "oracle":
        return BallisticOracle.from_scene(scene)
    if str(name) == "random":
        return RandomAgent(0)
    from stable_baselines3 import PPO

    return PPO.load(str(name), device="cpu")
