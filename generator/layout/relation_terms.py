"""Table 1 of the paper: the energy of one relation edge, and its geometric measures.

``evaluate(term, state, params)`` returns a ``Measure``: the energy (minus the log
factor, >= 0) and the quantities the satisfaction thresholds look at (distance, angle
off the wanted direction, and so on). Readings of the table, where it is garbled or
leaves the geometry open:

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

Rooms add the ``wall`` and ``alignment`` families (``_wall``, ``_alignment``) and line
of sight: a relation whose term lists ``sight`` boxes (``problem.needs_sight``: in
front of, behind, facing towards or away, between two objects) is blocked when the
segment between A's and B's centres crosses the footprint of one of those tall boxes.
A blocked relation does not hold whatever its other measures say; its energy gains
``SIGHT_PENALTY`` plus how far (metres) the segment would have to shift sideways to
clear each blocking box, so the sampler is pushed out of it by the shortest way.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import NamedTuple

from scenewright.core.geometry import (
    nearest_on_polyline,
    polyline_distance,
    polyline_rects_distance,
    rect_distance,
    to_local,
)
from scenewright.core.relations import FAMILIES
from scenewright.core.room import Opening, Room, Wall

from .factors import angle_between, equals, less, pointing_same_direction, range_
from .params import LayoutParams
from .problem import ROOM_ENDS, Endpoint, RelationTerm
from .state import State

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
        return _room_part_centre(end, problem.room)
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
        wall = _wall_of(end, state.problem.room)
        u, _ = wall.to_wall(*towards)
        if end.kind == "opening":
            opening = state.problem.room.openings[end.index]
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


def _unit(dx: float, dz: float) -> tuple[float, float]:
    length = math.hypot(dx, dz)
    return (dx / length, dz / length) if length > 1e-12 else (0.0, 0.0)


def _forward(end: Endpoint, state: State) -> tuple[float, float]:
    if end.kind == "object":
        return state.s[end.index], state.c[end.index]
    if end.kind in ("wall", "opening"):
        return _wall_of(end, state.problem.room).normal  # a wall "faces" into the room
    return 0.0, 1.0  # groups and paths have no yaw of their own: the world's forward


# -- room parts as relation ends -----------------------------------------------------------


def _wall_of(end: Endpoint, room: Room) -> Wall:
    """The wall an endpoint is (a wall) or is in (an opening)."""
    if end.kind == "wall":
        return room.walls[end.index]
    return room.part(room.openings[end.index].wall)


def _room_part_centre(end: Endpoint, room: Room) -> tuple[float, float]:
    if end.kind == "wall":
        return room.walls[end.index].to_world(room.walls[end.index].length / 2.0, 0.0)
    if end.kind == "opening":
        return room.openings[end.index].center
    return 0.0, 0.0


def _distance_to_room_part(a: Endpoint, b: Endpoint, state: State) -> float:
    """Distance from an endpoint's boxes (or path) to a wall, an opening's stretch of its
    wall, or (the room) the nearest wall."""
    room = state.problem.room
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


def evaluate(term: RelationTerm, state: State, params: LayoutParams) -> Measure:
    """The energy (>= 0) of one relation edge and its geometric measures."""
    return FAMILY_TERMS[term.spec.family].evaluate(term, state, params)


def satisfied(term: RelationTerm, measure: Measure, params: LayoutParams) -> bool:
    """Whether the relation holds geometrically (the thresholds of ``report``)."""
    return FAMILY_TERMS[term.spec.family].satisfied(term, measure, params)


def complaint(term: RelationTerm, measure: Measure, params: LayoutParams) -> str:
    """What is wrong with a relation that does not hold, in words."""
    return FAMILY_TERMS[term.spec.family].complaint(term, measure, params)


# -- next to -----------------------------------------------------------------------


def _next_to(term: RelationTerm, state: State, params: LayoutParams) -> Measure:
    distance = distance_between(term.a, term.b, state)
    energy = -less(distance, params.next_to_distance, params.h)
    spec = term.spec
    if not spec.directions:
        return Measure(energy, distance)
    blocker = None
    if term.sight:
        penalty, blocker = sight_blocked(term, state)
        energy += penalty
    ax, az = source_point(term.a, state)
    bx, bz, c, s = anchor(term.b, state, (ax, az))
    dx, dz = _unit(ax - bx, az - bz)
    chosen, best = None, math.inf
    for word, (wx, wz) in spec.direction_vectors(c, s).items():
        angle = angle_between(dx, dz, wx, wz)
        if angle < best - 1e-12:
            chosen, best = word, angle
    energy -= equals(best, 0.0, params.sigma2)
    return Measure(energy, distance, best, chosen if spec.chooses else None, blocker=blocker)


def _next_to_holds(term: RelationTerm, measure: Measure, params: LayoutParams) -> bool:
    near = measure.distance <= params.next_to_distance + EPSILON
    return (
        near
        and not measure.blocked
        and (not term.spec.directions or measure.angle <= DIRECTION_TOLERANCE + EPSILON)
    )


def _next_to_complaint(term: RelationTerm, measure: Measure, params: LayoutParams) -> str:
    words = term.spec.phrase
    if measure.blocked:
        return _blocked_complaint(term, measure)
    if measure.distance > params.next_to_distance:
        return f"{term.source} is not {words} {term.target} (distance {measure.distance:.1f} m)"
    return f"{term.source} is not {words} {term.target} ({math.degrees(measure.angle):.0f}° off)"


# -- facing ------------------------------------------------------------------------

#: Facing relations that ask only for A's heading relative to B's, wherever A stands:
#: their energy reads the two yaws alone.
HEADING_FACINGS = ("same", "opposite", "orthogonal")


def _facing(term: RelationTerm, state: State, params: LayoutParams) -> Measure:
    fx, fz = _forward(term.a, state)
    how = term.spec.facing
    if how in ("towards", "away"):
        ax, az = centre(term.a, state)
        bx, bz, _, _ = anchor(term.b, state, (ax, az))
        dx, dz = _unit(bx - ax, bz - az) if how == "towards" else _unit(ax - bx, az - bz)
        angle = angle_between(dx, dz, fx, fz)
        energy = -pointing_same_direction(dx, dz, fx, fz, params.sigma2)
        if term.sight:
            penalty, blocker = sight_blocked(term, state)
            return Measure(energy + penalty, angle=angle, blocker=blocker)
        return Measure(energy, angle=angle)
    gx, gz = _forward(term.b, state)
    angle = angle_between(fx, fz, gx, gz)
    if how == "opposite":
        angle = math.pi - angle
        return Measure(-equals(angle, 0.0, params.sigma2), angle=angle)
    if how == "same":
        return Measure(-equals(angle, 0.0, params.sigma2), angle=angle)
    off = abs(angle - math.pi / 2.0)  # orthogonal
    return Measure(-equals(angle, math.pi / 2.0, params.sigma2), angle=off)


def _facing_holds(term: RelationTerm, measure: Measure, params: LayoutParams) -> bool:
    return measure.angle <= FACING_TOLERANCE + EPSILON and not measure.blocked


def _facing_complaint(term: RelationTerm, measure: Measure, params: LayoutParams) -> str:
    if measure.blocked:
        return _blocked_complaint(term, measure)
    return f"{term.source} is not {term.spec.phrase} {term.target} ({math.degrees(measure.angle):.0f}° off)"


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


def _blocked_complaint(term: RelationTerm, measure: Measure) -> str:
    return f"{term.source} is not {term.spec.phrase} {term.target} (the line of sight runs through {measure.blocker})"


# -- support -----------------------------------------------------------------------


def _support(term: RelationTerm, state: State, params: LayoutParams) -> Measure:
    problem = state.problem
    a, b = term.a.index, term.b.index
    top = state.y[b] + problem.height[b]
    height_gap = abs(state.y[a] - top)
    energy = -equals(state.y[a], top, params.sigma2)
    rect_b = state.rects[b]
    lx, lz = to_local(rect_b, state.x[a], state.z[a])
    hw, hd = rect_b.hw, rect_b.hd
    inside = abs(lx) <= hw and abs(lz) <= hd
    within = range_(lx, -hw, hw, params.h) + range_(lz, -hd, hd, params.h)
    placement = term.spec.placement
    if placement == "anywhere":
        return Measure(energy - within, height_gap=height_gap, inside=inside)
    if placement == "middle":
        offset = math.hypot(lx, lz)
        return Measure(
            energy - equals(offset, 0.0, params.sigma2),
            height_gap=height_gap,
            inside=inside,
            offset=offset,
        )
    # A's half extents along B's axes, then the gaps between A's sides and B's edges.
    k1 = abs(state.c[a] * state.c[b] + state.s[a] * state.s[b])
    k2 = abs(state.c[a] * state.s[b] - state.s[a] * state.c[b])
    ex = problem.half_width[a] * k1 + problem.half_depth[a] * k2
    ez = problem.half_width[a] * k2 + problem.half_depth[a] * k1
    front = abs(hd - lz - ez)
    if placement == "front_edge":
        offset = front
    else:
        offset = min(front, abs(hd + lz - ez), abs(hw - lx - ex), abs(hw + lx - ex))
    # Only a centre off the top is penalised here: a soft pull towards the middle would
    # fight the pull towards the edge.
    overhang = math.hypot(max(abs(lx) - hw, 0.0), max(abs(lz) - hd, 0.0))
    energy -= equals(offset, 0.0, params.sigma2) + equals(overhang, 0.0, params.sigma2)
    return Measure(energy, height_gap=height_gap, inside=inside, offset=offset)


def _support_holds(term: RelationTerm, measure: Measure, params: LayoutParams) -> bool:
    on_top = measure.height_gap <= HEIGHT_TOLERANCE and measure.inside
    placement = term.spec.placement
    if placement == "middle":
        return on_top and measure.offset <= MIDDLE_TOLERANCE + EPSILON
    if placement in ("edge", "front_edge"):
        return on_top and measure.offset <= EDGE_TOLERANCE + EPSILON
    return on_top


def _support_complaint(term: RelationTerm, measure: Measure, params: LayoutParams) -> str:
    if (
        term.spec.placement == "anywhere"
        or measure.height_gap > HEIGHT_TOLERANCE
        or not measure.inside
    ):
        return f"{term.source} is not on top of {term.target}"
    return f"{term.source} is not {term.spec.phrase} {term.target} ({measure.offset:.2f} m off)"


# -- walls -------------------------------------------------------------------------


def _wall(term: RelationTerm, state: State, params: LayoutParams) -> Measure:
    """A's back against a wall (or in a corner, under or beside a window): the best of
    the candidates when B is the room, which is then recorded as ``chosen``."""
    room = state.problem.room
    placement, b = term.spec.wall, term.b
    if b.kind == "room":
        candidates = list(room.windows) if placement in WINDOW_PLACEMENTS else list(room.walls)
    elif b.kind == "wall":
        candidates = [room.walls[b.index]]
    else:
        candidates = [room.openings[b.index]]
    best = None
    for target in candidates:
        measure = _against(term.a.index, target, placement, state)
        if best is None or measure.energy < best.energy - 1e-12:
            best = measure
    if best is None:  # a room without the window the label needs
        return Measure(math.inf, offset=math.inf, inside=False)
    return best if b.kind == "room" else best._replace(chosen=None)


def _against(box: int, target: Wall | Opening, placement: str, state: State) -> Measure:
    """The wall measures of box ``box`` against one wall or window (see ``_wall``).

    ``distance``: the gap between the wall and the box's nearest corner (its back, once
    parallel); ``angle``: the box's forward off the wall's inner normal; ``offset``: how
    far the box runs past the ends of its wall, plus, in a corner, the gap between its
    side and the neighbouring wall, under a window the distance off the window's
    centre, beside one the overlap with it or the gap beyond ``BESIDE_DISTANCE``;
    ``inside``: a box under a window is lower than its sill.
    """
    problem, room = state.problem, state.problem.room
    window = target if isinstance(target, Opening) else None
    wall = room.part(window.wall) if window else target
    x, z, c, s = state.x[box], state.z[box], state.c[box], state.s[box]
    hw, hd = problem.half_width[box], problem.half_depth[box]
    nx, nz = wall.normal
    tx, tz = wall.direction
    # The box's reach along the wall's axes (its footprint's half extents there).
    reach_u = hw * abs(c * tx - s * tz) + hd * abs(s * tx + c * tz)
    reach_v = hw * abs(c * nx - s * nz) + hd * abs(s * nx + c * nz)
    u, v = wall.to_wall(x, z)
    gap = v - reach_v
    angle = angle_between(s, c, nx, nz)
    overhang = max(reach_u - u, u + reach_u - wall.length, 0.0)
    offset = overhang
    fits = True
    if placement == "corner":
        side = math.inf
        before, after = room.neighbours(wall.id)
        for other, at_start in ((before, True), (after, False)):
            if not (
                room.convex_corner(before, wall) if at_start else room.convex_corner(wall, after)
            ):
                continue
            _, v_other = other.to_wall(x, z)
            reach_other = hw * abs(c * other.normal[0] - s * other.normal[1]) + hd * abs(
                s * other.normal[0] + c * other.normal[1]
            )
            side = min(side, abs(v_other - reach_other))
        offset += side
    elif placement == "under_window":
        offset += abs(u - window.offset)
        fits = state.y[box] + problem.height[box] <= window.sill + EPSILON
    elif placement == "beside_window":
        low, high = window.span
        along = max(
            low - (u + reach_u), (u - reach_u) - high
        )  # < 0: overlaps the window along the wall
        offset += max(-along, 0.0) + max(along - BESIDE_DISTANCE, 0.0)
    energy = (
        -equals(gap, 0.0, WALL_SIGMA2)
        - equals(angle, 0.0, WALL_ANGLE_SIGMA2)
        - equals(offset, 0.0, WALL_SIGMA2)
    )
    if not fits:
        energy += 1.0  # cannot hold whatever the pose: a constant, so the rest still lays out
    return Measure(energy, distance=gap, angle=angle, chosen=target.id, offset=offset, inside=fits)


def _wall_holds(term: RelationTerm, measure: Measure, params: LayoutParams) -> bool:
    return (
        measure.inside
        and abs(measure.distance) <= WALL_TOLERANCE + EPSILON
        and measure.angle <= WALL_ANGLE_TOLERANCE + EPSILON
        and measure.offset
        <= (MIDDLE_TOLERANCE if term.spec.wall == "under_window" else WALL_TOLERANCE) + EPSILON
    )


def _wall_complaint(term: RelationTerm, measure: Measure, params: LayoutParams) -> str:
    target = measure.chosen or term.target
    words = f"{term.source} is not {term.spec.phrase} {target}"
    if math.isinf(measure.energy):
        return f"{words} (the room has no window)"
    if not measure.inside:
        return f"{words} (it is taller than the window's sill)"
    if abs(measure.distance) > WALL_TOLERANCE or measure.angle > WALL_ANGLE_TOLERANCE:
        return f"{words} (its back is {measure.distance:.2f} m from the wall, {math.degrees(measure.angle):.0f}° off)"
    return f"{words} ({measure.offset:.2f} m off)"


# -- alignment -----------------------------------------------------------------------


def _alignment(term: RelationTerm, state: State, params: LayoutParams) -> Measure:
    """A parallel to B (facing the same or the opposite way) with one of its faces in
    the plane of B's face on the same side: ``angle`` off parallel, ``offset`` the gap
    between the nearest pair of flush faces."""
    problem = state.problem
    a, b = term.a.index, term.b.index
    angle = angle_between(state.s[a], state.c[a], state.s[b], state.c[b])
    angle = min(angle, math.pi - angle)
    rect_b = state.rects[b]
    lx, lz = to_local(rect_b, state.x[a], state.z[a])
    k1 = abs(state.c[a] * state.c[b] + state.s[a] * state.s[b])
    k2 = abs(state.c[a] * state.s[b] - state.s[a] * state.c[b])
    ex = problem.half_width[a] * k1 + problem.half_depth[a] * k2
    ez = problem.half_width[a] * k2 + problem.half_depth[a] * k1
    hw, hd = rect_b.hw, rect_b.hd
    offset = min(abs(lz + ez - hd), abs(lz - ez + hd), abs(lx + ex - hw), abs(lx - ex + hw))
    energy = -equals(angle, 0.0, WALL_ANGLE_SIGMA2) - equals(offset, 0.0, WALL_SIGMA2)
    return Measure(energy, angle=angle, offset=offset)


def _alignment_holds(term: RelationTerm, measure: Measure, params: LayoutParams) -> bool:
    return measure.angle <= ALIGN_TOLERANCE + EPSILON and measure.offset <= WALL_TOLERANCE + EPSILON


def _alignment_complaint(term: RelationTerm, measure: Measure, params: LayoutParams) -> str:
    return (
        f"{term.source} is not {term.spec.phrase} {term.target} "
        f"({math.degrees(measure.angle):.0f}° off parallel, faces {measure.offset:.2f} m apart)"
    )


class FamilyTerm(NamedTuple):
    """The layout's side of a relation family: its energy and measures, the threshold
    that decides whether it holds, and the words for when it does not."""

    evaluate: Callable[[RelationTerm, State, LayoutParams], Measure]
    satisfied: Callable[[RelationTerm, Measure, LayoutParams], bool]
    complaint: Callable[[RelationTerm, Measure, LayoutParams], str]


#: One entry per geometric family of the relation registry. (``structural`` relations
#: become path starts when the problem is compiled and are never scored.)
FAMILY_TERMS: dict[str, FamilyTerm] = {
    "next_to": FamilyTerm(_next_to, _next_to_holds, _next_to_complaint),
    "facing": FamilyTerm(_facing, _facing_holds, _facing_complaint),
    "support": FamilyTerm(_support, _support_holds, _support_complaint),
    "wall": FamilyTerm(_wall, _wall_holds, _wall_complaint),
    "alignment": FamilyTerm(_alignment, _alignment_holds, _alignment_complaint),
}

_missing = set(FAMILIES) - set(FAMILY_TERMS) - {"structural"}
if _missing:  # a registry family the layout cannot score: refuse at start-up
    raise ImportError(f"the layout implements no relation family {', '.join(sorted(_missing))}")
