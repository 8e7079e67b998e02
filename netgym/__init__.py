"""netgym: a mass-spring goal-net simulator and the Gymnasium environment NetCatch-v0.

Importing netgym registers the environments below with Gymnasium;
``gym.make("netgym:NetCatch-v0")`` imports it on demand. For many environments at once, use
Gymnasium's ``gym.make_vec(..., vectorization_mode="sync")`` (or ``"async"``) or SB3's
``SubprocVecEnv``.

============================  ==========================================  ================
id                            what                                        reward_threshold
============================  ==========================================  ================
``NetCatch-v0``               the basket, 3 throws per episode            2.9
``NetCatchGoal-v0``           the handball goal (``line`` capture rule)   2.9
``NetCatchLongEpisode-v0``    the basket, 10 throws into one net          9.7
============================  ==========================================  ================

The thresholds are 97% of the balls of an episode caught on the sparse reward.
"""

from gymnasium.envs.registration import register, registry

__version__ = "0.1.0"

ENVIRONMENTS = {
    "NetCatch-v0": ({}, 2.9),
    "NetCatchGoal-v0": ({"scene": "goal"}, 2.9),
    "NetCatchLongEpisode-v0": ({"balls_per_episode": 10}, 9.7),
}

for _id, (_kwargs, _threshold) in ENVIRONMENTS.items():
    if _id not in registry:
        register(
            id=_id,
            entry_point="netgym.envs.net_catch:NetCatchEnv",
            kwargs=_kwargs,
            reward_threshold=_threshold,
        )
