"""One rules file's text -> its ``rules_ast.RulesFile``, or the syntax error in words.

``parse_text`` parses the text with the LALR parser (``rules_lark``), refuses blocks
nested deeper than ``MAX_BLOCK_NESTING`` and builds the AST (``rules_to_ast``). A syntax
error becomes a ``Diagnostic`` worded by ``rules_syntax_errors``; the text of a file not
named ``*.rules`` is never quoted. Reading a file and the files it includes is
``rules_includes``.
"""

from __future__ import annotations

import threading

from lark import Tree
from lark.exceptions import UnexpectedCharacters, UnexpectedToken

from scenewright.core.limits import MAX_BLOCK_NESTING

from . import rules_ast as ast
from .catalog import SourceLocation
from .rules_errors import Diagnostic, SourceTexts, is_rules_file_name
from .rules_lark import lalr_parser
from .rules_syntax_errors import not_rules_diagnostic, syntax_diagnostic
from .rules_to_ast import ToAst


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
    known = _PARSED.get((text, file))
    if known is not None:
        return known
    try:
        tree = lalr_parser().parse(text)
    except (UnexpectedToken, UnexpectedCharacters) as error:  # the two LALR parse errors
        if not (quoted and is_rules_file_name(file)):
            return not_rules_diagnostic(error, text, file)
        return syntax_diagnostic(error, text, file, sources)
    too_deep = _too_deep_block(tree)
    if too_deep is not None:
        return sources.diagnostic(
            SourceLocation(file, too_deep.meta.line, too_deep.meta.column),
            f"blocks nested more than {MAX_BLOCK_NESTING} deep; move the inner ones into a production "
            "of their own and call it (the limits: docs/limits.md)",
        )
    parsed = ToAst(file).transform(tree)
    if len(text) <= _PARSED_LARGEST:
        with _PARSED_LOCK:
            if len(_PARSED) >= _PARSED_KEPT:
                del _PARSED[next(iter(_PARSED))]  # the oldest
            _PARSED[(text, file)] = parsed
    return parsed


#: Files parsed lately, by (text, name): the AST is immutable (frozen dataclasses of
#: tuples) and depends on nothing else, so a program that loads the same rules again (a
#: house's rooms, the API called in a loop) parses each text once. Only parses without
#: a syntax error are kept: a diagnostic's wording depends on the other files read.
_PARSED: dict[tuple[str, str], ast.RulesFile] = {}
_PARSED_KEPT = 64
_PARSED_LOCK = threading.Lock()
_PARSED_LARGEST = 200_000  # characters: the shipped rule sets are under 20,000


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
