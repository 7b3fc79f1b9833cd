"""What ``scenewright complete`` is asked for: a ``Request``, an empty room (a
``core.room.Room``) and the categories it must hold. ``parse_request`` reads the command
line's form: the room as ``W x D`` or its corners (as the rules language takes them),
its doors and windows as ``WALL:OFFSET:WIDTH[:...]``, the categories as
``bed,bookshelf`` or ``chair=4``; ``existing_request`` makes one from a furnished scene.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass

from scenewright.core.errors import InputError, RoomError
from scenewright.core.limits import MAX_EXTENT
from scenewright.core.room import Room

#: Wall letters a door or window may name, besides the words and numbers ``Room.wall`` takes.
WALL_LETTERS = {"N": "north", "E": "east", "S": "south", "W": "west"}
#: A window's sill and height when the request does not give them (metres).
DEFAULT_SILL = 0.9
DEFAULT_WINDOW_HEIGHT = 1.2
#: The most of one category a request may ask for.
MAX_COUNT = 20
#: The largest room ``complete`` furnishes, each side of its bounding box in metres, and
#: the most corners: the starting poses search the floor on a 0.1 m grid and every
#: candidate is tested against every wall, so the work grows with the area times the
#: corners (a 100 m x 100 m hall is already a million grid points).
MAX_ROOM_SIDE = 100.0
MAX_ROOM_CORNERS = 64


@dataclass(frozen=True)
class Request:
    """What the user asked for: the empty ``room`` and ``requested`` category -> count,
    and how the categories and the layout mask are chosen (``categories``, ``mask``: one
    of ``scenewright.completion.CATEGORY_METHODS`` and ``MASK_METHODS``; the defaults
    are the baselines the leave-one-out measured as good as the paper's steps)."""

    room: Room
    requested: dict[str, int]
    categories: str = "co-occurrence"
    mask: str = "mean"


def parse_room(text: str) -> Room:
    """``W x D`` (``5x4``) or corners ``x,z x,z ...`` (at least three) -> a Room."""
    spec = text.strip()
    size = re.fullmatch(r"([0-9.]+)\s*[xX]\s*([0-9.]+)", spec)
    try:
        if size:
            width, depth = (_number(part, "room side") for part in size.groups())
            if not (0.5 <= width <= MAX_ROOM_SIDE and 0.5 <= depth <= MAX_ROOM_SIDE):
                raise InputError(
                    f"room {_clipped(spec)}: each side must lie between 0.5 and {MAX_ROOM_SIDE:g} m "
                    "(the room complete furnishes; docs/limits.md)"
                )
            return Room.rectangle(width, depth)
        corners = []
        points = spec.replace(";", " ").split()
        if len(points) > MAX_ROOM_CORNERS:
            raise InputError(
                f"room: {len(points)} corners; a room complete furnishes may have at most "
                f"{MAX_ROOM_CORNERS} (docs/limits.md)"
            )
        for point in points:
            parts = point.strip("()").split(",")
            if len(parts) != 2:
                raise InputError(
                    f"room {_clipped(spec)}: give W x D (5x4) or corners x,z x,z x,z ... ({_clipped(point)} is neither)"
                )
            corners.append(tuple(_number(part, "room corner") for part in parts))
        if any(abs(v) > MAX_EXTENT for corner in corners for v in corner):
            raise InputError(
                f"room {_clipped(spec)}: a corner lies further than {MAX_EXTENT:g} m out"
            )
        room = Room.polygon(corners)
    except RoomError as problem:
        raise InputError(f"room {_clipped(spec)}: {problem}") from None
    check_room_size(room, f"room {_clipped(spec)}")
    return room


def check_room_size(room: Room, where: str) -> None:
    """Refuse a room larger than ``complete`` furnishes (``MAX_ROOM_SIDE``, ``MAX_ROOM_CORNERS``)."""
    xs, zs = [c[0] for c in room.corners], [c[1] for c in room.corners]
    sides = (max(xs) - min(xs), max(zs) - min(zs))
    if max(sides) > MAX_ROOM_SIDE:
        raise InputError(
            f"{where}: the room is {sides[0]:g} x {sides[1]:g} m; a room complete furnishes may be at "
            f"most {MAX_ROOM_SIDE:g} m each way (docs/limits.md)"
        )
    if len(room.corners) > MAX_ROOM_CORNERS:
        raise InputError(
            f"{where}: the room has {len(room.corners)} corners; a room complete furnishes may have at "
            f"most {MAX_ROOM_CORNERS} (docs/limits.md)"
        )


def _clipped(text: str) -> str:
    """``text`` quoted and shortened to 60 characters: an error never repeats a long argument."""
    shown = repr(text)
    return shown if len(shown) <= 60 else shown[:56] + "...'"


def add_opening(room: Room, kind: str, text: str) -> Room:
    """``room`` with the door ``WALL:OFFSET:WIDTH[:HEIGHT]`` or the window
    ``WALL:OFFSET:WIDTH[:SILL[:HEIGHT]]``; WALL is N, E, S, W, a side word or a wall number,
    OFFSET the centre's distance from the wall's start (its west or north end for a
    rectangle's walls, as in a rules file)."""
    parts = text.split(":")
    most = 4 if kind == "door" else 5
    if not 3 <= len(parts) <= most:
        form = (
            "WALL:OFFSET:WIDTH[:HEIGHT]" if kind == "door" else "WALL:OFFSET:WIDTH[:SILL[:HEIGHT]]"
        )
        raise InputError(
            f"{kind} {text!r}: give {form}, e.g. {'S:0.8:0.9' if kind == 'door' else 'N:2.5:1.4'}"
        )
    wall_name = WALL_LETTERS.get(parts[0].strip().upper(), parts[0].strip().lower())
    wall = room.wall(wall_name)
    if wall is None:
        sides = ", ".join(dict.fromkeys(w.side for w in room.walls))
        raise InputError(
            f"{kind} {text!r}: the room has no wall {parts[0]!r} (sides: {sides}; or 1 to {len(room.walls)})"
        )
    numbers = [_number(part, f"{kind} {text!r}") for part in parts[1:]]
    offset, width = numbers[0], numbers[1]
    if kind == "door":  # a door stands on the floor; its height defaults to the room's
        height, sill = (numbers[2] if len(numbers) > 2 else None), 0.0
    else:
        sill = numbers[2] if len(numbers) > 2 else DEFAULT_SILL
        height = numbers[3] if len(numbers) > 3 else DEFAULT_WINDOW_HEIGHT
    try:
        return room.with_opening(kind, wall.id, offset, width, height=height, sill=sill)
    except RoomError as problem:
        raise InputError(f"{kind} {text!r}: {problem}") from None


def parse_categories(texts: list[str], known) -> dict[str, int]:
    """``["bed,bookshelf", "chair=4"]`` -> ``{"bed": 1, "bookshelf": 1, "chair": 4}``; each
    name must be in ``known`` (the indoor catalog)."""
    requested: dict[str, int] = {}
    for text in texts:
        for item in (part.strip() for part in text.split(",")):
            if not item:
                continue
            name, _, count_text = item.partition("=")
            name = name.strip()
            if name not in known:
                from difflib import get_close_matches

                close = get_close_matches(name, sorted(known), n=1)
                hint = f"; did you mean {close[0]!r}?" if close else ""
                raise InputError(f"--with {item!r}: {name!r} is not an indoor catalog entry{hint}")
            count = 1
            if count_text:
                if not count_text.strip().isdigit() or not 1 <= int(count_text) <= MAX_COUNT:
                    raise InputError(
                        f"--with {item!r}: the count must be a whole number from 1 to {MAX_COUNT}"
                    )
                count = int(count_text)
            requested[name] = requested.get(name, 0) + count
    if not requested:
        raise InputError("--with names no category: ask for at least one (--with bed,bookshelf)")
    return requested


def parse_request(
    room: str, doors: list[str], windows: list[str], categories: list[str], known
) -> Request:
    """The request the command line states (see the functions above for each part)."""
    built = parse_room(room)
    for text in doors:
        built = add_opening(built, "door", text)
    for text in windows:
        built = add_opening(built, "window", text)
    return Request(built, parse_categories(categories, known))


def _number(text: str, what: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise InputError(f"{what}: {text.strip()!r} is not a number") from None
    if not math.isfinite(value):
        raise InputError(f"{what}: {text.strip()!r} is not a finite number")
    return value


def existing_request(scene, added: dict[str, int], known) -> Request:
    """The request that completes a furnished ``scene`` (a scene.json's Scene, indoor):
    its room, its objects' categories as requested (so none is given up) and ``added``
    on top. ``InputError`` for a scene without a room or with an object whose type is no
    category of the indoor catalog ``known``."""
    if scene.room is None:
        raise InputError("the scene has no room (walls): only an indoor scene can be completed")
    requested: dict[str, int] = {}
    for obj in scene.placed_objects():
        if obj.type not in known:
            raise InputError(
                f"the scene's {obj.id} is a {obj.type!r}, which is no category of the indoor catalog"
            )
        requested[obj.type] = requested.get(obj.type, 0) + 1
    for name, count in added.items():
        requested[name] = requested.get(name, 0) + count
    check_room_size(scene.room, "the scene's room")
    return Request(scene.room, requested)
