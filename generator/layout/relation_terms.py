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
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import NamedTuple

from scenewright.core.relations import FAMILIES

from .factors import angle_between, equals, less, pointing_same_direction, range_
from .geometry import nearest_on_polyline, polyline_distance, polyline_rects_distance, rect_distance, to_local
from .params import LayoutParams
from .problem import Endpoint, RelationTerm
from .state import State

#: Thresholds of ``satisfied`` (documented in ``report``).
DIRECTION_TOLERANCE = math.radians(45.0)
FACING_TOLERANCE = math.radians(30.0)
HEIGHT_TOLERANCE = 0.01
MIDDLE_TOLERANCE = 0.10
EDGE_TOLERANCE = 0.05
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


def centre(end: Endpoint, state: State) -> tuple[float, float]:
    """An object's or group's centre in (x, z): a group's is its members' bounding box centre."""
    if end.kind == "object":
        return state.x[end.index], state.z[end.index]
    problem = state.problem
    x0 = z0 = math.inf
    x1 = z1 = -math.inf
    for box in end.members:
        ex = problem.half_width[box] * abs(state.c[box]) + problem.half_depth[box] * abs(state.s[box])
        ez = problem.half_width[box] * abs(state.s[box]) + problem.half_depth[box] * abs(state.c[box])
        x0, x1 = min(x0, state.x[box] - ex), max(x1, state.x[box] + ex)
        z0, z1 = min(z0, state.z[box] - ez), max(z1, state.z[box] + ez)
    return (x0 + x1) / 2.0, (z0 + z1) / 2.0


def source_point(end: Endpoint, state: State) -> tuple[float, float]:
    """Where directions from A start: an object's or group's centre, a path's first point."""
    if end.kind == "path":
        x, z = state.points[end.index][0]
        return x, z
    return centre(end, state)


def anchor(end: Endpoint, state: State, towards: tuple[float, float]) -> tuple[float, float, float, float]:
    """(x, z, cos yaw, sin yaw) of B as seen from a point: its centre and its axes.

    For a path: the nearest point on it and its tangent as forward.
    """
    if end.kind == "object":
        return state.x[end.index], state.z[end.index], state.c[end.index], state.s[end.index]
    if end.kind == "group":
        x, z = centre(end, state)
        return x, z, 1.0, 0.0
    points = state.points[end.index]
    _, x, z, segment = nearest_on_polyline(points, towards[0], towards[1])
    tx, tz = points[segment + 1][0] - points[segment][0], points[segment + 1][1] - points[segment][1]
    length = math.hypot(tx, tz) or 1.0
    return x, z, tz / length, tx / length  # forward (sin, cos) = tangent


def distance_between(a: Endpoint, b: Endpoint, state: State) -> float:
    """Minimum distance between the collision geometry of two endpoints (0 when touching).

    Between groups, member pairs are visited nearest first by a cheap lower bound (centre
    distance minus both circumradii), and the exact test stops once no bound can win; to
    a path, (member, segment) pairs likewise.
    """
    problem = state.problem
    if a.kind == "path" and b.kind == "path":
        gap = polyline_distance(state.points[a.index], state.points[b.index])
        return max(0.0, gap - (problem.path_width[a.index] + problem.path_width[b.index]) / 2.0)
    if a.kind == "path":
        a, b = b, a
    if b.kind == "path":
        gap = polyline_rects_distance(state.points[b.index], [state.rects[box] for box in a.members])
        return max(0.0, gap - problem.path_width[b.index] / 2.0)
    if len(a.members) == 1 and len(b.members) == 1:
        return box_distance(a.members[0], b.members[0], state)
    bounds = sorted(
        (math.hypot(state.x[p] - state.x[q], state.z[p] - state.z[q]) - (problem.size[p] + problem.size[q]) / 2.0, p, q)
        for p in a.members
        for q in b.members
    )
    best = math.inf
    for bound, p, q in bounds:
        if bound >= best:
            break
        best = min(best, box_distance(p, q, state))
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
    return 0.0, 1.0  # groups and paths have no yaw of their own: the world's forward


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
    ax, az = source_point(term.a, state)
    bx, bz, c, s = anchor(term.b, state, (ax, az))
    dx, dz = _unit(ax - bx, az - bz)
    chosen, best = None, math.inf
    for word, (wx, wz) in spec.direction_vectors(c, s).items():
        angle = angle_between(dx, dz, wx, wz)
        if angle < best - 1e-12:
            chosen, best = word, angle
    energy -= equals(best, 0.0, params.sigma2)
    return Measure(energy, distance, best, chosen if spec.chooses else None)


def _next_to_holds(term: RelationTerm, measure: Measure, params: LayoutParams) -> bool:
    near = measure.distance <= params.next_to_distance + EPSILON
    return near and (not term.spec.directions or measure.angle <= DIRECTION_TOLERANCE + EPSILON)


def _next_to_complaint(term: RelationTerm, measure: Measure, params: LayoutParams) -> str:
    words = term.spec.phrase
    if measure.distance > params.next_to_distance:
        return f"{term.source} is not {words} {term.target} (distance {measure.distance:.1f} m)"
    return f"{term.source} is not {words} {term.target} ({math.degrees(measure.angle):.0f}° off)"


# -- facing ------------------------------------------------------------------------


def _facing(term: RelationTerm, state: State, params: LayoutParams) -> Measure:
    fx, fz = _forward(term.a, state)
    how = term.spec.facing
    if how in ("towards", "away"):
        ax, az = centre(term.a, state)
        bx, bz, _, _ = anchor(term.b, state, (ax, az))
        dx, dz = _unit(bx - ax, bz - az) if how == "towards" else _unit(ax - bx, az - bz)
        angle = angle_between(dx, dz, fx, fz)
        return Measure(-pointing_same_direction(dx, dz, fx, fz, params.sigma2), angle=angle)
    gx, gz = _forward(term.b, state)
    angle = angle_between(fx, fz, gx, gz)
    if how == "same":
        return Measure(-equals(angle, 0.0, params.sigma2), angle=angle)
    off = abs(angle - math.pi / 2.0)  # orthogonal
    return Measure(-equals(angle, math.pi / 2.0, params.sigma2), angle=off)


def _facing_holds(term: RelationTerm, measure: Measure, params: LayoutParams) -> bool:
    return measure.angle <= FACING_TOLERANCE + EPSILON


def _facing_complaint(term: RelationTerm, measure: Measure, params: LayoutParams) -> str:
    return f"{term.source} is not {term.spec.phrase} {term.target} ({math.degrees(measure.angle):.0f}° off)"


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
        return Measure(energy - equals(offset, 0.0, params.sigma2), height_gap=height_gap, inside=inside, offset=offset)
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
    if term.spec.placement == "anywhere" or measure.height_gap > HEIGHT_TOLERANCE or not measure.inside:
        return f"{term.source} is not on top of {term.target}"
    return f"{term.source} is not {term.spec.phrase} {term.target} ({measure.offset:.2f} m off)"


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
}

_missing = set(FAMILIES) - set(FAMILY_TERMS) - {"structural"}
if _missing:  # a registry family the layout cannot score: refuse at start-up
    raise ImportError(f"the layout implements no relation family {', '.join(sorted(_missing))}")
