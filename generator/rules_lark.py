"""The rules language's LALR parser, and what its parse errors say about where they stopped.

``lalr_parser`` builds the parser from the grammar in ``rules.lark`` once per process;
its post-lexer keeps keywords whole words (``doors`` is not the keyword ``door`` and a
name ``s``). A parse stops with one of the two errors of ``ParseStop``; ``error_offset``
says where in the text, and ``terminal_literal`` gives a keyword's or punctuation's
text, for the messages that explain a syntax error in words.
"""

from __future__ import annotations

import functools
import threading
from collections.abc import Iterable
from importlib import resources

from lark import Lark, Token
from lark.exceptions import UnexpectedCharacters, UnexpectedToken

#: The two errors lark's LALR parser stops with: a token it cannot take, a character
#: no token starts with.
ParseStop = UnexpectedToken | UnexpectedCharacters


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
