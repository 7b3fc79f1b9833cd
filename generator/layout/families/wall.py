"""Wall labels: A (an object on the ground) with its back flush to a wall (rooms), or
as far off it as its catalog's ``wall_gap`` keeps it (the problem's ``wall_gap``: the
energy, the threshold and the placement all target that gap, in a corner off both walls).

Against a wall, in a corner, under or beside a window; for the room as target, on a
wall or window drawn by how much room it leaves (``_wall_spots``). A spot along it is
drawn at random, avoiding doors' swings and, for furniture taller than a window's sill,
the window. A placement of A by another relation is half the time pushed back onto the
nearest fitting spot (``snap``), so "against the wall, left of the bed" lands where
both hold; a data-driven move sometimes carries along rigidly what is in place by A
(``carry_to_wall``: the bed goes to another wall with the nightstands beside it).
Furniture against a wall is placed first by the initial placement, what has few places
to go (a window, a corner) before what may stand anywhere along a wall.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from scenewright.core.errors import InputError
from scenewright.core.relations import Relation, RelationLabel
from scenewright.core.room import Opening, Room, Wall

from ..factors import angle_between, equals
from ..motion import rigid, uniform, wrap
from ..params import LayoutParams
from ..relation_terms import (
    BESIDE_DISTANCE,
    EPSILON,
    MIDDLE_TOLERANCE,
    WALL_ANGLE_SIGMA2,
    WALL_ANGLE_TOLERANCE,
    WALL_SIGMA2,
    WALL_TOLERANCE,
    WINDOW_PLACEMENTS,
    Measure,
    opening_wall,
)
from ..state import State
from ..terms import ROOM_ENDS, Endpoint, RelationTerm
from .entry import LayoutFamily, where

if TYPE_CHECKING:
    from ..placement import Placer
    from ..problem import Problem

#: Gaps (metres) a BesideWindow proposal leaves between A and the window's edge.
BESIDE_GAP = (0.02, min(0.25, BESIDE_DISTANCE))

#: Random spots along a wall tried before one in front of a door (or of a window, for
#: furniture taller than its sill) is taken anyway.
WALL_TRIES = 6
#: Furniture taller than a window's sill closer than this (metres) to its wall stands
#: in front of the window (a door's zone is its swing, as deep as the door is wide).
WINDOW_KEEP = 0.5


def place(placer: Placer, term: RelationTerm, keep_heading: bool) -> dict | None:
    """A with its back flush to a wall the label allows (``place_at_wall``)."""
    return place_at_wall(placer, term)


def snap(placer: Placer, term: RelationTerm) -> dict | None:
    """A pushed onto the nearest spot the wall relation allows, as it stands."""
    return place_at_wall(placer, term, snap=True)


def off_wall(problem: Problem, box: int) -> float:
    """How far box ``box``'s centre stands from a wall its back is against, square to it:
    half its depth, plus the ``wall_gap`` its catalog keeps."""
    return problem.half_depth[box] + problem.wall_gap[box]


def place_at_wall(placer: Placer, term: RelationTerm, *, snap: bool = False) -> dict | None:
    """A (an object on the ground) with its back flush to a wall: yaw the wall's
    ``facing_yaw``, its centre half its depth (and its ``wall_gap``) from the wall, where the wall label
    wants it (``_wall_spots``). A spot is drawn by how much room it leaves, then a
    place along it at random, avoiding doors' swings and, for furniture taller than
    a window's sill, the window. ``snap``: the spot nearest A as it stands, at the
    place along the wall nearest A (no random draw)."""
    problem, state, rng = placer.problem, placer.state, placer.rng
    box = term.a.index
    if problem.support[box] >= 0:
        return None  # it moves with what it rests on
    spots = _wall_spots(placer, term)
    if not spots:
        return None
    hd = off_wall(problem, box)  # its centre's distance from the wall
    if snap:
        best, best_distance = None, math.inf
        for wall, low, high, _ in spots:
            u, _ = wall.to_wall(state.x[box], state.z[box])
            x, z = wall.to_world(min(max(u, low), high), hd)
            distance = math.hypot(x - state.x[box], z - state.z[box])
            if distance < best_distance - 1e-12:
                best, best_distance = (x, z, wall.facing_yaw), distance
        assert best is not None  # a spot is nearer than infinitely far
        return placer.pose_box(box, *best)
    total = sum(weight for *_, weight in spots)
    draw = rng.random() * total
    for wall, low, high, weight in spots:  # noqa: B007 (the drawn spot is used below)
        draw -= weight
        if draw < 0.0:
            break
    yaw = wall.facing_yaw
    c, s = math.cos(yaw), math.sin(yaw)
    for _ in range(WALL_TRIES if high > low else 1):
        u = uniform(rng, low, high) if high > low else low
        x, z = wall.to_world(u, hd)
        if _clear_of_openings(placer, box, x, z, c, s):
            break
    return placer.pose_box(box, x, z, yaw)


def carry_to_wall(placer: Placer, term: RelationTerm) -> dict | None:
    """A placed by its wall relation, and the free boxes a relation that holds now
    ties to A (with what rests on them) turned and shifted with it rigidly, so a bed
    moves to another wall with the nightstands that stand beside it; one that is
    not in place yet stays to be placed on its own."""
    problem, state = placer.problem, placer.state
    box = term.a.index
    placed = place_at_wall(placer, term)
    if not placed:
        return None
    in_place = set(problem.carried(box))
    for index in problem.terms_of_box[box]:
        tie = problem.relations[index]
        if (
            tie.a.kind != "object"
            or tie.b.kind != "object"
            or box not in (tie.a.index, tie.b.index)
        ):
            continue
        other = tie.b.index if tie.a.index == box else tie.a.index
        if other in placer.cluster_of[box] and placer.holds(tie):
            in_place.update(b for b in problem.carried(other) if b in placer.cluster_of[box])
    x, z, yaw = placed[box]
    pivot = (state.x[box], state.z[box])
    moved = rigid(
        state, sorted(in_place), pivot, wrap(yaw - state.yaw[box]), (x - pivot[0], z - pivot[1])
    )
    moved[box] = (x, z, yaw)
    return moved


def _wall_spots(placer: Placer, term: RelationTerm) -> list[tuple[Wall, float, float, float]]:
    """Where the wall label lets A's centre go, as (wall, lowest u, highest u, weight):
    a stretch of a wall (against: where A's whole footprint stays on the wall) or a
    single place (a corner, under a window, beside either edge of one). For the room
    as target every wall or window is a candidate, weighted by the room left along
    it (wall length minus A's width; 1 for a single place). Places A does not fit,
    and single places in a door's swing (or, for furniture taller than its sill, in
    front of a window), are left out unless nothing else is left."""
    problem, state = placer.problem, placer.state
    room, box, b = problem.indoors(), term.a.index, term.b
    hw = problem.half_width[box]
    placement = term.spec.wall
    if placement in WINDOW_PLACEMENTS:
        openings = room.windows if b.kind == "room" else [room.openings[b.index]]
        walls = []
    else:
        openings = []
        if b.kind == "room":
            walls = list(room.walls)
        elif b.kind == "wall":
            walls = [room.walls[b.index]]
        else:
            walls = [opening_wall(room, room.openings[b.index])]
    fitting: list[tuple[Wall, float, float, float]] = []
    rest: list[tuple[Wall, float, float, float]] = []
    for wall in walls:
        length = wall.length
        if placement == "against":
            room_left = length - 2.0 * hw
            spot = (
                (wall, hw, length - hw, room_left)
                if room_left > 0.0
                else (wall, length / 2.0, length / 2.0, 0.0)
            )
            (fitting if room_left > 0.0 else rest).append(spot)
            continue
        before, after = room.neighbours(wall.id)
        for other, at_start in ((before, True), (after, False)):
            if not (
                room.convex_corner(before, wall) if at_start else room.convex_corner(wall, after)
            ):
                continue
            u = _corner_u(placer, box, wall, other)
            if u is None:
                continue
            fits = hw - 1e-9 <= u <= length - hw + 1e-9 and _clear_at(placer, box, wall, u)
            (fitting if fits else rest).append((wall, u, u, 1.0))
    top = state.y[box] + problem.height[box]
    for window in openings:
        wall = opening_wall(room, window)
        if placement == "under_window":
            u = window.offset
            fits = (
                top <= window.sill
                and hw <= u <= wall.length - hw
                and _clear_at(placer, box, wall, u)
            )
            (fitting if fits else rest).append((wall, u, u, 1.0))
            continue
        gap = uniform(placer.rng, *BESIDE_GAP)
        low, high = window.span
        for u in (low - gap - hw, high + gap + hw):
            fits = hw <= u <= wall.length - hw and _clear_at(placer, box, wall, u)
            (fitting if fits else rest).append((wall, u, u, 1.0))
    if fitting:
        return fitting
    return [(wall, low, high, 1.0) for wall, low, high, _ in rest]


def _corner_u(placer: Placer, box: int, wall: Wall, other: Wall) -> float | None:
    """Where along ``wall`` A's centre goes (back flush, yaw the wall's facing_yaw) so
    that its footprint just touches the neighbouring wall ``other``: the distance of
    its centre from ``other`` is then its reach towards it (each plus its ``wall_gap``)."""
    problem = placer.problem
    yaw = wall.facing_yaw
    c, s = math.cos(yaw), math.sin(yaw)
    nx, nz = other.normal
    reach_other = (
        problem.half_width[box] * abs(c * nx - s * nz)
        + problem.half_depth[box] * abs(s * nx + c * nz)
        + problem.wall_gap[box]  # kept off both walls
    )
    tx, tz = wall.direction
    rate = tx * nx + tz * nz  # how fast the distance from ``other`` changes along ``wall``
    if abs(rate) < 1e-9:
        return None
    _, v0 = other.to_wall(*wall.to_world(0.0, off_wall(problem, box)))
    return (reach_other - v0) / rate


def _clear_at(placer: Placer, box: int, wall: Wall, u: float) -> bool:
    """``_clear_of_openings`` for the box with its back flush to ``wall`` at ``u``."""
    x, z = wall.to_world(u, off_wall(placer.problem, box))
    return _clear_of_openings(
        placer, box, x, z, math.cos(wall.facing_yaw), math.sin(wall.facing_yaw)
    )


def _clear_of_openings(placer: Placer, box: int, x: float, z: float, c: float, s: float) -> bool:
    """Whether the box at (x, z) turned by (c, s) keeps out of every door's swing and
    does not stand in front of a window lower than its top."""
    problem, room = placer.problem, placer.problem.indoors()
    hw, hd = problem.half_width[box], problem.half_depth[box]
    top = placer.state.y[box] + problem.height[box]
    for opening in room.openings:
        if opening.kind == "window" and top <= opening.sill:
            continue
        wall = opening_wall(room, opening)
        tx, tz = wall.direction
        nx, nz = wall.normal
        reach_u = hw * abs(c * tx - s * tz) + hd * abs(s * tx + c * tz)
        reach_v = hw * abs(c * nx - s * nz) + hd * abs(s * nx + c * nz)
        u, v = wall.to_wall(x, z)
        keep = opening.width if opening.kind == "door" else WINDOW_KEEP
        if v - reach_v < keep and abs(u - opening.offset) < reach_u + opening.width / 2.0:
            return False
    return True


def placing_rank(term: RelationTerm) -> int:
    """1 for a place with few spots (a corner, under or beside a window), 0 for anywhere
    along a wall."""
    return 1 if term.spec.wall != "against" else 0


def check_ends(
    edge: Relation, spec: RelationLabel, a: Endpoint, b: Endpoint, room: Room | None
) -> None:
    """Only an object stands against a wall, and it stands against a wall, a window or
    the room (a window or the room for a window label); never against a door."""
    if a.kind != "object":
        raise InputError(
            f"{where(edge)}: only an object can stand against a wall ({edge.source} is a {a.kind})"
        )
    door = b.kind == "opening" and room is not None and room.openings[b.index].kind == "door"
    if b.kind not in ROOM_ENDS or door:
        raise InputError(f"{where(edge)}: the target must be a wall, a window or the room")
    if spec.wall in ("under_window", "beside_window") and b.kind == "wall":
        raise InputError(f"{where(edge)}: the target must be a window or the room, not a wall")


# -- its energy, its threshold and its complaint ------------------------------------


def measure(term: RelationTerm, state: State, params: LayoutParams) -> Measure:
    """A's back against a wall (or in a corner, under or beside a window): the best of
    the candidates when B is the room, which is then recorded as ``chosen``."""
    room = state.problem.indoors()
    placement, b = term.spec.wall, term.b
    assert placement is not None  # every wall label names its placement
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
    problem, room = state.problem, state.problem.indoors()
    window: Opening | None
    if isinstance(target, Opening):
        window, wall = target, opening_wall(room, target)
    else:
        window, wall = None, target
    x, z, c, s = state.x[box], state.z[box], state.c[box], state.s[box]
    hw, hd = problem.half_width[box], problem.half_depth[box]
    kept = problem.wall_gap[box]  # the gap its catalog keeps to the wall (0: flush)
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
            side = min(side, abs(v_other - reach_other - kept))
        offset += side
    elif placement == "under_window":
        assert window is not None  # a window label measures against windows only
        offset += abs(u - window.offset)
        fits = state.y[box] + problem.height[box] <= window.sill + EPSILON
    elif placement == "beside_window":
        assert window is not None
        low, high = window.span
        along = max(
            low - (u + reach_u), (u - reach_u) - high
        )  # < 0: overlaps the window along the wall
        offset += max(-along, 0.0) + max(along - BESIDE_DISTANCE, 0.0)
    energy = (
        -equals(gap, kept, WALL_SIGMA2)
        - equals(angle, 0.0, WALL_ANGLE_SIGMA2)
        - equals(offset, 0.0, WALL_SIGMA2)
    )
    if not fits:
        energy += 1.0  # cannot hold whatever the pose: a constant, so the rest still lays out
    return Measure(
        energy, distance=gap, angle=angle, chosen=target.id, offset=offset, inside=fits, kept=kept
    )


def holds(term: RelationTerm, measure: Measure, params: LayoutParams) -> bool:
    return (
        measure.inside
        and abs(measure.distance - measure.kept) <= WALL_TOLERANCE + EPSILON
        and measure.angle <= WALL_ANGLE_TOLERANCE + EPSILON
        and measure.offset
        <= (MIDDLE_TOLERANCE if term.spec.wall == "under_window" else WALL_TOLERANCE) + EPSILON
    )


def complaint(term: RelationTerm, measure: Measure, params: LayoutParams) -> str:
    target = measure.chosen or term.target
    words = f"{term.source} is not {term.spec.phrase} {target}"
    if math.isinf(measure.energy):
        return f"{words} (the room has no window)"
    if not measure.inside:
        return f"{words} (it is taller than the window's sill)"
    if (
        abs(measure.distance - measure.kept) > WALL_TOLERANCE
        or measure.angle > WALL_ANGLE_TOLERANCE
    ):
        kept = f", not {measure.kept:.2f} m" if measure.kept else ""
        return f"{words} (its back is {measure.distance:.2f} m from the wall{kept}, {math.degrees(measure.angle):.0f}° off)"
    return f"{words} ({measure.offset:.2f} m off)"


FAMILY = LayoutFamily(
    measure=measure,
    holds=holds,
    complaint=complaint,
    place=place,
    stands_against_wall=True,
    placing_rank=placing_rank,
    snap=snap,
    carry=carry_to_wall,
    check_ends=check_ends,
)
