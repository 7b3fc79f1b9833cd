"""A house: several rooms joined by doors, on one floor.

World frame as everywhere (``core.frames``): metres, +Y up, north -Z, east +X; the house
is centred on the origin. A house is drawn on the centre lines of its walls: each
room's ``outline`` runs along the middle of the walls around it, so two neighbouring
rooms share the stretch of outline between them, and that stretch is one wall
(``HouseWall``), ``thickness`` thick, not two. Each room also has a ``Room`` of its own
(``core.room``): the inner faces of its walls, half a wall's thickness inside the
outline, with the room's doors and windows, in the room's own frame; ``offset`` is
where that frame's origin lies in the house. Every stage that knows rooms (the layout,
the describer, the checks) works on that room as it would on a room scene; the house
joins them.

Doors and windows of the house (``HouseOpening``) sit on the walls' centre lines: a
door between two rooms is one opening of the house and one opening in each room's own
``Room`` (each keeps its swing clear); the front door and windows are in outside
walls. An ``open`` door is a doorway with no leaf ("the kitchen is open to the living
room").
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

from scenewright.core.room import Room

#: Thickness of every wall of a house, interior and exterior (metres).
HOUSE_WALL_THICKNESS = 0.12
#: The separator between a room's id and an object's own id in a house scene
#: (``bedroom_2/bed_1``): ids inside a room stay the room's own.
ID_SEPARATOR = "/"

Point = tuple[float, float]


@dataclass(frozen=True)
class HouseOpening:
    """A door or window of the house, centred at ``center`` on its wall's centre line."""

    id: str
    kind: str  # "door" or "window"
    #: The rooms it opens into: two for a door between rooms, one for the front door or a window.
    rooms: tuple[str, ...]
    center: Point
    #: Unit vector (x, z) along the wall it is in.
    direction: Point
    width: float
    height: float
    sill: float = 0.0
    #: A doorway with no leaf, between rooms open to each other.
    open: bool = False

    @property
    def entrance(self) -> bool:
        """Whether this is a door to the outside."""
        return self.kind == "door" and len(self.rooms) == 1

    def to_dict(self) -> dict[str, Any]:
        return {
            "id": self.id,
            "kind": self.kind,
            "rooms": list(self.rooms),
            "center": list(self.center),
            "direction": list(self.direction),
            "width": self.width,
            "height": self.height,
            "sill": self.sill,
            "open": self.open,
        }

    @classmethod
    def from_dict(cls, data: dict[str, Any]) -> HouseOpening:
        return cls(
            id=str(data["id"]),
            kind=str(data["kind"]),
            rooms=tuple(str(r) for r in data["rooms"]),
            center=_point(data["center"]),
            direction=_point(data["direction"]),
            width=float(data["width"]),
            height=float(data["height"]),
            sill=float(data.get("sill", 0.0)),
            open=bool(data.get("open", False)),
        )


@dataclass(frozen=True)
class HouseWall:
    """One straight wall on its centre line, between ``rooms`` (a room id each side; None
    outside): the left side first, seen walking from ``start`` to ``end``."""

    start: Point
    end: Point
    rooms: tuple[str | None, str | None]
    height: float
    thickness: float = HOUSE_WALL_THICKNESS

    @property
    def length(self) -> float:
        return math.hypot(self.end[0] - self.start[0], self.end[1] - self.start[1])

    @property
    def outside(self) -> bool:
        return None in self.rooms

    def to_dict(self) -> dict[str, Any]:
        return {
            "start": list(self.start),
            "end": list(self.end),
            "rooms": list(self.rooms),
            "height": self.height,
            "thickness": self.thickness,
        }

    @classmethod
    def from_dict(cls, data: dict[str, Any]) -> HouseWall:
        left, right = data["rooms"]
        return cls(
            start=_point(data["start"]),
            end=_point(data["end"]),
            rooms=(left, right),
            height=float(data["height"]),
            thickness=float(data.get("thickness", HOUSE_WALL_THICKNESS)),
        )


@dataclass(frozen=True)
class HouseRoom:
    """One room of a house: its type and name, its outline (walls' centre lines, house
    frame), and its own ``Room`` (inner faces and openings, in its own frame)."""

    id: str
    type: str
    #: How the text names it: "kitchen", "second bedroom".
    name: str
    #: The rule set that furnishes it (a shipped name or a path).
    rules: str
    outline: tuple[Point, ...]
    offset: Point
    room: Room
    #: The room's own opening ids and the house's opening each one is: (("door_1", "door_3"), ...).
    openings: tuple[tuple[str, str], ...] = ()
    #: Once furnished: the seed its rule set was expanded with, its layout's statistics
    #: (scene.json's ``layout`` of a room scene) and its derivation.
    seed: int = 0
    layout: dict[str, Any] = field(default_factory=dict)
    derivation: tuple[dict[str, Any], ...] = ()

    @property
    def area(self) -> float:
        """The floor area inside the walls (square metres)."""
        return self.room.area

    def house_opening(self, local_id: str) -> str:
        return dict(self.openings)[local_id]

    def to_house(self, x: float, z: float) -> Point:
        return x + self.offset[0], z + self.offset[1]

    def to_dict(self) -> dict[str, Any]:
        return {
            "id": self.id,
            "type": self.type,
            "name": self.name,
            "rules": self.rules,
            "area": round(self.area, 6),
            "outline": [list(p) for p in self.outline],
            "offset": list(self.offset),
            "room": self.room.to_dict(),
            "openings": {local: house for local, house in self.openings},
            "seed": self.seed,
            "layout": self.layout,
            "derivation": list(self.derivation),
        }

    @classmethod
    def from_dict(cls, data: dict[str, Any]) -> HouseRoom:
        return cls(
            id=str(data["id"]),
            type=str(data["type"]),
            name=str(data["name"]),
            rules=str(data["rules"]),
            outline=tuple(_point(p) for p in data["outline"]),
            offset=_point(data["offset"]),
            room=Room.from_dict(data["room"]),
            openings=tuple((str(k), str(v)) for k, v in data.get("openings", {}).items()),
            seed=int(data.get("seed", 0)),
            layout=dict(data.get("layout", {})),
            derivation=tuple(data.get("derivation", [])),
        )


@dataclass(frozen=True)
class House:
    """A floor plan: rooms, the walls between and around them, doors and windows."""

    #: What the text calls the whole ("flat", "house", "office floor").
    noun: str
    #: The outer outline of the floor (walls' centre lines) and any courtyards in it.
    footprint: tuple[Point, ...]
    holes: tuple[tuple[Point, ...], ...]
    height: float
    rooms: tuple[HouseRoom, ...]
    walls: tuple[HouseWall, ...]
    openings: tuple[HouseOpening, ...]

    def room(self, room_id: str) -> HouseRoom:
        for room in self.rooms:
            if room.id == room_id:
                return room
        raise KeyError(room_id)

    def opening(self, opening_id: str) -> HouseOpening:
        for opening in self.openings:
            if opening.id == opening_id:
                return opening
        raise KeyError(opening_id)

    @property
    def doors(self) -> list[HouseOpening]:
        return [o for o in self.openings if o.kind == "door"]

    @property
    def entrance(self) -> HouseOpening | None:
        """The front door (the first door to the outside), if the house has one."""
        return next((o for o in self.openings if o.entrance), None)

    def neighbours(self, room_id: str) -> list[tuple[str, HouseOpening]]:
        """The rooms a door leads to from ``room_id``, with the door, in door order."""
        found = []
        for door in self.doors:
            if room_id in door.rooms and len(door.rooms) == 2:
                other = door.rooms[1] if door.rooms[0] == room_id else door.rooms[0]
                found.append((other, door))
        return found

    def reachable(self) -> set[str]:
        """The rooms one can walk to through doors from the front door (every room when
        the house has no front door: then from the first room)."""
        entrance = self.entrance
        start = entrance.rooms[0] if entrance is not None else self.rooms[0].id
        seen, todo = {start}, [start]
        while todo:
            for other, _door in self.neighbours(todo.pop()):
                if other not in seen:
                    seen.add(other)
                    todo.append(other)
        return seen

    @property
    def extent(self) -> tuple[float, float]:
        xs = [p[0] for p in self.footprint]
        zs = [p[1] for p in self.footprint]
        return max(xs) - min(xs), max(zs) - min(zs)

    def to_dict(self) -> dict[str, Any]:
        return {
            "noun": self.noun,
            "footprint": [list(p) for p in self.footprint],
            "holes": [[list(p) for p in hole] for hole in self.holes],
            "height": self.height,
            "rooms": [room.to_dict() for room in self.rooms],
            "walls": [wall.to_dict() for wall in self.walls],
            "openings": [opening.to_dict() for opening in self.openings],
        }

    @classmethod
    def from_dict(cls, data: dict[str, Any]) -> House:
        return cls(
            noun=str(data["noun"]),
            footprint=tuple(_point(p) for p in data["footprint"]),
            holes=tuple(tuple(_point(p) for p in hole) for hole in data.get("holes", [])),
            height=float(data["height"]),
            rooms=tuple(HouseRoom.from_dict(r) for r in data["rooms"]),
            walls=tuple(HouseWall.from_dict(w) for w in data["walls"]),
            openings=tuple(HouseOpening.from_dict(o) for o in data["openings"]),
        )


def room_of(object_id: str) -> str | None:
    """The room id in a house scene's object id (``bedroom_2/bed_1`` -> ``bedroom_2``)."""
    head, separator, _rest = object_id.partition(ID_SEPARATOR)
    return head if separator else None


def in_room(room_id: str, local_id: str) -> str:
    """A room's own id of one of its things, as the house scene names it."""
    return f"{room_id}{ID_SEPARATOR}{local_id}"


def _point(raw) -> Point:
    return float(raw[0]), float(raw[1])
