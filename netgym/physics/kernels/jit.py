"""The numba decorators of the physics kernels, so that every kernel compiles alike.

Kernels are cached on disk and use numpy's floating-point error model: a division by zero
gives inf or nan (which the divergence checks catch) instead of raising, so numba emits no
zero check before every division. Where no division by zero happens, results are bitwise the
same as with Python's error model, and the hot loops run faster (docs/BENCHMARKS.md).
"""

from __future__ import annotations

from numba import njit

kernel = njit(cache=True, error_model="numpy")
"""Decorator of a physics kernel."""

inline_kernel = njit(cache=True, inline="always", error_model="numpy")
"""Decorator of a small kernel inlined into its callers (numba IR inlining)."""
