"""Checkpoints inside a learner run, so that a run killed at any point resumes where its latest
checkpoint stopped instead of from zero.

A checkpoint is a folder ``OUT/checkpoints/ALGORITHM/ENV_ID/seed_K/``: the model (``model.zip``),
an off-policy learner's replay buffer (``replay_buffer.pkl``) and ``state.json`` (the steps
done, the learning curve so far, the wall and CPU seconds spent, the steps at which the run was
resumed). It is written at the start of a rollout (after the previous update, so no collected
step is lost) once ``every_s`` wall seconds have passed since the last, into a fresh folder
renamed onto the old one: a kill while writing leaves the previous checkpoint whole. Writing
one changes nothing in training (no random draw, no step), so a run that is never killed is the
same whatever its checkpoints. A resumed run draws its next episodes from streams of its own
(:data:`~agents.baselines.grid.TRAIN_SEED_STRIDE`) and lists where it was resumed.
"""

from __future__ import annotations

import json
import os
import shutil
import time
from pathlib import Path
from typing import Any

from stable_baselines3.common.callbacks import BaseCallback
from stable_baselines3.common.off_policy_algorithm import OffPolicyAlgorithm

CHECKPOINTS = "checkpoints"
"""The folder under the output folder that holds the runs' checkpoints (not committed)."""
EVERY_S = 600.0
"""Wall seconds between two checkpoints of a run."""


def checkpoint_folder(out: Path, run_name: str) -> Path:
    """Where the run ``run_name`` (``ALGORITHM/ENV_ID/seed_K``) keeps its checkpoint under ``out``."""
    return out / CHECKPOINTS / run_name


def load_state(folder: Path) -> dict[str, Any] | None:
    """The checkpoint's ``state.json``, None where there is no whole checkpoint."""
    try:
        return json.loads((folder / "state.json").read_text())
    except (FileNotFoundError, json.JSONDecodeError):
        return None


def resume(folder: Path, algorithm: type, env: Any) -> Any:
    """The model of the checkpoint in ``folder`` on ``env``, its replay buffer loaded (off-policy)."""
    model = algorithm.load(str(folder / "model.zip"), env=env, device="cpu")
    if isinstance(model, OffPolicyAlgorithm):
        model.load_replay_buffer(str(folder / "replay_buffer.pkl"))
    return model


def remove(folder: Path) -> None:
    """Delete the checkpoint (its run's result is written)."""
    shutil.rmtree(folder, ignore_errors=True)


class Checkpointer(BaseCallback):
    """Write the run's checkpoint to ``folder`` at the start of a rollout once ``every_s`` wall
    seconds have passed since the last (default :data:`EVERY_S`); ``state`` returns what ``state.json`` records beside the
    steps done (the curve, the seconds spent, the resumptions)."""

    def __init__(self, folder: Path, state: Any, every_s: float | None = None) -> None:
        super().__init__()
        self.folder, self.state = folder, state
        self.every_s = EVERY_S if every_s is None else every_s
        self._last = time.perf_counter()

    def _on_rollout_start(self) -> None:
        if time.perf_counter() - self._last >= self.every_s:
            self.write()

    def _on_step(self) -> bool:
        return True

    def write(self) -> None:
        """Write the checkpoint now, atomically (a fresh folder renamed onto the old one)."""
        fresh = self.folder.with_name(f".{self.folder.name}.{os.getpid()}.tmp")
        shutil.rmtree(fresh, ignore_errors=True)
        fresh.mkdir(parents=True)
        self.model.save(fresh / "model.zip")
        if isinstance(self.model, OffPolicyAlgorithm):
            self.model.save_replay_buffer(fresh / "replay_buffer.pkl")
        (fresh / "state.json").write_text(json.dumps({"steps": self.model.num_timesteps, **self.state()}))
        old = self.folder.with_name(f".{self.folder.name}.{os.getpid()}.old")
        if self.folder.exists():
            os.replace(self.folder, old)
        os.replace(fresh, self.folder)
        shutil.rmtree(old, ignore_errors=True)
        self._last = time.perf_counter()
