"""The constructive initial placement the sampler starts from.

Paths first (roads leave their junction at evenly spread headings, free roads cross
the scene), then the top-level items (groups and free objects) one at a time, each
after the items its relations point to and the most constrained first: a group's members are placed from their
relations to each other (the first member where the group's own relation wants the
group, e.g. beside its road), stacked things on their supports, unrelated members
beside a placed mate; then the group is placed as a whole once more. Every placement
draws ``initial_candidates`` poses from the sampler's data-driven moves and keeps the
one of lowest energy, so the start is already close to a valid layout. Items enter the
energy only as they are placed.

Pinned and warm-started boxes (``pinning.Pins``) enter first, at their given poses, and
count as placed; pinned and started paths get their given points. Then each new
junction with its roads (taking the evenly spread headings given roads leave free), and
each new free road, is the best of ``path_candidates`` random ones by the energy plus
how far pinned things that must be next to a road are from it, and such roads are
pulled towards those things (``Mover.pull``). The rest is placed around them as above.
A group holding any given box is not placed again as a whole (its given boxes stay
where they were put). Without pins or a start, nothing here draws a different number.

In a room, walls, doors and windows are fixed and count as placed, and furniture that
stands against a wall (a wall relation) goes first: what has few places to go (under or
beside a window, in a corner) before what may stand anywhere along a wall, each the
largest footprint first, so the room starts from a plausible state: the desk takes the
window and the bed a wall before the chair looks for a place in front of the desk. With line of sight, tall boxes not
yet placed wait outside the room (``_park``), so they block no view before they have a
place of their own.

In a room a box whose facing relation fixes its heading alone (same, opposite or square
to B's) takes that heading before its place is drawn, so what is placed beside it keeps
to its sides, and a group is put together on its own terms: each member's candidates are
judged by the relations among the members placed so far and their overlaps only
(``_best_among_mates``), not at the group's provisional spot, where a wall or another
group makes a row of desks fold into a block; a group nothing places is then put at the
best of ``initial_candidates`` spots on the floor (``_group_anywhere``). A group placed
by its relations to other groups that still crosses a wall is pushed off it together
with the groups it hangs on (``_push_off_walls``: a third row south of a first row put
in the middle of the room).
"""

from __future__ import annotations

import heapq
import itertools
import math
from collections.abc import Iterator, Mapping
from dataclasses import replace

import numpy as np

from scenewright.core.geometry import corners
from scenewright.core.relations import RELATIONS

from .energy import Energy
from .moves import Mover, draw_index, rigid, uniform, wrap
from .moves import reach as footprint_reach
from .pinning import Pins
from .problem import ROOM_ENDS, Endpoint, RelationTerm
from .relation_terms import HEADING_FACINGS, centre, evaluate
from .templates import not_templated, template_draw

#: Paths stay this far (metres) inside the extent when first laid out.
PATH_MARGIN = 1.0
#: New paths take this share of their maximum length (room permitting): long roads give
#: the items placed along them room, and the length term stays near 0 below the maximum.
PATH_LENGTH_SHARE = 0.95
#: Where free paths cross the scene: within this share of the extent from its centre.
LONE_PATH_SPREAD = 0.2
FREE_PATH_SPREAD = 0.4
#: Spread (radians) of the heading change at each control point of a new path.
PATH_WIGGLE = 0.15
#: Around pinned or started things, candidate junctions lie within this share of the
#: extent from its centre (without them: 0.15).
JUNCTION_SPREAD = 0.25
#: Several junctions lie within this share of the extent from its centre, each the
#: farthest from the others of this many candidate points.
JUNCTIONS_SPREAD = 0.3
SPREAD_CANDIDATES = 8
#: Tries for a random spot on the floor of a room that is not a rectangle.
FLOOR_TRIES = 20
#: How much further (metres) than it crosses a wall a group is pushed off it
#: (``_push_off_walls``).
PUSH_MARGIN = 0.05


def place_initial(
    energy: Energy,
    mover: Mover,
    rng: np.random.Generator,
    pins: Pins | None = None,
    frames: Mapping[int, Mapping[int, tuple[float, float, float]]] | None = None,
) -> None:
    """Lay out paths, junctions and all boxes; leaves every box active in ``energy``.

    Pinned and started boxes go first, at their poses; then paths (pinned and started
    ones at their points), then everything else around them. A group in ``frames``
    (group -> {box: (x, z, yaw)} about the group's centre, its own layout) keeps its
    members' poses relative to each other and is placed as one rigid footprint.
    """
    frames = frames or {}
    problem, state = energy.problem, energy.state
    pins = pins or Pins.none(problem)
    preset = pins.preset_boxes()
    if preset:
        for box in sorted(preset):
            pose = preset[box]
            state.set_pose(box, pose.x, pose.z, pose.yaw)
        energy.activate(sorted(preset))
    _park(energy)
    held = _held_terms(energy, mover, pins)
    _lay_paths(energy, rng, pins, held)
    for term in sorted(mover.pullable):  # roads and junctions pinned things must be next to
        _best_of(
            energy,
            lambda term=term: mover.pull(problem.relations[term]),
            energy.params.path_candidates,
            held,
        )
    for unit in _placing_order(energy):
        kind, index = unit
        if kind == "group":
            _place_group(energy, mover, rng, index, frames.get(index))
        elif not energy.active[index]:  # not pinned or started
            _place_box(
                energy,
                mover,
                rng,
                index,
                (),
                _borrowed_anchor(energy, Endpoint("object", index, (index,))),
            )
    for box in range(problem.n_boxes):  # stacked boxes outside any group, and the rest
        if not energy.active[box]:
            _place_box(energy, mover, rng, box, ())


def _placing_order(energy: Energy) -> Iterator[tuple[str, int]]:
    """The top-level items in the order they are placed: of those whose anchors (what
    their relations point to) are placed, furniture against the walls first
    (``_wall_order``), then the most constrained (``_priorities``), then the first
    created; when none is ready, the first created. Anchors once placed stay placed,
    so the ready items wait in a heap and only the others are looked at again."""
    problem = energy.problem
    priority = _priorities(energy)
    walls_first = _wall_order(energy)
    first: dict[tuple[str, int], tuple] = {}  # smallest goes first
    for position, unit in enumerate(problem.units):
        spots, area = walls_first.get(unit, (-1, 0.0))
        first[unit] = (-spots, -area, -priority[unit], position)
    waiting = list(problem.units)
    ready: list[tuple] = []
    while waiting or ready:
        still = []
        for unit in waiting:
            if _anchors_placed(energy, unit):
                heapq.heappush(ready, (first[unit], unit))
            else:
                still.append(unit)
        waiting = still
        if ready:
            yield heapq.heappop(ready)[1]
        else:
            yield waiting.pop(0)


def _priorities(energy: Energy) -> dict[tuple[str, int], int]:
    """How constrained each top-level item is: its count of relations to outside itself.

    An item that a more constrained one points at gets that one's count, so a tower a
    smithy must stand beside (and next to a road) is placed early, then the smithy, before
    the spot they need is taken by items that could go anywhere along the road.
    """
    problem = energy.problem
    unit_of: dict[tuple[str, int], tuple[str, int]] = {}
    own: dict[tuple[str, int], set[int]] = {}
    for unit in problem.units:
        members = _boxes_of(problem, unit)
        own[unit] = set(members)
        unit_of[unit] = unit
        for box in members:
            unit_of.setdefault(("object", box), unit)
    count = {unit: 0 for unit in problem.units}
    for term in problem.relations:
        source = unit_of.get((term.a.kind, term.a.index))
        if source is not None and (term.b.kind == "path" or not set(term.b.members) <= own[source]):
            count[source] += 1
    priority = dict(count)
    for term in problem.relations:
        source = unit_of.get((term.a.kind, term.a.index))
        target = unit_of.get((term.b.kind, term.b.index))
        if source is not None and target is not None and target != source:
            priority[target] = max(priority[target], count[source])
    return priority


def _wall_order(energy: Energy) -> dict[tuple[str, int], tuple[int, float]]:
    """For each free object with a wall relation, its rank: first those with few places
    to go (under or beside a window, in a corner), then those anywhere along a wall,
    each the largest footprint first; others are not listed (nothing outdoors)."""
    problem = energy.problem
    order = {}
    for unit in problem.units:
        kind, index = unit
        placements = [
            t.spec.wall for t in _outgoing(energy, kind, index) if t.spec.family == "wall"
        ]
        if kind == "object" and placements:
            spots = 1 if any(p != "against" for p in placements) else 0
            order[unit] = (spots, 4.0 * problem.half_width[index] * problem.half_depth[index])
    return order


def _park(energy: Energy) -> None:
    """In a room with line of sight: put the tall boxes that may block a view, and what
    rests on them, outside the room until they are placed (the state starts them all at
    the origin, in the middle of the room). Inactive boxes count for nothing else."""
    problem, state = energy.problem, energy.state
    if problem.room is None or not problem.line_of_sight:
        return
    tall = sorted(
        {box for term in problem.relations for box in term.sight if not energy.active[box]}
    )
    far = 10.0 * (max(problem.extent) + max(problem.size, default=1.0))  # well clear of the room
    for k, box in enumerate(tall):
        dx, dz = far + 2.0 * k * max(problem.size) - state.x[box], far - state.z[box]
        for item in problem.carried(box):
            if not energy.active[item]:
                state.set_pose(item, state.x[item] + dx, state.z[item] + dz, state.yaw[item])


def _outgoing(energy: Energy, end_kind: str, index: int) -> list[RelationTerm]:
    return energy.problem.outgoing.get((end_kind, index), [])


def _placed(energy: Energy, end: Endpoint) -> bool:
    """Whether an end has its place: a path (laid first), a room's part (fixed), or
    boxes all in the energy."""
    if end.kind == "path" or end.kind in ROOM_ENDS:
        return True
    return bool(end.members) and all(energy.active[b] for b in end.members)


def _boxes_of(problem, unit: tuple[str, int]) -> tuple[int, ...]:
    """The boxes of a top-level item: a group's members, or the object itself."""
    kind, index = unit
    return problem.group_members[index] if kind == "group" else (index,)


def _anchors_placed(energy: Energy, unit: tuple[str, int]) -> bool:
    """Whether everything the item's relations point to (outside itself) is placed."""
    own = set(_boxes_of(energy.problem, unit))
    return all(_placed(energy, t.b) or set(t.b.members) <= own for t in _outgoing(energy, *unit))


def _borrowed_anchor(energy: Energy, end: Endpoint) -> RelationTerm | None:
    """A place for an item nothing anchors: next to what anchors an item pointing at it.

    A tower with no relation of its own, that a blacksmith must be beside and that must
    itself be next to a road, is best put next to that road too.
    """
    problem = energy.problem
    for incoming in problem.incoming.get((end.kind, end.index), []):
        if incoming.a.kind == "path":
            continue
        for term in problem.outgoing[(incoming.a.kind, incoming.a.index)]:
            if term is not incoming and term.spec.family == "next_to" and _placed(energy, term.b):
                return replace(term, a=end, label="NextTo", spec=RELATIONS["NextTo"], sight=())
    return None


def _held_terms(energy: Energy, mover: Mover, pins: Pins):
    """A score of how far roads and junctions are from the pinned things that must be next
    to them (None when there are none): the NextTo* terms ``Mover.pull`` mends, measured
    from the pinned boxes of their source alone, since the rest of a group is not placed
    yet while roads are laid."""
    terms = []
    for index in sorted(mover.pullable):
        term = energy.problem.relations[index]
        kept = tuple(box for box in term.a.members if pins.box[box])
        if kept:
            terms.append(replace(term, a=Endpoint(term.a.kind, term.a.index, kept)))
    if not terms:
        return None
    state, params = energy.state, energy.params
    return lambda: sum(evaluate(term, state, params).energy for term in terms)


def _lay_paths(energy: Energy, rng: np.random.Generator, pins: Pins, held=None) -> None:
    if pins.preset:
        _lay_paths_around(energy, rng, pins, held)
        return
    problem, state = energy.problem, energy.state
    half_x, half_z = problem.extent[0] / 2.0, problem.extent[1] / 2.0
    junctions = [b for b in range(problem.n_boxes) if problem.is_junction[b]]
    if len(junctions) > 1:
        _spread_junctions(energy, rng, junctions)
    else:
        for junction in junctions:
            state.set_pose(
                junction,
                uniform(rng, -0.15, 0.15) * 2 * half_x,
                uniform(rng, -0.15, 0.15) * 2 * half_z,
                0.0,
            )
    energy.activate(junctions)
    for junction in junctions:
        paths = problem.paths_of_junction.get(junction, [])
        base = uniform(rng, 0.0, 2.0 * math.pi)
        for k, path in enumerate(paths):
            heading = base + 2.0 * math.pi * k / len(paths) + rng.normal(0.0, 0.1)
            start = (state.x[junction], state.z[junction])
            _set_path(energy, rng, path, start, heading, _room(start, heading, half_x, half_z))
    free = [path for path in range(problem.n_paths) if problem.path_start[path] < 0]
    # A lone road crosses near the middle; several spread out, each through the candidate
    # point farthest from the roads laid so far.
    spread = FREE_PATH_SPREAD if len(free) > 1 else LONE_PATH_SPREAD
    for path in free:
        heading = uniform(rng, 0.0, 2.0 * math.pi)
        laid = [
            p
            for other in range(problem.n_paths)
            if other not in free or other < path
            for p in state.points[other]
        ]
        candidates = [
            (uniform(rng, -spread, spread) * 2 * half_x, uniform(rng, -spread, spread) * 2 * half_z)
            for _ in range(8)
        ]
        middle = max(
            candidates,
            key=lambda c: min((math.hypot(c[0] - p[0], c[1] - p[1]) for p in laid), default=0.0),
        )
        back = _room(middle, heading + math.pi, half_x, half_z)
        ahead = _room(middle, heading, half_x, half_z)
        length = min(PATH_LENGTH_SHARE * problem.path_max_length[path], back + ahead)
        behind = min(back, length / 2.0)
        start = (middle[0] - math.cos(heading) * behind, middle[1] - math.sin(heading) * behind)
        _set_path(energy, rng, path, start, heading, length)


def _spread_junctions(energy: Energy, rng: np.random.Generator, junctions: list[int]) -> None:
    """Several junctions (road networks) spread over the scene: each at the candidate
    point (of ``SPREAD_CANDIDATES`` within ``JUNCTIONS_SPREAD`` of the extent from its
    centre) farthest from the junctions placed before it, so the networks' roads give
    the items beside them room instead of crossing each other in the middle."""
    state, (width, depth) = energy.state, energy.problem.extent
    placed: list[tuple[float, float]] = []
    for junction in junctions:
        candidates = [
            (
                uniform(rng, -JUNCTIONS_SPREAD, JUNCTIONS_SPREAD) * width,
                uniform(rng, -JUNCTIONS_SPREAD, JUNCTIONS_SPREAD) * depth,
            )
            for _ in range(SPREAD_CANDIDATES)
        ]
        x, z = max(
            candidates,
            key=lambda c: min((math.hypot(c[0] - p[0], c[1] - p[1]) for p in placed), default=0.0),
        )
        placed.append((x, z))
        state.set_pose(junction, x, z, 0.0)


def _free_headings(
    energy: Energy, pins: Pins, junction: int, paths: list[int], base: float
) -> list[float]:
    """Headings for the roads of a junction, by position in ``paths``: evenly spread from
    ``base``; when some roads are given, spread from the first given one's heading, each
    given road taking the free slot nearest its own heading and the others the rest in
    order."""
    count = len(paths)
    given = {path: pins.preset_points(path) for path in paths}
    given = {path: points for path, points in given.items() if points is not None}
    if not given:
        return [base + 2.0 * math.pi * k / count for k in range(count)]
    state = energy.state
    start = (state.x[junction], state.z[junction])

    def heading(points) -> float:
        return math.atan2(points[1][1] - start[1], points[1][0] - start[0])

    base = heading(next(iter(given.values())))
    slots = [base + 2.0 * math.pi * k / count for k in range(count)]
    for points in given.values():
        own = heading(points)
        nearest = min(range(len(slots)), key=lambda k: abs(wrap(slots[k] - own)))
        slots.pop(nearest)
    free_slots = iter(slots)
    return [0.0 if path in given else next(free_slots) for path in paths]


def _room(start: tuple[float, float], heading: float, half_x: float, half_z: float) -> float:
    """How far one can go from ``start`` along ``heading`` and stay PATH_MARGIN inside."""
    dx, dz = math.cos(heading), math.sin(heading)
    limits = []
    for position, direction, half in ((start[0], dx, half_x), (start[1], dz, half_z)):
        if abs(direction) > 1e-9:
            bound = (half - PATH_MARGIN) if direction > 0 else -(half - PATH_MARGIN)
            limits.append((bound - position) / direction)
    return max(min(limits), 0.0)


def _lay_paths_around(energy: Energy, rng: np.random.Generator, pins: Pins, held=None) -> None:
    """Paths when some boxes or paths are given (pinned or started): given paths at their
    points; each junction's other roads (and the junction, unless it is given) as the best
    of ``path_candidates`` fans, and each other free road as the best of as many
    crossings, by the energy (which already holds the given boxes) plus ``held`` (how far
    the pinned things that must be next to a road are from it): so new roads avoid
    pinned things and pass by those that must be next to them."""
    problem, state = energy.problem, energy.state
    half_x, half_z = problem.extent[0] / 2.0, problem.extent[1] / 2.0
    count = energy.params.path_candidates
    for junction in [b for b in range(problem.n_boxes) if problem.is_junction[b]]:
        paths = problem.paths_of_junction.get(junction, [])
        given = {
            path: pins.preset_points(path) for path in paths if pins.preset_points(path) is not None
        }
        placed = energy.active[junction]
        if not placed and given:  # where a given road starts
            first = next(iter(given.values()))[0]
            state.set_pose(junction, first[0], first[1], 0.0)
            placed = True
        if not energy.active[junction]:
            energy.activate([junction])
        for path, points in given.items():
            points = [list(p) for p in points]
            if not pins.path[path]:  # a started road begins at its junction
                points[0] = [state.x[junction], state.z[junction]]
            energy.propose({}, {path: points})
            energy.accept()
        if len(given) == len(paths) and placed:
            continue

        def fan(junction=junction, paths=paths, placed=placed) -> tuple[dict, dict]:
            if placed:
                x, z, boxes = state.x[junction], state.z[junction], {}
            else:
                x = uniform(rng, -JUNCTION_SPREAD, JUNCTION_SPREAD) * 2 * half_x
                z = uniform(rng, -JUNCTION_SPREAD, JUNCTION_SPREAD) * 2 * half_z
                boxes = {junction: (x, z, 0.0)}
            slots = _free_headings(energy, pins, junction, paths, uniform(rng, 0.0, 2.0 * math.pi))
            laid = {}
            for k, path in enumerate(paths):
                if pins.preset_points(path) is None:
                    heading = slots[k] + rng.normal(0.0, 0.1)
                    room = _room((x, z), heading, half_x, half_z)
                    laid[path] = _path_points(problem, rng, path, (x, z), heading, room)
            return boxes, laid

        _take_best(energy, fan, count, held)
    free = [path for path in range(problem.n_paths) if problem.path_start[path] < 0]
    for path in free:
        given = pins.preset_points(path)
        if given is not None:
            energy.propose({}, {path: [list(p) for p in given]})
            energy.accept()
    spread = FREE_PATH_SPREAD if len(free) > 1 else LONE_PATH_SPREAD
    for path in free:
        if pins.preset_points(path) is not None:
            continue

        def crossing(path=path) -> tuple[dict, dict]:
            heading = uniform(rng, 0.0, 2.0 * math.pi)
            middle = (
                uniform(rng, -spread, spread) * 2 * half_x,
                uniform(rng, -spread, spread) * 2 * half_z,
            )
            back = _room(middle, heading + math.pi, half_x, half_z)
            ahead = _room(middle, heading, half_x, half_z)
            length = min(PATH_LENGTH_SHARE * problem.path_max_length[path], back + ahead)
            behind = min(back, length / 2.0)
            start = (middle[0] - math.cos(heading) * behind, middle[1] - math.sin(heading) * behind)
            return {}, {path: _path_points(problem, rng, path, start, heading, length)}

        _take_best(energy, crossing, count, held)


def _take_best(energy: Energy, draw, count: int, extra=None) -> None:
    """Try ``count`` proposals from ``draw()`` and keep the one of lowest energy (plus
    ``extra()``, if given), even when it is worse than the state now (a placeholder)."""
    best, best_delta = None, math.inf
    for _ in range(count):
        proposal = draw()
        delta = energy.propose(*proposal)
        kept = energy.kept(delta)
        if extra is not None:
            delta += extra()
        energy.reject()
        if delta < best_delta:
            best, best_delta, best_kept = proposal, delta, kept
    if best is not None:
        energy.repropose(best, best_kept)
        energy.accept()


def _set_path(
    energy: Energy, rng: np.random.Generator, path: int, start, heading: float, room: float
) -> None:
    energy.propose({}, {path: _path_points(energy.problem, rng, path, start, heading, room)})
    energy.accept()


def _path_points(
    problem, rng: np.random.Generator, path: int, start, heading: float, room: float
) -> list[list[float]]:
    """Control points of a new path from ``start`` along ``heading`` (wiggling a little)."""
    half_x, half_z = problem.extent[0] / 2.0 - PATH_MARGIN, problem.extent[1] / 2.0 - PATH_MARGIN
    segments = problem.path_segments[path]
    step = min(PATH_LENGTH_SHARE * problem.path_max_length[path], room) / segments
    points = [[float(start[0]), float(start[1])]]
    for _ in range(segments):
        heading += float(np.clip(rng.normal(0.0, PATH_WIGGLE), -0.4, 0.4))
        x = points[-1][0] + math.cos(heading) * step
        z = points[-1][1] + math.sin(heading) * step
        points.append([min(max(x, -half_x), half_x), min(max(z, -half_z), half_z)])
    return points


def _best_of(energy: Energy, draw, count: int, extra=None) -> None:
    """Try ``count`` proposals from ``draw()`` and keep the one of lowest energy (plus
    ``extra()``, a score outside the energy, if given) if it lowers it."""
    best, best_delta = None, 0.0
    baseline = extra() if extra is not None else 0.0
    defer = extra is None and energy.room is not None and energy.params.incremental
    for _ in range(count):
        proposal = draw()
        if proposal is None or proposal[0] is None:
            continue
        delta = energy.propose(*proposal, defer_access=defer)
        if defer:
            # Its access part can lower it by at most all there is: one that cannot beat
            # the best so far even so is not worth reachability's cost.
            if best is not None and delta - energy.access_floor() >= best_delta:
                energy.reject()
                continue
            delta = energy.complete()
        kept = energy.kept(delta)
        if extra is not None:
            delta += extra() - baseline
        energy.reject()
        if best is None or delta < best_delta:
            best, best_delta, best_kept = proposal, delta, kept
    if best is not None and best_delta < 0.0:
        energy.repropose(best, best_kept)  # its update as computed when it was tried
        energy.accept()


def _place_box(
    energy: Energy,
    mover: Mover,
    rng: np.random.Generator,
    box: int,
    mates: tuple[int, ...],
    anchor_term: RelationTerm | None = None,
) -> None:
    """Place one box: on its support, by a relation with something placed, or near a mate.

    Facing relations only turn the box, so they are applied once it has a place.
    """
    problem, state = energy.problem, energy.state
    own = Endpoint("object", box, (box,))
    outgoing = [t for t in _outgoing(energy, "object", box) if _placed(energy, t.b)]
    support = [t for t in outgoing if t.b.kind == "object" and problem.support[box] == t.b.index]
    positional = [t for t in outgoing if t.spec.family != "facing"]
    walls = [t for t in positional if t.spec.family == "wall"]
    facing = [t for t in outgoing if t.spec.family == "facing"]
    incoming = [
        t
        for t in problem.incoming.get(("object", box), [])
        if t.spec.family == "next_to" and t.a.kind != "path" and _placed(energy, t.a)
    ]
    placed_mates = [m for m in mates if energy.active[m] and problem.support[m] == -1]

    def draw():
        if support:
            return mover.place_for_relation(support[0]), {}
        if positional or incoming:
            pick = draw_index(rng, len(positional) + len(incoming))
            if pick < len(positional):
                return mover.place_by(positional[pick], walls), {}
            return mover.place_target_for(incoming[pick - len(positional)]), {}
        if anchor_term is not None:
            return mover.place_for_relation(anchor_term), {}
        if placed_mates:
            mate = placed_mates[draw_index(rng, len(placed_mates))]
            near = RelationTerm(
                "", "", "NextTo", RELATIONS["NextTo"], own, Endpoint("object", mate, (mate,))
            )
            return mover.place_for_relation(near), {}
        return _anywhere(energy, rng, box), {}

    template = template_draw(energy, rng, box)
    if template is not None:  # a learned pair's source: its template gives place and turn
        draw, facing = template, not_templated(energy, facing)
    # In a room, a heading its facing relations fix whatever the place (same, opposite or
    # square to B's) is taken before the place: NextTo* placements keep A's heading and
    # AlignedWith keeps its way round, so a desk placed left of a desk already facing the
    # board stays left of it once turned (turned after, about its own centre, it would
    # not). Outdoors it sped the village up but lengthened the town's tail (docs/layout.md).
    for term in facing:
        if problem.room is not None and term.spec.facing in HEADING_FACINGS and not support:
            turned = mover.turn_to_face(term)
            for item, pose in (turned or {}).items():
                state.set_pose(item, *pose)
    first = draw()[0]
    for item, pose in first.items():
        state.set_pose(item, *pose)
    if (
        mates and energy.problem.room is not None
    ):  # judged among its mates: it enters once, at its best pose
        _best_among_mates(energy, draw, energy.params.initial_candidates, mates, box)
        energy.activate([box])
    else:
        energy.activate([box])
        _best_of(energy, draw, energy.params.initial_candidates)
    for term in facing:
        if problem.room is not None and mover.faces_as_asked(
            term
        ):  # its heading came first and the place kept it
            continue
        _best_of(energy, lambda term=term: (mover.turn_to_face(term), {}), 2)


def _best_among_mates(
    energy: Energy, draw, count: int, mates: tuple[int, ...], newcomer: int
) -> None:
    """``_best_of`` for a member of a group being put together, judged by the group
    alone: the relations among its placed members and their overlaps with each other.
    The member (``newcomer``) is not in the energy yet: the best pose is set in the
    state (the caller then brings it in, once, where the energy would have had it
    move), unless a candidate moves something already in the energy.

    The group is placed as a whole afterwards; judged by the whole energy, a member's
    candidates would be judged at the group's provisional spot, where a wall or another
    row of desks makes the wrong arrangement (a desk behind its neighbour instead of
    beside it) the cheapest.
    """
    problem, state = energy.problem, energy.state
    placed = [m for m in mates if energy.active[m] or m == newcomer]
    inside = set(placed)
    terms = [
        problem.relations[t]
        for t in sorted({t for m in placed for t in problem.terms_of_box[m]})
        if energy.placeable[t] and energy.term_boxes[t] <= inside
    ]
    ground = [m for m in placed if problem.support[m] < 0]

    def score() -> float:
        total = sum(evaluate(term, state, energy.params).energy for term in terms)
        for k, first in enumerate(ground):
            for second in ground[k + 1 :]:
                total += energy.pair_energy(first, second)
        return total

    best, best_score = None, score()
    for _ in range(count):
        proposal = draw()
        if proposal is None or proposal[0] is None:
            continue
        with state.trying(proposal[0]):
            value = score()
        if value < best_score:
            best, best_score = proposal, value
    if best is None:
        return
    if any(energy.active[item] for item in best[0]) or best[1]:
        energy.propose(*best)
        energy.accept()
    else:
        for item, pose in best[0].items():
            state.set_pose(item, *pose)


def _floor_spot(
    energy: Energy, rng: np.random.Generator, reach_x: float, reach_z: float
) -> tuple[float, float]:
    """A random (x, z) at least (reach_x, reach_z) inside the extent, and in a room that
    is not a rectangle on its floor when one of FLOOR_TRIES draws is."""
    problem = energy.problem
    half_x = max(problem.extent[0] / 2.0 - reach_x, 0.0)
    half_z = max(problem.extent[1] / 2.0 - reach_z, 0.0)
    x, z = uniform(rng, -half_x, half_x), uniform(rng, -half_z, half_z)
    room = problem.room
    if room is not None and len(room.walls) > 4:  # an L-shaped room's box has floor missing
        for _ in range(FLOOR_TRIES):
            if room.contains(x, z):
                break
            x, z = uniform(rng, -half_x, half_x), uniform(rng, -half_z, half_z)
    return x, z


def _anywhere(energy: Energy, rng: np.random.Generator, box: int) -> dict:
    problem, state = energy.problem, energy.state
    reach = problem.size[box] / 2.0
    yaw = wrap(math.pi / 2.0 * int(rng.integers(4)))
    x, z = _floor_spot(energy, rng, reach, reach)
    turn = wrap(yaw - state.yaw[box])
    return rigid(
        state,
        problem.carried(box),
        (state.x[box], state.z[box]),
        turn,
        (x - state.x[box], z - state.z[box]),
    )


def _place_group(
    energy: Energy, mover: Mover, rng: np.random.Generator, group: int, frame: Mapping | None = None
) -> None:
    problem = energy.problem
    members = problem.group_members[group]
    # Members already in (pinned or warm-started) stay where they are: the others are
    # placed around them, and the group is not moved as a whole.
    given = not mover.group_whole[group] or any(energy.active[box] for box in members)
    anchors = (
        [t for t in _outgoing(energy, "group", group) if _placed(energy, t.b)] if not given else []
    )
    if not anchors and not given:
        borrowed = _borrowed_anchor(energy, Endpoint("group", group, members))
        anchors = [borrowed] if borrowed else []
    if frame is not None and not given:
        _place_frame(energy, mover, rng, group, frame, anchors)
    order = sorted(members, key=lambda b: (len(problem.beneath(b)), b))  # supports first
    for position, box in enumerate(order):
        if energy.active[box]:
            continue
        anchor = (
            replace(anchors[0], a=Endpoint("object", box, (box,)))
            if anchors and position == 0
            else None
        )
        _place_box(energy, mover, rng, box, members, anchor)
    if given:
        return
    # Facing relations to things outside the group turn the group as a whole; the
    # group is then only shifted into place, so they keep holding.
    outside_facing = [
        t
        for box in members
        for t in _outgoing(energy, "object", box)
        if t.spec.family == "facing"
        and not set(t.b.members) <= set(members)
        and _placed(energy, t.b)
    ]
    for term in outside_facing:
        if problem.room is not None and mover.faces_as_asked(term):
            continue
        _best_of(energy, lambda term=term: (mover.turn_group_to_face(term), {}), 1)
    if anchors:  # the group as a whole, by each of its relations in turn
        in_turn = itertools.cycle(anchors)
        keep = bool(outside_facing)
        _best_of(
            energy,
            lambda: (mover.place_for_relation(next(in_turn), keep_heading=keep), {}),
            energy.params.initial_candidates * len(anchors),
        )
        _push_off_walls(energy, mover, group, anchors)
    elif problem.room is not None:  # nothing places it: the best spot on the floor
        whole = Endpoint("group", group, members)
        _best_of(
            energy,
            lambda: (_group_anywhere(energy, mover, rng, whole, turn=not outside_facing), {}),
            energy.params.initial_candidates,
        )


def _push_off_walls(energy: Energy, mover: Mover, group: int, anchors: list[RelationTerm]) -> None:
    """In a room, when a group placed by its relations to other groups still crosses a
    wall (the third row of desks south of a first row put in the middle of the room),
    shift it with the groups it hangs on (through their relations to groups, in turn)
    rigidly away from the wall it crosses, by as far as it crosses it: the best of one
    shift per wall crossed (along its inner normal) by the energy, kept only if it
    lowers it. The rows before had their spots chosen before the ones relying on them
    were placed."""
    room = energy.room
    if room is None:
        return
    problem = energy.problem
    excess = max(room.wall_excess(box) for box in problem.group_members[group])
    if excess <= 0.0:
        return
    chain, todo = [group], [t.b.index for t in anchors if t.b.kind == "group"]
    while todo:
        other = todo.pop()
        if other in chain or not mover.group_whole[other]:
            continue
        chain.append(other)
        todo.extend(
            t.b.index
            for t in _outgoing(energy, "group", other)
            if t.b.kind == "group" and _placed(energy, t.b)
        )
    boxes = sorted({box for member in chain for box in mover.group_boxes[member]})
    # Away from the walls it crosses: those whose line a corner of its footprints is beyond.
    points = [
        point for box in problem.group_members[group] for point in corners(energy.state.rects[box])
    ]
    lines = room.walls_geometry.lines
    directions = sorted(
        {(nx, nz) for nx, nz, offset in lines if any(nx * x + nz * z < offset for x, z in points)}
    )
    shift = excess + PUSH_MARGIN
    candidates = iter(
        [
            (rigid(energy.state, boxes, (0.0, 0.0), 0.0, (nx * shift, nz * shift)), {})
            for nx, nz in directions
        ]
    )
    _best_of(energy, lambda: next(candidates), len(directions))


def _group_anywhere(
    energy: Energy, mover: Mover, rng: np.random.Generator, whole: Endpoint, turn: bool
) -> dict:
    """A group shifted rigidly to a random spot where its footprint lies within the
    extent (a room: on the floor), turned by a random quarter turn when ``turn``."""
    problem, state = energy.problem, energy.state
    x, z = centre(whole, state)
    quarter = wrap(math.pi / 2.0 * int(rng.integers(4))) if turn else 0.0
    boxes = mover.moving_boxes(whole)
    turned = rigid(state, boxes, (x, z), quarter, (0.0, 0.0))
    with state.trying(turned):  # how far the turned footprint reaches from its centre
        reach_x = max(
            abs(state.x[b] - x) + footprint_reach(problem, state, b, 1.0, 0.0)
            for b in whole.members
        )
        reach_z = max(
            abs(state.z[b] - z) + footprint_reach(problem, state, b, 0.0, 1.0)
            for b in whole.members
        )
    nx, nz = _floor_spot(energy, rng, reach_x, reach_z)
    return rigid(state, boxes, (x, z), quarter, (nx - x, nz - z))


def _place_frame(
    energy: Energy,
    mover: Mover,
    rng: np.random.Generator,
    group: int,
    frame: Mapping,
    anchors: list[RelationTerm],
) -> None:
    """Bring a group laid out in its own frame in as one rigid footprint: its members at
    their frame poses, the whole put by one of its anchors (then by all of them in turn,
    as every group is), or, when nothing anchors it, the best of ``initial_candidates``
    spots anywhere in the extent, each turned by a quarter turn."""
    problem, state = energy.problem, energy.state
    members = problem.group_members[group]
    for box in members:
        state.set_pose(box, *frame[box])
    whole = Endpoint("group", group, members)

    def draw() -> tuple[dict, dict]:
        if anchors:
            return mover.place_for_relation(anchors[draw_index(rng, len(anchors))]), {}
        half_x, half_z = problem.extent[0] / 2.0, problem.extent[1] / 2.0
        x, z = centre(whole, state)
        turn = wrap(math.pi / 2.0 * int(rng.integers(4)))
        shift = (uniform(rng, -half_x, half_x) - x, uniform(rng, -half_z, half_z) - z)
        return rigid(state, list(members), (x, z), turn, shift), {}

    for box, pose in draw()[0].items():
        state.set_pose(box, *pose)
    energy.activate(list(members))
    if not anchors:  # else the group is placed by its anchors once more, as every group is
        _best_of(energy, draw, energy.params.initial_candidates)
