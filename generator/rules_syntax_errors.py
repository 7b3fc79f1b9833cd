"""A syntax error in a rules file, said in words, never in terminal names.

A syntax error is explained in three steps:

1. A '{' never closed: if a '}' inserted before the line of the error (or before the
   unexpected word, or at the end of the file) lets the parser read the rest of that
   line, the error is the missing '}', reported at the '{' still open on the parser's
   stack.
2. Where the parser stopped: the place of the error (``rules_syntax_places``), which
   says how the names and keywords there are worded.
3. What was expected, in words: the terminals the parser takes there, each said from
   its pattern (``Lark.get_terminal``): a keyword or punctuation as itself, the others
   from ``_WORDS``; the place says what its names and keywords are. A word in the
   wrong place gets "did you mean" (a misspelt field or setting, a name in the wrong
   case).

A syntax error in a file whose text must not be shown (``not_rules_diagnostic``) says
where, and nothing of what.
"""

from __future__ import annotations

import functools
import re
from collections.abc import Iterable

from lark import Token, Tree
from lark.exceptions import UnexpectedCharacters, UnexpectedToken

from scenewright.core.relations import RELATIONS

from .catalog import SourceLocation
from .rules_errors import (
    RULES_SUFFIX,
    Diagnostic,
    SourceTexts,
    camel_case,
    case_hint,
    case_mix_up,
    did_you_mean,
    snake_case,
)
from .rules_lark import ParseStop, error_offset, lalr_parser, terminal_literal
from .rules_syntax_places import Context, stopped_at

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


def syntax_diagnostic(error: ParseStop, text: str, file: str, sources: SourceTexts) -> Diagnostic:
    """The diagnostic for a syntax error in a rules file whose text may be quoted."""
    unclosed = _unclosed_block(error, text)
    if unclosed is not None:
        brace, message = unclosed
        assert brace.line is not None and brace.column is not None  # lexed from the text
        return sources.diagnostic(SourceLocation(file, brace.line, brace.column), message)
    offset, message = _explain(error, text)
    line = text.count("\n", 0, offset) + 1
    column = offset - (text.rfind("\n", 0, offset) + 1) + 1
    return sources.diagnostic(SourceLocation(file, line, column), message)


def not_rules_diagnostic(error: ParseStop, text: str, file: str) -> Diagnostic:
    """A syntax error in a file whose text must not be shown: where, and nothing of what."""
    offset = error_offset(error, text)
    line = text.count("\n", 0, offset) + 1
    column = offset - (text.rfind("\n", 0, offset) + 1) + 1
    return Diagnostic(
        SourceLocation(file, line, column),
        f"'{file}' is not a rules file: it does not parse as "
        f"rules here (the text of a file not named *{RULES_SUFFIX} is never shown)",
    )


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
        if isinstance(value, Token) and terminal_literal(value.type) == "{"
    ]
    offset = error_offset(error, text)
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
        return error_offset(error, text) > offset
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
        literal = terminal_literal(value.type) if isinstance(value, Token) else None
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


# -- 3. what was expected, in words ---------------------------------------------------


def _explain(error: ParseStop, text: str) -> tuple[int, str]:
    """Where a syntax error is (an offset in ``text``) and what it is, in one sentence."""
    offset = _word_start(text, error_offset(error, text))
    context, accepts = stopped_at(error, text, offset)
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


def _case_mix_up(context: Context, word: str, accepts: frozenset[str], after: str) -> str:
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
        and (literal := terminal_literal(terminal.name))
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


def _expected(context: Context, accepts: frozenset[str]) -> list[str]:
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
        terminal for terminal in terminals if (terminal_literal(terminal.name) or "").isidentifier()
    ]
    others = sorted(
        (terminal for terminal in terminals if terminal not in keywords),
        key=lambda terminal: terminal.pattern.type == "str",
    )  # named terminals first
    for terminal in keywords + others:
        said_as = terminal_literal(terminal.name) or terminal.name
        if said_as in covered or said_as in _SEPARATORS or (said_as == "}" and ends_statement):
            continue  # a '}' is the end of a block's last statement
        words.append(
            context.words.get(said_as)
            or _WORDS.get(said_as)
            or (f"'{said_as}'" if terminal_literal(terminal.name) else said_as.lower())
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
