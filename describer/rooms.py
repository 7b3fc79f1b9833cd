"""What the text can say about a room: names for its walls, doors, windows and corners,
and which of them a relation's words name.

A room's parts are never introduced like objects: every room has walls, so "the north
wall" needs no introduction, and the doors and windows are introduced by the room
sentence ("The room has a door in the south wall and two windows in the north wall.").
Each part has one definite name, chosen from the geometry (``core.room``) so that it
picks out exactly that part in the room, whatever the text said before:

- a wall by its compass side (``Wall.side``): "the north wall"; where several walls
  share a side (an L-shaped room), by what sets it apart from them, in this order:
  length ("the longer north wall"), depth ("the outer north wall", "the inner north
  wall": further out or in along the side's direction), position along the side
  ("the western north wall"). A distinction counts only with a margin a reader can see
  (``LONGER_RATIO``, ``POSITION_MARGIN``).
- a door or window: "the window" when it is the only one; "the north window" when it
  is the only one in a wall on that side; "the window in the longer north wall" when
  it is the only one in its wall; else by its place along its wall ("the western
  window in the north wall", "the second window from the west in the north wall").
- a corner (where two walls meet at less than 180 degrees; furniture cannot stand in a
  reflex corner): "the corner by the door" when a door's opening is within
  ``DOOR_NEAR_CORNER`` of it and of no other corner; else by the compass direction it
  points to (the bisector of its walls, outwards): "the north-east corner", and, where
  two corners share that name, "the north-east corner of the longer north wall".

A part no rule can name unambiguously (a room with three walls on one side, two of
them alike) has no name, and relations to it are not stated.

Which part a relation's words name (``RoomView.place``) depends on its family: a
relation to the room node names the wall or window the layout chose (its ``chosen``);
``AgainstWall`` names the wall, ``InCorner`` the corner of its wall that the object
stands in (measured from the object's footprint), ``UnderWindow`` / ``BesideWindow``
the window; a relation of another family to a wall, door or window names that part.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from scenewright.core.frames import footprint_corners
from scenewright.core.geometry import point_segment_distance
from scenewright.core.relations import RELATIONS, Relation
from scenewright.core.room import ROOM_NODE, Opening, Room, Wall, compass_word
from scenewright.core.scene import SceneObject

from .english import ordinal_word

#: "The corner by the door": the door's opening is at most this far (metres) from the
#: corner, and this far from no other corner.
DOOR_NEAR_CORNER = 1.0
#: "The longer north wall": at least 10 % longer than the other north wall.
LONGER_RATIO = 1.1
#: "The outer north wall", "the western window": at least this much further (metres)
#: that way than any other of the same name, so a reader sees the difference.
POSITION_MARGIN = 0.25

#: The eight compass directions as unit vectors (x, z), keyed by ``core.room``'s own
#: words for them (north is -Z, east +X).
COMPASS_VECTORS: dict[str, tuple[float, float]] = {
    compass_word(math.sin(angle), -math.cos(angle)): (math.sin(angle), -math.cos(angle))
    for angle in (k * math.pi / 4.0 for k in range(8))
}

#: What the words of a wall label name, by its placement (``RelationLabel.wall``): the
#: wall the object's back is against, the corner it stands in, or the window.
PLACEMENT_NAMES = {
    "against": "wall",
    "corner": "corner",
    "under_window": "opening",
    "beside_window": "opening",
}

#: Separates a corner's walls in its id ("wall_4|wall_1"): no scene-graph id holds it.
CORNER_ID_SEPARATOR = "|"


def direction_adjective(word: str, count: int) -> str:
    """ "western" to tell one of two apart, "westernmost" one of three or more."""
    return f"{word}ern" if count == 2 else f"{word}ernmost"


@dataclass(frozen=True)
class Corner:
    """A corner furniture can stand in: where wall ``before`` ends and wall ``after`` starts."""

    id: str
    point: tuple[float, float]
    before: str
    after: str
    side: str  # the compass word of the direction it points to, outwards


class RoomView:
    """The room of one scene as the text names it (see the module docstring)."""

    def __init__(self, room: Room, objects: list[SceneObject]) -> None:
        self.room = room
        self._objects = {o.id: o for o in objects}
        self.corners: dict[str, Corner] = {}
        walls = room.walls
        self.reflex_corners = 0
        for index, after in enumerate(walls):
            before = walls[index - 1]
            if not room.convex_corner(before, after):
                self.reflex_corners += 1
                continue
            bx, bz = before.normal[0] + after.normal[0], before.normal[1] + after.normal[1]
            corner_id = f"{before.id}{CORNER_ID_SEPARATOR}{after.id}"
            self.corners[corner_id] = Corner(
                corner_id, after.start, before.id, after.id, compass_word(-bx, -bz)
            )
        self.names: dict[str, str | None] = {}
        for wall in walls:
            self.names[wall.id] = self._wall_name(wall)
        for opening in room.openings:
            self.names[opening.id] = self._opening_name(opening)
        for corner in self.corners.values():
            self.names[corner.id] = self._corner_name(corner)
        self._places: dict[Relation, str | None] = {}

    # -- what the text asks ------------------------------------------------------------

    def kind(self, place_id: str) -> str | None:
        """ "wall", "door", "window" or "corner" for a part of the room, None otherwise."""
        if place_id in self.corners:
            return "corner"
        part = self._part(place_id)
        if part is None:
            return None
        return "wall" if isinstance(part, Wall) else part.kind

    def name(self, place_id: str) -> str | None:
        """The part's definite name, or None when nothing sets it apart."""
        return self.names.get(place_id)

    @property
    def shape(self) -> str | None:
        """ "L-shaped" for six walls with one reflex corner; None for other shapes."""
        return "L-shaped" if len(self.room.walls) == 6 and self.reflex_corners == 1 else None

    def opening_groups(self) -> list[tuple[str, str, tuple[str, ...]]]:
        """The openings as the room sentence lists them: (kind, wall id, opening ids),
        doors first, then windows, each in wall order."""
        groups: dict[tuple[str, str], tuple[str, ...]] = {}
        for kind in ("door", "window"):
            for wall in self.room.walls:
                found = tuple(o.id for o in self.room.openings_on(wall.id) if o.kind == kind)
                if found:
                    groups[(kind, wall.id)] = found
        return [(kind, wall, ids) for (kind, wall), ids in groups.items()]

    def wall_phrase(self, wall_id: str) -> str:
        """A wall's name, or, for one nothing sets apart, "one of the north walls" (still true)."""
        return self.names[wall_id] or f"one of the {self.room.wall_by_id(wall_id).side} walls"

    def place(self, relation: Relation) -> str | None:
        """The part of the room the relation's words name (a wall, door, window or corner
        id), or None when it names none that the text can name."""
        if relation not in self._places:
            self._places[relation] = self._find_place(relation)
        return self._places[relation]

    # -- which part a relation names ---------------------------------------------------------

    def _find_place(self, relation: Relation) -> str | None:
        part = self._part(relation.chosen if relation.target == ROOM_NODE else relation.target)
        if part is None:
            return None
        spec = RELATIONS[relation.label]
        place: str | None
        if spec.family != "wall":
            place = part.id
        else:
            assert spec.wall is not None  # every wall label names how it is placed
            place = _PLACE_FINDERS[PLACEMENT_NAMES[spec.wall]](self, part, relation.source)
        return place if place is not None and self.names.get(place) is not None else None

    def _the_wall(self, part: Wall | Opening, source: str) -> str:
        return part.id if isinstance(part, Wall) else part.wall

    def _the_opening(self, part: Wall | Opening, source: str) -> str | None:
        # A window label aimed at a wall leaves open which window: nothing to name.
        return part.id if isinstance(part, Opening) else None

    def _the_corner(self, part: Wall | Opening, source: str) -> str | None:
        """The corner at either end of the wall that the object's side is nearest to."""
        wall = self.room.part(self._the_wall(part, source))
        thing = self._objects.get(source)
        if thing is None:
            return None
        footprint = footprint_corners(
            thing.position[0], thing.position[2], thing.yaw, thing.size[0], thing.size[2]
        )
        best, best_gap = None, math.inf
        for corner in self.corners.values():
            if wall.id not in (corner.before, corner.after):
                continue
            other = self.room.wall_by_id(
                corner.after if corner.before == wall.id else corner.before
            )
            gap = abs(min(other.to_wall(x, z)[1] for x, z in footprint))
            if gap < best_gap - 1e-9:
                best, best_gap = corner.id, gap
        return best

    def _part(self, part_id: str | None) -> Wall | Opening | None:
        if part_id is None:
            return None
        try:
            return self.room.part(part_id)
        except KeyError:
            return None

    # -- names ---------------------------------------------------------------------------

    def _wall_name(self, wall: Wall) -> str | None:
        namesakes = [w for w in self.room.walls if w.side == wall.side]
        if len(namesakes) == 1:
            return f"the {wall.side} wall"
        modifier = _longer_or_shorter(wall, namesakes) or _outer_or_inner(wall, namesakes)
        if modifier is None:  # along the side: "the western north wall"
            side = COMPASS_VECTORS[wall.side]
            for word in (_turned(side, 1), _turned(side, -1)):
                if _furthest(wall, namesakes, COMPASS_VECTORS[word]):
                    modifier = direction_adjective(word, len(namesakes))
                    break
        return f"the {modifier} {wall.side} wall" if modifier else None

    def _opening_name(self, opening: Opening) -> str | None:
        kind = opening.kind
        alike = [o for o in self.room.openings if o.kind == kind]
        if len(alike) == 1:
            return f"the {kind}"
        wall = self.room.wall_of(opening)
        if [o for o in alike if self.room.wall_of(o).side == wall.side] == [opening]:
            return f"the {wall.side} {kind}"
        wall_name = self.names[wall.id]
        if wall_name is None:
            return None
        on_wall = sorted((o for o in alike if o.wall == wall.id), key=lambda o: o.offset)
        if on_wall == [opening]:
            return f"the {kind} in {wall_name}"
        # Openings never overlap, so along their wall each is clearly before or after the next.
        index = on_wall.index(opening)
        towards_start = compass_word(-wall.direction[0], -wall.direction[1])
        towards_end = compass_word(*wall.direction)
        if index == 0:
            return f"the {direction_adjective(towards_start, len(on_wall))} {kind} in {wall_name}"
        if index == len(on_wall) - 1:
            return f"the {direction_adjective(towards_end, len(on_wall))} {kind} in {wall_name}"
        return f"the {ordinal_word(index + 1)} {kind} from the {towards_start} in {wall_name}"

    def _corner_name(self, corner: Corner) -> str | None:
        for door in self.room.doors:
            near = [
                c
                for c in self.corners.values()
                if _distance_to_opening(c.point, door, self.room) <= DOOR_NEAR_CORNER
            ]
            if near == [corner] and self.names[door.id]:
                return f"the corner by {self.names[door.id]}"
        namesakes = [c for c in self.corners.values() if c.side == corner.side]
        if len(namesakes) == 1:
            return f"the {corner.side} corner"
        # Where two corners point the same way, the one at an end of a wall that is named.
        for wall_id in (corner.before, corner.after):
            at_ends = [c for c in namesakes if wall_id in (c.before, c.after)]
            if at_ends == [corner] and self.names[wall_id]:
                return f"the {corner.side} corner of {self.names[wall_id]}"
        return None


#: How ``RoomView.place`` finds the part a wall label's words name, by ``PLACEMENT_NAMES``.
_PLACE_FINDERS = {
    "wall": RoomView._the_wall,
    "corner": RoomView._the_corner,
    "opening": RoomView._the_opening,
}


def _longer_or_shorter(wall: Wall, namesakes: list[Wall]) -> str | None:
    others = [w.length for w in namesakes if w is not wall]
    superlative = len(namesakes) > 2
    if wall.length >= LONGER_RATIO * max(others):
        return "longest" if superlative else "longer"
    if wall.length * LONGER_RATIO <= min(others):
        return "shortest" if superlative else "shorter"
    return None


def _outer_or_inner(wall: Wall, namesakes: list[Wall]) -> str | None:
    """Further out along the side's own direction ("outer"), or further in ("inner")."""
    outwards = COMPASS_VECTORS[wall.side]
    superlative = len(namesakes) > 2
    if _furthest(wall, namesakes, outwards):
        return "outermost" if superlative else "outer"
    if _furthest(wall, namesakes, (-outwards[0], -outwards[1])):
        return "innermost" if superlative else "inner"
    return None


def _furthest(wall: Wall, namesakes: list[Wall], direction: tuple[float, float]) -> bool:
    """Whether ``wall``'s middle is further along ``direction`` than every namesake's by
    ``POSITION_MARGIN``."""

    def along(w: Wall) -> float:
        x, z = _midpoint(w)
        return x * direction[0] + z * direction[1]

    return all(along(wall) >= along(w) + POSITION_MARGIN for w in namesakes if w is not wall)


def _midpoint(wall: Wall) -> tuple[float, float]:
    return (wall.start[0] + wall.end[0]) / 2.0, (wall.start[1] + wall.end[1]) / 2.0


def _turned(vector: tuple[float, float], quarter: int) -> str:
    """The compass word a quarter turn from ``vector`` (1: clockwise seen from above)."""
    x, z = vector
    return compass_word(-z * quarter, x * quarter)


def _distance_to_opening(point: tuple[float, float], opening: Opening, room: Room) -> float:
    """Distance from a point on the floor to the stretch of wall an opening fills."""
    (ax, az), (bx, bz) = room.opening_ends(opening)
    return point_segment_distance(point[0], point[1], ax, az, bx, bz)
