"""The layout energy v = v_r + v_c + v_p + v_q + extent, kept up to date incrementally.

Parts (all >= 0, 0 when everything holds):

- ``relations`` (v_r): one term per relation edge (``families.evaluate``).
- ``collisions`` (v_c): per overlapping pair of boxes, -c log(1 - depth), depth being the
  minimum separating translation over the pair's summed footprint diagonals. Boxes on
  the ground collide in plan; when one of them is stacked, the vertical overlap counts
  too (a pot on a table does not collide with the stool beside it). A box and its
  support never collide.
- ``paths`` (v_p): per ground box and path, the same penalty for the box's depth into
  the path's buffered polyline, over the box's diagonal plus the path's width.
- ``path_shape`` (v_q): per path less(total length, max length) and less(turn, gamma) at
  each inner control point, and for a branch greater(its angle to its road, gamma);
  per junction greater(angle, gamma) between neighbouring outgoing paths.
- ``extent``: c times how far a box's corners (relative to its diagonal) or a path's
  control points (relative to its width) stick out of the scene extent. In a room the
  boxes' share is replaced by ``walls``.
- ``walls``, ``square``, ``clearance``, ``door_swing``, ``windows``, ``access``: the room's own terms
  (``room_terms``); 0 outdoors, where no ``RoomTerms`` is built and they cost nothing.
- ``mask``: only when the problem has a layout mask (``mask_term``): per box it is for,
  the weight times 1 less the mask's mean under its footprint (summed over the masks
  for it, each with its own weight). Without a mask the part
  does not exist (``parts`` has no such key), so layouts without one are unchanged.
- ``learned``: only with a learned context (``learned_term``): per related pair of a
  kind the context has, the learned weights of its relative pose. Without a context the
  part does not exist either.

Tempering: with a context, the sampler takes the ``learned`` part at temperature 1, lets
it stand in for the relation terms of its pairs while a pair's source stands on the
pair's grid, and anneals the rest (``sampler``); ``soft_delta`` is the share of a
proposal's change that is not annealed (the learned part and those relation terms),
``learned_delta`` the learned part's.

``Energy`` caches every term. ``propose`` applies a move to the state and returns the
energy change computed from the terms touching the moved boxes and paths only (the
grid finds the colliding pairs, and in a scene of many paths a second grid the paths a
box may touch); ``accept`` keeps it, ``reject`` undoes it. With
``incremental=False`` it recomputes every term instead (for comparison); either way the
caches the sampler reads (relation energies, troubled boxes) stay current.
Boxes start inactive (absent from the energy) so the constructive placement can add
them one item at a time through the same machinery.
"""

from __future__ import annotations

from typing import Any, NamedTuple

from scenewright.core.geometry import polyline_rect_penetration

from .branches import attach
from .families import evaluate
from .params import LayoutParams
from .problem import Problem
from .relation_terms import Measure
from .room_terms import ROOM_PARTS, RoomChanges, RoomTerms
from .single_terms import SingleTerms
from .state import Grid, State

PARTS = ("relations", "collisions", "paths", "path_shape", "extent") + ROOM_PARTS
#: The part a layout mask adds (after ``PARTS``), present only when there is a mask.
MASK_PART = "mask"
#: The part a learned context adds (last), present only when there is one.
LEARNED_PART = "learned"

#: Scenes with at least this many paths file them in a grid (``Energy.path_grid``); with
#: fewer, testing each path's bounds is cheaper than keeping the grid up to date.
PATH_GRID_MIN = 16


class Changes(NamedTuple):
    """What an incremental proposal changes: the part deltas and the new term values."""

    delta: dict[str, float]  # by part
    relation: dict[int, float]  # by term
    moved: set[int]  # boxes whose pairs and path hits are replaced
    pairs: dict[tuple[int, int], float]  # (box, other): the moved boxes' new collisions
    moved_paths: set[int]  # paths whose hits are replaced
    hits: dict[tuple[int, int], float]  # (box, path): new box-path collisions
    shape: dict[int, float]  # by path
    junction: dict[int, float]  # by junction box
    box_extent: dict[int, float]
    path_extent: dict[int, float]
    room: RoomChanges | None  # the room's terms (None outdoors)
    mask: dict[int, float]  # by box: the moved listed boxes' new mask values
    learned: dict[int, float]  # by learned pair: the new values of the moved boxes' pairs
    measures: dict[int, Measure]  # by term: the measures behind ``relation`` (active terms)


class Pending(NamedTuple):
    """A proposal applied to the state but not yet accepted or rejected."""

    saved_boxes: list[tuple[int, tuple[float, float, float]]]  # poses to restore on reject
    saved_paths: list[tuple[int, list]]  # control points to restore on reject
    update: Changes | dict  # incremental changes, or a full recomputation (``_fresh``)
    filings: dict  # box -> where the grid filed it before (``Grid.filing``), for reject


class Kept(NamedTuple):
    """A proposal's computed update, kept while others are tried (``Energy.kept``)."""

    update: Changes | dict
    delta: float  # the energy change ``propose`` returned (completed when deferred)
    learned_delta: float  # ``Energy.learned_delta`` and ``soft_delta`` it set
    soft_delta: float


class Energy(SingleTerms):
    """Cached energy terms of a state, with propose / accept / reject."""

    def __init__(self, problem: Problem, state: State, params: LayoutParams):
        self.problem, self.state, self.params = problem, state, params
        sizes = sorted(problem.size) or [1.0]
        self.grid = Grid(min(max(2.0 * sizes[len(sizes) // 2], 0.5), 8.0))
        self.active = [False] * problem.n_boxes
        self.collides_with_paths = [
            problem.support[b] == -1 and not problem.is_junction[b] for b in range(problem.n_boxes)
        ]
        self.term_boxes = [frozenset(t.a.members + t.b.members) for t in problem.relations]
        self.placeable = [t.placeable for t in problem.relations]
        self.live = [False] * len(problem.relations)  # relations found active (``relation_active``)
        self._pending: Pending | None = None
        # Per path, its control points' bounding box grown by half its width (x0, x1, z0,
        # z1): a box whose bounding circle misses it cannot touch the path, so the exact
        # test is skipped (it would give 0 too).
        self.path_bounds = [self._path_bounds(path) for path in range(problem.n_paths)]
        # With many paths, the paths filed by those bounds in cells like the boxes', so a
        # box finds the few it may touch from the cells it is filed under.
        self.path_grid = Grid(self.grid.cell) if problem.n_paths >= PATH_GRID_MIN else None
        self.hit_paths: list[set[int]] = [
            set() for _ in range(problem.n_boxes)
        ]  # set by ``_install``
        for path in range(problem.n_paths):
            self._file_path(path)
        #: The room's terms (walls, square, clearance, door swing, access); None outdoors.
        self.room = (
            RoomTerms(problem, state, params, self.active, self.grid)
            if problem.room is not None
            else None
        )
        #: The part names this energy has: ``PARTS``, and ``MASK_PART`` with a mask.
        self.part_names = PARTS + ((MASK_PART,) if problem.mask is not None else ())
        self.part_names += (LEARNED_PART,) if problem.learned is not None else ()
        #: The relation terms the learned part stands in for while sampling (none without one).
        self.tempered = problem.learned.tempered if problem.learned is not None else {}
        #: The pending proposal's change in the learned part and the ``tempered`` terms, and in
        #: the learned part alone.
        self.soft_delta = self.learned_delta = 0.0
        self._install(self._fresh())

    # -- single terms ---------------------------------------------------------------

    def relation_active(self, term_index: int) -> bool:
        """Whether the relation counts yet: both ends placeable and all their boxes placed."""
        if self.live[term_index]:
            return True
        live = self.placeable[term_index] and all(
            self.active[box] for box in self.term_boxes[term_index]
        )
        self.live[term_index] = live  # placed boxes stay placed: once live, always live
        return live

    def relation_energy(self, term_index: int) -> float:
        if not self.relation_active(term_index):
            return 0.0
        return evaluate(self.problem.relations[term_index], self.state, self.params).energy

    def measure(self, term_index: int) -> Measure:
        """``evaluate`` of a relation at the current state (what ``report.assess`` reads).

        Kept from the last time it was measured while none of the boxes and paths it
        reads (``terms_of_box``, ``terms_of_path``: its ends and what may block its view)
        has moved since: ``accept`` drops the measures of the terms a move touches and
        keeps those the move computed. Poses change only through ``propose``, so a kept
        measure is the one ``evaluate`` would give again. Between checks of a chain few
        relations move, and a large scene's check no longer measures them all."""
        kept = self.measures.get(term_index)
        if kept is not None:
            return kept
        measure = evaluate(self.problem.relations[term_index], self.state, self.params)
        if self._pending is None and self.relation_active(term_index):
            self.measures[term_index] = measure
        return measure

    def troubled_boxes(self) -> list[int]:
        """Boxes that currently overlap something or stick out of the extent, and in a
        room those in breach of a room term (``RoomTerms.troubled``)."""
        found = {
            box
            for box in range(self.problem.n_boxes)
            if self.pairs[box] or self.box_extent[box] > 0.0
        }
        for hits in self.path_hits:
            found.update(hits)
        if self.room is not None:
            found.update(self.room.troubled())
        found.update(self.strays())
        return sorted(found)

    def strays(self) -> list[int]:
        """Placed boxes whose centre lies beyond a mask that confines them (``mask_term``)."""
        mask = self.problem.mask
        if mask is None:
            return []
        return [
            box
            for box in range(self.problem.n_boxes)
            if mask.listed[box] and self.active[box] and mask.strays(box, self.state.rects[box])
        ]

    # -- the whole energy -------------------------------------------------------------

    def full(self) -> dict[str, float]:
        """Every part recomputed from scratch (the reference the caches must match)."""
        return self._fresh()["parts"]

    def _fresh(self) -> dict:
        """Every cached term recomputed from scratch, with the parts they sum to."""
        problem = self.problem
        fresh: dict[str, Any] = {
            "relation": [self.relation_energy(t) for t in range(len(problem.relations))],
            "pairs": [{} for _ in range(problem.n_boxes)],
            "path_hits": [{} for _ in range(problem.n_paths)],
            "shape": [self.path_shape_energy(p) for p in range(problem.n_paths)],
            "junction": {j: self.junction_energy(j) for j in problem.paths_of_junction},
            "box_extent": [self.box_extent_energy(b) for b in range(problem.n_boxes)],
            "path_extent": [self.path_extent_energy(p) for p in range(problem.n_paths)],
            "mask": [self.mask_energy(b) for b in range(problem.n_boxes)],
            "learned": [self.learned_energy(k) for k in range(len(problem.learned.pairs))]
            + ([self.balance_energy()] if problem.learned.balance is not None else [])
            if problem.learned
            else [],
        }
        collisions = paths = 0.0
        for box in range(problem.n_boxes):
            if not self.active[box]:
                continue
            for other in self.grid.near_box(box):
                if other > box:
                    value = self.pair_energy(box, other)
                    if value > 0.0:
                        fresh["pairs"][box][other] = fresh["pairs"][other][box] = value
                        collisions += value
            if self.collides_with_paths[box]:
                for path in self.paths_near(box):
                    value = self.path_energy(box, path)
                    if value > 0.0:
                        fresh["path_hits"][path][box] = value
                        paths += value
        fresh["parts"] = {
            "relations": sum(fresh["relation"]),
            "collisions": collisions,
            "paths": paths,
            "path_shape": sum(fresh["shape"]) + sum(fresh["junction"].values()),
            "extent": sum(fresh["box_extent"]) + sum(fresh["path_extent"]),
        }
        fresh["room"] = self.room.fresh() if self.room is not None else None
        for part in ROOM_PARTS:
            fresh["parts"][part] = fresh["room"]["parts"][part] if self.room is not None else 0.0
        if problem.mask is not None:
            fresh["parts"][MASK_PART] = sum(fresh["mask"])
        if problem.learned is not None:
            fresh["parts"][LEARNED_PART] = sum(fresh["learned"])
        return fresh

    def _install(self, fresh: dict) -> None:
        """Make freshly computed terms the cache."""
        self.relation, self.pairs, self.path_hits = (
            fresh["relation"],
            fresh["pairs"],
            fresh["path_hits"],
        )
        self.measures: dict[int, Measure] = {}  # kept relation measures (``measure``)
        # Per box, the paths whose hits hold it (the reverse of ``path_hits``).
        self.hit_paths = [set() for _ in range(self.problem.n_boxes)]
        for path, hits in enumerate(self.path_hits):
            for box in hits:
                self.hit_paths[box].add(path)
        self.shape, self.junction = fresh["shape"], fresh["junction"]
        self.box_extent, self.path_extent = fresh["box_extent"], fresh["path_extent"]
        self.mask = fresh["mask"]
        self.learned = fresh["learned"]
        if self.room is not None:
            self.room.install(fresh["room"])
        self.parts = dict(fresh["parts"])
        self.total = sum(self.parts.values())

    # -- moves ---------------------------------------------------------------------------

    def activate(self, boxes: list[int]) -> None:
        """Bring boxes (at their current poses) into the energy."""
        for box in boxes:
            self.active[box] = True
        self.propose({box: self.state.pose(box) for box in boxes}, {}, entering=True)
        self.accept()

    def propose(
        self,
        boxes: dict,
        paths: dict,
        *,
        entering: bool = False,
        defer_access: bool = False,
        known: Kept | None = None,
    ) -> float:
        """Apply new box poses {box: (x, z, yaw)} and path points {path: points}; return the energy change.

        ``defer_access`` (a room, incremental): the change without the ``access`` part,
        which can fall by at most ``access_floor()`` and is added by ``complete()``; a
        proposal that is rejected on the rest alone never computes it (``sampler``).
        Without a room's access terms, or with ``incremental=False``, the change is whole.
        ``known``: this very proposal's update, ``kept`` when it was last pending (see
        ``repropose``), is taken instead of being computed again.
        """
        state, grid, problem = self.state, self.grid, self.problem
        if paths and problem.branches_of:  # a road's branches move along with it
            paths = attach(problem, state, paths)
        xs, zs, yaws = state.x, state.z, state.yaw
        saved_boxes = [(box, (xs[box], zs[box], yaws[box])) for box in boxes]  # ``State.pose``
        saved_paths = [(path, state.points[path]) for path in paths]
        filings = {}
        active, size, set_pose, spans, keys = (
            self.active,
            problem.size,
            state.set_pose,
            grid.spans,
            grid.keys,
        )
        for box, (x, z, yaw) in boxes.items():
            set_pose(box, x, z, yaw)
            if active[box]:
                if entering:
                    grid.insert(box, x, z, size[box] / 2.0)
                else:
                    filings[box] = (
                        spans[box],
                        keys[box],
                    )  # ``Grid.filing``: an active box is filed
                    grid.move(box, x, z, size[box] / 2.0)
        for path, points in paths.items():
            state.points[path] = points
            self.path_bounds[path] = self._path_bounds(path)
            self._file_path(path)
        if known is not None:
            self._pending = Pending(saved_boxes, saved_paths, known.update, filings)
            if self.problem.learned is not None:
                self.learned_delta, self.soft_delta = known.learned_delta, known.soft_delta
            return known.delta
        if not self.params.incremental:
            fresh = self._fresh()
            self._pending = Pending(saved_boxes, saved_paths, fresh, filings)
            if self.problem.learned is not None:
                self.learned_delta = fresh["parts"][LEARNED_PART] - self.parts[LEARNED_PART]
                self.soft_delta = self.learned_delta + self._soft_relations(
                    {t: fresh["relation"][t] for t in self.tempered}, dict(saved_boxes)
                )
            return sum(fresh["parts"].values()) - self.total
        changes = self._changes(
            list(boxes), list(paths), _translated_together(saved_boxes, boxes), defer_access
        )
        self._pending = Pending(saved_boxes, saved_paths, changes, filings)
        if self.problem.learned is not None:
            self.learned_delta = changes.delta[LEARNED_PART]
            self.soft_delta = self.learned_delta + self._soft_relations(
                changes.relation, dict(saved_boxes)
            )
        return sum(changes.delta.values())

    def _soft_relations(
        self, new_relation: dict[int, float], saved: dict[int, tuple[float, float, float]]
    ) -> float:
        """The change in the tempered relation terms among ``new_relation`` (term -> new
        value) that is sampled with the learned part: a term counts while its pair's
        source stands on the pair's grid (``CompiledLearned.on_grid``), before the move
        at the ``saved`` poses of the moved boxes, after it at the state's."""
        learned, tempered, pose, relation = (
            self.problem.learned,
            self.tempered,
            self.state.pose,
            self.relation,
        )
        assert learned is not None  # soft terms exist with a context only

        def before(box: int) -> tuple[float, float, float]:
            return saved[box] if box in saved else pose(box)

        sides: dict[int, tuple[bool, bool]] = {}  # per pair: on its grid after the move, before it
        change = 0.0
        for t, value in new_relation.items():
            pair = tempered.get(t)
            if pair is None:
                continue
            if pair not in sides:
                source, target, _ = learned.pairs[pair]
                sides[pair] = (
                    learned.on_grid(pair, pose(source), pose(target)),
                    learned.on_grid(pair, before(source), before(target)),
                )
            after, earlier = sides[pair]
            if after:
                change += value
            if earlier:
                change -= relation[t]
        return change

    def _changes(
        self, boxes: list[int], paths: list[int], together: bool, defer_access: bool = False
    ) -> Changes:
        """New values of every term touching the moved boxes and paths, and the part deltas.

        When the boxes moved ``together`` (one shared translation, no turn), terms and
        pairs among themselves cannot have changed and keep their cached values.
        ``defer_access``: see ``propose``.
        """
        problem, active = self.problem, self.active
        moved = set(boxes)
        moved_paths = set(paths)
        delta = dict.fromkeys(self.part_names, 0.0)
        # Each part's change is summed in a local, in the order the terms come (the same sums).

        terms: set[int] = set()
        for box in boxes:
            terms.update(problem.terms_of_box[box])
        for path in paths:
            terms.update(problem.terms_of_path[path])
        new_relation, new_measures = {}, {}
        relations, term_boxes, relation, state, params = (
            problem.relations,
            self.term_boxes,
            self.relation,
            self.state,
            self.params,
        )
        live = self.live
        change = 0.0
        for term in sorted(terms):
            if together and not relations[term].reads_fixed_geometry and term_boxes[term] <= moved:
                continue
            if live[term] or self.relation_active(
                term
            ):  # ``relation_energy``, its measure kept for ``accept``
                measure = new_measures[term] = evaluate(relations[term], state, params)
                value = measure.energy
            else:
                value = 0.0
            new_relation[term] = value
            change += value - relation[term]
        delta["relations"] = change

        new_pairs: dict[tuple[int, int], float] = {}
        pairs, near_box, pair_depth, penalty = (
            self.pairs,
            self.grid.near_box,
            self.pair_depth,
            self.penalty,
        )
        change = 0.0
        for box in boxes:
            if not active[box]:
                continue
            for other, value in pairs[box].items():
                if other not in moved:
                    change -= value
                elif other > box:
                    if together:
                        new_pairs[(box, other)] = value
                    else:
                        change -= value
            for other in near_box(box):
                if other == box or (other in moved and (other < box or together)):
                    continue
                depth = pair_depth(box, other)  # ``pair_energy``, unfolded: most pairs are apart
                if depth > 0.0:
                    value = penalty(depth)
                    if value > 0.0:
                        new_pairs[(box, other)] = value
                        change += value
        delta["collisions"] = change

        new_hits: dict[tuple[int, int], float] = {}
        path_bounds, path_hits, collides, xs, zs, size = (
            self.path_bounds,
            self.path_hits,
            self.collides_with_paths,
            self.state.x,
            self.state.z,
            problem.size,
        )
        change = 0.0
        path_width, points, rects = problem.path_width, self.state.points, self.state.rects
        for box in boxes:
            if active[box] and collides[box] and path_bounds:
                x, z, radius = xs[box], zs[box], size[box] / 2.0
                # Paths it was off and may not touch now would add 0 (an old hit of 0 and
                # the skip below): only the others are visited, in order.
                for path in self._paths_to_test(box):
                    x0, x1, z0, z1 = path_bounds[path]
                    change -= path_hits[path].get(box, 0.0)
                    if x + radius < x0 or x - radius > x1 or z + radius < z0 or z - radius > z1:
                        continue  # cannot touch it (``may_touch_path``, inlined: this runs every step)
                    width = path_width[path]  # ``path_energy``, its test just made
                    depth = polyline_rect_penetration(points[path], width / 2.0, rects[box]) / (
                        size[box] + width
                    )
                    if depth > 0.0:
                        value = penalty(depth)
                        if value > 0.0:
                            new_hits[(box, path)] = value
                            change += value
        for path in paths:
            for box, value in path_hits[path].items():
                if box not in moved:
                    change -= value
            for box in self._boxes_near_path(path):
                if box not in moved and collides[box]:
                    value = self.path_energy(box, path)
                    if value > 0.0:
                        new_hits[(box, path)] = value
                        change += value
        delta["paths"] = change

        new_shape = {}
        change = 0.0
        for path in paths:
            new_shape[path] = self.path_shape_energy(path)
            change += new_shape[path] - self.shape[path]
        new_junction = {}
        junctions = self.junction
        if paths:
            touched = {problem.path_start[p] for p in paths if problem.path_start[p] >= 0} | (
                moved & junctions.keys()
            )
        else:  # the moved boxes that are junctions (most moves: none), no set made
            touched = [box for box in boxes if box in junctions] if junctions else ()
        if touched:
            for junction in sorted(touched):
                new_junction[junction] = self.junction_energy(junction)
                change += new_junction[junction] - self.junction[junction]
        delta["path_shape"] = change

        new_box_extent = {}
        box_extent = self.box_extent
        change = 0.0
        outdoors, intensity = (
            self.room is None,
            self.params.collision_intensity,
        )  # ``box_extent_energy``:
        for box in boxes:
            value = (
                intensity * self.box_excess(box) / size[box] if active[box] and outdoors else 0.0
            )
            new_box_extent[box] = value
            change += value - box_extent[box]
        new_path_extent = {}
        for path in paths:
            new_path_extent[path] = self.path_extent_energy(path)
            change += new_path_extent[path] - self.path_extent[path]
        delta["extent"] = change
        room = None
        if self.room is not None and boxes:
            room = self.room.changes(boxes, defer_access)
            delta.update(room.delta)
        new_mask = {}
        if problem.mask is not None:
            for box in boxes:
                if problem.mask.listed[box]:
                    new_mask[box] = self.mask_energy(box)
                    delta[MASK_PART] += new_mask[box] - self.mask[box]
        new_learned = {}
        if problem.learned is not None:
            learned_pairs = problem.learned.pairs
            for pair in sorted({k for box in boxes for k in problem.learned.pairs_of_box[box]}):
                source, target, _ = learned_pairs[pair]
                if together and source in moved and target in moved:
                    continue  # a shared translation keeps the relative pose
                new_learned[pair] = self.learned_energy(pair)
                delta[LEARNED_PART] += new_learned[pair] - self.learned[pair]
            balance = problem.learned.balance
            if balance is not None and boxes:
                index = len(learned_pairs)  # the balance term's value follows the pairs'
                new_learned[index] = self.balance_energy()
                delta[LEARNED_PART] += new_learned[index] - self.learned[index]
        return Changes(
            delta,
            new_relation,
            moved,
            new_pairs,
            moved_paths,
            new_hits,
            new_shape,
            new_junction,
            new_box_extent,
            new_path_extent,
            room,
            new_mask,
            new_learned,
            new_measures,
        )

    def kept(self, delta: float) -> Kept | None:
        """The pending proposal's computed update (its energy change ``delta`` as its caller
        took it), to be put back by ``repropose`` after it is rejected and others are
        tried; None when it holds a room's part (its access part may have been deferred
        and completed, which ``repropose`` would not redo the same way)."""
        assert self._pending is not None  # called on a pending proposal
        update = self._pending.update
        if self.room is not None:
            return None
        learned = (
            (self.learned_delta, self.soft_delta)
            if self.problem.learned is not None
            else (0.0, 0.0)
        )
        return Kept(update, delta, *learned)

    def repropose(self, proposal: tuple[dict, dict], kept: Kept | None) -> float:
        """``propose(*proposal)`` once more, after it was rejected and only other
        proposals (all rejected) came between: the state it meets is the one it met then
        (poses, path points and bounds, the grids' cell lists, in the same order: a
        rejected move's boxes and paths go back last in the cells they left, and a
        proposal puts them last in the cells it files them under), so its update is the
        one ``kept`` holds and is not computed again. Without one, it is computed."""
        if kept is None:
            return self.propose(*proposal)
        return self.propose(*proposal, known=kept)

    def access_floor(self) -> float:
        """How far the pending proposal's deferred ``access`` part can lower the energy at
        most (0 when nothing was deferred): all of the access part there is now."""
        room = (
            self._pending.update.room
            if self._pending is not None and not isinstance(self._pending.update, dict)
            else None
        )
        if room is None or not room.deferred:
            return 0.0
        assert self.room is not None  # a room's changes come from the room's terms
        return self.room.access_total()

    def complete(self) -> float:
        """The pending proposal's whole energy change, its deferred ``access`` part added
        (the same number ``propose`` gives without deferring)."""
        changes = self._add_deferred_access()
        if isinstance(changes, dict):
            return sum(changes["parts"].values()) - self.total
        return sum(changes.delta.values())

    def _add_deferred_access(self) -> Changes | dict:
        """The pending proposal's update, with its deferred ``access`` part evaluated
        (at most once) when ``propose`` left it out."""
        pending = self._pending
        assert pending is not None  # called on a pending proposal
        changes = pending.update
        if not isinstance(changes, dict) and changes.room is not None and changes.room.deferred:
            assert self.room is not None  # a room's changes come from the room's terms
            room = self.room.access_changes(changes.room, [box for box, _ in pending.saved_boxes])
            changes.delta["access"] = room.delta["access"]
            changes = changes._replace(room=room)
            self._pending = pending._replace(update=changes)
        return changes

    def _boxes_near_path(self, path: int) -> list[int]:
        x0, x1, z0, z1 = self.path_bounds[path]
        return sorted(self.grid.in_area(x0, z0, x1, z1))

    def accept(self) -> None:
        """Keep the proposed move: store its term values."""
        self._add_deferred_access()  # a deferred access part is evaluated before it is kept
        pending, self._pending = self._pending, None
        assert pending is not None  # called on a pending proposal
        if isinstance(pending.update, dict):
            self._install(pending.update)
            return
        changes, moved = pending.update, pending.update.moved
        for term, value in changes.relation.items():
            self.relation[term] = value
        measures, problem = self.measures, self.problem
        for box in moved:  # what the move touched is measured anew (``measure``) ...
            for term in problem.terms_of_box[box]:
                measures.pop(term, None)
        for path in changes.moved_paths:
            for term in problem.terms_of_path[path]:
                measures.pop(term, None)
        measures.update(changes.measures)  # ... but for what it measured already
        for box in moved:
            for other in self.pairs[box]:
                if other not in moved:
                    del self.pairs[other][box]
            self.pairs[box] = {}
        for (box, other), value in changes.pairs.items():
            self.pairs[box][other] = value
            self.pairs[other][box] = value
        path_hits, hit_paths = self.path_hits, self.hit_paths
        for path in changes.moved_paths:
            for box in path_hits[path]:
                hit_paths[box].discard(path)
            path_hits[path].clear()
        for box in moved:
            for path in hit_paths[box]:
                path_hits[path].pop(box, None)
            hit_paths[box].clear()
        for (box, path), value in changes.hits.items():
            path_hits[path][box] = value
            hit_paths[box].add(path)
        for path, value in changes.shape.items():
            self.shape[path] = value
        self.junction.update(changes.junction)
        for box, value in changes.box_extent.items():
            self.box_extent[box] = value
        for path, value in changes.path_extent.items():
            self.path_extent[path] = value
        if changes.room is not None:
            assert self.room is not None  # a room's changes come from the room's terms
            self.room.accept(changes.room)
        for box, value in changes.mask.items():
            self.mask[box] = value
        for pair, value in changes.learned.items():
            self.learned[pair] = value
        for part, value in changes.delta.items():
            self.parts[part] += value
        self.total = sum(self.parts.values())

    def reject(self) -> None:
        """Undo the proposed move."""
        pending, self._pending = self._pending, None
        assert pending is not None  # called on a pending proposal
        state, grid, problem = self.state, self.grid, self.problem
        filings = pending.filings
        for box, (x, z, yaw) in pending.saved_boxes:
            state.set_pose(box, x, z, yaw)
            if self.active[box]:
                grid.move(box, x, z, problem.size[box] / 2.0, filings.get(box))
        for path, points in pending.saved_paths:
            state.points[path] = points
            self.path_bounds[path] = self._path_bounds(path)
            self._file_path(path)


def _translated_together(saved: list, boxes: dict) -> bool:
    """True when every moved box was shifted by the same vector and none turned."""
    if len(saved) < 2:
        return False
    first, (x0, z0, yaw0) = saved[0]
    nx, nz, nyaw = boxes[first]
    dx, dz = nx - x0, nz - z0
    for box, (x, z, yaw) in saved:
        new_x, new_z, new_yaw = boxes[box]
        if new_yaw != yaw or new_x - x != dx or new_z - z != dz:
            return False
    return True
