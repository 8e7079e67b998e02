"""One line on stderr when the simulator's numba kernels compile, so that a first run does not
sit silent: numba compiles them on their first call unless its on-disk cache has them.

:func:`announce_compilation` listens to numba's compile events and writes the line at the first
compilation of a netgym kernel, then stays quiet; a run that loads every kernel from the cache
writes nothing. Subprocesses started afterwards (vectorised environments' workers) inherit the
environment variable :data:`SHOWN` and stay quiet too.
"""

from __future__ import annotations

import os
import sys
from typing import TextIO

from numba.core import event

SHOWN = "NETGYM_COMPILE_NOTICE_SHOWN"
"""Set in the environment once the line was written (by this process or its parent)."""
TYPICAL_SECONDS = 15   # from an empty cache to the first step of NetCatch-v0 (scripts/first_step_time.py)
MESSAGE = (f"netgym: compiling the simulator's kernels (first run only, ~{TYPICAL_SECONDS} s; "
           "later runs load them from numba's cache)...")


class CompileNotice(event.Listener):
    """A numba compile-event listener that writes :data:`MESSAGE` to ``stream`` (default
    stderr) when the first kernel of ``package`` starts compiling, unless :data:`SHOWN` is set."""

    def __init__(self, package: str = "netgym", stream: TextIO | None = None) -> None:
        self.package = package
        self.stream = stream

    def on_start(self, ev: event.Event) -> None:
        """Write the line if a kernel of the package starts compiling and nobody has yet."""
        if os.environ.get(SHOWN) or not _defined_in(ev, self.package):
            return
        os.environ[SHOWN] = "1"
        stream = sys.stderr if self.stream is None else self.stream
        stream.write(MESSAGE + "\n")
        stream.flush()

    def on_end(self, ev: event.Event) -> None:
        """Nothing to do when a compilation ends."""


def _defined_in(ev: event.Event, package: str) -> bool:
    """True if the compile event is of a function of ``package`` or its submodules."""
    dispatcher = (ev.data or {}).get("dispatcher")
    module = getattr(getattr(dispatcher, "py_func", None), "__module__", None) or ""
    return module == package or module.startswith(package + ".")


def announce_compilation() -> CompileNotice:
    """Register a :class:`CompileNotice` for numba's compile events; returns it."""
    notice = CompileNotice()
    event.register("numba:compile", notice)
    return notice
