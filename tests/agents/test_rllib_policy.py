"""Loading an RLlib checkpoint folder as a policy: what happens without one, or without Ray.
(A real checkpoint, trained on a cluster and evaluated, is tests/agents/test_rllib_cluster.py's.)"""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

from agents.policies import load_policy
from agents.rllib_policy import MODULE_PATH, RLlibPolicy, is_rllib_checkpoint


def _checkpoint_layout(folder: Path) -> Path:
    (folder / MODULE_PATH).mkdir(parents=True)
    (folder / "rllib_checkpoint.json").write_text("{}")
    return folder


def test_a_folder_without_rllib_checkpoint_json_is_neither_checkpoint_nor_policy(tmp_path: Path) -> None:
    assert not is_rllib_checkpoint(tmp_path)
    with pytest.raises(FileNotFoundError, match="RLlib checkpoint folder"):
        load_policy(tmp_path)
    with pytest.raises(FileNotFoundError, match="no rllib_checkpoint.json"):
        RLlibPolicy(tmp_path)


def test_a_checkpoint_without_its_module_names_the_missing_folder(tmp_path: Path) -> None:
    (tmp_path / "rllib_checkpoint.json").write_text("{}")
    with pytest.raises(FileNotFoundError, match="default_policy"):
        load_policy(tmp_path)


def test_without_ray_a_checkpoint_names_the_rllib_extra(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setitem(sys.modules, "ray", None)  # import ray raises ImportError, as without the extra
    with pytest.raises(ImportError, match=r'pip install -e "\.\[rllib\]"'):
        load_policy(_checkpoint_layout(tmp_path))
