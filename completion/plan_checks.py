"""What makes a drawn plan wrong, each problem as (JSON path, message).

A plan is design knowledge the product learns from, so it must be a room one could
live in: every piece wholly inside the walls; no two pieces on the floor overlapping
(a piece ``on`` another must lie within it, and flat things, a rug, may lie under
anything); each door's swing (the square as deep as the door is wide, ``Room.swing_zone``)
free; each piece's catalog clearance on every side it names (``clearance front 0.8``: a
wardrobe's doors, a desk's chair; a weight bench's sides) inside the room and free of everything but the seats used at it
(``activity.SEATS``); nothing taller than a window's sill standing in front of it; and
each free area clear of all of these.
Distances below ``TOLERANCE`` (5 mm) are drawing slack, not problems.

``unreachable`` finds the pieces no way at least 0.6 m wide from a door reaches. It is
not yet one of the rules a plan must pass: 13 of the 80 shipped plans still hem a piece
in (a test holds that list, so it can only shrink). The walkable way is the layout's
own test (``generator.layout.reachability``): the free floor is the floor at least 0.3 m from the walls and from every floor piece taller than
a rug, the way in is the free floor connected to a door, and a piece whose catalog entry
names sides it is used from (``access``) is reached when the way comes within 0.4 m of
them. A piece used from a seat (a desk, a dining table: a seat within that 0.4 m) is
reached through the seat too: one pulls the chair out to use it, as seats may stand in
a piece's clearance.
"""

from __future__ import annotations

import math

from scenewright.core.frames import to_local, to_world
from scenewright.core.geometry import left_normal, make_rect, rect_distance

#: Metres of overlap or overhang taken as drawing slack.
TOLERANCE = 0.005
#: A piece this close to a window's wall (metres) stands in front of the window.
WINDOW_DEPTH = 0.35
#: How a problem names the floor kept free on each side of a piece.
SIDE_WORDS = {
    "front": "in front of",
    "back": "behind",
    "left": "to the left of",
    "right": "to the right of",
}
#: A piece at most this tall (metres, the catalog's height) is flat: it may lie under others.
FLAT_HEIGHT = 0.02


def plan_problems(plan) -> list[tuple[str, str]]:
    """Every problem of ``plan`` (a ``plan.Plan``), in furniture order; empty when it is sound."""
    from scenewright.completion.activity import SEATS
    from scenewright.generator import indoor_catalog

    catalog = indoor_catalog()
    index = {piece.id: k for k, piece in enumerate(plan.furniture)}
    room = plan.room
    problems: list[tuple[str, str]] = []
    floor = [piece for piece in plan.furniture if piece.on is None and not is_flat(piece, catalog)]
    for k, piece in enumerate(plan.furniture):
        where = f"$.furniture[{k}]"
        excess = room.footprint_excess(piece.corners)
        if excess > TOLERANCE:
            problems.append((where, f"{piece.id} crosses the walls by {excess:.2f} m"))
        if piece.on is not None:
            support = plan.piece(piece.on)
            overhang = _overhang(piece.corners, support)
            if overhang > TOLERANCE:
                problems.append(
                    (
                        where,
                        f"{piece.id} overhangs {support.id}, which it stands on, by {overhang:.2f} m",
                    )
                )
    for k, first in enumerate(floor):
        for second in floor[k + 1 :]:
            depth = overlap_depth(first.corners, second.corners)
            if depth > TOLERANCE:
                problems.append(
                    (
                        f"$.furniture[{index[second.id]}]",
                        f"{second.id} overlaps {first.id} by {depth:.2f} m",
                    )
                )
    for door in room.doors:
        swing = room.swing_zone(door)
        for piece in floor:
            if overlap_depth(swing, piece.corners) > TOLERANCE:
                problems.append(
                    (f"$.furniture[{index[piece.id]}]", f"{piece.id} stands in {door.id}'s swing")
                )
    for piece in floor:
        where = f"$.furniture[{index[piece.id]}]"
        for side, depth in catalog[piece.category].clearance:
            zone, named = (
                clearance_zone(piece, side, depth),
                f"the {depth:g} m clearance {SIDE_WORDS[side]} {piece.id}",
            )
            if room.footprint_excess(zone) > TOLERANCE:
                problems.append((where, f"{named} runs into a wall"))
            for other in floor:
                if (
                    other.id != piece.id
                    and other.category not in SEATS
                    and overlap_depth(zone, other.corners) > TOLERANCE
                ):
                    problems.append((where, f"{other.id} stands in {named}"))
    problems += _free_area_problems(plan, floor, catalog)
    for window in room.windows:
        wall = room.part(window.wall)
        u0, u1 = window.span
        glass = [
            wall.to_world(u0, 0.0),
            wall.to_world(u1, 0.0),
            wall.to_world(u1, WINDOW_DEPTH),
            wall.to_world(u0, WINDOW_DEPTH),
        ]
        for piece in floor:
            tall = catalog[piece.category].size[1] > window.sill + TOLERANCE
            if tall and overlap_depth(glass, piece.corners) > TOLERANCE:
                problems.append(
                    (
                        f"$.furniture[{index[piece.id]}]",
                        f"{piece.id} stands in front of {window.id}",
                    )
                )
    return problems


def _free_area_problems(plan, floor, catalog) -> list[tuple[str, str]]:
    """A free area must be free: on the floor, clear of the furniture (rugs aside), of
    the doors' swings and of every clearance (it is where something more could stand
    without getting in the way)."""
    zones = [(f"{door.id}'s swing", plan.room.swing_zone(door)) for door in plan.room.doors]
    for piece in floor:
        for side, depth in catalog[piece.category].clearance:
            zones.append(
                (f"the clearance {SIDE_WORDS[side]} {piece.id}", clearance_zone(piece, side, depth))
            )
    zones += [(piece.id, piece.corners) for piece in floor]
    problems = []
    for k, area in enumerate(plan.free_areas):
        (x, z), (w, d) = area.center, area.size
        corners = [
            (x - w / 2, z - d / 2),
            (x + w / 2, z - d / 2),
            (x + w / 2, z + d / 2),
            (x - w / 2, z + d / 2),
        ]
        if plan.room.footprint_excess(corners) > TOLERANCE:
            problems.append((f"$.free_areas[{k}]", "the free area crosses the walls"))
        for name, zone in zones:
            if overlap_depth(corners, zone) > TOLERANCE:
                problems.append(
                    (f"$.free_areas[{k}]", f"the free area is not free: {name} is in it")
                )
    return problems


def unreachable(plan, catalog) -> list:
    """The floor pieces of ``plan`` someone uses (their catalog entry names access sides)
    that no 0.6 m wide way from a door reaches, in furniture order (module docstring);
    none in a room without a door."""
    from scenewright.completion.activity import SEATS
    from scenewright.generator.layout.reachability import CORRIDOR_HALF, access_grid
    from scenewright.generator.layout.room_terms import FLAT_HEIGHT as WALKED_OVER

    grid = access_grid(plan.room)
    if not grid.has_doors:
        return []
    ground = [piece for piece in plan.furniture if piece.on is None]
    rects = {p.id: make_rect(p.center[0], p.center[1], p.size[0], p.size[1], p.yaw) for p in ground}
    taken = 0
    for piece in ground:
        if catalog[piece.category].size[1] > WALKED_OVER:
            taken |= grid.obstacle(rects[piece.id]).bits
    way = grid.label(grid.static & ~taken)
    used = [piece for piece in ground if catalog[piece.category].access]
    reached = {
        p.id: bool(way & grid.access(rects[p.id], catalog[p.category].access).bits) for p in used
    }
    reach = CORRIDOR_HALF + grid.cell  # how near the way must come to a side used (the layout's)
    seats = [p for p in used if p.category in SEATS and reached[p.id]]
    return [
        piece
        for piece in used
        if not reached[piece.id]
        and not any(
            seat.id != piece.id and rect_distance(rects[seat.id], rects[piece.id]) <= reach
            for seat in seats
        )
    ]


def is_flat(piece, catalog) -> bool:
    """Whether the piece lies flat on the floor (a rug): other pieces may stand on it."""
    return catalog[piece.category].size[1] <= FLAT_HEIGHT


def front_zone(piece, depth: float) -> list[tuple[float, float]]:
    """Corners (x, z) of the floor ``depth`` metres deep in front of ``piece``, as wide as it."""
    return clearance_zone(piece, "front", depth)


def clearance_zone(piece, side: str, depth: float) -> list[tuple[float, float]]:
    """Corners (x, z) of the floor ``depth`` metres deep beside ``piece`` on its own
    ``side`` (``front``, ``back``, ``left``: local +X, ``right``), as long as that side."""
    half_w, half_d = piece.size[0] / 2.0, piece.size[1] / 2.0
    ux, uz = {"front": (0.0, 1.0), "back": (0.0, -1.0), "left": (1.0, 0.0), "right": (-1.0, 0.0)}[
        side
    ]
    # The side's own half length (along it) and its distance from the centre (out of it).
    along, out = (half_w, half_d) if uz else (half_d, half_w)
    local = [
        (ux * (out + k) + uz * a, uz * (out + k) + ux * a)
        for k, a in ((0.0, -along), (0.0, along), (depth, along), (depth, -along))
    ]
    return [to_world(piece.center[0], piece.center[1], piece.yaw, lx, lz) for lx, lz in local]


def overlap_depth(first: list[tuple[float, float]], second: list[tuple[float, float]]) -> float:
    """How deep two convex polygons (corners in order) overlap: the least overlap of
    their projections over every edge normal of both (separating axis test); 0 apart."""
    depth = math.inf
    for polygon in (first, second):
        n = len(polygon)
        for k in range(n):
            normal = left_normal(*polygon[k], *polygon[(k + 1) % n])
            if normal is None:
                continue
            ax, az = normal
            a = [x * ax + z * az for x, z in first]
            b = [x * ax + z * az for x, z in second]
            overlap = min(max(a), max(b)) - max(min(a), min(b))
            if overlap <= 0.0:
                return 0.0
            depth = min(depth, overlap)
    return 0.0 if depth == math.inf else depth


def _overhang(corners: list[tuple[float, float]], support) -> float:
    """How far (metres) the corners reach beyond ``support``'s footprint."""
    worst = 0.0
    for x, z in corners:
        lx, lz = to_local(support.center[0], support.center[1], support.yaw, x, z)
        worst = max(worst, abs(lx) - support.size[0] / 2.0, abs(lz) - support.size[1] / 2.0)
    return worst
