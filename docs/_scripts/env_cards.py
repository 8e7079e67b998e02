"""Env cards: one docs page per registered NetCatch id, generated from the env class's docstring
and the id's registration (``netgym.ENVIRONMENTS`` and Gymnasium's spec), as Gymnasium generates
its environment pages (``docs/_scripts/gen_mds.py`` there), and committed under
``docs/environments/`` so that they read on the repository's pages too. The docs build
(``mkdocs_hooks.py``) and the tests fail when a card is missing or differs from what this script
makes, so a new id gets its page and no card drifts from the code it describes.

Usage::

    python docs/_scripts/env_cards.py      # write every card
"""

from __future__ import annotations

import inspect
import re
import sys
import warnings
from pathlib import Path

import gymnasium as gym
from gymnasium.envs.registration import load_env_creator

DOCS = Path(__file__).resolve().parents[1]
sys.path[:0] = [str(DOCS.parent), str(DOCS / "_scripts")]

import netgym  # noqa: E402
from netgym.envs import NetCatchEnv  # noqa: E402
from card_sections import action_section, observation_section, space_text, starting_state_section  # noqa: E402
from griffe_roles import plain_roles  # noqa: E402
from quotes import BASELINES, environments  # noqa: E402
from agents.baselines.analysis import load_cells  # noqa: E402
from agents.baselines.tables import best_line  # noqa: E402

SECTIONS = ("Description", "Action Space", "Observation Space", "Rewards", "Starting State", "Episode End",
            "Arguments", "Version History")
"""Gymnasium's sections of an environment page, in its order."""

POSTERS = DOCS / "figures" / "envs"
"""Where each id's poster lies (``ID.png``), written by ``scripts/render_posters.py``."""

def docstring_sections(cls: type) -> dict[str, str]:
    """The ``## Heading`` sections of ``cls``'s docstring by title-cased heading; the text before
    the first heading is ``"Description"``."""
    sections: dict[str, str] = {}
    heading, lines = "Description", []
    for line in inspect.getdoc(cls).splitlines():
        if line.startswith("## "):
            sections[heading] = "\n".join(lines).strip()
            heading, lines = line[3:].strip().title(), []
        else:
            lines.append(line)
    sections[heading] = "\n".join(lines).strip()
    return {name: plain_roles(text) for name, text in sections.items()}


LONG_VALUE = 40
"""Registered values whose text is longer than this are named, not written out, in a card's
header table (its Arguments section writes them out)."""


def _kwargs_text(kwargs: dict, short: bool = False) -> str:
    """The registration's arguments as code; ``short``: long values left out."""
    if not kwargs:
        return "none: every argument at its default below"
    return ", ".join(f"`{name}` (under Arguments)" if short and len(repr(value)) > LONG_VALUE else f"`{name}={value!r}`"
                     for name, value in kwargs.items())


def entry_point_arguments(entry_point: str) -> str:
    """The arguments an id's entry point takes besides NetCatchEnv's (a wrapper's), as a table
    of their defaults and ``:param`` texts; empty when the entry point is NetCatchEnv."""
    function = load_env_creator(entry_point)
    if function is NetCatchEnv:
        return ""
    texts = dict(re.findall(r":param (\w+): (.+?)(?=\n:param|\Z)", inspect.getdoc(function), re.S))
    named = [p for p in inspect.signature(function).parameters.values() if p.kind is not p.VAR_KEYWORD]
    rows = [f"| ``{p.name}`` | {p.default!r} | {' '.join(texts.get(p.name, '').split())} |" for p in named]
    return plain_roles(f"Its entry point, `{entry_point}`, also takes:\n\n"
                       "| argument | default | meaning |\n|---|---|---|\n" + "\n".join(rows))


def env_card(env_id: str) -> str:
    """The markdown page of ``env_id``: a header table, the poster and Gymnasium's eight sections,
    the spaces and what the id varies read from the env it makes."""
    entry, spec = netgym.ENVIRONMENTS[env_id], gym.spec(env_id)
    with warnings.catch_warnings():  # an id kept beside its newer version says so on make; its card says it too
        warnings.simplefilter("ignore", DeprecationWarning)
        env = gym.make(env_id)
    docs = docstring_sections(NetCatchEnv)
    missing = [name for name in SECTIONS if name not in docs and name != "Description"]
    if missing:
        raise ValueError(f"NetCatchEnv's docstring has no section {missing}: every env card needs them")
    poster = POSTERS / f"{env_id}.png"
    if not poster.is_file():
        raise FileNotFoundError(f"{env_id} has no poster {poster}: run python scripts/render_posters.py")
    balls = netgym.balls_per_episode(env_id)
    lines = [
        f"# {env_id}", "",
        f"![{env_id}](../figures/envs/{env_id}.png)", "",
        "| property | value |", "|---|---|",
        f"| Make | `gymnasium.make(\"{env_id}\")` |",
        f"| Tests | {entry.tests} |",
        f"| Action Space | `{space_text(env.action_space)}` |",
        f"| Observation Space | `{space_text(env.observation_space)}`: {entry.observation} |",
        f"| Balls per episode | {balls} |",
        f"| Reward threshold | {spec.reward_threshold} |",
        f"| Best baseline | {best_line(load_cells(BASELINES), env_id)} "
        "([Baselines](../baselines.md)) |",
        f"| Registered with | {_kwargs_text(entry.kwargs, short=True)} |",
        f"| Entry point | `{spec.entry_point}` |", "",
        "## Description", "", f"**{env_id}**: {entry.tests}.", "", docs["Description"], "",
        "## Action Space", "", action_section(env, docs["Action Space"]), "",
        "## Observation Space", "", observation_section(env, docs["Observation Space"]), "",
        "## Rewards", "", docs["Rewards"], "",
        "## Starting State", "", starting_state_section(env, docs["Starting State"]), "",
        "## Episode End", "", docs["Episode End"], f"On this id, `balls_per_episode` = {balls}.", "",
        "## Info", "", docs.get("Info", ""), "",
        "## Arguments", "", f"This id is registered with {_kwargs_text(entry.kwargs)}. Any argument below can be "
        f"passed to `gymnasium.make(\"{env_id}\", ...)`.", "", docs["Arguments"], "",
        *([wrapper, ""] if (wrapper := entry_point_arguments(spec.entry_point)) else []),
        "## Version History", "", docs["Version History"], "",
    ]
    env.close()
    return "\n".join(lines).rstrip() + "\n"


def index_page() -> str:
    """The environments' index: one line per id (the README's table, linked from here)."""
    return ("# Environments\n\nEvery id netgym registers; each has a card with Gymnasium's sections.\n\n"
            + environments(cards="") + "\n")


def env_pages() -> dict[str, str]:
    """Every generated page, by its path under ``docs/``."""
    pages = {"environments/index.md": index_page()}
    pages.update({f"environments/{env_id}.md": env_card(env_id) for env_id in netgym.ENVIRONMENTS})
    return pages


def stale_pages() -> list[str]:
    """The generated pages that are missing under ``docs/`` or differ from what this script makes."""
    return [path for path, text in env_pages().items()
            if not (DOCS / path).is_file() or (DOCS / path).read_text() != text]


def main() -> None:
    """Write every card and the index."""
    for path, text in env_pages().items():
        (DOCS / path).parent.mkdir(parents=True, exist_ok=True)
        (DOCS / path).write_text(text)
    print(f"wrote {len(netgym.ENVIRONMENTS)} env cards and their index to {DOCS / 'environments'}")


if __name__ == "__main__":
    main()
