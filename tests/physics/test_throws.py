"""Whole throws: property tests over random launches, determinism, the fast path against the
full simulation, and the simulator's input checks."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from netgym.bench.throws import sample_throws
from netgym.launch import Thrower, action_to_launch, launch_velocity, sample_thrower
from netgym.physics.simulator import Simulator
from netgym.physics.throw import throw

_SIMS: dict[str, Simulator] = {}


def _sim(scene: str) -> Simulator:
    """One simulator per scene for the property tests, reset before each use."""
    if scene not in _SIMS:
        _SIMS[scene] = Simulator(scene)
    _SIMS[scene].reset()
    return _SIMS[scene]


def _launch(sim: Simulator, place: tuple[float, float, float], action: tuple[float, float, float]):
    cfg = sim.config.throw
    rng = np.random.default_rng(0)
    base = sample_thrower(cfg, sim.opening, rng)
    lerp = [lo + u * (hi - lo) for u, (lo, hi) in zip(place, (cfg.distance, cfg.bearing, cfg.height))]
    thrower = Thrower(distance=lerp[0], bearing=lerp[1], height=lerp[2], centre=base.centre)
    return thrower.position, launch_velocity(*action_to_launch(np.array(action), cfg), thrower)


unit = st.floats(0.0, 1.0)
signed = st.floats(-1.0, 1.0)


@pytest.mark.parametrize("scene", ["basket", "goal"])
@given(place=st.tuples(unit, unit, unit), action=st.tuples(signed, signed, signed))
def test_random_throws_are_finite_consistent_and_deterministic(scene: str, place, action) -> None:
    sim = _sim(scene)
    position, velocity = _launch(sim, place, action)
    result = throw(sim, position, velocity)
    assert np.all(np.isfinite(sim.state.x)) and np.all(np.isfinite(sim.state.v))
    assert np.all(np.isfinite(result.final_position))
    # a ball that came in through the opening and did not leave through it is inside the net
    assert result.captured == result.entered
    assert result.time <= sim.config.simulation.time_limit + 0.5 * sim.config.simulation.dt
    assert sim.n_balls == int(result.captured and sim.config.capture_rule == "held")  # goals (line) are taken out
    # the same throw from the same state gives the same outcome, bit for bit
    again = throw(_sim(scene), position, velocity)
    assert (again.captured, again.reason, again.substeps) == (result.captured, result.reason, result.substeps)
    assert np.array_equal(again.final_position, result.final_position)


def test_an_action_maps_linearly_onto_speed_elevation_and_azimuth() -> None:
    """The launch velocity of an action has the speed, the elevation above the horizon and the
    heading (offset from the direction to the opening's centre) that the action's entries map to
    linearly from [-1, 1] onto the scene's ranges."""
    sim = _sim("basket")
    cfg = sim.config.throw
    thrower = sample_thrower(cfg, sim.opening, np.random.default_rng(3))
    action = np.array([0.3, -0.7, 0.2])
    velocity = launch_velocity(*action_to_launch(action, cfg), thrower)
    expected = [lo + (a + 1.0) / 2.0 * (hi - lo) for a, (lo, hi) in zip(action, (cfg.speed, cfg.elevation, cfg.azimuth))]
    speed = np.linalg.norm(velocity)
    to_centre = sim.opening.centre[:2] - thrower.position[:2]
    heading = math.degrees(math.atan2(velocity[1], velocity[0]) - math.atan2(to_centre[1], to_centre[0]))
    assert speed == pytest.approx(expected[0])
    assert math.degrees(math.asin(velocity[2] / speed)) == pytest.approx(expected[1])
    assert (heading + 180.0) % 360.0 - 180.0 == pytest.approx(expected[2])


def test_a_throw_away_from_the_net_is_decided_in_closed_form() -> None:
    sim = _sim("basket")
    result = throw(sim, [5.0, 0.0, 1.8], [8.0, 0.0, 5.0])
    assert not result.captured and result.reason == "flies_away" and result.substeps == 0
    assert sim.n_balls == 0


def test_a_ball_that_glances_off_and_leaves_for_good_is_decided_as_it_leaves() -> None:
    """Up off the rim and away: once the ball is clear of the net's surroundings on a flight that
    never comes back, the miss is decided (it was flown on to the time limit)."""
    launch = [0.113, 3.237, 1.652], [0.02, -1.452, 8.234]
    sim = _sim("basket")
    result = throw(sim, *launch)
    assert not result.captured and result.reason == "flies_away"
    assert result.substeps > 0 and result.time < 2.0
    assert not throw(_sim("basket"), *launch, fast=False).captured


def test_a_ball_that_stops_on_the_ground_beside_the_sleeping_net_is_decided_at_rest() -> None:
    """Bounced and slid to a stop under the basket, clear of everything: nothing can move it any
    more, so the miss is decided when it stops (it was flown on to the time limit)."""
    sim = _sim("basket")
    result = throw(sim, [-3.81, -2.29, 1.78], [3.6, 1.1, 1.55])
    assert not result.captured and result.reason == "at_rest" and result.substeps == 0
    assert result.time < 0.5 * sim.config.simulation.time_limit and not np.any(result.final_velocity)
    assert result.final_position[2] == sim.model.ball_radius


def test_a_lob_into_the_basket_is_captured_early_and_stays() -> None:
    sim = _sim("basket")
    result = throw(sim, [5.0, 0.0, 1.8], [-5.0, 0.0, 6.1])
    assert result.captured and result.reason in ("cannot_leave", "at_rest_in_net")
    assert result.time < 0.5 * sim.config.simulation.time_limit
    assert sim.n_balls == 1
    second = throw(sim, [0.0, 5.0, 1.8], [0.0, -5.0, 6.1])  # lands on the first ball
    assert second.captured and sim.n_balls == 2


@pytest.mark.parametrize(("position", "velocity", "message"), [
    ([0.0, 0.0], [0.0, 0.0, 0.0], r"position must have shape \(3,\)"),
    ([0.0, 0.0, float("nan")], [0.0, 0.0, 0.0], "position must be finite"),
    ([5.0, 0.0, 0.1], [0.0, 0.0, 0.0], "below the ground"),
    ([5.0, 0.0, 2.0], [0.0, 0.0, float("inf")], "velocity must be finite"),
    ([5.0, 0.0, 2.0], [0.0, 150.0, 0.0], "speed 150 m/s; allowed: at most 100 m/s"),
])
def test_bad_launch_raises_and_leaves_the_state_alone(position, velocity, message) -> None:
    sim = _sim("basket")
    before = sim.state.copy()
    with pytest.raises(ValueError, match=message):
        throw(sim, position, velocity)
    assert sim.n_balls == 0 and np.array_equal(sim.state.x, before.x)


def test_remove_ball_checks_its_index() -> None:
    sim = _sim("basket")
    with pytest.raises(IndexError, match="ball index 0 out of range"):
        sim.remove_ball(0)


def test_clearance_is_the_distance_to_the_nearest_obstacle() -> None:
    from netgym.physics.kernels.surroundings import clearance

    sim = _sim("basket")
    m = sim.model
    sim.launch_ball([0.2, -0.3, 2.0], [0.0, 0.0, 0.0])
    sim.launch_ball([2.5, 0.0, 1.0], [0.0, 0.0, 0.0])
    rng = np.random.default_rng(5)
    net = sim.state.x[: m.n_net]
    start, end = net[m.segments[:, 0]], net[m.segments[:, 1]]
    on_segment = np.linspace(0.0, 1.0, 2001)[None, :, None]
    for _ in range(20):
        centre = rng.uniform([-3, -3, 0.3], [3, 3, 5])
        sim.state.x[-1] = centre
        # only a spring with an end within its length of the nearest end can hold the nearest point
        ends = np.minimum(np.linalg.norm(start - centre, axis=1), np.linalg.norm(end - centre, axis=1))
        near = ends - np.linalg.norm(end - start, axis=1) <= ends.min()
        points = start[near, None, :] + on_segment * (end - start)[near, None, :]  # 0.1 mm apart along each spring
        particles = np.linalg.norm(points - centre, axis=2).min() - m.ball_radius
        a, b = m.poles.start, m.poles.end
        t = np.clip(np.sum((centre - a) * (b - a), axis=1) / np.sum((b - a) ** 2, axis=1), 0, 1)
        poles = (np.linalg.norm(centre - (a + t[:, None] * (b - a)), axis=1) - m.ball_radius - m.poles.radius).min()
        other = np.linalg.norm(sim.state.x[-2] - centre) - 2 * m.ball_radius
        expected = min(particles, poles, other)
        got = clearance(sim.state.x, m.n_net, len(sim.state.x) - 1, m.ball_radius, m.segments, m.poles)
        assert expected - 1e-4 <= got <= expected + 1e-12


def test_the_boxed_clearance_never_exceeds_the_exact_one() -> None:
    """clearance_at_least (the net by its bounding box) is a lower bound of the exact clearance
    wherever the ball is, inside the net's box and out, with another ball and the poles about;
    equal where the poles or the other ball are nearest; far from the net it is close to it."""
    from netgym.physics.stepping import net_box
    from netgym.physics.kernels.surroundings import clearance, clearance_at_least

    sim = Simulator("basket")
    m = sim.model
    sim.launch_ball([2.5, 0.0, 1.0], [0.0, 0.0, 0.0])
    sim.launch_ball([0.0, 0.0, 5.0], [0.0, 0.0, 0.0])
    x, row = sim.state.x, len(sim.state.x) - 1
    box = np.empty(6)
    net_box(x, m.n_net, box)
    rng = np.random.default_rng(11)
    gaps = []
    for _ in range(300):
        x[row] = rng.uniform([-6, -6, 0.3], [6, 6, 8])
        exact = clearance(x, m.n_net, row, m.ball_radius, m.segments, m.poles)
        bound = clearance_at_least(x, m.n_net, row, m.ball_radius, box, m.poles)
        assert bound <= exact
        gaps.append((bound, exact))
    far = [(b, e) for b, e in gaps if b > 3.0]
    assert far and all(e - b < 0.5 * e for b, e in far)


def test_a_ball_resting_on_a_jittering_net_is_decided_at_rest() -> None:
    """A ball dropped onto the goal's roof comes to rest there while the light net under it keeps
    a velocity jitter above ``rest_speed`` (of the order of its acceleration x dt): the rest test
    reads positions, so the throw is decided at rest, not at the time limit, and as a miss."""
    sim = Simulator("goal")
    result = throw(sim, [0.43, -0.56, 2.3], [0.0, 0.0, 0.0])
    assert result.reason == "at_rest" and not result.captured and result.time < 3.0
    sim.launch_ball([0.43, -0.56, 2.3], [0.0, 0.0, 0.0])
    sim.step(round(3.0 / sim.dt))
    s, row = sim.state, sim.model.n_net
    near = np.linalg.norm(s.x - s.x[row], axis=1) < 2.0 * sim.model.ball_radius + 0.2
    assert np.abs(s.v[near]).max() > sim.config.simulation.rest_speed  # the jitter a velocity test would wait on


def test_the_segment_broad_phase_changes_nothing() -> None:
    """A ball's net contacts resolved with the list of nearby segments give bitwise what testing
    every segment gives (an unbounded extent lists every particle), on the states of a fast ball
    hitting a loaded basket: resting balls, impacts, and impacts that move the bodies so far that
    the list is abandoned mid-way."""
    from netgym.physics.kernels import impulse_contacts as contacts

    sim = _sim("basket")
    for x in (-0.4, 0.3):
        throw(sim, [x, 0.2, 3.6], [0.0, 0.0, 0.0])
    sim.launch_ball([-5.0, 0.0, 3.5], [9.0, 0.0, 0.5])  # into the far side of the net, hard
    m, k = sim.model, sim.kernel_model
    moves = []
    for _ in range(200):
        sim.step(1)
        s = sim.state
        for ahead in (0.0, 0.01):  # as the step left it; its balls flown on 10 ms into the net, unresolved
            start = s.x.copy()
            start[m.n_net:] += ahead * s.v[m.n_net:]
            extent = contacts._segment_extent(start, k.segments)
            for b in range(m.n_net, len(s.x)):
                results = []
                for bound in (extent, np.inf):
                    x, v = start.copy(), s.v.copy()
                    moved = contacts._ball_net(contacts.Bodies(x, v, s.inv_mass, start), b, k, bound,
                                               np.empty(m.n_net, dtype=np.int64))
                    results.append((x, v, moved))
                (x1, v1, moved), (x2, v2, _) = results
                assert np.array_equal(x1, x2) and np.array_equal(v1, v2)
                moves.append(moved)
    moves = np.array(moves)
    assert np.sum(moves > 0.0) > 200  # contacts resolved
    assert np.any(moves > contacts.NEAR_MARGIN / 4)  # and the list abandoned mid-way


@pytest.mark.slow
def test_the_fast_path_integrates_on_the_full_simulations_step_grid() -> None:
    """The ball flies in closed form to whole steps after the launch only, so that where the fast
    path integrates it takes the full simulation's own steps: every integration request of these
    throws into the held goal that touch the net ends a whole number of steps after the
    launch, and each throw's outcome is the full simulation's."""
    sim = Simulator("goal", {"capture_rule": "held"})
    touching = 0
    for position, velocity in sample_throws("goal", 6, seed=3):
        sim.reset()
        launched, ends = sim.state.time, []
        fast = throw(sim, position, velocity, observer=lambda s: ends.append(s.state.time - launched))
        if fast.substeps == 0:
            continue  # decided in closed form: nothing integrated
        touching += 1
        steps = np.array(ends) / sim.dt
        assert np.abs(steps - np.round(steps)).max() < 1e-6
        sim.reset()
        assert throw(sim, position, velocity, fast=False).captured == fast.captured
    assert touching >= 4
