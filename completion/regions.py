"""Composite rooms: a room that Equation 2 makes several types at once is split by
virtual walls into one sub-room (region) per type (Fu et al. 2017, Section 5.2).

The paper divides such a room "by adding virtual boundaries in the room to make the
subrooms have the similar proportional relation to the average areas of their scene
types" and completes each sub-room as a room of its one type. It does not say where
the boundaries run or which part goes where (its limitations section: the largest
type goes in the middle or nearest the window). Our reading, for a rectangular room:

- **Strips across the long side.** The virtual walls run across the room's longer
  side (parallel to its short side), so every region keeps the room's full depth and
  a stretch of both long walls; region k's length along the long side is that side
  times ``mean_area_k / sum mean_area``.
- **The order is the one most like the types' plans.** Every order of the types along
  the long side is tried (at most 3! = 6); each region is a room of its own (the real
  walls on its sides, the virtual walls as walls, the openings whose centres fall on
  its walls), and the order whose regions' room-only features (door-window angle,
  aspect, relative size) lie nearest, summed, to their types' ``K`` most similar plans
  wins, as the paper compares rooms. Ties: the paper's rule, the largest type nearest
  a window, then the types' order.
- **A region without a door is entered through a virtual wall.** Every plan has a
  door, and the door decides the canonical frame of a region's layout mask
  (``features``): a region with no door of the room's gets one, 0.9 m wide, in the
  middle of the virtual wall it shares with the region nearest the room's door.

Rooms that are not rectangles are not split (their layout mask is the first type's,
over the whole room). Everything here is geometry: it draws nothing.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass

import numpy as np

from scenewright.completion.plan_model import PlanModel
from scenewright.core.errors import RoomError
from scenewright.core.room import Room

#: The width of the door a region without one is given in its virtual wall (metres).
VIRTUAL_DOOR = 0.9
#: How far from axis-aligned a rectangle's walls may be and still be split (metres).
SQUARE = 1e-6


@dataclass(frozen=True)
class Region:
    """One part of a composite room: its ``room_type``, its rectangle ``bounds``
    (x0, z0, x1, z1), the sub-room ``room`` (walls on the rectangle, the openings of the
    room whose centres fall on them, plus a virtual door when it has no real one) and
    whether that door is virtual."""

    room_type: str
    bounds: tuple[float, float, float, float]
    room: Room
    virtual_door: bool

    def contains(self, points) -> np.ndarray:
        """(n,) whether each of the (n, 2) points lies in the region's rectangle."""
        points = np.asarray(points, dtype=float).reshape(-1, 2)
        x0, z0, x1, z1 = self.bounds
        return (
            (points[:, 0] >= x0)
            & (points[:, 0] <= x1)
            & (points[:, 1] >= z0)
            & (points[:, 1] <= z1)
        )

    def to_dict(self) -> dict:
        return {
            "type": self.room_type,
            "bounds": [float(v) for v in self.bounds],
            "virtual_door": self.virtual_door,
        }

    def has_room_corner(self, room: Room) -> bool:
        """Whether a corner of the whole (rectangular) ``room`` is a corner of this region:
        a strip between two virtual walls has none, so nothing of it can stand in one."""
        corners = np.asarray(room.corners, dtype=float)
        x0, z0, x1, z1 = self.bounds
        mine = np.array([(x0, z0), (x0, z1), (x1, z0), (x1, z1)])
        return bool((np.abs(corners[:, None, :] - mine[None, :, :]).max(axis=2) < 1e-6).any())


def is_rectangle(room: Room) -> bool:
    """Whether the room is an axis-aligned rectangle (four corners on its bounding box)."""
    corners = np.array(room.corners)
    if len(corners) != 4:
        return False
    low, high = corners.min(axis=0), corners.max(axis=0)
    on_box = (np.abs(corners - low) < SQUARE) | (np.abs(corners - high) < SQUARE)
    return bool(on_box.all())


def strips(room: Room, lengths, order) -> list[tuple[float, float, float, float]]:
    """The rectangles (x0, z0, x1, z1) of strips across the room's long side, of the
    given ``lengths`` along it, in ``order`` (indices into ``lengths``) from the west
    (or north, for a room deeper than wide) end."""
    corners = np.array(room.corners)
    (x0, z0), (x1, z1) = corners.min(axis=0), corners.max(axis=0)
    along_x = (x1 - x0) >= (z1 - z0) - 1e-9
    start = x0 if along_x else z0
    boxes = []
    for position, k in enumerate(order):
        end = (x1 if along_x else z1) if position == len(order) - 1 else start + lengths[k]
        boxes.append((start, z0, end, z1) if along_x else (x0, start, x1, end))
        start = end
    return boxes


def virtual_walls(regions) -> list[tuple[tuple[float, float], tuple[float, float]]]:
    """The segments ((x, z), (x, z)) between neighbouring regions, in order."""
    walls = []
    for first, second in zip(regions, regions[1:], strict=False):
        ax0, az0, ax1, az1 = first.bounds
        bx0, bz0, _, _ = second.bounds
        if abs(ax1 - bx0) < 1e-9 and bz0 == az0:  # side by side along x: the wall runs along z
            walls.append(((ax1, az0), (ax1, az1)))
        else:
            walls.append(((ax0, az1), (ax1, az1)))
    return walls


def sub_room(room: Room, bounds, door_side=None) -> tuple[Room, bool]:
    """The room on the rectangle ``bounds``: walls north, east, south, west as
    ``Room.rectangle`` orders them, each of ``room``'s openings whose centre lies on one
    of its walls (cut to the wall where it runs past a corner), and, when none of them
    is a door, a virtual door in the middle of the wall ``door_side`` (the wall's
    index 0..3) if given. Returns the room and whether its door is virtual."""
    x0, z0, x1, z1 = bounds
    sub = Room.polygon([(x0, z0), (x1, z0), (x1, z1), (x0, z1)], room.height, centre=False)
    for opening in room.openings:
        cx, cz = opening.center
        for wall in sub.walls:
            u, v = wall.to_wall(cx, cz)
            if abs(v) > 1e-6 or not -1e-9 <= u <= wall.length + 1e-9:
                continue
            low, high = max(u - opening.width / 2.0, 0.0), min(u + opening.width / 2.0, wall.length)
            if high - low < 0.05:
                break
            extra = (
                {"height": opening.height}
                if opening.kind == "door"
                else {"height": opening.height, "sill": opening.sill}
            )
            try:
                sub = sub.with_opening(
                    opening.kind, wall.id, (low + high) / 2.0, high - low, **extra
                )
            except RoomError:
                pass  # overlapping another cut opening: the region's mask frame needs no more
            break
    if sub.doors or door_side is None:
        return sub, False
    wall = sub.walls[door_side]
    width = min(VIRTUAL_DOOR, wall.length)
    return sub.with_opening("door", wall.id, wall.length / 2.0, width), True


def split_room(model: PlanModel, room: Room, types) -> tuple[Region, ...]:
    """The regions of a room of ``types`` (see the module docstring); () for one type or
    a room that is not a rectangle."""
    from scenewright.completion.features import room_parts
    from scenewright.completion.selection import ROOM_PARTS, nearest_plans

    if len(types) < 2 or not is_rectangle(room):
        return ()
    means = [model.types[t].mean_area for t in types]
    width, depth = room.extent
    long_side = max(width, depth)
    lengths = [long_side * mean / sum(means) for mean in means]
    largest = max(range(len(types)), key=lambda k: (means[k], -k))
    best = None
    for order in itertools.permutations(range(len(types))):
        regions = _regions_in_order(room, types, lengths, order)
        distance = 0.0
        for region in regions:
            mean_area = model.types[region.room_type].mean_area
            parts = room_parts(region.room, mean_area)
            plans = nearest_plans(model, region.room_type, parts)
            distance += float(
                np.mean(
                    [np.linalg.norm(np.asarray(p.feature)[list(ROOM_PARTS)] - parts) for p in plans]
                )
            )
        window = _window_distance(room, regions[order.index(largest)])
        key = (round(distance, 9), round(window, 9), order)
        if best is None or key < best[0]:
            best = (key, regions)
    assert best is not None  # there is at least one order
    return best[1]


def _regions_in_order(room: Room, types, lengths, order) -> tuple[Region, ...]:
    boxes = strips(room, lengths, order)
    along_x = room.extent[0] >= room.extent[1] - 1e-9  # as ``strips`` runs them
    rooms = [sub_room(room, box) for box in boxes]
    # A region without a door opens onto its neighbour on the side of the nearest real door.
    with_door = [k for k, (sub, _) in enumerate(rooms) if sub.doors]
    regions = []
    for k, box in enumerate(boxes):
        sub, virtual = rooms[k]
        if not sub.doors:
            towards = (
                min(with_door, key=lambda j: (abs(j - k), j))
                if with_door
                else (k - 1 if k else k + 1)
            )
            # Walls of a rectangle: 0 north, 1 east, 2 south, 3 west.
            side = (1 if towards > k else 3) if along_x else (2 if towards > k else 0)
            sub, virtual = sub_room(room, box, side)
        x0, z0, x1, z1 = (float(v) for v in box)
        regions.append(Region(types[order[k]], (x0, z0, x1, z1), sub, virtual))
    return tuple(regions)


def _window_distance(room: Room, region: Region) -> float:
    """How far the region's centre lies from the room's nearest window (0 without one)."""
    if not room.windows:
        return 0.0
    x0, z0, x1, z1 = region.bounds
    centre = np.array([(x0 + x1) / 2.0, (z0 + z1) / 2.0])
    return min(float(np.linalg.norm(np.asarray(w.center) - centre)) for w in room.windows)


def region_of_points(regions, points) -> np.ndarray:
    """(n,) the index of the region each of the (n, 2) points lies in (the first, on a
    virtual wall), -1 outside them all."""
    points = np.asarray(points, dtype=float).reshape(-1, 2)
    found = np.full(len(points), -1)
    for k in reversed(range(len(regions))):
        found[regions[k].contains(points)] = k
    return found


def footprint_share(
    region: Region, x: float, z: float, width: float, depth: float, yaw: float, samples: int = 5
) -> float:
    """The share of a footprint (centre, sides, yaw) inside the region: of its
    ``samples`` x ``samples`` points, those in the rectangle."""
    grid = (np.arange(samples) + 0.5) / samples - 0.5
    local = np.array([(a * width, b * depth) for a in grid for b in grid])
    c, s = math.cos(yaw), math.sin(yaw)
    points = np.column_stack(
        [x + local[:, 0] * c + local[:, 1] * s, z - local[:, 0] * s + local[:, 1] * c]
    )
    return float(np.mean(region.contains(points)))
