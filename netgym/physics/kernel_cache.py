"""Keeps numba's on-disk cache of the physics kernels consistent with their sources.

numba checks a cached kernel only against the source file it is defined in, not against the
files of the kernels it calls: after an edit of ``integrators.py`` (an editable install updated
by ``git pull``, say), the cached ``stepping.advance`` would go on running the old integrator.
:func:`drop_stale_kernels` therefore keys the whole folder's cache on a hash of all its sources.
"""

from __future__ import annotations

import hashlib
from pathlib import Path

STAMP = "kernel_sources.sha256"


def drop_stale_kernels(folder: Path) -> None:
    """Delete every cached numba kernel under ``folder/__pycache__`` when any ``*.py`` source
    of ``folder`` changed since the cache was stamped, so that all kernels recompile together.
    Does nothing where the folder cannot be written (numba then caches elsewhere or not at all)."""
    digest = hashlib.sha256()
    for source in sorted(folder.glob("*.py")):
        digest.update(source.name.encode() + b"\0" + source.read_bytes())
    cache = folder / "__pycache__"
    stamp = cache / STAMP
    try:
        if stamp.is_file() and stamp.read_text() == digest.hexdigest():
            return
        for kernel in (*cache.glob("*.nbi"), *cache.glob("*.nbc")):
            kernel.unlink(missing_ok=True)
        cache.mkdir(exist_ok=True)
        stamp.write_text(digest.hexdigest())
    except OSError:
        return
