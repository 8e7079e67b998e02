"""Property tests of the environment's life cycle: random sequences of reset, step and pickle
with valid and invalid inputs.

Invariants: only the documented errors are raised; a failed call changes no state; an episode
never pays more than ``balls_per_episode``; the same sequence with the same seed gives the same
results."""

from __future__ import annotations

import pickle

import numpy as np
from hypothesis import given
from hypothesis import strategies as st

from netgym.envs import NetCatchEnv
from netgym.errors import EpisodeEndedError, SimulationDivergedError

BALLS = 2
DOCUMENTED = (ValueError, EpisodeEndedError, SimulationDivergedError)

valid_actions = st.lists(st.floats(-1.5, 1.5), min_size=3, max_size=3).map(lambda a: np.array(a, dtype=np.float32))
invalid_actions = st.sampled_from([np.zeros(2), np.full(3, np.nan), np.array([True, False, True]), "abc",
                                   np.zeros((1, 3)), [1.0, np.inf, 0.0]])
operations = st.lists(st.one_of(
    st.tuples(st.just("reset"), st.integers(0, 2**16)),
    st.tuples(st.just("step"), st.one_of(valid_actions, valid_actions, invalid_actions)),
    st.tuples(st.just("pickle"), st.none()),
    st.tuples(st.just("bad_reset"), st.sampled_from([{"nope": 1}, "options"])),
), max_size=8)


def _state(env: NetCatchEnv) -> tuple:
    s = env.sim.state
    rng = env.np_random.bit_generator.state if env.thrower is not None else None
    return (s.x.tobytes(), s.v.tobytes(), s.entered.tobytes(), s.time, env.sim.awake, env.sim.substeps,
            env.thrower, str(rng))


def _replay(seed: int, ops: list) -> list:
    env = NetCatchEnv(balls_per_episode=BALLS)
    env.reset(seed=seed)
    transcript, paid = [], 0.0
    for name, arg in ops:
        before = _state(env)
        try:
            if name == "reset":
                obs, _ = env.reset(seed=arg)
                paid = 0.0
                transcript.append(("reset", obs.tobytes()))
            elif name == "bad_reset":
                env.reset(options=arg)
            elif name == "pickle":
                env = pickle.loads(pickle.dumps(env))
                transcript.append(("pickle", _state(env) == before))
            else:
                obs, reward, terminated, truncated, info = env.step(arg)
                paid += reward
                assert paid <= BALLS
                transcript.append(("step", obs.tobytes(), reward, terminated, info["reason"], info["substeps"]))
        except DOCUMENTED as error:
            assert _state(env) == before, f"{name} failed with {error!r} and changed the state"
            transcript.append(("error", type(error).__name__))
    return transcript


@given(seed=st.integers(0, 2**16), ops=operations)
def test_random_life_cycles_keep_the_invariants_and_replay_identically(seed: int, ops: list) -> None:
    first = _replay(seed, ops)
    assert first == _replay(seed, ops)
    assert all(entry[1] for entry in first if entry[0] == "pickle")

