"""From room outlines to a house: its walls, where its doors and windows go, each room's own ``Room``.

``build_house`` works on any outlines, generated or given, as long as neighbouring
rooms share the stretch of outline between them (the walls' centre lines):

- walls: every room's outline is cut where other rooms' outlines run along it; a piece
  another room shares is one wall between the two (kept once), a piece nobody shares
  an outside wall;
- doors: each planned door goes in the longest wall its two rooms share (the front door
  in the longest outside wall of its room, a south-facing one when there is a tie), near
  one end of it or in its middle as the plan's stream draws, clear of the corners and of
  other openings; an open doorway is as wide as the wall allows up to ``OPEN_WIDTH``;
- windows: a room that wants one gets one in its longest outside wall (a second in the
  next longest in a room of ``TWO_WINDOWS_AREA`` with ``WINDOW_PER_METRES`` of outside wall), shaped like the window of
  its rule set's own room;
- rooms: each outline moved in by half a wall's thickness is the room's ``Room`` (inner
  faces), in its own frame, with the openings that belong to it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from scenewright.core.errors import InputError, RoomError
from scenewright.core.geometry import signed_area
from scenewright.core.house import (
    HOUSE_WALL_THICKNESS,
    House,
    HouseOpening,
    HouseRoom,
    HouseWall,
)
from scenewright.core.room import DEFAULT_DOOR_HEIGHT, Room

from .outline import Outlines, PlannedDoor, PlannedRoom

Point = tuple[float, float]

#: Widths (m): a door between rooms, the front door, the widest open doorway.
DOOR_WIDTH = 0.9
FRONT_DOOR_WIDTH = 1.0
OPEN_WIDTH = 1.2
#: Free wall kept between an opening and a corner, and between two openings (m).
CORNER_MARGIN = 0.2
#: A room with this much outside wall and this much floor or more gets two windows
#: (every window takes wall that furniture would stand against).
WINDOW_PER_METRES = 7.0
TWO_WINDOWS_AREA = 22.0
#: The window of a room whose rule set's room has none: width, height, sill.
DEFAULT_WINDOW = (1.2, 1.3, 0.9)
_EPS = 1e-6


class HouseError(InputError):
    """Outlines that make no house (rooms overlapping, a door between rooms that do not touch)."""


@dataclass
class _Piece:
    """A stretch of one room's outline: shared with ``other`` (a room index) or outside (None)."""

    room: int
    other: int | None
    start: Point
    end: Point

    @property
    def length(self) -> float:
        return math.dist(self.start, self.end)

    @property
    def direction(self) -> Point:
        length = self.length
        return (self.end[0] - self.start[0]) / length, (self.end[1] - self.start[1]) / length

    def at(self, u: float) -> Point:
        tx, tz = self.direction
        return self.start[0] + u * tx, self.start[1] + u * tz


def build_house(
    outlines: Outlines, rng: np.random.Generator, thickness: float = HOUSE_WALL_THICKNESS
) -> House:
    rooms = outlines.rooms
    pieces = _pieces(rooms)
    walls = _walls(rooms, pieces, outlines.height, thickness)
    openings: list[HouseOpening] = []
    taken: dict[int, list[tuple[float, float]]] = {}  # piece index -> occupied (u0, u1)
    swings: list[tuple[float, float, float, float]] = []  # boxes kept free by doors placed
    for planned in outlines.doors:
        openings.append(_door(planned, rooms, pieces, taken, swings, rng, len(openings)))
    if outlines.windows is None:
        openings.extend(_windows(rooms, pieces, taken))
    else:
        for window in outlines.windows:
            k = _room_index(rooms, window.room)
            direction = _direction_at(pieces, k, None, window.center)
            openings.append(
                HouseOpening(
                    f"window_{sum(o.kind == 'window' for o in openings) + 1}",
                    "window",
                    (window.room,),
                    window.center,
                    direction,
                    window.width,
                    window.height,
                    window.sill,
                )
            )
    house_rooms = tuple(
        _house_room(room, [o for o in openings if room.id in o.rooms], outlines.height, thickness)
        for room in rooms
    )
    return House(
        noun=outlines.noun,
        footprint=outlines.footprint,
        holes=outlines.holes,
        height=outlines.height,
        rooms=house_rooms,
        walls=tuple(walls),
        openings=tuple(openings),
    )


# -- walls -------------------------------------------------------------------------------------


def _edges(outline) -> list[tuple[Point, Point]]:
    return [(outline[k], outline[(k + 1) % len(outline)]) for k in range(len(outline))]


def _pieces(rooms: list[PlannedRoom]) -> list[_Piece]:
    """Every room's outline cut into pieces shared with one other room or outside."""
    pieces: list[_Piece] = []
    for k, room in enumerate(rooms):
        for a, b in _edges(room.outline):
            length = math.dist(a, b)
            if length < _EPS:
                continue
            tx, tz = (b[0] - a[0]) / length, (b[1] - a[1]) / length
            covered: list[tuple[float, float, int]] = []
            for j, other in enumerate(rooms):
                if j == k:
                    continue
                for c, d in _edges(other.outline):
                    # collinear: both ends on the line through a, b
                    if abs(_cross(a, tx, tz, c)) > 1e-4 or abs(_cross(a, tx, tz, d)) > 1e-4:
                        continue
                    uc = (c[0] - a[0]) * tx + (c[1] - a[1]) * tz
                    ud = (d[0] - a[0]) * tx + (d[1] - a[1]) * tz
                    lo, hi = max(min(uc, ud), 0.0), min(max(uc, ud), length)
                    if hi - lo > 1e-4:
                        covered.append((lo, hi, j))
            covered.sort()
            u = 0.0
            for lo, hi, j in covered:
                if lo < u - 1e-4:
                    raise HouseError(
                        f"rooms {rooms[j].id} and another overlap along the wall of {room.id}"
                    )
                if lo > u + 1e-4:
                    pieces.append(_Piece(k, None, _along(a, tx, tz, u), _along(a, tx, tz, lo)))
                pieces.append(_Piece(k, j, _along(a, tx, tz, lo), _along(a, tx, tz, hi)))
                u = hi
            if u < length - 1e-4:
                pieces.append(_Piece(k, None, _along(a, tx, tz, u), b))
    return pieces


def _walls(rooms, pieces: list[_Piece], height: float, thickness: float) -> list[HouseWall]:
    walls = []
    for piece in pieces:
        if piece.other is not None and piece.other < piece.room:
            continue  # the other room's piece is the same wall
        left_is_room = signed_area(rooms[piece.room].outline) > 0
        mine = rooms[piece.room].id
        theirs = rooms[piece.other].id if piece.other is not None else None
        sides = (mine, theirs) if left_is_room else (theirs, mine)
        walls.append(HouseWall(piece.start, piece.end, sides, height, thickness))
    return walls


# -- doors and windows -------------------------------------------------------------------------


def _door(planned: PlannedDoor, rooms, pieces, taken, swings, rng, number: int) -> HouseOpening:
    ids = [_room_index(rooms, r) for r in planned.rooms]
    front = len(ids) == 1
    other = None if front else ids[1]
    candidates = [(n, p) for n, p in enumerate(pieces) if p.room == ids[0] and p.other == other]
    words = " and ".join(planned.rooms)
    if not candidates:
        where = "an outside wall" if front else "a wall"
        raise HouseError(
            f"a door for {words}: they share no {where}"
            if not front
            else f"the front door: {planned.rooms[0]} has no outside wall"
        )
    if planned.open:
        width = OPEN_WIDTH
    else:
        width = planned.width or (FRONT_DOOR_WIDTH if front else DOOR_WIDTH)
    center = planned.center
    if center is not None:
        n, piece = min(candidates, key=lambda item: _distance_to(item[1], center))
        u = _project(piece, center)
        if _distance_to(piece, center) > 0.05:
            raise HouseError(
                f"the door of {words} at {planned.center} is not on a wall between them"
            )
        width = planned.width or width
    else:
        inward = _inward(rooms[ids[0]])

        def preference(item):
            n, p = item
            facing_south = front and _outward_normal(p, inward)[1] > 0.9
            return (p.length >= width + 2 * CORNER_MARGIN, facing_south, round(p.length, 3), -n)

        n, piece = max(candidates, key=preference)
        room_for = piece.length - 2 * CORNER_MARGIN
        if room_for < 0.7:
            raise HouseError(
                f"a door for {words}: the wall they share is only {piece.length:.2f} m"
            )
        width = min(width, room_for)
        sides = [(piece, _inward(rooms[piece.room]))]
        if piece.other is not None:
            sides.append((piece, -_inward(rooms[piece.room])))

        def clear(u: float) -> bool:
            boxes = [_swing_box(p, u, width, inward) for p, inward in sides]
            return not any(_boxes_meet(a, b) for a in boxes for b in swings)

        # the front door and open doorways go mid-wall (furniture runs into the corners
        # either side: a kitchen's counters); a door between rooms near a corner as often
        middle = front or planned.open
        u = _place(piece.length, width, taken.get(n, []), rng, front=middle, clear=clear)
        swings.extend(_swing_box(piece, u, width, inward) for _p, inward in sides)
    taken.setdefault(n, []).append((u - width / 2, u + width / 2))
    _mirror_taken(pieces, n, u, width, taken)
    return HouseOpening(
        f"door_{number + 1}",
        "door",
        tuple(planned.rooms),
        piece.at(u),
        piece.direction,
        round(width, 6),
        DEFAULT_DOOR_HEIGHT,
        0.0,
        planned.open,
    )


def _place(length: float, width: float, occupied, rng, *, front: bool, clear) -> float:
    """Where along a wall ``length`` long an opening ``width`` wide goes: near its start,
    in its middle or near its end (drawn), clear of the openings in the wall and of the
    swings of the doors placed (``clear``); else anywhere along it that is."""
    lo = CORNER_MARGIN + width / 2
    hi = length - CORNER_MARGIN - width / 2
    options = [(lo + hi) / 2] if front else [lo, (lo + hi) / 2, hi]
    order = [options[k] for k in rng.permutation(len(options))]
    order += [float(u) for u in np.linspace(lo, hi, 9) if float(u) not in order]

    def free(u: float) -> bool:
        return all(
            u + width / 2 + CORNER_MARGIN <= a or u - width / 2 - CORNER_MARGIN >= b
            for a, b in occupied
        )

    for u in order:
        if free(u) and clear(u):
            return u
    return next((u for u in order if free(u)), order[0])


def _inward(room: PlannedRoom) -> float:
    """+1 when the room lies on the left of its outline's edges, -1 when on the right."""
    return 1.0 if signed_area(room.outline) > 0 else -1.0


def _swing_box(piece: _Piece, u: float, width: float, inward: float):
    """The box (x0, z0, x1, z1) a door ``width`` wide at ``u`` keeps free on one side."""
    tx, tz = piece.direction
    nx, nz = -tz * inward, tx * inward
    a = piece.at(u - width / 2)
    b = piece.at(u + width / 2)
    c = (b[0] + nx * width, b[1] + nz * width)
    d = (a[0] + nx * width, a[1] + nz * width)
    xs, zs = [p[0] for p in (a, b, c, d)], [p[1] for p in (a, b, c, d)]
    return min(xs), min(zs), max(xs), max(zs)


def _boxes_meet(a, b) -> bool:
    return a[0] < b[2] - 1e-6 and b[0] < a[2] - 1e-6 and a[1] < b[3] - 1e-6 and b[1] < a[3] - 1e-6


def _mirror_taken(pieces, n: int, u: float, width: float, taken) -> None:
    """Mark the same stretch taken on the other room's piece of the same wall."""
    piece = pieces[n]
    if piece.other is None:
        return
    centre = piece.at(u)
    for m, other in enumerate(pieces):
        if (
            other.room == piece.other
            and other.other == piece.room
            and _distance_to(other, centre) < 1e-4
        ):
            v = _project(other, centre)
            taken.setdefault(m, []).append((v - width / 2, v + width / 2))


def _windows(rooms: list[PlannedRoom], pieces: list[_Piece], taken) -> list[HouseOpening]:
    windows: list[HouseOpening] = []
    for k, room in enumerate(rooms):
        if not room.wants_window:
            continue
        outside = sorted(
            ((n, p) for n, p in enumerate(pieces) if p.room == k and p.other is None),
            key=lambda item: (-round(item[1].length, 3), item[0]),
        )
        total = sum(p.length for _n, p in outside)
        area = abs(signed_area(room.outline))
        wanted = 2 if total >= WINDOW_PER_METRES and area >= TWO_WINDOWS_AREA else 1
        width, height, sill = room.window or DEFAULT_WINDOW
        made = 0
        for n, piece in outside:
            if made == wanted:
                break
            room_for = piece.length - 2 * CORNER_MARGIN
            fits = min(width, room_for)
            if fits < 0.6:
                continue
            u = piece.length / 2
            occupied = taken.get(n, [])
            if not all(
                u + fits / 2 + CORNER_MARGIN <= a or u - fits / 2 - CORNER_MARGIN >= b
                for a, b in occupied
            ):
                free = _free_spot(piece.length, fits, occupied)
                if free is None:
                    continue
                u = free
            taken.setdefault(n, []).append((u - fits / 2, u + fits / 2))
            windows.append(
                HouseOpening(
                    f"window_{len(windows) + 1}",
                    "window",
                    (room.id,),
                    piece.at(u),
                    piece.direction,
                    round(fits, 6),
                    height,
                    sill,
                )
            )
            made += 1
    return windows


def _free_spot(length: float, width: float, occupied) -> float | None:
    lo = CORNER_MARGIN + width / 2
    hi = length - CORNER_MARGIN - width / 2
    for u in np.linspace(lo, hi, 25):
        if all(
            u + width / 2 + CORNER_MARGIN <= a or u - width / 2 - CORNER_MARGIN >= b
            for a, b in occupied
        ):
            return float(u)
    return None


# -- each room's own Room -----------------------------------------------------------------------


def _house_room(
    room: PlannedRoom, openings: list[HouseOpening], height: float, thickness: float
) -> HouseRoom:
    inner = inset(room.outline, thickness / 2.0)
    xs, zs = [p[0] for p in inner], [p[1] for p in inner]
    offset = ((min(xs) + max(xs)) / 2.0, (min(zs) + max(zs)) / 2.0)
    try:
        shape = Room.polygon(
            [(x - offset[0], z - offset[1]) for x, z in inner], height, centre=False
        )
    except RoomError as error:
        raise HouseError(f"room {room.id}: {error}") from None
    pairs = []
    for opening in openings:
        local = (opening.center[0] - offset[0], opening.center[1] - offset[1])
        wall = _wall_at(shape, local, thickness / 2.0)
        if wall is None:
            raise HouseError(f"room {room.id}: {opening.id} is not in one of its walls")
        u, _v = wall.to_wall(*local)
        half = opening.width / 2
        u = min(max(u, half), wall.length - half)
        try:
            shape = shape.with_opening(
                opening.kind,
                wall.id,
                round(u, 6),
                opening.width,
                opening.height,
                opening.sill,
            )
        except RoomError as error:
            raise HouseError(f"room {room.id}: {opening.id}: {error}") from None
        pairs.append((shape.openings[-1].id, opening.id))
    return HouseRoom(
        id=room.id,
        type=room.type,
        name=room.name,
        rules=room.rules,
        outline=tuple(room.outline),
        offset=offset,
        room=shape,
        openings=tuple(pairs),
    )


def _wall_at(shape: Room, point: Point, depth: float):
    """The wall of ``shape`` whose inner face runs ``depth`` in front of ``point`` (an
    opening's centre on the wall's centre line)."""
    best, best_gap = None, 0.03
    for wall in shape.walls:
        u, v = wall.to_wall(*point)
        if -1e-6 <= u <= wall.length + 1e-6 and abs(v + depth) < best_gap:
            best, best_gap = wall, abs(v + depth)
    return best


def inset(outline, distance: float) -> list[Point]:
    """The polygon ``outline`` moved ``distance`` inwards, corners mitred."""
    points = list(outline)
    n = len(points)
    sign = 1.0 if signed_area(points) > 0 else -1.0
    lines = []
    for k in range(n):
        a, b = points[k], points[(k + 1) % n]
        length = math.dist(a, b)
        tx, tz = (b[0] - a[0]) / length, (b[1] - a[1]) / length
        # the inside is on the left of a counter-clockwise outline (positive shoelace area)
        nx, nz = -tz * sign, tx * sign
        lines.append(((a[0] + nx * distance, a[1] + nz * distance), (tx, tz)))
    corners = []
    for k in range(n):
        (p, d), (q, e) = lines[k - 1], lines[k]
        det = d[0] * (-e[1]) - d[1] * (-e[0])
        if abs(det) < 1e-9:
            corners.append(q)
            continue
        s = ((q[0] - p[0]) * (-e[1]) - (q[1] - p[1]) * (-e[0])) / det
        corners.append((round(p[0] + s * d[0], 9), round(p[1] + s * d[1], 9)))
    return corners


# -- small geometry -------------------------------------------------------------------------------


def _room_index(rooms: list[PlannedRoom], room_id: str) -> int:
    for k, room in enumerate(rooms):
        if room.id == room_id:
            return k
    raise HouseError(f"there is no room {room_id!r}")


def _direction_at(pieces, k: int, other, point: Point) -> Point:
    candidates = [p for p in pieces if p.room == k and p.other == other]
    if not candidates:
        raise HouseError("a window of a room with no outside wall")
    piece = min(candidates, key=lambda p: _distance_to(p, point))
    if _distance_to(piece, point) > 0.05:
        raise HouseError(f"the window at {point} is not on an outside wall of its room")
    return piece.direction


def _outward_normal(piece: _Piece, inward: float) -> Point:
    """The unit normal (x, z) of a piece pointing out of the room (``inward`` as ``_inward``)."""
    tx, tz = piece.direction
    return tz * inward, -tx * inward


def _cross(a: Point, tx: float, tz: float, p: Point) -> float:
    return (p[0] - a[0]) * tz - (p[1] - a[1]) * tx


def _along(a: Point, tx: float, tz: float, u: float) -> Point:
    return round(a[0] + u * tx, 9), round(a[1] + u * tz, 9)


def _project(piece: _Piece, point: Point) -> float:
    tx, tz = piece.direction
    return (point[0] - piece.start[0]) * tx + (point[1] - piece.start[1]) * tz


def _distance_to(piece: _Piece, point: Point) -> float:
    u = min(max(_project(piece, point), 0.0), piece.length)
    return math.dist(piece.at(u), point)
