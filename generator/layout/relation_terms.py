"""Table 1 of the paper: the geometry every relation family's energy reads, and its thresholds.

Each family's energy, threshold and complaint is its module in ``families``;
``families.evaluate(term, state, params)`` returns a ``Measure``: the energy (minus the
log factor, >= 0) and the quantities the satisfaction thresholds look at (distance,
angle off the wanted direction, and so on). Here are what they share: the ``Measure``,
the thresholds (documented in ``report``), the ends' centres, anchors and forwards, the
distance between two ends, and line of sight. Readings of the table, where it is
garbled or leaves the geometry open:

- distanceBetween is the minimum distance between collision boxes: footprint distance
  combined with the vertical gap; to a group, the nearest of its members (the union of
  their boxes); to a path, the distance to its centre line minus half its width.
- directionFromTo(B, A) runs from B's centre to A's centre; for a path B it starts at
  the path point nearest A's centre. B's own directions (left, forward, ...) are its
  local axes; a group has the world's axes, a path its tangent at that nearest point.
- OnTopOf*: the extracted table reads equals(boundary(A, up)y, boundary(B, down)y),
  which would put A's top at B's bottom (under B). The sensible reading, used here, is
  A's base on B's top: equals(boundary(A, down)y, boundary(B, up)y). Heights follow the
  support, so this term is 0 for the first support and honest for any extra one.
- OnTopOfEdge / FrontEdge: besides touching the edge, A's centre must stay over B's top
  (the table alone would also be satisfied by A hanging outside the edge); this adds
  equals(how far the centre is off the top, 0), which is 0 anywhere over the top.
- FacingAwayFrom: the table's range(fA . fB, -1, 0) compares forward vectors, which
  cannot tell back-to-back from face-to-face. Since the describer says "A faces away
  from B", it is scored as A's forward pointing from B to A (FacingTowards mirrored).

Rooms add the ``wall`` and ``alignment`` families (``families.wall``,
``families.alignment``) and line of sight: a relation whose term lists ``sight`` boxes (``problem.needs_sight``, as the family says: in
front of, behind, facing towards or away, between two objects) is blocked when the
segment between A's and B's centres crosses the footprint of one of those tall boxes.
A blocked relation does not hold whatever its other measures say; its energy gains
``SIGHT_PENALTY`` plus how far (metres) the segment would have to shift sideways to
clear each blocking box, so the sampler is pushed out of it by the shortest way.
"""

from __future__ import annotations

import math
from typing import NamedTuple

from scenewright.core.geometry import (
    nearest_on_polyline,
    polyline_distance,
    polyline_rects_distance,
    rect_distance,
)
from scenewright.core.room import Opening, Room, Wall

from .state import State
from .terms import ROOM_ENDS, Endpoint, RelationTerm

#: Thresholds of ``satisfied`` (documented in ``report``).
DIRECTION_TOLERANCE = math.radians(45.0)
FACING_TOLERANCE = math.radians(30.0)
HEIGHT_TOLERANCE = 0.01
MIDDLE_TOLERANCE = 0.10
EDGE_TOLERANCE = 0.05
#: Wall labels: the back within 5 cm of the wall and parallel to it within 2 degrees
#: (a corner's side within 5 cm too; centred under a window within MIDDLE_TOLERANCE);
#: beside a window means at most BESIDE_DISTANCE from its edge along the wall.
WALL_TOLERANCE = 0.05
WALL_ANGLE_TOLERANCE = math.radians(2.0)
BESIDE_DISTANCE = 0.6
#: AlignedWith: parallel within 5 degrees, faces flush within WALL_TOLERANCE.
ALIGN_TOLERANCE = math.radians(5.0)
#: The wall and alignment terms pull in centimetres and degrees, so their Gaussians are
#: narrower than the paper's sigma^2 = 0.1 (metres, radians): 10 cm off costs 1.
WALL_SIGMA2 = 0.005
WALL_ANGLE_SIGMA2 = 0.01
#: Line of sight: a blocked relation's energy gains this much, plus the sideways
#: shift (metres) that would clear each blocking box. (A box blocks when it stands on
#: the ground and is at least ``problem.SIGHT_HEIGHT`` = 1.2 m tall, a seated person's eyes.)
SIGHT_PENALTY = 1.0
#: Placements that stand by a window rather than a wall.
WINDOW_PLACEMENTS = ("under_window", "beside_window")
#: Small slack so a relation placed exactly on its threshold is not lost to rounding.
EPSILON = 1e-9


class Measure(NamedTuple):
    """A relation's energy and the geometry its satisfaction threshold reads."""

    energy: float
    distance: float = 0.0  # NextTo*: distanceBetween(A, B) in metres
    angle: float = 0.0  # radians off the wanted direction (NextTo*, Facing*)
    chosen: str | None = None  # Choose* labels: the direction that fits best
    height_gap: float = 0.0  # OnTopOf*: |A's base - B's top| in metres
    inside: bool = True  # OnTopOf*: A's centre over B's top
    offset: float = 0.0  # OnTopOfMiddle: centre distance; *Edge: gap to the edge
    blocker: str | None = None  # line of sight: the tall object in the way (the deepest)
    kept: float = 0.0  # wall labels: the gap A's catalog keeps to the wall (``wall_gap``)

    @property
    def blocked(self) -> bool:
        """Line of sight: a tall object stands between A and B."""
        return self.blocker is not None


def centre(end: Endpoint, state: State) -> tuple[float, float]:
    """An object's or group's centre in (x, z): a group's is its members' bounding box
    centre; a wall's its middle, an opening's its own centre, the room's the origin."""
    if end.kind == "object":
        return state.x[end.index], state.z[end.index]
    problem = state.problem
    if end.kind in ROOM_ENDS:
        return _room_part_centre(end, problem.indoors())
    x0 = z0 = math.inf
    x1 = z1 = -math.inf
    half_width, half_depth, cs, ss, xs, zs = (
        problem.half_width,
        problem.half_depth,
        state.c,
        state.s,
        state.x,
        state.z,
    )
    for box in end.members:  # (plain comparisons: this runs for every group term, every step)
        c, s = abs(cs[box]), abs(ss[box])
        ex = half_width[box] * c + half_depth[box] * s
        ez = half_width[box] * s + half_depth[box] * c
        x, z = xs[box], zs[box]
        if x - ex < x0:
            x0 = x - ex
        if x + ex > x1:
            x1 = x + ex
        if z - ez < z0:
            z0 = z - ez
        if z + ez > z1:
            z1 = z + ez
    return (x0 + x1) / 2.0, (z0 + z1) / 2.0


def source_point(end: Endpoint, state: State) -> tuple[float, float]:
    """Where directions from A start: an object's or group's centre, a path's first point."""
    if end.kind == "path":
        x, z = state.points[end.index][0]
        return x, z
    return centre(end, state)


def anchor(
    end: Endpoint, state: State, towards: tuple[float, float]
) -> tuple[float, float, float, float]:
    """(x, z, cos yaw, sin yaw) of B as seen from a point: its centre and its axes.

    For a path: the nearest point on it and its tangent as forward.
    """
    if end.kind == "object":
        return state.x[end.index], state.z[end.index], state.c[end.index], state.s[end.index]
    if end.kind == "group":
        x, z = centre(end, state)
        return x, z, 1.0, 0.0
    if end.kind in (
        "wall",
        "opening",
    ):  # the nearest point of the wall, its inner normal as forward
        room = state.problem.indoors()
        wall = _wall_of(end, room)
        u, _ = wall.to_wall(*towards)
        if end.kind == "opening":
            opening = room.openings[end.index]
            low, high = opening.span
            u = min(max(u, low), high)
        x, z = wall.to_world(min(max(u, 0.0), wall.length), 0.0)
        return x, z, wall.normal[1], wall.normal[0]  # forward (sin, cos) = normal
    if end.kind == "room":
        return 0.0, 0.0, 1.0, 0.0
    points = state.points[end.index]
    _, x, z, segment = nearest_on_polyline(points, towards[0], towards[1])
    tx, tz = (
        points[segment + 1][0] - points[segment][0],
        points[segment + 1][1] - points[segment][1],
    )
    length = math.hypot(tx, tz) or 1.0
    return x, z, tz / length, tx / length  # forward (sin, cos) = tangent


def distance_between(a: Endpoint, b: Endpoint, state: State) -> float:
    """Minimum distance between the collision geometry of two endpoints (0 when touching).

    Between groups, the member pair of least cheap lower bound (centre distance minus
    both circumradii) is measured first, then only pairs whose bound could beat the best
    so far; to a path, (member, segment) pairs likewise.
    """
    problem = state.problem
    if a.kind in ROOM_ENDS:
        a, b = b, a
    if b.kind in ROOM_ENDS:
        return _distance_to_room_part(a, b, state)
    if a.kind == "path" and b.kind == "path":
        gap = polyline_distance(state.points[a.index], state.points[b.index])
        return max(0.0, gap - (problem.path_width[a.index] + problem.path_width[b.index]) / 2.0)
    if a.kind == "path":
        a, b = b, a
    if b.kind == "path":
        gap = polyline_rects_distance(
            state.points[b.index], [state.rects[box] for box in a.members]
        )
        return max(0.0, gap - problem.path_width[b.index] / 2.0)
    if len(a.members) == 1 and len(b.members) == 1:
        return box_distance(a.members[0], b.members[0], state)
    xs, zs, size = state.x, state.z, problem.size
    bounds = [
        (math.hypot(xs[p] - xs[q], zs[p] - zs[q]) - (size[p] + size[q]) / 2.0, p, q)
        for p in a.members
        for q in b.members
    ]
    # The pair of least bound first (its exact distance bounds the rest), then only the
    # pairs whose bound could beat the best so far: the same minimum as visiting all.
    _, p, q = min(bounds)
    best = box_distance(p, q, state)
    for bound, p, q in bounds:
        if bound < best:
            distance = box_distance(p, q, state)
            if distance < best:
                best = distance
    return best


def box_distance(first: int, second: int, state: State) -> float:
    """Distance between two boxes: footprint gap combined with the vertical gap."""
    problem = state.problem
    planar = rect_distance(state.rects[first], state.rects[second])
    vertical = max(
        state.y[first] - (state.y[second] + problem.height[second]),
        state.y[second] - (state.y[first] + problem.height[first]),
        0.0,
    )
    return math.hypot(planar, vertical) if vertical > 0.0 else planar


def unit(dx: float, dz: float) -> tuple[float, float]:
    length = math.hypot(dx, dz)
    return (dx / length, dz / length) if length > 1e-12 else (0.0, 0.0)


def forward(end: Endpoint, state: State) -> tuple[float, float]:
    if end.kind == "object":
        return state.s[end.index], state.c[end.index]
    if end.kind in ("wall", "opening"):
        return _wall_of(end, state.problem.indoors()).normal  # a wall "faces" into the room
    return 0.0, 1.0  # groups and paths have no yaw of their own: the world's forward


# -- room parts as relation ends -----------------------------------------------------------


def _wall_of(end: Endpoint, room: Room) -> Wall:
    """The wall an endpoint is (a wall) or is in (an opening)."""
    if end.kind == "wall":
        return room.walls[end.index]
    return opening_wall(room, room.openings[end.index])


def opening_wall(room: Room, opening: Opening) -> Wall:
    """The wall a door or window is in."""
    wall = room.part(opening.wall)
    assert isinstance(wall, Wall)  # the room checked it names one of its walls
    return wall


def _room_part_centre(end: Endpoint, room: Room) -> tuple[float, float]:
    if end.kind == "wall":
        return room.walls[end.index].to_world(room.walls[end.index].length / 2.0, 0.0)
    if end.kind == "opening":
        return room.openings[end.index].center
    return 0.0, 0.0


def _distance_to_room_part(a: Endpoint, b: Endpoint, state: State) -> float:
    """Distance from an endpoint's boxes (or path) to a wall, an opening's stretch of its
    wall, or (the room) the nearest wall."""
    room = state.problem.indoors()
    if b.kind == "room":
        segments = [(w.start, w.end) for w in room.walls]
    elif b.kind == "wall":
        segments = [(room.walls[b.index].start, room.walls[b.index].end)]
    else:
        segments = [room.opening_ends(room.openings[b.index])]
    if a.kind == "path":
        return min(
            max(
                0.0,
                polyline_distance(state.points[a.index], [list(p), list(q)])
                - state.problem.path_width[a.index] / 2.0,
            )
            for p, q in segments
        )
    rects = [state.rects[box] for box in a.members]
    return min(polyline_rects_distance([list(p), list(q)], rects) for p, q in segments)


#: Facing relations that ask only for A's heading relative to B's, wherever A stands:
#: their energy reads the two yaws alone.
HEADING_FACINGS = ("same", "opposite", "orthogonal")


# -- line of sight -------------------------------------------------------------------


def sight_blocked(term: RelationTerm, state: State) -> tuple[float, str | None]:
    """(energy penalty, id of the deepest blocking box or None) of the segment between
    A's and B's centres (both objects) against the footprints of ``term.sight``.

    A box blocks when the segment crosses its footprint (separating axis test on the
    segment's normal and the box's two axes); its depth is how far the segment's line
    would have to shift sideways to clear it.
    """
    problem = state.problem
    a, b = term.a.index, term.b.index
    ax, az, bx, bz = state.x[a], state.z[a], state.x[b], state.z[b]
    dx, dz = bx - ax, bz - az
    length = math.hypot(dx, dz)
    if length < 1e-9:
        return 0.0, None
    tx, tz = dx / length, dz / length
    total, deepest, worst = 0.0, EPSILON, -1
    for box in term.sight:
        px, pz = state.x[box] - ax, state.z[box] - az
        along = px * tx + pz * tz
        across = pz * tx - px * tz
        radius = problem.size[box] / 2.0
        if along < -radius or along > length + radius or abs(across) >= radius:
            continue  # its bounding circle misses the segment
        c, s, hw, hd = state.c[box], state.s[box], problem.half_width[box], problem.half_depth[box]
        # Axis 1: the segment's normal (-tz, tx); the box's reach across it.
        depth = hw * abs(c * tz + s * tx) + hd * abs(s * tz - c * tx) - abs(across)
        if depth <= EPSILON:
            continue
        # Axes 2 and 3: the box's left (c, -s) and forward (s, c), with the segment's
        # ends relative to the box's centre (-px, -pz) and (dx - px, dz - pz).
        u0, u1 = -px * c + pz * s, (dx - px) * c - (dz - pz) * s
        if min(u0, u1) >= hw or max(u0, u1) <= -hw:
            continue
        w0, w1 = -px * s - pz * c, (dx - px) * s + (dz - pz) * c
        if min(w0, w1) >= hd or max(w0, w1) <= -hd:
            continue
        total += depth
        if depth > deepest:
            deepest, worst = depth, box
    if worst < 0:
        return 0.0, None
    return SIGHT_PENALTY + total, problem.ids[worst]


def blocked_complaint(term: RelationTerm, measure: Measure) -> str:
    return f"{term.source} is not {term.spec.phrase} {term.target} (the line of sight runs through {measure.blocker})"
