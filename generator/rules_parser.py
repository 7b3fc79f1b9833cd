"""Rules text -> ``rules_ast`` dataclasses, following includes; syntax errors in words.

``parse_text`` parses one file with the LALR grammar in ``rules.lark`` (built once and
cached) and a lark ``Transformer``. ``parse_tree`` parses a file and, depth-first, the
files it includes (paths relative to the including file; each file once; a cycle is
reported at the ``include`` that closes it). A rule set reads only inside its
``ReadScope`` (its own folder, unless the user allows more) and only regular files of
at most ``MAX_RULES_BYTES``, so a pipe, a device or a huge file cannot stall or
exhaust it; the text of a file not named ``*.rules`` is never quoted. Lark's
exceptions become ``Diagnostic``s that say what was expected in words, never in
terminal names: a '{' that is never closed is reported where it opened, and a word in
the wrong place gets "did you mean" (a misspelt field or setting, a name in the wrong
case).
"""

from __future__ import annotations

import functools
import os
import re
import threading
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass, field
from importlib import resources
from pathlib import Path

from lark import Lark, Token, Transformer, Tree, v_args
from lark.exceptions import UnexpectedCharacters, UnexpectedToken

from scenewright.core.errors import InputError
from scenewright.core.files import UnusableFile, read_regular_file
from scenewright.core.limits import MAX_BLOCK_NESTING, MAX_NODES
from scenewright.core.relations import RELATIONS

from . import rules_ast as ast
from .catalog import SourceLocation
from .rules_errors import (
    RULES_SUFFIX,
    Diagnostic,
    SourceTexts,
    camel_case,
    case_hint,
    case_mix_up,
    did_you_mean,
    is_rules_file_name,
    snake_case,
)

#: The two errors lark's LALR parser stops with: a token it cannot take, a character
#: no token starts with.
ParseStop = UnexpectedToken | UnexpectedCharacters

#: Catalog fields and scene settings: the grammar's rules of these names each become an
#: ``ast.Setting`` (the ``start`` setting's rule is ``start_symbol``).
ENTRY_FIELDS = (
    "noun",
    "plural",
    "size",
    "shape",
    "mesh",
    "colour",
    "width",
    "max_length",
    "segments",
    "clearance",
    "access",
)
SCENE_SETTINGS = (
    "extent",
    "ground",
    "walls",
    "room",
    "square",
    "line_of_sight",
    "start",
    "max_depth",
    "max_nodes",
    "templates",
)


#: Building the parser twice at once fails: lark compiles the grammar's literals with
#: ``ast.literal_eval``, which CPython 3.11 does not allow in two threads at a time
#: ("AST constructor recursion depth mismatch", seen in dask's threaded workers).
_BUILDING = threading.Lock()


def lalr_parser() -> Lark:
    """The rules language's LALR parser, built once per process (building its tables
    from the grammar takes about 0.1 s)."""
    with _BUILDING:
        return _build_parser()


@functools.cache
def _build_parser() -> Lark:
    grammar = resources.files("scenewright.generator").joinpath("rules.lark").read_text()
    whole_words = _WholeKeywords()
    parser = Lark(
        grammar,
        parser="lalr",
        lexer="contextual",
        postlex=whole_words,
        propagate_positions=True,
        maybe_placeholders=True,
    )
    whole_words.keywords = frozenset(
        terminal.name
        for terminal in parser.terminals
        if terminal.pattern.type == "str" and terminal.pattern.value[:1].isalpha()
    )
    return parser


class _WholeKeywords:
    """Lark post-lexer that keeps keywords whole words.

    Where the parser takes a keyword but no name, the contextual lexer reads ``doors``
    as the keyword ``door`` and a name ``s``, and ``squareon`` as ``square on``, which
    parses. A keyword that runs straight on into a name or number is therefore a syntax
    error at the rest of the word, which the explainer reports as the whole word
    (``unexpected 'doors'; did you mean 'door'?``). ``5x4`` stays a room size.
    """

    always_accept: tuple[str, ...] = ()

    def __init__(self) -> None:
        self.keywords: frozenset[str] = frozenset()

    def process(self, stream: Iterable[Token]) -> Iterable[Token]:
        previous = None
        for token in stream:
            if (
                previous is not None
                and previous.type in self.keywords
                and token.start_pos == previous.end_pos
                and (token.value[:1].isalnum() or token.value[:1] == "_")
                and not (previous.value == "x" and token.type == "NUMBER")
            ):
                raise UnexpectedToken(token, set())
            yield token
            previous = token


# -- text -> AST --------------------------------------------------------------------


@dataclass(frozen=True)
class _Located:
    """A value and where it was written (a statement's probability or ``as`` name),
    passed up to ``statement``, which keeps the two in separate fields."""

    value: object
    location: SourceLocation


@dataclass(frozen=True)
class _Block:
    statements: tuple[ast.Statement, ...]
    location: SourceLocation


class _ToAst(Transformer):
    """Builds the dataclasses of ``rules_ast`` bottom-up from lark's parse tree."""

    def __init__(self, file: str):
        super().__init__()
        self.file = file

    def _at(self, item) -> SourceLocation:
        return SourceLocation(self.file, item.line, item.column)

    # settings of entries, styles and scenes

    def _setting(self, name: str, meta, values: list[Token]) -> ast.Setting:
        if not values:
            return ast.Setting(name, True, self._at(meta), self._at(meta))
        converted = [_value(token) for token in values]
        value = converted[0] if len(converted) == 1 else tuple(converted)
        return ast.Setting(name, value, self._at(meta), self._at(values[0]))

    def __default__(self, data, children, meta):
        # The grammar's rule `start` is a whole file, so the `start` setting's rule is
        # `start_symbol`; every other field and setting rule is named like its keyword.
        if data == "access":  # always a tuple of sides, however many
            setting = self._setting("access", meta, children)
            return (
                setting
                if isinstance(setting.value, tuple)
                else ast.Setting(
                    setting.name, (setting.value,), setting.location, setting.value_location
                )
            )
        if data in ENTRY_FIELDS or (data in SCENE_SETTINGS and data not in ("start", "room")):
            return self._setting(str(data), meta, children)
        if data == "start_symbol":
            return self._setting("start", meta, children)
        return super().__default__(data, children, meta)

    def kind(self, children):
        return children[0]

    # the room block

    @v_args(meta=True)
    def room(self, meta, children):
        shape, *rest = children
        body = rest[-1] if rest and isinstance(rest[-1], list) else []
        corners = [shape, *(item for item in rest if isinstance(item, tuple))]
        size = shape[1] if shape[0] == "size" else None
        height = next((item for item in body if isinstance(item, _Located)), None)
        room = ast.RoomDecl(
            size=size,
            corners=None if size else tuple(corner[1] for corner in corners),
            height=height.value if height else None,
            openings=tuple(item for item in body if isinstance(item, ast.OpeningDecl)),
            location=self._at(meta),
            height_location=height.location if height else None,
        )
        return ast.Setting("room", room, self._at(meta), self._at(meta))

    def room_size(self, children):
        return ("size", (float(children[0]), float(children[1])))

    def room_corner(self, children):
        return ("corner", (float(children[0]), float(children[1])))

    def room_body(self, children):
        return [child for child in children if child is not None]

    @v_args(meta=True)
    def wall_height(self, meta, children):
        return _Located(float(children[0]), self._at(children[0]))

    def wall_name(self, children):
        return children[0]

    @v_args(meta=True)
    def door(self, meta, children):
        return self._opening("door", meta, children)

    @v_args(meta=True)
    def window(self, meta, children):
        return self._opening("window", meta, children)

    def _opening(self, kind: str, meta, children) -> ast.OpeningDecl:
        wall, *numbers = children
        values = tuple(float(n) for n in numbers if n is not None)
        return ast.OpeningDecl(kind, str(wall), values, self._at(meta), self._at(wall))

    @v_args(meta=True)
    def style(self, meta, children):
        name, weight, *fields = children
        return ast.StyleDecl(
            str(name),
            float(weight) if weight is not None else None,
            tuple(fields),
            self._at(meta),
            self._at(weight) if weight is not None else None,
        )

    @v_args(meta=True)
    def entry(self, meta, children):
        kind, name, *rest = children
        fields = tuple(item for item in rest if isinstance(item, ast.Setting))
        styles = tuple(item for item in rest if isinstance(item, ast.StyleDecl))
        return ast.EntryDecl(str(kind), str(name), fields, styles, self._at(meta), self._at(name))

    @v_args(meta=True)
    def scene(self, meta, children):
        name, *settings = children
        return ast.SceneDecl(str(name), tuple(settings), self._at(meta))

    def include(self, children):
        return ast.IncludeDecl(children[0][1:-1], self._at(children[0]))

    # productions

    @v_args(meta=True)
    def name_ref(self, meta, children):
        return ast.Reference("name", str(children[0]), self._at(meta))

    @v_args(meta=True)
    def some_ref(self, meta, children):
        return ast.Reference("some", str(children[0]), self._at(meta))

    @v_args(meta=True)
    def each_ref(self, meta, children):
        return ast.Reference("each", str(children[0]), self._at(meta))

    @v_args(meta=True)
    def nth_ref(self, meta, children):
        name, ordinal = children
        return ast.Reference("nth", str(name), self._at(meta), _ordinal(ordinal))

    def arguments(self, children):
        return tuple(child for child in children if child is not None)

    @v_args(meta=True)
    def call(self, meta, children):
        name, arguments = children
        return ast.Call(str(name), arguments or (), self._at(meta))

    def relation(self, children):
        label, target = children
        return ast.Relation(str(label), target, self._at(label))

    @v_args(meta=True)
    def count(self, meta, children):
        low, high, weights = children
        return ast.Count(
            float(low),
            float(high if high is not None else low),
            self._at(meta),
            weights.value if weights else None,
            weights.location if weights else None,
        )

    @v_args(meta=True)
    def count_weights(self, meta, children):
        return _Located(tuple(float(weight) for weight in children), self._at(meta))

    @v_args(meta=True)
    def probability(self, meta, children):
        return _Located(float(children[0]), self._at(meta))

    def binding(self, children):
        return _Located(str(children[0]), self._at(children[0]))

    @v_args(meta=True)
    def block(self, meta, children):
        return _Block(tuple(child for child in children if child is not None), self._at(meta))

    @v_args(meta=True)
    def statement(self, meta, children):
        count, probability, subject, binding, *relations, block = children
        return ast.Statement(
            subject=subject,
            location=self._at(meta),
            count=count,
            probability=probability.value if probability else None,
            probability_location=probability.location if probability else None,
            binding=binding.value if binding else None,
            binding_location=binding.location if binding else None,
            relations=tuple(relations),
            block=block.statements if block else None,
            block_location=block.location if block else None,
        )

    @v_args(meta=True)
    def alternative(self, meta, children):
        weight, block = children
        return ast.Alternative(
            float(weight) if weight is not None else None, block.statements, self._at(meta)
        )

    def params(self, children):
        return tuple(ast.Param(str(name), self._at(name)) for name in children if name is not None)

    @v_args(meta=True)
    def production(self, meta, children):
        name, params, *alternatives = children
        return ast.Production(str(name), params or (), tuple(alternatives), self._at(meta))

    def start(self, children):
        return ast.RulesFile(
            path=self.file,
            includes=tuple(c for c in children if isinstance(c, ast.IncludeDecl)),
            scenes=tuple(c for c in children if isinstance(c, ast.SceneDecl)),
            entries=tuple(c for c in children if isinstance(c, ast.EntryDecl)),
            productions=tuple(c for c in children if isinstance(c, ast.Production)),
        )


def _value(token: Token):
    if token.type == "NUMBER":
        return float(token)
    if token.type == "STRING":
        return str(token)[1:-1]
    return str(token)


def parse_text(
    text: str, file: str, sources: SourceTexts | None = None, quoted: bool = True
) -> ast.RulesFile | Diagnostic:
    """Parse one file's text; a syntax error is returned as its ``Diagnostic``.

    The text may be quoted in diagnostics when ``quoted`` and the file is named
    ``*.rules``; a syntax error in any other file says only that it is not a rules
    file, and where, without a word of its text.
    """
    sources = sources or SourceTexts()
    sources.add(file, text, quoted)
    try:
        tree = lalr_parser().parse(text)
    except (UnexpectedToken, UnexpectedCharacters) as error:  # the two LALR parse errors
        if not (quoted and is_rules_file_name(file)):
            return _not_rules(error, text, file)
        return _syntax_diagnostic(error, text, file, sources)
    too_deep = _too_deep_block(tree)
    if too_deep is not None:
        return sources.diagnostic(
            SourceLocation(file, too_deep.meta.line, too_deep.meta.column),
            f"blocks nested more than {MAX_BLOCK_NESTING} deep; move the inner ones into a production "
            "of their own and call it (the limits: docs/limits.md)",
        )
    return _ToAst(file).transform(tree)


def _too_deep_block(tree: Tree) -> Tree | None:
    """The first statement block nested more than ``MAX_BLOCK_NESTING`` deep inside a
    production's block, if any: found without recursion, so that the transformer, which
    recurses, only ever meets shallow trees."""
    pending = [(tree, 0)]
    while pending:
        node, depth = pending.pop()
        if node.data == "block":
            depth += 1
            if depth > MAX_BLOCK_NESTING + 1:  # the production's own block, then the nested ones
                return node
        pending.extend(
            (child, depth) for child in reversed(node.children) if isinstance(child, Tree)
        )
    return None


def _ordinal(token: Token) -> int:
    """``#N`` as N. An N of more digits than any node count has (more than an int may
    be read from) stands as one past ``MAX_NODES``: the checks report it out of range."""
    digits = token[1:].lstrip("0") or "0"
    return int(digits) if len(digits) <= len(str(MAX_NODES)) else MAX_NODES + 1


def _not_rules(error: ParseStop, text: str, file: str) -> Diagnostic:
    """A syntax error in a file whose text must not be shown: where, and nothing of what."""
    offset = _error_offset(error, text)
    line = text.count("\n", 0, offset) + 1
    column = offset - (text.rfind("\n", 0, offset) + 1) + 1
    return Diagnostic(
        SourceLocation(file, line, column),
        f"'{file}' is not a rules file: it does not parse as "
        f"rules here (the text of a file not named *{RULES_SUFFIX} is never shown)",
    )


# -- files and includes -------------------------------------------------------------


#: The most a rules file may hold (4 MiB): far more than any rule set needs, little
#: enough that reading and parsing it stays quick.
MAX_RULES_BYTES = 4 * 1024 * 1024

#: The environment variable that lets rule sets read more than their own folder:
#: paths separated by ``os.pathsep`` (":"), each a folder (with all below it) or a file.
ALLOW_VARIABLE = "SCENEWRIGHT_ALLOW_OUTSIDE"


@dataclass(frozen=True)
class ReadScope:
    """Where a rule set may read files (includes, meshes, templates): inside its root,
    the folder of the rules file the user named, and inside what the user allows
    besides. Paths are compared with their links resolved, so a link in the rule set's
    folder to a file elsewhere is outside."""

    root: Path
    allowed: tuple[Path, ...] = ()

    @classmethod
    def of(
        cls, path: str | os.PathLike[str], allow: Iterable[str | os.PathLike[str]] = ()
    ) -> ReadScope:
        """The scope of the rule set whose top file is ``path``, with the paths of
        ``allow`` and of the ``ALLOW_VARIABLE`` environment variable allowed besides."""
        return cls.of_folder(Path(path).parent, allow)

    @classmethod
    def of_folder(
        cls, folder: str | os.PathLike[str], allow: Iterable[str | os.PathLike[str]] = ()
    ) -> ReadScope:
        """The scope of a folder (a rule set's, a plan set's), with the paths of ``allow``
        and of the ``ALLOW_VARIABLE`` environment variable allowed besides. A path that
        is a loop of symbolic links is an ``InputError``."""
        from_environment = [
            item for item in os.environ.get(ALLOW_VARIABLE, "").split(os.pathsep) if item
        ]
        allowed = tuple(_resolved(item, "allowed") for item in [*allow, *from_environment])
        return cls(_resolved(folder, "folder"), allowed)

    def outside(self, path: str | os.PathLike[str], holder: str = "rule set") -> str | None:
        """None when ``path`` is in the scope; else why not, completing "file 'F' ..."."""
        try:
            real = Path(path).resolve()
        except (RuntimeError, OSError):  # a loop of links
            return "is a loop of symbolic links"
        if any(real.is_relative_to(place) for place in (self.root, *self.allowed)):
            return None
        link = f" (it leads to {real})" if real != Path(os.path.abspath(path)) else ""
        return (
            f"is outside the {holder}'s folder {self.root}{link}; a {holder} reads only its own folder "
            f"unless the user allows more (--allow-outside PATH or {ALLOW_VARIABLE}, see docs/security.md)"
        )


def _resolved(path: str | os.PathLike[str], what: str) -> Path:
    """``path`` with its links resolved; ``InputError`` for a loop of links."""
    try:
        return Path(path).resolve()
    except (RuntimeError, OSError):
        shown = ascii(os.fspath(path))
        shown = shown if len(shown) <= 60 else shown[:56] + "...'"
        raise InputError(
            f"the {what} path {shown} is a loop of symbolic links; name a real file or folder"
        ) from None


@dataclass
class ParsedTree:
    """A rules file and everything it includes, parsed (or the diagnostics why not).

    ``files`` is in depth-first include order, each included file before the file
    that includes it; ``paths`` maps each file's display name to its real path;
    ``scope`` is where the rule set may read files.
    """

    scope: ReadScope
    files: list[ast.RulesFile] = field(default_factory=list)
    paths: dict[str, Path] = field(default_factory=dict)
    sources: SourceTexts = field(default_factory=SourceTexts)
    diagnostics: list[Diagnostic] = field(default_factory=list)


def parse_tree(
    path: Path, display: str, allow: Iterable[str | os.PathLike[str]] = ()
) -> ParsedTree:
    """Parse ``path`` (shown as ``display`` in diagnostics) and the files it includes,
    which must lie in its folder or in ``allow`` (``ReadScope``)."""
    tree = ParsedTree(ReadScope.of(path, allow))
    _parse_into(tree, Path(path), display, include_stack=[], include_location=None)
    return tree


def _parse_into(
    tree: ParsedTree,
    path: Path,
    display: str,
    include_stack: list[tuple[Path, str]],
    include_location: SourceLocation | None,
) -> None:
    real = path.resolve()
    for index, (seen, _) in enumerate(include_stack):
        if seen == real:
            assert include_location is not None  # only an included file closes a cycle
            chain = " -> ".join([name for _, name in include_stack[index:]] + [display])
            tree.diagnostics.append(
                tree.sources.diagnostic(include_location, f"include cycle: {chain}")
            )
            return
    if any(known.resolve() == real for known in tree.paths.values()):
        return  # already included along another route: its declarations are in once
    text = _read_rules_file(tree, path, display, include_location)
    if text is None:
        return
    tree.paths[display] = path
    # Quoted only when named *.rules both as written and where its links lead.
    parsed = parse_text(text, display, tree.sources, quoted=is_rules_file_name(real.name))
    if isinstance(parsed, Diagnostic):
        tree.diagnostics.append(parsed)
        return
    stack = include_stack + [(real, display)]
    for include in parsed.includes:
        child = path.parent / include.path
        outside = tree.scope.outside(child)
        if outside is not None:
            message = f"included file '{include.path}' {outside}"
            tree.diagnostics.append(tree.sources.diagnostic(include.location, message))
            continue
        child_display = os.path.normpath(os.path.join(os.path.dirname(display), include.path))
        _parse_into(tree, child, child_display, stack, include.location)
    tree.files.append(parsed)


def _read_rules_file(
    tree: ParsedTree, path: Path, display: str, include_location: SourceLocation | None
) -> str | None:
    """The text of a rules file: a regular file of at most ``MAX_RULES_BYTES`` of UTF-8;
    or None, with a diagnostic saying why not (at the ``include``, for an included file)."""
    try:
        text = read_regular_file(path, MAX_RULES_BYTES, "a rules file").decode("utf-8")
    except UnicodeDecodeError:
        reason = "not UTF-8 text"
    except UnusableFile as problem:
        reason = f"it {problem}"
    except OSError as error:
        reason = error.strerror or str(error)
    else:
        # Lines are counted at "\n" only, as the parser counts them (no newline translation).
        return text
    if include_location is None:  # the file asked for: the error is at its start
        tree.diagnostics.append(
            Diagnostic(SourceLocation(display, 1, 1), f"cannot read '{display}': {reason}")
        )
    else:
        tree.diagnostics.append(
            tree.sources.diagnostic(
                include_location, f"cannot read included file '{display}': {reason}"
            )
        )
    return None


# -- syntax errors in words ---------------------------------------------------------
#
# A syntax error is explained in three steps:
# 1. A '{' never closed: if a '}' inserted before the line of the error (or before the
#    unexpected word, or at the end of the file) lets the parser read the rest of that
#    line, the error is the missing '}', reported at the '{' still open on the parser's
#    stack.
# 2. Where the parser stopped: the text before the error is parsed alone, so that the
#    parser stops at its end in the state it was in before it saw the unexpected token
#    (a token it cannot take may first make it finish a rule, in a way that depends on
#    the token). Lark's ``UnexpectedInput.match_examples`` then finds the ``_CONTEXTS``
#    entry with an example that stops in the same LALR state. The examples are parsed
#    with the grammar of the day, so the table follows grammar changes; tests check that
#    each example still stops in its place, and that every place in a valid file where a
#    word may come next is in the table.
# 3. What was expected, in words: the terminals the parser takes there, each said from
#    its pattern (``Lark.get_terminal``): a keyword or punctuation as itself, the others
#    from ``_WORDS``; the context says what its names and keywords are.


@dataclass(frozen=True, eq=False)
class _Context:
    """A place in a rules file where the parser can stop, and how errors there are worded."""

    #: Texts that end at this place (in each of its LALR states).
    examples: tuple[str, ...]
    #: What may stand here, said first; ``{keywords}`` lists the keywords taken here.
    lead: tuple[str, ...] = ()
    #: ``{keywords}`` lists only the keywords that start this grammar rule.
    keywords_of: str = ""
    #: Terminals the lead says already (named, or keywords and punctuation as written).
    covers: frozenset[str] = frozenset()
    #: What a terminal means here ({"CAMEL": "a relation label"}).
    words: Mapping[str, str] = field(default_factory=dict)
    #: What an unknown word here is ("catalog field"); without it, "unexpected 'word'".
    unknown: str = ""
    #: What the snake_case names here are ("types"), for a CamelCase word written here.
    snake: str = "names here"
    #: What the CamelCase names here are ("relation labels"), for a snake_case word here.
    camel: str = ""
    #: The CamelCase names that may stand here: the case hint is given only for one of them.
    camel_known: Callable[[], Iterable[str]] | None = None
    #: The case hint is given only when the text after the word matches this (a production's '->').
    camel_when: str = ""
    #: Right after a statement's snake_case subject: a '(' means a call in the wrong case.
    calls: bool = False
    #: ';' and new lines only separate declarations here: not "the end of the statement".
    declarations: bool = False


def _inside(opening: str, items: Iterable[str]) -> tuple[str, ...]:
    """Texts that stop inside a block: after its '{', after a separator, after each item."""
    items = tuple(items)
    return (
        opening,
        f"{opening}\n",
        f"{opening} ;",
        f"{opening} {items[0]}\n",
        f"{opening} {items[0]};",
    ) + tuple(f"{opening} {item}" for item in items)


#: One of each catalog field, style, scene setting and statement: the parser is in a
#: different LALR state after each, so the examples stop after every one of them.
_FIELDS = (
    'noun "a"',
    'plural "a"',
    "size 1 x 1 x 1",
    "shape a",
    'mesh "a"',
    "colour #aaaaaa",
    "width 1",
    "max_length 1",
    "segments 1",
)
_ENTRY_FIELDS = ("clearance front 1", "access a", "access a b")
_STYLES = ("style s { }", "style s 2 { }", 'style s { noun "a" }', 'style s 2 { noun "a" }')
_SETTINGS = (
    "extent 1 x 1",
    "ground a",
    "walls",
    "start A",
    "max_depth 1",
    "max_nodes 1",
    'templates "a"',
    "square a",
    "line_of_sight a",
    "room 1 x 1",
    "room 1 x 1 { }",
    "room (1, 1) (2, 2) (1, 2) { }",
)
_ROOM_ITEMS = (
    "height 1",
    "door a 1 1",
    "door a 1 1 1",
    "door 1 1 1",
    "window a 1 1 1 1",
    "window 2 1 1 1 1",
)
_BLOCKS = ("{ }", "{ a }", "{ a; }", "{ ; }", "{ a; b }", "{ ; a }", "{\na\n}")
_STATEMENTS = (
    "A",
    "A()",
    "A(b)",
    "A(b, c)",
    "a as b",
    "a NextTo b",
    "a NextTo b NextTo c",
    "a as b NextTo c",
    "some a",
    "each a",
    "a #1",
    "a NextTo some b",
    "a NextTo each b",
    "a NextTo b #1",
) + tuple(
    f"a {block}" for block in _BLOCKS
)  # and "a", a bare subject: the context "after a subject"

_TARGET = ("a bound name", "'some TYPE'", "'each TYPE'", "'TYPE #N'")
_AFTER_SUBJECT_WORDS = {"CAMEL": "a relation label"}


#: Where the parser stops when the text before an error is a whole file (no examples:
#: a text that parses is at the top level).
_TOP_LEVEL = _Context(
    examples=(),
    lead=("a catalog entry ({keywords})", "a production"),
    keywords_of="kind",
    covers=frozenset({"CAMEL"}),
    camel="nonterminals",
    camel_when=r"\s*(->|\()",
    declarations=True,
)

_CONTEXTS: dict[str, _Context] = {
    "fields": _Context(
        examples=_inside("object a {", _FIELDS + _ENTRY_FIELDS + _STYLES),
        lead=("a field ({keywords})",),
        keywords_of="_entry_field",
        unknown="catalog field",
        declarations=True,
    ),
    "style fields": _Context(
        examples=_inside("object a { style s {", _FIELDS)
        + _inside("object a { style s 2 {", _FIELDS),
        lead=("a field ({keywords})",),
        keywords_of="_field",
        unknown="style field",
        declarations=True,
    ),
    "room": _Context(
        examples=("scene s { room",),
        lead=("the room's size 'W x D' or its corners '(x, z) (x, z) ...'",),
        covers=frozenset({"NUMBER", "("}),
    ),
    "room corners": _Context(
        examples=(
            "scene s { room (1, 1)",
            "scene s { room (1, 1) (2, 2)",
            "scene s { room (1, 1) (2, 2) (1, 2)",
        ),
        lead=("another corner '(x, z)'", "the room's block '{'", "the end of the room"),
        covers=frozenset({"(", "{"}),
    ),
    "room items": _Context(
        examples=_inside("scene s { room 1 x 1 {", _ROOM_ITEMS),
        lead=("the room's wall height, a door or a window ({keywords})",),
        keywords_of="_room_item",
        unknown="room item",
        declarations=True,
    ),
    "wall name": _Context(
        examples=("scene s { room 1 x 1 { door", "scene s { room 1 x 1 { window"),
        lead=("the wall: its side (north, east, south, west) or its number",),
        covers=frozenset({"NAME", "NUMBER"}),
    ),
    "scene settings": _Context(
        examples=_inside("scene s {", _SETTINGS),
        lead=("a scene setting ({keywords})",),
        keywords_of="_setting",
        unknown="scene setting",
        declarations=True,
    ),
    "alternative": _Context(
        examples=(
            "S ->",
            "S ->\n",
            "S -> { } |",
            "S -> { } |\n",
            "S -> { }\n|",
            "S -> { } | { } |",
            "S(a) ->",
        ),
        lead=("an alternative: a block '{' or a weight like '2:'",),
        covers=frozenset({"{", "NUMBER", "_NL"}),
    ),
    "block after a weight": _Context(
        examples=("S -> 2:", "S -> 2:\n", "S -> { } | 2:", "S -> { } | 2:\n"),
        lead=("a block '{'",),
        covers=frozenset({"{", "_NL"}),
    ),
    "statement": _Context(
        examples=(
            "S -> {",
            "S -> {\n",
            "S -> { ;",
            "S -> { a\n",
            "S -> { a;",
            "S -> { a;;",
            "S -> { a\n\n",
            "S -> { a;\n",
        ),
        lead=("a statement (a type, a nonterminal, a bound name, 'some', 'each' or a count)",),
        covers=frozenset({"NAME", "CAMEL", "NUMBER", "some", "each"}),
    ),
    "subject": _Context(
        examples=("S -> { 2", "S -> { 0.5?", "S -> { 2 0.5?", "S -> { 1..2", "S -> { 1..2 0.5?"),
        lead=("a type", "a nonterminal") + _TARGET,
        covers=frozenset({"NAME", "CAMEL", "some", "each"}),
    ),
    "after a subject": _Context(
        examples=("S -> { a", "S -> { 2 a", "S -> { 0.5? a", "S -> { 2 0.5? a", "S -> { 1..2 a"),
        words=_AFTER_SUBJECT_WORDS,
        camel="relation labels",
        camel_known=RELATIONS.names,
        calls=True,
    ),
    "after a statement part": _Context(
        examples=tuple(f"S -> {{ {statement}" for statement in _STATEMENTS),
        words=_AFTER_SUBJECT_WORDS,
        camel="relation labels",
        camel_known=RELATIONS.names,
    ),
    "target": _Context(
        examples=(
            "S -> { a NextTo",
            "S -> { a NextTo b NextTo",
            "S -> { A(",
            "S -> { A(b,",
            "S -> { A(b, c,",
        ),
        lead=_TARGET,
        covers=frozenset({"NAME", "some", "each"}),
        snake="bound names",
    ),
    "type": _Context(
        examples=("S -> { some", "S -> { each", "S -> { a NextTo some", "S -> { a NextTo each"),
        words={"NAME": "a type"},
        snake="types",
    ),
    "binding": _Context(
        examples=("S -> { a as",), words={"NAME": "a name to bind"}, snake="bound names"
    ),
    "parameters": _Context(
        examples=("P(", "P(a,"), words={"NAME": "a parameter name"}, snake="parameters"
    ),
    "start symbol": _Context(
        examples=("scene s { start",),
        words={"CAMEL": "a nonterminal"},
        camel="nonterminals",
        camel_when=r"[ \t]*($|[\n;}#])",
    ),
    "type name": _Context(
        examples=("object", "group", "path", "junction"),
        words={"NAME": "a type name"},
        snake="types",
    ),
    "style name": _Context(
        examples=("object a { style",), words={"NAME": "a style name"}, snake="style names"
    ),
    "scene name": _Context(
        examples=("scene",), words={"NAME": "a scene name"}, snake="scene names"
    ),
    "ground": _Context(
        examples=("scene s { ground",), words={"NAME": "a ground name"}, snake="ground names"
    ),
    "shape": _Context(
        examples=("object a { shape",), words={"NAME": "a shape name"}, snake="shape names"
    ),
}

#: The context of a place no example reaches: every terminal said on its own.
_ANYWHERE = _Context(examples=())

_END_OF_STATEMENT = "the end of the statement"
_SEPARATORS = ("_NL", ";")

#: What a terminal is, in words, where its pattern does not say it: regular expressions
#: by terminal name, punctuation by its text (a keyword is always said as itself).
_WORDS = {
    "NAME": "a name",
    "CAMEL": "a CamelCase name",
    "NUMBER": "a number",
    "STRING": 'a quoted string ("...")',
    "COLOUR": "a colour like #8b5a2b",
    "ORDINAL": "an ordinal like #1",
    "$END": "the end of the file",
    "{": "a block '{'",
}

#: A word as the user wrote it: letters, digits, '_' and inner '-' (``max-depth``).
_WORD = re.compile(r"[A-Za-z_][A-Za-z0-9_]*(?:-[A-Za-z0-9_]+)*")
_WORD_BEFORE = re.compile(r"[A-Za-z_][A-Za-z0-9_]*$")


def _syntax_diagnostic(error: ParseStop, text: str, file: str, sources: SourceTexts) -> Diagnostic:
    unclosed = _unclosed_block(error, text)
    if unclosed is not None:
        brace, message = unclosed
        assert brace.line is not None and brace.column is not None  # lexed from the text
        return sources.diagnostic(SourceLocation(file, brace.line, brace.column), message)
    offset, message = _explain(error, text)
    line = text.count("\n", 0, offset) + 1
    column = offset - (text.rfind("\n", 0, offset) + 1) + 1
    return sources.diagnostic(SourceLocation(file, line, column), message)


def _literal(terminal: str) -> str | None:
    """The text of a keyword or punctuation terminal (``AS`` -> ``as``); None for the others."""
    pattern = lalr_parser().get_terminal(terminal).pattern
    return pattern.value if pattern.type == "str" else None


def _error_offset(error: ParseStop, text: str) -> int:
    """Where in ``text`` the parser stopped (its length: at the end of the file)."""
    if isinstance(error, UnexpectedCharacters):
        assert error.pos_in_stream is not None  # the lexer stops at a place in the text
        return error.pos_in_stream
    if error.token.type == "$END":
        return len(text)
    return error.token.start_pos


# -- 1. a '{' never closed ----------------------------------------------------------


def _unclosed_block(error: ParseStop, text: str) -> tuple[Token, str] | None:
    """The '{' that the error shows is never closed, and the message saying so; None if
    the text has a '}' for every '{', or no '}' lets the parser read past the error."""
    braces = [match.group() for match in _BRACES.finditer(text)]
    unmatched = braces.count("{") - braces.count("}")
    stack = error.interactive_parser.parser_state.value_stack
    # A '{' is dropped from the tree when its block is reduced, so every '{' token still
    # on the stack is a block that has not been closed yet.
    opened = [
        index
        for index, value in enumerate(stack)
        if isinstance(value, Token) and _literal(value.type) == "{"
    ]
    offset = _error_offset(error, text)
    # With the '}' the parser must read the rest of the error's line: one more word is
    # not enough ("scene s { Extent 3 }" reads 'Extent' as a production's name).
    line_end = text.find("\n", offset)
    line_end = len(text) if line_end < 0 else line_end
    for missing in range(1, min(unmatched, len(opened)) + 1):
        closing = "}\n" * missing
        for point, where in _closing_points(text, offset):
            if _reads_past(text[:point] + closing + text[point:], line_end + len(closing)):
                innermost = opened[-1]
                owner = _block_owner(stack, innermost)
                return stack[innermost], (
                    f"the block {f'of {owner} ' if owner else ''}opened here is never "
                    f"closed (missing '}}' {where})"
                )
    return None


#: Strings, comments (a '#' that no letter or digit follows, as one does in a colour or
#: an ordinal) and braces: the braces found are those outside strings and comments.
_BRACES = re.compile(r'"[^"\n]*"|#(?![0-9A-Za-z])[^\n]*|[{}]')


def _closing_points(text: str, offset: int) -> list[tuple[int, str]]:
    """Where a missing '}' may go, and how the message says where."""
    if offset == len(text):
        return [(offset, "at the end of the file")]
    line_start = text.rfind("\n", 0, offset) + 1
    line = text.count("\n", 0, offset) + 1
    points = [(line_start, f"before line {line}")]
    if text[line_start:offset].strip():
        word = _WORD.match(text, offset)
        points.append((offset, f"before '{word.group() if word else text[offset]}' on line {line}"))
    return points


def _reads_past(text: str, offset: int) -> bool:
    """Whether ``text`` parses, or fails only after ``offset``."""
    try:
        lalr_parser().parse(text)
    except (UnexpectedToken, UnexpectedCharacters) as error:
        return _error_offset(error, text) > offset
    return True


def _block_owner(stack: list, brace: int) -> str:
    """What the '{' at ``stack[brace]`` opens, in words ("object 'table'", "production
    'Stall'", "'stall'" for a statement's block), or "" if the stack does not say."""
    for index in range(brace - 1, -1, -1):
        value = stack[index]
        if isinstance(value, Tree) and value.data == "kind":
            return f"{value.children[0]} '{stack[index + 1]}'"
        if isinstance(value, Tree) and value.data == "_subject":
            return f"'{next(value.scan_values(lambda v: isinstance(v, Token)))}'"
        literal = _literal(value.type) if isinstance(value, Token) else None
        if literal in ("scene", "style"):
            return f"{literal} '{stack[index + 1]}'"
        if literal in ("->", "|"):
            head = next(
                (
                    at
                    for at in range(index - 1, -1, -1)
                    if isinstance(stack[at], Token) and stack[at].type == "CAMEL"
                ),
                None,
            )
            if head is None:
                return ""
            production = f"production '{stack[head]}'"
            earlier = sum(
                1
                for item in stack[head:index]
                if isinstance(item, Tree)
                for subtree in item.iter_subtrees()
                if subtree.data == "alternative"
            )
            return f"alternative {earlier + 1} of {production}" if literal == "|" else production
        if literal == "{":
            return ""
    return ""


# -- 2. where the parser stopped ----------------------------------------------------


class _StateKey(int):
    """The number of an LALR state, compared by ``match_examples`` in place of lark's
    parser state, whose equality also counts the stack depth: with it an example would
    only match stops nested exactly as deep as its own (in the first statement of a
    top-level block, say); with the state alone it stands for its place at every depth."""

    @classmethod
    def of(cls, error: ParseStop) -> _StateKey | None:
        if isinstance(error.state, _StateKey):
            return error.state
        position = getattr(error.state, "position", None)
        return cls(position) if isinstance(position, int) else None


@functools.cache
def _example_stop(example: str) -> ParseStop | None:
    """The error with which the parser stops at the end of an example (None if it parses)."""
    try:
        lalr_parser().parse(example)
    except (UnexpectedToken, UnexpectedCharacters) as error:
        error.state = _StateKey.of(error)
        return error
    return None


def _parse_example(example: str) -> Tree:
    """``match_examples``'s parse function: raises the example's (cached) error (every
    example has one; one that parsed would be parsed again for its tree)."""
    error = _example_stop(example)
    if error is not None:
        raise error.with_traceback(None)
    return lalr_parser().parse(example)


def _context(stop: ParseStop) -> _Context:
    """The ``_CONTEXTS`` entry with an example that stops where ``stop`` does."""
    stop.state = _StateKey.of(stop)
    if stop.state is None:
        return _ANYWHERE
    name = stop.match_examples(
        _parse_example, {name: context.examples for name, context in _CONTEXTS.items()}
    )
    return _CONTEXTS[name] if name else _ANYWHERE


def _place(error: ParseStop, text: str, offset: int) -> tuple[_Context, frozenset[str]]:
    """Where the parser was before the unexpected input at ``offset``, and what it takes there."""
    prefix = text[:offset]
    try:
        lalr_parser().parse(prefix)
    except (UnexpectedToken, UnexpectedCharacters) as stop:
        if _error_offset(stop, prefix) < len(
            prefix
        ):  # the text before reads otherwise alone (a new line before '|')
            stop = error
        return _context(stop), frozenset(stop.interactive_parser.accepts())
    parser = lalr_parser().parse_interactive(prefix)
    parser.exhaust_lexer()
    return _TOP_LEVEL, frozenset(parser.accepts())


# -- 3. what was expected, in words ---------------------------------------------------


def _explain(error: ParseStop, text: str) -> tuple[int, str]:
    """Where a syntax error is (an offset in ``text``) and what it is, in one sentence."""
    offset = _word_start(text, _error_offset(error, text))
    context, accepts = _place(error, text, offset)
    hint = ""
    if isinstance(error, UnexpectedCharacters):
        unexpected = f"unexpected character '{text[offset]}'"
    elif offset == len(text):
        unexpected = "unexpected end of file"
    elif error.token.type == "_NL":
        unexpected = "unexpected end of line"
    elif match := _WORD.match(text, offset):
        word = match.group()
        hint = _case_mix_up(context, word, accepts, text[offset + len(word) :])
        unexpected = (
            f"unknown {context.unknown} '{word}'"
            if context.unknown and not hint
            else f"unexpected '{word}'"
        )
        hint = hint or _keyword_meant(word, _keywords(accepts))
    else:
        unexpected = f"unexpected '{error.token}'"
        before = _WORD_BEFORE.search(text, 0, offset)
        if context.calls and str(error.token) == "(" and before and before.group()[0].islower():
            unexpected += f" after '{before.group()}'"
            hint = case_hint("nonterminals are CamelCase", camel_case(before.group()))
    if hint:
        return offset, unexpected + hint
    expected = _expected(context, accepts)
    return offset, unexpected + (f"; expected {_join_words(expected)}" if expected else "")


def _word_start(text: str, offset: int) -> int:
    """Where the word that ``offset`` is in starts: a lexer that expects only keywords
    reads ``nouns`` as the keyword ``noun`` and an unexpected ``s``, and the error is
    about the whole word, where the keyword stood."""
    start = offset
    while start > 0 and (text[start - 1].isalnum() or text[start - 1] == "_"):
        start -= 1
    word = _WORD.match(text, start)
    return start if word and word.end() > offset else offset


def _keyword_meant(word: str, keywords: list[str]) -> str:
    """ "did you mean" the keyword nearest ``word``, or the longest one of four letters or
    more that it starts with (``start_symbol``: 'start'); nothing for a single letter."""
    if len(word) < 2:
        return ""
    prefixes = sorted(
        (keyword for keyword in keywords if len(keyword) >= 4 and word.startswith(keyword)), key=len
    )
    return did_you_mean(word, keywords) or (
        did_you_mean(prefixes[-1], prefixes[-1:]) if prefixes else ""
    )


def _case_mix_up(context: _Context, word: str, accepts: frozenset[str], after: str) -> str:
    """The case hint for a word written in the other case than the names that may stand
    here ("; types are snake_case: did you mean 'market_stand'?"), or ""."""
    if word[0].isupper() and "NAME" in accepts and "CAMEL" not in accepts:
        if word in RELATIONS or after.startswith("("):
            return ""  # a relation label or a call where a name must stand: not a matter of case
        return case_hint(f"{context.snake} are snake_case", snake_case(word))
    if word[0].isupper() or "CAMEL" not in accepts or "NAME" in accepts or not context.camel:
        return ""
    convention = f"{context.camel} are CamelCase"
    if context.camel_known is not None:
        return case_mix_up(word, context.camel_known(), convention)
    if context.camel_when and not re.match(context.camel_when, after):
        return ""
    return case_hint(convention, camel_case(word))


def _keywords(accepts: Iterable[str], rule: str = "") -> list[str]:
    """The keywords among ``accepts`` (those that start ``rule``, if given), in grammar order."""
    first = _first_terminals(rule) if rule else None
    return [
        literal
        for terminal in lalr_parser().terminals
        if terminal.name in accepts
        and (first is None or terminal.name in first)
        and (literal := _literal(terminal.name))
        and literal.isidentifier()
    ]


@functools.cache
def _first_terminals(rule: str) -> frozenset[str]:
    """The terminals that can start the grammar rule ``rule`` (its first symbols)."""
    first: set[str] = set()
    pending, seen = [rule], {rule}
    while pending:
        origin = pending.pop()
        for grammar_rule in lalr_parser().rules:
            if grammar_rule.origin.name != origin or not grammar_rule.expansion:
                continue
            symbol = grammar_rule.expansion[0]
            if symbol.is_term:
                first.add(symbol.name)
            elif symbol.name not in seen:
                seen.add(symbol.name)
                pending.append(symbol.name)
    return frozenset(first)


def _expected(context: _Context, accepts: frozenset[str]) -> list[str]:
    """What the parser takes here, as phrases: the context's lead, the keywords, the
    other terminals (named ones, then punctuation), the end of the statement and of the file."""
    words: list[str] = []
    covered = set(context.covers)
    lead_keywords = _keywords(accepts, context.keywords_of)
    for phrase in context.lead:
        words.append(phrase.replace("{keywords}", ", ".join(lead_keywords)))
        if "{keywords}" in phrase:
            covered.update(lead_keywords)
    ends_statement = not context.declarations and any(
        name in accepts and name not in covered for name in _SEPARATORS
    )
    terminals = [terminal for terminal in lalr_parser().terminals if terminal.name in accepts]
    keywords = [
        terminal for terminal in terminals if (_literal(terminal.name) or "").isidentifier()
    ]
    others = sorted(
        (terminal for terminal in terminals if terminal not in keywords),
        key=lambda terminal: terminal.pattern.type == "str",
    )  # named terminals first
    for terminal in keywords + others:
        said_as = _literal(terminal.name) or terminal.name
        if said_as in covered or said_as in _SEPARATORS or (said_as == "}" and ends_statement):
            continue  # a '}' is the end of a block's last statement
        words.append(
            context.words.get(said_as)
            or _WORDS.get(said_as)
            or (f"'{said_as}'" if _literal(terminal.name) else said_as.lower())
        )
    if ends_statement:
        words.append(_END_OF_STATEMENT)
    if "$END" in accepts:
        words.append(_WORDS["$END"])
    return words


def _join_words(words: list[str]) -> str:
    if len(words) <= 1:
        return "".join(words)
    return ", ".join(words[:-1]) + " or " + words[-1]
