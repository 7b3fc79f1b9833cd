"""A room: its walls (a simple polygon), doors and windows, and the geometry all stages ask of it.

World frame as everywhere (``core.frames``): metres, +Y up, north is -Z, east +X. A room
is the polygon of its walls' inner faces, corners in order around it; wall ``k`` runs
from corner ``k`` to corner ``k + 1`` (the last back to the first). A rectangle
``W x D`` is centred on the origin with corners north-west, north-east, south-east,
south-west, so its walls are, in order, the north, east, south and west walls. A
polygon given by corners is shifted so its bounding box is centred on the origin (the
scene's extent is that box).

Each wall has a frame of its own: ``u`` runs along it from its start corner (0) to its
end corner (``length``), ``v`` is the distance into the room along its inner normal.
An opening (door or window) sits in one wall: ``offset`` is its centre's ``u``,
``width`` its extent along the wall, ``sill`` its bottom above the floor (0 for a
door), ``height`` its own height. A door swings into the room: its swing zone is the
square ``width`` x ``width`` in front of it, kept free of furniture by the layout.

Walls, doors and windows are nodes of the scene graph (kinds ``wall``, ``door``,
``window``; ids ``wall_1``, ``door_1``, ``window_1``, ... in declaration order) so
relations can name them; the room node ``room`` stands for "whichever wall (or window)
fits", chosen by the layout and recorded as the relation's ``chosen``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import cached_property

from scenewright.core.errors import RoomError
from scenewright.core.geometry import left_normal, point_segment_distance, signed_area

#: Scene-graph node kinds of a room and its parts, and the id of the node that stands for the room.
ROOM_KINDS = ("room", "wall", "door", "window")
ROOM_NODE = "room"
OPENING_KINDS = ("door", "window")

DEFAULT_WALL_HEIGHT = 2.6
DEFAULT_DOOR_HEIGHT = 2.05
#: Thickness of a wall behind its inner face (drawing only; the room is the inner faces).
WALL_THICKNESS = 0.12

#: Eight compass words by the direction (x, z) they name (north is -Z, east +X).
_COMPASS8 = (
    ("north", (0.0, -1.0)),
    ("north-east", (math.sqrt(0.5), -math.sqrt(0.5))),
    ("east", (1.0, 0.0)),
    ("south-east", (math.sqrt(0.5), math.sqrt(0.5))),
    ("south", (0.0, 1.0)),
    ("south-west", (-math.sqrt(0.5), math.sqrt(0.5))),
    ("west", (-1.0, 0.0)),
    ("north-west", (-math.sqrt(0.5), -math.sqrt(0.5))),
)


def compass_word(dx: float, dz: float) -> str:
    """The nearest of the eight compass words to the direction (dx, dz)."""
    return max(_COMPASS8, key=lambda item: item[1][0] * dx + item[1][1] * dz)[0]


@dataclass(frozen=True)
class Wall:
    """One wall's inner face, from corner ``start`` to corner ``end`` (x, z), ``height`` tall."""

    id: str
    start: tuple[float, float]
    end: tuple[float, float]
    height: float
    #: Inner normal (x, z): unit, pointing into the room.
    normal: tuple[float, float]

    # Derived once: the layout asks for them at every step.
    @cached_property
    def length(self) -> float:
        return math.hypot(self.end[0] - self.start[0], self.end[1] - self.start[1])

    @cached_property
    def direction(self) -> tuple[float, float]:
        """Unit vector (x, z) along the wall, start to end."""
        length = self.length
        return (self.end[0] - self.start[0]) / length, (self.end[1] - self.start[1]) / length

    @property
    def side(self) -> str:
        """The compass side of the room this wall is on: a wall whose inner face looks
        south is the north wall."""
        return compass_word(-self.normal[0], -self.normal[1])

    @property
    def facing_yaw(self) -> float:
        """The yaw of an object with its back to this wall, facing into the room."""
        return math.atan2(self.normal[0], self.normal[1])

    def to_wall(self, x: float, z: float) -> tuple[float, float]:
        """World (x, z) in the wall's frame: (u along it from its start, v into the room)."""
        dx, dz = x - self.start[0], z - self.start[1]
        tx, tz = self.direction
        return dx * tx + dz * tz, dx * self.normal[0] + dz * self.normal[1]

    def to_world(self, u: float, v: float) -> tuple[float, float]:
        """The wall frame's (u, v) in world (x, z)."""
        tx, tz = self.direction
        return self.start[0] + u * tx + v * self.normal[0], self.start[
            1
        ] + u * tz + v * self.normal[1]


@dataclass(frozen=True)
class Opening:
    """A door or a window in a wall (see the module docstring for the frame)."""

    id: str
    kind: str  # "door" or "window"
    wall: str
    offset: float
    width: float
    height: float
    sill: float = 0.0
    #: Centre of the opening on the wall's inner face (x, z), set by the room.
    center: tuple[float, float] = (0.0, 0.0)

    @property
    def top(self) -> float:
        return self.sill + self.height

    @property
    def span(self) -> tuple[float, float]:
        """Where it starts and ends along its wall (u, metres from the wall's start)."""
        return self.offset - self.width / 2.0, self.offset + self.width / 2.0


@dataclass(frozen=True)
class Room:
    """A room's walls (in order around it) and its openings."""

    walls: tuple[Wall, ...]
    openings: tuple[Opening, ...] = ()
    _by_id: dict[str, Wall | Opening] = field(default_factory=dict, compare=False, repr=False)

    def __post_init__(self) -> None:
        by_id: dict[str, Wall | Opening] = {wall.id: wall for wall in self.walls}
        by_id.update({opening.id: opening for opening in self.openings})
        object.__setattr__(self, "_by_id", by_id)

    # -- building -----------------------------------------------------------------

    @classmethod
    def rectangle(cls, width: float, depth: float, height: float = DEFAULT_WALL_HEIGHT) -> Room:
        """A ``width`` x ``depth`` room centred on the origin: walls north, east, south, west."""
        hw, hd = width / 2.0, depth / 2.0
        return cls.polygon([(-hw, -hd), (hw, -hd), (hw, hd), (-hw, hd)], height, centre=False)

    @classmethod
    def polygon(cls, corners, height: float = DEFAULT_WALL_HEIGHT, *, centre: bool = True) -> Room:
        """A room whose inner wall faces run through ``corners`` (x, z) in order; the
        bounding box is moved onto the origin unless ``centre`` is False."""
        points = [(float(x), float(z)) for x, z in corners]
        if len(points) < 3:
            raise RoomError("a room needs at least 3 corners")
        if not all(math.isfinite(v) for p in points for v in p):
            raise RoomError("a room corner is not a finite number")
        if centre:
            xs, zs = [p[0] for p in points], [p[1] for p in points]
            cx, cz = (min(xs) + max(xs)) / 2.0, (min(zs) + max(zs)) / 2.0
            points = [(x - cx, z - cz) for x, z in points]
        n = len(points)
        for k in range(n):
            a, b = points[k], points[(k + 1) % n]
            if math.hypot(b[0] - a[0], b[1] - a[1]) < 0.05:
                raise RoomError(
                    f"wall {k + 1} is shorter than 5 cm (corners {k + 1} and {(k + 1) % n + 1} coincide)"
                )
        _refuse_self_crossing(points)
        area = signed_area(points)
        if abs(area) < 0.25:
            raise RoomError("the room's floor is smaller than 0.25 square metres")
        if height <= 0.0 or not math.isfinite(height):
            raise RoomError(f"wall height {height:g} is not a positive number of metres")
        walls = []
        for k in range(n):
            (x0, z0), (x1, z1) = points[k], points[(k + 1) % n]
            left = left_normal(x0, z0, x1, z1)
            assert left is not None  # walls shorter than 5 cm were refused above
            # Counter-clockwise in (x, z) (positive shoelace area): the inside is on the left.
            normal = left if area > 0 else (-left[0] + 0.0, -left[1] + 0.0)  # + 0.0: no -0.0
            walls.append(Wall(f"wall_{k + 1}", (x0, z0), (x1, z1), float(height), normal))
        return cls(tuple(walls))

    def with_opening(
        self,
        kind: str,
        wall: str,
        offset: float,
        width: float,
        height: float | None = None,
        sill: float = 0.0,
    ) -> Room:
        """This room with one more door or window; refuses one that does not fit its wall."""
        if kind not in OPENING_KINDS:
            raise RoomError(f"an opening is a door or a window, not {kind!r}")
        target = self.wall(wall)
        if target is None:
            raise RoomError(f"there is no wall {wall!r} (the walls are {_names(self)})")
        if height is None:
            height = min(DEFAULT_DOOR_HEIGHT, target.height) if kind == "door" else 1.2
        if kind == "door":
            sill = 0.0
        for name, value in (("width", width), ("height", height)):
            if not (value > 0.0 and math.isfinite(value)):
                raise RoomError(f"the {kind}'s {name} {value:g} is not a positive number of metres")
        if sill < 0.0 or not math.isfinite(sill):
            raise RoomError(f"the window's sill {sill:g} is below the floor")
        if width > target.length + 1e-9:
            raise RoomError(
                f"the {kind} ({width:g} m wide) is wider than {_wall_words(target)} ({target.length:g} m)"
            )
        if offset - width / 2.0 < -1e-9 or offset + width / 2.0 > target.length + 1e-9:
            raise RoomError(
                f"the {kind} at {offset:g} m, {width:g} m wide, runs past the end of "
                f"{_wall_words(target)} ({target.length:g} m long)"
            )
        if sill + height > target.height + 1e-9:
            raise RoomError(
                f"the {kind}'s top ({sill + height:g} m) is above the wall ({target.height:g} m)"
            )
        for other in self.openings_on(target.id):
            if abs(other.offset - offset) < (other.width + width) / 2.0 - 1e-9:
                raise RoomError(
                    f"the {kind} overlaps {other.id.replace('_', ' ')} on {_wall_words(target)}"
                )
        count = sum(1 for o in self.openings if o.kind == kind) + 1
        center = target.to_world(offset, 0.0)
        opening = Opening(
            f"{kind}_{count}",
            kind,
            target.id,
            float(offset),
            float(width),
            float(height),
            float(sill),
            center,
        )
        return Room(self.walls, self.openings + (opening,))

    # -- lookups ------------------------------------------------------------------

    def wall(self, name: str) -> Wall | None:
        """A wall by id (``wall_2``), number (``2``) or, for a side only one wall is on,
        compass side (``north``)."""
        found = self._by_id.get(name)
        if isinstance(found, Wall):
            return found
        if name.isdigit() and 1 <= int(name) <= len(self.walls):
            return self.walls[int(name) - 1]
        on_side = [wall for wall in self.walls if wall.side == name]
        return on_side[0] if len(on_side) == 1 else None

    def part(self, part_id: str) -> Wall | Opening:
        """The wall or opening with this id."""
        return self._by_id[part_id]

    def wall_by_id(self, wall_id: str) -> Wall:
        """The wall with this id (``wall_2``)."""
        return self.walls[self._wall_index[wall_id]]

    def wall_of(self, opening: Opening) -> Wall:
        """The wall an opening is in."""
        return self.wall_by_id(opening.wall)

    def openings_on(self, wall_id: str) -> list[Opening]:
        return [o for o in self.openings if o.wall == wall_id]

    @property
    def doors(self) -> list[Opening]:
        return [o for o in self.openings if o.kind == "door"]

    @property
    def windows(self) -> list[Opening]:
        return [o for o in self.openings if o.kind == "window"]

    def neighbours(self, wall_id: str) -> tuple[Wall, Wall]:
        """The walls before and after this one around the room."""
        index = self._wall_index[wall_id]
        return self.walls[index - 1], self.walls[(index + 1) % len(self.walls)]

    @cached_property
    def _wall_index(self) -> dict[str, int]:
        return {wall.id: k for k, wall in enumerate(self.walls)}

    @cached_property
    def corners(self) -> tuple[tuple[float, float], ...]:
        return tuple(wall.start for wall in self.walls)

    @cached_property
    def bounds(self) -> tuple[float, float, float, float]:
        """The room's bounding box: (x0, z0, x1, z1)."""
        xs = [p[0] for p in self.corners]
        zs = [p[1] for p in self.corners]
        return min(xs), min(zs), max(xs), max(zs)

    @property
    def extent(self) -> tuple[float, float]:
        """Width (x) and depth (z) of the room's bounding box."""
        x0, z0, x1, z1 = self.bounds
        return x1 - x0, z1 - z0

    @property
    def area(self) -> float:
        return abs(signed_area(self.corners))

    @property
    def height(self) -> float:
        return max(wall.height for wall in self.walls)

    def convex_corner(self, first: Wall, second: Wall) -> bool:
        """Whether the corner where ``first`` ends and ``second`` starts is an inside
        corner one can stand furniture in (interior angle under 180 degrees)."""
        # Going round, the walls turn towards the inside at a convex corner.
        bx, bz = second.direction
        return bx * first.normal[0] + bz * first.normal[1] > 1e-9

    # -- geometry ---------------------------------------------------------------------

    def contains(self, x: float, z: float) -> bool:
        """Whether the point (x, z) is on the floor (inside the walls)."""
        inside = False
        corners = self.corners
        n = len(corners)
        for k in range(n):
            (x0, z0), (x1, z1) = corners[k], corners[(k + 1) % n]
            if (z0 > z) != (z1 > z) and x < x0 + (z - z0) * (x1 - x0) / (z1 - z0):
                inside = not inside
        return inside

    def boundary_distance(self, x: float, z: float) -> float:
        """Distance from (x, z) to the nearest wall face."""
        return min(point_segment_distance(x, z, *wall.start, *wall.end) for wall in self.walls)

    def footprint_excess(self, corners: list[tuple[float, float]]) -> float:
        """How far (metres) a convex footprint (its corners, in order) crosses the walls:
        the deepest of its corners outside the room and of the room's corners inside it.
        0 when it stands wholly on the floor."""
        excess = 0.0
        for x, z in corners:
            if not self.contains(x, z):
                excess = max(excess, self.boundary_distance(x, z))
        clockwise = signed_area(corners) < 0
        for wx, wz in self.corners:  # a room corner poking into the footprint (L-shaped rooms)
            excess = max(excess, _depth_in_convex(wx, wz, corners, clockwise))
        return excess

    def opening_ends(self, opening: Opening) -> tuple[tuple[float, float], tuple[float, float]]:
        """The two ends (x, z) of the stretch of wall an opening fills."""
        wall, (u0, u1) = self.wall_of(opening), opening.span
        return wall.to_world(u0, 0.0), wall.to_world(u1, 0.0)

    def swing_zone(self, door: Opening) -> list[tuple[float, float]]:
        """The door's swing zone: corners (x, z) of the ``width`` x ``width`` square in
        front of it, inside the room."""
        wall = self.wall_of(door)
        u0, u1 = door.span
        return [
            wall.to_world(u0, 0.0),
            wall.to_world(u1, 0.0),
            wall.to_world(u1, door.width),
            wall.to_world(u0, door.width),
        ]

    # -- plain data -----------------------------------------------------------------

    def to_dict(self) -> dict:
        """scene.json's ``room``: walls (inner faces, in order) and openings."""
        return {
            "walls": [
                {"id": w.id, "from": list(w.start), "to": list(w.end), "height": w.height}
                for w in self.walls
            ],
            "openings": [
                {
                    "id": o.id,
                    "kind": o.kind,
                    "wall": o.wall,
                    "center": list(o.center),
                    "width": o.width,
                    "height": o.height,
                    "sill": o.sill,
                }
                for o in self.openings
            ],
        }

    @classmethod
    def from_dict(cls, data: dict) -> Room:
        """The room ``to_dict`` gave (walls must join up corner to corner)."""
        raw_walls = data["walls"]
        corners = [tuple(float(v) for v in w["from"]) for w in raw_walls]
        heights = {float(w.get("height", DEFAULT_WALL_HEIGHT)) for w in raw_walls}
        room = cls.polygon(corners, max(heights), centre=False)
        # Keep each wall's own id and height as written.
        walls = tuple(
            Wall(
                str(raw["id"]),
                wall.start,
                wall.end,
                float(raw.get("height", wall.height)),
                wall.normal,
            )
            for raw, wall in zip(raw_walls, room.walls, strict=False)
        )
        room = cls(walls)
        by_id = {w.id: w for w in walls}
        openings = []
        for raw in data.get("openings", []):
            wall = by_id.get(raw["wall"])
            if wall is None:
                raise RoomError(
                    f"opening {raw['id']!r} is in wall {raw['wall']!r}, which the room does not have"
                )
            u, _ = wall.to_wall(*raw["center"])
            openings.append(
                Opening(
                    str(raw["id"]),
                    raw["kind"],
                    wall.id,
                    u,
                    float(raw["width"]),
                    float(raw["height"]),
                    float(raw.get("sill", 0.0)),
                    (float(raw["center"][0]), float(raw["center"][1])),
                )
            )
        return cls(walls, tuple(openings))


def _names(room: Room) -> str:
    sides = [wall.side for wall in room.walls]
    if len(set(sides)) == len(sides):
        return ", ".join(sides)
    return f"1 to {len(room.walls)}"


def _wall_words(wall: Wall) -> str:
    return f"{wall.id.replace('_', ' ')} (the {wall.side} wall)"


def _depth_in_convex(
    x: float, z: float, corners: list[tuple[float, float]], clockwise: bool
) -> float:
    """How deep (x, z) lies inside a convex polygon (its corners going round ``clockwise``
    or not, by the sign of its area): its distance to the nearest edge, or 0 outside."""
    n = len(corners)
    depth = math.inf
    for k in range(n):
        (x0, z0), (x1, z1) = corners[k], corners[(k + 1) % n]
        length = math.hypot(x1 - x0, z1 - z0)
        if length == 0.0:
            continue
        # Signed distance to the edge's line, positive on the inside.
        cross = ((x1 - x0) * (z - z0) - (z1 - z0) * (x - x0)) / length
        inside = -cross if clockwise else cross
        if inside <= 0.0:
            return 0.0
        depth = min(depth, inside)
    return 0.0 if depth == math.inf else depth


def _refuse_self_crossing(points: list[tuple[float, float]]) -> None:
    n = len(points)
    for i in range(n):
        a0, a1 = points[i], points[(i + 1) % n]
        for j in range(i + 1, n):
            if j == i or (j + 1) % n == i or (i + 1) % n == j:
                continue  # neighbouring walls share a corner
            b0, b1 = points[j], points[(j + 1) % n]
            if _segments_cross(a0, a1, b0, b1):
                raise RoomError(
                    f"walls {i + 1} and {j + 1} cross: the corners must go once around the room"
                )


def _segments_cross(p, q, r, s) -> bool:
    def orient(a, b, c) -> float:
        return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])

    d1, d2, d3, d4 = orient(r, s, p), orient(r, s, q), orient(p, q, r), orient(p, q, s)
    if ((d1 > 0) != (d2 > 0)) and ((d3 > 0) != (d4 > 0)) and 0 not in (d1, d2, d3, d4):
        return True
    return False
