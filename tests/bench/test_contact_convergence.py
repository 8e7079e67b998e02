"""Convergence through contact (netgym.bench.accuracy.contact_convergence): the phases, the slopes and
the flags it reports, and what it measures of the simulator: a ball's free flight is exact for
every integrator until the first contact, and errors appear only once it touches the net."""

from __future__ import annotations

import math

import numpy as np
import pytest

from netgym.bench.accuracy.contact_convergence import (ENSEMBLE_OFFSET, PHASES, QUICK_LADDERS, ensemble_launches,
                                              fitted_slope, flagged, measure_strike, phase_errors, summary)
from netgym.bench.accuracy.convergence_table import default_cost, slope_table, strike_table
from netgym.bench.accuracy.work_precision import STRIKE
from netgym.physics.simulator import Simulator


def test_phase_errors_take_the_largest_distance_of_each_phase() -> None:
    reference = np.zeros((12, 3))
    balls = reference.copy()
    balls[:, 0] = np.arange(12) * 1e-3  # the error grows by 1 mm a sample
    errors = phase_errors(balls, reference, contact=3)  # 5 samples (10 ms) after the contact
    assert errors == {PHASES[0]: pytest.approx(2e-3), PHASES[1]: pytest.approx(7e-3), PHASES[2]: pytest.approx(11e-3)}
    assert math.isnan(phase_errors(balls, reference, contact=12)[PHASES[1]])


def test_fitted_slope_recovers_a_known_order_and_ignores_round_off() -> None:
    dts = [0.1 / 2 ** k for k in range(6)]
    assert fitted_slope(dts, [3.0 * dt ** 4 for dt in dts]) == pytest.approx(4.0)
    assert fitted_slope(dts, [0.5 * dt for dt in dts]) == pytest.approx(1.0)
    assert math.isnan(fitted_slope(dts, [1e-12] * len(dts)))  # round-off has no order
    # points at or below the floor (what the reference resolves) are left out of the fit
    assert fitted_slope(dts, [dt if dt > 0.02 else 1e-3 for dt in dts], floor=1e-3) == pytest.approx(1.0)
    assert flagged(1e-5, 2e-6) and not flagged(1e-4, 2e-6)


def test_ensemble_launches_lie_within_the_offset_and_are_seeded() -> None:
    launches = ensemble_launches(16, seed=3)
    offsets = np.array([p - STRIKE[0] for p, _ in launches])
    assert np.all(np.linalg.norm(offsets, axis=1) <= ENSEMBLE_OFFSET) and np.ptp(offsets) > ENSEMBLE_OFFSET
    assert all(np.array_equal(v, STRIKE[1]) for _, v in launches)
    assert np.array_equal(offsets, np.array([p - STRIKE[0] for p, _ in ensemble_launches(16, seed=3)]))


@pytest.fixture(scope="module")
def quick_strike() -> dict:
    """The report's strike, 0.3 s, two steps of every integrator, against RK4 at 125 us."""
    sim = Simulator("basket", check_stability=False)
    return measure_strike(sim, STRIKE, QUICK_LADDERS, seconds=0.3, reference_dt=1.25e-4)


def test_free_flight_is_exact_until_the_first_contact(quick_strike: dict) -> None:
    """Before the ball touches the net every integrator flies it to round-off (the reference's
    first contact found where the ball leaves its parabola, after it falls to the net); after
    the contact the methods differ."""
    assert 0.1 < quick_strike["contact_time"] < 0.3
    for row in quick_strike["rows"]:
        assert not row["diverged"]
        assert row["errors"][PHASES[0]] < 1e-12
        assert row["errors"][PHASES[1]] > 1e-7
    assert quick_strike["self_difference"][PHASES[0]] < 1e-12


def test_tables_mark_rows_the_reference_cannot_resolve(quick_strike: dict) -> None:
    table = strike_table(quick_strike)
    assert len(table.splitlines()) == 2 + sum(len(v) for v in QUICK_LADDERS.values())
    first = table.splitlines()[2].split("|")
    assert first[3].strip().endswith("*")  # round-off before the contact: within the reference's own difference
    one = summary([quick_strike])
    assert len(slope_table(one, one).splitlines()) == 2 + len(QUICK_LADDERS) * len(PHASES)
    assert all(math.isnan(s["slope"]) for s in one["slopes"] if s["phase"] == PHASES[0])
    assert one["rows"][0][PHASES[1]]["median"] == quick_strike["rows"][0]["errors"][PHASES[1]]
    assert default_cost(one).startswith("The default, imex_euler at 2 ms")
