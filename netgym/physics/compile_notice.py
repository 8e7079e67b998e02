"""Lines on stderr while the simulator's numba kernels compile, so that a start does not sit
silent: numba compiles a kernel at its first call unless its on-disk cache has it already.

:class:`CompileNotice` listens to numba's compile events. At the first compilation of a netgym
kernel it writes :data:`MESSAGE`; while a compilation goes on for more than a few seconds it
keeps a line up to date with the kernels compiled so far, the seconds spent on them and the
kernel compiling now, and ends that line when the compilation ends. A run that loads every
kernel from the cache writes nothing. Subprocesses started afterwards (vectorised environments'
workers) inherit the environment variable :data:`SHOWN` and stay quiet.
"""

from __future__ import annotations

import os
import sys
import time
from collections.abc import Callable
from typing import TextIO

from numba.core import event

SHOWN = "NETGYM_COMPILE_NOTICE_SHOWN"
"""Set in the environment once the notice was written (by this process or its parent)."""
MESSAGE = ("netgym: compiling the simulator's kernels that numba's cache does not have yet "
           "(once; later runs load them from the cache)")


class CompileNotice(event.Listener):
    """A numba compile-event listener for the kernels of ``package``: writes :data:`MESSAGE` to
    ``stream`` (default stderr) when the first of them starts compiling, unless :data:`SHOWN` is
    set then, and from ``quiet`` seconds into a compilation a progress line (see
    :meth:`progress`), rewritten as each kernel ends and ended with the outermost one."""

    def __init__(self, package: str = "netgym", stream: TextIO | None = None, quiet: float = 2.0,
                 clock: Callable[[], float] = time.perf_counter) -> None:
        self.package, self.stream, self.quiet, self.clock = package, stream, quiet, clock
        self.silent: bool | None = None  # decided at the first compilation: True if a parent wrote the notice
        self.compiling: list[str] = []   # the kernels compiling now, outermost first
        self.compiled = 0
        self.spent = 0.0                 # seconds of the compilations that ended
        self.started = 0.0               # when the outermost compilation now going on started
        self.shown = False               # whether this compilation's progress line was written
        self.width = 0                   # the length of that line as last written

    def on_start(self, ev: event.Event) -> None:
        """Note the kernel; write the notice at the package's first compilation."""
        name = _kernel_name(ev, self.package)
        if name is None:
            return
        if self.silent is None:
            self.silent = bool(os.environ.get(SHOWN))
            os.environ[SHOWN] = "1"
            self._write(MESSAGE + "\n")
        if not self.compiling:
            self.started, self.shown, self.width = self.clock(), False, 0
        self.compiling.append(name)

    def on_end(self, ev: event.Event) -> None:
        """Count the kernel; show the progress once the compilation has lasted ``quiet`` s."""
        if _kernel_name(ev, self.package) is None:
            return
        self.compiling.pop()
        self.compiled += 1
        elapsed = self.clock() - self.started
        if self.shown or elapsed >= self.quiet:
            line = self.progress(self.spent + elapsed)
            self._write("\r" + line.ljust(self.width))  # padded over the longer line it replaces
            self.shown, self.width = True, len(line)
        if not self.compiling:
            self.spent += elapsed
            if self.shown:
                self._write("\n")

    def progress(self, seconds: float) -> str:
        """The progress line: kernels compiled, seconds spent compiling, the kernel compiling now."""
        now = f", compiling {self.compiling[-1]}" if self.compiling else ""
        return f"netgym: {self.compiled} kernels compiled in {seconds:.0f} s{now}"

    def _write(self, text: str) -> None:
        if self.silent:
            return
        stream = sys.stderr if self.stream is None else self.stream
        stream.write(text)
        stream.flush()


def _kernel_name(ev: event.Event, package: str) -> str | None:
    """``module.function`` (the package's prefix left out) of the kernel the compile event is
    about, or None when the kernel is not of ``package`` or its submodules."""
    dispatcher = (ev.data or {}).get("dispatcher")
    function = getattr(dispatcher, "py_func", None)
    module = getattr(function, "__module__", None) or ""
    if module != package and not module.startswith(package + "."):
        return None
    return f"{module.removeprefix(package + '.')}.{function.__name__}"


_ANNOUNCED: list[CompileNotice] = []  # the notice announce_compilation registered, once


def announce_compilation() -> CompileNotice:
    """Register a :class:`CompileNotice` for numba's compile events (once); returns it."""
    if not _ANNOUNCED:
        _ANNOUNCED.append(CompileNotice())
        event.register("numba:compile", _ANNOUNCED[0])
    return _ANNOUNCED[0]


def compile_seconds() -> float:
    """Wall seconds this process has spent compiling netgym's kernels, up to the last
    compilation that ended (what a watchdog leaves out of the time it measures)."""
    return announce_compilation().spent
