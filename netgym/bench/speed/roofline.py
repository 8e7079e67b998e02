"""A roofline of the spring pass: what this machine can do against what the pass does.

The spring pass (:func:`netgym.physics.kernels.smooth_forces.spring_forces`) reads, per spring, its two
particle indices and three parameters (rest length, ks, kd), the positions and velocities of its
two particles, and adds a force to each of them: a floor on its time is set by the bytes it
moves at the bandwidth of the cache level its arrays live in, by its arithmetic at the core's
floating-point peak, and by its one square root and one division. This module measures the
machine's side with small numba kernels (a streaming triad, independent fused multiply-adds,
independent square roots and divisions) and the pass's own time on a scene's net, one thread,
called from compiled code as the integrators call it.

Counts per spring (float64, 8 bytes): reads 2 indices + 3 parameters + 2 x 3 positions +
2 x 3 velocities = 17 words; the two force rows are read and written back, 2 x 3 words each way:
:data:`SPRING_BYTES`. Arithmetic (:data:`SPRING_FLOPS`): 3 differences, a dot product
(5), 3 scalings by the inverse length, 3 velocity differences and their projection (5), the
magnitude (4) and 3 + 6 for the force and its two accumulations: 32, besides one square root
and one division. These are the counts of a pass that reads each spring's own data; the dense
groups of :class:`~netgym.physics.kernels.springs.Springs` read neither indices nor a stiffness and
damping a spring, which is how a pass can come near this floor.
"""

from __future__ import annotations

import math
import re
import time
from collections.abc import Callable
from pathlib import Path

import numpy as np
from numba import njit

import netgym.physics
from netgym.physics.kernel_cache import drop_stale_kernels
from netgym.physics.kernels import smooth_forces as forces
from netgym.physics.simulator import Simulator

drop_stale_kernels(Path(__file__).parent, depends_on=(Path(netgym.physics.__file__).parent,))  # its kernels call physics

SPRING_BYTES = 8 * (17 + 12)
SPRING_FLOPS = 32
SPRING_SQRT_DIV = 1      # one square root and one division per spring


@njit(cache=True, error_model="numpy")
def _triad(a, b, c, scale):
    for k in range(a.shape[0]):
        a[k] = b[k] + scale * c[k]


@njit(cache=True, fastmath=True)
def _fma_chains(x, repeats):
    """Eight independent multiply-add chains per element of ``x`` (``repeats`` passes), the
    elements independent too, so the compiler may vectorise them (fastmath): the core's peak."""
    total = 0.0
    for k in range(x.shape[0]):
        a0 = a1 = a2 = a3 = a4 = a5 = a6 = a7 = x[k]
        for _ in range(repeats):
            a0 = a0 * 0.999999 + 1e-7
            a1 = a1 * 0.999998 + 2e-7
            a2 = a2 * 0.999997 + 3e-7
            a3 = a3 * 0.999996 + 4e-7
            a4 = a4 * 0.999995 + 5e-7
            a5 = a5 * 0.999994 + 6e-7
            a6 = a6 * 0.999993 + 7e-7
            a7 = a7 * 0.999992 + 8e-7
        total += a0 + a1 + a2 + a3 + a4 + a5 + a6 + a7
    return total


@njit(cache=True, error_model="numpy")
def _sqrt_div(x, out):
    """One square root and one division per element, all independent."""
    for k in range(x.shape[0]):
        out[k] = 1.0 / math.sqrt(x[k])


def _best(run: Callable[[], None], repeats: int) -> float:
    """The shortest of ``repeats`` timings of ``run`` (after one untimed call), in seconds."""
    run()
    best = math.inf
    for _ in range(repeats):
        start = time.perf_counter()
        run()
        best = min(best, time.perf_counter() - start)
    return best


def bandwidth(total_bytes: int, repeats: int = 20) -> float:
    """Bytes per second of a triad ``a = b + s c`` over three float64 arrays of ``total_bytes``
    in all (reads of b and c and the write of a counted, 24 bytes an element)."""
    n = max(total_bytes // 24, 1024)
    a, b, c = np.zeros(n), np.ones(n), np.full(n, 2.0)
    return 24 * n / _best(lambda: _triad(a, b, c, 0.5), repeats)


def fma_peak(repeats: int = 10) -> float:
    """Floating-point operations per second of independent fused multiply-adds (2 each)."""
    x = np.random.default_rng(0).random(4096)
    passes = 1000
    seconds = _best(lambda: _fma_chains(x, passes), repeats)
    return 2 * 8 * x.shape[0] * passes / seconds


def sqrt_div_rate(repeats: int = 20) -> float:
    """Independent (square root + division) pairs per second."""
    x = np.random.default_rng(0).random(1 << 14) + 1.0
    out = np.empty_like(x)
    return x.shape[0] / _best(lambda: _sqrt_div(x, out), repeats)


def spring_pass_arguments(scene: str = "basket") -> tuple[np.ndarray, ...]:
    """The arguments of :func:`~netgym.physics.kernels.smooth_forces.spring_forces` for ``scene``'s net at rest."""
    sim = Simulator(scene)
    return sim.state.x, sim.state.v, sim.kernel_model.springs, np.zeros_like(sim.state.x)


@njit(cache=True, error_model="numpy")
def _spring_passes(x, v, springs, f, passes):
    """``passes`` spring passes in a row, called from compiled code as the integrators call it."""
    for _ in range(passes):
        forces.spring_forces(x, v, springs, f)


PASSES_A_TIMING = 100
"""Spring passes a timing of :func:`spring_pass_seconds` runs in one compiled call."""


def spring_pass_seconds(arguments: tuple[np.ndarray, ...], repeats: int = 20) -> float:
    """Seconds of one spring pass over :func:`spring_pass_arguments`, as the integrators pay it:
    the best of ``repeats`` timings of :data:`PASSES_A_TIMING` passes run in one compiled call,
    a pass's share. A call from Python would add numba's dispatch (unboxing the arguments,
    about 1.5 us, half a nanosecond a spring on the basket), which no simulation step pays:
    the integrators call the pass from their own kernels."""
    return _best(lambda: _spring_passes(*arguments, PASSES_A_TIMING), repeats) / PASSES_A_TIMING


@njit(cache=True, error_model="numpy")
def _copies(x, v, springs, f, passes):
    """The pass's copies alone: positions, velocities and forces into columns, forces back."""
    columns, n = springs.columns, springs.n_particles
    for _ in range(passes):
        forces._to_columns(x, columns[forces.POSITIONS], n)
        forces._to_columns(v, columns[forces.VELOCITIES], n)
        forces._to_columns(f, columns[forces.TOTALS], n)
        forces._from_columns(columns[forces.TOTALS], f, n)


@njit(cache=True, error_model="numpy")
def _dense_forces(x, v, springs, f, passes):
    """The dense groups' force loops alone (each slot's force on both its particles)."""
    columns = springs.columns
    for _ in range(passes):
        for group in springs.groups:
            if group.dense:
                forces._dense_group_forces(columns[forces.POSITIONS], columns[forces.VELOCITIES], springs.dense_params,
                                           springs.dense_forces, group.offset, group.first, group.length,
                                           group.start, group.ks, group.kd)


@njit(cache=True, error_model="numpy")
def _dense_adds(x, v, springs, f, passes):
    """The dense groups' additions alone (both planes of forces into the particles' totals)."""
    totals = springs.columns[forces.TOTALS]
    for _ in range(passes):
        for group in springs.groups:
            if group.dense:
                forces._add_dense_group(totals, springs.dense_forces[forces.ON_SECOND], group.first + group.offset,
                                        group.length, group.start)
                forces._add_dense_group(totals, springs.dense_forces[forces.ON_FIRST], group.first, group.length,
                                        group.start)


PARTS = {"column copies": _copies, "dense force loops": _dense_forces, "dense additions": _dense_adds}
"""The parts of the spring pass timed alone by :func:`spring_pass_parts`, each calling the pass's
own inlined kernels; the rest of the pass is its sparse groups and its loops over groups."""


def spring_pass_parts(arguments: tuple[np.ndarray, ...], repeats: int = 20) -> dict[str, float]:
    """Seconds a pass of each of :data:`PARTS` alone, timed as :func:`spring_pass_seconds` times
    the whole pass, and of the rest (the whole pass less the parts: the sparse groups and the
    loops over groups); the dense slots outnumber the springs they hold (registers filled out)."""
    forces.spring_forces(*arguments)
    parts = {name: _best(lambda part=part: part(*arguments, PASSES_A_TIMING), repeats) / PASSES_A_TIMING
             for name, part in PARTS.items()}
    whole = spring_pass_seconds(arguments, repeats)
    return {**parts, "sparse groups and the rest": whole - sum(parts.values()), "whole pass": whole}


def packed_instructions(kernel, *args) -> tuple[int, int]:
    """(packed, scalar) double-precision arithmetic instructions in the machine code of
    ``kernel`` (a netgym numba kernel) compiled for ``args``: packed ones (``...pd`` on ymm or
    zmm registers) are what vectorisation leaves; a loop is scalar where this is (0, n). A
    cached kernel's code cannot be inspected, so an uncached copy is compiled."""
    copy = njit(error_model="numpy")(kernel.py_func)
    copy(*args)
    lines = "\n".join(copy.inspect_asm().values()).splitlines()
    arithmetic = re.compile(r"^\s*v(?:add|sub|mul|div|sqrt|fn?m(?:add|sub)\w*)(pd|sd)\s")
    kinds = [m.group(1) for m in map(arithmetic.match, lines) if m]
    wide = [line for line in lines if arithmetic.match(line) and re.search(r"%[yz]mm", line)]
    packed, scalar = len(wide), kinds.count("sd")
    return packed, scalar


def roofline(scene: str = "basket", quick: bool = False) -> dict[str, float]:
    """The machine's roofs, the spring pass's floor from them and its measured time, per spring
    (ns); the scene's arrays fit in the L2 cache, so the L2 bandwidth is the memory roof."""
    repeats = 3 if quick else 20
    arguments = spring_pass_arguments(scene)
    n_springs = int(arguments[2].pairs.shape[0])
    seconds = spring_pass_seconds(arguments, 2 if quick else 20)
    l2 = bandwidth(256 * 1024, repeats)
    dram = bandwidth((16 if quick else 768) * 1024 * 1024, 2 if quick else 5)
    peak = fma_peak(2 if quick else 10)
    sqrt_div = sqrt_div_rate(repeats)
    parts = spring_pass_parts(arguments, 2 if quick else 20)
    springs = arguments[2]
    dense_slots = int(springs.groups["length"][springs.groups["dense"]].sum())
    floors = {"memory (L2)": 1e9 * SPRING_BYTES / l2, "arithmetic": 1e9 * SPRING_FLOPS / peak,
              "square root and division": 1e9 * SPRING_SQRT_DIV / sqrt_div}
    return {"scene": scene, "springs": n_springs, "bytes_per_spring": SPRING_BYTES,
            "flops_per_spring": SPRING_FLOPS, "l2_bandwidth_gb_s": l2 / 1e9, "dram_bandwidth_gb_s": dram / 1e9,
            "fma_peak_gflop_s": peak / 1e9, "sqrt_div_per_ns": sqrt_div / 1e9,
            **{f"floor_ns_{name}": value for name, value in floors.items()},
            "floor_ns": max(floors.values()), "measured_ns_per_spring": 1e9 * seconds / n_springs,
            "spring_pass_packed_scalar_instructions": packed_instructions(forces.spring_forces, *arguments),
            "dense_slots": dense_slots, "sparse_springs": int(springs.sparse.shape[0]),
            "parts_ns_per_spring": {name: 1e9 * value / n_springs for name, value in parts.items()}}


def to_markdown(record: dict) -> str:
    """The roofline table of a result file's record (:func:`netgym.bench.results.read_results`
    of what ``scripts/roofline.py`` wrote), with its source."""
    f = record["figures"]
    packed, scalar = f["spring_pass_packed_scalar_instructions"]
    rows = [("L2-resident triad bandwidth", f"{f['l2_bandwidth_gb_s']:.1f} GB/s",
             f"{f['bytes_per_spring']} bytes a spring", f"{f['floor_ns_memory (L2)']:.2f} ns"),
            ("DRAM-sized triad bandwidth", f"{f['dram_bandwidth_gb_s']:.1f} GB/s", "(the net's arrays fit in L2)", ""),
            ("FMA peak (vectorised)", f"{f['fma_peak_gflop_s']:.1f} GFLOP/s", f"{f['flops_per_spring']} flops a spring",
             f"{f['floor_ns_arithmetic']:.2f} ns"),
            ("square root + division (vectorised)", f"{f['sqrt_div_per_ns']:.2f} per ns", "one of each a spring",
             f"{f['floor_ns_square root and division']:.2f} ns")]
    lines = ["| roof | this machine | the spring pass needs | floor per spring |", "|---|---:|---|---:|"]
    lines += [f"| {a} | {b} | {c} | {d} |" for a, b, c, d in rows]
    lines += ["", f"On the {f['scene']} net ({f['springs']} springs, one thread) the pass takes "
              f"**{f['measured_ns_per_spring']:.2f} ns per spring**, {f['measured_ns_per_spring'] / f['floor_ns']:.1f}x "
              f"its floor of {f['floor_ns']:.2f} ns (the highest roof); its machine code has {packed} packed and "
              f"{scalar} scalar double-precision arithmetic instructions.", ""]
    if "parts_ns_per_spring" in f:
        lines += _parts_table(f) + [""]
    lines += [f"Source: `docs/results/roofline.json`, written by `{record['command']}` ({record['written']}, "
              f"{record['machine']})."]
    return "\n".join(lines)


def _parts_table(f: dict) -> list[str]:
    """Where the pass's time goes: each part timed alone, ns per spring and its share."""
    parts, whole = f["parts_ns_per_spring"], f["parts_ns_per_spring"]["whole pass"]
    lines = [f"Where it goes (each part timed alone, ns per spring of the {f['springs']}; the dense groups run "
             f"{f['dense_slots']} slots, registers filled out, and {f['sparse_springs']} springs are in sparse groups):",
             "", "| part of the pass | ns per spring | share |", "|---|---:|---:|"]
    lines += [f"| {name} | {value:.2f} | {100 * value / whole:.0f}% |" for name, value in parts.items()
              if name != "whole pass"]
    return lines + [f"| whole pass | {whole:.2f} | |"]
