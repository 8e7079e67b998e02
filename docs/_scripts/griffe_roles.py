"""A griffe extension for the API reference: Sphinx roles in docstrings (``:class:`~a.B```)
become code spans of the name (`` `B` ``), the way the env cards show them, since mkdocstrings
renders docstrings as Markdown."""

from __future__ import annotations

import re
from typing import Any

import griffe

ROLE = re.compile(r":(?:class|mod|func|meth|data|attr|exc):`~?([\w.]+)`")


def plain_roles(text: str) -> str:
    """``text`` with every Sphinx role a code span of the name's last part."""
    return ROLE.sub(lambda m: f"`{m.group(1).rsplit('.', 1)[-1]}`", text)


class SphinxRoles(griffe.Extension):
    """Rewrites every docstring's Sphinx roles as it is loaded."""

    def on_instance(self, *, obj: griffe.Object, **kwargs: Any) -> None:
        """Rewrite the roles of ``obj``'s docstring."""
        if obj.docstring is not None:
            obj.docstring.value = plain_roles(obj.docstring.value)
