"""Rules text -> ``rules_ast`` dataclasses, following includes; syntax errors in words.

``parse_text`` parses one file with the LALR grammar in ``rules.lark`` (built once and
cached) and a lark ``Transformer``. ``parse_tree`` parses a file and, depth-first, the
files it includes (paths relative to the including file; each file once; a cycle is
reported at the ``include`` that closes it). Lark's exceptions become ``Diagnostic``s
that say what was expected in words, never in terminal names.
"""

from __future__ import annotations

import functools
import os
from dataclasses import dataclass, field
from importlib import resources
from pathlib import Path

from lark import Lark, Token, Transformer, v_args
from lark.exceptions import UnexpectedCharacters, UnexpectedToken

from . import rules_ast as ast
from .catalog import KINDS, SourceLocation
from .rules_errors import Diagnostic, SourceTexts, did_you_mean

#: Catalog fields and scene settings, as the grammar spells them (for error messages).
ENTRY_FIELDS = ("noun", "plural", "size", "shape", "mesh", "colour", "width", "max_length", "segments")
SCENE_SETTINGS = ("extent", "ground", "walls", "start", "max_depth", "max_nodes", "templates")


@functools.cache
def _parser() -> Lark:
    grammar = resources.files("scenewright.generator").joinpath("rules.lark").read_text()
    return Lark(grammar, parser="lalr", lexer="contextual", propagate_positions=True, maybe_placeholders=True)


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
        if data in ENTRY_FIELDS or (data in SCENE_SETTINGS and data != "start"):
            return self._setting(str(data), meta, children)
        if data == "start_symbol":
            return self._setting("start", meta, children)
        return super().__default__(data, children, meta)

    def kind(self, children):
        return children[0]

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
        return ast.Reference("nth", str(name), self._at(meta), int(ordinal[1:]))

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
        low, high = children
        return ast.Count(float(low), float(high if high is not None else low), self._at(meta))

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
        return ast.Alternative(float(weight) if weight is not None else None, block.statements, self._at(meta))

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


def parse_text(text: str, file: str, sources: SourceTexts | None = None) -> ast.RulesFile | Diagnostic:
    """Parse one file's text; a syntax error is returned as its ``Diagnostic``."""
    sources = sources or SourceTexts()
    sources.add(file, text)
    try:
        tree = _parser().parse(text)
    except (UnexpectedToken, UnexpectedCharacters) as error:  # the two LALR parse errors
        return _syntax_diagnostic(error, text, file, sources)
    return _ToAst(file).transform(tree)


# -- files and includes -------------------------------------------------------------


@dataclass
class ParsedTree:
    """A rules file and everything it includes, parsed (or the diagnostics why not).

    ``files`` is in depth-first include order, each included file before the file
    that includes it; ``paths`` maps each file's display name to its real path.
    """

    files: list[ast.RulesFile] = field(default_factory=list)
    paths: dict[str, Path] = field(default_factory=dict)
    sources: SourceTexts = field(default_factory=SourceTexts)
    diagnostics: list[Diagnostic] = field(default_factory=list)


def parse_tree(path: Path, display: str) -> ParsedTree:
    """Parse ``path`` (shown as ``display`` in diagnostics) and the files it includes."""
    tree = ParsedTree()
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
            chain = " -> ".join([name for _, name in include_stack[index:]] + [display])
            tree.diagnostics.append(tree.sources.diagnostic(include_location, f"include cycle: {chain}"))
            return
    if any(known.resolve() == real for known in tree.paths.values()):
        return  # already included along another route: its declarations are in once
    try:
        # newline="": positions count lines as the parser does, at "\n" only
        with open(path, encoding="utf-8", newline="") as stream:
            text = stream.read()
    except (OSError, UnicodeDecodeError) as error:
        reason = "not UTF-8 text" if isinstance(error, UnicodeDecodeError) else (error.strerror or str(error))
        if include_location is None:  # the file asked for: the error is at its start
            tree.diagnostics.append(Diagnostic(SourceLocation(display, 1, 1), f"cannot read '{display}': {reason}"))
        else:
            tree.diagnostics.append(
                tree.sources.diagnostic(include_location, f"cannot read included file '{display}': {reason}")
            )
        return
    tree.paths[display] = path
    parsed = parse_text(text, display, tree.sources)
    if isinstance(parsed, Diagnostic):
        tree.diagnostics.append(parsed)
        return
    stack = include_stack + [(real, display)]
    for include in parsed.includes:
        child_display = os.path.normpath(os.path.join(os.path.dirname(display), include.path))
        _parse_into(tree, path.parent / include.path, child_display, stack, include.location)
    tree.files.append(parsed)


# -- syntax errors in words ---------------------------------------------------------

_END_OF_STATEMENT = "the end of the statement"

#: What each terminal is, in words; keyword terminals not listed are quoted as is.
_WORDS = {
    "NAME": "a name",
    "NUMBER": "a number",
    "STRING": 'a quoted string ("...")',
    "COLOUR": "a colour like #8b5a2b",
    "ORDINAL": "an ordinal like #1",
    "_NL": _END_OF_STATEMENT,
    "SEMICOLON": _END_OF_STATEMENT,
    "$END": "the end of the file",
    "LBRACE": "a block '{'",
    "RBRACE": "'}'",
    "LPAR": "'('",
    "RPAR": "')'",
    "COMMA": "','",
    "COLON": "':'",
    "QMARK": "'?'",
    "VBAR": "'|'",
}


def _terminal_text(name: str) -> str:
    """The literal text of a keyword or punctuation terminal (``AS`` -> ``as``)."""
    for terminal in _parser().terminals:
        if terminal.name == name and terminal.pattern.type == "str":
            return terminal.pattern.value
    return name.lower()


def _expected_words(expected: set[str]) -> list[str]:
    """The terminals a parser state accepts, as a short list of phrases.

    A state is recognised by a keyword it accepts (``noun``: inside a catalog entry;
    ``extent``: a scene block; ``object``: the top level; ``some``: where a subject or
    target may stand), so its whole family of keywords is said in one phrase.
    """
    if expected == {"NUMBER", "LBRACE", "_NL"}:  # after '->' or '|' (a newline may come first)
        return ["an alternative: a block '{' or a weight like '2:'"]
    keywords = {_terminal_text(name) for name in expected if name not in _WORDS and name not in ("NAME", "CAMEL")}
    words: list[str] = []
    if "noun" in keywords:
        words.append("a field (" + ", ".join(ENTRY_FIELDS + ("style",)) + ")")
        keywords -= set(ENTRY_FIELDS) | {"style"}
    if "extent" in keywords:
        words.append("a scene setting (" + ", ".join(SCENE_SETTINGS) + ")")
        keywords -= set(SCENE_SETTINGS)
    if "object" in keywords:  # the top level
        words.append("a catalog entry (" + ", ".join(KINDS) + ")")
        keywords -= set(KINDS)
        if "CAMEL" in expected:
            words.append("a production")
    elif "some" in keywords and "NUMBER" in expected:  # the start of a statement
        words.append("a statement (a type, a nonterminal, a bound name, 'some', 'each' or a count)")
        keywords -= {"some", "each"}
    elif "some" in keywords and "CAMEL" in expected:  # a subject after its count or '?'
        words.append("a type, a nonterminal, a bound name, 'some TYPE', 'each TYPE' or 'TYPE #N'")
        keywords -= {"some", "each"}
    elif "some" in keywords:  # a relation's target or a call's argument
        words.append("a bound name, 'some TYPE', 'each TYPE' or 'TYPE #N'")
        keywords -= {"some", "each"}
    elif "CAMEL" in expected:  # after a subject a label; after 'start' a nonterminal
        words.append("a relation label" if "LBRACE" in expected else "a nonterminal")
    elif "NAME" in expected:
        words.append(_WORDS["NAME"])
    if "as" in keywords:
        words.insert(0, "'as'")
        keywords.discard("as")
    if "->" in keywords:
        words.append("'->'")
        keywords.discard("->")
    words.extend(f"'{keyword}'" for keyword in sorted(keywords))
    # A statement may end with either; a newline alone is only allowed layout (after '->').
    # Between declarations, fields and scene settings, separators are only layout.
    in_declarations = any(word.startswith(("a catalog entry", "a field", "a scene setting")) for word in words)
    ends_statement = "SEMICOLON" in expected and not in_declarations
    for name in ("NUMBER", "STRING", "COLOUR", "ORDINAL", "LPAR", "RPAR", "COMMA", "COLON", "QMARK",
                 "VBAR", "LBRACE", "RBRACE", "_NL", "SEMICOLON", "$END"):
        if name not in expected or (name == "RBRACE" and ends_statement):
            continue
        if name in ("_NL", "SEMICOLON") and not ends_statement:
            continue
        if name == "NUMBER" and any("count" in word for word in words):
            continue
        if _WORDS[name] not in words:
            words.append(_WORDS[name])
    return words


def _join_words(words: list[str]) -> str:
    if len(words) <= 1:
        return "".join(words)
    return ", ".join(words[:-1]) + " or " + words[-1]


def _describe_token(token: Token) -> str:
    if token.type == "$END":
        return "end of file"
    if token.type == "_NL":
        return "end of line"
    return f"'{token}'"


def _end_position(text: str) -> tuple[int, int]:
    lines = text.split("\n")
    return len(lines), len(lines[-1]) + 1


def _syntax_diagnostic(
    error: UnexpectedToken | UnexpectedCharacters, text: str, file: str, sources: SourceTexts
) -> Diagnostic:
    # Lark's ``expected`` is the LALR state's lookahead set, which merges contexts (a
    # statement's subject would seem to accept ')' because an argument does); asking the
    # parser where it failed which terminals it takes gives the exact set.
    expected = set(error.interactive_parser.accepts())
    if isinstance(error, UnexpectedCharacters):
        line, column = error.line, error.column
        message = f"unexpected character '{text[error.pos_in_stream]}'"
    elif error.token.type == "$END":
        line, column = _end_position(text)
        message = "unexpected end of file"
    else:
        line, column = error.token.line, error.token.column
        message = _unexpected_word_message(error.token, expected)
    words = _expected_words(expected)
    if words and "did you mean" not in message:
        message += f"; expected {_join_words(words)}"
    line = max(1, min(line or 1, len(text.split("\n"))))
    column = max(1, column or 1)
    return sources.diagnostic(SourceLocation(file, line, column), message)


def _unexpected_word_message(token: Token, expected: set[str]) -> str:
    """The message for an unexpected token, naming a misspelt field or setting."""
    keywords = {_terminal_text(name) for name in expected}
    word = str(token)
    if token.type == "NAME" or token.type not in ("NUMBER", "STRING", "COLOUR", "ORDINAL", "CAMEL"):
        if "noun" in keywords and word.isidentifier():
            return f"unknown catalog field '{word}'" + did_you_mean(word, ENTRY_FIELDS + ("style",))
        if "extent" in keywords and word.isidentifier():
            return f"unknown scene setting '{word}'" + did_you_mean(word, SCENE_SETTINGS)
        if "object" in keywords and word.isidentifier():
            return f"unexpected '{word}'" + did_you_mean(word, KINDS + ("scene", "include"))
    return f"unexpected {_describe_token(token)}"
