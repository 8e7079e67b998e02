"""Reset options of NetCatchEnv: validated before anything changes."""

from __future__ import annotations

from typing import Any, Mapping

from netgym.arguments import is_real
from netgym.config import ThrowConfig
from netgym.errors import InvalidArgumentError

RESET_OPTIONS = ("overrides", "thrower")


def checked_reset_options(options: Any, ranges: ThrowConfig) -> dict[str, Any]:
    """The reset options of :meth:`~netgym.envs.NetCatchEnv.reset`, validated against the
    scene's throw ``ranges`` before anything changes: ``{"thrower": {...}, "overrides": {...}}``
    with only the keys given; a bad option raises an :class:`InvalidArgumentError` naming it."""
    if options is None:
        return {}
    if not isinstance(options, Mapping):
        raise InvalidArgumentError(f"options must be a dict or None, got {type(options).__name__}")
    unknown = sorted(set(map(str, options)) - set(RESET_OPTIONS))
    if unknown:
        raise InvalidArgumentError(f"unknown reset option(s) {unknown}; NetCatch-v0 takes {list(RESET_OPTIONS)}")
    thrower = options.get("thrower", {})
    if not isinstance(thrower, Mapping):
        raise InvalidArgumentError(f"options['thrower'] must be a dict, got {type(thrower).__name__}")
    allowed = {"distance": ranges.distance, "bearing": ranges.bearing, "height": ranges.height}
    for key, value in thrower.items():
        if key not in allowed:
            raise InvalidArgumentError(f"options['thrower'] has unknown key {key!r}; allowed: {list(allowed)}")
        lo, hi = allowed[key]
        if not is_real(value) or not lo <= float(value) <= hi:
            raise InvalidArgumentError(f"options['thrower']['{key}'] = {value!r}; "
                                       f"allowed: a number in [{lo:g}, {hi:g}]")
    overrides = options.get("overrides", {})
    if not isinstance(overrides, Mapping):
        raise InvalidArgumentError(f"options['overrides'] must be a dict, got {type(overrides).__name__}")
    if any(str(field).startswith("throw.") for field in overrides):
        raise InvalidArgumentError("options['overrides'] may not change the throw ranges (they define the spaces); "
                                   "make a new env with those overrides instead")
    checked: dict[str, Any] = {}
    if "thrower" in options:
        checked["thrower"] = {k: float(v) for k, v in thrower.items()}
    if "overrides" in options:
        checked["overrides"] = dict(overrides)
    return checked
