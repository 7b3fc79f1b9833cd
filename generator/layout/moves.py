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
  source where that relation holds (``placement.Placer``; each family's way is its entry
  in ``families``), or move its target instead (B shifted next to A, lined up with A, or
  turned so that A is on the side the label names); an A with several placing
  relations gets the best of a few tries under all of them; a wall move sometimes
  carries along rigidly what is in place by A (the bed goes to another wall with the
  nightstands beside it); a NextTo* from a pinned A to a free road pulls the road;
- ``path``: move one control point of a path, or bend the path's tail around a point;
- ``junction``: move a junction, with the start of every path leaving it.

After each check of the stop rule the sampler points the mover at what is still wrong
(``focus``): unsatisfied relations are drawn more often for data-driven moves, and
overlapping or outlying boxes for jitter.

Pinned boxes and paths (``pinning.Pins``) are left out up front, so no check is made
per proposal: jitter, rotate and junction moves draw from the free boxes only; group
and cluster moves carry only their free boxes (pinned boxes and what rests on them stay
behind); data-driven moves never place or turn a pinned box, nor a whole group holding
a pinned box or one resting on it; path moves draw from the free paths.

``MOVES`` maps each kind to the method that draws it; the order of ``MOVE_WEIGHTS``
fixes which kind a random number picks.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable

import numpy as np

from scenewright.core.room import Wall

from .families import LAYOUT_FAMILIES, evaluate
from .motion import HALF_PI, draw_index, log_uniform, rigid, wrap
from .params import LayoutParams
from .pinning import Pins
from .placement import Placer
from .problem import Problem
from .relation_terms import centre, opening_wall
from .state import State
from .terms import Endpoint, RelationTerm

#: A proposal: new box poses {box: (x, z, yaw)} and path points {path: points}, or None.
Proposal = tuple[dict, dict] | None

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

#: Share of data-driven moves of a relation whose target may move that move B towards A
#: (NextTo*), line B up with A (AlignedWith) or turn B (a side of B named) instead of A.
REVERSE_SHARE = 0.3

#: Extra weight a relation found unsatisfied at the last check gets in data-driven moves
#: (the squared energies of the others are mostly well below 1).
FOCUS_WEIGHT = 1.0

#: Share of jitter and cluster moves of furniture standing against a wall that slide
#: along the wall (a random shift would take it off the wall).
SLIDE_SHARE = 0.5
#: Share of data-driven moves of an A tied to others that carry those in place along.
CARRY_SHARE = 0.3
#: A box slides along its wall only when it stands against it: back within this gap
#: (metres) and angle (radians).
SLIDE_GAP = 0.1
SLIDE_ANGLE = 0.1


class Mover(Placer):
    """Draws proposals for one problem: the random moves, and the data-driven ones by
    the placements it inherits."""

    def __init__(
        self,
        problem: Problem,
        state: State,
        rng: np.random.Generator,
        params: LayoutParams,
        pins: Pins | None = None,
        rigid_groups: Iterable[int] = (),
    ):
        super().__init__(problem, state, rng, params, pins, rigid_groups)
        pins = self.pins
        self.boxes = [b for b in range(problem.n_boxes) if self.movable_box[b]]
        # A grid's junctions and roads stay where they are laid (straight and square).
        self.junctions = [
            b
            for b in range(problem.n_boxes)
            if problem.is_junction[b] and not pins.box[b] and not problem.grid[b]
        ]
        self.paths = [
            p for p in range(problem.n_paths) if not pins.path[p] and not problem.path_grid[p]
        ]
        rigid = set(rigid_groups)
        self.rigid_group_of = {box: g for g in rigid for box in problem.group_members[g]}
        self.groups = [
            g
            for g, members in enumerate(problem.group_members)
            if members
            and self.group_boxes[g]
            and (g in rigid or not set(members) <= self.held_in_group)
        ]
        self.relations = [  # relations a move can act on
            t
            for t, term in enumerate(problem.relations)
            if term.placeable
            and (self._movable(term.a) or self._movable(term.b) or t in self.pullable)
        ]
        self._relation_positions = np.array(
            self.relations, dtype=np.intp
        )  # for ``relation_move``'s weights
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

    def focus(self, unsatisfied: list[int], troubled: list[int]) -> None:
        """Steer later proposals to these relations (indices) and boxes (overlapping, outside)."""
        position = {term: k for k, term in enumerate(self.relations)}
        self.focus_positions = [position[t] for t in unsatisfied if t in position]
        self.focus_boxes = [box for box in troubled if self.movable_box[box]]
        self.focus_groups = sorted(
            {self.rigid_group_of[box] for box in troubled if box in self.rigid_group_of}
        )

    def propose(self, relation_energy: list[float]) -> Proposal:
        """One random proposal; ``relation_energy`` steers the data-driven moves."""
        if not self.kinds:
            return None
        draw = self.rng.random()
        kind = self.kinds[-1]
        for candidate, edge in zip(self.kinds, self.cumulative, strict=False):
            if draw < edge:
                kind = candidate
                break
        return MOVES[kind](self, relation_energy)

    # -- drawing what to move, by kind ---------------------------------------------------

    def draw_jitter(self, relation_energy: list[float]) -> Proposal:
        """Jitter a box: half the time one in trouble, when there is one."""
        if self.focus_boxes and self.rng.random() < 0.5:
            return self.jitter(self.focus_boxes[draw_index(self.rng, len(self.focus_boxes))])
        return self.jitter(self.boxes[draw_index(self.rng, len(self.boxes))])

    def draw_rotate(self, relation_energy: list[float]) -> Proposal:
        return self.rotate(self.boxes[draw_index(self.rng, len(self.boxes))])

    def draw_group(self, relation_energy: list[float]) -> Proposal:
        """Move a group: half the time a rigid group in trouble, when there is one."""
        if self.focus_groups and self.rng.random() < 0.5:
            return self.relocate_group(
                self.focus_groups[draw_index(self.rng, len(self.focus_groups))]
            )
        return self.move_group(self.groups[draw_index(self.rng, len(self.groups))])

    def draw_cluster(self, relation_energy: list[float]) -> Proposal:
        return self.move_cluster(self.clusters[draw_index(self.rng, len(self.clusters))])

    def draw_path(self, relation_energy: list[float]) -> Proposal:
        return self.move_path(self.paths[draw_index(self.rng, len(self.paths))])

    def draw_junction(self, relation_energy: list[float]) -> Proposal:
        return self.move_junction(self.junctions[draw_index(self.rng, len(self.junctions))])

    # -- local moves ---------------------------------------------------------------------

    def jitter(self, box: int) -> tuple[dict, dict]:
        problem, state, rng = self.problem, self.state, self.rng
        below = problem.support[box]
        scale = min(problem.half_width[below], problem.half_depth[below]) if below >= 0 else 2.0
        sigma = log_uniform(rng, 0.02, 1.0) * scale
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
            turn = rng.normal(0.0, log_uniform(rng, 0.02, 0.8))
        return rigid(
            state, self.problem.carried(box), (state.x[box], state.z[box]), turn, (0.0, 0.0)
        ), {}

    def move_group(self, group: int) -> tuple[dict, dict]:
        state, rng = self.state, self.rng
        members = self.problem.group_members[group]
        pivot = centre(Endpoint("group", group, members), state)
        sigma = log_uniform(rng, 0.05, 3.0)
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
        sigma = log_uniform(self.rng, 0.05, 2.0)
        shift = (self.rng.normal(0.0, sigma), self.rng.normal(0.0, sigma))
        if self.wall_terms:
            anchored = next((box for box in boxes if box in self.wall_terms), None)
            if anchored is not None and self.rng.random() < SLIDE_SHARE:
                shift = self._along_wall(anchored, shift)
        return rigid(self.state, boxes, (0.0, 0.0), 0.0, shift), {}

    def move_path(self, path: int) -> tuple[dict, dict] | None:
        problem, state, rng = self.problem, self.state, self.rng
        points = state.points[path]
        # A road's start stays at its junction, or on the road it branches from.
        first = 1 if problem.path_start[path] >= 0 or problem.path_parent[path] >= 0 else 0
        if first >= len(points):
            return None
        index = int(rng.integers(first, len(points)))
        new = [list(p) for p in points]
        if rng.random() < 0.5 or index == 0:
            sigma = log_uniform(rng, 0.05, 2.0)
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
        sigma = log_uniform(rng, 0.05, 2.0)
        dx, dz = rng.normal(0.0, sigma), rng.normal(0.0, sigma)
        return self._shift_junction(junction, dx, dz)

    # -- data-driven moves -------------------------------------------------------------

    def relation_move(self, relation_energy: list[float]) -> Proposal:
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
        family = LAYOUT_FAMILIES[term.spec.family]
        a_movable, b_movable = self._movable(term.a), self._movable(term.b)
        turnable = term.b.kind == "object" and b_movable and term.spec.names_target_side
        boxes: dict | None
        if turnable and self.rng.random() < REVERSE_SHARE:
            boxes = self.turn_target_for(term)
        elif (
            b_movable
            and family.place_target is not None
            and (not a_movable or self.rng.random() < REVERSE_SHARE)
        ):
            boxes = family.place_target(self, term)
        elif a_movable and len(self._placing_terms(term.a)) > 1:
            boxes = self.place_for_all(term.a)
        elif (
            a_movable
            and family.carry is not None
            and term.a.index in self.cluster_of
            and self.rng.random() < CARRY_SHARE
        ):
            boxes = family.carry(self, term)
        elif a_movable:
            boxes = self.place_for_relation(term)
        elif index in self.pullable:
            return self.pull(term)
        else:
            return None
        return (boxes, {}) if boxes else None

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

    def _along_wall(self, box: int, shift: tuple[float, float]) -> tuple[float, float]:
        """``shift`` projected onto the wall the box stands against by its (first) wall
        relation (the wall, or window, that relation measures best), so the box keeps
        its gap to it; unchanged when the box is not against that wall now."""
        term = self.wall_terms[box][0]
        measure = evaluate(term, self.state, self.params)
        if (
            math.isinf(measure.energy)
            or abs(measure.distance - measure.kept) > SLIDE_GAP
            or measure.angle > SLIDE_ANGLE
        ):
            return shift  # not against it (or no window for a window label)
        room = self.problem.indoors()
        part = room.part(measure.chosen or term.target)
        wall = part if isinstance(part, Wall) else opening_wall(room, part)
        tx, tz = wall.direction
        along = shift[0] * tx + shift[1] * tz
        return along * tx, along * tz


#: How a proposal of each kind is drawn, in the order of ``MOVE_WEIGHTS``.
MOVES: dict[str, Callable[[Mover, list[float]], Proposal]] = {
    "jitter": Mover.draw_jitter,
    "rotate": Mover.draw_rotate,
    "group": Mover.draw_group,
    "cluster": Mover.draw_cluster,
    "relation": Mover.relation_move,
    "path": Mover.draw_path,
    "junction": Mover.draw_junction,
}
