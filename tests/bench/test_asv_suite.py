"""The asv suite (benchmarks/, asv.conf.json) stays valid and runs: asv's own check, then every
benchmark once in asv's quick mode in this environment. Timings are not judged here (CI's
machines are shared); `asv continuous` judges them (docs/CONTRIBUTING.md)."""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


def _asv(*args: str, home: Path) -> subprocess.CompletedProcess:
    """asv with ``args`` in the repository, its machine file kept in ``home``."""
    return subprocess.run([sys.executable, "-m", "asv", *args], cwd=ROOT, capture_output=True, text=True,
                          env={**os.environ, "HOME": str(home)}, timeout=1800, check=False)


@pytest.mark.slow
def test_the_asv_suite_passes_asvs_check_and_every_benchmark_runs(tmp_path: Path) -> None:
    assert _asv("machine", "--yes", home=tmp_path).returncode == 0
    check = _asv("check", "--python=same", home=tmp_path)
    assert check.returncode == 0 and "No problems found" in check.stdout, check.stdout + check.stderr
    run = _asv("run", "--quick", "--python=same", "--dry-run", "--show-stderr", home=tmp_path)
    out = run.stdout + run.stderr
    assert run.returncode == 0, out  # asv run exits 2 when a benchmark failed
    discovered = re.search(r"Running (\d+) total benchmarks", out)
    assert discovered and int(discovered.group(1)) >= 9, out
    results = re.findall(r"^\[[ \d.]+%\] ··· (?!Setting up|=)(\S+)\s+(\S+)", out, flags=re.MULTILINE)
    assert len(results) == int(discovered.group(1)), out
    assert not [name for name, status in results if status in ("failed", "n/a")], out
