"""A floor plan before its walls are built: room outlines, and which rooms a door joins.

Both ways to a house meet here: ``floor_plan.generate_outlines`` makes an ``Outlines``
from a plan in the rules language, ``given_plan.read_given_plan`` from a user's JSON; then
``walls.build_house`` turns it into a ``core.house.House`` (walls, door and window
positions, each room's own ``Room``).
"""

from __future__ import annotations

from dataclasses import dataclass, field

Point = tuple[float, float]


@dataclass(frozen=True)
class PlannedRoom:
    id: str
    type: str
    #: What the text calls it ("kitchen", "second bedroom").
    name: str
    #: The rule set that furnishes it (shipped name or absolute path).
    rules: str
    #: The room on its walls' centre lines, corners in order (house frame).
    outline: tuple[Point, ...]
    #: Whether it should get a window (its rule set places things by one).
    wants_window: bool = True
    #: The least free width it needs (m).
    width: float = 1.0
    #: The shape of its windows (width, height, sill): its rule set's room's first window.
    window: tuple[float, float, float] | None = None


@dataclass(frozen=True)
class PlannedDoor:
    #: The two rooms it joins, or one room for a door to the outside.
    rooms: tuple[str, ...]
    open: bool = False
    #: Its centre on the wall's centre line, when the plan gives it; else the walls choose.
    center: Point | None = None
    width: float | None = None


@dataclass(frozen=True)
class PlannedWindow:
    room: str
    center: Point
    width: float = 1.2
    height: float = 1.3
    sill: float = 0.9


@dataclass
class Outlines:
    noun: str
    footprint: tuple[Point, ...]
    holes: tuple[tuple[Point, ...], ...]
    height: float
    rooms: list[PlannedRoom]
    doors: list[PlannedDoor]
    #: None: the walls put windows on the outside walls of the rooms that want them.
    windows: list[PlannedWindow] | None = None
    #: How the plan was made (attempts, the sizes drawn), for scene.json.
    notes: dict = field(default_factory=dict)
