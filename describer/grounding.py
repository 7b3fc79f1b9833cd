"""Grounding: which characters of a sentence name which entities, recorded as the words are made.

Every phrase that names an entity (``refer.Discourse``: "an oak tree", "the second
road", "it", "the sign of the third market stand") is wrapped, where it is made, in two
invisible marks that carry the index of what it names in a per-sentence table
(``Marks``). The templates move these strings about as any others (they may reorder,
repeat or drop them); once a sentence is rendered, ``Marks.read`` strips the marks and
returns the plain text with a ``Mention`` for every marked phrase: its character span
and the entities it names. So a span is known from how the sentence was made, never
found by searching the text: "the first road" and "the second road" in one sentence are
two spans with two different ids, however alike their words.

Marks nest: "the sign of the third market stand" is one mention of the sign holding a
mention of the market stand. A mark is ``OPEN``, one character of the Supplementary
Private Use Area-A (U+F0000 + the table index) and, after the phrase, ``CLOSE``; no
word of the describer's uses those code points, and ``world_of`` refuses a scene whose
nouns do (``holds_marks``). A template that cuts a
mark in two (slicing a string), or writes the marks itself, makes the sentence
unreadable: ``TemplateError``.

Mentions name entities as the text sees them (a group is one entity, "a group of
trees"); ``World.grounded_ids`` turns them into what a picture shows: the group's
objects, paths and junctions.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

from .errors import TemplateError

#: Opens a marked phrase (followed by its index character).
OPEN = "\ue000"
#: Closes the innermost open marked phrase.
CLOSE = "\ue001"
#: The index character of table entry k is chr(INDEX_BASE + k).
INDEX_BASE = 0xF0000
#: How many marks one sentence may hold (the Private Use Area-A's size).
MAX_MARKS = 0xFFFFD - INDEX_BASE + 1

_LEADING_OPENS = re.compile(f"(?:{OPEN}[\U000f0000-\U000ffffd])*")


@dataclass(frozen=True)
class Mention:
    """A phrase of the text, ``text[start:end]``, the entities it names (derivation ids; a
    group is named by its own id) and ``ids``, what those are in a picture
    (``World.grounded_ids``: a group's objects, paths and junctions; empty until
    ``Description`` fills it in)."""

    start: int
    end: int
    entities: tuple[str, ...]
    ids: tuple[str, ...] = ()


class Marks:
    """The marked phrases of the sentence being made."""

    def __init__(self) -> None:
        self._named: list[tuple[str, ...]] = []

    def clear(self) -> None:
        """Start a new sentence (indices restart from 0)."""
        self._named.clear()

    def mark(self, phrase: str, entities: tuple[str, ...]) -> str:
        """``phrase`` wrapped in marks recording that it names ``entities``."""
        if len(self._named) >= MAX_MARKS:
            raise ValueError(f"more than {MAX_MARKS} phrases in one sentence")
        self._named.append(tuple(entities))
        return f"{OPEN}{chr(INDEX_BASE + len(self._named) - 1)}{phrase}{CLOSE}"

    def read(self, marked: str) -> tuple[str, tuple[Mention, ...]]:
        """The text without its marks, and one mention per marked phrase, in the order
        the phrases start (an outer phrase before the phrases inside it)."""
        plain: list[str] = []
        length = 0
        open_at: list[tuple[int, int]] = []  # (start in the plain text, table index)
        found: list[tuple[int, int, int]] = []  # (start, -end, index): outer first at one start
        position = 0
        while position < len(marked):
            character = marked[position]
            if character == OPEN:
                index = ord(marked[position + 1]) - INDEX_BASE if position + 1 < len(marked) else -1
                if not 0 <= index < len(self._named):
                    raise _broken(marked)
                open_at.append((length, index))
                position += 2
                continue
            if character == CLOSE:
                if not open_at:
                    raise _broken(marked)
                start, index = open_at.pop()
                found.append((start, -length, index))
            else:
                plain.append(character)
                length += 1
            position += 1
        if open_at:
            raise _broken(marked)
        found.sort()
        return "".join(plain), tuple(
            Mention(start, -end, self._named[index]) for start, end, index in found
        )


def holds_marks(text: str) -> bool:
    """Whether ``text`` holds a character the marks are made of (a noun must not)."""
    return any(c in (OPEN, CLOSE) or INDEX_BASE <= ord(c) <= 0xFFFFD for c in text)


def unmarked(text: str) -> str:
    """``text`` without any marks (what a reader sees)."""
    return re.sub(f"{OPEN}[\U000f0000-\U000ffffd]|{CLOSE}", "", text)


def split_leading_marks(text: str) -> tuple[str, str]:
    """The opening marks ``text`` starts with, and the rest: a word put in front of the
    rest ("a" in "a desk") then falls inside the phrases that start there."""
    opens = _LEADING_OPENS.match(text)
    assert opens is not None  # the pattern matches the empty string too
    leading = opens.end()
    return text[:leading], text[leading:]


def _broken(marked: str) -> Exception:
    return TemplateError(
        "a description template cut a named phrase apart or wrote the describer's private marks "
        f"(U+E000, U+E001) itself: {unmarked(marked)[:200]!r}"
    )
