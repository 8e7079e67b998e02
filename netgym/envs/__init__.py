"""Gymnasium environments of netgym."""

from netgym.envs.net_catch import NetCatchEnv

__all__ = ["NetCatchEnv"]
