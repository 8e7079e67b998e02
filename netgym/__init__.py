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
``NetCatchWindy-v0``          the basket in air with a hidden wind        4.5
                              (0-3 m/s, drawn per episode), 5 throws,
                              feedback of each throw in the observation
``NetCatchNoisy-v0``          the basket, launch noise (sd 0.3 m/s,       2.7
                              1.5 degrees elevation and azimuth)
``NetCatchRandomized-v0``     the basket with ball mass, ball/net          2.9
                              restitution and friction, structural
                              stiffness and damping drawn per episode
``NetCatchPixels-v0``         NetCatch-v0 seen as 84 x 84 RGB images from  2.9
                              the thrower's release point (ThrowerView)
============================  ==========================================  ================

The thresholds are 97% of the balls of an episode caught on the sparse reward for the first
three; 90% for the windy variant (an informed oracle that knows the wind catches 100%, the
ballistic oracle that does not 54%, see docs/AGENTS.md) and for the noisy one (about what the
ballistic oracle catches through the noise: 91%).
"""

from gymnasium.envs.registration import register, registry

__version__ = "0.1.0"

ENVIRONMENTS = {
    "NetCatch-v0": ({}, 2.9),
    "NetCatchGoal-v0": ({"scene": "goal"}, 2.9),
    "NetCatchLongEpisode-v0": ({"balls_per_episode": 10}, 9.7),
    "NetCatchWindy-v0": ({"balls_per_episode": 5, "overrides": {"air.density": 1.2}, "wind": (0.0, 3.0),
                          "feedback": True}, 4.5),
    "NetCatchNoisy-v0": ({"launch_noise": (0.3, 1.5, 1.5)}, 2.7),
    "NetCatchRandomized-v0": ({"randomize": {"ball.mass": (0.5, 2.0), "contact.ball_net.restitution": (0.2, 0.7),
                                             "contact.ball_net.friction": (0.1, 0.6),
                                             "springs.structural.ks": (1000.0, 3000.0),
                                             "springs.structural.kd": (20.0, 80.0)}}, 2.9),
}

for _id, (_kwargs, _threshold) in ENVIRONMENTS.items():
    if _id not in registry:
        register(
            id=_id,
            entry_point="netgym.envs.net_catch:NetCatchEnv",
            kwargs=_kwargs,
            reward_threshold=_threshold,
        )
if "NetCatchPixels-v0" not in registry:
    register(id="NetCatchPixels-v0", entry_point="netgym.wrappers:thrower_view_env", kwargs={"size": 84},
             reward_threshold=2.9)
