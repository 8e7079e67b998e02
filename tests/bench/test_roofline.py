"""The roofline's measuring kernels and its counts."""

from __future__ import annotations

import numpy as np

from netgym.bench.speed import roofline


def test_the_instruction_count_tells_a_vectorised_loop_from_a_scalar_one() -> None:
    a, b, c = np.zeros(1024), np.ones(1024), np.ones(1024)
    packed, _ = roofline.packed_instructions(roofline._triad, a, b, c, 0.5)
    assert packed > 0  # a triad over contiguous arrays vectorises
    _, scalar = roofline.packed_instructions(roofline.forces.spring_forces, *roofline.spring_pass_arguments())
    assert scalar > 0


def test_the_kernels_compute_what_they_time() -> None:
    a, b, c = np.zeros(8), np.arange(8.0), np.full(8, 2.0)
    roofline._triad(a, b, c, 0.5)
    assert np.array_equal(a, b + 1.0)
    x, out = np.array([4.0, 16.0]), np.empty(2)
    roofline._sqrt_div(x, out)
    assert np.array_equal(out, [0.5, 0.25])
    x = np.array([1.0])
    expected = 0.0
    for k in range(8):
        acc = 1.0
        for _ in range(3):
            acc = acc * (0.999999 - 1e-6 * k) + 1e-7 * (k + 1)
        expected += acc
    assert np.isclose(roofline._fma_chains(x, 3), expected, rtol=1e-12)


def test_the_floor_is_the_highest_roof_and_the_counts_are_the_passs() -> None:
    figures = roofline.roofline(quick=True)
    floors = [value for name, value in figures.items() if name.startswith("floor_ns_")]
    assert len(floors) == 3 and figures["floor_ns"] == max(floors)
    assert figures["bytes_per_spring"] == 8 * (2 + 3 + 6 + 6 + 12) and figures["springs"] == 3250
    assert figures["measured_ns_per_spring"] > 0


def test_the_parts_timed_alone_do_the_passs_own_work() -> None:
    """The copies put the state in the pass's columns; the dense force loops alone leave the
    forces the whole pass leaves; the parts' and rest's times add up to the whole pass."""
    x, v, springs, f = roofline.spring_pass_arguments()
    v = np.random.default_rng(0).normal(0.0, 0.1, v.shape)  # the dampers act too
    roofline.forces.spring_forces(x, v, springs, f)
    whole = springs.dense_forces.copy()
    springs.dense_forces[:] = np.nan
    roofline._copies(x, v, springs, np.zeros_like(f), 1)
    n = springs.n_particles
    columns = springs.columns
    assert np.array_equal(columns[roofline.forces.POSITIONS][:, :n], x.T)
    assert np.array_equal(columns[roofline.forces.VELOCITIES][:, :n], v.T)
    roofline._dense_forces(x, v, springs, f, 1)
    assert np.array_equal(springs.dense_forces, whole, equal_nan=True)
    parts = roofline.spring_pass_parts((x, v, springs, f), repeats=2)
    assert set(parts) == {*roofline.PARTS, "sparse groups and the rest", "whole pass"}
    assert np.isclose(sum(value for name, value in parts.items() if name != "whole pass"), parts["whole pass"])
