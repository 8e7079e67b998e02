"""The typed, ranged fields of the scene's config dataclasses and their validation: a field
declares its range (:func:`number`) or its choices (:func:`choice`) in its metadata, and
:func:`build` and :func:`replaced` check every value against its field's type hint and that
metadata, raising :class:`~netgym.errors.ConfigError` that names the field (``simulation.dt``)
and what it allows. :mod:`netgym.config` declares the scene with them."""

from __future__ import annotations

import dataclasses
import functools
import math
import typing
from dataclasses import field
from typing import Any, Mapping

from netgym.arguments import is_integer, is_real
from netgym.errors import ConfigError


def number(lo: float, hi: float, *, lo_open: bool = False, hi_open: bool = False,
           default: Any = dataclasses.MISSING) -> Any:
    """A dataclass field whose value (or each element) must lie in ``lo..hi`` (optional in
    scene files when it has a ``default``)."""
    return field(default=default, metadata={"range": (lo, hi, lo_open, hi_open)})


def choice(*options: str, default: Any = dataclasses.MISSING) -> Any:
    """A dataclass field whose value must be one of ``options`` (optional in scene files when
    it has a ``default``)."""
    return field(default=default, metadata={"choices": options})


def replaced(node: Any, keys: list[str], value: Any, dotted: str) -> Any:
    """A copy of the config ``node`` with the field at ``keys`` (its path below ``node``) set to
    ``value``, validated."""
    head, *rest = keys
    field = next((f for f in dataclasses.fields(node) if f.name == head), None)
    child = getattr(node, head, None)
    if field is None or (rest and not dataclasses.is_dataclass(child)):
        raise ConfigError(f"unknown field {dotted!r}")
    new = replaced(child, rest, value, dotted) if rest else _convert(value, _hints(type(node))[head], dotted, field)
    return dataclasses.replace(node, **{head: new})


def _range_text(spec: tuple[float, float, bool, bool]) -> str:
    lo, hi, lo_open, hi_open = spec
    return f"{'(' if lo_open else '['}{lo:g}, {hi:g}{')' if hi_open else ']'}"


def _in_range(value: float, spec: tuple[float, float, bool, bool]) -> bool:
    lo, hi, lo_open, hi_open = spec
    above = value > lo if lo_open else value >= lo
    below = value < hi if hi_open else value <= hi
    return math.isfinite(value) and above and below


def _scalar(value: Any, kind: type, name: str, f: dataclasses.Field) -> Any:
    if kind is bool:
        if not isinstance(value, bool):
            raise ConfigError(f"{name} must be true or false, got {value!r}")
        return value
    if kind is str:
        if not isinstance(value, str):
            raise ConfigError(f"{name} must be a string, got {value!r}")
        choices = f.metadata.get("choices")
        if choices and value not in choices:
            raise ConfigError(f"{name} = {value!r} is not allowed; choose one of {list(choices)}")
        return value
    if not is_real(value):
        raise ConfigError(f"{name} must be a number, got {value!r}")
    if kind is int and not is_integer(value):
        raise ConfigError(f"{name} must be an integer, got {value!r}")
    spec = f.metadata.get("range")
    if spec and not _in_range(float(value), spec):
        raise ConfigError(f"{name} = {value!r} is out of range; allowed: {_range_text(spec)}")
    return kind(value)


def _convert(value: Any, hint: Any, name: str, f: dataclasses.Field) -> Any:
    if dataclasses.is_dataclass(hint):
        if not isinstance(value, Mapping):
            raise ConfigError(f"{name} must be a table, got {value!r}")
        return build(hint, value, name)
    if typing.get_origin(hint) is tuple:
        kinds = typing.get_args(hint)
        if not isinstance(value, (list, tuple)) or len(value) != len(kinds):
            raise ConfigError(f"{name} must be a list of {len(kinds)} numbers, got {value!r}")
        return tuple(_scalar(v, k, f"{name}[{i}]", f) for i, (v, k) in enumerate(zip(value, kinds)))
    return _scalar(value, hint, name, f)


@functools.cache
def _hints(cls: type) -> dict[str, Any]:
    """The resolved type hints of a config class (resolving them is most of a validation's time)."""
    return typing.get_type_hints(cls)


def build(cls: type, table: Mapping[str, Any], path: str) -> Any:
    """A ``cls`` from the parsed ``table`` found at the dotted ``path`` ("" for the scene), every
    field validated and every nested table built."""
    hints = _hints(cls)
    names = [f.name for f in dataclasses.fields(cls)]
    prefix = f"{path}." if path else ""
    unknown = sorted(set(table) - set(names))
    if unknown:
        raise ConfigError(f"unknown field {prefix}{unknown[0]}; allowed fields: {names}")
    missing = [f.name for f in dataclasses.fields(cls)
               if f.name not in table and f.default is dataclasses.MISSING]
    if missing:
        raise ConfigError(f"missing field {prefix}{missing[0]}")
    values = {f.name: _convert(table[f.name], hints[f.name], prefix + f.name, f)
              for f in dataclasses.fields(cls) if f.name in table}
    return cls(**values)
