"""The project's size limits (issue 59), read from the syntax tree of every module of netgym/,
agents/, scripts/ and benchmarks/: a module at most 400 lines, a script of scripts/ at most 80,
a class at most 300, a function at most 60 (from its ``def`` line to its last, decorators
left out), and a numba kernel, a function decorated with the project's ``kernel`` or
``inline_kernel`` or with numba's ``njit`` or ``jit``, at most 10 parameters (named records
where more travel together). Each offender is named with its size and its limit.
"""

from __future__ import annotations

import ast
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
FOLDERS = ("netgym", "agents", "scripts", "benchmarks")
MODULE_LINES = 400
SCRIPT_LINES = 80
CLASS_LINES = 300
FUNCTION_LINES = 60
KERNEL_PARAMETERS = 10
KERNEL_DECORATORS = {"kernel", "inline_kernel", "njit", "jit"}


def _decorator_name(decorator: ast.expr) -> str | None:
    """``kernel`` of ``@kernel``, ``@numba.njit`` and ``@njit(cache=True)`` alike."""
    if isinstance(decorator, ast.Call):
        decorator = decorator.func
    if isinstance(decorator, ast.Attribute):
        return decorator.attr
    return decorator.id if isinstance(decorator, ast.Name) else None


def _parameters(arguments: ast.arguments) -> int:
    """Every parameter a function takes: positional, keyword-only, ``*args`` and ``**kwargs``."""
    return (len(arguments.posonlyargs) + len(arguments.args) + len(arguments.kwonlyargs)
            + (arguments.vararg is not None) + (arguments.kwarg is not None))


def _lines(node: ast.AST) -> int:
    return node.end_lineno - node.lineno + 1


def offenders(root: Path = ROOT, folders: tuple[str, ...] = FOLDERS) -> list[str]:
    """Every breach of the limits in the Python files under ``folders`` of ``root``, one line
    each: where (path, and the class or function's qualified name), what, and the limit."""
    found = []
    for folder in folders:
        for path in sorted((root / folder).rglob("*.py")):
            if "__pycache__" in path.parts:
                continue
            where = path.relative_to(root).as_posix()
            text = path.read_text(encoding="utf-8")
            limit = SCRIPT_LINES if folder == "scripts" else MODULE_LINES
            if len(text.splitlines()) > limit:
                found.append(f"{where}: module of {len(text.splitlines())} lines (limit {limit})")
            found += _inside(ast.parse(text, where), where, "")
    return found


def _inside(node: ast.AST, where: str, prefix: str) -> list[str]:
    """The breaches of the classes and functions within ``node``, named from ``prefix``."""
    found = []
    for child in ast.iter_child_nodes(node):
        if isinstance(child, ast.ClassDef):
            name = prefix + child.name
            if _lines(child) > CLASS_LINES:
                found.append(f"{where}: class {name} of {_lines(child)} lines (limit {CLASS_LINES})")
        elif isinstance(child, (ast.FunctionDef, ast.AsyncFunctionDef)):
            name = prefix + child.name
            if _lines(child) > FUNCTION_LINES:
                found.append(f"{where}: function {name} of {_lines(child)} lines (limit {FUNCTION_LINES})")
            count = _parameters(child.args)
            if count > KERNEL_PARAMETERS and any(_decorator_name(d) in KERNEL_DECORATORS for d in child.decorator_list):
                found.append(f"{where}: kernel {name} of {count} parameters (limit {KERNEL_PARAMETERS})")
        else:
            found += _inside(child, where, prefix)
            continue
        found += _inside(child, where, f"{name}.")
    return found


def test_the_code_keeps_the_size_limits() -> None:
    found = offenders()
    assert not found, "over the limits of issue 59:\n" + "\n".join(found)


def test_the_limits_name_every_offender(tmp_path: Path) -> None:
    """A made-up tree with one breach of each limit, and one of each just within it."""
    def function(name: str, lines: int, decorator: str = "", parameters: int = 0) -> str:
        body = "".join(f"    x{k} = {k}\n" for k in range(lines - 1))
        return f"{decorator}def {name}({', '.join(f'p{k}' for k in range(parameters))}):\n{body}\n"

    code = (function("long", FUNCTION_LINES + 1) + function("fits", FUNCTION_LINES)
            + function("wide", 2, "@kernel\n", KERNEL_PARAMETERS + 1)
            + function("wide_numba", 2, "@numba.njit(cache=True)\n", KERNEL_PARAMETERS + 1)
            + function("kernel_within", 2, "@inline_kernel\n", KERNEL_PARAMETERS)
            + function("plain_wide", 2, "", KERNEL_PARAMETERS + 1)
            + "class Big:\n" + "".join(f"    y{k} = {k}\n" for k in range(CLASS_LINES - 2))
            + "    " + function("method", 2, "", 0).replace("\n    ", "\n        "))
    (tmp_path / "netgym" / "deep").mkdir(parents=True)
    (tmp_path / "scripts").mkdir()
    (tmp_path / "netgym" / "deep" / "mod.py").write_text(code + "z = 0\n" * MODULE_LINES)
    (tmp_path / "scripts" / "run.py").write_text("z = 0\n" * (SCRIPT_LINES + 1))
    (tmp_path / "scripts" / "short.py").write_text("z = 0\n" * SCRIPT_LINES)
    found = offenders(tmp_path, ("netgym", "scripts"))
    module_lines = len((tmp_path / "netgym" / "deep" / "mod.py").read_text().splitlines())
    assert found == [f"netgym/deep/mod.py: module of {module_lines} lines (limit {MODULE_LINES})",
                     f"netgym/deep/mod.py: function long of {FUNCTION_LINES + 1} lines (limit {FUNCTION_LINES})",
                     f"netgym/deep/mod.py: kernel wide of {KERNEL_PARAMETERS + 1} parameters (limit {KERNEL_PARAMETERS})",
                     f"netgym/deep/mod.py: kernel wide_numba of {KERNEL_PARAMETERS + 1} parameters "
                     f"(limit {KERNEL_PARAMETERS})",
                     f"netgym/deep/mod.py: class Big of {CLASS_LINES + 1} lines (limit {CLASS_LINES})",
                     f"scripts/run.py: module of {SCRIPT_LINES + 1} lines (limit {SCRIPT_LINES})"]
