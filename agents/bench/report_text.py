"""The benchmark report's fixed prose (docs/BENCHMARKS.md), read from its template
``docs/_templates/report.md``: for each section what is measured and by which command, and what the
table means. Sentences whose figures come from the run are made in :mod:`agents.bench.report`; the
figures in the template come from measurements outside the report's run, each with its command or
test."""

from __future__ import annotations

import re
from pathlib import Path

from netgym.bench.results import RESULTS

TEMPLATE = RESULTS.parent / "_templates" / "report.md"
"""The prose, one section per name (``<!-- NAME -->`` or, for a list of items, ``<!-- NAME (list) -->``)."""


def sections(path: Path = TEMPLATE) -> dict[str, str | tuple[str, ...]]:
    """Each section of the template: a list's items as a tuple (one a line), else its one paragraph."""
    found: dict[str, str | tuple[str, ...]] = {}
    for name, listed, body in re.findall(r"<!-- ([A-Z_]+)( \(list\))? -->\n(.*?)(?=\n<!-- |\Z)", path.read_text(),
                                         re.S):
        lines = tuple(line for line in body.split("\n") if line)
        found[name] = lines if listed else " ".join(lines)
    return found


_SECTIONS = sections()
INTRO_TEXT = _SECTIONS["INTRO_TEXT"]
LOAD_TEXT = _SECTIONS["LOAD_TEXT"]
OUTCOMES_NOTES = _SECTIONS["OUTCOMES_NOTES"]
SIM_THROUGHPUT_TEXT = _SECTIONS["SIM_THROUGHPUT_TEXT"]
ENV_THROUGHPUT_TEXT = _SECTIONS["ENV_THROUGHPUT_TEXT"]
HELD_GOAL_TEXT = _SECTIONS["HELD_GOAL_TEXT"]
PEERS_TEXT = _SECTIONS["PEERS_TEXT"]
DESIGN_TEXT = _SECTIONS["DESIGN_TEXT"]
DESIGN_ITEMS = _SECTIONS["DESIGN_ITEMS"]
REJECTED_TEXT = _SECTIONS["REJECTED_TEXT"]
REJECTED_ITEMS = _SECTIONS["REJECTED_ITEMS"]
EPISODES_TEXT = _SECTIONS["EPISODES_TEXT"]
EPISODES_NOTES = _SECTIONS["EPISODES_NOTES"]
AGREEMENT_TEXT = _SECTIONS["AGREEMENT_TEXT"]
AGREEMENT_NOTES = _SECTIONS["AGREEMENT_NOTES"]
PAUSE_ACCURACY_TEXT = _SECTIONS["PAUSE_ACCURACY_TEXT"]
PAUSE_ACCURACY_NOTES = _SECTIONS["PAUSE_ACCURACY_NOTES"]
CREEP_TEXT = _SECTIONS["CREEP_TEXT"]
CREEP_NOTES = _SECTIONS["CREEP_NOTES"]
ROOFLINE_TEXT = _SECTIONS["ROOFLINE_TEXT"]
VARIANT_SPEED_TEXT = _SECTIONS["VARIANT_SPEED_TEXT"]
VARIANT_SPEED_NOTES = _SECTIONS["VARIANT_SPEED_NOTES"]
CONTACT_CONVERGENCE_TEXT = _SECTIONS["CONTACT_CONVERGENCE_TEXT"]
CONTACT_CONVERGENCE_NOTES = _SECTIONS["CONTACT_CONVERGENCE_NOTES"]
COMPLIANT_CONVERGENCE_TEXT = _SECTIONS["COMPLIANT_CONVERGENCE_TEXT"]
COMPLIANT_CONVERGENCE_NOTES = _SECTIONS["COMPLIANT_CONVERGENCE_NOTES"]
