"""Result files: the one source of every figure the README and the docs quote.

A script that measures something writes its figures with :func:`write_results` to a JSON file
(``docs/results/NAME.json`` in the repository), together with the command that produced them,
when and where it ran. The tables in the README and the docs that quote those figures are
generated from the files (``python scripts/quote_results.py``), and a test fails when a quoted
table and its result file disagree.
"""

from __future__ import annotations

import datetime
import json
import os
import platform
import sys
from pathlib import Path
from typing import Any

from netgym.errors import InvalidArgumentError

RESULTS = Path(__file__).resolve().parents[2] / "docs" / "results"
"""Where the repository keeps its result files."""


def write_results(path: str | Path, figures: Any, command: list[str] | None = None) -> Path:
    """Write ``figures`` (JSON-serialisable) to ``path`` with their provenance: the command
    line (default: this process's), the date and time, the machine and Python; returns the path.
    Atomic: the file is written beside ``path`` and renamed onto it, so that a reader never
    meets, and a process killed while writing never leaves, a half-written ``path``."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    record = {
        "command": " ".join(["python", *(command if command is not None else sys.argv)]),
        "written": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC"),
        "machine": f"{platform.machine()}, {platform.system()}, Python {platform.python_version()}",
        "figures": figures,
    }
    written = path.with_name(f".{path.name}.{os.getpid()}.tmp")
    written.write_text(json.dumps(record, indent=1) + "\n")
    os.replace(written, path)
    return path


def read_results(path: str | Path) -> dict[str, Any]:
    """The record :func:`write_results` wrote at ``path`` (``command``, ``written``, ``machine``,
    ``figures``); a clear error when the file is missing or is not such a record."""
    path = Path(path)
    if not path.is_file():
        raise FileNotFoundError(f"result file {path} is missing: run the command that writes it")
    record = json.loads(path.read_text())
    if not isinstance(record, dict) or "figures" not in record:
        raise InvalidArgumentError(f"{path} is not a result file (no 'figures' field)")
    return record
