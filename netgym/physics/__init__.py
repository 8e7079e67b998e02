"""The simulator: net building, numba kernels, stepping, throws."""

from pathlib import Path

from netgym.physics.compile_notice import announce_compilation
from netgym.physics.kernel_cache import drop_stale_kernels

drop_stale_kernels(Path(__file__).parent)
announce_compilation()
