"""netgym: a mass-spring goal-net simulator and the Gymnasium environment NetCatch-v0.

Importing netgym registers ``NetCatch-v0`` (and its vector entry point) with Gymnasium;
``gym.make("netgym:NetCatch-v0")`` imports it on demand.
"""

from gymnasium.envs.registration import register, registry

__version__ = "0.1.0"

if "NetCatch-v0" not in registry:
    register(
        id="NetCatch-v0",
        entry_point="netgym.envs.net_catch:NetCatchEnv",
        vector_entry_point="netgym.envs.vector:NetCatchVectorEnv",
    )
