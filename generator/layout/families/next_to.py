"""NextTo*: A beside B, at a small gap, on the side the label names.

A label with a ``reach`` (``Beside*``: paired furniture; ``Seated*``: a seat at its
table) holds within that gap rather than the layout's general 2 m, and is placed within
it; a seat label also turns A to face B squarely (``seat_off``).

A is placed beside B (at a random point along a road B, turned to face the road most of
the time; beside a wall, window or the room on the side named, into the room by
default), or, in a data-driven move, B is shifted next to A instead. Beside an object
that keeps free space on that side, A stands beyond that space when things placed by A
may not stand in it (``kept_free``: the teacher's chair between the teacher's desk and
the board), and a way's width off the only side B is used from when A, as wide as that
side, would bar it (a pupil's chair behind a desk). A pinned A pulls its road to it
(``Placer.pull``); an item nothing anchors borrows B of a NextTo* of what points at it.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from scenewright.core.frames import to_local, to_world
from scenewright.core.relations import SEAT_SQUARE_TOLERANCE, RelationLabel

from ..factors import angle_between, equals, less
from ..motion import draw_index, end_reach, rigid, uniform, wrap
from ..params import LayoutParams
from ..reachability import CORRIDOR_HALF
from ..relation_terms import (
    DIRECTION_TOLERANCE,
    EPSILON,
    Measure,
    anchor,
    blocked_complaint,
    centre,
    distance_between,
    opening_wall,
    sight_blocked,
    source_point,
    unit,
)
from ..state import State
from ..terms import ROOM_ENDS, Endpoint, RelationTerm
from .entry import LayoutFamily
from .support import place_on_top

if TYPE_CHECKING:
    from ..placement import Placer
    from ..problem import Problem

#: Gaps (metres) a data-driven NextTo proposal leaves between A and B.
GAP_RANGE = (0.05, 0.8)

#: Gaps (metres) a seat's placement leaves between it and its table: within its reach,
#: not touching (a chair pushed fully in would stand in the table's box).
SEAT_GAP_RANGE = (0.05, 0.3)

#: The variance (m², rad²) of the pull of a label with a reach back within it, and of a
#: seat's turn to square: 2 cm beyond the reach costs 1, 10 degrees off about 1.
REACH_SIGMA2 = 0.0002
SEAT_SIGMA2 = 0.015

#: How far (as a share of B's half side) a data-driven NextTo proposal may slide A along B.
LATERAL_SHARE = 0.5


def on_its_top(problem: Problem, term: RelationTerm) -> bool:
    """Whether A rests on B and the label names one of B's own sides: the side of B's
    top A stands at (a lamp at the left end of a sideboard), not beside B."""
    return (
        term.a.kind == "object"
        and term.b.kind == "object"
        and problem.support[term.a.index] == term.b.index
        and term.spec.names_target_side
        and len(term.spec.directions) == 1
    )


def _place_at_end_of_top(placer: Placer, term: RelationTerm) -> dict | None:
    """A placed on B's top as its support relation places it, on the side the label
    names: mirrored across B's middle when it came down on the other side."""
    problem, state = placer.problem, placer.state
    a, b = term.a.index, term.b.index
    support = next(
        (
            t
            for t in problem.outgoing.get(("object", a), [])
            if t.spec.support and t.b.kind == "object" and t.b.index == b
        ),
        None,
    )
    if support is None:
        return None
    poses = place_on_top(placer, support)
    x, z, yaw = poses[a]
    ((dx, dz),) = term.spec.directions.values()  # B's own side: left (1, 0), front (0, 1)...
    lx, lz = to_local(state.x[b], state.z[b], state.yaw[b], x, z)
    if lx * dx + lz * dz < 0.0:  # the other side: mirror across B's middle
        lx, lz = (-lx, lz) if dx else (lx, -lz)
        nx, nz = to_world(state.x[b], state.z[b], state.yaw[b], lx, lz)
        poses = {k: (px + nx - x, pz + nz - z, pyaw) for k, (px, pz, pyaw) in poses.items()}
    return poses


def place(placer: Placer, term: RelationTerm, keep_heading: bool = False) -> dict | None:
    """A beside B as the label wants: beside a road at a random point along it (turned to
    face it most of the time, unless ``keep_heading``), beside a room's part, on the
    side of B the label names, slid a little along that side, or, for an A resting on B,
    at that side of B's top (``on_its_top``)."""
    problem, state, rng = placer.problem, placer.state, placer.rng
    a, b = term.a, term.b
    if b.kind in ROOM_ENDS:
        return _place_by_room_part(placer, term)
    if on_its_top(problem, term):
        return _place_at_end_of_top(placer, term)
    ax, az = centre(a, state)
    gap = uniform(rng, *gap_range(term.spec))
    turn = 0.0
    if b.kind == "path":
        points = state.points[b.index]
        segment = draw_index(rng, len(points) - 1)
        t = uniform(rng, 0.05, 0.95)
        (p0x, p0z), (p1x, p1z) = points[segment], points[segment + 1]
        length = math.hypot(p1x - p0x, p1z - p0z) or 1.0
        tx, tz = (p1x - p0x) / length, (p1z - p0z) / length
        side = 1.0 if rng.random() < 0.5 else -1.0
        nx, nz = -tz * side, tx * side  # a normal of the road, on the chosen side
        bx, bz = p0x + t * (p1x - p0x), p0z + t * (p1z - p0z)
        if not keep_heading and rng.random() < 0.7:  # turn A to face the road
            heading = placer.heading(a)
            turn = wrap(math.atan2(-nx, -nz) - heading)
        offset = problem.path_width[b.index] / 2.0
        wx, wz = nx, nz
    else:
        bx, bz, c, s = anchor(b, state, (ax, az))
        wx, wz = placer.wanted_direction(term, c, s)
        offset = end_reach(problem, state, b, wx, wz)
        if not term.spec.seat:  # a seat is its table's partner: it stands in the kept space
            offset += kept_free(placer, a, b, wx, wz)
        # Slide sideways along B's side a little, so several things beside B can fit.
        slide = uniform(rng, -LATERAL_SHARE, LATERAL_SHARE) * end_reach(problem, state, b, -wz, wx)
        bx, bz = bx - wz * slide, bz + wx * slide
        if term.spec.seat and not keep_heading:  # the seat faces its table squarely
            turn = wrap(math.atan2(-wx, -wz) - placer.heading(a))
    boxes = placer.moving_boxes(a)
    pivot = (ax, az)
    if turn:  # measure A's reach and centre as they will be once turned
        with state.trying(rigid(state, boxes, pivot, turn, (0.0, 0.0))):
            a_reach = end_reach(problem, state, a, -wx, -wz)
            ax, az = centre(a, state)
    else:
        a_reach = end_reach(problem, state, a, -wx, -wz)
    distance = offset + a_reach + gap
    return rigid(state, boxes, pivot, turn, (bx + wx * distance - ax, bz + wz * distance - az))


def place_target(placer: Placer, term: RelationTerm) -> dict:
    """New poses for B (shifted, not turned) at which the NextTo* ``term`` holds."""
    problem, state = placer.problem, placer.state
    a, b = term.a, term.b
    ax, az = source_point(a, state)
    bx, bz, c, s = anchor(b, state, (ax, az))
    wx, wz = placer.wanted_direction(term, c, s)
    if a.kind == "path":
        a_reach = problem.path_width[a.index] / 2.0
    else:
        a_reach = end_reach(problem, state, a, -wx, -wz)
    distance = (
        a_reach
        + end_reach(problem, state, b, wx, wz)
        + (0.0 if term.spec.seat else kept_free(placer, a, b, wx, wz))
        + uniform(placer.rng, *gap_range(term.spec))
    )
    return rigid(
        state,
        placer.moving_boxes(b),
        (bx, bz),
        0.0,
        (ax - wx * distance - bx, az - wz * distance - bz),
    )


def gap_range(spec: RelationLabel) -> tuple[float, float]:
    """The gaps (metres) a placement by ``spec`` draws from: within its reach."""
    if spec.seat:
        return SEAT_GAP_RANGE
    if spec.reach is not None:
        return (min(GAP_RANGE[0], spec.reach / 4.0), spec.reach * 0.8)
    return GAP_RANGE


def kept_free(placer: Placer, a: Endpoint, end: Endpoint, wx: float, wz: float) -> float:
    """How far (metres) a NextTo* placement of ``a`` beside ``end`` in the unit
    direction (wx, wz) stays off ``end``: the depth of the free space ``end`` keeps
    on that side (its catalog ``clearance``), when ``a`` is an object that others
    are placed by and some of them may not stand in that space (they are no partners
    of ``end``'s); else 0 (``a`` itself, as ``end``'s partner, may stand in it: a
    chair pulled up to a desk). So a teacher's desk in front of a board stands beyond
    the space kept in front of the board, with room for its chair between.

    When that side is the only one ``end`` is used from (its ``access``) and ``a``
    would bar the way to it (``_bars``: a tall box on the ground as wide as the side,
    in a room with a door), ``a`` stands a way's width off it instead (``way_width``):
    a pupil's chair behind a desk used from its back leaves the aisle to it, where
    one pulled up close took the desk's only way in and the chain had to pull every
    chair back."""
    if end.kind != "object" or a.kind != "object":
        return 0.0
    box = end.index
    c, s = placer.state.c[box], placer.state.s[box]
    lx, lz = wx * c - wz * s, wx * s + wz * c  # B's local axes: +x its left, +z its front
    if abs(lz) >= abs(lx):
        side = "front" if lz > 0.0 else "back"
    else:
        side = "left" if lx > 0.0 else "right"
    way = (
        placer.way_width
        if placer.problem.access[box] == (side,) and _bars(placer, a, box, side, wx, wz)
        else 0.0
    )
    strangers = placer.followers[a.index] - placer.partners[box]
    if not placer.problem.clearance[box] or not strangers:
        return way
    kept = max(
        (metres for named, metres in placer.problem.clearance[box] if named == side), default=0.0
    )
    if kept == 0.0:
        return way
    # Room for those placed by A between it and the space: the deepest of them, by its
    # shorter side (they stand on A's side towards B or not: the tries decide).
    between = max(
        2.0 * min(placer.problem.half_width[f], placer.problem.half_depth[f]) for f in strangers
    )
    return max(way, kept + between)


def _bars(placer: Placer, a: Endpoint, box: int, side: str, wx: float, wz: float) -> bool:
    """Whether ``a`` (an object), standing beside ``box``'s ``side`` in the unit
    direction (wx, wz), would leave no way to that side however far off it stood: it
    blocks ways and, with a half corridor either side of it, it is as wide as the side
    is long (a pupil's chair behind a 0.7 m desk; not a chair at a 1.2 m desk, whose
    ends stay free)."""
    if not placer.blocks_way[a.index]:
        return False
    problem = placer.problem
    across = 2.0 * end_reach(problem, placer.state, a, -wz, wx)
    length = 2.0 * (
        problem.half_width[box] if side in ("front", "back") else problem.half_depth[box]
    )
    return across + 2.0 * CORRIDOR_HALF >= length


def _place_by_room_part(placer: Placer, term: RelationTerm) -> dict:
    """A next to a wall, an opening or the room (a wall drawn by its length): at a
    small gap from the wall, at a random place along it (along the opening's
    stretch), on the side the label names (into the room by default)."""
    problem, state, rng = placer.problem, placer.state, placer.rng
    room, b = problem.indoors(), term.b
    if b.kind == "opening":
        opening = room.openings[b.index]
        wall = opening_wall(room, opening)
        low, high = opening.span
    else:
        if b.kind == "wall":
            wall = room.walls[b.index]
        else:
            lengths = np.array([w.length for w in room.walls])
            wall = room.walls[int(rng.choice(len(lengths), p=lengths / lengths.sum()))]
        low, high = 0.0, wall.length
    if term.spec.directions:
        wx, wz = placer.wanted_direction(
            term, wall.normal[1], wall.normal[0]
        )  # the wall faces into the room
    else:
        wx, wz = wall.normal
    px, pz = wall.to_world(uniform(rng, low, high), 0.0)
    ax, az = centre(term.a, state)
    distance = end_reach(problem, state, term.a, -wx, -wz) + uniform(rng, *GAP_RANGE)
    return rigid(
        state,
        placer.moving_boxes(term.a),
        (ax, az),
        0.0,
        (px + wx * distance - ax, pz + wz * distance - az),
    )


def needs_sight(spec: RelationLabel) -> bool:
    """Whether the label's directions are all on B's own front or back ("in front of",
    "behind"): A must then be seen from B."""
    if spec.frame == "target" and spec.directions:
        return all(abs(lz) > abs(lx) for lx, lz in spec.directions.values())
    return False


# -- its energy, its threshold and its complaint ------------------------------------


def reach(spec: RelationLabel, params: LayoutParams) -> float:
    """The largest gap (metres) at which a label holds: its own, or the general one."""
    return params.next_to_distance if spec.reach is None else spec.reach


def seat_off(term: RelationTerm, state: State, wx: float, wz: float) -> float:
    """How far (radians) a seat A is turned off facing squarely the side of B that lies
    in the world direction (wx, wz) from B (it should face -(wx, wz))."""
    if term.a.kind != "object":
        return 0.0
    box = term.a.index
    return angle_between(state.s[box], state.c[box], -wx, -wz)


def measure(term: RelationTerm, state: State, params: LayoutParams) -> Measure:
    distance = distance_between(term.a, term.b, state)
    spec = term.spec
    if spec.reach is None:
        energy = -less(distance, params.next_to_distance, params.h)
    else:  # a hinge: free within the reach, a steep pull back beyond it
        energy = -equals(max(distance - spec.reach, 0.0), 0.0, REACH_SIGMA2)
    if not spec.directions:
        return Measure(energy, distance)
    blocker = None
    if term.sight:
        penalty, blocker = sight_blocked(term, state)
        energy += penalty
    ax, az = source_point(term.a, state)
    bx, bz, c, s = anchor(term.b, state, (ax, az))
    dx, dz = unit(ax - bx, az - bz)
    chosen, best, side = None, math.inf, (0.0, 0.0)
    for word, (wx, wz) in spec.direction_vectors(c, s).items():
        angle = angle_between(dx, dz, wx, wz)
        if angle < best - 1e-12:
            chosen, best, side = word, angle, (wx, wz)
    energy -= equals(best, 0.0, params.sigma2)
    off = 0.0
    if spec.seat:
        off = seat_off(term, state, *side)
        energy -= equals(off, 0.0, SEAT_SIGMA2)
    return Measure(
        energy, distance, best, chosen if spec.chooses else None, blocker=blocker, offset=off
    )


def holds(term: RelationTerm, measure: Measure, params: LayoutParams) -> bool:
    near = measure.distance <= reach(term.spec, params) + EPSILON
    return (
        near
        and not measure.blocked
        and (not term.spec.directions or measure.angle <= DIRECTION_TOLERANCE + EPSILON)
        and measure.offset <= SEAT_SQUARE_TOLERANCE + EPSILON
    )


def complaint(term: RelationTerm, measure: Measure, params: LayoutParams) -> str:
    words = term.spec.phrase
    if measure.blocked:
        return blocked_complaint(term, measure)
    if measure.distance > reach(term.spec, params) + EPSILON:
        shown = f"{measure.distance:.1f}" if term.spec.reach is None else f"{measure.distance:.2f}"
        return f"{term.source} is not {words} {term.target} (distance {shown} m)"
    if measure.offset > SEAT_SQUARE_TOLERANCE + EPSILON:
        return (
            f"{term.source} is not {words} {term.target} "
            f"(turned {math.degrees(measure.offset):.0f}° off facing it)"
        )
    return f"{term.source} is not {words} {term.target} ({math.degrees(measure.angle):.0f}° off)"


FAMILY = LayoutFamily(
    measure=measure,
    holds=holds,
    complaint=complaint,
    place=place,
    place_target=place_target,
    anchors_target=True,
    pulls_roads=True,
    needs_sight=needs_sight,
)
