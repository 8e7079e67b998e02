"""The types that decide a throw's outcome: reasons, capture rules, the fast path's tuning, the film."""

from __future__ import annotations

import math

import gymnasium as gym
import numpy as np
import pytest

import netgym
from netgym.aim import BallisticAim
from netgym.config import load_scene
from netgym.envs.observation import aim_at_centre
from netgym.physics.film import Film, FrameClock
from netgym.physics.model.opening import Opening
from netgym.physics.outcomes import HeldRule, LineRule, Reason, capture_rule
from netgym.physics.throw import TUNING

GOAL_MOUTH = Opening.of_net(load_scene("goal").net)
RADIUS = 0.11


def _past_the_plane(depth: float) -> np.ndarray:
    """A point ``depth`` past the goal mouth's plane (inwards), level with its centre."""
    point = GOAL_MOUTH.centre
    point[GOAL_MOUTH.axis] -= GOAL_MOUTH.sign * depth
    return point


def test_reasons_are_the_strings_info_holds() -> None:
    assert [str(reason) for reason in Reason] == ["flies_away", "at_rest", "at_rest_in_net", "cannot_reach_opening",
                                                  "cannot_leave", "crossed_line", "out_of_play", "time_limit",
                                                  "time_limit_in_net"]
    assert Reason.CANNOT_REACH_OPENING.for_outcome(True) is Reason.CANNOT_LEAVE
    assert Reason.CANNOT_REACH_OPENING.for_outcome(False) is Reason.CANNOT_REACH_OPENING
    assert Reason.AT_REST == "at_rest" and f"{Reason.TIME_LIMIT}" == "time_limit"
    assert Reason("out_of_play") is Reason.OUT_OF_PLAY


@pytest.mark.slow
@pytest.mark.parametrize("env_id", [i for i in netgym.ENVIRONMENTS if i != "NetCatchPixels-v0"])
def test_no_reason_labels_both_outcomes(env_id: str) -> None:
    """Aimed and random episodes of every id: each reason seen comes with one outcome only."""
    env = gym.make(env_id, disable_env_checker=True)
    aim = BallisticAim(env.unwrapped.scene)
    rng = np.random.default_rng(0)
    outcomes: dict[str, set[bool]] = {}
    for episode in range(16):
        obs, _ = env.reset(seed=episode)
        done = False
        while not done:
            action = aim_at_centre(aim, obs) if episode % 2 else rng.uniform(-1, 1, 3).astype(np.float32)
            obs, _, done, _, info = env.step(action)
            outcomes.setdefault(info["reason"], set()).add(bool(info["captured"]))
    assert {True, False} <= set().union(*outcomes.values())  # both outcomes occurred
    assert all(len(seen) == 1 for seen in outcomes.values()), outcomes


def test_the_scene_names_its_rule_once() -> None:
    assert isinstance(capture_rule("held"), HeldRule) and isinstance(capture_rule("line"), LineRule)
    with pytest.raises(ValueError, match="capture_rule = 'inside' is not one of"):
        capture_rule("inside")


def test_the_line_rule_decides_once_the_whole_ball_is_over_the_line() -> None:
    line = LineRule()
    half_over = _past_the_plane(0.5 * RADIUS)
    over = _past_the_plane(RADIUS)
    assert line.decision(GOAL_MOUTH, RADIUS, half_over, entered=True, from_front=True) is None
    assert line.decision(GOAL_MOUTH, RADIUS, over, entered=True, from_front=True) is Reason.CROSSED_LINE
    assert line.decision(GOAL_MOUTH, RADIUS, over, entered=False, from_front=True) is Reason.OUT_OF_PLAY
    assert line.decision(GOAL_MOUTH, RADIUS, over, entered=False, from_front=False) is None  # launched behind it
    assert line.captured(Reason.CROSSED_LINE, entered=True, inside=False)
    assert not line.captured(Reason.OUT_OF_PLAY, entered=False, inside=True)
    assert not line.captured(None, entered=True, inside=True) and not line.keeps_captured


def test_the_held_rule_decides_nothing_and_counts_a_ball_inside() -> None:
    held = HeldRule()
    assert held.decision(GOAL_MOUTH, RADIUS, _past_the_plane(1.0), entered=True, from_front=True) is None
    assert held.captured(None, entered=True, inside=True)
    assert not held.captured(None, entered=True, inside=False) and not held.captured(None, False, True)
    assert held.keeps_captured


def test_a_flight_is_cut_at_the_rules_first_decision() -> None:
    asked: list[float] = []

    def decided_at(t: float) -> bool:
        asked.append(t)
        return t >= 0.3

    assert HeldRule().decision_instant(1.0, decided_at, 1e-4) == 1.0 and not asked
    instant = LineRule().decision_instant(1.0, decided_at, 1e-4)
    assert 0.3 <= instant <= 0.3 + 1e-4
    assert LineRule().decision_instant(0.2, decided_at, 1e-4) == 0.2


def test_the_fast_path_tuning_keeps_its_margins_in_order() -> None:
    """A ball is simulated before it can touch anything the awake net may reach, and two instants
    the same to the clock are closer than the capture rule's own tolerance."""
    assert TUNING.clearance < TUNING.awake_margin and TUNING.time_epsilon < TUNING.line_time_tolerance


def test_a_film_records_each_instant_once() -> None:
    class Sim:  # what a film reads of a simulator
        dt = 0.002
        state = type("State", (), {"time": 0.0})()

    sim, recorded = Sim(), []
    film = Film(FrameClock(0.1), lambda s: recorded.append(s.state.time))
    for time in (0.0, 0.0005, 0.05, 0.0995, 0.1, 0.2011):
        sim.state.time = time
        film(sim)
    assert recorded == [0.0, 0.0995]


def test_a_filmed_request_stops_at_each_instant_and_ends_as_the_whole() -> None:
    """The driver cuts an Integrate request at the substeps nearest a film's instants: the
    state ends bitwise where the uncut request leaves it, and every instant is filmed once."""
    from netgym.physics.plans import Integrate
    from netgym.physics.simulator import Simulator

    filmed, plain = Simulator("basket"), Simulator("basket")
    for sim in (filmed, plain):
        sim.launch_ball([0.2, 0.1, 3.6], [1.0, 0.0, 0.0])
    times: list[float] = []
    before = filmed.substeps, plain.substeps

    def whole():
        yield Integrate(100, filmed.integrator, filmed.dt)

    filmed.run(whole(), Film(FrameClock(1.0 / 30.0), lambda s: times.append(s.state.time)))
    plain.step(100)
    assert np.array_equal(filmed.state.x, plain.state.x) and np.array_equal(filmed.state.v, plain.state.v)
    assert filmed.state.time == plain.state.time
    assert filmed.substeps - before[0] == plain.substeps - before[1] == 100
    k = np.round(np.array(times) * 30.0)
    assert np.array_equal(k, np.arange(1, 1 + math.floor(100 * filmed.dt * 30.0 + 1e-9)))
    assert np.abs(np.array(times) - k / 30.0).max() <= 0.5 * filmed.dt + 1e-9
