"""The house's layer map (docs/ARCHITECTURE.md): netgym's rooms import only the rooms below them,
and netgym imports nothing of agents.

A room is a folder without subfolders, or a module of a folder that has them: ``netgym/physics/
kernels/`` is one room, ``netgym/physics/simulator.py`` another. Two guards hold the map. The
contracts of ``[tool.importlinter]`` in pyproject.toml (the layers of netgym and of
netgym.physics, exhaustive, so that a new room fails until it is placed; netgym forbidden to
import agents), run as ``lint-imports`` is run by hand. And this file's own reading of every
import statement under netgym/, by which no rooms import each other, in pairs or round a longer
circle, whether or not a contract names them. The docs' layer map is checked against the
contracts, so that the page and the check cannot drift apart.
"""

from __future__ import annotations

import ast
import re
import subprocess
import sys
import tomllib
from collections import defaultdict
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PACKAGE = ROOT / "netgym"
LINT = "import sys; from importlinter.cli import lint_imports_command; sys.exit(lint_imports_command())"
"""``lint-imports`` under this interpreter (the console script may belong to another)."""


def _modules(package: Path = PACKAGE) -> dict[str, Path]:
    """Every module under ``package``, by its dotted name (a package by its ``__init__.py``)."""
    found = {}
    for path in sorted(package.rglob("*.py")):
        if "__pycache__" in path.parts:
            continue
        parts = path.relative_to(package.parent).with_suffix("").parts
        found[".".join(parts[:-1] if parts[-1] == "__init__" else parts)] = path
    return found


def _room(path: Path, root: Path) -> str:
    """The room of ``path`` (relative to ``root``): its folder where that has no subpackage, else
    the module itself."""
    folder = path.parent
    if any(child.is_dir() and (child / "__init__.py").is_file() for child in folder.iterdir()):
        return path.relative_to(root).with_suffix("").as_posix()
    return folder.relative_to(root).as_posix() + "/"


def _imported(path: Path, modules: dict[str, Path]) -> set[str]:
    """The modules of ``modules`` that ``path``'s import statements name, wherever they stand
    (inside functions and ``TYPE_CHECKING`` too): ``from package import module`` names the
    module, ``from module import name`` the module."""
    name = next(dotted for dotted, where in modules.items() if where == path)
    package = name if path.name == "__init__.py" else name.rpartition(".")[0]
    found = set()
    for node in ast.walk(ast.parse(path.read_text(), str(path))):
        if isinstance(node, ast.Import):
            targets = [alias.name for alias in node.names]
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                anchor = package.split(".")[:len(package.split(".")) - node.level + 1]
                base = ".".join([*anchor, *([base] if base else [])])
            targets = [f"{base}.{alias.name}" if f"{base}.{alias.name}" in modules else base for alias in node.names]
        else:
            continue
        for target in targets:
            while target and target not in modules:  # `import a.b.c` of a name inside a.b
                target = target.rpartition(".")[0]
            if target:
                found.add(target)
    return found


def room_imports(package: Path = PACKAGE) -> dict[tuple[str, str], set[tuple[str, str]]]:
    """Per (room, room it imports): the (file, file) imports that make the arrow, as paths from
    the folder that holds ``package``."""
    modules, root = _modules(package), package.parent
    arrows: dict[tuple[str, str], set[tuple[str, str]]] = defaultdict(set)
    for path in modules.values():
        for target in _imported(path, modules):
            here, there = _room(path, root), _room(modules[target], root)
            if here != there:
                arrows[here, there].add((path.relative_to(root).as_posix(),
                                         modules[target].relative_to(root).as_posix()))
    return arrows


def circles(arrows: dict[tuple[str, str], set[tuple[str, str]]]) -> list[list[str]]:
    """The sets of two or more rooms that reach each other by their imports (strongly connected)."""
    reach: dict[str, set[str]] = defaultdict(set)
    for here, there in arrows:
        reach[here].add(there)
    rooms = {room for arrow in arrows for room in arrow}

    def reachable(start: str) -> set[str]:
        seen, todo = set(), [start]
        while todo:
            for room in reach[todo.pop()] - seen:
                seen.add(room)
                todo.append(room)
        return seen

    onward = {room: reachable(room) for room in rooms}
    found = {frozenset({room} | {other for other in onward[room] if room in onward[other]}) for room in rooms}
    return sorted(sorted(group) for group in found if len(group) > 1)


def test_the_import_contracts_are_kept() -> None:
    """``lint-imports`` (import-linter, the dev extra) keeps every contract of pyproject.toml."""
    run = subprocess.run([sys.executable, "-c", LINT, "--no-cache"], cwd=ROOT, capture_output=True, text=True,
                         timeout=300)
    assert run.returncode == 0 and " 0 broken" in run.stdout, run.stdout[-6000:] + run.stderr[-3000:]


def test_no_rooms_of_netgym_import_each_other() -> None:
    arrows = room_imports()
    assert arrows, "no imports read: the reader is broken"
    both_ways = {f"{a} <-> {b}: " + "; ".join(f"{x} -> {y}" for x, y in sorted(arrows[a, b] | arrows[b, a]))
                 for a, b in arrows if (b, a) in arrows}
    assert sorted(both_ways) == []
    assert circles(arrows) == [], "rooms that import each other round a circle"


def test_netgym_imports_nothing_of_agents() -> None:
    found = []
    for path in sorted(PACKAGE.rglob("*.py")):
        for node in ast.walk(ast.parse(path.read_text())):
            names = ([alias.name for alias in node.names] if isinstance(node, ast.Import)
                     else [node.module or ""] if isinstance(node, ast.ImportFrom) and not node.level else [])
            found += [f"{path.relative_to(ROOT)}: {name}" for name in names if name.split(".")[0] == "agents"]
    assert found == []


def test_the_reader_finds_a_circle_where_there_is_one(tmp_path: Path) -> None:
    """The room reader on a made-up package: a <-> b/ through a module each, c/ below both."""
    files = {"pkg/__init__.py": "", "pkg/a.py": "from pkg.b import inner\n", "pkg/b/__init__.py": "",
             "pkg/b/inner.py": "def f():\n    from pkg import a\n", "pkg/c/__init__.py": "",
             "pkg/c/low.py": "", "pkg/d.py": "import pkg.c.low\nfrom .c import low\n"}
    for name, text in files.items():
        (tmp_path / name).parent.mkdir(parents=True, exist_ok=True)
        (tmp_path / name).write_text(text)
    arrows = room_imports(tmp_path / "pkg")
    assert set(arrows) == {("pkg/a", "pkg/b/"), ("pkg/b/", "pkg/a"), ("pkg/d", "pkg/c/")}
    assert circles(arrows) == [["pkg/a", "pkg/b/"]]


def _contracts() -> dict[str, list[set[str]]]:
    """Each layers contract's layers, from the ground up, by its container."""
    config = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["importlinter"]
    return {contract["containers"][0]: [{name.strip() for name in layer.split("|")}
                                        for layer in reversed(contract["layers"])]
            for contract in config["contracts"] if contract["type"] == "layers"}


def _map(container: str) -> list[set[str]]:
    """The rooms of each floor of ``container``'s table in docs/ARCHITECTURE.md's layer map, from
    the ground up (a room named as `kernels/` or `simulator.py`)."""
    text = (ROOT / "docs" / "ARCHITECTURE.md").read_text()
    section = text.split(f"### `{container}`, from the ground up\n", 1)[1].split("\n#", 1)[0]
    rows = [line.split("|")[1:-1] for line in section.splitlines() if re.match(r"\|\s*\d+\s*\|", line)]
    return [{re.sub(r"(/|\.py)$", "", name) for name in re.findall(r"`([^`]+)`", rooms)} for _, rooms, *_ in rows]


def test_the_docs_layer_map_is_the_contracts() -> None:
    contracts = _contracts()
    assert set(contracts) == {"netgym", "netgym.physics"}
    for container, layers in contracts.items():
        assert _map(container) == layers, container
