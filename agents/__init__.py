"""Agents for NetCatch-v0: a ballistic oracle, a random baseline and trained policies."""
