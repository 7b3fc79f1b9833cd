"""Proposals for the sampler: each returns new box poses and path points, or None.

A proposal is ``(boxes, paths)``: ``{box: (x, z, yaw)}`` and ``{path: points}``. Whatever
rests on a moved box moves with it rigidly, so supports carry their stacks. Move types:

- ``jitter``: shift one box (a stacked box slides over its support's top; a box
  standing against a wall as its wall relation wants half the time slides along it);
- ``rotate``: turn one box a little, or snap it to a multiple of 90 degrees;
- ``group``: move or turn a whole group rigidly; a group laid out in its own frame
  (``rigid_groups``) that is in trouble is drawn half the time, and then half the time
  put anew where its relations hold (``relocate_group``);
  in a room (``walls``) boxes and groups only turn by quarter turns (square to the
  room's longest wall), so furniture stays square to the walls unless a relation turns
  it (a chair facing a desk);
- ``cluster``: shift a set of items tied together by relations (a tower, the smithy
  beside it and the sign behind it; in a room facing relations that ask for a heading
  only tie nothing) as one, so they can leave a bad spot together (in
  a room, half the time along the wall the first of them against a wall stands at: a
  bed with its nightstands moves along its wall);
- ``relation`` (data-driven): pick a relation, favouring badly scored ones, and put its
  source where that relation holds (on the right side of B at a small gap, on B's top,
  beside a road at a random point along it, turned to face B, ...), or move its target
  instead (B shifted next to A, or turned so that A is on the side the label names); an
  A with several placing relations gets the best of a few tries under all of them;
  in rooms: A with its back flush to a wall (``_place_at_wall``: at a random spot along
  the wall, in a corner, under or beside a window; for the room as target, on a wall or
  window drawn by how much room it leaves), parallel to B with a face flush
  (AlignedWith, or B to A; for an A not held by a wall, half the time by the smallest
  correction where it stands, ``snap_aligned``, so a desk a few centimetres out of its
  row is pushed back into line instead of moved away), turned to B's opposite heading (FacingOpposite), next to
  a wall, window or the room at a small gap on the side named (into the room);
  beside an object that keeps free space on that side, A stands beyond that space when
  things placed by A may not stand in it (``kept_free``: the teacher's chair between
  the teacher's desk and the board), and a way's width off the only side B is used
  from when A, as wide as that side, would bar it (a pupil's chair behind a desk); a try by
  another relation of an A that must also stand against a wall is then pushed back
  onto the nearest fitting wall (``snap``), so "against the wall, left of the bed"
  lands where both hold; a wall move sometimes carries along rigidly what is in place
  by A (the bed goes to another wall with the nightstands beside it, the desk with its
  chair);
- ``path``: move one control point of a path, or bend the path's tail around a point;
- ``junction``: move a junction, with the start of every path leaving it.

After each check of the stop rule the sampler points the mover at what is still wrong
(``focus``): unsatisfied relations are drawn more often for data-driven moves, and
overlapping or outlying boxes for jitter.

Pinned boxes and paths (``pinning.Pins``) are left out up front, so no check is made
per proposal: jitter, rotate and junction moves draw from the free boxes only; group
and cluster moves carry only their free boxes (pinned boxes and what rests on them stay
behind); data-driven moves never place or turn a pinned box, nor a whole group holding
a pinned box or one resting on it; path moves draw from the free paths. A NextTo*
from a pinned box (or a group holding one) to a free path or junction cannot be
mended by moving the box, so a data-driven ``pull`` brings the road to it instead: the
path's nearest movable control point, or the junction with the starts of its paths.

The same ``place_for_relation`` makes the constructive initial placement's candidates.
"""

from __future__ import annotations

import math
from collections.abc import Iterable

import numpy as np

from scenewright.core.frames import to_local, to_world
from scenewright.core.geometry import nearest_on_polyline
from scenewright.core.room import Wall

from .params import LayoutParams
from .pinning import Pins
from .problem import ROOM_ENDS, Endpoint, Problem, RelationTerm
from .relation_terms import (
    BESIDE_DISTANCE,
    HEADING_FACINGS,
    WINDOW_PLACEMENTS,
    anchor,
    centre,
    evaluate,
    satisfied,
    source_point,
)
from .room_terms import CORRIDOR_HALF, FLAT_HEIGHT, access_grid
from .state import State

#: Relative frequencies of the move types.
MOVE_WEIGHTS = {
    "jitter": 0.27,
    "rotate": 0.12,
    "group": 0.12,
    "cluster": 0.06,
    "relation": 0.28,
    "path": 0.10,
    "junction": 0.05,
}

#: Gaps (metres) a data-driven NextTo proposal leaves between A and B.
GAP_RANGE = (0.05, 0.8)

#: How far (as a share of B's half side) a data-driven NextTo proposal may slide A along B.
LATERAL_SHARE = 0.5

#: Share of data-driven NextTo moves that move B towards A instead of A towards B.
REVERSE_SHARE = 0.3

#: Extra weight a relation found unsatisfied at the last check gets in data-driven moves
#: (the squared energies of the others are mostly well below 1).
FOCUS_WEIGHT = 1.0

#: Tries of a data-driven move for an item with several placing relations.
MULTI_TRIES = 8

#: Gaps (metres) a data-driven AlignedWith proposal leaves between A and B, and a
#: BesideWindow one between A and the window's edge.
ALIGN_GAP = (0.02, 0.3)
BESIDE_GAP = (0.02, min(0.25, BESIDE_DISTANCE))

#: Share of data-driven AlignedWith placements of an A without a wall relation that only
#: correct A where it stands (``snap_aligned``) rather than draw a new place beside B
#: (``place_aligned``).
SNAP_ALIGN_SHARE = 0.5

#: Random spots along a wall tried before one in front of a door (or of a window, for
#: furniture taller than its sill) is taken anyway.
WALL_TRIES = 6
#: Furniture taller than a window's sill closer than this (metres) to its wall stands
#: in front of the window (a door's zone is its swing, as deep as the door is wide).
WINDOW_KEEP = 0.5
#: Share of jitter and cluster moves of furniture standing against a wall that slide
#: along the wall (a random shift would take it off the wall).
SLIDE_SHARE = 0.5
#: Share of data-driven wall moves of an A tied to others that carry those in place along.
CARRY_SHARE = 0.3
#: A box slides along its wall only when it stands against it: back within this gap
#: (metres) and angle (radians).
SLIDE_GAP = 0.1
SLIDE_ANGLE = 0.1

HALF_PI = math.pi / 2.0

#: A heading this close (radians) to the one a facing relation asks for already has it.
FACED = 1e-9


def wrap(angle: float) -> float:
    """The angle in [-pi, pi)."""
    return angle - 2.0 * math.pi * math.floor((angle + math.pi) / (2.0 * math.pi))


def rigid(
    state: State,
    boxes: list[int],
    pivot: tuple[float, float],
    turn: float,
    shift: tuple[float, float],
) -> dict:
    """New poses of ``boxes`` turned by ``turn`` about ``pivot`` then shifted."""
    if turn == 0.0:  # exact translation, so the energy can see that nothing turned
        return {
            box: (state.x[box] + shift[0], state.z[box] + shift[1], state.yaw[box]) for box in boxes
        }
    c, s = math.cos(turn), math.sin(turn)
    px, pz = pivot
    moved = {}
    for box in boxes:
        rx, rz = state.x[box] - px, state.z[box] - pz
        moved[box] = (
            px + rx * c + rz * s + shift[0],
            pz - rx * s + rz * c + shift[1],
            wrap(state.yaw[box] + turn),
        )
    return moved


def carried_by(problem: Problem, boxes) -> list[int]:
    """The boxes plus everything stacked on them, each once, in a fixed order."""
    found: list[int] = []
    for box in boxes:
        for item in problem.carried(box):
            if item not in found:
                found.append(item)
    return found


def reach(problem: Problem, state: State, box: int, wx: float, wz: float) -> float:
    """How far a box's footprint reaches from its centre along the unit direction (wx, wz)."""
    c, s = state.c[box], state.s[box]
    return problem.half_width[box] * abs(c * wx - s * wz) + problem.half_depth[box] * abs(
        s * wx + c * wz
    )


def end_reach(problem: Problem, state: State, end: Endpoint, wx: float, wz: float) -> float:
    """How far an object or group reaches from its centre along (wx, wz)."""
    if end.kind == "object":
        return reach(problem, state, end.index, wx, wz)
    cx, cz = centre(end, state)
    return max(
        (state.x[b] - cx) * wx + (state.z[b] - cz) * wz + reach(problem, state, b, wx, wz)
        for b in end.members
    )


def uniform(rng: np.random.Generator, low: float, high: float) -> float:
    """The number ``rng.uniform(low, high)`` draws, without its cost per call: numpy's
    ``Generator.uniform`` is low + (high - low) times one standard uniform draw, the one
    ``rng.random()`` makes (``tests/test_layout_shortcuts.py`` holds them equal). A range it
    refuses (high below low, or not finite) is left to it, so that it raises as ever."""
    span = high - low
    if 0.0 <= span < math.inf and math.copysign(1.0, span) > 0.0:
        return low + span * rng.random()
    return rng.uniform(low, high)


def draw_index(rng: np.random.Generator, count: int) -> int:
    """A uniform index below ``count``, the one ``int(rng.integers(count))`` draws: for a
    count of 1 numpy returns 0 without drawing, so no call is made (it costs microseconds,
    and many picks are from one thing: a group's one anchor, a road's one junction)."""
    return 0 if count == 1 else int(rng.integers(count))


def _log_uniform(rng: np.random.Generator, low: float, high: float) -> float:
    return math.exp(uniform(rng, math.log(low), math.log(high)))


class Mover:
    """Draws proposals for one problem; holds the precomputed choices."""

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
        held_in_group = {box for group in rigid_groups for box in problem.group_members[group]}
        # Whether a move may place this box by itself: a free (unpinned) non-junction object.
        self.movable_box = [
            not problem.is_junction[b] and not pins.box[b] and b not in held_in_group
            for b in range(problem.n_boxes)
        ]
        self.boxes = [b for b in range(problem.n_boxes) if self.movable_box[b]]
        self.junctions = [
            b for b in range(problem.n_boxes) if problem.is_junction[b] and not pins.box[b]
        ]
        self.paths = [p for p in range(problem.n_paths) if not pins.path[p]]
        carried = [
            carried_by(problem, problem.group_members[g]) for g in range(len(problem.group_ids))
        ]
        # A group moves as a whole only when nothing in it is pinned or rests on a pinned box;
        # random rigid moves carry its free boxes only.
        self.group_whole = [not any(pins.fixed(b) for b in boxes) for boxes in carried]
        self.group_boxes = [[b for b in boxes if not pins.fixed(b)] for boxes in carried]
        rigid = set(rigid_groups)
        self.rigid_group_of = {box: g for g in rigid for box in problem.group_members[g]}
        self.groups = [
            g
            for g, members in enumerate(problem.group_members)
            if members and self.group_boxes[g] and (g in rigid or not set(members) <= held_in_group)
        ]
        self.top_group_of = {box: g for g in problem.top_groups for box in problem.group_members[g]}
        # NextTo* from something pins hold to a free path or junction: pulled (``pull``).
        self.pullable = {
            t
            for t, term in enumerate(problem.relations)
            if term.placeable
            and term.spec.family == "next_to"
            and self._held(term.a)
            and self._pulls(term.b)
        }
        self.relations = [  # relations a move can act on
            t
            for t, term in enumerate(problem.relations)
            if term.placeable
            and (self._movable(term.a) or self._movable(term.b) or t in self.pullable)
        ]
        self._relation_positions = np.array(
            self.relations, dtype=np.intp
        )  # for ``relation_move``'s weights
        self.clusters = [
            c
            for c in ([b for b in boxes if not pins.fixed(b)] for boxes in _clusters(problem))
            if c
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
        # Free boxes with a wall relation (rooms only): their jitter may slide along the wall.
        self.wall_terms: dict[int, list[RelationTerm]] = {}
        for term in problem.relations:
            if (
                term.spec.family == "wall"
                and self.movable_box[term.a.index]
                and problem.support[term.a.index] < 0
            ):
                self.wall_terms.setdefault(term.a.index, []).append(term)
        # Quarter turns in a room are square to its longest wall (0 when the walls run
        # north-south and east-west, so those rooms snap as to the world's axes).
        self.square_base = 0.0
        if problem.room is not None:
            longest = max(problem.room.walls, key=lambda wall: wall.length)
            self.square_base = math.remainder(longest.facing_yaw, HALF_PI) + 0.0
        self.focus_positions: list[int] = []
        self.focus_boxes: list[int] = []
        self.focus_groups: list[int] = []  # rigid groups holding a troubled box
        available = {
            "jitter": bool(self.boxes),
            "rotate": bool(self.boxes),
            "group": bool(self.groups),
            "cluster": bool(self.clusters),
            "relation": bool(self.relations),
            "path": bool(self.paths),
            "junction": bool(self.junctions),
        }
        self.kinds = [kind for kind in MOVE_WEIGHTS if available[kind]]
        weights = np.array([MOVE_WEIGHTS[kind] for kind in self.kinds])
        self.cumulative = list(np.cumsum(weights / weights.sum())) if self.kinds else []

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
        """Whether ``pull`` may move this end: a free path or a free junction."""
        if end.kind == "path":
            return not self.pins.path[end.index]
        return (
            end.kind == "object"
            and self.problem.is_junction[end.index]
            and not self.pins.box[end.index]
        )

    def focus(self, unsatisfied: list[int], troubled: list[int]) -> None:
        """Steer later proposals to these relations (indices) and boxes (overlapping, outside)."""
        position = {term: k for k, term in enumerate(self.relations)}
        self.focus_positions = [position[t] for t in unsatisfied if t in position]
        self.focus_boxes = [box for box in troubled if self.movable_box[box]]
        self.focus_groups = sorted(
            {self.rigid_group_of[box] for box in troubled if box in self.rigid_group_of}
        )

    def propose(self, relation_energy: list[float]) -> tuple[dict, dict] | None:
        """One random proposal; ``relation_energy`` steers the data-driven moves."""
        if not self.kinds:
            return None
        draw = self.rng.random()
        kind = self.kinds[-1]
        for candidate, edge in zip(self.kinds, self.cumulative, strict=False):
            if draw < edge:
                kind = candidate
                break
        if kind == "jitter":
            if self.focus_boxes and self.rng.random() < 0.5:
                return self.jitter(self.focus_boxes[draw_index(self.rng, len(self.focus_boxes))])
            return self.jitter(self.boxes[draw_index(self.rng, len(self.boxes))])
        if kind == "rotate":
            return self.rotate(self.boxes[draw_index(self.rng, len(self.boxes))])
        if kind == "group":
            if self.focus_groups and self.rng.random() < 0.5:
                return self.relocate_group(
                    self.focus_groups[draw_index(self.rng, len(self.focus_groups))]
                )
            return self.move_group(self.groups[draw_index(self.rng, len(self.groups))])
        if kind == "cluster":
            return self.move_cluster(self.clusters[draw_index(self.rng, len(self.clusters))])
        if kind == "relation":
            return self.relation_move(relation_energy)
        if kind == "path":
            return self.move_path(self.paths[draw_index(self.rng, len(self.paths))])
        return self.move_junction(self.junctions[draw_index(self.rng, len(self.junctions))])

    # -- local moves ---------------------------------------------------------------------

    def jitter(self, box: int) -> tuple[dict, dict]:
        problem, state, rng = self.problem, self.state, self.rng
        below = problem.support[box]
        scale = min(problem.half_width[below], problem.half_depth[below]) if below >= 0 else 2.0
        sigma = _log_uniform(rng, 0.02, 1.0) * scale
        shift = (rng.normal(0.0, sigma), rng.normal(0.0, sigma))
        if box in self.wall_terms and rng.random() < SLIDE_SHARE:
            shift = self._along_wall(box, shift)
        return rigid(state, problem.carried(box), (state.x[box], state.z[box]), 0.0, shift), {}

    def rotate(self, box: int) -> tuple[dict, dict]:
        state, rng = self.state, self.rng
        if self.problem.walls or rng.random() < 0.3:
            base = self.square_base
            target = base + HALF_PI * (
                round((state.yaw[box] - base) / HALF_PI) + int(rng.integers(-1, 2))
            )
            turn = target - state.yaw[box]
        else:
            turn = rng.normal(0.0, _log_uniform(rng, 0.02, 0.8))
        return rigid(
            state, self.problem.carried(box), (state.x[box], state.z[box]), turn, (0.0, 0.0)
        ), {}

    def move_group(self, group: int) -> tuple[dict, dict]:
        state, rng = self.state, self.rng
        members = self.problem.group_members[group]
        pivot = centre(Endpoint("group", group, members), state)
        sigma = _log_uniform(rng, 0.05, 3.0)
        turn = 0.0
        if rng.random() < 0.3:
            turn = (
                HALF_PI * (1 if rng.random() < 0.5 else -1)
                if self.problem.walls
                else rng.normal(0.0, 0.3)
            )
        shift = (rng.normal(0.0, sigma), rng.normal(0.0, sigma))
        return rigid(state, self.group_boxes[group], pivot, turn, shift), {}

    def relocate_group(self, group: int) -> tuple[dict, dict] | None:
        """A rigid group in trouble (overlapping, outside): half the time a random rigid
        move, half the time put anew where its own relations hold (the best of a few
        tries, ``place_for_all``), e.g. at another spot along its road."""
        end = Endpoint("group", group, self.problem.group_members[group])
        if self.rng.random() < 0.5 or not self._placing_terms(end):
            return self.move_group(group)
        boxes = self.place_for_all(end)
        return (boxes, {}) if boxes else None

    def move_cluster(self, boxes: list[int]) -> tuple[dict, dict]:
        sigma = _log_uniform(self.rng, 0.05, 2.0)
        shift = (self.rng.normal(0.0, sigma), self.rng.normal(0.0, sigma))
        if self.wall_terms:
            anchored = next((box for box in boxes if box in self.wall_terms), None)
            if anchored is not None and self.rng.random() < SLIDE_SHARE:
                shift = self._along_wall(anchored, shift)
        return rigid(self.state, boxes, (0.0, 0.0), 0.0, shift), {}

    def move_path(self, path: int) -> tuple[dict, dict] | None:
        problem, state, rng = self.problem, self.state, self.rng
        points = state.points[path]
        first = 1 if problem.path_start[path] >= 0 else 0
        if first >= len(points):
            return None
        index = int(rng.integers(first, len(points)))
        new = [list(p) for p in points]
        if rng.random() < 0.5 or index == 0:
            sigma = _log_uniform(rng, 0.05, 2.0)
            new[index] = [
                points[index][0] + rng.normal(0.0, sigma),
                points[index][1] + rng.normal(0.0, sigma),
            ]
        else:  # bend the tail from this point on about the previous one
            turn = rng.normal(0.0, 0.15)
            c, s = math.cos(turn), math.sin(turn)
            px, pz = points[index - 1]
            for k in range(index, len(points)):
                rx, rz = points[k][0] - px, points[k][1] - pz
                new[k] = [px + rx * c + rz * s, pz - rx * s + rz * c]
        return {}, {path: new}

    def move_junction(self, junction: int) -> tuple[dict, dict]:
        rng = self.rng
        sigma = _log_uniform(rng, 0.05, 2.0)
        dx, dz = rng.normal(0.0, sigma), rng.normal(0.0, sigma)
        return self._shift_junction(junction, dx, dz)

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

    # -- data-driven moves -------------------------------------------------------------

    def relation_move(self, relation_energy: list[float]) -> tuple[dict, dict] | None:
        # Squared, so clearly violated relations (energy above ~1) win over the small
        # residues soft factors always keep; relations last found unsatisfied get a boost.
        weights = np.array(relation_energy, dtype=float)[self._relation_positions] ** 2 + 0.01
        for position in self.focus_positions:
            weights[position] += FOCUS_WEIGHT
        # Inverse-CDF sampling as rng.choice(p=...) does it, without its checks of p each step.
        cdf = (weights / weights.sum()).cumsum()
        cdf /= cdf[-1]
        index = self.relations[int(cdf.searchsorted(self.rng.random(), side="right"))]
        term = self.problem.relations[index]
        a_movable, b_movable = self._movable(term.a), self._movable(term.b)
        turnable = term.b.kind == "object" and b_movable and term.spec.names_target_side
        if turnable and self.rng.random() < REVERSE_SHARE:
            boxes = self.turn_target_for(term)
        elif (
            b_movable
            and term.spec.family == "next_to"
            and (not a_movable or self.rng.random() < REVERSE_SHARE)
        ):
            boxes = self.place_target_for(term)
        elif (
            term.spec.family == "alignment"
            and b_movable
            and (not a_movable or self.rng.random() < REVERSE_SHARE)
        ):
            boxes = self.place_aligned(term.b.index, term.a.index)  # symmetric: line B up with A
        elif a_movable and len(self._placing_terms(term.a)) > 1:
            boxes = self.place_for_all(term.a)
        elif (
            a_movable
            and term.spec.family == "wall"
            and term.a.index in self.cluster_of
            and self.rng.random() < CARRY_SHARE
        ):
            boxes = self.carry_to_wall(term)
        elif a_movable:
            boxes = self.place_for_relation(term)
        elif index in self.pullable:
            return self.pull(term)
        else:
            return None
        return (boxes, {}) if boxes else None

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
            first = 1 if problem.path_start[path] >= 0 else 0
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

    def _placing_terms(self, end: Endpoint) -> list[RelationTerm]:
        """A's relations that say where it goes (NextTo*, OnTopOf*), not only how it turns."""
        key = (end.kind, end.index)
        if key not in self._placing:
            self._placing[key] = [
                t for t in self.problem.outgoing.get(key, []) if t.spec.family != "facing"
            ]
        return self._placing[key]

    def place_for_all(self, end: Endpoint) -> dict | None:
        """For an A with several placing relations: the best of a few data-driven poses.

        Each try places A by one of its relations drawn at random (``place_by``); the
        tries are ranked by the energy of all of A's placing relations together, so a
        smithy that must be both beside a tower and next to a road lands where both
        hold, when any try found it.
        """
        state = self.state
        terms = self._placing_terms(end)
        walls = [t for t in terms if t.spec.family == "wall"]
        best, best_energy = None, math.inf
        for _ in range(MULTI_TRIES):
            proposal = self.place_by(terms[draw_index(self.rng, len(terms))], walls)
            if not proposal:
                continue
            with state.trying(proposal):
                energy = sum(evaluate(term, state, self.params).energy for term in terms)
            if energy < best_energy:
                best, best_energy = proposal, energy
        return best

    def place_by(self, term: RelationTerm, walls: list[RelationTerm]) -> dict | None:
        """A placed by ``term``; when A must also stand against a wall (``walls``, its
        wall relations) and ``term`` is another kind, then half the time pushed onto the
        nearest spot that wall relation allows (keeping its place along the wall). An A
        held by no wall that must be lined up with a box (AlignedWith) is likewise, half
        the time, lined up with it where ``term`` put it (``snap_aligned``): a desk put
        left of its neighbour lands in line with it too."""
        proposal = self.place_for_relation(term)
        if not proposal or term.a.kind != "object":
            return proposal
        if walls:
            if term.spec.family != "wall" and self.rng.random() < 0.5:
                wall_term = walls[draw_index(self.rng, len(walls))]
                with self.state.trying(proposal):
                    snapped = self._place_at_wall(wall_term, snap=True)
                if snapped:
                    proposal = {**proposal, **snapped}
            return proposal
        lines = [
            t
            for t in self._placing_terms(term.a)
            if t.spec.family == "alignment" and t.b.kind == "object"
        ]
        if lines and term.spec.family != "alignment" and self.rng.random() < 0.5:
            line = lines[draw_index(self.rng, len(lines))]
            with self.state.trying(proposal):
                snapped = self.snap_aligned(term.a.index, line.b.index)
            if snapped:
                proposal = {**proposal, **snapped}
        return proposal

    def place_for_relation(self, term: RelationTerm, *, keep_heading: bool = False) -> dict | None:
        """New poses for A (and all it carries) at which ``term`` holds, or None.

        ``keep_heading``: a NextTo* placement only shifts A (never turns it to face a road).
        """
        family = term.spec.family
        if family == "next_to":
            return self._place_next_to(term, keep_heading)
        if family == "facing":
            if (
                term.a.kind == "object"
                and term.a.index in self.top_group_of
                and self.rng.random() < 0.5
            ):
                if self.group_whole[self.top_group_of[term.a.index]]:
                    return self.turn_group_to_face(term)
            return self.turn_to_face(term)
        if family == "wall":
            return self._place_at_wall(term)
        if family == "alignment":
            # Not for A held by a wall: standing against B's wall lines its back up with
            # B's already, and a shift in B's frame could take it off the wall.
            if term.a.index not in self.wall_terms and self.rng.random() < SNAP_ALIGN_SHARE:
                return self.snap_aligned(term.a.index, term.b.index)
            return self.place_aligned(term.a.index, term.b.index)
        return self._place_on_top(term)

    def moving_boxes(self, end: Endpoint) -> list[int]:
        if end.kind == "group":
            return self.group_boxes[end.index]
        return self.problem.carried(end.index)

    def _place_next_to(self, term: RelationTerm, keep_heading: bool = False) -> dict:
        problem, state, rng = self.problem, self.state, self.rng
        a, b = term.a, term.b
        if b.kind in ROOM_ENDS:
            return self._place_by_room_part(term)
        ax, az = centre(a, state)
        gap = uniform(rng, *GAP_RANGE)
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
                heading = self._heading(a)
                turn = wrap(math.atan2(-nx, -nz) - heading)
            offset = problem.path_width[b.index] / 2.0
            wx, wz = nx, nz
        else:
            bx, bz, c, s = anchor(b, state, (ax, az))
            wx, wz = self._wanted_direction(term, c, s)
            offset = end_reach(problem, state, b, wx, wz) + self.kept_free(a, b, wx, wz)
            # Slide sideways along B's side a little, so several things beside B can fit.
            slide = uniform(rng, -LATERAL_SHARE, LATERAL_SHARE) * end_reach(
                problem, state, b, -wz, wx
            )
            bx, bz = bx - wz * slide, bz + wx * slide
        boxes = self.moving_boxes(a)
        pivot = (ax, az)
        if turn:  # measure A's reach and centre as they will be once turned
            with state.trying(rigid(state, boxes, pivot, turn, (0.0, 0.0))):
                a_reach = end_reach(problem, state, a, -wx, -wz)
                ax, az = centre(a, state)
        else:
            a_reach = end_reach(problem, state, a, -wx, -wz)
        distance = offset + a_reach + gap
        return rigid(state, boxes, pivot, turn, (bx + wx * distance - ax, bz + wz * distance - az))

    def place_target_for(self, term: RelationTerm) -> dict:
        """New poses for B (shifted, not turned) at which the NextTo* ``term`` holds."""
        problem, state = self.problem, self.state
        a, b = term.a, term.b
        ax, az = source_point(a, state)
        bx, bz, c, s = anchor(b, state, (ax, az))
        wx, wz = self._wanted_direction(term, c, s)
        if a.kind == "path":
            a_reach = problem.path_width[a.index] / 2.0
        else:
            a_reach = end_reach(problem, state, a, -wx, -wz)
        distance = (
            a_reach
            + end_reach(problem, state, b, wx, wz)
            + self.kept_free(a, b, wx, wz)
            + uniform(self.rng, *GAP_RANGE)
        )
        return rigid(
            state,
            self.moving_boxes(b),
            (bx, bz),
            0.0,
            (ax - wx * distance - bx, az - wz * distance - bz),
        )

    def kept_free(self, a: Endpoint, end: Endpoint, wx: float, wz: float) -> float:
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
        c, s = self.state.c[box], self.state.s[box]
        lx, lz = wx * c - wz * s, wx * s + wz * c  # B's local axes: +x its left, +z its front
        if abs(lz) >= abs(lx):
            side = "front" if lz > 0.0 else "back"
        else:
            side = "left" if lx > 0.0 else "right"
        way = (
            self.way_width
            if self.problem.access[box] == (side,) and self._bars(a, box, side, wx, wz)
            else 0.0
        )
        strangers = self.followers[a.index] - self.partners[box]
        if not self.problem.clearance[box] or not strangers:
            return way
        kept = max(
            (metres for named, metres in self.problem.clearance[box] if named == side), default=0.0
        )
        if kept == 0.0:
            return way
        # Room for those placed by A between it and the space: the deepest of them, by its
        # shorter side (they stand on A's side towards B or not: the tries decide).
        between = max(
            2.0 * min(self.problem.half_width[f], self.problem.half_depth[f]) for f in strangers
        )
        return max(way, kept + between)

    def _bars(self, a: Endpoint, box: int, side: str, wx: float, wz: float) -> bool:
        """Whether ``a`` (an object), standing beside ``box``'s ``side`` in the unit
        direction (wx, wz), would leave no way to that side however far off it stood: it
        blocks ways and, with a half corridor either side of it, it is as wide as the side
        is long (a pupil's chair behind a 0.7 m desk; not a chair at a 1.2 m desk, whose
        ends stay free)."""
        if not self.blocks_way[a.index]:
            return False
        problem = self.problem
        across = 2.0 * end_reach(problem, self.state, a, -wz, wx)
        length = 2.0 * (
            problem.half_width[box] if side in ("front", "back") else problem.half_depth[box]
        )
        return across + 2.0 * CORRIDOR_HALF >= length

    def turn_target_for(self, term: RelationTerm) -> dict:
        """Turn B (an object, with what it carries) in place so that A is on the side named
        (of several sides, the one reached by the smallest turn)."""
        state = self.state
        box = term.b.index
        ax, az = centre(term.a, state)
        heading = math.atan2(ax - state.x[box], az - state.z[box])  # B's yaw if A were in front
        # A side at local (lx, lz) points along (dx, dz) when B's yaw is heading - atan2(lx, lz).
        turns = [
            wrap(heading - math.atan2(lx, lz) - state.yaw[box])
            for lx, lz in term.spec.directions.values()
        ]
        turn = min(turns, key=abs)
        return rigid(
            state, self.problem.carried(box), (state.x[box], state.z[box]), turn, (0.0, 0.0)
        )

    def _heading(self, end: Endpoint) -> float:
        """Yaw of an object, or of a group's first member (the group's front)."""
        box = end.index if end.kind == "object" else end.members[0]
        return self.state.yaw[box]

    def _wanted_direction(self, term: RelationTerm, c: float, s: float) -> tuple[float, float]:
        """A unit direction from B to A in which ``term`` holds (drawn where it is open);
        ``c``, ``s``: B's yaw's cosine and sine."""
        wanted = list(term.spec.direction_vectors(c, s).values())
        if len(wanted) == 1:
            return wanted[0]
        if wanted:
            return wanted[draw_index(self.rng, len(wanted))]
        angle = uniform(self.rng, -math.pi, math.pi)
        return math.sin(angle), math.cos(angle)

    def turn_group_to_face(self, term: RelationTerm) -> dict | None:
        """Turn the whole top-level group holding A about its centre so A faces as ``term``
        wants (None when something in the group is pinned)."""
        group = self.top_group_of[term.a.index]
        if not self.group_whole[group]:
            return None
        members = self.problem.group_members[group]
        pivot = centre(Endpoint("group", group, members), self.state)
        turn = self._facing_turn(term)
        return rigid(self.state, self.group_boxes[group], pivot, turn, (0.0, 0.0))

    def turn_to_face(self, term: RelationTerm) -> dict | None:
        """Turn A (an object, with what it carries) in place so the Facing* ``term`` holds."""
        if term.a.kind != "object":
            return None
        box = term.a.index
        pivot = (self.state.x[box], self.state.z[box])
        return rigid(
            self.state, self.problem.carried(box), pivot, self._facing_turn(term), (0.0, 0.0)
        )

    def faces_as_asked(self, term: RelationTerm) -> bool:
        """Whether A (an object) already has the heading a facing relation that asks for
        a heading only (same, opposite or square to B's) wants, to FACED (radians): then
        a turn to face would leave it where it is, and the constructive placement makes
        no such proposal. False for the other facing relations."""
        if (
            term.spec.facing not in HEADING_FACINGS
            or term.a.kind != "object"
            or term.b.kind not in ("object", "group")
        ):
            return False
        b_yaw = (
            self.state.yaw[term.b.index] if term.b.kind == "object" else 0.0
        )  # a group faces the world's forward
        off = wrap(self.state.yaw[term.a.index] - b_yaw)
        wanted = {"same": 0.0, "opposite": math.pi, "orthogonal": HALF_PI}[term.spec.facing]
        return abs(abs(off) - wanted) < FACED

    def _facing_turn(self, term: RelationTerm) -> float:
        """The turn of A (an object) after which the Facing* ``term`` holds."""
        state = self.state
        a, b = term.a, term.b
        ax, az = state.x[a.index], state.z[a.index]
        bx, bz, c, s = anchor(b, state, (ax, az))
        how = term.spec.facing
        if how == "towards":
            yaw = math.atan2(bx - ax, bz - az)
        elif how == "away":
            yaw = math.atan2(ax - bx, az - bz)
        else:
            b_yaw = math.atan2(s, c) if b.kind != "group" else 0.0
            if how == "same":
                yaw = b_yaw
            elif how == "opposite":
                yaw = b_yaw + math.pi
            else:
                yaw = b_yaw + (HALF_PI if self.rng.random() < 0.5 else -HALF_PI)
        return wrap(yaw - state.yaw[a.index])

    def _place_on_top(self, term: RelationTerm) -> dict:
        problem, state, rng = self.problem, self.state, self.rng
        a, b = term.a.index, term.b.index
        quarter = int(rng.integers(4)) if rng.random() < 0.3 else 0
        yaw = wrap(state.yaw[b] + quarter * HALF_PI)
        # A's half extents along B's axes once turned to ``yaw``.
        ex, ez = (
            (problem.half_width[a], problem.half_depth[a])
            if quarter % 2 == 0
            else (problem.half_depth[a], problem.half_width[a])
        )
        room_x = max(problem.half_width[b] - ex, 0.0)
        room_z = max(problem.half_depth[b] - ez, 0.0)
        placement = term.spec.placement
        if placement == "middle":
            lx = lz = 0.0
        elif placement == "front_edge":
            lx, lz = uniform(rng, -room_x, room_x), room_z
        elif placement == "edge":
            edge = int(rng.integers(4))
            lx = (room_x if edge == 0 else -room_x) if edge < 2 else uniform(rng, -room_x, room_x)
            lz = (room_z if edge == 2 else -room_z) if edge >= 2 else uniform(rng, -room_z, room_z)
        else:
            lx, lz = uniform(rng, -room_x, room_x), uniform(rng, -room_z, room_z)
        x, z = to_world(state.x[b], state.z[b], state.yaw[b], lx, lz)
        return rigid(
            state,
            problem.carried(a),
            (state.x[a], state.z[a]),
            wrap(yaw - state.yaw[a]),
            (x - state.x[a], z - state.z[a]),
        )

    # -- rooms ---------------------------------------------------------------------------

    def _along_wall(self, box: int, shift: tuple[float, float]) -> tuple[float, float]:
        """``shift`` projected onto the wall the box stands against by its (first) wall
        relation (the wall, or window, that relation measures best), so the box stays
        flush; unchanged when the box is not against that wall now."""
        term = self.wall_terms[box][0]
        measure = evaluate(term, self.state, self.params)
        if (
            math.isinf(measure.energy)
            or abs(measure.distance) > SLIDE_GAP
            or measure.angle > SLIDE_ANGLE
        ):
            return shift  # not against it (or no window for a window label)
        room = self.problem.room
        part = room.part(measure.chosen or term.target)
        wall = part if isinstance(part, Wall) else room.part(part.wall)
        tx, tz = wall.direction
        along = shift[0] * tx + shift[1] * tz
        return along * tx, along * tz

    def _pose_box(self, box: int, x: float, z: float, yaw: float) -> dict:
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

    def _place_at_wall(self, term: RelationTerm, *, snap: bool = False) -> dict | None:
        """A (an object on the ground) with its back flush to a wall: yaw the wall's
        ``facing_yaw``, its centre half its depth from the wall, where the wall label
        wants it (``_wall_spots``). A spot is drawn by how much room it leaves, then a
        place along it at random, avoiding doors' swings and, for furniture taller than
        a window's sill, the window. ``snap``: the spot nearest A as it stands, at the
        place along the wall nearest A (no random draw)."""
        problem, state, rng = self.problem, self.state, self.rng
        box = term.a.index
        if problem.support[box] >= 0:
            return None  # it moves with what it rests on
        spots = self._wall_spots(term)
        if not spots:
            return None
        hd = problem.half_depth[box]
        if snap:
            best, best_distance = None, math.inf
            for wall, low, high, _ in spots:
                u, _ = wall.to_wall(state.x[box], state.z[box])
                x, z = wall.to_world(min(max(u, low), high), hd)
                distance = math.hypot(x - state.x[box], z - state.z[box])
                if distance < best_distance - 1e-12:
                    best, best_distance = (x, z, wall.facing_yaw), distance
            return self._pose_box(box, *best)
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
            if self._clear_of_openings(box, x, z, c, s):
                break
        return self._pose_box(box, x, z, yaw)

    def carry_to_wall(self, term: RelationTerm) -> dict | None:
        """A placed by its wall relation, and the free boxes a relation that holds now
        ties to A (with what rests on them) turned and shifted with it rigidly, so a bed
        moves to another wall with the nightstands that stand beside it; one that is
        not in place yet stays to be placed on its own."""
        problem, state = self.problem, self.state
        box = term.a.index
        placed = self._place_at_wall(term)
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
            if other in self.cluster_of[box] and satisfied(
                tie, evaluate(tie, state, self.params), self.params
            ):
                in_place.update(b for b in problem.carried(other) if b in self.cluster_of[box])
        x, z, yaw = placed[box]
        pivot = (state.x[box], state.z[box])
        moved = rigid(
            state, sorted(in_place), pivot, wrap(yaw - state.yaw[box]), (x - pivot[0], z - pivot[1])
        )
        moved[box] = (x, z, yaw)
        return moved

    def _wall_spots(self, term: RelationTerm) -> list[tuple[Wall, float, float, float]]:
        """Where the wall label lets A's centre go, as (wall, lowest u, highest u, weight):
        a stretch of a wall (against: where A's whole footprint stays on the wall) or a
        single place (a corner, under a window, beside either edge of one). For the room
        as target every wall or window is a candidate, weighted by the room left along
        it (wall length minus A's width; 1 for a single place). Places A does not fit,
        and single places in a door's swing (or, for furniture taller than its sill, in
        front of a window), are left out unless nothing else is left."""
        problem, state = self.problem, self.state
        room, box, b = problem.room, term.a.index, term.b
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
                walls = [room.part(room.openings[b.index].wall)]
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
                    room.convex_corner(before, wall)
                    if at_start
                    else room.convex_corner(wall, after)
                ):
                    continue
                u = self._corner_u(box, wall, other)
                if u is None:
                    continue
                fits = hw - 1e-9 <= u <= length - hw + 1e-9 and self._clear_at(box, wall, u)
                (fitting if fits else rest).append((wall, u, u, 1.0))
        top = state.y[box] + problem.height[box]
        for window in openings:
            wall = room.part(window.wall)
            if placement == "under_window":
                u = window.offset
                fits = (
                    top <= window.sill
                    and hw <= u <= wall.length - hw
                    and self._clear_at(box, wall, u)
                )
                (fitting if fits else rest).append((wall, u, u, 1.0))
                continue
            gap = uniform(self.rng, *BESIDE_GAP)
            low, high = window.span
            for u in (low - gap - hw, high + gap + hw):
                fits = hw <= u <= wall.length - hw and self._clear_at(box, wall, u)
                (fitting if fits else rest).append((wall, u, u, 1.0))
        if fitting:
            return fitting
        return [(wall, low, high, 1.0) for wall, low, high, _ in rest]

    def _corner_u(self, box: int, wall: Wall, other: Wall) -> float | None:
        """Where along ``wall`` A's centre goes (back flush, yaw the wall's facing_yaw) so
        that its footprint just touches the neighbouring wall ``other``: the distance of
        its centre from ``other`` is then its reach towards it."""
        problem = self.problem
        yaw = wall.facing_yaw
        c, s = math.cos(yaw), math.sin(yaw)
        nx, nz = other.normal
        reach_other = problem.half_width[box] * abs(c * nx - s * nz) + problem.half_depth[
            box
        ] * abs(s * nx + c * nz)
        tx, tz = wall.direction
        rate = tx * nx + tz * nz  # how fast the distance from ``other`` changes along ``wall``
        if abs(rate) < 1e-9:
            return None
        _, v0 = other.to_wall(*wall.to_world(0.0, problem.half_depth[box]))
        return (reach_other - v0) / rate

    def _clear_at(self, box: int, wall: Wall, u: float) -> bool:
        """``_clear_of_openings`` for the box with its back flush to ``wall`` at ``u``."""
        x, z = wall.to_world(u, self.problem.half_depth[box])
        return self._clear_of_openings(
            box, x, z, math.cos(wall.facing_yaw), math.sin(wall.facing_yaw)
        )

    def _clear_of_openings(self, box: int, x: float, z: float, c: float, s: float) -> bool:
        """Whether the box at (x, z) turned by (c, s) keeps out of every door's swing and
        does not stand in front of a window lower than its top."""
        problem, room = self.problem, self.problem.room
        hw, hd = problem.half_width[box], problem.half_depth[box]
        top = self.state.y[box] + problem.height[box]
        for opening in room.openings:
            if opening.kind == "window" and top <= opening.sill:
                continue
            wall = room.part(opening.wall)
            tx, tz = wall.direction
            nx, nz = wall.normal
            reach_u = hw * abs(c * tx - s * tz) + hd * abs(s * tx + c * tz)
            reach_v = hw * abs(c * nx - s * nz) + hd * abs(s * nx + c * nz)
            u, v = wall.to_wall(x, z)
            keep = opening.width if opening.kind == "door" else WINDOW_KEEP
            if v - reach_v < keep and abs(u - opening.offset) < reach_u + opening.width / 2.0:
                return False
        return True

    def place_aligned(self, mover: int, other: int) -> dict | None:
        """Box ``mover`` parallel to box ``other`` with a face flush: beside it (to its left
        or right) with the backs or the fronts in one line, or in front of or behind it
        with a side in line with its side, at a small gap. A box already parallel keeps
        its way round (same or opposite heading); another takes ``other``'s heading."""
        problem, state, rng = self.problem, self.state, self.rng
        if problem.support[mover] >= 0 or not self.movable_box[mover]:
            return None
        b_yaw = state.yaw[other]
        dot = state.s[mover] * state.s[other] + state.c[mover] * state.c[other]
        yaw = b_yaw + math.pi if dot < -0.5 else b_yaw
        ex, ez = problem.half_width[mover], problem.half_depth[mover]  # parallel: its axes are B's
        hw, hd = problem.half_width[other], problem.half_depth[other]
        gap = uniform(rng, *ALIGN_GAP)
        side = 1.0 if rng.random() < 0.5 else -1.0
        if rng.random() < 0.75:  # beside B, backs (mostly) or fronts flush
            lx = side * (hw + ex + gap)
            lz = ez - hd if rng.random() < 0.7 else hd - ez
        else:  # in front of or behind B, a side flush
            lz = side * (hd + ez + gap)
            lx = hw - ex if rng.random() < 0.5 else ex - hw
        x, z = to_world(state.x[other], state.z[other], b_yaw, lx, lz)
        return self._pose_box(mover, x, z, wrap(yaw))

    def snap_aligned(self, mover: int, other: int) -> dict | None:
        """Box ``mover`` lined up with box ``other`` by the smallest correction: turned
        parallel to it (whichever way round is nearer) about its own centre, then shifted
        along one of ``other``'s axes until the nearest pair of faces that can be flush
        without the two overlapping is flush. A desk 6 cm out of line with its neighbour
        in a row is pushed back into line where it stands, still beside it, where
        ``place_aligned`` would draw a new place (and break what holds there)."""
        problem, state = self.problem, self.state
        if problem.support[mover] >= 0 or not self.movable_box[mover]:
            return None
        b_yaw = state.yaw[other]
        dot = state.s[mover] * state.s[other] + state.c[mover] * state.c[other]
        yaw = wrap(b_yaw + math.pi if dot < 0.0 else b_yaw)
        ex, ez = problem.half_width[mover], problem.half_depth[mover]  # parallel: its axes are B's
        hw, hd = problem.half_width[other], problem.half_depth[other]
        lx, lz = to_local(state.x[other], state.z[other], b_yaw, state.x[mover], state.z[mover])
        best = None
        for axis, flush in ((0, hw - ex), (0, ex - hw), (1, hd - ez), (1, ez - hd)):
            nx, nz = (flush, lz) if axis == 0 else (lx, flush)
            if abs(nx) < hw + ex - 1e-9 and abs(nz) < hd + ez - 1e-9:
                continue  # the two would overlap
            shift = abs(nx - lx) + abs(nz - lz)
            if best is None or shift < best[0]:
                best = (shift, nx, nz)
        if best is None:  # A lies across B: no face can be made flush by one shift
            return self.place_aligned(mover, other)
        x, z = to_world(state.x[other], state.z[other], b_yaw, best[1], best[2])
        return self._pose_box(mover, x, z, yaw)

    def _place_by_room_part(self, term: RelationTerm) -> dict:
        """A next to a wall, an opening or the room (a wall drawn by its length): at a
        small gap from the wall, at a random place along it (along the opening's
        stretch), on the side the label names (into the room by default)."""
        problem, state, rng = self.problem, self.state, self.rng
        room, b = problem.room, term.b
        if b.kind == "opening":
            opening = room.openings[b.index]
            wall = room.part(opening.wall)
            low, high = opening.span
        else:
            if b.kind == "wall":
                wall = room.walls[b.index]
            else:
                lengths = np.array([w.length for w in room.walls])
                wall = room.walls[int(rng.choice(len(lengths), p=lengths / lengths.sum()))]
            low, high = 0.0, wall.length
        if term.spec.directions:
            wx, wz = self._wanted_direction(
                term, wall.normal[1], wall.normal[0]
            )  # the wall faces into the room
        else:
            wx, wz = wall.normal
        px, pz = wall.to_world(uniform(rng, low, high), 0.0)
        ax, az = centre(term.a, state)
        distance = end_reach(problem, state, term.a, -wx, -wz) + uniform(rng, *GAP_RANGE)
        return rigid(
            state,
            self.moving_boxes(term.a),
            (ax, az),
            0.0,
            (px + wx * distance - ax, pz + wz * distance - az),
        )


def _clusters(problem: Problem) -> list[list[int]]:
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
