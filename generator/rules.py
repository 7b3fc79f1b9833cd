"""Loading rule sets: a name or path in, a checked ``Rules`` (or every error) out.

``load_rules("village")`` reads the shipped ``grammar_rules/village.rules``;
``load_rules("my/scene.rules")`` reads a file. Either way the file and its includes
are parsed, statically checked (``rules_check``) and turned into a ``Catalog`` and
``SceneParams``; any error raises ``RulesError`` carrying all of them, warnings stay
on ``Rules.warnings``. ``check_rules`` returns every diagnostic instead of raising, for
``scenewright validate``.

A rule set reads files (includes, meshes, its templates folder) only inside the folder
of the rules file named here; ``allow`` names more folders or files it may read, as
does the ``SCENEWRIGHT_ALLOW_OUTSIDE`` environment variable (``rules_scope.ReadScope``,
docs/security.md).
"""

from __future__ import annotations

import functools
import os
import re
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from importlib import resources
from pathlib import Path
from types import MappingProxyType

from scenewright.core.room import Room
from scenewright.core.scene_graph import SceneParams

from . import rules_ast as ast
from .catalog import Catalog, CatalogEntry, SourceLocation, Style
from .rules_check import check_tree
from .rules_check_scene import build_room
from .rules_check_values import DEFAULT_MAX_DEPTH, DEFAULT_MAX_NODES
from .rules_errors import RULES_SUFFIX, Diagnostic, RulesError, SourceTexts
from .rules_includes import ParsedTree, parse_tree

_SHIPPED_PACKAGE = "scenewright.grammar_rules"


@dataclass(frozen=True)
class Rules:
    """A checked rule set, ready to expand.

    ``name`` is the rule set's name (the file name without ``.rules``); the scene
    block's own name is ``params.name``; its description templates folder, if it
    brings one, is ``params.templates``. ``productions`` maps each nonterminal to its
    production; ``path`` is the root file.
    """

    name: str
    path: Path
    catalog: Catalog
    params: SceneParams
    productions: dict[str, ast.Production]
    start: str
    max_depth: int
    max_nodes: int
    warnings: tuple[Diagnostic, ...] = ()
    #: The text of every file, for diagnostics raised later (by expansion).
    sources: SourceTexts = field(default_factory=SourceTexts, compare=False, repr=False)


#: A shipped room rule set, read for the indoor catalog it includes.
INDOOR_CATALOG_READER = "bedroom"


def shipped_rule_sets() -> list[str]:
    """Names of the rule sets shipped with the package, sorted (``["bedroom", ...]``): the
    files with a ``scene`` block, not the house plans beside them (``plan NAME { ... }``,
    which ``scenewright.house`` reads)."""
    return list(_shipped_scenes())


@functools.cache
def _shipped_scenes() -> tuple[str, ...]:
    folder = resources.files(_SHIPPED_PACKAGE)
    return tuple(
        sorted(
            item.name[: -len(RULES_SUFFIX)]
            for item in folder.iterdir()
            if item.name.endswith(RULES_SUFFIX)
            and not is_plan_text(item.read_text(encoding="utf-8"))
        )
    )


def is_plan_text(text: str) -> bool:
    """Whether a rules text is a house plan: its first word outside comments is ``plan``."""
    found = re.search(r"[A-Za-z_]+", re.sub(r"#[^\n]*", "", text))
    return found is not None and found.group(0) == "plan"


@functools.cache
def indoor_catalog() -> Mapping[str, CatalogEntry]:
    """The shipped indoor catalog's entries by name (``CatalogEntry``, read-only): the
    types every shipped room rule set draws from, and the looks (noun, shape, colour) an
    example's object of such a type borrows. Read once, through a shipped room rule set
    that includes it (a catalog file alone has no scene block to load)."""
    return MappingProxyType(dict(load_rules(INDOOR_CATALOG_READER).catalog.entries))


def created_types(rules: Rules) -> set[str]:
    """The names the subjects of ``rules``' statements give (types and groups made, and
    names bound before): of a shared catalog, what this rule set makes."""
    return {
        statement.subject.name
        for production in rules.productions.values()
        for statement in ast.production_statements(production)
        if isinstance(statement.subject, ast.Reference)
    }


def load_rules(source: str | os.PathLike, *, allow: Iterable[str | os.PathLike] = ()) -> Rules:
    """Parse and check a rule set (shipped name or path); raise ``RulesError`` on errors.

    ``allow``: folders (with everything below them) or files outside the rule set's
    folder that it may read.
    """
    tree, diagnostics = _parse_and_check(source, allow)
    errors = [d for d in diagnostics if d.is_error]
    if errors:
        raise RulesError(errors)
    return _build(tree, tuple(d for d in diagnostics if not d.is_error))


def parse_rules_tree(
    source: str | os.PathLike, *, allow: Iterable[str | os.PathLike] = ()
) -> ParsedTree:
    """The parsed files of a rule set that loads, with their real paths, for tools that
    rewrite its text (``scenewright fit``); raise ``RulesError`` as ``load_rules`` does."""
    tree, diagnostics = _parse_and_check(source, allow)
    errors = [d for d in diagnostics if d.is_error]
    if errors:
        raise RulesError(errors)
    return tree


def check_rules(
    source: str | os.PathLike, *, allow: Iterable[str | os.PathLike] = ()
) -> list[Diagnostic]:
    """Every diagnostic about a rule set, warnings included; never raises for bad content.

    A missing file still raises ``RulesError`` (there is nothing to check). ``allow``
    as for ``load_rules``.
    """
    return _parse_and_check(source, allow)[1]


def _resolve(source: str | os.PathLike) -> tuple[Path, str]:
    """The file to read and the name to show in diagnostics."""
    text = os.fspath(source)
    if isinstance(source, str) and text in shipped_rule_sets():
        shipped = resources.files(_SHIPPED_PACKAGE).joinpath(text + RULES_SUFFIX)
        return Path(str(shipped)), text + RULES_SUFFIX
    path = Path(text)
    if not path.exists():  # anything else that is there is read, or refused, as a rules file
        known = ", ".join(shipped_rule_sets())
        where = SourceLocation(text, 1, 1)
        with_suffix = path.with_name(path.name + RULES_SUFFIX)
        hint = (
            f"; did you mean '{with_suffix}'?"
            if not text.endswith(RULES_SUFFIX) and with_suffix.is_file()
            else ""
        )
        raise RulesError(
            [
                Diagnostic(
                    where,
                    f"no rules file '{text}' (and no shipped rule set of that name: {known}){hint}",
                )
            ]
        )
    return path, text


def _parse_and_check(
    source: str | os.PathLike, allow: Iterable[str | os.PathLike]
) -> tuple[ParsedTree, list[Diagnostic]]:
    path, display = _resolve(source)
    tree = parse_tree(path, display, allow)
    if tree.diagnostics:  # syntax or include errors: the checks would only echo them
        return tree, list(tree.diagnostics)
    return tree, check_tree(tree)


# -- AST -> catalog and scene parameters --------------------------------------------


def _build(tree: ParsedTree, warnings: tuple[Diagnostic, ...]) -> Rules:
    root = tree.files[-1]
    catalog = Catalog()
    for file in tree.files:
        for entry in file.entries:
            catalog.add(_catalog_entry(entry, tree.paths[file.path].parent))
    scene = next(scene for file in tree.files for scene in file.scenes)
    settings = {setting.name: setting for setting in scene.settings}
    templates = next((setting for setting in scene.settings if setting.name == "templates"), None)
    room = None
    if "room" in settings:
        room, _ = build_room(settings["room"].room())  # checked already: it builds
    elif "walls" in settings and settings["walls"].value:
        room = Room.rectangle(*_extent(settings))
    params = SceneParams(
        name=scene.name,
        extent=room.extent if room else _extent(settings),
        ground=settings["ground"].text() if "ground" in settings else SceneParams.ground,
        room=room,
        square=_switch(settings, "square"),
        line_of_sight=_switch(settings, "line_of_sight"),
        # like a mesh, the folder is written relative to the file that names it
        templates=_beside(tree.paths[templates.location.file].parent, templates.text())
        if templates
        else None,
    )
    productions = {p.name: p for file in tree.files for p in file.productions}
    return Rules(
        name=Path(root.path).name.removesuffix(RULES_SUFFIX),
        path=tree.paths[root.path],
        catalog=catalog,
        params=params,
        productions=productions,
        start=settings["start"].text(),
        max_depth=int(settings["max_depth"].number())
        if "max_depth" in settings
        else DEFAULT_MAX_DEPTH,
        max_nodes=int(settings["max_nodes"].number())
        if "max_nodes" in settings
        else DEFAULT_MAX_NODES,
        warnings=warnings,
        sources=tree.sources,
    )


def _extent(settings: dict[str, ast.Setting]) -> tuple[float, float]:
    """The scene block's ``extent`` (width, depth), or the default."""
    if "extent" not in settings:
        return SceneParams.extent
    width, depth = settings["extent"].numbers()
    return width, depth


def _switch(settings: dict[str, ast.Setting], name: str) -> bool:
    """Whether an on/off setting of the scene block is on (it is unless written off)."""
    return name not in settings or settings[name].text() == "on"


def _beside(folder: Path, relative: str) -> str:
    """The absolute path of a file or folder a rules file names relative to itself."""
    return str((folder / relative).resolve())


def _hex_colour(text: str) -> tuple[float, float, float]:
    """``#8b5a2b`` -> RGB in [0, 1], the values as written (no gamma conversion)."""
    red, green, blue = (int(text[i : i + 2], 16) / 255.0 for i in (1, 3, 5))
    return red, green, blue


def _looks(fields: tuple[ast.Setting, ...], folder: Path) -> dict:
    """The look fields of an entry or style as ``CatalogEntry`` / ``Style`` arguments."""
    looks: dict = {}
    for setting in fields:
        if setting.name == "colour":
            looks["colour"] = _hex_colour(setting.text())
        elif setting.name == "mesh":
            looks["mesh"] = _beside(folder, setting.text())
        elif setting.name == "segments":
            looks["segments"] = int(setting.number())
        elif setting.name == "clearance":
            looks["clearance"] = (*looks.get("clearance", ()), setting.value)
        elif setting.name == "wall_gap":
            looks["wall_gap"] = float(setting.number())
        elif setting.name == "access":
            looks["access"] = () if setting.words() == ("none",) else setting.words()
        else:
            looks[setting.name] = setting.value
    return looks


def _catalog_entry(entry: ast.EntryDecl, folder: Path) -> CatalogEntry:
    styles = tuple(
        Style(
            style.name,
            style.weight if style.weight is not None else 1.0,
            **_looks(style.fields, folder),
        )
        for style in entry.styles
    )
    looks = _looks(entry.fields, folder)
    looks.setdefault("shape", "box")
    return CatalogEntry(entry.name, entry.kind, styles=styles, location=entry.location, **looks)
