"""The places in a rules file where a syntax error can stop the parser, and their wording.

``stopped_at`` finds where the parser was before the unexpected input: the text before
the error is parsed alone, so that the parser stops at its end in the state it was in
before it saw the unexpected token (a token it cannot take may first make it finish a
rule, in a way that depends on the token). Lark's ``UnexpectedInput.match_examples``
then finds the ``_CONTEXTS`` entry with an example that stops in the same LALR state;
each ``Context`` says how errors at its place are worded. The examples are parsed with
the grammar of the day, so the table follows grammar changes; tests check that each
example still stops in its place, and that every place in a valid file where a word may
come next is in the table.
"""

from __future__ import annotations

import functools
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass, field

from lark import Tree
from lark.exceptions import UnexpectedCharacters, UnexpectedToken

from scenewright.core.relations import RELATIONS

from .rules_lark import ParseStop, error_offset, lalr_parser


@dataclass(frozen=True, eq=False)
class Context:
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
_ENTRY_FIELDS = ("clearance front 1", "access a", "access a b", "wall_gap 1", "network a")
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
_TOP_LEVEL = Context(
    examples=(),
    lead=("a catalog entry ({keywords})", "a production"),
    keywords_of="kind",
    covers=frozenset({"CAMEL"}),
    camel="nonterminals",
    camel_when=r"\s*(->|\()",
    declarations=True,
)

_CONTEXTS: dict[str, Context] = {
    "fields": Context(
        examples=_inside("object a {", _FIELDS + _ENTRY_FIELDS + _STYLES),
        lead=("a field ({keywords})",),
        keywords_of="_entry_field",
        unknown="catalog field",
        declarations=True,
    ),
    "style fields": Context(
        examples=_inside("object a { style s {", _FIELDS)
        + _inside("object a { style s 2 {", _FIELDS),
        lead=("a field ({keywords})",),
        keywords_of="_field",
        unknown="style field",
        declarations=True,
    ),
    "room": Context(
        examples=("scene s { room",),
        lead=("the room's size 'W x D' or its corners '(x, z) (x, z) ...'",),
        covers=frozenset({"NUMBER", "("}),
    ),
    "room corners": Context(
        examples=(
            "scene s { room (1, 1)",
            "scene s { room (1, 1) (2, 2)",
            "scene s { room (1, 1) (2, 2) (1, 2)",
        ),
        lead=("another corner '(x, z)'", "the room's block '{'", "the end of the room"),
        covers=frozenset({"(", "{"}),
    ),
    "room items": Context(
        examples=_inside("scene s { room 1 x 1 {", _ROOM_ITEMS),
        lead=("the room's wall height, a door or a window ({keywords})",),
        keywords_of="_room_item",
        unknown="room item",
        declarations=True,
    ),
    "wall name": Context(
        examples=("scene s { room 1 x 1 { door", "scene s { room 1 x 1 { window"),
        lead=("the wall: its side (north, east, south, west) or its number",),
        covers=frozenset({"NAME", "NUMBER"}),
    ),
    "scene settings": Context(
        examples=_inside("scene s {", _SETTINGS),
        lead=("a scene setting ({keywords})",),
        keywords_of="_setting",
        unknown="scene setting",
        declarations=True,
    ),
    "alternative": Context(
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
    "block after a weight": Context(
        examples=("S -> 2:", "S -> 2:\n", "S -> { } | 2:", "S -> { } | 2:\n"),
        lead=("a block '{'",),
        covers=frozenset({"{", "_NL"}),
    ),
    "statement": Context(
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
    "subject": Context(
        examples=("S -> { 2", "S -> { 0.5?", "S -> { 2 0.5?", "S -> { 1..2", "S -> { 1..2 0.5?"),
        lead=("a type", "a nonterminal") + _TARGET,
        covers=frozenset({"NAME", "CAMEL", "some", "each"}),
    ),
    "after a subject": Context(
        examples=("S -> { a", "S -> { 2 a", "S -> { 0.5? a", "S -> { 2 0.5? a", "S -> { 1..2 a"),
        words=_AFTER_SUBJECT_WORDS,
        camel="relation labels",
        camel_known=RELATIONS.names,
        calls=True,
    ),
    "after a statement part": Context(
        examples=tuple(f"S -> {{ {statement}" for statement in _STATEMENTS),
        words=_AFTER_SUBJECT_WORDS,
        camel="relation labels",
        camel_known=RELATIONS.names,
    ),
    "target": Context(
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
    "type": Context(
        examples=("S -> { some", "S -> { each", "S -> { a NextTo some", "S -> { a NextTo each"),
        words={"NAME": "a type"},
        snake="types",
    ),
    "binding": Context(
        examples=("S -> { a as",), words={"NAME": "a name to bind"}, snake="bound names"
    ),
    "parameters": Context(
        examples=("P(", "P(a,"), words={"NAME": "a parameter name"}, snake="parameters"
    ),
    "start symbol": Context(
        examples=("scene s { start",),
        words={"CAMEL": "a nonterminal"},
        camel="nonterminals",
        camel_when=r"[ \t]*($|[\n;}#])",
    ),
    "type name": Context(
        examples=("object", "group", "path", "junction"),
        words={"NAME": "a type name"},
        snake="types",
    ),
    "style name": Context(
        examples=("object a { style",), words={"NAME": "a style name"}, snake="style names"
    ),
    "scene name": Context(examples=("scene",), words={"NAME": "a scene name"}, snake="scene names"),
    "ground": Context(
        examples=("scene s { ground",), words={"NAME": "a ground name"}, snake="ground names"
    ),
    "shape": Context(
        examples=("object a { shape",), words={"NAME": "a shape name"}, snake="shape names"
    ),
}

#: The context of a place no example reaches: every terminal said on its own.
_ANYWHERE = Context(examples=())


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


def _context(stop: ParseStop) -> Context:
    """The ``_CONTEXTS`` entry with an example that stops where ``stop`` does."""
    stop.state = _StateKey.of(stop)
    if stop.state is None:
        return _ANYWHERE
    name = stop.match_examples(
        _parse_example, {name: context.examples for name, context in _CONTEXTS.items()}
    )
    return _CONTEXTS[name] if name else _ANYWHERE


def stopped_at(error: ParseStop, text: str, offset: int) -> tuple[Context, frozenset[str]]:
    """Where the parser was before the unexpected input at ``offset``, and what it takes there."""
    prefix = text[:offset]
    try:
        lalr_parser().parse(prefix)
    except (UnexpectedToken, UnexpectedCharacters) as stop:
        if error_offset(stop, prefix) < len(
            prefix
        ):  # the text before reads otherwise alone (a new line before '|')
            stop = error
        return _context(stop), frozenset(stop.interactive_parser.accepts())
    parser = lalr_parser().parse_interactive(prefix)
    parser.exhaust_lexer()
    return _TOP_LEVEL, frozenset(parser.accepts())
