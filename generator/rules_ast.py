"""The parsed form of a rules file: plain frozen dataclasses, each with its location.

The parser builds these from the text without judging them; the static checks
(``rules_check``) judge them, and ``rules`` turns a checked set into a catalog and
scene parameters. Values are kept as written (numbers as floats, colours as the
``#rrggbb`` text) so that every check can point at the exact place of a bad value.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass
from typing import TypeGuard

from .catalog import SourceLocation


@dataclass(frozen=True)
class Setting:
    """One ``name value...`` line of a catalog entry, style or scene block.

    ``value`` is a float, a string (``noun``, ``mesh``, ``templates``: a path kept as
    written, relative to the file), a tuple of floats (``size``, ``extent``), a tuple
    of words and numbers (``clearance front 0.8``, ``access left right``), a
    ``RoomDecl`` (``room``), or ``True`` for a bare flag (``walls``).
    """

    name: str
    value: SettingValue
    location: SourceLocation
    value_location: SourceLocation

    # The grammar fixes each setting's form by its name; these read the value in that
    # form, for code that has already looked at the name.

    def number(self) -> float:
        """The value of a one-number setting (``width``, ``max_depth``, ...)."""
        assert isinstance(self.value, float), self
        return self.value

    def text(self) -> str:
        """The value of a one-word or quoted-string setting (``noun``, ``colour``, ...)."""
        assert isinstance(self.value, str), self
        return self.value

    def numbers(self) -> tuple[float, ...]:
        """The value of a setting of several numbers (``size``, ``extent``)."""
        assert isinstance(self.value, tuple) and _all_numbers(self.value), self
        return self.value

    def words(self) -> tuple[str, ...]:
        """The value of a setting of several words (``access``)."""
        assert isinstance(self.value, tuple) and _all_words(self.value), self
        return self.value

    def word_and_number(self) -> tuple[str, float]:
        """The value of a setting of a word and a number (``clearance front 0.8``)."""
        assert isinstance(self.value, tuple) and len(self.value) == 2, self
        word, number = self.value
        assert isinstance(word, str) and isinstance(number, float), self
        return word, number

    def room(self) -> RoomDecl:
        """The value of the ``room`` setting."""
        assert isinstance(self.value, RoomDecl), self
        return self.value


@dataclass(frozen=True)
class OpeningDecl:
    """``door WALL OFFSET WIDTH [HEIGHT]`` or ``window WALL OFFSET WIDTH SILL HEIGHT`` in a room block."""

    kind: str
    wall: str
    numbers: tuple[float, ...]
    location: SourceLocation
    wall_location: SourceLocation


@dataclass(frozen=True)
class RoomDecl:
    """``room W x D { ... }`` or ``room (x, z) (x, z) ... { ... }``: exactly one of
    ``size`` and ``corners``; ``height`` is the walls' height if given."""

    size: tuple[float, float] | None
    corners: tuple[tuple[float, float], ...] | None
    height: float | None
    openings: tuple[OpeningDecl, ...]
    location: SourceLocation
    height_location: SourceLocation | None = None


#: What a setting's value can be (``Setting``).
SettingValue = float | str | bool | tuple[float | str, ...] | RoomDecl


def _all_numbers(values: tuple[float | str, ...]) -> TypeGuard[tuple[float, ...]]:
    return all(isinstance(v, float) for v in values)


def _all_words(values: tuple[float | str, ...]) -> TypeGuard[tuple[str, ...]]:
    return all(isinstance(v, str) for v in values)


@dataclass(frozen=True)
class StyleDecl:
    """``style NAME [WEIGHT] { field* }`` inside a catalog entry."""

    name: str
    weight: float | None
    fields: tuple[Setting, ...]
    location: SourceLocation
    weight_location: SourceLocation | None = None


@dataclass(frozen=True)
class EntryDecl:
    """``KIND TYPE { field* style* }``: one catalog entry as written."""

    kind: str
    name: str
    fields: tuple[Setting, ...]
    styles: tuple[StyleDecl, ...]
    location: SourceLocation
    name_location: SourceLocation


@dataclass(frozen=True)
class SceneDecl:
    """``scene NAME { setting* }``."""

    name: str
    settings: tuple[Setting, ...]
    location: SourceLocation


@dataclass(frozen=True)
class IncludeDecl:
    """``include "file"``, the path as written (relative to the including file)."""

    path: str
    location: SourceLocation


@dataclass(frozen=True)
class Reference:
    """A reference to nodes, as a statement's subject, a relation target or an argument.

    ``kind`` is ``"name"`` (a bound name, a parameter, or - as a subject only - a type
    to create), ``"some"`` (one node of the type at random), ``"each"`` (every node of
    the type) or ``"nth"`` (the ``index``-th node of the type, 1-based).
    """

    kind: str
    name: str
    location: SourceLocation
    index: int = 0


@dataclass(frozen=True)
class Call:
    """A nonterminal as a statement's subject, with its arguments."""

    nonterminal: str
    arguments: tuple[Reference, ...]
    location: SourceLocation


@dataclass(frozen=True)
class Relation:
    """``LABEL TARGET`` after a statement's subject."""

    label: str
    target: Reference
    location: SourceLocation


@dataclass(frozen=True)
class Count:
    """``N`` or ``MIN..MAX`` repetitions: uniform in the range (both ends included), or
    ``MIN..MAX {W W ...}`` with one weight per count from MIN to MAX."""

    low: float
    high: float
    location: SourceLocation
    weights: tuple[float, ...] | None = None
    weights_location: SourceLocation | None = None


@dataclass(frozen=True)
class Statement:
    """``[COUNT] [PROB?] SUBJECT [as NAME] (LABEL TARGET)* [{ statement* }]``."""

    subject: Reference | Call
    location: SourceLocation
    count: Count | None = None
    probability: float | None = None
    probability_location: SourceLocation | None = None
    binding: str | None = None
    binding_location: SourceLocation | None = None
    relations: tuple[Relation, ...] = ()
    block: tuple[Statement, ...] | None = None
    block_location: SourceLocation | None = None


@dataclass(frozen=True)
class Alternative:
    """``[WEIGHT:] { statement* }``: one right-hand side of a production."""

    weight: float | None
    statements: tuple[Statement, ...]
    location: SourceLocation


@dataclass(frozen=True)
class Param:
    """One parameter of a production: a name bound, at each call, to an argument's nodes."""

    name: str
    location: SourceLocation


@dataclass(frozen=True)
class Production:
    """``Nonterminal[(params)] -> alternative (| alternative)*``."""

    name: str
    params: tuple[Param, ...]
    alternatives: tuple[Alternative, ...]
    location: SourceLocation


@dataclass(frozen=True)
class RulesFile:
    """Everything one file declares, in file order within each kind."""

    path: str
    includes: tuple[IncludeDecl, ...] = ()
    scenes: tuple[SceneDecl, ...] = ()
    entries: tuple[EntryDecl, ...] = ()
    productions: tuple[Production, ...] = ()


def all_statements(statements: tuple[Statement, ...]) -> Iterator[Statement]:
    """The statements and, depth-first, those of their blocks."""
    for statement in statements:
        yield statement
        if statement.block is not None:
            yield from all_statements(statement.block)


def production_statements(production: Production) -> Iterator[Statement]:
    """Every statement of every alternative of ``production``, blocks included."""
    for alternative in production.alternatives:
        yield from all_statements(alternative.statements)
