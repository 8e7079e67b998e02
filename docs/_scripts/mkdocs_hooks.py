"""MkDocs hooks of the docs site: the env cards (``docs/environments/``) must be those
``env_cards.py`` makes from the code, or the build fails; each card is listed in the navigation;
the replay page the docs embed is made from the code at each build."""

from __future__ import annotations

import importlib.util
import subprocess
import sys
from pathlib import Path

from mkdocs.exceptions import PluginError

ROOT = Path(__file__).resolve().parents[2]


def _env_cards():
    """The module ``env_cards.py`` beside this file (MkDocs loads hooks by path, not as a package)."""
    spec = importlib.util.spec_from_file_location("env_cards", Path(__file__).with_name("env_cards.py"))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def on_config(config):
    """List every registered id's card under the environments' index."""
    import netgym

    for k, item in enumerate(config["nav"]):
        if isinstance(item, dict) and "Environments" in item:
            config["nav"][k] = {"Environments": ["environments/index.md",
                                                 *({env_id: f"environments/{env_id}.md"}
                                                   for env_id in netgym.ENVIRONMENTS)]}
    return config


def on_pre_build(config) -> None:
    """Refuse to build with a missing or out-of-date env card."""
    stale = _env_cards().stale_pages()
    if stale:
        raise PluginError(f"env cards out of date: {', '.join(stale)}; run python docs/_scripts/env_cards.py")


def on_post_build(config) -> None:
    """Write the embedded replay (``episode.html`` at the site's root): the oracle's episode of
    ``scripts/render_throw.py``'s defaults."""
    output = Path(config["site_dir"]) / "episode.html"
    result = subprocess.run([sys.executable, str(ROOT / "scripts" / "render_throw.py"), "--output", str(output)],
                            cwd=ROOT, capture_output=True, text=True)
    if result.returncode != 0:
        raise PluginError(f"the replay could not be made:\n{result.stderr[-2000:]}")
