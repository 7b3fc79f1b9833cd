"""Diagnostics for rules files: one located message each, and the error that carries them.

A ``Diagnostic`` is what the parser, the static checks and expansion report about a
rules file: where (file:line:column), what (one sentence), how bad (error or warning)
and the offending source line, so it prints as

    village.rules:12:9: error: unknown relation label 'NextTwo'; did you mean 'NextTo'?
        sign NextTwo t
             ^

The suggestions that end many messages are worded here too: "did you mean" the nearest
known word, and the case a word should be in (``case_mix_up``).

Only rules text is ever quoted: ``SourceTexts`` keeps the lines of files named
``*.rules`` alone, so no diagnostic prints a line of another file (an include of a
data file or of /etc/passwd, say), whatever is wrong with it.
"""

from __future__ import annotations

import difflib
import re
from collections.abc import Iterable, Sequence
from dataclasses import dataclass

from scenewright.core.errors import InputError
from scenewright.core.limits import printable

from .catalog import SourceLocation

ERROR = "error"
WARNING = "warning"

#: Indentation of the quoted source line under a diagnostic's first line.
_EXCERPT_INDENT = "    "

#: The suffix of a rules file's name; the lines of files without it are never quoted.
RULES_SUFFIX = ".rules"


def is_rules_file_name(name: str) -> bool:
    """Whether a file is named as a rules file (``*.rules``), so its lines may be quoted."""
    return name.endswith(RULES_SUFFIX)


@dataclass(frozen=True)
class Diagnostic:
    """One finding about a rules file, located at ``location``."""

    location: SourceLocation
    message: str
    severity: str = ERROR
    source_line: str | None = None

    @property
    def is_error(self) -> bool:
        return self.severity == ERROR

    def __str__(self) -> str:
        head = f"{self.location}: {self.severity}: {self.message}"
        if self.source_line is None or not self.source_line.strip():
            return head
        line = self.source_line.expandtabs(4)
        text = line.lstrip()
        # The caret sits under the column, counted in the line as shown (tabs expanded,
        # leading indentation removed).
        column_in_line = len(self.source_line[: self.location.column - 1].expandtabs(4))
        caret = max(0, column_in_line - (len(line) - len(text)))
        return f"{head}\n{_EXCERPT_INDENT}{text}\n{_EXCERPT_INDENT}{' ' * caret}^"


class RulesError(InputError):
    """A rules file that cannot be used, with every error diagnostic found in it."""

    def __init__(self, diagnostics: Sequence[Diagnostic]):
        self.diagnostics = list(diagnostics)
        super().__init__(format_diagnostics(self.diagnostics))


class ExpansionError(InputError):
    """Expansion of valid-looking rules failed (unbounded recursion, missing reference).

    It is the rule author's fault, so it is an ``InputError``; the message names the
    chain of productions that led there and the location of the statement.
    """

    def __init__(self, diagnostic: Diagnostic):
        self.diagnostic = diagnostic
        self.diagnostics = [diagnostic]
        super().__init__(str(diagnostic))


def format_diagnostics(diagnostics: Iterable[Diagnostic]) -> str:
    """All diagnostics, one block each, errors and warnings as they come."""
    return "\n".join(str(diagnostic) for diagnostic in diagnostics)


def did_you_mean(word: str, known: Iterable[str]) -> str:
    """``"; did you mean 'X'?"`` for the closest known word, or ``""`` if none is close."""
    matches = difflib.get_close_matches(word, sorted(set(known)), n=1, cutoff=0.6)
    return f"; did you mean '{matches[0]}'?" if matches else ""


# The language's two cases: types, bound names and parameters are snake_case;
# nonterminals and relation labels are CamelCase.


def snake_case(word: str) -> str:
    """``MarketStand`` -> ``market_stand``: a word as a type or name is written."""
    return (
        re.sub(r"(?<=[a-z0-9])(?=[A-Z])|(?<=[A-Z])(?=[A-Z][a-z])", "_", word)
        .replace("-", "_")
        .lower()
    )


def camel_case(word: str) -> str:
    """``market_stand``, ``marketStand`` -> ``MarketStand``: a word as a nonterminal or label is written."""
    return "".join(part[:1].upper() + part[1:] for part in re.split(r"[_-]+", word))


def case_hint(convention: str, suggestion: str) -> str:
    """``"; nonterminals are CamelCase: did you mean 'Market'?"`` (``convention`` says which case)."""
    return f"; {convention}: did you mean '{suggestion}'?"


def case_mix_up(word: str, known: Iterable[str], convention: str) -> str:
    """``case_hint`` for the known word that ``word`` spells in the wrong case (``next_to``
    or ``nextTo`` for ``NextTo``), or ``""`` if no known word differs from it only in case
    and underscores."""
    key = _case_key(word)
    matches = sorted(name for name in set(known) if _case_key(name) == key and name != word)
    return case_hint(convention, matches[0]) if matches else ""


def _case_key(word: str) -> str:
    return word.replace("_", "").replace("-", "").lower()


class SourceTexts:
    """The text of every rules file read so far, to quote the line a diagnostic points at."""

    def __init__(self) -> None:
        self._lines: dict[str, list[str]] = {}

    def add(self, file: str, text: str, quoted: bool = True) -> None:
        """Keep ``file``'s lines for quoting, unless ``quoted`` is false or the file is
        not named ``*.rules``: then its diagnostics show no line."""
        if not (quoted and is_rules_file_name(file)):
            return
        # Lines as the parser counts them: split at "\n" only (not at "\r", form feeds
        # or Unicode line separators, which str.splitlines would also split at).
        # A stray "\r" inside a line would move the terminal's cursor: show it as a space.
        # Other control and bidirectional-control characters show as U+FFFD.
        self._lines[file] = [
            printable(line.rstrip("\r").replace("\r", " ")) for line in text.split("\n")
        ]

    def line(self, location: SourceLocation) -> str | None:
        lines = self._lines.get(location.file)
        if lines is None or not 1 <= location.line <= len(lines):
            return None
        return lines[location.line - 1]

    def diagnostic(
        self, location: SourceLocation, message: str, severity: str = ERROR
    ) -> Diagnostic:
        return Diagnostic(location, message, severity, self.line(location))
