"""numba's cache must not run a kernel compiled against an older version of a kernel it calls."""

from __future__ import annotations

import os
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

from netgym.physics.kernel_cache import STAMP, drop_stale_kernels

CALLER = """
from numba import njit
from pkg.callee import value

@njit(cache=True)
def call():
    return value()
"""
CALLEE = """
from numba import njit

@njit(cache=True)
def value():
    return {}
"""
RUN = "from pathlib import Path; import pkg.kernel_cache as c; {}from pkg.caller import call; print(call())"


def _write_package(root: Path, returned: int, room: str = "") -> Path:
    """A package with a cached caller and its callee, the callee in the subfolder ``room`` if given."""
    pkg = root / "pkg"
    (pkg / room).mkdir(parents=True, exist_ok=True)
    (pkg / "__init__.py").write_text("")
    (pkg / room / "__init__.py").write_text("")
    (pkg / "kernel_cache.py").write_text(Path(__file__).parents[2].joinpath("netgym/physics/kernel_cache.py").read_text())
    callee = ".".join(["pkg", *([room] if room else []), "callee"])
    (pkg / "caller.py").write_text(textwrap.dedent(CALLER).replace("pkg.callee", callee))
    (pkg / room / "callee.py").write_text(textwrap.dedent(CALLEE.format(returned)))
    return pkg


def _call(root: Path, guarded: bool, cache_dir: Path | None = None) -> str:
    guard = "c.drop_stale_kernels(Path('pkg')); " if guarded else ""
    env = {k: v for k, v in os.environ.items() if k != "NUMBA_CACHE_DIR"}
    if cache_dir is not None:
        env["NUMBA_CACHE_DIR"] = str(cache_dir)
    done = subprocess.run([sys.executable, "-c", RUN.format(guard)], cwd=root, capture_output=True, text=True,
                          timeout=300, check=True, env=env)
    return done.stdout.strip()


def test_without_the_guard_numba_runs_a_stale_callee(tmp_path: Path) -> None:
    """The hazard itself: the cached caller keeps the callee's old body."""
    _write_package(tmp_path, 1)
    assert _call(tmp_path, guarded=False) == "1"
    _write_package(tmp_path, 2)
    assert _call(tmp_path, guarded=False) == "1"


def test_the_guard_recompiles_every_kernel_after_any_source_change(tmp_path: Path) -> None:
    pkg = _write_package(tmp_path, 1)
    assert _call(tmp_path, guarded=True) == "1"
    assert (pkg / "__pycache__" / STAMP).is_file()
    cached = sorted(p.name for p in (pkg / "__pycache__").glob("*.nb[ic]"))
    assert cached  # the kernels were cached ...
    assert _call(tmp_path, guarded=True) == "1"  # ... and an unchanged package keeps them
    assert sorted(p.name for p in (pkg / "__pycache__").glob("*.nb[ic]")) == cached
    _write_package(tmp_path, 2)
    assert _call(tmp_path, guarded=True) == "2"


def test_the_guard_covers_kernels_in_subfolders(tmp_path: Path) -> None:
    """A callee in a room of the package, changed: its caller in the package's top recompiles."""
    _write_package(tmp_path, 1, room="kernels")
    assert _call(tmp_path, guarded=True) == "1"
    _write_package(tmp_path, 2, room="kernels")
    assert _call(tmp_path, guarded=False) == "1"  # the hazard across folders too
    assert _call(tmp_path, guarded=True) == "2"


def test_a_guard_that_depends_on_another_folder_recompiles_after_a_change_there(tmp_path: Path) -> None:
    """A caller in ``pkg/bench`` of a callee in ``pkg/physics`` (as the roofline's kernels call
    the spring pass): guarded with ``depends_on`` it recompiles when the callee changes; guarded
    on its own folder alone it would not."""
    pkg = _write_package(tmp_path, 1, room="physics")
    (pkg / "bench").mkdir()
    (pkg / "bench" / "__init__.py").write_text("")
    (pkg / "caller.py").rename(pkg / "bench" / "caller.py")
    run = RUN.replace("pkg.caller", "pkg.bench.caller")
    guards = {"own": "c.drop_stale_kernels(Path('pkg/bench')); ",
              "both": "c.drop_stale_kernels(Path('pkg/bench'), depends_on=(Path('pkg/physics'),)); "}

    def call(guard: str) -> str:
        return subprocess.run([sys.executable, "-c", run.format(guards[guard])], cwd=tmp_path, capture_output=True,
                              text=True, timeout=300, check=True).stdout.strip()

    assert call("own") == "1"
    (pkg / "physics" / "callee.py").write_text(textwrap.dedent(CALLEE.format(2)))
    assert call("own") == "1"  # the hazard: its own folder did not change
    assert call("both") == "2"
    (pkg / "physics" / "callee.py").write_text(textwrap.dedent(CALLEE.format(3)))
    assert call("both") == "3"


@pytest.mark.slow
def test_the_guard_works_where_numba_cache_dir_puts_the_cache(tmp_path: Path) -> None:
    cache_dir = tmp_path / "numba-cache"
    pkg = _write_package(tmp_path, 1)
    assert _call(tmp_path, guarded=False, cache_dir=cache_dir) == "1"
    _write_package(tmp_path, 2)
    assert _call(tmp_path, guarded=False, cache_dir=cache_dir) == "1"  # the hazard there too
    assert _call(tmp_path, guarded=True, cache_dir=cache_dir) == "2"
    assert list(cache_dir.rglob(STAMP)) and not (pkg / "__pycache__" / STAMP).exists()


def test_a_folder_that_cannot_hold_a_cache_is_left_alone(tmp_path: Path) -> None:
    missing = tmp_path / "no_such_folder"
    drop_stale_kernels(missing)
    assert not missing.exists()
