"""The package's import graph (issue 31): no module imports, directly or through others, a module that imports it
back, and every module imports on its own.

The graph is read from the source with ``ast``: every ``import`` and ``from ... import`` of a project module, at
the top of a module or inside a function (an import done late still closes a cycle when that function runs),
relative imports resolved against the module's package. Imports under ``if TYPE_CHECKING:`` never run and are
left out. ``from package import name`` is an edge to ``package.name`` when that is a module, to ``package`` (its
``__init__``) otherwise.
"""
from __future__ import annotations

import ast
import json
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

PACKAGE_DIR = Path(__file__).resolve().parent.parent / "drywall_lab"


# --- the graph ---------------------------------------------------------------------------------------------------
def module_files(package_dir: Path) -> dict[str, tuple[Path, bool]]:
    """Every module of the package below ``package_dir``: dotted name -> (its file, whether it is a package)."""
    modules = {}
    for path in sorted(package_dir.rglob("*.py")):
        parts = list(path.relative_to(package_dir.parent).with_suffix("").parts)
        is_package = parts[-1] == "__init__"
        modules[".".join(parts[:-1] if is_package else parts)] = (path, is_package)
    return modules


def _runtime_nodes(tree: ast.AST):
    """Every node of ``tree`` but those under ``if TYPE_CHECKING:`` (or ``typing.TYPE_CHECKING``)."""
    todo = [tree]
    while todo:
        node = todo.pop()
        yield node
        for child in ast.iter_child_nodes(node):
            if isinstance(child, ast.If) and ast.unparse(child.test) in ("TYPE_CHECKING", "typing.TYPE_CHECKING"):
                todo.extend(child.orelse)
            else:
                todo.append(child)


def import_graph(package_dir: Path) -> dict[str, set[str]]:
    """Module name -> the project modules it imports (anywhere in it, see the module docstring)."""
    modules = module_files(package_dir)
    root = package_dir.name

    def known(name: str) -> str | None:
        """``name``, or the nearest package above it that is one of the modules (None outside the project)."""
        while name and name not in modules:
            name = name.rpartition(".")[0]
        return name or None

    graph: dict[str, set[str]] = {}
    for name, (path, is_package) in modules.items():
        package = name if is_package else name.rpartition(".")[0]
        found: set[str | None] = set()
        for node in _runtime_nodes(ast.parse(path.read_text(encoding="utf-8"), str(path))):
            if isinstance(node, ast.Import):
                found.update(known(a.name) for a in node.names if a.name.split(".")[0] == root)
            elif isinstance(node, ast.ImportFrom):
                if node.level:  # relative: level 1 is this module's package, 2 the one above, ...
                    base = package.split(".")[: len(package.split(".")) - node.level + 1]
                    source = ".".join(base + ([node.module] if node.module else []))
                else:
                    source = node.module or ""
                if source.split(".")[0] != root:
                    continue
                for alias in node.names:
                    found.add(f"{source}.{alias.name}" if f"{source}.{alias.name}" in modules else known(source))
        found.discard(None)
        found.discard(name)
        graph[name] = found  # type: ignore[assignment]
    return graph


def find_cycle(graph: dict[str, set[str]]) -> list[str] | None:
    """One cycle of ``graph`` as the path that closes it (``[a, b, a]``), or None when there is none."""
    state: dict[str, str] = {}  # "open" while on the current path, "done" once every path from it is seen
    path: list[str] = []

    def visit(node: str) -> list[str] | None:
        state[node] = "open"
        path.append(node)
        for nxt in sorted(graph.get(node, ())):
            if state.get(nxt) == "open":
                return path[path.index(nxt):] + [nxt]
            if nxt not in state and (cycle := visit(nxt)):
                return cycle
        path.pop()
        state[node] = "done"
        return None

    for start in sorted(graph):
        if start not in state and (cycle := visit(start)):
            return cycle
    return None


# --- the helpers on made-up graphs -------------------------------------------------------------------------------
def test_find_cycle_finds_a_cycle_and_passes_a_graph_without_one():
    assert find_cycle({"a": {"b"}, "b": {"c"}, "c": set()}) is None
    assert find_cycle({"a": {"b", "c"}, "b": {"c"}, "c": set(), "d": {"a"}}) is None  # a diamond is no cycle
    assert find_cycle({"a": {"b"}, "b": {"c"}, "c": {"a"}}) == ["a", "b", "c", "a"]
    assert find_cycle({"x": {"a"}, "a": {"b"}, "b": {"a"}}) == ["a", "b", "a"]
    assert find_cycle({"a": {"a"}}) == ["a", "a"]


def test_import_graph_reads_imports_in_functions_and_relative_ones(tmp_path):
    pkg = tmp_path / "demo"
    (pkg / "sub").mkdir(parents=True)
    files = {
        "__init__.py": "",
        "a.py": "import os\n\ndef f():\n    from demo.sub import b  # late\n    return b\n",
        "sub/__init__.py": "from .b import NAME\n",
        "sub/b.py": "from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n    from demo import c\nfrom .. import a\nNAME = 1\n",
        "c.py": "from demo.sub import NAME\n",
    }
    for name, text in files.items():
        (pkg / name).write_text(textwrap.dedent(text), encoding="utf-8")
    graph = import_graph(pkg)
    assert graph == {"demo": set(), "demo.a": {"demo.sub.b"}, "demo.sub": {"demo.sub.b"}, "demo.sub.b": {"demo.a"},
                     "demo.c": {"demo.sub"}}
    assert find_cycle(graph) == ["demo.a", "demo.sub.b", "demo.a"]


# --- the package -------------------------------------------------------------------------------------------------
def test_the_package_has_no_import_cycle():
    graph = import_graph(PACKAGE_DIR)
    assert "drywall_lab.course" in graph and "drywall_lab.exercise" in graph["drywall_lab.field"]
    cycle = find_cycle(graph)
    assert cycle is None, "import cycle: " + " -> ".join(cycle)


def test_library_modules_import_nothing_of_the_course():
    """The course (``drywall_lab.course``) is the notebooks' helpers: library modules never import it."""
    graph = import_graph(PACKAGE_DIR)
    users = sorted(m for m, deps in graph.items() if not m.startswith("drywall_lab.course")
                   and any(d == "drywall_lab.course" or d.startswith("drywall_lab.course.") for d in deps))
    assert users == []
    assert graph["drywall_lab.fast"] == set() and graph["drywall_lab.exercise"] == set()


#: Run in one fresh interpreter: each module imported with none of the project's modules loaded before it (the
#: third-party ones stay loaded, so that torch is imported once); one JSON line per module.
_IMPORT_EACH = """
import importlib, json, sys, traceback
for name in json.loads(sys.argv[1]):
    for loaded in [m for m in sys.modules if m == "drywall_lab" or m.startswith("drywall_lab.")]:
        del sys.modules[loaded]
    try:
        importlib.import_module(name)
        error = None
    except BaseException as e:
        error = traceback.format_exception_only(type(e), e)[-1].strip()
    print(json.dumps([name, error]), flush=True)
"""


def test_every_module_imports_on_its_own():
    names = sorted(module_files(PACKAGE_DIR))
    done = subprocess.run([sys.executable, "-c", _IMPORT_EACH, json.dumps(names)], capture_output=True, text=True,
                          cwd=PACKAGE_DIR.parent, timeout=600)
    results = dict(json.loads(line) for line in done.stdout.splitlines() if line.startswith("["))
    assert sorted(results) == names, f"the import run stopped early:\n{done.stderr[-3000:]}"
    failed = {name: error for name, error in results.items() if error}
    assert not failed, "modules that do not import on their own:\n" + "\n".join(f"{n}: {e}" for n, e in failed.items())
