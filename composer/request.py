"""What a text asks for, as data: the things it names (``Entity``), what it says of
them (``Statement``, whose object may be a room part, ``Place``), the room, and every
word it could not use (``Issue``), with character spans; and the words of a text
(``tokenize``). ``parse`` reads a text into a ``Request``; ``plan`` and ``outdoor``
turn one into a rule set.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field

_TOKEN = re.compile(r"\d+(?:\.\d+)?|[A-Za-z][A-Za-z'’-]*|[.,;:!?]")


@dataclass
class Token:
    text: str
    start: int
    end: int
    low: str
    used: bool = False
    note: str = ""  # why a known word went unused


@dataclass
class Entity:
    id: str
    type: str
    style: str | None
    colour: str | None
    start: int
    end: int
    #: The group it is a member of ("the first row of desks consists of four desks").
    parent: str | None = None
    #: Whether it is a group itself.
    group: bool = False
    #: The group whose paragraph the text was in when it named this thing first (after
    #: "the first market stand consists of ..."): outdoors it may be one of its members
    #: (``composer.outdoor.adopt_members``).
    paragraph: str | None = None


@dataclass(frozen=True)
class Place:
    """A room part as a relation's object: a wall, window or corner, by number or any."""

    kind: str  # "wall", "window", "corner"
    number: int | None = None  # wall or window number; None: the layout chooses
    corner: tuple[str, str] | None = None  # a named corner ("north", "west")
    by_door: bool = False  # "the corner by the door"
    #: "opposite the window": the wall across the room from the window's ("window") or
    #: the door's ("door"); its number is settled once the text is read (``parse``).
    opposite: str | None = None


@dataclass(frozen=True)
class Statement:
    source: str
    label: str
    target: str | Place
    start: int
    end: int


@dataclass
class Issue:
    start: int
    end: int
    text: str
    message: str


@dataclass
class Request:
    """What a text asks for (see the module docstring)."""

    entities: list[Entity] = field(default_factory=list)
    statements: list[Statement] = field(default_factory=list)
    room: str = "room"
    size: tuple[float, float] | None = None
    size_factor: float = 1.0
    planned_size: tuple[float, float] = (0.0, 0.0)  # the room's sides as planned
    made: list[str] = field(default_factory=list)  # entity ids in the order the rules make them
    door_walls: list[str] = field(default_factory=list)  # as planned
    starts: dict[str, list[tuple[float, float, float]]] = field(default_factory=dict)  # x, z, yaw
    doors: list[str] = field(default_factory=list)  # one wall side per door
    windows: list[str] = field(default_factory=list)  # one wall side per window
    absent: dict[str, tuple[int, int]] = field(default_factory=dict)
    issues: list[Issue] = field(default_factory=list)
    used: list[tuple[int, int]] = field(default_factory=list)


def tokenize(text: str) -> list[Token]:
    return [
        Token(m.group(), m.start(), m.end(), m.group().lower().replace("’", "'"))
        for m in _TOKEN.finditer(text)
    ]
