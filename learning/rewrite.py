"""Fitted parameters written back into a rule set's text, changing only its numbers.

``rewrite_rules`` edits each file of a parsed rule set in place of its numbers: an
alternative's weight (``3: {`` -> ``0.61: {``, or ``{`` -> ``0.61: {`` where none was
written), an optional statement's probability, a range's weights (``2..4`` ->
``2..4 {0.2 0.5 0.3}``), a style's weight. Comments, order, spacing and everything else
stay as they were, so the fitted file reads like the one the user wrote. Parameters the
examples could not identify keep their numbers.

``fitted_files`` decides where each file goes: the root file to the path asked for,
the files it includes beside it at the same relative paths (so its ``include`` lines
still find them).
"""

from __future__ import annotations

import os
import re
from pathlib import Path

from scenewright.generator import rules_ast as ast
from scenewright.generator.catalog import SourceLocation
from scenewright.generator.derivation import all_statements, site_of
from scenewright.generator.rules_includes import ParsedTree

from .errors import FitOutputError
from .weights import WeightFit

_NUMBER = re.compile(r"-?[0-9]+(?:\.[0-9]+)?")
_RANGE = re.compile(r"[0-9]+\s*\.\.\s*[0-9]+")
_STYLE_NAME = re.compile(r"style\s+[a-z_][a-z0-9_]*")
#: Digits written for a fitted probability: finer than any standard error of a fit.
DIGITS = 3


def number(value: float, *, positive: bool) -> str:
    """A probability as written into rules: ``DIGITS`` decimals, no trailing zeros, and
    never 0 where the language needs a positive weight."""
    text = f"{value:.{DIGITS}f}".rstrip("0").rstrip(".")
    if positive and float(text) <= 0:
        return f"0.{'0' * (DIGITS - 1)}1"
    return text


def rewrite_rules(tree: ParsedTree, fit: WeightFit) -> dict[str, str]:
    """The text of each file of ``tree`` (display name -> text) with the identified
    parameters of ``fit`` written in; files without such parameters are unchanged."""
    fitted = {parameter.key: parameter for parameter in fit.parameters if parameter.identified}
    texts = {}
    for file in tree.files:
        editor = _Editor(tree.paths[file.path].read_text(encoding="utf-8"))
        _edit_file(file, fitted, editor)
        texts[file.path] = editor.result()
    return texts


def fitted_files(tree: ParsedTree, texts: dict[str, str], output: Path) -> list[tuple[Path, str]]:
    """Where each rewritten file goes and its text: the root file at ``output``, each
    included file at its path relative to the root's folder, under ``output``'s folder.

    Raises ``FitOutputError`` for an included file outside the root's folder (its
    ``include`` line could not find a copy) or one that would be written over itself
    with changed numbers (the user's input is never overwritten).
    """
    root = tree.files[-1].path
    root_folder = tree.paths[root].resolve().parent
    target_folder = output.parent
    placed = []
    for file in tree.files:
        source = tree.paths[file.path].resolve()
        if file.path == root:
            target = output
        else:
            relative = Path(os.path.relpath(source, root_folder))
            if relative.parts and relative.parts[0] == "..":
                raise FitOutputError(
                    f"{file.path}: an included file outside the rule set's folder cannot be written beside "
                    f"{output}; copy it into the rule set's folder first"
                )
            target = target_folder / relative
        if target.resolve() == source:
            if texts[file.path] == source.read_text(encoding="utf-8"):
                continue  # an unchanged include that is already where the output needs it
            raise FitOutputError(
                f"{target}: would overwrite the input; write the fitted rules into another folder"
            )
        placed.append((target, texts[file.path]))
    return placed


class _Editor:
    """The edits of one file's text, located by the parser's (line, column)."""

    def __init__(self, text: str):
        self.text = text
        self.starts = [0] + [match.end() for match in re.finditer("\n", text)]
        self.edits: list[tuple[int, int, str]] = []

    def offset(self, location: SourceLocation) -> int:
        return self.starts[location.line - 1] + location.column - 1

    def match(self, pattern: re.Pattern, location: SourceLocation) -> re.Match:
        found = pattern.match(self.text, self.offset(location))
        if found is None:  # the parser put the location there, so this is a bug
            raise AssertionError(f"no {pattern.pattern!r} at {location}")
        return found

    def replace(self, start: int, end: int, replacement: str) -> None:
        self.edits.append((start, end, replacement))

    def replace_number(self, location: SourceLocation, value: str) -> None:
        found = self.match(_NUMBER, location)
        self.replace(found.start(), found.end(), value)

    def insert_after(self, pattern: re.Pattern, location: SourceLocation, addition: str) -> None:
        end = self.match(pattern, location).end()
        self.replace(end, end, addition)

    def result(self) -> str:
        text = self.text
        for start, end, replacement in sorted(self.edits, reverse=True):
            text = text[:start] + replacement + text[end:]
        return text


def _edit_file(file: ast.RulesFile, fitted: dict, editor: _Editor) -> None:
    """Write every fitted number of one file into ``editor``."""
    for production in file.productions:
        parameter = fitted.get(("alternative", production.name, site_of(production.location)))
        if parameter is not None:
            for alternative, estimate in zip(
                production.alternatives, parameter.estimate, strict=False
            ):
                weight = number(estimate, positive=True)
                if alternative.weight is None:
                    at = editor.offset(alternative.location)
                    editor.replace(at, at, f"{weight}: ")
                else:
                    editor.replace_number(alternative.location, weight)
        for alternative in production.alternatives:
            for statement in all_statements(alternative.statements):
                _edit_statement(production.name, statement, fitted, editor)
    for entry in file.entries:
        parameter = fitted.get(("style", entry.name, site_of(entry.location)))
        for style, estimate in zip(
            entry.styles, parameter.estimate if parameter else (), strict=False
        ):
            weight = number(estimate, positive=True)
            if style.weight_location is not None:
                editor.replace_number(style.weight_location, weight)
            else:
                editor.insert_after(_STYLE_NAME, style.location, f" {weight}")


def _edit_statement(rule: str, statement: ast.Statement, fitted: dict, editor: _Editor) -> None:
    count = statement.count
    parameter = fitted.get(("count", rule, site_of(count.location))) if count is not None else None
    if parameter is not None:
        weights = (
            "{" + " ".join(number(value, positive=False) for value in parameter.estimate) + "}"
        )
        if count.weights_location is not None:
            start = editor.offset(count.weights_location)
            editor.replace(start, editor.text.index("}", start) + 1, weights)
        else:
            editor.insert_after(_RANGE, count.location, f" {weights}")
    if statement.probability is not None:
        parameter = fitted.get(("optional", rule, site_of(statement.probability_location)))
        if parameter is not None:
            editor.replace_number(
                statement.probability_location, number(parameter.estimate[1], positive=False)
            )
