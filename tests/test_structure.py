"""The shape of the code: no import circle between modules, and no library module too
long to read. Read from the source with ``ast`` (nothing is imported), so an import
hidden inside a function counts as much as one at the top of a file; imports under
``if TYPE_CHECKING:`` do not count, since they never run.

The import layers themselves (core < generator < stages < application) are the
contract in pyproject.toml, checked by ``make lint``; this test is the part of that
promise that must hold even where the lint tools are not installed.
"""

from __future__ import annotations

import ast
import functools
import re
from pathlib import Path

import networkx as nx
import pytest

ROOT = Path(__file__).resolve().parent.parent
#: The longest a library module may grow, in lines.
MAX_LINES = 1000


def package_folders() -> dict[str, Path]:
    """Import name -> folder, from pyproject's package-dir (``scenewright.core`` -> core/)."""
    text = (ROOT / "pyproject.toml").read_text()
    table = text.split("[tool.setuptools.package-dir]", 1)[1].split("\n[", 1)[0]
    mapping = dict(re.findall(r'^"([\w.]+)" = "([\w/]+)"$', table, re.MULTILINE))
    return {name: ROOT / folder for name, folder in mapping.items()}


@functools.cache
def library_modules() -> dict[str, Path]:
    """Every library module by its import name (``scenewright.generator.expand``)."""
    modules: dict[str, Path] = {}
    folders = package_folders()
    for package, folder in folders.items():
        for path in folder.rglob("*.py"):
            parts = path.relative_to(folder).with_suffix("").parts
            name = ".".join((package, *parts))
            # A subfolder that is a package of its own is listed under its own name.
            if any(name.startswith(other + ".") for other in folders if len(other) > len(package)):
                continue
            modules[name.removesuffix(".__init__")] = path
    return modules


def imported_modules(name: str, path: Path, modules: dict[str, Path]) -> set[str]:
    """The library modules that module ``name`` imports anywhere in its text. ``from P
    import M`` of a submodule M counts as importing M, not the package P."""
    package = name if path.name == "__init__.py" else name.rpartition(".")[0]
    found: set[str] = set()
    tree = ast.parse(path.read_text(), str(path))
    type_only = {
        id(inner)
        for block in ast.walk(tree)
        if isinstance(block, ast.If) and "TYPE_CHECKING" in ast.unparse(block.test)
        for statement in block.body
        for inner in ast.walk(statement)
    }
    for node in ast.walk(tree):
        if id(node) in type_only:
            continue
        candidates: list[str] = []
        if isinstance(node, ast.Import):
            candidates = [alias.name for alias in node.names]
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")[: len(package.split(".")) - (node.level - 1)]
                source = ".".join([*base, *([node.module] if node.module else [])])
            else:
                source = node.module or ""
            submodules = [f"{source}.{alias.name}" for alias in node.names]
            candidates = [m for m in submodules if m in modules] or [source]
        for candidate in candidates:
            while candidate and candidate not in modules:
                candidate = candidate.rpartition(".")[0]
            if candidate and candidate != name:
                found.add(candidate)
    return found


def import_graph() -> nx.DiGraph:
    modules = library_modules()
    graph = nx.DiGraph()
    graph.add_nodes_from(modules)
    for name, path in modules.items():
        for imported in imported_modules(name, path, modules):
            # A package's __init__ that gathers its modules' names is not a circle with them.
            if not imported.startswith(name + "."):
                graph.add_edge(name, imported)
    return graph


def test_the_module_list_covers_the_pipeline():
    names = set(library_modules())
    for expected in ("scenewright.core.scene", "scenewright.generator.expand", "scenewright.api"):
        assert expected in names


def test_no_module_imports_itself_back_through_others():
    graph = import_graph()
    cycles = sorted(sorted(component) for component in nx.strongly_connected_components(graph))
    circles = [component for component in cycles if len(component) > 1]
    assert circles == [], f"import circles: {circles}"


def test_a_circle_is_found_when_there_is_one(tmp_path, monkeypatch):
    """The check itself: two modules importing each other inside functions are caught."""
    (tmp_path / "pkg").mkdir()
    (tmp_path / "pkg" / "__init__.py").write_text("")
    (tmp_path / "pkg" / "a.py").write_text("def f():\n    from pkg.b import g\n")
    (tmp_path / "pkg" / "b.py").write_text(
        "from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n    from pkg import c\n"
        "def g():\n    from . import a\n"
    )
    (tmp_path / "pkg" / "c.py").write_text("")
    modules = {"pkg": tmp_path / "pkg" / "__init__.py"} | {
        f"pkg.{m}": tmp_path / "pkg" / f"{m}.py" for m in "abc"
    }
    assert imported_modules("pkg.a", modules["pkg.a"], modules) == {"pkg.b"}
    assert imported_modules("pkg.b", modules["pkg.b"], modules) == {"pkg.a"}


@pytest.mark.parametrize("name", sorted(library_modules()))
def test_no_library_module_is_too_long(name):
    lines = len(library_modules()[name].read_text().splitlines())
    assert lines <= MAX_LINES, f"{name} has {lines} lines (at most {MAX_LINES})"


#: A user doc says what a user can do and what the limits are; design reasoning and
#: dated measurements live in docs/notes/, which this limit does not cover.
MAX_DOC_LINES = 599


@pytest.mark.parametrize("doc", sorted(p.name for p in (ROOT / "docs").glob("*.md")))
def test_no_user_doc_is_too_long(doc):
    lines = (ROOT / "docs" / doc).read_text(encoding="utf-8").count("\n")
    assert lines <= MAX_DOC_LINES, f"docs/{doc} has {lines} lines, more than {MAX_DOC_LINES}"
