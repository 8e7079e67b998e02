"""The parts of an env card read from the env itself: its spaces, each entry with its range or
bounds, and what its registration varies (launch noise, wind, scene draws, pixels)."""

from __future__ import annotations

import inspect

import gymnasium as gym
import numpy as np

from griffe_roles import plain_roles
from netgym.envs import ObservationIndex
from netgym.launch import LAUNCH_ENTRIES
from netgym.wrappers import ThrowerView

VECTOR_CARD = "NetCatch-v0.md#observation-space"
"""Where the entries of the vector observation that pixels replace are listed."""


def space_text(space: gym.Space) -> str:
    """``space`` as Gymnasium prints it, or ``Box(low, high, shape, dtype)`` where its bounds
    differ per entry (the card's table of entries lists them)."""
    if isinstance(space, gym.spaces.Box) and (np.ptp(space.low) or np.ptp(space.high)):
        return f"Box(low, high, {space.shape}, {space.dtype})"
    return str(space)


def _number(value: float) -> str:
    return f"{float(value):g}"


def _table(header: tuple[str, ...], rows: list[tuple[str, ...]], right: tuple[int, ...] = ()) -> str:
    """A markdown table; the columns numbered in ``right`` aligned right."""
    rule = ["---:" if k in right else "---" for k in range(len(header))]
    return "\n".join("| " + " | ".join(cells) + " |" for cells in [header, rule, *rows])


def _thrower_view(env: gym.Env) -> ThrowerView | None:
    while isinstance(env, gym.Wrapper):
        if isinstance(env, ThrowerView):
            return env
        env = env.env
    return None


def action_section(env: gym.Env, prose: str) -> str:
    """The action space, each entry's range on ``env``'s scene, and its launch noise if any."""
    base = env.unwrapped
    rows = [(str(k), what, f"{_number(getattr(base.scene.throw, field)[0])} to "
                           f"{_number(getattr(base.scene.throw, field)[1])}", unit)
            for k, (field, what, unit) in enumerate(LAUNCH_ENTRIES)]
    parts = [f"`{space_text(env.action_space)}`. {prose}",
             _table(("index", "sets", "range on this id's scene", "unit"), rows, right=(0, 2))]
    if base.launch_noise is not None:
        noise = base.launch_noise
        parts.append(f"**Launch noise.** Each release is drawn from a Gaussian around the launch the action "
                     f"asks for, with standard deviations of {_number(noise.speed)} m/s of speed, "
                     f"{_number(noise.elevation)} degrees of elevation and {_number(noise.azimuth)} degrees of "
                     "azimuth; `info[\"aimed_velocity\"]` is the launch asked for, `info[\"launch_velocity\"]` "
                     "the one thrown.")
    return "\n\n".join(parts)


def observation_section(env: gym.Env, prose: str) -> str:
    """The observation space: the image of a pixel env, or each vector entry with its bounds."""
    space, view = env.observation_space, _thrower_view(env)
    if view is not None:
        description = plain_roles(inspect.getdoc(ThrowerView)).split("\n:param", 1)[0].strip()
        return (f"`{space_text(space)}`. {description} The image is {space.shape[1]} x {space.shape[0]} pixels "
                f"with a vertical field of view of {_number(view.fov)} degrees. The entries of the vector "
                f"observation it replaces: [NetCatch-v0]({VECTOR_CARD}).")
    structure = env.unwrapped.observation_structure
    rows = [(str(k), f"`{name}`", ObservationIndex(k).meaning, ObservationIndex(k).unit,
             _number(space.low[k]), _number(space.high[k])) for name, k in structure.items()]
    return "\n\n".join([f"`{space_text(space)}`, {len(structure)} entries. {prose}",
                        _table(("index", "name", "meaning", "unit", "low", "high"), rows, right=(0, 4, 5))])


def starting_state_section(env: gym.Env, prose: str) -> str:
    """How an episode starts, with what ``env`` draws per episode: its wind and scene fields."""
    base, parts = env.unwrapped, [prose]
    if base.wind_range is not None:
        parts.append(f"**Wind.** Drawn per episode: speed uniform in [{_number(base.wind_range.low)}, "
                     f"{_number(base.wind_range.high)}] m/s, direction uniform around the compass; air of density "
                     f"{_number(base.scene.air.density)} kg/m^3 drags the balls.")
    if base.randomize is not None:
        rows = [(f"`{field}`", _number(low), _number(high)) for field, low, high in base.randomize.ranges]
        parts += ["**Scene draws.** Each of these scene fields is drawn uniformly per episode; never observed, "
                  "`info[\"scene_draws\"]` reports them:", _table(("scene field", "low", "high"), rows, right=(1, 2))]
    return "\n\n".join(parts)
