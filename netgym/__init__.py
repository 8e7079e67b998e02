"""netgym: a mass-spring goal-net simulator and the Gymnasium environment NetCatch-v0.

Importing netgym registers the environments of :data:`ENVIRONMENTS` with Gymnasium;
``gym.make("netgym:NetCatch-v0")`` imports it on demand. For many environments at once, use
Gymnasium's ``gym.make_vec(..., vectorization_mode="sync")`` (or ``"async"``) or SB3's
``SubprocVecEnv``. Each id has a page of its own in the docs (``docs/environments/``,
generated from :class:`~netgym.envs.NetCatchEnv`'s docstring and the id's entry here); the
capture rates of the reference agents on each are in ``docs/AGENTS.md``.
"""

from typing import Any, NamedTuple

from gymnasium.envs.registration import register, registry

__version__ = "0.1.0"


class Registration(NamedTuple):
    """How one environment id is registered, and what it is for."""

    kwargs: dict[str, Any]       # arguments of the entry point
    reward_threshold: float      # the return that counts as solved
    tests: str                   # what the id tests, one line
    observation: str             # what its observation is or adds to NetCatch-v0's, one line
    entry_point: str = "netgym.envs.net_catch:NetCatchEnv"


ENVIRONMENTS: dict[str, Registration] = {
    "NetCatch-v0": Registration(
        {}, 2.9, "aim: lob balls over the rim of the default basket; caught balls stay and load the net",
        "thrower distance, height and bearing; caught and throws left; height of the pile"),
    "NetCatchGoal-v0": Registration(
        {"scene": "goal"}, 2.9, "aim at a front-open handball goal (the `line` rule: a goal counts once over the line)",
        "as NetCatch-v0"),
    "NetCatchLongEpisode-v0": Registration(
        {"balls_per_episode": 10}, 9.7, "10 throws into one basket: a filling, deforming net and a growing pile",
        "as NetCatch-v0"),
    "NetCatchWindy-v0": Registration(
        {"balls_per_episode": 5, "overrides": {"air.density": 1.2}, "wind": (0.0, 3.0), "feedback": True}, 4.5,
        "learn within an episode: air drag and a hidden wind of 0-3 m/s drawn per episode, 5 throws",
        "adds feedback of the previous throw (caught, where it crossed the opening's plane)"),
    "NetCatchNoisy-v0": Registration(
        {"launch_noise": (0.3, 1.5, 1.5)}, 2.7,
        "robust aim: Gaussian launch noise (sd 0.3 m/s, 1.5 degrees of elevation and azimuth)", "as NetCatch-v0"),
    "NetCatchRandomized-v0": Registration(
        {"randomize": {"ball.mass": (0.5, 2.0), "contact.ball_net.restitution": (0.2, 0.7),
                       "contact.ball_net.friction": (0.1, 0.6), "springs.structural.ks": (1000.0, 3000.0),
                       "springs.structural.kd": (20.0, 80.0)}}, 2.9,
        "domain randomisation: ball mass, ball/net restitution and friction, net stiffness and damping per episode",
        "as NetCatch-v0 (the draws are in `info`, never observed)"),
    "NetCatchRandomized-v1": Registration(
        {"balls_per_episode": 5, "overrides": {"air.density": 1.2}, "feedback": True,
         "randomize": {"ball.mass": (0.5, 2.0), "air.drag_coefficient": (0.0, 1.0),
                       "contact.ball_net.restitution": (0.2, 0.7), "contact.ball_net.friction": (0.1, 0.6),
                       "springs.structural.ks": (1000.0, 3000.0), "springs.structural.kd": (20.0, 80.0)}}, 4.5,
        "identify the flight within an episode: the ball's mass and drag coefficient (and the net's physics) "
        "drawn per episode and hidden, 5 throws",
        "adds feedback of the previous throw (caught, where it crossed the opening's plane)"),
    "NetCatchPixels-v0": Registration(
        {"size": 84}, 2.9, "NetCatch-v0 from pixels", "an 84 x 84 RGB image from the thrower's release point",
        entry_point="netgym.wrappers:thrower_view_env"),
}
"""Every registered id. The thresholds are 97% of an episode's balls caught on the sparse reward,
90% for the windy and the noisy variants (what an oracle that cannot know the wind, or undo the
noise, comes near) and for NetCatchRandomized-v1."""


def balls_per_episode(env_id: str) -> int:
    """Throws in one episode of ``env_id`` (NetCatchEnv's default, 3, unless registered otherwise)."""
    return int(ENVIRONMENTS[env_id].kwargs.get("balls_per_episode", 3))


for _id, _entry in ENVIRONMENTS.items():
    if _id not in registry:
        register(id=_id, entry_point=_entry.entry_point, kwargs=_entry.kwargs, reward_threshold=_entry.reward_threshold)
