"""The rules language's LALR parser, and what its parse errors say about where they stopped.

``lalr_parser`` gives the parser of the grammar in ``rules.lark``, once per process.
Building its tables from the grammar costs a command more than its whole layout, so
they are stored beside the grammar (``rules_lark_tables.json``, written by ``make
parser-tables``) and loaded instead, when they were made
from this very grammar with this lark version (else the parser is built as before). Its
post-lexer keeps keywords whole words (``doors`` is not the keyword ``door`` and a
name ``s``). A parse stops with one of the two errors of ``ParseStop``; ``error_offset``
says where in the text, and ``terminal_literal`` gives a keyword's or punctuation's
text, for the messages that explain a syntax error in words.
"""

from __future__ import annotations

import functools
import hashlib
import json
import threading
from collections.abc import Iterable
from importlib import resources
from pathlib import Path
from typing import Any

import lark
from lark import Lark, Token
from lark.exceptions import UnexpectedCharacters, UnexpectedToken
from lark.grammar import Rule
from lark.lexer import TerminalDef

#: The two errors lark's LALR parser stops with: a token it cannot take, a character
#: no token starts with.
ParseStop = UnexpectedToken | UnexpectedCharacters


#: Building the parser twice at once fails: lark compiles the grammar's literals with
#: ``ast.literal_eval``, which CPython 3.11 does not allow in two threads at a time
#: ("AST constructor recursion depth mismatch", seen in dask's threaded workers).
_BUILDING = threading.Lock()


#: The stored parser tables, beside the grammar.
TABLES = "rules_lark_tables.json"
#: How the parser is built; the stored tables hold these options.
OPTIONS: dict[str, Any] = {
    "parser": "lalr",
    "lexer": "contextual",
    "propagate_positions": True,
    "maybe_placeholders": True,
}


def lalr_parser() -> Lark:
    """The rules language's LALR parser, made once per process (module docstring)."""
    with _BUILDING:
        return _parser()


@functools.cache
def _parser() -> Lark:
    grammar = _grammar()
    whole_words = _WholeKeywords()
    parser = _stored_parser(grammar, whole_words)
    if parser is None:
        parser = Lark(grammar, postlex=whole_words, **OPTIONS)
    whole_words.keywords = frozenset(
        terminal.name
        for terminal in parser.terminals
        if terminal.pattern.type == "str" and terminal.pattern.value[:1].isalpha()
    )
    return parser


def _stored_parser(grammar: str, whole_words: _WholeKeywords) -> Lark | None:
    """The parser from the stored tables, if they were made from ``grammar`` with this
    lark and load whole; else None (the parser is then built: slower, never wrong)."""
    try:
        stored = stored_tables()
        if stored is None or stored.get("made_from") != made_from(grammar):
            return None
        return Lark.__new__(Lark)._load(stored["parser"], postlex=whole_words)
    except Exception:  # a damaged file fails in many ways (lark asserts): building is never wrong
        return None


def _grammar() -> str:
    return resources.files("scenewright.generator").joinpath("rules.lark").read_text()


def made_from(grammar: str) -> dict[str, str]:
    """What the parser tables of ``grammar`` depend on: the grammar and lark's version."""
    return {
        "grammar_sha256": hashlib.sha256(grammar.encode()).hexdigest(),
        "lark": lark.__version__,
    }


def stored_tables() -> dict[str, Any] | None:
    """The stored tables (``TABLES``) and what they were made from; None if missing."""
    try:
        text = resources.files("scenewright.generator").joinpath(TABLES).read_text()
    except FileNotFoundError:
        return None
    return json.loads(text, object_hook=_decoded)


def write_tables(path: Path) -> None:
    """Build the parser from the grammar and store its tables at ``path``."""
    grammar = _grammar()
    parser = Lark(grammar, **OPTIONS)
    data, memo = parser.memo_serialize([TerminalDef, Rule])
    stored = {"made_from": made_from(grammar), "parser": {"data": data, "memo": memo}}
    path.write_text(json.dumps(_encoded(stored), separators=(",", ":"), sort_keys=True) + "\n")


# JSON has neither tuples nor keys other than strings; lark's tables have both.
def _encoded(value: Any) -> Any:
    if isinstance(value, dict):
        if all(isinstance(key, str) for key in value):
            return {key: _encoded(item) for key, item in value.items()}
        return {"__items__": [[_encoded(key), _encoded(item)] for key, item in value.items()]}
    if isinstance(value, tuple):
        return {"__tuple__": [_encoded(item) for item in value]}
    if isinstance(value, list):
        return [_encoded(item) for item in value]
    return value


def _decoded(value: dict) -> Any:
    if len(value) == 1 and "__items__" in value:
        return {(tuple(k) if isinstance(k, list) else k): item for k, item in value["__items__"]}
    if len(value) == 1 and "__tuple__" in value:
        return tuple(value["__tuple__"])
    return value


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


def terminal_literal(terminal: str) -> str | None:
    """The text of a keyword or punctuation terminal (``AS`` -> ``as``); None for the others."""
    pattern = lalr_parser().get_terminal(terminal).pattern
    return pattern.value if pattern.type == "str" else None


def error_offset(error: ParseStop, text: str) -> int:
    """Where in ``text`` the parser stopped (its length: at the end of the file)."""
    if isinstance(error, UnexpectedCharacters):
        assert error.pos_in_stream is not None  # the lexer stops at a place in the text
        return error.pos_in_stream
    if error.token.type == "$END":
        return len(text)
    return error.token.start_pos
