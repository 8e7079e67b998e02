"""Checks of the arguments users pass, shared by the simulator, the environments and the config:
each failure is an :class:`~netgym.errors.InvalidArgumentError` (a ValueError) that names the
argument."""

from __future__ import annotations

import json
from collections.abc import Mapping
from typing import Any

import numpy as np

from netgym.errors import InvalidArgumentError


def is_integer(value: Any) -> bool:
    """True for a Python or NumPy integer that is not a bool."""
    return isinstance(value, (int, np.integer)) and not isinstance(value, (bool, np.bool_))


def is_real(value: Any) -> bool:
    """True for a Python or NumPy integer or float that is not a bool."""
    return is_integer(value) or isinstance(value, (float, np.floating))


def integer_argument(value: Any, name: str, minimum: int) -> int:
    """``value`` as an int, or an InvalidArgumentError naming ``name`` unless it is an integer
    >= ``minimum``."""
    if not is_integer(value) or value < minimum:
        raise InvalidArgumentError(f"{name} = {value!r}; allowed: an integer >= {minimum}")
    return int(value)


def vector_argument(value: Any, name: str) -> np.ndarray:
    """``value`` as a finite float64 3-vector, or an InvalidArgumentError naming ``name``."""
    arr = np.asarray(value, dtype=np.float64)
    if arr.shape != (3,):
        raise InvalidArgumentError(f"{name} must have shape (3,), got {arr.shape}")
    if not np.all(np.isfinite(arr)):
        raise InvalidArgumentError(f"{name} must be finite, got {arr.tolist()}")
    return arr


def parse_overrides(text: str) -> dict[str, Any]:
    """``"a.b=1,c.d=x"`` (a command line's scene overrides) as a dict, values read as JSON where
    they parse and kept as strings where not."""
    out: dict[str, Any] = {}
    for item in text.split(","):
        key, _, value = item.partition("=")
        try:
            out[key] = json.loads(value)
        except json.JSONDecodeError:
            out[key] = value
    return out


def describe_overrides(overrides: Mapping[str, Any]) -> str:
    """Scene overrides as a label: ``"a.b=1, c.d=x"``."""
    return ", ".join(f"{k}={v}" for k, v in overrides.items())
