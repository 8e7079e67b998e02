"""The README and the docs site: env cards per registered id, quoted figures that match their
result files, no figures in docstrings, a README within its limits, a site that builds clean."""

from __future__ import annotations

import ast
import functools
import os
import re
import shutil
import subprocess
import sys
import tomllib
from pathlib import Path

import gymnasium as gym
import pytest

import netgym
from agents.bench import report
from netgym.launch import LAUNCH_ENTRIES

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "docs" / "_scripts"))

import env_cards  # noqa: E402
import quotes  # noqa: E402

MEASURED = re.compile(r"\d[\d.,]*\s*(?:us|µs|ns|throws/s|steps/s|substeps/s)\b|\d[\d.,]*\s*ms (?:a|per|each)\b"
                      r"|(?:catch(?:es)?|caught|agree(?:s)? on) \d[\d.]*%")
"""A measured figure: a timing, a rate, a capture or agreement percentage."""


def test_every_registered_id_has_a_current_card_with_gymnasiums_sections() -> None:
    pages = env_cards.env_pages()
    registered = [env_id for env_id in gym.registry if env_id.startswith("NetCatch")]
    assert sorted(registered) == sorted(netgym.ENVIRONMENTS)
    for env_id in registered:
        card = pages[f"environments/{env_id}.md"]
        headings = re.findall(r"^## (.+)$", card, re.M)
        assert [h for h in headings if h in env_cards.SECTIONS] == list(env_cards.SECTIONS), env_id
        for section in env_cards.SECTIONS:  # no section is left empty
            body = card.split(f"## {section}\n", 1)[1].split("\n## ", 1)[0]
            assert body.strip(), f"{env_id}: empty {section}"
        assert f'gymnasium.make("{env_id}")' in card
        assert (env_cards.POSTERS / f"{env_id}.png").is_file()
    assert env_cards.stale_pages() == []


@functools.cache
def _card(env_id: str) -> str:
    return env_cards.env_card(env_id)


def _section(card: str, title: str) -> str:
    return card.split(f"## {title}\n", 1)[1].split("\n## ", 1)[0]


def _rows(text: str) -> list[list[str]]:
    """The body rows of the markdown tables in ``text``, as cells."""
    lines = [line for line in text.splitlines() if line.startswith("|")]
    rule = re.compile(r"\|(\s*:?-+:?\s*\|)+$")
    headers = {k - 1 for k, line in enumerate(lines) if rule.match(line)}
    return [[cell.strip() for cell in line.strip("|").split("|")] for k, line in enumerate(lines)
            if k not in headers and not rule.match(line)]


def _shapes(text: str) -> set[tuple[int, ...]]:
    """Every shape, ``(11,)`` or ``(84, 84, 3)``, named in ``text``."""
    return {tuple(int(n) for n in found.split(",") if n.strip())
            for found in re.findall(r"\((\d+(?:, \d+)*,?)\)", text)}


@pytest.mark.parametrize("env_id", list(netgym.ENVIRONMENTS))
def test_each_card_describes_its_own_env(env_id: str) -> None:
    card, env = _card(env_id), gym.make(env_id)
    base, observation_space = env.unwrapped, env.observation_space
    header = card.split("\n## ", 1)[0]
    assert not re.search(r"^\|\s*\|\s*\|$", header, re.M), "an empty header row"
    observation = _section(card, "Observation Space")
    header_row = next(line for line in header.splitlines() if line.startswith("| Observation Space |"))
    for text in (header_row, observation):
        assert _shapes(text) == {observation_space.shape} and str(observation_space.dtype) in text
    if base.observation_space is observation_space:  # a vector: every entry named, with its bounds
        rows = [row for row in _rows(observation) if row[0].isdigit()]
        assert [row[1].strip("`") for row in rows] == list(base.observation_structure)
        assert [float(row[-2]) for row in rows] == pytest.approx(observation_space.low.tolist())
        assert [float(row[-1]) for row in rows] == pytest.approx(observation_space.high.tolist())
    else:
        assert str(observation_space) in observation
    action = _section(card, "Action Space")
    assert str(env.action_space) in action and str(env.action_space) in header
    ranges = [tuple(float(x) for x in row[2].split(" to ")) for row in _rows(action) if row[0].isdigit()]
    assert ranges == [tuple(getattr(base.scene.throw, field)) for field, _, _ in LAUNCH_ENTRIES]
    noise, start = base.launch_noise, _section(card, "Starting State")
    assert ("**Launch noise.**" in action) == (noise is not None)
    if noise is not None:
        assert all(f"{sd:g} " in action for sd in (noise.speed, noise.elevation, noise.azimuth))
    assert ("**Wind.**" in start) == (base.wind_range is not None)
    if base.wind_range is not None:
        assert f"[{base.wind_range.low:g}, {base.wind_range.high:g}] m/s" in start
    drawn = {row[0].strip("`"): (float(row[1]), float(row[2])) for row in _rows(start)}
    assert drawn == ({} if base.randomize is None else {f: (lo, hi) for f, lo, hi in base.randomize.ranges})
    env.close()


def test_quoted_figures_match_their_result_files(tmp_path: Path) -> None:
    assert quotes.stale_blocks() == []
    for name in quotes.FILES:  # a hand edit of a quoted figure is caught
        if (ROOT / name).is_file():
            (tmp_path / name).parent.mkdir(parents=True, exist_ok=True)
            shutil.copy(ROOT / name, tmp_path / name)
    readme = tmp_path / "README.md"
    text = readme.read_text()
    block = text.split("<!-- quote:at-a-glance -->\n", 1)[1]
    edited = re.sub(r"\| (\d+)\.(\d) \|", lambda m: f"| {int(m.group(1)) + 1}.{m.group(2)} |", block, count=1)
    assert edited != block
    readme.write_text(text.replace(block, edited))
    assert quotes.stale_blocks(tmp_path) == ["README.md: at-a-glance"]


def test_the_baselines_pages_words_on_the_windy_seeds_hold_in_their_result_files() -> None:
    """docs/baselines.md says of the long windy runs, in words: every seed within a point of the
    informed oracle on throws 2-5; two of three at or above the best fixed first throw on throw 1,
    the third less than a point below."""
    from netgym.bench.results import RESULTS, read_results

    seeds = read_results(RESULTS / "windy_long_seeds.json")["figures"]["rows"]
    rows = {row["policy"]: row for row in read_results(RESULTS / "windy_per_throw.json")["figures"]["rows"]}
    informed = rows["informed oracle (knows the wind)"]
    fixed = next(row for name, row in rows.items() if name.startswith("best fixed first throw"))
    informed_later = sum(informed["by_throw"][1:]) / (4 * informed["episodes"])
    assert len(seeds) == 3 and all(row["episodes"] == fixed["episodes"] for row in seeds)
    assert all(sum(row["by_throw"][1:]) / (4 * row["episodes"]) >= informed_later - 0.01 for row in seeds)
    gaps = sorted(fixed["by_throw"][0] - row["by_throw"][0] for row in seeds)  # first throws caught fewer
    assert gaps[0] <= 0 and gaps[1] <= 0 and 0 < gaps[2] < 0.01 * fixed["episodes"]
    text = " ".join((ROOT / "docs" / "baselines.md").read_text().split())
    assert "two of the three seeds catch at least as many as the best fixed first throw" in text


def test_the_benchmark_report_is_what_its_result_files_render() -> None:
    """docs/BENCHMARKS.md is what ``scripts/report.py --render`` makes of docs/results/report.json
    and the result files sections 10-12 quote, so no hand edit of it outlives the next run."""
    assert report.to_markdown(*report.load()) == (ROOT / "docs" / "BENCHMARKS.md").read_text()


def test_a_report_comes_back_from_its_result_file_as_it_was_saved(tmp_path: Path) -> None:
    kept, _ = report.load()
    record = report.save(kept, tmp_path / "report.json")
    assert report.load(tmp_path / "report.json") == (kept, record)


def test_every_quoted_block_is_generated() -> None:
    for name in quotes.FILES:
        text = (ROOT / name).read_text()
        opened = re.findall(r"<!-- quote:([\w-]+) -->", text)
        assert opened == re.findall(r"<!-- /quote:([\w-]+) -->", text), name
        assert set(opened) <= set(quotes.BLOCKS), name
    assert "at-a-glance" in re.findall(r"<!-- quote:([\w-]+) -->", (ROOT / "README.md").read_text())


def _docstrings(path: Path):
    tree = ast.parse(path.read_text())
    for node in ast.walk(tree):
        if isinstance(node, (ast.Module, ast.ClassDef, ast.FunctionDef, ast.AsyncFunctionDef)):
            doc = ast.get_docstring(node)
            if doc:
                yield getattr(node, "name", path.stem), doc


def test_no_measured_figures_in_docstrings() -> None:
    found = [f"{path.relative_to(ROOT)}::{name}: {match.group(0)!r}"
             for path in sorted((ROOT / "netgym").rglob("*.py")) if "bench" not in path.parts
             for name, doc in _docstrings(path) for match in MEASURED.finditer(doc)]
    assert found == []


def test_the_figure_pattern_finds_a_timing_and_a_capture_rate() -> None:
    assert MEASURED.search("the sweep takes 28 us instead of 39")
    assert MEASURED.search("the blind oracle catches 54% of windy throws")
    assert not MEASURED.search("90% of the integrator's stability limit, 0.1 m/s")


def test_readme_is_an_entry_point() -> None:
    text = (ROOT / "README.md").read_text()
    assert len(text.splitlines()) <= 150 and len(text.split()) <= 1500
    assert not re.search(r"\b20\d\d-\d\d-\d\d\b|this (?:\d-core )?machine|experiment/|branch", text)
    for link in re.findall(r"\]\(((?:docs/)[^)#]+)", text):
        assert (ROOT / link).exists(), link


def test_every_module_the_readme_runs_is_the_standard_librarys_ours_or_in_an_extra() -> None:
    project = tomllib.loads((ROOT / "pyproject.toml").read_text())
    ours = {pattern.rstrip("*") for pattern in project["tool"]["setuptools"]["packages"]["find"]["include"]}
    extras = {re.match(r"[\w.-]+", requirement).group(0).lower().replace("-", "_")
              for requirements in project["project"]["optional-dependencies"].values() for requirement in requirements}
    run = {module.split(".")[0] for module in re.findall(r"python -m ([\w.]+)", (ROOT / "README.md").read_text())}
    assert run - set(sys.stdlib_module_names) - ours - extras == set()


@pytest.mark.slow
def test_the_docs_site_builds_with_warnings_as_errors(tmp_path: Path) -> None:
    result = subprocess.run([sys.executable, "-m", "mkdocs", "build", "--strict", "--site-dir", str(tmp_path / "site")], cwd=ROOT,
                            capture_output=True, text=True, timeout=600,
                            env={**os.environ, "NO_MKDOCS_2_WARNING": "1"})
    assert result.returncode == 0, result.stderr[-3000:]
    site = tmp_path / "site"
    assert (site / "environments" / "NetCatchWindy-v0.html").is_file()
    api = (site / "api.html").read_text()
    assert "NetCatchEnv" in api and "ThrowResult" in api
    pages = [page for page in site.rglob("*.html")  # 404.html: a web server's page, linked from its root
             if 'name="generator" content="mkdocs' in page.read_text() and page.name != "404.html"]
    assert len(pages) > len(netgym.ENVIRONMENTS)
    for page in pages:  # opened from disk, every link of MkDocs' pages leads to a file, not a folder's listing
        for link in re.findall(r'(?:href|src)="(?![a-z]+:)([^"#?]+)', page.read_text()):
            assert (page.parent / link).is_file(), f"{page.relative_to(site)}: {link}"
