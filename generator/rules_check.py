"""Static checks of a parsed rule set: everything that can be wrong before expansion.

``check_tree`` looks at a file and its includes together and returns diagnostics in
file order: the catalog (fields, values, nouns of at most ``MAX_NOUN_CHARS``, styles,
mesh files that must load and lie in the rule set's ``ReadScope``, shape names the
renderer must know - a warning), the scene block (and its templates folder, in the
scope too), and the productions (labels, types, names in scope, calls and their
arguments, counts, probabilities and weights, blocks on groups only, PathConnectedTo
from a path to a junction), then the whole grammar: undefined nonterminals,
nonterminals that can never finish expanding (a fixpoint over the alternatives), and -
as warnings - nonterminals the start symbol never reaches and types no statement
creates.
Numbers must lie within the bounds of ``scenewright.core.limits`` and text may hold
no control or bidirectional-control characters.
A rule set with no error diagnostics is safe to turn into a catalog and to expand.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

from scenewright.core.errors import MeshFileError, RoomError
from scenewright.core.limits import (
    MAX_DEPTH,
    MAX_EXTENT,
    MAX_NODES,
    MAX_PATH_LENGTH,
    MAX_SEGMENTS,
    MAX_SIZE,
    MAX_WEIGHT,
    MIN_LENGTH,
    forbidden_character,
)
from scenewright.core.relations import RELATIONS
from scenewright.core.room import DEFAULT_WALL_HEIGHT, Room
from scenewright.core.shapes import MESH_SUFFIXES, SHAPES, load_mesh_file

from . import rules_ast as ast
from .catalog import STYLE_FIELDS, SourceLocation
from .rules_errors import WARNING, Diagnostic, SourceTexts, case_mix_up, did_you_mean
from .rules_includes import ParsedTree
from .rules_scope import ReadScope

#: The sides a clearance or access may name, and the words access also takes.
SIDE_WORDS = ("front", "back", "left", "right")
ACCESS_WORDS = ("any", "none", *SIDE_WORDS)
#: Type names a room's parts take: a catalog entry may not use them in a room.
ROOM_TYPES = ("wall", "door", "window")
#: The most free floor a clearance may keep beside an object (metres).
MAX_CLEARANCE = 10.0


def build_room(decl: ast.RoomDecl) -> tuple[Room | None, list[tuple[SourceLocation, str]]]:
    """The room a ``room`` setting declares, or None and what is wrong, where."""
    try:
        height = decl.height if decl.height is not None else DEFAULT_WALL_HEIGHT
        if decl.size is not None:
            if min(decl.size) < MIN_LENGTH or max(decl.size) > MAX_EXTENT:
                return None, [
                    (
                        decl.location,
                        f"each side of the room must lie between {MIN_LENGTH:g} and {MAX_EXTENT:g} m",
                    )
                ]
            room = Room.rectangle(*decl.size, height)
        else:
            assert decl.corners is not None  # a room block has a size or corners
            if any(abs(v) > MAX_EXTENT for corner in decl.corners for v in corner):
                return None, [
                    (decl.location, f"a room corner lies further than {MAX_EXTENT:g} m out")
                ]
            room = Room.polygon(decl.corners, height)
    except RoomError as problem:
        return None, [
            (
                decl.height_location
                if "height" in str(problem) and decl.height_location
                else decl.location,
                f"bad room: {problem}",
            )
        ]
    problems = []
    for opening in decl.openings:
        numbers = opening.numbers
        opening_height: float | None
        if opening.kind == "door":
            offset, width, *rest = numbers
            opening_height, sill = (rest[0] if rest else None), 0.0
        else:
            offset, width, sill, opening_height = numbers
        if room.wall(opening.wall) is None:
            problems.append(
                (
                    opening.wall_location,
                    f"the room has no wall '{opening.wall}'; name a wall by its "
                    f"side ({', '.join(dict.fromkeys(w.side for w in room.walls))}) or its number "
                    f"(1 to {len(room.walls)}, in the order of the corners)",
                )
            )
            continue
        try:
            room = room.with_opening(
                opening.kind,
                opening.wall,
                offset=offset,
                width=width,
                height=opening_height,
                sill=sill,
            )
        except RoomError as problem:
            problems.append((opening.location, str(problem)))
    return (None if problems else room), problems


DEFAULT_MAX_DEPTH = 32
DEFAULT_MAX_NODES = 2000

#: Fields that shape a path's polyline, so only ``path`` entries take them.
PATH_FIELDS = ("width", "max_length", "segments")
#: The largest value of each numeric field and scene setting (``core.limits``).
UPPER_LIMITS = {
    "width": MAX_SIZE,
    "max_length": MAX_PATH_LENGTH,
    "segments": MAX_SEGMENTS,
    "max_depth": MAX_DEPTH,
    "max_nodes": MAX_NODES,
}
#: Where every limit is listed.
LIMITS_DOC = "docs/limits.md"
#: The longest noun or plural, in characters: a noun phrase is a few words, and the
#: describer's English (inflection) takes time that grows fast with its length.
MAX_NOUN_CHARS = 200


def check_tree(tree: ParsedTree) -> list[Diagnostic]:
    """Every diagnostic about a parsed rule set (errors and warnings)."""
    checker = _Checker(tree.sources, tree.paths, tree.scope)
    checker.check(tree.files)
    file_order = {file.path: index for index, file in enumerate(tree.files)}
    return sorted(
        checker.diagnostics,
        key=lambda d: (file_order.get(d.location.file, -1), d.location.line, d.location.column),
    )


def _is_whole(value: float) -> bool:
    return float(value).is_integer()


def _number(value: float) -> str:
    return str(int(value)) if _is_whole(value) else str(value)


@dataclass
class _Checker:
    """One pass over a parsed rule set, collecting its diagnostics."""

    sources: SourceTexts
    paths: dict[str, Path]
    scope: ReadScope  # where the rule set may read files: meshes and templates must lie in it
    diagnostics: list[Diagnostic] = field(default_factory=list)
    kinds: dict[str, str] = field(default_factory=dict)  # type name -> kind
    productions: dict[str, ast.Production] = field(default_factory=dict)  # the first of each name
    created_types: set[str] = field(default_factory=set)  # types some statement creates
    #: Type -> the statements that create it and whether each may make none (``0.6? T``,
    #: ``0..2 T``): a ``some T`` where every one may is a warning (``check_type_reference``).
    makers: dict[str, list[tuple[bool, SourceLocation]]] = field(default_factory=dict)
    max_nodes: int = DEFAULT_MAX_NODES  # the scene's, once its block is checked
    room: Room | None = None  # the scene's room, once its block is checked
    has_room: bool = False  # the scene declares a room (even one with errors)

    def error(self, location: SourceLocation, message: str) -> None:
        self.diagnostics.append(self.sources.diagnostic(location, message))

    def warning(self, location: SourceLocation, message: str) -> None:
        self.diagnostics.append(self.sources.diagnostic(location, message, WARNING))

    # -- the rule set as a whole --------------------------------------------------

    def check(self, files: list[ast.RulesFile]) -> None:
        entries = [entry for file in files for entry in file.entries]
        first_entry: dict[str, ast.EntryDecl] = {}
        for entry in entries:
            if entry.name in first_entry:
                self.error(
                    entry.name_location,
                    f"duplicate catalog entry '{entry.name}' "
                    f"(first declared at {first_entry[entry.name].location})",
                )
                continue
            first_entry[entry.name] = entry
            self.kinds[entry.name] = entry.kind
        for entry in entries:
            self.check_entry(entry)

        start = self.check_scenes(files)
        if self.has_room:
            for name in ROOM_TYPES:
                if name in first_entry:
                    self.error(
                        first_entry[name].name_location,
                        f"'{name}' names the room's {name}s in a scene "
                        f"with a room; give this catalog entry another name",
                    )
        for file in files:
            for production in file.productions:
                if production.name in self.productions:
                    self.error(
                        production.location,
                        f"duplicate production for '{production.name}' "
                        f"(first at {self.productions[production.name].location})",
                    )
                else:
                    self.productions[production.name] = production
        for production in self.productions.values():
            self.note_makers(production)
        for production in self.productions.values():
            self.check_production(production)
        root = files[-1].path
        for entry in first_entry.values():
            # An included file may be a catalog several rule sets share: each makes only some of it.
            if entry.name not in self.created_types and entry.location.file == root:
                self.warning(
                    entry.name_location,
                    f"type '{entry.name}' is never created (no statement makes one)",
                )
        if start is not None:
            self.check_start(*start)
        self.check_termination()

    # -- catalog ------------------------------------------------------------------

    def check_entry(self, entry: ast.EntryDecl) -> None:
        fields = self.check_fields(entry.fields, entry.kind, style=False)
        if "noun" not in fields:
            self.error(
                entry.name_location, f"catalog entry '{entry.name}' has no noun (add: noun \"...\")"
            )
        seen: dict[str, ast.StyleDecl] = {}
        for style in entry.styles:
            if style.name in seen:
                self.error(style.location, f"duplicate style '{style.name}' of '{entry.name}'")
            seen[style.name] = style
            if style.weight is not None:
                assert style.weight_location is not None  # the parser sets both
                if style.weight <= 0:
                    self.error(
                        style.weight_location,
                        f"style weight must be positive, not {_number(style.weight)}",
                    )
                elif style.weight > MAX_WEIGHT:
                    self.error(
                        style.weight_location,
                        _too_large("a style weight", style.weight, MAX_WEIGHT, ""),
                    )
            self.check_fields(style.fields, entry.kind, style=True)

    def check_fields(
        self, fields: tuple[ast.Setting, ...], kind: str, style: bool
    ) -> dict[str, ast.Setting]:
        seen: dict[str, ast.Setting] = {}
        sides: set[str] = set()
        for setting in fields:
            name, value, at = setting.name, setting.value, setting.value_location
            if name == "clearance":  # one line per side
                self.check_clearance(setting, kind, sides)
                continue
            if name in seen:
                self.error(setting.location, f"duplicate field '{name}'")
                continue
            seen[name] = setting
            if name == "access":
                self.check_access(setting, kind)
                continue
            if isinstance(value, str) and self.check_text(name, value, at):
                continue
            if style and name not in STYLE_FIELDS:
                self.error(
                    setting.location,
                    f"a style cannot set '{name}' (only {', '.join(STYLE_FIELDS)})",
                )
            elif name in PATH_FIELDS and kind != "path":
                self.error(
                    setting.location,
                    f"'{name}' applies to paths only, not to {_with_article(kind)}",
                )
            if name == "size" and any(v <= 0 for v in setting.numbers()):
                self.error(at, "sizes must be positive")
            elif name == "size" and min(setting.numbers()) < MIN_LENGTH:
                self.error(at, _too_small("each side of a size", min(setting.numbers())))
            elif name == "size" and max(setting.numbers()) > MAX_SIZE:
                self.error(
                    at, _too_large("each side of a size", max(setting.numbers()), MAX_SIZE, " m")
                )
            elif name in ("width", "max_length") and setting.number() <= 0:
                self.error(at, f"'{name}' must be positive, not {_number(setting.number())}")
            elif name in ("width", "max_length") and setting.number() < MIN_LENGTH:
                self.error(at, _too_small(f"'{name}'", setting.number()))
            elif name == "segments" and (setting.number() < 1 or not _is_whole(setting.number())):
                self.error(
                    at,
                    "'segments' must be a whole number of at least 1, "
                    f"not {_number(setting.number())}",
                )
            elif name in UPPER_LIMITS and setting.number() > UPPER_LIMITS[name]:
                self.error(
                    at,
                    _too_large(
                        f"'{name}'",
                        setting.number(),
                        UPPER_LIMITS[name],
                        "" if name == "segments" else " m",
                    ),
                )
            elif name == "colour" and not _is_hex_colour(setting.text()):
                self.error(at, f"colour '{value}' is not of the form #rrggbb")
            elif name == "mesh":
                self.check_mesh(setting.text(), setting)
            elif name == "shape":
                self.check_shape(setting.text(), setting)
            elif name in ("noun", "plural") and not setting.text().strip():
                self.error(at, f"'{name}' must not be empty")
            elif name in ("noun", "plural") and len(setting.text()) > MAX_NOUN_CHARS:
                self.error(
                    at,
                    f"'{name}' is {len(setting.text())} characters long; "
                    f"it may have at most {MAX_NOUN_CHARS}",
                )
        return seen

    def check_clearance(self, setting: ast.Setting, kind: str, sides: set[str]) -> None:
        side, metres = setting.word_and_number()
        if kind != "object":
            self.error(
                setting.location,
                f"'clearance' applies to objects only, not to {_with_article(kind)}",
            )
        elif side not in SIDE_WORDS:
            self.error(
                setting.value_location,
                f"clearance side '{side}' is not one of {', '.join(SIDE_WORDS)}"
                + did_you_mean(side, SIDE_WORDS),
            )
        elif side in sides:
            self.error(setting.location, f"a second clearance {side}")
        elif not 0 < metres <= MAX_CLEARANCE:
            self.error(
                setting.location,
                f"a clearance must be more than 0 and at most {MAX_CLEARANCE:g} m, "
                f"not {_number(metres)}",
            )
        sides.add(side)

    def check_access(self, setting: ast.Setting, kind: str) -> None:
        words = setting.words()
        if kind != "object":
            self.error(
                setting.location, f"'access' applies to objects only, not to {_with_article(kind)}"
            )
            return
        for word in words:
            if word not in ACCESS_WORDS:
                self.error(
                    setting.value_location,
                    f"access '{word}' is not one of {', '.join(ACCESS_WORDS)}"
                    + did_you_mean(word, ACCESS_WORDS),
                )
                return
        if len(words) > 1 and ({"any", "none"} & set(words)):
            self.error(setting.value_location, "'access any' and 'access none' stand alone")
        elif len(set(words)) < len(words):
            self.error(setting.value_location, "a side is named twice")

    def check_text(self, name: str, value: str, at: SourceLocation) -> bool:
        """Error (and True) when a string holds a control or bidirectional-control
        character, which would garble or reorder the lines it is printed on."""
        bad = forbidden_character(value)
        if bad is not None:
            self.error(
                at,
                f"'{name}' contains the character {bad}; text may not hold control or "
                "bidirectional-control characters",
            )
        return bad is not None

    def folder_of(self, setting: ast.Setting) -> Path:
        """The folder of the file a setting is written in: its paths are relative to it."""
        return self.paths[setting.location.file].parent

    def check_mesh(self, file: str, setting: ast.Setting) -> None:
        folder = self.folder_of(setting)
        if not file.lower().endswith(MESH_SUFFIXES):
            suffixes = ", ".join(MESH_SUFFIXES[:-1]) + " or " + MESH_SUFFIXES[-1]
            self.error(setting.value_location, f"mesh '{file}' is not a {suffixes} file")
        elif (outside := self.scope.outside(folder / file)) is not None:
            self.error(setting.value_location, f"mesh file '{file}' {outside}")
        elif not (folder / file).exists():
            self.error(
                setting.value_location,
                f"mesh file '{file}' not found (looked in {folder.resolve()})",
            )
        else:
            try:
                load_mesh_file(folder / file)
            except MeshFileError as problem:
                self.error(setting.value_location, f"mesh file '{file}' {problem.reason}")

    def check_shape(self, shape: str, setting: ast.Setting) -> None:
        """A shape the renderer has no builder for is drawn as a plain box: warn."""
        if shape not in SHAPES:
            self.warning(
                setting.value_location,
                f"unknown shape '{shape}', drawn as a plain box"
                + (did_you_mean(shape, SHAPES) or "; 'scenewright list --shapes' lists the shapes"),
            )

    # -- scene block --------------------------------------------------------------

    def check_scenes(self, files: list[ast.RulesFile]) -> tuple[str, SourceLocation] | None:
        """Check the one scene block; return its start symbol and where it is named."""
        scenes = [scene for file in files for scene in file.scenes]
        if not scenes:
            root = files[-1].path
            self.error(
                SourceLocation(root, 1, 1),
                "no scene block; add one, e.g. scene village { extent 40 x 40  start Village }",
            )
            return None
        for extra in scenes[1:]:
            self.error(
                extra.location, f"a second scene block (the first is at {scenes[0].location})"
            )
        scene = scenes[0]
        settings: dict[str, ast.Setting] = {}
        for setting in scene.settings:
            if setting.name in settings:
                self.error(setting.location, f"duplicate scene setting '{setting.name}'")
                continue
            settings[setting.name] = setting
            value, at = setting.value, setting.value_location
            if isinstance(value, str) and self.check_text(setting.name, value, at):
                continue
            if setting.name == "extent" and any(v <= 0 for v in setting.numbers()):
                self.error(at, "the extent must be positive")
            elif setting.name == "extent" and min(setting.numbers()) < MIN_LENGTH:
                self.error(at, _too_small("each side of the extent", min(setting.numbers())))
            elif setting.name == "extent" and max(setting.numbers()) > MAX_EXTENT:
                self.error(
                    at,
                    _too_large("each side of the extent", max(setting.numbers()), MAX_EXTENT, " m"),
                )
            elif setting.name in ("max_depth", "max_nodes") and (
                setting.number() < 1 or not _is_whole(setting.number())
            ):
                self.error(
                    at,
                    f"'{setting.name}' must be a whole number of at least 1, "
                    f"not {_number(setting.number())}",
                )
            elif setting.name in UPPER_LIMITS and setting.number() > UPPER_LIMITS[setting.name]:
                self.error(
                    at,
                    _too_large(
                        f"'{setting.name}'", setting.number(), UPPER_LIMITS[setting.name], ""
                    ),
                )
            elif setting.name == "templates":
                self.check_templates(setting.text(), setting)
            elif setting.name in ("square", "line_of_sight") and value not in ("on", "off"):
                self.error(at, f"'{setting.name}' is 'on' or 'off', not '{value}'")
            elif setting.name == "room":
                self.check_room(setting.room(), settings)
        if "room" in settings:
            for other in ("extent", "walls"):
                if other in settings:
                    self.error(
                        settings[other].location,
                        f"'{other}' and 'room' both set the scene's floor; "
                        f"keep the room (its walls give the extent)",
                    )
        self.has_room = "room" in settings or "walls" in settings
        max_nodes = settings.get("max_nodes")
        if (
            max_nodes is not None
            and _is_whole(max_nodes.number())
            and 1 <= max_nodes.number() <= MAX_NODES
        ):
            self.max_nodes = int(max_nodes.number())
        if "start" not in settings:
            self.error(
                scene.location, "the scene block has no start symbol (add: start NONTERMINAL)"
            )
            return None
        return settings["start"].text(), settings["start"].value_location

    def check_room(self, decl: ast.RoomDecl, settings: dict[str, ast.Setting]) -> None:
        self.room, problems = build_room(decl)
        for location, message in problems:
            self.error(location, message)

    def check_templates(self, folder_name: str, setting: ast.Setting) -> None:
        """The description templates folder, like a mesh, is found relative to its file
        and must lie in the rule set's scope (its files are checked when read)."""
        folder = self.folder_of(setting)
        if (outside := self.scope.outside(folder / folder_name)) is not None:
            self.error(setting.value_location, f"templates folder '{folder_name}' {outside}")
        elif not (folder / folder_name).is_dir():
            self.error(
                setting.value_location,
                f"templates folder '{folder_name}' not found (looked in {folder.resolve()})",
            )
        else:
            self.check_template_files(folder / folder_name, setting)

    def check_template_files(self, folder: Path, setting: ast.Setting) -> None:
        """Each ``*.j2`` file of a templates folder must be a regular file in it once its
        links are resolved: the describer reads no other."""
        real_folder = folder.resolve()
        for path in sorted(folder.glob("*.j2")):
            real = path.resolve()
            if not real.is_relative_to(real_folder):
                problem = f"leads outside that folder (to {real})"
            elif not real.is_file():
                problem = "is not a regular file"
            else:
                continue
            self.error(
                setting.value_location,
                f"template '{path.name}' of templates folder '{setting.value}' {problem}",
            )

    def check_start(self, start: str, location: SourceLocation) -> None:
        if start not in self.productions:
            self.error(
                location,
                f"start symbol '{start}' has no production" + did_you_mean(start, self.productions),
            )
            return
        if self.productions[start].params:
            self.error(location, f"start symbol '{start}' takes parameters; it must take none")
        reached = self.reachable(start)
        for name, production in self.productions.items():
            if name not in reached:
                self.warning(
                    production.location,
                    f"nonterminal '{name}' is never used (start '{start}' does not reach it)",
                )

    # -- productions --------------------------------------------------------------

    def note_makers(self, production: ast.Production) -> None:
        """Record in ``makers`` each statement of ``production`` that creates a type."""
        for statement in ast.production_statements(production):
            subject = statement.subject
            if (
                isinstance(subject, ast.Reference)
                and subject.kind == "name"
                and subject.name in self.kinds
            ):
                optional = (statement.probability is not None and statement.probability < 1) or (
                    statement.count is not None and statement.count.low == 0
                )
                self.makers.setdefault(subject.name, []).append((optional, statement.location))

    def check_production(self, production: ast.Production) -> None:
        scope: dict[str, str | None] = {}
        for param in production.params:
            if param.name in scope:
                self.error(param.location, f"duplicate parameter '{param.name}'")
            elif param.name in self.kinds:
                self.error(
                    param.location,
                    f"parameter '{param.name}' has the name of a type; choose another name",
                )
            scope[param.name] = None  # what an argument is, is known only at the call
        for alternative in production.alternatives:
            if alternative.weight is not None and alternative.weight <= 0:
                self.error(
                    alternative.location,
                    f"alternative weight must be positive, not {_number(alternative.weight)}",
                )
            elif alternative.weight is not None and alternative.weight > MAX_WEIGHT:
                self.error(
                    alternative.location,
                    _too_large("an alternative weight", alternative.weight, MAX_WEIGHT, ""),
                )
            self.check_block(alternative.statements, dict(scope))

    def check_block(
        self, statements: tuple[ast.Statement, ...], scope: dict[str, str | None]
    ) -> None:
        """Check statements in order; ``scope`` (bound name -> kind of its nodes, if
        known) gains each statement's binding."""
        for statement in statements:
            self.check_statement(statement, scope)
            if statement.binding:
                scope[statement.binding] = self.subject_kind(statement.subject, scope)

    def check_statement(self, statement: ast.Statement, scope: dict[str, str | None]) -> None:
        subject = statement.subject
        self.check_count(statement.count)
        if statement.probability is not None and not 0 <= statement.probability <= 1:
            assert statement.probability_location is not None  # the parser sets both
            self.error(
                statement.probability_location,
                f"probability must be between 0 and 1, not {_number(statement.probability)}",
            )
        created_kind = self.check_subject(subject, scope)
        if statement.binding and statement.binding in self.kinds:
            assert statement.binding_location is not None  # the parser sets both
            self.error(
                statement.binding_location,
                f"'{statement.binding}' is a type; bind the nodes to another name",
            )
        for relation in statement.relations:
            if relation.label not in RELATIONS:
                self.error(
                    relation.location,
                    f"unknown relation label '{relation.label}'"
                    + (
                        case_mix_up(
                            relation.label, RELATIONS.names(), "relation labels are CamelCase"
                        )
                        or did_you_mean(relation.label, RELATIONS.names())
                    ),
                )
            family = RELATIONS[relation.label].family if relation.label in RELATIONS else None
            if (
                family != "wall" or self.has_room
            ):  # outdoors, the wall label's own error says it all
                self.check_target(relation.target, scope)
            if family == "structural":
                self.check_path_connection(subject, relation.target, scope)
            if family == "wall":
                self.check_wall_relation(relation)
        if statement.block is not None:
            self.check_group_block(statement, statement.block, created_kind, scope)

    def check_wall_relation(self, relation: ast.Relation) -> None:
        """A wall label needs a room, and a wall (or, by a window, a window) as its target."""
        label = RELATIONS[relation.label]
        wanted = "window" if label.wall in ("under_window", "beside_window") else "wall"
        target = relation.target
        if not self.has_room:
            self.error(
                relation.location,
                f"{relation.label} needs a room: give the scene block one "
                "(room W x D { door ... window ... })",
            )
        elif target.name != wanted or target.kind not in ("some", "nth"):
            self.error(
                target.location,
                f"{relation.label} stands by a {wanted}: write 'some {wanted}' "
                f"(the layout picks the {wanted} that fits) or '{wanted} #N'",
            )
        elif self.room is not None and target.kind == "nth":
            count = len(self.room.walls) if wanted == "wall" else len(self.room.windows)
            if target.index > count:
                self.error(
                    target.location,
                    f"'{wanted} #{target.index}': the room has {count} {wanted}"
                    + ("" if count == 1 else "s"),
                )

    def check_group_block(
        self,
        statement: ast.Statement,
        block: tuple[ast.Statement, ...],
        created_kind: str | None,
        scope: dict[str, str | None],
    ) -> None:
        """A block (``block``, the statement's) nests its nodes in the group its statement
        creates: only a new group takes one."""
        subject = statement.subject
        unknown_name = (
            isinstance(subject, ast.Reference)
            and subject.kind == "name"
            and subject.name not in scope
            and subject.name not in self.kinds
        )
        if created_kind != "group" and not unknown_name:  # an unknown name is reported already
            what = (
                f"'{subject.name}' is {_with_article(created_kind)}"
                if created_kind and isinstance(subject, ast.Reference)  # a call creates no kind
                else _subject_words(subject)
            )
            assert statement.block_location is not None  # the parser sets it with the block
            self.error(statement.block_location, f"a block nests nodes in a new group, but {what}")
        inner = dict(scope) | ({statement.binding: "group"} if statement.binding else {})
        self.check_block(block, inner)

    def check_count(self, count: ast.Count | None) -> None:
        if count is None:
            return
        for value in (count.low, count.high):
            if value < 0 or not _is_whole(value):
                self.error(count.location, f"a count must be a whole number, not {_number(value)}")
                return
        if count.low > count.high:
            self.error(
                count.location, f"range {_number(count.low)}..{_number(count.high)} has min > max"
            )
        elif count.high > self.max_nodes:
            raise_it = (
                f"raise it in the scene block, e.g. max_nodes {_number(count.high)}"
                if count.high <= MAX_NODES
                else f"max_nodes may be at most {MAX_NODES}, see {LIMITS_DOC}"
            )
            self.error(
                count.location,
                f"count {_number(count.high)} exceeds max_nodes {self.max_nodes} ({raise_it})",
            )
        elif count.weights is not None:
            assert count.weights_location is not None  # the parser sets both
            self.check_count_weights(count, count.weights, count.weights_location)

    def check_count_weights(
        self, count: ast.Count, weights: tuple[float, ...], where: SourceLocation
    ) -> None:
        """``LOW..HIGH {W ...}`` (``weights`` written at ``where``): one weight per count,
        none negative, not all zero."""
        wanted = int(count.high - count.low) + 1
        if len(weights) != wanted:
            self.error(
                where,
                f"range {_number(count.low)}..{_number(count.high)} has {wanted} counts but "
                f"{len(weights)} weight{'s' if len(weights) != 1 else ''}",
            )
        elif any(weight < 0 for weight in weights):
            negative = next(weight for weight in weights if weight < 0)
            self.error(where, f"count weights may not be negative, not {_number(negative)}")
        elif any(weight > MAX_WEIGHT for weight in weights):
            self.error(where, _too_large("a count weight", max(weights), MAX_WEIGHT, ""))
        elif not any(weights):
            self.error(where, "count weights are all 0: at least one count must be possible")

    def check_path_connection(
        self, subject: ast.Reference | ast.Call, target: ast.Reference, scope: dict[str, str | None]
    ) -> None:
        """``PathConnectedTo`` starts a path at a junction: check kinds where known."""
        for reference, kind, wanted in (
            (subject, self.subject_kind(subject, scope), "path"),
            (target, self.reference_kind(target, scope), "junction"),
        ):
            if kind is not None and kind != wanted:
                assert isinstance(reference, ast.Reference)  # a call's kind is not known
                self.error(
                    reference.location,
                    f"PathConnectedTo connects a path to a junction, "
                    f"but '{reference.name}' is {_with_article(kind)}",
                )

    def subject_kind(
        self, subject: ast.Reference | ast.Call, scope: dict[str, str | None]
    ) -> str | None:
        """The kind of a subject's nodes, when known without expanding."""
        return None if isinstance(subject, ast.Call) else self.reference_kind(subject, scope)

    def reference_kind(self, reference: ast.Reference, scope: dict[str, str | None]) -> str | None:
        if reference.kind == "name" and reference.name in scope:
            return scope[reference.name]
        return self.kinds.get(reference.name)

    def check_subject(
        self, subject: ast.Reference | ast.Call, scope: dict[str, str | None]
    ) -> str | None:
        """Check a statement's subject; return the kind of type it creates, if it creates one."""
        if isinstance(subject, ast.Call):
            self.check_call(subject, scope)
            return None
        if subject.kind == "name":
            if subject.name in scope:
                return None
            if self.has_room and subject.name in ROOM_TYPES:
                self.error(
                    subject.location,
                    f"the room's {subject.name}s come from its room block and cannot be "
                    f"created; refer to them as 'some {subject.name}' or '{subject.name} #1'",
                )
                return None
            if subject.name in self.kinds:
                self.created_types.add(subject.name)
                return self.kinds[subject.name]
            self.error(
                subject.location,
                f"unknown type or name '{subject.name}'"
                + (
                    case_mix_up(subject.name, self.productions, "nonterminals are CamelCase")
                    or did_you_mean(subject.name, list(self.kinds) + sorted(scope))
                ),
            )
            return None
        self.check_type_reference(subject)
        return None

    def check_target(self, reference: ast.Reference, scope: dict[str, str | None]) -> None:
        if reference.kind != "name":
            self.check_type_reference(reference)
        elif reference.name in scope:
            return
        elif reference.name in self.kinds:
            name = reference.name
            self.error(
                reference.location,
                f"'{name}' is a type, not a bound name; write "
                f"'some {name}', 'each {name}' or '{name} #1'",
            )
        else:
            self.error(
                reference.location,
                f"unbound name '{reference.name}'" + did_you_mean(reference.name, scope),
            )

    def check_type_reference(self, reference: ast.Reference) -> None:
        if self.has_room and reference.name in ROOM_TYPES:
            return
        if reference.name not in self.kinds:
            self.error(
                reference.location,
                f"unknown type '{reference.name}'" + did_you_mean(reference.name, self.kinds),
            )
        if reference.kind == "nth" and reference.index < 1:
            self.error(reference.location, f"'#{reference.index}': ordinals count from #1")
        elif reference.kind == "nth" and reference.index > self.max_nodes:
            self.error(
                reference.location,
                f"this ordinal is larger than max_nodes {self.max_nodes}, "
                "so it can never name a node",
            )
        makers = self.makers.get(reference.name, [])
        if reference.kind in ("some", "nth") and makers and all(optional for optional, _ in makers):
            written = (
                f"some {reference.name}"
                if reference.kind == "some"
                else f"{reference.name} #{reference.index}"
            )
            self.warning(
                reference.location,
                f"'{written}' may find none: every statement that makes "
                f"{_with_article(reference.name)} may make none (line {makers[0][1].line}), and where a scene "
                "has none its expansion stops here; refer to it only where one is certain",
            )

    def check_call(self, call: ast.Call, scope: dict[str, str | None]) -> None:
        for argument in call.arguments:
            self.check_target(argument, scope)
        production = self.productions.get(call.nonterminal)
        if production is None:
            self.error(
                call.location,
                f"undefined nonterminal '{call.nonterminal}'"
                + (
                    case_mix_up(call.nonterminal, self.kinds, "types are snake_case")
                    or case_mix_up(call.nonterminal, scope, "bound names are snake_case")
                    or did_you_mean(call.nonterminal, self.productions)
                ),
            )
            return
        expected, given = len(production.params), len(call.arguments)
        if expected != given:
            self.error(
                call.location,
                f"'{call.nonterminal}' takes {_parameters(expected)} "
                f"({production.location}), but {given} {'is' if given == 1 else 'are'} given",
            )

    # -- the grammar --------------------------------------------------------------

    def reachable(self, start: str) -> set[str]:
        reached, pending = {start}, [start]
        while pending:
            for name in _calls(self.productions[pending.pop()]):
                if name in self.productions and name not in reached:
                    reached.add(name)
                    pending.append(name)
        return reached

    def check_termination(self) -> None:
        """Error for each nonterminal none of whose alternatives can ever finish.

        A nonterminal terminates when one of its alternatives makes only calls that
        terminate, not counting calls it may skip (optional, or a count that may be 0).
        Fixpoint: keep adding terminating nonterminals until nothing changes.
        """
        terminating: set[str] = set()
        changed = True
        while changed:
            changed = False
            for name, production in self.productions.items():
                if name in terminating:
                    continue
                if any(
                    all(
                        call in terminating or call not in self.productions
                        for call in _required_calls(alt.statements)
                    )
                    for alt in production.alternatives
                ):
                    terminating.add(name)
                    changed = True
        for name, production in self.productions.items():
            if name in terminating:
                continue
            blocking = next(
                call
                for call in _required_calls(production.alternatives[0].statements)
                if call not in terminating and call in self.productions
            )
            reason = (
                "it always calls itself"
                if blocking == name
                else f"it always calls '{blocking}', which never finishes"
            )
            self.error(
                production.location,
                f"'{name}' can never finish expanding: {reason} "
                f"(make the call optional, e.g. '0.5? {blocking}' or '0..2 {blocking}', "
                "or add an alternative without it)",
            )


def _too_small(what: str, value: float) -> str:
    return f"{what} must be at least {MIN_LENGTH:g} m, not {value:g} (the limits: {LIMITS_DOC})"


def _too_large(what: str, value: float, limit: float, unit: str) -> str:
    shown = _number(value) if value < 1e15 else f"{value:g}"
    return f"{what} may be at most {limit:g}{unit}, not {shown} (the limits: {LIMITS_DOC})"


def _is_hex_colour(text: str) -> bool:
    digits = text[1:]
    return len(digits) == 6 and all(c in "0123456789abcdefABCDEF" for c in digits)


def _with_article(kind: str) -> str:
    return ("an " if kind[0] in "aeiou" else "a ") + kind


def _parameters(count: int) -> str:
    return "no parameters" if count == 0 else f"{count} parameter{'s' if count > 1 else ''}"


def _subject_words(subject: ast.Reference | ast.Call) -> str:
    if isinstance(subject, ast.Call):
        return f"'{subject.nonterminal}' is a nonterminal call"
    return "the subject refers to existing nodes"


def _calls(production: ast.Production) -> list[str]:
    """Every nonterminal a production may call, in order of appearance."""
    return [
        statement.subject.nonterminal
        for statement in ast.production_statements(production)
        if isinstance(statement.subject, ast.Call)
    ]


def _required_calls(statements: tuple[ast.Statement, ...]) -> list[str]:
    """The calls an alternative cannot skip: not optional, count at least 1."""
    required: list[str] = []
    for statement in statements:
        optional = (statement.probability is not None and statement.probability < 1) or (
            statement.count is not None and statement.count.low < 1
        )
        if optional:
            continue
        if isinstance(statement.subject, ast.Call):
            required.append(statement.subject.nonterminal)
        if statement.block:
            required.extend(_required_calls(statement.block))
    return required
