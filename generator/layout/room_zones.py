"""The fixed geometry a room's energy terms measure against: its walls as quick tests
(``Walls``), the zones kept free of tall boxes (a door's swing, a window's view:
``KeptZone``), the strip a box keeps clear beside one of its sides (``zone_rect``),
how far a yaw is off the walls' axes (``square_off``), and the collision penalty of a
depth. ``room_terms`` builds the energy from these.
"""

from __future__ import annotations

import math
from typing import NamedTuple

from scenewright.core.geometry import Rect, corners
from scenewright.core.room import Opening, Room

from .reachability import bounds
from .relation_terms import opening_wall

#: A window's view: the strip as wide as the window and WINDOW_VIEW_DEPTH deep in front
#: of it (metres), kept free of ground boxes whose top rises more than
#: WINDOW_VIEW_MARGIN above the sill (a desk or a sofa about as high as the sill may
#: stand there; a bookshelf may not).
WINDOW_VIEW_DEPTH = 0.5
WINDOW_VIEW_MARGIN = 0.3

#: Depths are clipped below 1 so the log penalty stays finite (as ``single_terms.MAX_DEPTH``).
MAX_DEPTH = 0.99


def penalty(depth: float, intensity: float) -> float:
    """The collision penalty -c log(1 - depth) of a normalised depth (0 for depth 0)."""
    return -intensity * math.log1p(-min(depth, MAX_DEPTH)) if depth > 0.0 else 0.0


def square_off(yaw: float, axes: tuple[float, ...]) -> float:
    """How far (radians, 0..pi/4) a yaw is off the nearest multiple of 90 degrees from any of ``axes``."""
    quarter = math.pi / 2.0
    best = math.pi
    for axis in axes:
        off = (yaw - axis) % quarter
        off = min(off, quarter - off)
        if off < best:
            best = off
    return best


def wall_axes(room: Room) -> tuple[float, ...]:
    """The yaws (mod 90 degrees, in [0, pi/2)) a box can have square to some wall: a
    box whose forward (sin yaw, cos yaw) runs along or across a wall."""
    axes: list[float] = []
    for wall in room.walls:
        tx, tz = wall.direction
        axis = math.atan2(tx, tz) % (math.pi / 2.0)
        if axis > math.pi / 2.0 - 1e-9:
            axis = 0.0
        if all(abs(axis - other) > 1e-9 for other in axes):
            axes.append(axis)
    return tuple(sorted(axes))


def zone_rect(rect: Rect, side: str, metres: float) -> Rect:
    """The strip ``metres`` deep beside one side of a footprint, as wide as that side."""
    cx, cz, hw, hd, c, s = rect
    if side == "front":
        lx, lz, zw, zd = 0.0, hd + metres / 2.0, hw, metres / 2.0
    elif side == "back":
        lx, lz, zw, zd = 0.0, -(hd + metres / 2.0), hw, metres / 2.0
    elif side == "left":  # local +X is the box's left
        lx, lz, zw, zd = hw + metres / 2.0, 0.0, metres / 2.0, hd
    else:
        lx, lz, zw, zd = -(hw + metres / 2.0), 0.0, metres / 2.0, hd
    return Rect(cx + lx * c + lz * s, cz - lx * s + lz * c, zw, zd, c, s)


def swing_rect(room: Room, door: Opening) -> Rect:
    """A door's swing zone (``Room.swing_zone``) as a footprint: centred in front of the
    door, its forward along the wall's inner normal."""
    points = room.swing_zone(door)
    cx = sum(p[0] for p in points) / 4.0
    cz = sum(p[1] for p in points) / 4.0
    nx, nz = opening_wall(room, door).normal
    return Rect(cx, cz, door.width / 2.0, door.width / 2.0, nz, nx)  # forward (s, c) = normal


def view_rect(room: Room, window: Opening) -> Rect:
    """A window's view (WINDOW_VIEW_DEPTH deep, as wide as the window) as a footprint:
    its forward along the wall's inner normal."""
    wall = opening_wall(room, window)
    cx, cz = wall.to_world(window.offset, WINDOW_VIEW_DEPTH / 2.0)
    nx, nz = wall.normal
    return Rect(
        cx, cz, window.width / 2.0, WINDOW_VIEW_DEPTH / 2.0, nz, nx
    )  # forward (s, c) = normal


class KeptZone(NamedTuple):
    """A fixed footprint kept free of tall boxes (a door's swing, a window's view), with
    its axis-aligned bounds and its diagonal, both computed once."""

    rect: Rect
    bounds: tuple[float, float, float, float]
    diagonal: float


def kept_zone(rect: Rect) -> KeptZone:
    return KeptZone(rect, bounds(rect), 2.0 * math.hypot(rect.hw, rect.hd))


#: A corner this close (metres) outside a wall counts as on it: furniture placed flush
#: against a wall ends up a rounding error either side of it.
FLUSH = 1e-9


class Walls:
    """The room's polygon as the scalar tests the energy runs every step."""

    def __init__(self, room: Room):
        self.room = room
        n = len(room.walls)
        #: Each wall's line as (nx, nz, offset): n . p - offset is the signed distance of p
        #: into the room. In a convex room a footprint whose corners all have it >= 0
        #: stands on the floor (no room corner can be inside it): most of the time, so
        #: the general test is skipped.
        self.lines = [
            (w.normal[0], w.normal[1], w.normal[0] * w.start[0] + w.normal[1] * w.start[1])
            for w in room.walls
        ]
        self.convex = all(
            room.convex_corner(room.walls[k], room.walls[(k + 1) % n]) for k in range(n)
        )
        #: For a room that is a rectangle square to the axes, its bounds (x0, z0, x1, z1):
        #: a footprint's bounds within them (FLUSH aside) is all the convex test asks.
        x0, z0, x1, z1 = room.bounds
        square = n == 4 and all(abs(w.normal[0]) in (0.0, 1.0) for w in room.walls)
        self.box = (x0 - FLUSH, z0 - FLUSH, x1 + FLUSH, z1 + FLUSH) if square else None

    def excess(self, rect: Rect) -> float:
        """How far (metres) a footprint crosses the walls (``Room.footprint_excess``),
        with the two quick answers of a footprint wholly inside first."""
        if self.box is not None:
            x0, z0, x1, z1 = bounds(rect)
            room_x0, room_z0, room_x1, room_z1 = self.box
            if room_x0 <= x0 and x1 <= room_x1 and room_z0 <= z0 and z1 <= room_z1:
                return 0.0
        points = corners(rect)
        if self.convex and all(
            nx * x + nz * z >= offset - FLUSH for x, z in points for nx, nz, offset in self.lines
        ):
            return 0.0
        return self.room.footprint_excess(points)
