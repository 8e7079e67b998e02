"""netgym: a mass-spring goal-net simulator and the Gymnasium environment NetCatch-v0."""
__version__ = "0.1.0"
