"""Keeps numba's on-disk cache of the physics kernels consistent with their sources.

numba checks a cached kernel only against the source file it is defined in, not against the
files of the kernels it calls: after an edit of ``integrators.py`` (an editable install updated
by ``git pull``, say), the cached ``stepping.advance`` would go on running the old integrator.
:func:`drop_stale_kernels` therefore keys the cache of a folder and all its subfolders (the
package's rooms) on a hash of all their sources, wherever numba keeps that cache: next to the
sources, under ``NUMBA_CACHE_DIR``, or in the user-wide cache numba falls back to when the install
folder cannot be written.
"""

from __future__ import annotations

import hashlib
from pathlib import Path

from numba.core.caching import FunctionCache

STAMP = "kernel_sources.sha256"


def numba_cache_folder(folder: Path) -> Path | None:
    """The folder where numba caches the kernels defined in ``folder``'s sources, as numba
    itself chooses it; None when there are no sources or numba could cache them nowhere."""
    sources = sorted(folder.glob("*.py"))
    if not sources:
        return None
    namespace: dict = {}
    exec(compile("def probe():\n    pass\n", str(sources[0]), "exec"), namespace)  # a function "defined" there
    try:
        return Path(FunctionCache(namespace["probe"]).cache_path)
    except RuntimeError:  # numba: no writable place to cache functions of this file
        return None


def drop_stale_kernels(folder: Path, depends_on: tuple[Path, ...] = ()) -> None:
    """Delete every cached numba kernel of the sources in ``folder`` and its subfolders when any
    ``*.py`` source there, or in the folders ``depends_on`` (whose kernels they call), changed
    since the caches were stamped, so that all kernels recompile together. Does nothing where
    numba caches nothing (or the cache cannot be written)."""
    digest = hashlib.sha256()
    for root in (folder, *depends_on):
        for source in sorted(root.rglob("*.py")):
            digest.update(source.relative_to(root.parent).as_posix().encode() + b"\0" + source.read_bytes())
    for place in sorted({source.parent for source in folder.rglob("*.py")}):
        _restamp(place, digest.hexdigest())


def _restamp(folder: Path, digest: str) -> None:
    """Delete the cached kernels of ``folder``'s own sources unless their cache bears ``digest``;
    then stamp it with ``digest``."""
    cache = numba_cache_folder(folder)
    if cache is None:
        return
    stamp = cache / STAMP
    try:
        if stamp.is_file() and stamp.read_text() == digest:
            return
        for kernel in (*cache.glob("*.nbi"), *cache.glob("*.nbc")):
            kernel.unlink(missing_ok=True)
        cache.mkdir(parents=True, exist_ok=True)
        stamp.write_text(digest)
    except OSError:
        return
