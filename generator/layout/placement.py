"""Placement: new poses for an item at which its relations hold.

``Placer`` holds what placing needs to know of one problem (which boxes and groups may
be placed, which are tied together, which stand against a wall) and places an item by
one relation (``place_for_relation``: the relation's family entry, ``families``, says
how), by all of its placing relations at once (``place_for_all``), or pulls a road to a
pinned item (``pull``). The constructive initial placement (``initial``) and the
sampler's data-driven moves (``moves.Mover``, a ``Placer``) both draw their
candidates here, so a start and a move put an item the same ways.

Pinned boxes and paths (``pinning.Pins``) are left out up front: no placement places
or turns a pinned box, nor a whole group holding a pinned box or one resting on it. A
NextTo* from a pinned box (or a group holding one) to a free path or junction cannot
be mended by moving the box, so ``pull`` brings the road to it instead: the path's
nearest movable control point, or the junction with the starts of its paths.
"""

from __future__ import annotations

import math
from collections.abc import Iterable

import numpy as np

from scenewright.core.geometry import nearest_on_polyline

from .families import LAYOUT_FAMILIES, evaluate, placing, satisfied
from .families.next_to import GAP_RANGE
from .motion import carried_by, draw_index, end_reach, reach, rigid, uniform, wrap
from .params import LayoutParams
from .pinning import Pins
from .problem import FLAT_HEIGHT, Problem
from .reachability import CORRIDOR_HALF, access_grid
from .relation_terms import HEADING_FACINGS, centre
from .state import State
from .terms import Endpoint, RelationTerm

#: Tries of a data-driven move for an item with several placing relations.
MULTI_TRIES = 8

#: Share of placements by another relation of an A that also has a relation a family
#: snaps onto (against a wall, lined up with a box) that are then snapped onto it.
SNAP_SHARE = 0.5


class Placer:
    """Places items of one problem; holds the precomputed choices."""

    def __init__(
        self,
        problem: Problem,
        state: State,
        rng: np.random.Generator,
        params: LayoutParams,
        pins: Pins | None = None,
        rigid_groups: Iterable[int] = (),
    ):
        self.problem, self.state, self.rng, self.params = problem, state, rng, params
        self.pins = pins = pins or Pins.none(problem)
        self._placing: dict[tuple[str, int], list[RelationTerm]] = {}
        # Boxes of ``rigid_groups`` move only with their whole group (a group laid out in its
        # own frame first, ``decompose``): no move places or turns one of them alone.
        self.held_in_group = held_in_group = {
            box for group in rigid_groups for box in problem.group_members[group]
        }
        # Whether a move may place this box by itself: a free (unpinned) non-junction object.
        self.movable_box = [
            not problem.is_junction[b] and not pins.box[b] and b not in held_in_group
            for b in range(problem.n_boxes)
        ]
        carried = [
            carried_by(problem, problem.group_members[g]) for g in range(len(problem.group_ids))
        ]
        # A group moves as a whole only when nothing in it is pinned or rests on a pinned box;
        # random rigid moves carry its free boxes only.
        self.group_whole = [not any(pins.fixed(b) for b in boxes) for boxes in carried]
        self.group_boxes = [[b for b in boxes if not pins.fixed(b)] for boxes in carried]
        self.top_group_of = {box: g for g in problem.top_groups for box in problem.group_members[g]}
        # NextTo* from something pins hold to a free path or junction: pulled (``pull``).
        self.pullable = {
            t
            for t, term in enumerate(problem.relations)
            if term.placeable
            and LAYOUT_FAMILIES[term.spec.family].pulls_roads
            and self._held(term.a)
            and self._pulls(term.b)
        }
        self.clusters = [
            c for c in ([b for b in boxes if not pins.fixed(b)] for boxes in clusters(problem)) if c
        ]
        self.cluster_of = {box: cluster for cluster in self.clusters for box in cluster}
        # Per box, the boxes its relation partners are, and those placed by a relation to it
        # (``kept_free``).
        self.partners: list[set[int]] = [set() for _ in range(problem.n_boxes)]
        self.followers: list[set[int]] = [set() for _ in range(problem.n_boxes)]
        for term in problem.relations:
            for first in term.a.members:
                for second in term.b.members:
                    self.partners[first].add(second)
                    self.partners[second].add(first)
            if term.a.kind == "object" and term.b.kind == "object":
                self.followers[term.b.index].add(term.a.index)
        # Boxes that take floor a person walks on, and the width of a way to a box's side
        # (``kept_free``): in a room with a door only, where reachability is scored.
        grid = access_grid(problem.room) if problem.room is not None else None
        scored = grid is not None and grid.has_doors
        self.blocks_way = [
            scored
            and problem.support[b] < 0
            and not problem.is_junction[b]
            and problem.height[b] > FLAT_HEIGHT
            for b in range(problem.n_boxes)
        ]
        #: Two half corridors and a cell of the grid, so the way survives its rounding.
        self.way_width = 2.0 * CORRIDOR_HALF + grid.cell if grid is not None else 0.0
        # Free boxes with a wall relation (rooms only): their jitter may slide along the wall,
        # and they are lined up with others only by standing against the wall.
        self.wall_terms: dict[int, list[RelationTerm]] = {}
        for term in problem.relations:
            if (
                LAYOUT_FAMILIES[term.spec.family].stands_against_wall
                and self.movable_box[term.a.index]
                and problem.support[term.a.index] < 0
            ):
                self.wall_terms.setdefault(term.a.index, []).append(term)

    def forget_placing(self) -> None:
        """Drop what ``_placing_terms`` kept, after ``Problem.retarget`` changed relations."""
        self._placing.clear()

    def _movable(self, end: Endpoint) -> bool:
        """Whether a move may place this end: a free non-junction object, or a group with
        members none of which is pinned or rests on a pinned box."""
        if end.kind == "object":
            return self.movable_box[end.index]
        return end.kind == "group" and bool(end.members) and self.group_whole[end.index]

    def _held(self, end: Endpoint) -> bool:
        """Whether pins keep this end from being placed: a pinned object, or a group holding
        a pinned box (or one resting on a pinned box)."""
        if end.kind == "object":
            return self.pins.box[end.index]
        return end.kind == "group" and bool(end.members) and not self.group_whole[end.index]

    def _pulls(self, end: Endpoint) -> bool:
        """Whether ``pull`` may move this end: a free path or a free junction (not a
        grid's: it stays straight and square)."""
        if end.kind == "path":
            return not self.pins.path[end.index] and not self.problem.path_grid[end.index]
        return (
            end.kind == "object"
            and self.problem.is_junction[end.index]
            and not self.pins.box[end.index]
            and not self.problem.grid[end.index]
        )

    def _placing_terms(self, end: Endpoint) -> list[RelationTerm]:
        """A's relations that say where it goes (NextTo*, OnTopOf*), not only how it turns."""
        key = (end.kind, end.index)
        if key not in self._placing:
            self._placing[key] = [
                t
                for t in self.problem.outgoing.get(key, [])
                if LAYOUT_FAMILIES[t.spec.family].places
            ]
        return self._placing[key]

    def place_for_all(self, end: Endpoint) -> dict | None:
        """For an A with several placing relations: the best of a few data-driven poses.

        Each try places A by one of its relations drawn at random (``place_by``; of
        those that place alone only when no other places it: ``families.placing``); the
        tries are ranked by the energy of all of A's placing relations together, so a
        smithy that must be both beside a tower and next to a road lands where both
        hold, when any try found it.
        """
        state = self.state
        terms = self._placing_terms(end)
        drawn = placing(terms)
        best, best_energy = None, math.inf
        for _ in range(MULTI_TRIES):
            proposal = self.place_by(drawn[draw_index(self.rng, len(drawn))])
            if not proposal:
                continue
            with state.trying(proposal):
                energy = sum(evaluate(term, state, self.params).energy for term in terms)
            if energy < best_energy:
                best, best_energy = proposal, energy
        return best

    def place_by(self, term: RelationTerm) -> dict | None:
        """A placed by ``term``; then, when A also has a relation of a family that snaps
        (``LayoutFamily.snap``: against a wall, lined up with a box) and ``term`` is of
        another family, half the time pushed onto the nearest pose one of those relations
        allows from where ``term`` put it. The first such family (in the table's order)
        that A has relations of decides: against the wall, left of the bed lands where
        both hold; a desk put left of its neighbour lands in line with it too."""
        proposal = self.place_for_relation(term)
        if not proposal or term.a.kind != "object":
            return proposal
        for name, family in LAYOUT_FAMILIES.items():
            if family.snap is None:
                continue
            snapping = [t for t in self._placing_terms(term.a) if t.spec.family == name]
            if not snapping:
                continue
            if term.spec.family != name and self.rng.random() < SNAP_SHARE:
                onto = snapping[draw_index(self.rng, len(snapping))]
                with self.state.trying(proposal):
                    snapped = family.snap(self, onto)
                if snapped:
                    proposal = {**proposal, **snapped}
            return proposal
        return proposal

    def place_for_relation(self, term: RelationTerm, *, keep_heading: bool = False) -> dict | None:
        """New poses for A (and all it carries) at which ``term`` holds, or None, as its
        family places it.

        ``keep_heading``: a NextTo* placement only shifts A (never turns it to face a road).
        """
        return LAYOUT_FAMILIES[term.spec.family].place(self, term, keep_heading)

    def holds(self, term: RelationTerm) -> bool:
        """Whether a relation holds at the current state."""
        return satisfied(term, evaluate(term, self.state, self.params), self.params)

    def moving_boxes(self, end: Endpoint) -> list[int]:
        if end.kind == "group":
            return self.group_boxes[end.index]
        return self.problem.carried(end.index)

    def heading(self, end: Endpoint) -> float:
        """Yaw of an object, or of a group's first member (the group's front)."""
        box = end.index if end.kind == "object" else end.members[0]
        return self.state.yaw[box]

    def wanted_direction(self, term: RelationTerm, c: float, s: float) -> tuple[float, float]:
        """A unit direction from B to A in which ``term`` holds (drawn where it is open);
        ``c``, ``s``: B's yaw's cosine and sine."""
        wanted = list(term.spec.direction_vectors(c, s).values())
        if len(wanted) == 1:
            return wanted[0]
        if wanted:
            return wanted[draw_index(self.rng, len(wanted))]
        angle = uniform(self.rng, -math.pi, math.pi)
        return math.sin(angle), math.cos(angle)

    def pose_box(self, box: int, x: float, z: float, yaw: float) -> dict:
        """The box at exactly (x, z, yaw) (flush means flush, not flush up to rounding),
        with what rests on it carried along rigidly."""
        state = self.state
        turn = wrap(yaw - state.yaw[box])
        moved = rigid(
            state,
            self.problem.carried(box),
            (state.x[box], state.z[box]),
            turn,
            (x - state.x[box], z - state.z[box]),
        )
        moved[box] = (x, z, yaw)
        return moved

    def pull(self, term: RelationTerm) -> tuple[dict, dict] | None:
        """Bring B (a free path or junction) next to A (held by pins): the path's control
        point nearest A goes to a small gap beside A, or the junction is shifted there."""
        problem, state, rng = self.problem, self.state, self.rng
        ax, az = centre(term.a, state)
        gap = uniform(rng, *GAP_RANGE)
        if term.b.kind == "path":
            path = term.b.index
            points = state.points[path]
            _, nx, nz, segment = nearest_on_polyline(points, ax, az)
            dx, dz = self._away(nx - ax, nz - az)
            distance = (
                end_reach(problem, state, term.a, dx, dz) + problem.path_width[path] / 2.0 + gap
            )
            tx, tz = ax + dx * distance, az + dz * distance
            first = 1 if problem.path_start[path] >= 0 or problem.path_parent[path] >= 0 else 0
            candidates = [k for k in (segment, segment + 1) if k >= first]
            k = min(candidates, key=lambda k: math.hypot(points[k][0] - tx, points[k][1] - tz))
            new = [list(p) for p in points]
            new[k] = [tx, tz]
            return {}, {path: new}
        junction = term.b.index
        jx, jz = state.x[junction], state.z[junction]
        dx, dz = self._away(jx - ax, jz - az)
        distance = (
            end_reach(problem, state, term.a, dx, dz)
            + reach(problem, state, junction, -dx, -dz)
            + gap
        )
        return self._shift_junction(junction, ax + dx * distance - jx, az + dz * distance - jz)

    def _away(self, dx: float, dz: float) -> tuple[float, float]:
        """(dx, dz) as a unit vector; a random one when it is (almost) zero."""
        length = math.hypot(dx, dz)
        if length < 1e-9:
            angle = uniform(self.rng, -math.pi, math.pi)
            return math.sin(angle), math.cos(angle)
        return dx / length, dz / length

    def _shift_junction(self, junction: int, dx: float, dz: float) -> tuple[dict, dict]:
        """The junction shifted by (dx, dz), with the first point of every path leaving it."""
        problem, state = self.problem, self.state
        boxes = {junction: (state.x[junction] + dx, state.z[junction] + dz, state.yaw[junction])}
        paths = {}
        for path in problem.paths_of_junction.get(junction, []):
            new = [list(p) for p in state.points[path]]
            new[0] = [new[0][0] + dx, new[0][1] + dz]
            paths[path] = new
        return boxes, paths


def clusters(problem: Problem) -> list[list[int]]:
    """Sets of top-level items (with all their boxes) that relations tie together.

    Items are top-level groups and boxes outside groups (a stacked box belongs to what
    it rests on); two items are tied when a relation joins anything in them, except, in
    a room, a facing relation that asks only for a heading (same, opposite or square to
    B's): every desk facing the board would otherwise tie the whole room into one
    cluster, board and all, and a cluster move would take the board off its wall. Paths and
    junctions tie nothing. Only sets of two or more items are returned, in a fixed order.
    """
    unit_of: dict[int, int] = {}
    for group in problem.top_groups:
        for box in problem.group_members[group]:
            unit_of[box] = -1 - group
    for box in range(problem.n_boxes):
        if box not in unit_of and not problem.is_junction[box]:
            beneath = problem.beneath(box)
            root = beneath[-1] if beneath else box
            unit_of[box] = unit_of.get(root, root)
    parent: dict[int, int] = {unit: unit for unit in unit_of.values()}

    def find(unit: int) -> int:
        while parent[unit] != unit:
            parent[unit] = parent[parent[unit]]
            unit = parent[unit]
        return unit

    for term in problem.relations:
        if problem.room is not None and term.spec.facing in HEADING_FACINGS:
            continue  # a shared shift keeps it: it ties no cluster (else all desks facing a board are one)
        ends = [unit_of[box] for box in term.a.members[:1] + term.b.members[:1] if box in unit_of]
        if len(ends) == 2 and find(ends[0]) != find(ends[1]):
            parent[find(ends[0])] = find(ends[1])
    members: dict[int, list[int]] = {}
    units: dict[int, set[int]] = {}
    for box in sorted(unit_of):
        root = find(unit_of[box])
        members.setdefault(root, []).append(box)
        units.setdefault(root, set()).add(unit_of[box])
    return [carried_by(problem, boxes) for root, boxes in members.items() if len(units[root]) > 1]
