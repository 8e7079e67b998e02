"""Gymnasium environments of netgym."""

from netgym.envs.net_catch import NetCatchEnv, ObservationIndex

__all__ = ["NetCatchEnv", "ObservationIndex"]
