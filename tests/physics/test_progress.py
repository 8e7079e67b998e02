"""Every plan ends: the fast throws that once never returned, the progress guarantee of a throw,
of the pause and of the settling of a new net, and the watchdog of an environment step."""

from __future__ import annotations

import gymnasium as gym
import numpy as np
import pytest

import netgym  # noqa: F401  (registers the environments)
from netgym.errors import NoProgressError, StepTimeoutError
from netgym.physics.progress_guard import MAX_STILL_PIECES, ProgressGuard
from netgym.physics.simulator import Simulator
from netgym.physics.throw import decisions, throw
from netgym.physics.watchdog import Watchdog

# launches into the basket at 78-96 m/s that spun for ever on the fast path (a net asleep, woken,
# put to sleep again while the ball, too fast to fly a whole step clear, never moved)
SPUN = [
    ((-4.669847, 1.786765, 2.407016), (93.303545, -35.699559, 0.0)),
    ((2.4427, -5.3387, 0.853), (-44.1413, 83.998, 10.8646)),
    ((4.6183, -0.7879, 1.536), (-74.8125, -2.7651, 24.1422)),
]


@pytest.mark.parametrize(("position", "velocity"), SPUN)
def test_fast_throws_that_once_spun_return_with_the_full_simulations_outcome(basket: Simulator, position,
                                                                              velocity) -> None:
    fast = throw(basket, position, velocity)
    basket.reset()
    full = throw(basket, position, velocity, fast=False)
    assert fast.time <= basket.config.simulation.time_limit
    assert (fast.captured, fast.entered) == (full.captured, full.entered)


def test_a_throw_that_stops_moving_time_on_raises_a_named_error(basket: Simulator,
                                                                monkeypatch: pytest.MonkeyPatch) -> None:
    """The spin above, brought back by hand: a scene put to sleep after every piece though the
    ball cannot fly; the guard stops it, and its message names the launch and the state."""
    monkeypatch.setattr(decisions, "flight_time", lambda throw: 0.0)
    monkeypatch.setattr(decisions, "can_roll_alone", lambda throw: True)
    monkeypatch.setattr("netgym.physics.throw.recipe.can_roll_alone", lambda throw: False)
    position, velocity = SPUN[0]
    with pytest.raises(NoProgressError) as caught:
        throw(basket, position, velocity)
    message = str(caught.value)
    assert "[-4.669847, 1.786765, 2.407016] m at [93.303545, -35.699559, 0.0] m/s" in message
    assert "basket scene" in message and "the ball at" in message and "pieces in a row" in message


def test_the_guard_allows_still_pieces_up_to_its_bound_and_counts_all_pieces() -> None:
    guard = ProgressGuard(0.0, 1.0, 0.5, lambda: "a plan")
    assert guard.most == (MAX_STILL_PIECES + 1) * 6
    for _ in range(MAX_STILL_PIECES):
        guard.piece(0.0)
    guard.piece(0.5)  # time moved on: the count of still pieces starts again
    for _ in range(MAX_STILL_PIECES):
        guard.piece(0.5)
    with pytest.raises(NoProgressError, match="a plan: 5 pieces in a row"):
        guard.piece(0.5)
    moving = ProgressGuard(0.0, 1.0, 0.5, lambda: "a plan")
    with pytest.raises(NoProgressError, match="more than the 30 its span"):
        for k in range(31):
            moving.piece(1e-3 * (k + 1))


def test_a_relaxation_that_takes_no_step_raises_a_named_error(basket: Simulator,
                                                              monkeypatch: pytest.MonkeyPatch) -> None:
    """The pause (and the settling of a new net, the same relaxation) with requests that take no
    step: the guard stops it instead of asking again for ever."""
    def nothing(sim, model, settings, n_steps, workspace, rest):
        rest.record.memory[0]["steps"], rest.record.memory[0]["at_rest"] = 0, False

    monkeypatch.setattr("netgym.physics.plans.relax", nothing)
    basket.launch_ball([0.0, 0.0, 1.0], [0.0, 0.0, 0.0])
    basket.wake()
    with pytest.raises(NoProgressError, match="the relaxation of the basket scene with 1 balls"):
        basket.relax()


def test_the_watchdog_stops_a_run_past_its_bounds_and_leaves_compiling_out() -> None:
    now, compiled = [0.0], [0.0]
    dog = Watchdog(lambda: "the throw of the test", max_requests=3, max_seconds=10.0, clock=lambda: now[0],
                   compiling=lambda: compiled[0])
    sim = Simulator("basket")
    now[0], compiled[0] = 50.0, 45.0  # 50 s gone by, 45 of them compiling
    dog(sim)
    assert dog.seconds() == pytest.approx(5.0)
    now[0] = 56.0
    with pytest.raises(StepTimeoutError, match="the throw of the test was stopped by its watchdog after 2 requests"):
        dog(sim)
    counting = Watchdog(lambda: "a run", max_requests=2, clock=lambda: 0.0, compiling=lambda: 0.0)
    counting(sim)
    counting(sim)
    with pytest.raises(StepTimeoutError, match="after 3 requests"):
        counting(sim)


def test_an_env_step_past_its_watchdog_says_what_was_thrown(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr("netgym.physics.watchdog.MAX_REQUESTS", 0)
    env = gym.make("NetCatch-v0")
    env.reset(seed=0)
    with pytest.raises(StepTimeoutError, match=r"NetCatch-v0 step 1 \(the throw from \[.*\] m at \[.*\] m/s"):
        env.step(np.array([0.0, 0.5, 0.0]))  # into the net on seed 0: the throw integrates
