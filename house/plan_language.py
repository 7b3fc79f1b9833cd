"""Reading a floor plan written in the rules language (``plan NAME { ... }``).

A plan file is a ``.rules`` file whose one block is a ``plan`` instead of a ``scene``:
it lists the rooms of a dwelling (type, count, area, the rule set that furnishes
them), which must connect, and the footprint they share (grammar: ``plan.lark``;
docs/rules-language.md, "Floor plans"). ``read_plan`` parses and checks it and returns
a ``PlanSpec``; every mistake is a located ``Diagnostic`` as the rules' own are
(``file:line:column``, the line, a caret, "did you mean").
"""

from __future__ import annotations

import os
from dataclasses import dataclass, field, fields, is_dataclass
from functools import cache
from pathlib import Path

from lark import Lark, Token, Tree
from lark.exceptions import UnexpectedCharacters, UnexpectedEOF, UnexpectedInput, UnexpectedToken

from scenewright.core.errors import RoomError
from scenewright.core.geometry import signed_area
from scenewright.core.room import DEFAULT_WALL_HEIGHT, Room
from scenewright.generator import load_rules, shipped_rule_sets
from scenewright.generator import rules_ast as ast
from scenewright.generator.catalog import SourceLocation
from scenewright.generator.rules import is_plan_text
from scenewright.generator.rules_errors import Diagnostic, RulesError, did_you_mean

#: Room types that are for walking through: a plan's corridors and halls get the
#: outside door when no room is marked ``entrance``, and rooms left without a door
#: of their own get one into them first.
CIRCULATION = ("hall", "corridor", "landing", "passage")
#: The most rooms one plan may make (every count at its top), and the largest footprint side.
MAX_ROOMS = 60
MAX_SIDE = 200.0
#: A room's area range when the plan gives none: this share of its rule set's own room.
DEFAULT_AREA_SHARE = (0.85, 1.15)
#: Its narrowest width when the plan gives none: this share of its rule set's room's
#: narrower side, or 0.8 of the side of a square of its least area, whichever is less.
DEFAULT_WIDTH_SHARE = 0.7


@dataclass(frozen=True)
class RoomSpec:
    """One ``room`` statement: ``count`` rooms of ``type`` (each present with ``probability``)."""

    type: str
    count: tuple[int, int]
    probability: float
    area: tuple[float, float]
    width: float
    #: The rule set that furnishes it: a shipped name or an absolute path.
    rules: str
    entrance: bool
    #: What the text calls one ("kitchen", "guest room"); default: the type in words.
    name: str
    #: Whether its rule set places things by a window, so it needs an outside wall.
    wants_window: bool
    #: Its rule set's room's first window (width, height, sill), the shape its windows take.
    window: tuple[float, float, float] | None
    location: SourceLocation


@dataclass(frozen=True)
class Connection:
    """``connect A B ...`` (every room of each B type gets a door to a room of type A) or
    ``open A B`` (every B open to an A: a doorway without a leaf)."""

    hub: str
    others: tuple[str, ...]
    open: bool
    location: SourceLocation


@dataclass(frozen=True)
class PlanSpec:
    name: str
    path: Path
    noun: str
    #: ``(width range, depth range)`` of a rectangle, or None when ``corners`` are given.
    size: tuple[tuple[float, float], tuple[float, float]] | None
    corners: tuple[tuple[float, float], ...]
    courtyards: tuple[tuple[tuple[float, float], ...], ...]
    height: float
    rooms: tuple[RoomSpec, ...]
    connections: tuple[Connection, ...]
    location: SourceLocation = field(default=SourceLocation("", 1, 1))

    def room_spec(self, room_type: str) -> RoomSpec:
        return next(spec for spec in self.rooms if spec.type == room_type)


def is_plan_file(source: str | os.PathLike) -> bool:
    """Whether a rules file (a path, or a shipped name) holds a ``plan`` block."""
    path = plan_path(source)
    if path is None:
        return False
    try:
        with open(path, encoding="utf-8", errors="replace") as handle:
            text = handle.read(65536)
    except OSError:
        return False
    return is_plan_text(text)


@cache
def shipped_plans() -> tuple[str, ...]:
    """Names of the shipped plans (``apartment``, ``house``, ...), sorted."""
    from importlib import resources

    folder = resources.files("scenewright.grammar_rules")
    names = []
    for item in folder.iterdir():
        if item.name.endswith(".rules") and is_plan_text(item.read_text(encoding="utf-8")):
            names.append(item.name.removesuffix(".rules"))
    return tuple(sorted(names))


@cache
def room_rule_sets() -> tuple[str, ...]:
    """The shipped rule sets whose scene is a room: the room types a plan may name."""
    return tuple(name for name in shipped_rule_sets() if load_rules(name).params.room is not None)


def read_plan(source: str | os.PathLike) -> PlanSpec:
    """Parse and check a plan file; ``RulesError`` (every located mistake) when it is wrong."""
    path = plan_path(source)
    if path is None:
        raise RulesError(
            [Diagnostic(SourceLocation(os.fspath(source), 1, 1), "no plan file of that name")]
        )
    display = (
        f"{source}.rules" if isinstance(source, str) and source in shipped_plans() else str(source)
    )
    text = path.read_text(encoding="utf-8")
    lines = text.splitlines()
    try:
        tree = _parser().parse(text)
    except UnexpectedInput as error:
        raise RulesError([_syntax_diagnostic(error, display, lines)]) from None
    reader = _Reader(display, path, lines)
    spec = reader.plan(_tree(tree.children[0]))
    if reader.diagnostics:
        raise RulesError(reader.diagnostics)
    return spec


# -- parsing -----------------------------------------------------------------------


@cache
def _parser() -> Lark:
    grammar = (Path(__file__).parent / "plan.lark").read_text(encoding="utf-8")
    return Lark(grammar, parser="lalr", propagate_positions=True)


def plan_path(source: str | os.PathLike) -> Path | None:
    """The file a shipped name (``apartment``) or a path names, or None when there is none."""
    text = os.fspath(source)
    if isinstance(source, str) and "/" not in text and not text.endswith(".rules"):
        from importlib import resources

        shipped = resources.files("scenewright.grammar_rules").joinpath(text + ".rules")
        if shipped.is_file():
            return Path(str(shipped))
    path = Path(text)
    return path if path.is_file() else None


def _syntax_diagnostic(error: UnexpectedInput, file: str, lines: list[str]) -> Diagnostic:
    line, column = max(error.line, 1), max(error.column, 1)
    if isinstance(error, UnexpectedEOF):
        message = "the plan ends before its closing '}'"
    elif isinstance(error, UnexpectedToken):
        expected = sorted(_words(error.accepts or error.expected))
        found = error.token.value if error.token.type != "$END" else "the end"
        message = f"unexpected '{found}'" + (f"; expected {_join(expected)}" if expected else "")
    elif isinstance(error, UnexpectedCharacters):
        message = f"unexpected character {error.char!r}"
    else:  # pragma: no cover - lark raises one of the three above
        message = "this is not a plan"
    source_line = lines[line - 1] if 0 < line <= len(lines) else None
    return Diagnostic(SourceLocation(file, line, column), message, source_line=source_line)


_TERMINAL_WORDS = {
    "NAME": "a name",
    "NUMBER": "a number",
    "INT": "a whole number",
    "SIGNED": "a number",
    "STRING": 'a "string"',
    "PROBABILITY": "a probability like 0.5?",
    "LPAR": "'('",
    "RPAR": "')'",
    "RBRACE": "'}'",
    "LBRACE": "'{'",
    "COMMA": "','",
}


def _words(terminals) -> set[str]:
    words = set()
    for name in terminals:
        if name in _TERMINAL_WORDS:
            words.add(_TERMINAL_WORDS[name])
        elif name.isupper() and not name.startswith("__"):
            words.add(f"'{name.lower()}'")
        else:
            words.add(f"'{name.lower()}'")
    return words


def _join(words: list[str]) -> str:
    return words[0] if len(words) == 1 else ", ".join(words[:-1]) + " or " + words[-1]


class _Reader:
    """Turns the parse tree into a ``PlanSpec``, collecting located diagnostics."""

    def __init__(self, file: str, path: Path, lines: list[str]) -> None:
        self.file, self.path, self.lines = file, path, lines
        self.diagnostics: list[Diagnostic] = []

    def where(self, item: Tree | Token) -> SourceLocation:
        meta = item if isinstance(item, Token) else item.meta
        return SourceLocation(self.file, getattr(meta, "line", 1), getattr(meta, "column", 1))

    def error(self, item: Tree | Token, message: str) -> None:
        location = self.where(item)
        line = self.lines[location.line - 1] if 0 < location.line <= len(self.lines) else None
        self.diagnostics.append(Diagnostic(location, message, source_line=line))

    def plan(self, tree: Tree) -> PlanSpec:
        name_token, *statements = tree.children
        seen: dict[str, Tree] = {}
        noun, size, corners, height = (
            str(name_token).replace("_", " "),
            None,
            (),
            DEFAULT_WALL_HEIGHT,
        )
        courtyards: list[tuple[tuple[float, float], ...]] = []
        rooms: list[RoomSpec] = []
        connections: list[tuple[Tree, bool]] = []
        footprint_tree = None
        declared: set[str] = set()
        for statement in statements:
            kind = statement.data
            if kind in ("noun", "footprint", "height") and kind in seen:
                self.error(statement, f"a second '{kind}': a plan has one")
                continue
            seen[kind] = statement
            if kind == "noun":
                noun = _string(statement.children[0])
                if not noun.strip():
                    self.error(statement, "the noun is empty")
            elif kind == "footprint":
                footprint_tree = statement
                size, corners = self.footprint(statement)
            elif kind == "courtyard":
                courtyards.append(self.corners(statement, "courtyard"))
            elif kind == "height":
                height = float(_token(statement.children[0]))
                if not 2.0 <= height <= 10.0:
                    self.error(statement, f"a wall height of {height:g} m: give 2 to 10 m")
            elif kind == "room":
                declared.add(
                    str(next(c for c in statement.children if getattr(c, "type", "") == "NAME"))
                )
                room = self.room(statement)
                if room is not None:
                    if any(other.type == room.type for other in rooms):
                        self.error(
                            statement,
                            f"a second 'room {room.type}': give one statement a count "
                            f"(room {room.type} 2) or a 'rules' of its own under another type",
                        )
                    else:
                        rooms.append(room)
            else:
                connections.append((statement, kind == "open"))
        location = SourceLocation(self.file, 1, 1)
        if footprint_tree is None:
            self.error(Token("NAME", "", line=1, column=1), "the plan has no 'footprint'")
        if not declared:
            self.error(tree, "the plan has no rooms ('room TYPE ...')")
        spec = PlanSpec(
            name=self.path.name.removesuffix(".rules"),
            path=self.path,
            noun=noun,
            size=size,
            corners=corners,
            courtyards=tuple(courtyards),
            height=height,
            rooms=tuple(rooms),
            connections=tuple(
                c for t, o in connections if (c := self.connection(t, o, rooms, declared))
            ),
            location=location,
        )
        if footprint_tree is not None and rooms and not self.diagnostics:
            self.check_space(spec, footprint_tree)
        return spec

    def footprint(self, tree: Tree):
        first = tree.children[0]
        if isinstance(first, Tree) and first.data == "size":
            ranges = tuple(self.range(r, "footprint side", 2.0, MAX_SIDE) for r in first.children)
            return (ranges[0], ranges[1]), ()
        return None, self.corners(tree, "footprint")

    def corners(self, tree: Tree, what: str) -> tuple[tuple[float, float], ...]:
        points = tuple(
            (float(_token(c.children[0])), float(_token(c.children[1])))
            for c in map(_tree, tree.children)
        )
        if len(points) < 3:
            self.error(tree, f"a {what} needs at least three corners")
            return points
        if any(abs(v) > MAX_SIDE for p in points for v in p):
            self.error(tree, f"a {what} corner lies more than {MAX_SIDE:g} m out")
            return points
        try:
            Room.polygon(points)
        except RoomError as error:
            self.error(tree, f"the {what}: {error}")
        return points

    def range(self, tree: Tree, what: str, low: float, high: float) -> tuple[float, float]:
        values = [float(_token(v)) for v in tree.children]
        lo, hi = values[0], values[-1]
        if lo > hi:
            self.error(tree, f"the {what} range {lo:g}..{hi:g} runs backwards")
        elif lo < low or hi > high:
            self.error(tree, f"a {what} of {lo:g}..{hi:g}: give {low:g} to {high:g}")
        return lo, hi

    def room(self, tree: Tree) -> RoomSpec | None:
        children = list(tree.children)
        probability = 1.0
        if isinstance(children[0], Token) and children[0].type == "PROBABILITY":
            probability = float(_token(children.pop(0))[:-1] or 0)
            if not 0.0 < probability <= 1.0:
                self.error(tree, f"a probability of {probability:g}: give more than 0, at most 1")
        type_token = _token(children.pop(0))
        room_type = str(type_token)
        count = (1, 1)
        options: dict[str, Tree] = {}
        for child in children:
            if isinstance(child, Tree) and child.data == "count":
                values = [int(_token(v)) for v in child.children]
                count = (values[0], values[-1])
                if count[0] > count[1]:
                    self.error(child, f"the count {count[0]}..{count[1]} runs backwards")
                elif count[1] < 1 or count[1] > MAX_ROOMS:
                    self.error(child, f"a count of {count[1]}: give 1 to {MAX_ROOMS}")
            elif isinstance(child, Tree):
                if child.data in options:
                    self.error(child, f"a second '{child.data}' for room {room_type}")
                options[child.data] = child
        rules = self.rules_of(room_type, type_token, options.get("rules"))
        if rules is None:
            return None
        source, loaded_room, wants_window = rules
        first_window = next(iter(loaded_room.windows), None)
        own_area = loaded_room.area
        own_width = min(loaded_room.extent)
        area = (
            self.range(options["area"].children[0], "room area", 1.0, 2000.0)
            if "area" in options
            else (
                round(own_area * DEFAULT_AREA_SHARE[0], 1),
                round(own_area * DEFAULT_AREA_SHARE[1], 1),
            )
        )
        width = (
            float(_token(options["width"].children[0]))
            if "width" in options
            else round(max(1.0, min(own_width * DEFAULT_WIDTH_SHARE, 0.8 * area[0] ** 0.5)), 1)
        )
        if width < 0.8 or width * width > area[1] * 1.5:
            self.error(
                options.get("width", tree),
                f"room {room_type}: a narrowest width of {width:g} m does not fit an area of "
                f"at most {area[1]:g} m²",
            )
        name = (
            _string(options["name"].children[0])
            if "name" in options
            else room_type.replace("_", " ")
        )
        return RoomSpec(
            type=room_type,
            count=count,
            probability=probability,
            area=area,
            width=width,
            rules=source,
            entrance="entrance" in options,
            name=name,
            wants_window=wants_window,
            window=(first_window.width, first_window.height, first_window.sill)
            if first_window is not None
            else None,
            location=self.where(type_token),
        )

    def rules_of(self, room_type: str, token: Token, option: Tree | None):
        """The rule set that furnishes ``room_type``: (source, its room, whether it uses windows)."""
        if option is None:
            known = list(room_rule_sets())
            if room_type not in known:
                self.error(
                    token,
                    f"no shipped rule set furnishes room type '{room_type}'"
                    f"{did_you_mean(room_type, known) or ''}; name one with "
                    f'rules "FILE.rules" (shipped: {", ".join(known)})',
                )
                return None
            source = room_type
            where: Tree | Token = token
        else:
            value = _token(option.children[0])
            where = option
            if value.type == "STRING":
                source = str((self.path.parent / _string(value)).resolve())
            else:
                source = str(value)
        try:
            loaded = load_rules(source)
        except RulesError as error:
            first = error.diagnostics[0] if getattr(error, "diagnostics", None) else error
            self.error(where, f"room {room_type}: its rule set does not load: {first}")
            return None
        if loaded.params.room is None:
            self.error(
                where,
                f"room {room_type}: rule set '{loaded.name}' is not a room (no 'room' in its scene)",
            )
            return None
        return source, loaded.params.room, _uses_windows(loaded)

    def connection(
        self, tree: Tree, open_: bool, rooms: list[RoomSpec], declared: set[str]
    ) -> Connection | None:
        names = [str(t) for t in tree.children]
        known = sorted(declared)
        ok = all(name in [room.type for room in rooms] for name in names)
        for token in tree.children:
            if str(token) not in declared:
                hint = did_you_mean(str(token), known) or ""
                self.error(token, f"'{token}' is not a room of this plan{hint}")
                ok = False
        if ok and names[0] in names[1:]:
            self.error(tree, f"'{names[0]}' cannot connect to itself here")
            ok = False
        if not ok:
            return None
        return Connection(names[0], tuple(names[1:]), open_, self.where(tree))

    def check_space(self, spec: PlanSpec, footprint: Tree) -> None:
        """Refuse, at the room or at the footprint, rooms that cannot fit."""
        if spec.size is not None:
            biggest = spec.size[0][1] * spec.size[1][1]
        else:
            biggest = abs(signed_area(spec.corners)) - sum(
                abs(signed_area(c)) for c in spec.courtyards
            )
        least = 0.0
        for room in spec.rooms:
            if room.area[0] > biggest:
                self.diagnostics.append(
                    Diagnostic(
                        room.location,
                        f"room {room.type} needs at least {room.area[0]:g} m² but the whole "
                        f"footprint has {biggest:.4g} m²",
                        source_line=self.lines[room.location.line - 1],
                    )
                )
            if room.probability >= 1.0:
                least += room.area[0] * room.count[0]
        if least > biggest and not self.diagnostics:
            self.error(
                footprint,
                f"the rooms the plan always has need at least {least:.4g} m² but the footprint "
                f"has at most {biggest:.4g} m²",
            )
        if sum(room.count[1] for room in spec.rooms) > MAX_ROOMS:
            self.error(footprint, f"the plan can make more than {MAX_ROOMS} rooms")


def _uses_windows(rules) -> bool:
    """Whether a rule set's productions name a window (``some window``, ``window #1``)."""
    return any(
        reference.name == "window"
        for production in rules.productions.values()
        for reference in _references(production)
    )


def _references(item):
    """Every ``Reference`` in a rules AST node, however deep."""
    if isinstance(item, ast.Reference):
        yield item
    elif is_dataclass(item):
        for attribute in fields(item):
            yield from _references(getattr(item, attribute.name))
    elif isinstance(item, (list, tuple)):
        for part in item:
            yield from _references(part)


def _string(token) -> str:
    return str(token)[1:-1]


def _token(node: Tree | Token) -> Token:
    """A child the grammar makes a token (a number, a name, a string)."""
    assert isinstance(node, Token), node
    return node


def _tree(node: Tree | Token) -> Tree:
    """A child the grammar makes a rule's tree."""
    assert isinstance(node, Tree), node
    return node
