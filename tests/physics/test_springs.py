"""The force pass over springs grouped by index offset against a plain loop over the springs."""

from __future__ import annotations

import math

import numpy as np
import pytest

from netgym.physics.kernels import smooth_forces as forces, spring_law
from netgym.physics.simulator import Simulator
from netgym.physics.kernels.springs import EXISTS, Springs


def _serial_spring_forces(x, v, pairs, params, f) -> None:
    """The textbook loop: each spring in the given order adds its force (the law, not its
    grouping, from :mod:`~netgym.physics.kernels.spring_law`) to both ends."""
    for (i, j), (rest, ks, kd) in zip(pairs.tolist(), params.tolist()):
        d = [x[i, c] - x[j, c] for c in range(3)]
        length = math.sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2])
        if length <= 1e-12:
            continue
        inv = 1.0 / length
        u = [d[c] * inv for c in range(3)]
        closing = (v[i, 0] - v[j, 0]) * u[0] + (v[i, 1] - v[j, 1]) * u[1] + (v[i, 2] - v[j, 2]) * u[2]
        mag = spring_law.tension.py_func(length, rest, ks, kd, closing)
        for c in range(3):
            f[i, c] += mag * u[c]
            f[j, c] -= mag * u[c]


def _bits(a: np.ndarray) -> np.ndarray:
    return a.view(np.uint64)


@pytest.mark.parametrize("scene", ["basket", "goal"])
def test_grouped_pass_is_bitwise_the_serial_loop_on_a_scenes_net(scene: str) -> None:
    """A disturbed net (forces already in ``f``, balls' rows untouched): every bit the same as
    the loop over the springs sorted by particle pair; the dense groups hold most springs."""
    sim = Simulator(scene)
    model, springs = sim.model, sim.kernel_model.springs
    rng = np.random.default_rng(1)
    x, v = sim.state.x.copy(), rng.normal(0.0, 1.0, sim.state.x.shape)
    x[:model.n_net] += rng.normal(0.0, 0.01, (model.n_net, 3))
    expected = rng.normal(0.0, 1.0, x.shape)
    got = expected.copy()
    _serial_spring_forces(x, v, model.springs, model.spring_params, expected)
    forces.spring_forces(x, v, springs, got)
    assert np.array_equal(_bits(got), _bits(expected))
    dense = springs.groups["dense"]
    assert springs.dense_params[EXISTS].sum() > 0.9 * len(model.springs)
    assert dense.any() and (~dense).any()


@pytest.mark.parametrize("scene", ["basket", "goal"])
def test_dense_blocks_and_columns_start_cache_lines(scene: str) -> None:
    """Every row of the dense blocks and the columns, and every dense range, starts a cache line
    (8 float64), so vector loads of first particles, parameters and forces read one line each."""
    springs = Simulator(scene).kernel_model.springs
    for rows in (springs.dense_params, *springs.dense_forces, *springs.columns):
        assert rows.flags.c_contiguous and rows.ctypes.data % 64 == 0 and rows.shape[1] % 8 == 0
    dense = springs.groups[springs.groups["dense"]]
    for field in ("first", "length", "start"):
        assert np.all(dense[field] % 8 == 0)
    # the widened ranges stay inside the columns
    reach = dense["offset"] + dense["first"] + dense["length"]
    assert np.all(reach <= springs.columns.shape[2])


def test_grouped_pass_is_bitwise_the_serial_loop_on_random_springs_with_degenerate_ones() -> None:
    """Random graphs, pairs given in any order and either way round, springs of two stiffnesses
    and two dampings (so an offset's springs fall into several groups, dense and sparse), some of
    zero length (they add nothing), zero forces and signed zeros in ``f``: the serial loop over
    the pairs sorted, to the last bit."""
    rng = np.random.default_rng(7)
    dense_groups = 0
    for trial in range(30):
        n = int(rng.integers(2, 60))
        offsets = rng.integers(1, max(2, n // 3), 4)
        chain = [(i, i + d) for d in offsets for i in range(n - d) if rng.random() < 0.8]
        extra = [tuple(sorted(rng.choice(n, 2, replace=False))) for _ in range(int(rng.integers(0, 20)))]
        pairs = np.array(sorted(set(map(tuple, map(sorted, chain + extra)))), dtype=np.int64).reshape(-1, 2)
        params = np.column_stack([rng.uniform(0.1, 1.0, len(pairs)), rng.choice([30.0, 100.0 / 3.0], len(pairs)),
                                  rng.choice([0.0, 0.7], len(pairs), p=[0.1, 0.9])])
        x, v = rng.normal(0.0, 1.0, (n + 2, 3)), rng.normal(0.0, 1.0, (n + 2, 3))
        x[rng.integers(0, n, 3)] = x[0]          # some springs of zero length
        f = rng.choice([0.0, -0.0, 1.5], size=x.shape)
        expected = f.copy()
        _serial_spring_forces(x, v, pairs, params, expected)
        shuffled = rng.permutation(len(pairs))
        swapped = pairs[shuffled][:, ::-1] if trial % 2 else pairs[shuffled]
        got = f.copy()
        springs = Springs.of(swapped, params[shuffled], n)
        forces.spring_forces(x, v, springs, got)
        assert np.array_equal(_bits(got), _bits(expected)), trial
        dense_groups += int(springs.groups["dense"].sum())
    assert dense_groups > 30


@pytest.mark.parametrize("pairs, params, message", [
    ([[0, 1]], [[1.0, 1.0, 0.0], [1.0, 1.0, 0.0]], "1 spring pairs but 2 rows"),
    ([[2, 2]], [[1.0, 1.0, 0.0]], "two different particles of 0..3"),
    ([[0, 4]], [[1.0, 1.0, 0.0]], "two different particles of 0..3"),
    ([[0, 1], [1, 0]], [[1.0, 1.0, 0.0]] * 2, "comes twice"),
])
def test_springs_of_rejects_bad_pairs_by_name(pairs, params, message) -> None:
    with pytest.raises(ValueError, match=message):
        Springs.of(np.array(pairs), np.array(params), 4)


def test_the_spring_law_is_hookes_law_with_a_damper_along_the_axis() -> None:
    """A 2 m spring of rest length 1.5 m, ks 100 N/m pulls its ends together with 50 N; at rest
    length it pulls with nothing; closing at 0.3 m/s its 4 N s/m damper pushes them apart by 1.2 N."""
    law = spring_law
    assert law.tension.py_func(2.0, 1.5, 100.0, 0.0, 0.0) == pytest.approx(-50.0)
    assert law.tension.py_func(1.5, 1.5, 100.0, 4.0, 0.0) == 0.0
    assert law.tension.py_func(1.5, 1.5, 100.0, 4.0, -0.3) == pytest.approx(1.2)


def test_the_spring_force_is_minus_the_gradient_of_its_energy() -> None:
    """Central differences of the energy along the axis give the elastic tension, at stretched and
    compressed lengths; across the axis the stiffness over ks is 1 - L / l when stretched, as the
    tension's turning of the axis gives (force / length), and 0 when compressed."""
    law, rest, ks, h = spring_law, 1.5, 100.0, 1e-6
    for length in (1.2, 1.5, 2.0, 3.7):
        gradient = (law.energy.py_func(length + h, rest, ks) - law.energy.py_func(length - h, rest, ks)) / (2 * h)
        assert -gradient == pytest.approx(law.elastic_tension.py_func(length, rest, ks), abs=1e-6)
    assert law.stretch.py_func(2.0, 1.5) == pytest.approx(-law.elastic_tension.py_func(2.0, 1.5, ks) / (ks * 2.0))
    assert law.stretch.py_func(1.2, 1.5) == 0.0 and law.stretch.py_func(0.0, 1.5) == 0.0
