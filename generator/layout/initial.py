"""The constructive initial placement the sampler starts from.

Paths first (``initial_roads``: roads leave their junction at evenly spread headings,
free roads cross the scene), then the top-level items (groups and free objects) one at a time, each
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
pulled towards those things (``Placer.pull``). The rest is placed around them as above.
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
from .families import LAYOUT_FAMILIES, evaluate, placing
from .initial_roads import lay_paths, lengthen
from .lots import LOT_SPACING, LotItem, LotPlan, frontage_items, plan_lots
from .motion import draw_index, rigid, uniform, wrap
from .motion import reach as footprint_reach
from .pinning import Pins
from .placement import Placer
from .pose_templates import not_templated, template_draw
from .relation_terms import centre
from .terms import ROOM_ENDS, Endpoint, RelationTerm

#: Tries for a random spot on the floor of a room that is not a rectangle.
FLOOR_TRIES = 20
#: How much further (metres) than it crosses a wall a group is pushed off it
#: (``_push_off_walls``).
PUSH_MARGIN = 0.05


def place_initial(
    energy: Energy,
    mover: Placer,
    rng: np.random.Generator,
    pins: Pins | None = None,
    frames: Mapping[int, Mapping[int, tuple[float, float, float]]] | None = None,
    lots: bool = False,
) -> LotPlan | None:
    """Lay out paths, junctions and all boxes; leaves every box active in ``energy``.

    Pinned and started boxes go first, at their poses; then paths (pinned and started
    ones at their points), then everything else around them. A group in ``frames``
    (group -> {box: (x, z, yaw)} about the group's centre, its own layout) keeps its
    members' poses relative to each other and is placed as one rigid footprint.

    With ``lots`` (a large outdoor scene, ``decompose``) the roads of several junctions
    are spread to avoid each other and the items that stand beside a road are given
    lots along it first (``lots.plan_lots``); the plan is returned (else None). An item
    the plan gives another road (its road drawn by ``some road``) has its relations to
    the road pointed at that one (``Problem.retarget``: ``energy.problem`` must be the
    chain's own, ``Problem.with_own_relations``).
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
    items = frontage_items(energy, frames) if lots else []
    need: dict[int, float] | None = None
    if lots:
        need = {}
        for item in items:
            need[item.path] = need.get(item.path, 0.0) + item.width + LOT_SPACING
    lay_paths(energy, rng, pins, held, fit=need)
    for term in sorted(mover.pullable):  # roads and junctions pinned things must be next to
        _best_of(
            energy,
            lambda term=term: mover.pull(problem.relations[term]),
            energy.params.path_candidates,
            held,
        )
    plan = None
    if lots:
        plan = plan_lots(energy, items)
        if plan.left:  # short of frontage: longer roads, where there is room
            plan = _with_longer_roads(energy, items, plan)
        for item in plan.moved:  # given another road of its type (``lots``): it is its own
            for term in item.terms:
                problem.retarget(term, item.path)
            mover.forget_placing()
        for poses in plan.poses.values():
            for box, (x, z, yaw) in poses.items():
                energy.state.set_pose(box, x, z, yaw)
            energy.activate(sorted(poses))
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
    return plan


def _with_longer_roads(energy: Energy, items: list[LotItem], plan: LotPlan) -> LotPlan:
    """The lots again after the roads that items found no room beside (theirs, or every
    road of the type ``some road`` may give them) are made longer where there is room
    (``initial_roads.lengthen``); kept if fewer items are left without a lot, else the
    roads are put back and ``plan`` stands."""
    short = sorted({path for item in plan.left for path in (item.roads or (item.path,))})
    before = lengthen(energy, short)
    if not before:
        return plan
    drawn = {id(item): item.path for item in items}
    for item in plan.moved:  # the plan's moves are undone: each item starts on its own road
        item.path = energy.problem.relations[item.terms[0]].b.index
    again = plan_lots(energy, items)
    if len(again.left) < len(plan.left):
        return again
    for item in items:
        item.path = drawn[id(item)]
    for path, points in before.items():
        energy.propose({}, {path: points})
        energy.accept()
    return plan


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
        ranks = [
            rank(t)
            for t in _outgoing(energy, kind, index)
            if (rank := LAYOUT_FAMILIES[t.spec.family].placing_rank) is not None
        ]
        if kind == "object" and ranks:
            spots = max(ranks)
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
            if (
                term is not incoming
                and LAYOUT_FAMILIES[term.spec.family].anchors_target
                and _placed(energy, term.b)
            ):
                return replace(term, a=end, label="NextTo", spec=RELATIONS["NextTo"], sight=())
    return None


def _held_terms(energy: Energy, mover: Placer, pins: Pins):
    """A score of how far roads and junctions are from the pinned things that must be next
    to them (None when there are none): the NextTo* terms ``Placer.pull`` mends, measured
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
    mover: Placer,
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
    positional = placing(outgoing)
    turning = [t for t in outgoing if not LAYOUT_FAMILIES[t.spec.family].places]
    incoming = [
        t
        for t in problem.incoming.get(("object", box), [])
        if LAYOUT_FAMILIES[t.spec.family].anchors_target
        and t.a.kind != "path"
        and _placed(energy, t.a)
    ]
    placed_mates = [m for m in mates if energy.active[m] and problem.support[m] == -1]

    def draw():
        if support:
            return mover.place_for_relation(support[0]), {}
        if positional or incoming:
            pick = draw_index(rng, len(positional) + len(incoming))
            if pick < len(positional):
                return mover.place_by(positional[pick]), {}
            target_term = incoming[pick - len(positional)]
            place_target = LAYOUT_FAMILIES[target_term.spec.family].place_target
            assert place_target is not None  # a family that anchors its target places it
            return place_target(mover, target_term), {}
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
        draw, turning = template, not_templated(energy, turning)
    # In a room, a heading its facing relations fix whatever the place (same, opposite or
    # square to B's) is taken before the place: NextTo* placements keep A's heading and
    # AlignedWith keeps its way round, so a desk placed left of a desk already facing the
    # board stays left of it once turned (turned after, about its own centre, it would
    # not). Outdoors it sped the village up but lengthened the town's tail (docs/layout.md).
    for term in turning:
        if problem.room is not None and _heading_only(term) and not support:
            turned = _turn(mover, term)
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
    for term in turning:
        if problem.room is not None and _turned(
            mover, term
        ):  # its heading came first and the place kept it
            continue
        _best_of(energy, lambda term=term: (_turn(mover, term), {}), 2)


def _turn(mover: Placer, term: RelationTerm, *, whole_group: bool = False) -> dict | None:
    """A (or the top-level group holding it) turned as a relation that only turns A asks
    (its family's ``turn`` or ``turn_group``)."""
    family = LAYOUT_FAMILIES[term.spec.family]
    turn = family.turn_group if whole_group else family.turn
    assert turn is not None  # a family that does not place A turns it
    return turn(mover, term)


def _heading_only(term: RelationTerm) -> bool:
    """Whether a turning relation fixes A's heading whatever its place."""
    heading_only = LAYOUT_FAMILIES[term.spec.family].heading_only
    return heading_only is not None and heading_only(term)


def _turned(mover: Placer, term: RelationTerm) -> bool:
    """Whether A already has the heading a turning relation asks for."""
    turned = LAYOUT_FAMILIES[term.spec.family].turned
    return turned is not None and turned(mover, term)


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
    energy: Energy,
    mover: Placer,
    rng: np.random.Generator,
    group: int,
    frame: Mapping | None = None,
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
        if not LAYOUT_FAMILIES[t.spec.family].places
        and not set(t.b.members) <= set(members)
        and _placed(energy, t.b)
    ]
    for term in outside_facing:
        if problem.room is not None and _turned(mover, term):
            continue
        _best_of(energy, lambda term=term: (_turn(mover, term, whole_group=True), {}), 1)
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


def _push_off_walls(energy: Energy, mover: Placer, group: int, anchors: list[RelationTerm]) -> None:
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
    candidates: Iterator[tuple[dict, dict]] = iter(
        [
            (rigid(energy.state, boxes, (0.0, 0.0), 0.0, (nx * shift, nz * shift)), {})
            for nx, nz in directions
        ]
    )
    _best_of(energy, lambda: next(candidates), len(directions))


def _group_anywhere(
    energy: Energy, mover: Placer, rng: np.random.Generator, whole: Endpoint, turn: bool
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
    mover: Placer,
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

    def draw() -> tuple[dict | None, dict]:
        if anchors:
            return mover.place_for_relation(anchors[draw_index(rng, len(anchors))]), {}
        half_x, half_z = problem.extent[0] / 2.0, problem.extent[1] / 2.0
        x, z = centre(whole, state)
        turn = wrap(math.pi / 2.0 * int(rng.integers(4)))
        shift = (uniform(rng, -half_x, half_x) - x, uniform(rng, -half_z, half_z) - z)
        return rigid(state, list(members), (x, z), turn, shift), {}

    first = draw()[0]
    assert first is not None  # the group's first pose, by an anchor or anywhere
    for box, pose in first.items():
        state.set_pose(box, *pose)
    energy.activate(list(members))
    if not anchors:  # else the group is placed by its anchors once more, as every group is
        _best_of(energy, draw, energy.params.initial_candidates)
