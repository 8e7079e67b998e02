"""Gymnasium environments of netgym."""

from netgym.envs.net_catch import NetCatchEnv
from netgym.envs.observation import ObservationIndex

__all__ = ["NetCatchEnv", "ObservationIndex"]
