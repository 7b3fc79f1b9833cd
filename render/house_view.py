"""What a picture or a file of a house draws (``core.house``), as numbers: pure numpy.

- Walls: ``house.walls``, each once (a wall two rooms share is one wall), named
  ``wall_1``, ``wall_2``, ... in that order (``wall_name``), drawn on its centre line,
  its thickness either side, with a hole for each door and window in it
  (``wall_openings``). Where walls meet, each is drawn to fill the junction once
  (``wall_reach``): a corner is covered by one of its walls, a T-junction's stem stops
  at the face of the wall running through, and walls running straight on meet end to
  end.
- The cut-away (``wall_heights``): a view from straight above draws every wall to its
  full height (only the tops show, hiding nothing). Any other view draws the outside
  walls whose inner face turns towards the viewer (the far walls, behind the rooms, as
  a room's view keeps them) full height, and cuts every other wall, the near outside
  walls and every wall between rooms, down to ``CUT_HEIGHT``: low enough to see over
  into every room, high enough that each doorway shows as a gap. A door or window is
  drawn cut as its wall is (``opening_height``).
- Doors and windows are the house's own (``house.openings``: ``door_3``, ``window_2``),
  one entity each, an interior door once, not once per room. Each sits in its wall's
  thickness facing into the first of its rooms (``opening_pose``): a door's leaf on that
  side, as that room's own ``Room`` has it.
"""

from __future__ import annotations

import math

import numpy as np

from scenewright.core.frames import transform_matrix
from scenewright.core.house import House, HouseOpening, HouseWall

#: The height (m) a view from the side cuts the walls between rooms and the near
#: outside walls down to: over the furniture's bulk, under a door's top, above a
#: typical window sill so windows show as a strip of glass.
CUT_HEIGHT = 1.1
#: The automatic perspective view of a house looks down this steeply (radians), so the
#: whole floor shows, room by room, over the cut walls.
HOUSE_ELEVATION = math.radians(60.0)
#: Distances (m) under which two points are one, and a point lies on a wall.
_NEAR = 1e-4
_ON_WALL = 1e-3


def wall_name(index: int) -> str:
    """The name of ``house.walls[index]`` in pictures and files."""
    return f"wall_{index + 1}"


def straight_above(towards_viewer) -> bool:
    """Whether a viewer in direction ``towards_viewer`` looks straight down."""
    towards = np.asarray(towards_viewer, dtype=float)
    return math.hypot(towards[0], towards[2]) <= 1e-6 * float(np.linalg.norm(towards))


def wall_heights(house: House, towards_viewer) -> list[float]:
    """The height each of ``house.walls`` is drawn to by a viewer in direction
    ``towards_viewer`` (a world vector from the house to the viewer; module docstring)."""
    if straight_above(towards_viewer):
        return [wall.height for wall in house.walls]
    towards = np.asarray(towards_viewer, dtype=float)
    heights = []
    for wall in house.walls:
        height = min(wall.height, CUT_HEIGHT)
        if wall.outside:
            room = next(r for r in wall.rooms if r is not None)
            nx, nz = inward_normal(house, wall.start, wall.end, room)
            if nx * towards[0] + nz * towards[2] > 1e-9:  # a far wall: kept whole
                height = wall.height
        heights.append(height)
    return heights


def inward_normal(house: House, start, end, room_id: str) -> tuple[float, float]:
    """The unit normal (x, z) of the wall line ``start``-``end`` that points into room
    ``room_id`` (found by trying both sides against the room's outline)."""
    dx, dz = end[0] - start[0], end[1] - start[1]
    length = math.hypot(dx, dz)
    dx, dz = dx / length, dz / length
    mx, mz = (start[0] + end[0]) / 2.0, (start[1] + end[1]) / 2.0
    outline = house.room(room_id).outline
    step = min(0.05, length / 4.0)
    if _inside(outline, (mx - dz * step, mz + dx * step)):
        return -dz, dx
    return dz, -dx


def wall_reach(house: House, index: int) -> tuple[float, float]:
    """How far past its start and its end (m) wall ``index`` is drawn, so that walls
    meeting at a point fill it once, with no two faces in one place (a renderer that
    traces rays shades coincident faces as dark speckles): 0 where a wall runs straight
    on from it (the two meet end to end); at a T-junction, -half a thickness for the
    stem (it stops at the face of the wall running through); at a corner, +half a
    thickness for the first of the walls meeting there (it covers the corner) and
    -half for the others."""
    wall = house.walls[index]
    direction = _direction(wall)
    half = wall.thickness / 2.0
    reach = []
    for point in (wall.start, wall.end):
        meeting = [
            k
            for k, other in enumerate(house.walls)
            if k != index
            and (math.dist(other.start, point) < _NEAR or math.dist(other.end, point) < _NEAR)
        ]
        if not meeting or any(_parallel(direction, house.walls[k]) for k in meeting):
            reach.append(0.0)  # a free end, or the wall runs straight on
        elif any(
            _parallel(_direction(house.walls[j]), house.walls[k])
            for j in meeting
            for k in meeting
            if j < k
        ):
            reach.append(-half)  # a stem: another wall runs through here
        else:
            reach.append(half if index < min(meeting) else -half)  # a corner
    return reach[0], reach[1]


def _parallel(direction: tuple[float, float], wall: HouseWall) -> bool:
    other = _direction(wall)
    return abs(direction[0] * other[1] - direction[1] * other[0]) < 1e-6


def wall_openings(house: House) -> list[list[tuple[HouseOpening, float]]]:
    """For each of ``house.walls``: the openings in it with their centre's distance
    along it from its start, in order along the wall."""
    found: list[list[tuple[HouseOpening, float]]] = [[] for _ in house.walls]
    for opening in house.openings:
        index = opening_wall(house, opening)
        if index is not None:
            wall = house.walls[index]
            dx, dz = _direction(wall)
            u = (opening.center[0] - wall.start[0]) * dx + (opening.center[1] - wall.start[1]) * dz
            found[index].append((opening, u))
    return [sorted(row, key=lambda item: item[1]) for row in found]


def opening_wall(house: House, opening: HouseOpening) -> int | None:
    """The index of the wall ``opening`` is in (its centre on the wall's centre line,
    along it), or None."""
    for index, wall in enumerate(house.walls):
        dx, dz = _direction(wall)
        if abs(dx * opening.direction[1] - dz * opening.direction[0]) > 1e-3:
            continue
        px, pz = opening.center[0] - wall.start[0], opening.center[1] - wall.start[1]
        u = px * dx + pz * dz
        if abs(px * dz - pz * dx) < _ON_WALL and -_ON_WALL <= u <= wall.length + _ON_WALL:
            return index
    return None


def opening_pose(house: House, opening: HouseOpening) -> np.ndarray:
    """4x4 local-to-world matrix of an opening's frame, as ``render.meshes.opening_mesh``
    builds a door or window: origin on the floor at its centre on the face of its wall
    in its first room, local +Z into that room, +X along the wall."""
    start = opening.center
    end = (start[0] + opening.direction[0], start[1] + opening.direction[1])
    nx, nz = inward_normal(house, start, end, opening.rooms[0])
    half = _thickness(house, opening) / 2.0
    return transform_matrix(
        opening.center[0] + nx * half, 0.0, opening.center[1] + nz * half, math.atan2(nx, nz)
    )


def opening_height(house: House, opening: HouseOpening, towards_viewer) -> float:
    """The height (m) up to which a view draws ``opening``: its wall's drawn height."""
    index = opening_wall(house, opening)
    if index is None:
        return house.height
    return wall_heights(house, towards_viewer)[index]


def wall_owner(wall: HouseWall) -> str:
    """The room a file puts ``wall`` under: the first room it borders."""
    return next(room for room in wall.rooms if room is not None)


def _thickness(house: House, opening: HouseOpening) -> float:
    index = opening_wall(house, opening)
    return house.walls[index].thickness if index is not None else house.walls[0].thickness


def _direction(wall: HouseWall) -> tuple[float, float]:
    length = max(wall.length, 1e-12)
    return (wall.end[0] - wall.start[0]) / length, (wall.end[1] - wall.start[1]) / length


def _inside(polygon, point) -> bool:
    """Whether ``point`` (x, z) lies inside ``polygon`` (even-odd rule)."""
    x, z = point
    inside = False
    count = len(polygon)
    for k in range(count):
        (x0, z0), (x1, z1) = polygon[k], polygon[(k + 1) % count]
        if (z0 > z) != (z1 > z) and x < x0 + (z - z0) * (x1 - x0) / (z1 - z0):
            inside = not inside
    return inside
