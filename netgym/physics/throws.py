"""Deprecated: throws moved to :mod:`netgym.physics.throw`."""

from __future__ import annotations

import warnings
from typing import Any

from netgym.physics import throw as _throw

_MOVED = ("TUNING", "FastPathTuning", "Throw", "ThrowResult")


def __getattr__(name: str) -> Any:
    """The moved names, with a DeprecationWarning naming their new home."""
    if name in _MOVED:
        warnings.warn(f"netgym.physics.throws.{name} is deprecated; import it from netgym.physics.throw",
                      DeprecationWarning, stacklevel=2)
        return getattr(_throw, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
