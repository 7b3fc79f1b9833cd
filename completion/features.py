"""A plan's room feature and its layout mask (Section 5.1 of the paper).

The room feature is ``f_r = (angle(w, d) / pi, r_s, r_e, phi)``:

- ``angle(w, d)``: the angle between the vectors from the room's centre to the mean
  position of its windows (``w``) and of its doors (``d``), divided by pi so that it
  lies in [0, 1] like the other three (the paper compares features by Euclidean
  distance "with uniform weighting for individual components"; radians would outweigh
  the ratios). A room without a window takes the middle value, 0.5.
- ``r_s``: occupancy, the floor area of the furniture over the room's area (pieces
  standing on others and flat ones, a rug, cover no floor of their own);
- ``r_e``: the short side of the room's bounding box over its long side;
- ``phi = area / (area + mean area of the type's rooms)``: how large the room is for
  its type.

The layout mask is a 10 x 10 matrix of how much of each cell furniture covers, in a
canonical frame. The paper aligns masks "by the long edges of the rooms" and flips them
so the furniture's barycentre is in the bottom-right; an empty room being completed has
no furniture, so here the flips are chosen by the door, which every room has
(door-aware): the room is turned so its long side is canonical x (the mask's columns
run along it), and flipped so the doors' mean position is in the top-left quarter
(canonical x <= 0, z <= 0). When the doors sit on a centre line the windows decide (their mean to the
bottom-right), then, for a furnished plan, the furniture's barycentre, as in the paper.
Row 0 of the mask is canonical -z (the top), column 0 canonical -x (the left).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from scenewright.core.frames import to_local_many

MASK_SIZE = 10
#: Sample points per mask cell along each side (the coverage is their share inside furniture).
SAMPLES_PER_CELL = 8
#: Closer than this (metres) to the room's centre line, a position decides no flip.
CENTRE_SLACK = 0.01


@dataclass(frozen=True)
class CanonicalFrame:
    """Room (x, z) -> canonical (x, z): swap the axes when the room is deeper than wide
    (``transpose``), then mirror x and/or z. Its own inverse up to the order of steps."""

    transpose: bool
    flip_x: bool
    flip_z: bool

    def apply(self, points: np.ndarray) -> np.ndarray:
        """(n, 2) room points (centred on the room's bounding box) -> (n, 2) canonical."""
        points = np.asarray(points, dtype=float).reshape(-1, 2)
        out = points[:, ::-1].copy() if self.transpose else points.copy()
        out *= np.array([-1.0 if self.flip_x else 1.0, -1.0 if self.flip_z else 1.0])
        return out

    def invert(self, points: np.ndarray) -> np.ndarray:
        """(n, 2) canonical points -> (n, 2) room points."""
        out = np.asarray(points, dtype=float).reshape(-1, 2) * np.array(
            [-1.0 if self.flip_x else 1.0, -1.0 if self.flip_z else 1.0]
        )
        return out[:, ::-1].copy() if self.transpose else out

    def to_dict(self) -> dict:
        return {"transpose": self.transpose, "flip_x": self.flip_x, "flip_z": self.flip_z}


def room_centre(room) -> np.ndarray:
    """(2,) centre of the room's bounding box."""
    corners = np.array(room.corners)
    return (corners.min(axis=0) + corners.max(axis=0)) / 2.0


def canonical_frame(room, furniture=()) -> CanonicalFrame:
    """The door-aware canonical frame of ``room`` (see the module docstring);
    ``furniture`` (``plan.Furniture``) breaks the last tie."""
    width, depth = room.extent
    transpose = depth > width + 1e-9
    centre = room_centre(room)
    unflipped = CanonicalFrame(transpose, False, False)

    def mean_of(points) -> np.ndarray | None:
        return unflipped.apply(np.array(points) - centre).mean(axis=0) if len(points) else None

    door = mean_of([o.center for o in room.doors])
    window = mean_of([o.center for o in room.windows])
    floor = [p for p in furniture if p.on is None]
    mass = None
    if floor:
        areas = np.array([p.area for p in floor])
        mass = (unflipped.apply(np.array([p.center for p in floor]) - centre) * areas[:, None]).sum(
            axis=0
        ) / areas.sum()
    flips = []
    for axis in (0, 1):
        flip = False
        for position, wanted in ((door, -1.0), (window, 1.0), (mass, 1.0)):
            if position is not None and abs(position[axis]) > CENTRE_SLACK:
                flip = position[axis] * wanted < 0.0
                break
        flips.append(flip)
    return CanonicalFrame(bool(transpose), bool(flips[0]), bool(flips[1]))


def occupancy_mask(room, furniture, frame: CanonicalFrame, size: int = MASK_SIZE) -> np.ndarray:
    """(size, size) share of each cell covered by floor furniture (pieces ``on`` others
    and flat ones excluded by the caller), in ``frame``; rows run along canonical z."""
    width, depth = room.extent
    long_side, short_side = (depth, width) if frame.transpose else (width, depth)
    n = size * SAMPLES_PER_CELL
    xs = (np.arange(n) + 0.5) / n * long_side - long_side / 2.0
    zs = (np.arange(n) + 0.5) / n * short_side - short_side / 2.0
    grid_x, grid_z = np.meshgrid(xs, zs)  # (n, n): row = canonical z
    points = frame.invert(np.stack([grid_x.ravel(), grid_z.ravel()], axis=1)) + room_centre(room)
    covered = np.zeros(len(points), dtype=bool)
    pieces = list(furniture)
    if pieces:
        centres = np.array([p.center for p in pieces])
        yaws = np.array([p.yaw for p in pieces])
        half = np.array([p.size for p in pieces]) / 2.0
        local = to_local_many(centres, yaws, np.broadcast_to(points, (len(pieces), *points.shape)))
        inside = (np.abs(local) <= half[:, None, :]).all(axis=2)  # (pieces, points)
        covered = inside.any(axis=0)
    cells = covered.reshape(size, SAMPLES_PER_CELL, size, SAMPLES_PER_CELL)
    return cells.mean(axis=(1, 3))


def door_window_angle(room) -> float:
    """The angle (radians, 0..pi) between the room centre's vectors to the mean window
    and the mean door; pi / 2 when the room has no window or no door."""
    centre = room_centre(room)
    if not room.windows or not room.doors:
        return math.pi / 2.0
    w = np.mean([o.center for o in room.windows], axis=0) - centre
    d = np.mean([o.center for o in room.doors], axis=0) - centre
    norms = np.linalg.norm(w) * np.linalg.norm(d)
    if norms == 0.0:
        return math.pi / 2.0
    return float(math.acos(max(-1.0, min(1.0, float(np.dot(w, d)) / norms))))


def room_feature(room, floor_area: float, type_mean_area: float) -> np.ndarray:
    """(4,) ``f_r`` of a room whose furniture covers ``floor_area`` square metres, in a
    type whose rooms average ``type_mean_area``: (angle / pi, r_s, r_e, phi)."""
    angle, aspect, relative_size = room_parts(room, type_mean_area)
    return np.array([angle, floor_area / room.area, aspect, relative_size])


def room_parts(room, type_mean_area: float) -> np.ndarray:
    """(3,) the parts of ``f_r`` that describe the room alone, without its furniture:
    (angle / pi, r_e, phi)."""
    width, depth = room.extent
    area = room.area
    return np.array(
        [
            door_window_angle(room) / math.pi,
            min(width, depth) / max(width, depth),
            area / (area + type_mean_area),
        ]
    )
