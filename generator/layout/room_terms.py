"""The energy terms a room adds to the layout, with their geometry and their caches.

Six parts, all 0 outdoors (``problem.room`` None: ``energy.py`` then builds no
``RoomTerms`` and the parts cost nothing):

- ``walls``: c * (how far a box's footprint crosses the walls / its diagonal), c the
  collision intensity; the room's polygon replaces the rectangular extent for boxes, so a
  box in an L-shaped room cannot cross the inner corner.
- ``square``: per box (not junctions) -equals(off, 0, SQUARE_SIGMA2), ``off`` its yaw's
  angle off the nearest wall axis (a multiple of 90 degrees from some wall's direction).
- ``clearance``: per free zone a box keeps beside it (``problem.clearance``) and per
  other ground box standing in it, the collision penalty of their overlap; plus, for a
  zone that crosses a wall, the penalty of how far it does.
- ``door_swing``: per door and ground box standing in its swing, the collision penalty.
- ``windows``: per window and ground box standing in front of it (``view_rect``) whose
  top rises more than WINDOW_VIEW_MARGIN above the sill, the collision penalty: a
  wardrobe or a piano is not put against a window when another place will do. The
  verdict reports such a box unless a wall relation of its own names the window's wall
  or the window (``_asked_views``): a rule may leave the box nowhere else.
- ``access``: per box that needs reaching (``problem.access`` not empty) and cannot be
  reached on foot from a door, ACCESS_BASE + ACCESS_SLOPE * its distance (metres, in
  whole cells) to the floor that can; the same per door after the first that cannot be
  reached from it. Global: any obstacle that moves can open or close a way. 0 in a room
  without a door (nothing is reached from nowhere).

Reachability is decided on the room's occupancy grid (``reachability.AccessGrid``):
the reachable floor is the free floor connected to the first door's opening
(``AccessGrid.rooted``). The verdict also judges the floor as SceneEval does
(``reachability.floor_verdict``): a door off the free floor's largest part, or less than
NAVIGABLE_SHARE of the free floor on it, is a problem.

Incremental evaluation (``RoomTerms.changes``) re-evaluates only the moved boxes' own
terms and the clearance zones they own or stand in. Access keeps the reachable floor
of the current layout; after a move it is updated from the old one (``_reach_after``:
take out the moved boxes' windows where that provably cuts no way, then grow what is
left back over the free floor), or grown from the doors when that proof fails. A full
recomputation (``RoomTerms.fresh``) labels the free floor instead
(``scipy.ndimage.label``); both give the same cells, so the same values, exactly.
"""

from __future__ import annotations

import math
from typing import NamedTuple

from scenewright.core.geometry import Rect, rect_penetration
from scenewright.core.room import Room

from .factors import equals
from .params import LayoutParams
from .problem import FLAT_HEIGHT, Problem
from .reachability import (
    CORRIDOR_HALF,
    FloorVerdict,
    Raster,
    access_grid,
    bounds,
    floor_verdict,
)
from .room_zones import (
    WINDOW_VIEW_MARGIN,
    KeptZone,
    Walls,
    kept_zone,
    penalty,
    square_off,
    swing_rect,
    view_rect,
    wall_axes,
    zone_rect,
)
from .state import Grid, State

#: The parts a room adds to the energy, in the order ``energy.PARTS`` lists them.
ROOM_PARTS = ("walls", "square", "clearance", "door_swing", "windows", "access")


#: The square term's Gaussian width (radians^2): off^2 / (2 * 0.05) costs 0.69 at 15
#: degrees off the walls, 2.7 at 30 and 6.2 at 45 (the most a yaw can be off).
SQUARE_SIGMA2 = 0.05

#: Growths (cells) of a moved box's window tried in turn by the incremental proof that
#: it cuts no way (``RoomTerms._reach_after``) before growing the reachable floor from
#: the doors.
CUT_TEST_GROWTH = (0, 3, 8, 16, 32)
#: Energy of a box nobody can reach: a constant (as much as a clearly broken relation)
#: plus a slope per metre between its access sides and the reachable floor, so moves
#: that bring it nearer the way in are favoured.
ACCESS_BASE = 3.0
ACCESS_SLOPE = 3.0
#: The verdict's least share of the free floor in its largest part (SceneEval's
#: navigability, ``reachability.floor_verdict``): less is a problem, and the boxes
#: round the floor cut off are troubled (``RoomTerms.troubled``). No energy scores the
#: share: the chain runs on until a check finds the floor whole enough, which leaves the
#: rooms that never cut their floor as they were (an energy per square metre cut off
#: cost bedrooms steps and was not needed: docs/notes/design.md, "The floor in one piece").
NAVIGABLE_SHARE = 0.99

#: Slack (metres) of the verdicts in ``problems``: crossing a wall, standing in a door's
#: swing or in a kept-free zone by at most 1 cm still counts as clear.
ROOM_TOLERANCE = 0.01

#: The sides a clearance zone or an access side may name, and how the report says them.
SIDES = ("front", "back", "left", "right")
SIDE_WORDS = {
    "front": "in front of",
    "back": "behind",
    "left": "to the left of",
    "right": "to the right of",
}


class AccessState(NamedTuple):
    """Reachability as the energy knows it: ``reach``, the plane of the floor reachable
    from the first door; per placed box that needs reaching a ``witness`` (a bit of
    ``reach`` among its access cells, None when it is unreachable) and its energy
    (``values``); per unreachable box its distance to the reachable floor in cells
    (``apart``); per other door its energy (``doors``: ACCESS_BASE and the slope, as for
    a box, when none of its door cells is reached) and, unreached, its distance
    (``door_apart``)."""

    reach: int
    witness: dict[int, int | None]
    values: dict[int, float]
    apart: dict[int, int]
    doors: dict[int, float]
    door_apart: dict[int, int]

    @property
    def total(self) -> float:
        """The access part: every box's and every door's energy."""
        return sum(self.values.values()) + sum(self.doors.values())


#: Reachability before anything is evaluated.
NO_ACCESS = AccessState(0, {}, {}, {}, {}, {})


class AccessChanges(NamedTuple):
    """Reachability after a proposal, and the moved obstacles' new cells (planes)."""

    state: AccessState
    taken: dict[int, int]


class RoomChanges(NamedTuple):
    """What a proposal changes in the room's terms."""

    delta: dict[str, float]  # by part
    moved: set[int]
    walls: dict[int, float]  # by box
    square: dict[int, float]
    swing: dict[int, float]
    view: dict[int, float]
    zones: set[int]  # zones whose owner moved: all their hits are replaced
    hits: dict[tuple[int, int], float]  # (zone, box): new clearance overlaps
    zone_wall: dict[int, float]  # by zone
    access: (
        AccessChanges | None
    )  # None: reachability unchanged (or not yet evaluated: ``deferred``)
    deferred: bool = False  # reachability left for ``access_changes`` (``RoomTerms.changes``)


class RoomTerms:
    """The room's energy terms for one problem: static geometry and cached values."""

    def __init__(
        self, problem: Problem, state: State, params: LayoutParams, active: list[bool], grid: Grid
    ):
        self.problem, self.state, self.params, self.active, self.grid = (
            problem,
            state,
            params,
            active,
            grid,
        )
        room = problem.indoors()
        self.room = room
        self.walls_geometry = Walls(room)
        self.axes = wall_axes(room)
        #: Reached from the first door: the floor it reaches is one piece (``rooted``).
        self.access_grid = access_grid(room).rooted()
        #: Whether reachability is scored: in a room with a door (from nowhere nothing is
        #: reached), whether or not some box needs reaching, since every door must lead
        #: onto the floor the first one does.
        self.scored = self.access_grid.has_doors
        #: The doors with door cells other than the one the reachable floor grows from:
        #: each must be reached from it.
        cells = self.access_grid
        self.far_doors = [
            d for d, seeds in enumerate(cells.door_seeds) if seeds and d != cells.root
        ]
        n = problem.n_boxes
        ground = [problem.support[b] == -1 and not problem.is_junction[b] for b in range(n)]
        #: Tall boxes on the floor or on a floor covering (a chair on a rug): they block
        #: corridors, door swings and clearance zones, as SceneEval counts every tall box
        #: within 1 cm of the floor.
        standing = [
            not problem.is_junction[b] and all(problem.covering[s] for s in problem.beneath(b))
            for b in range(n)
        ]
        self.obstacle = [standing[b] and problem.height[b] > FLAT_HEIGHT for b in range(n)]
        self.obstacles = [b for b in range(n) if self.obstacle[b]]
        #: Boxes someone must reach, and the sides they use ((("any",) for any side).
        #: A table a seat stands at is used by the person on that seat: reaching the
        #: seat (which needs reaching itself) reaches the table, so the way to the
        #: table's side does not push the seat off it.
        seated = {
            t.b.index
            for t in problem.relations
            if t.spec.seat and t.a.kind == "object" and t.b.kind == "object"
        }
        self.needs_access = [
            ground[b] and bool(problem.access[b]) and b not in seated for b in range(n)
        ]
        self.access_boxes = (
            [b for b in range(n) if self.needs_access[b]] if self.access_grid.has_doors else []
        )
        self.swings = [(door.id, swing_rect(room, door)) for door in room.doors]
        #: Zones kept free of tall boxes (``kept_zone``): each door's swing, and each
        #: window's view with the lowest top that blocks it.
        self.swing_zones = [kept_zone(rect) for _, rect in self.swings]
        self.views = [
            (kept_zone(view_rect(room, w)), w.sill + WINDOW_VIEW_MARGIN) for w in room.windows
        ]
        #: (box, window index) pairs the rules put there: a wall relation naming the
        #: window's wall or the window itself. Only there may a tall box stand before it.
        self.asked_views = _asked_views(problem, room)
        # Clearance zones: (owner, side, metres) each; per box the zones it owns.
        self.zones: list[tuple[int, str, float]] = []
        self.zones_of: list[list[int]] = [[] for _ in range(n)]
        for box in range(n):
            if problem.is_junction[box]:
                continue
            for side, metres in problem.clearance[box]:
                if side in SIDES and metres > 0.0:
                    self.zones_of[box].append(len(self.zones))
                    self.zones.append((box, side, float(metres)))
        self.zone_reach = max((m for _, _, m in self.zones), default=0.0)
        #: Each zone's diagonal, the normaliser of depths into it.
        self.zone_sizes = [
            math.hypot(
                2.0
                * (problem.half_width[o] if side in ("front", "back") else problem.half_depth[o]),
                m,
            )
            for o, side, m in self.zones
        ]
        # Who may stand in a box's zones anyway: its relation partners (a chair pulled up
        # to a desk) and what it rests on.
        partners: list[set[int]] = [set() for _ in range(n)]
        for term in problem.relations:
            for a in term.a.members:
                for b in term.b.members:
                    partners[a].add(b)
                    partners[b].add(a)
        self.exempt = [partners[b] | set(problem.beneath(b)) | {b} for b in range(n)]
        self.intensity = params.collision_intensity
        # Rasters of each box at the last two poses they were made for: box -> [(pose, Raster)].
        self._obstacle_memo: dict[int, list[tuple[tuple, Raster]]] = {}
        self._access_memo: dict[int, list[tuple[tuple, Raster]]] = {}
        #: Proposals that moved an obstacle (``evaluated``), and those of them whose
        #: reachable floor was found from the doors anew (``labelled``): for the benchmark.
        self.labelled = self.evaluated = 0

    # -- single terms ------------------------------------------------------------------

    def wall_excess(self, box: int) -> float:
        return self.walls_geometry.excess(self.state.rects[box])

    def wall_energy(self, box: int) -> float:
        if not self.active[box]:
            return 0.0
        return self.intensity * self.wall_excess(box) / self.problem.size[box]

    def square_energy(self, box: int) -> float:
        if not self.active[box] or not self.problem.square or self.problem.is_junction[box]:
            return 0.0
        return -equals(square_off(self.state.yaw[box], self.axes), 0.0, SQUARE_SIGMA2)

    def swing_depth(self, door: int, box: int) -> float:
        """Planar depth (metres) of a box in a door's swing zone."""
        return rect_penetration(self.swings[door][1], self.state.rects[box])

    def swing_energy(self, box: int) -> float:
        if not self.active[box] or not self.obstacle[box]:
            return 0.0
        return self.zones_energy(box, self.swing_zones)

    def view_energy(self, box: int) -> float:
        """What a ground box standing in front of a window, and taller than its sill by
        more than WINDOW_VIEW_MARGIN, pays (module docstring)."""
        if not self.active[box] or not self.obstacle[box] or not self.views:
            return 0.0
        top = self.state.y[box] + self.problem.height[box]
        return self.zones_energy(box, [zone for zone, lowest in self.views if top > lowest])

    def zones_energy(self, box: int, zones: list[KeptZone]) -> float:
        """The collision penalty of the box in each of ``zones``, its depth in the zone
        over the two diagonals."""
        size = self.problem.size[box]
        rect = self.state.rects[box]
        x0, z0, x1, z1 = bounds(rect)
        energy = 0.0
        for zone in zones:
            zx0, zz0, zx1, zz1 = zone.bounds
            if x1 <= zx0 or zx1 <= x0 or z1 <= zz0 or zz1 <= z0:
                continue
            depth = rect_penetration(zone.rect, rect)
            if depth > 0.0:
                energy += penalty(depth / (zone.diagonal + size), self.intensity)
        return energy

    def zone(self, zone: int) -> Rect:
        owner, side, metres = self.zones[zone]
        return zone_rect(self.state.rects[owner], side, metres)

    def intrudes(self, zone: int, box: int) -> bool:
        """Whether ``box`` counts when it stands in ``zone``: a tall ground box, placed,
        neither the owner nor a partner of it nor under it."""
        return (
            self.obstacle[box] and self.active[box] and box not in self.exempt[self.zones[zone][0]]
        )

    def zone_depth(self, zone: int, rect: Rect, box: int) -> float:
        """Planar depth (metres) of a box in a zone at ``rect``."""
        return rect_penetration(rect, self.state.rects[box])

    def zone_hit_energy(self, zone: int, rect: Rect, box: int) -> float:
        depth = self.zone_depth(zone, rect, box)
        if depth <= 0.0:
            return 0.0
        return penalty(depth / (self.zone_sizes[zone] + self.problem.size[box]), self.intensity)

    def zone_wall_energy(self, zone: int, rect: Rect) -> float:
        excess = self.walls_geometry.excess(rect)
        return penalty(excess / self.zone_sizes[zone], self.intensity) if excess > 0.0 else 0.0

    def _zone_candidates(self, rect: Rect) -> set[int]:
        return self.grid.in_area(*bounds(rect))

    def _owners_near(self, box: int) -> set[int]:
        """Boxes whose zones may reach ``box``: owners within the longest zone of it."""
        return self.grid.in_area(*bounds(self.state.rects[box], self.zone_reach))

    # -- reachability -------------------------------------------------------------------

    def obstacle_cells(self, box: int) -> Raster:
        """The cells the box takes from the free floor at its current pose."""
        return self._memoised(
            self._obstacle_memo, box, lambda rect: self.access_grid.obstacle(rect)
        )

    def access_cells(self, box: int) -> Raster:
        """The cells a person may use the box from at its current pose."""
        sides = self.problem.access[box]
        return self._memoised(
            self._access_memo, box, lambda rect: self.access_grid.access(rect, sides)
        )

    def _memoised(self, memo: dict, box: int, make) -> Raster:
        """A raster of the box at its current pose, made by ``make(rect)`` unless it is
        one of the last two made (a rejected proposal comes back to the pose before)."""
        pose = self.state.pose(box)
        entries = memo.setdefault(box, [])
        for known, raster in entries:
            if known == pose:
                return raster
        raster = make(self.state.rects[box])
        entries.insert(0, (pose, raster))
        del entries[2:]
        return raster

    def free(self) -> int:
        """The free floor: static floor no placed tall box takes."""
        used = 0
        for bits in self.taken:
            used |= bits
        return self.access_grid.static & ~used

    def find_witness(self, box: int, reach: int) -> int | None:
        """A bit of ``reach`` among the box's access cells, or None."""
        hit = reach & self.access_cells(box).bits
        return (hit & -hit).bit_length() - 1 if hit else None

    def _evaluate_access(
        self, reach: int, known: AccessState, moved: set[int], same: bool
    ) -> AccessState:
        """Every placed access box's witness and energy on the reachable floor ``reach``,
        and every other door's. ``known``: the witnesses and values before, still good
        for a box that has not ``moved`` if its witness is in ``reach`` (and, unreachable,
        if ``reach`` is the ``same`` as before); an unreached door's distance likewise."""
        old_witness, old_values = known.witness, known.values
        witness: dict[int, int | None] = {}
        values: dict[int, float] = {}
        apart: dict[int, int] = {}
        unreachable = []
        for box in self.access_boxes:
            if not self.active[box]:
                continue
            if box not in moved and box in old_witness:
                cell = old_witness[box]
                if cell is not None and (reach >> cell) & 1:
                    witness[box], values[box] = cell, 0.0
                    continue
                if cell is None and same:  # unreachable before, and nothing changed
                    witness[box], values[box], apart[box] = None, old_values[box], known.apart[box]
                    continue
            witness[box] = cell = self.find_witness(box, reach)
            values[box] = 0.0
            if cell is None:
                unreachable.append(box)
        grid = self.access_grid
        target = reach or grid.seeds or grid.static  # nothing reachable: how far from a door
        for box in unreachable:
            cells = grid.distance(target, self.access_cells(box).window, known.apart.get(box))
            apart[box] = cells
            values[box] = ACCESS_BASE + ACCESS_SLOPE * cells * grid.cell
        doors: dict[int, float] = {}
        door_apart: dict[int, int] = {}
        for door in self.far_doors:
            if reach & grid.door_seeds[door]:
                doors[door] = 0.0
                continue
            if same and door in known.door_apart:
                cells = known.door_apart[door]
            else:
                cells = grid.distance(target, grid.door_windows[door], known.door_apart.get(door))
            door_apart[door] = cells
            doors[door] = ACCESS_BASE + ACCESS_SLOPE * cells * grid.cell
        return AccessState(reach, witness, values, apart, doors, door_apart)

    def _reach_after(self, moved: list[int]) -> tuple[int, dict[int, int]]:
        """The reachable floor with the moved obstacles at their new poses, computed from
        the reachable floor before (exact), and the moved obstacles' new cells.

        Take the window of each moved obstacle whose new cells meet the reachable floor
        (its cells' bounding box) out of the reachable floor (one that lands on none of it
        leaves it whole: what it freed can only add to it); that cuts no way when the reachable cells on the ring just
        outside the window form at most one arc (a way through the window can go round
        along it) and, if the window holds door cells, the arc holds one too (else the
        floor beyond might have been reached only through the door cells taken out). A
        window that fails is tried again grown by CUT_TEST_GROWTH cells (a box in a gap
        between two others: round both). What is left is reachable, so growing it (with
        the door cells) over the free floor gives the reachable floor exactly, in as many
        rounds as the farthest cell the moves freed is from it. When no window passes, the
        reachable floor is found from the doors alone (``AccessGrid.reachable``).
        """
        grid = self.access_grid
        taken = {box: self.obstacle_cells(box).bits for box in moved}
        used = 0
        for box, bits in enumerate(self.taken):
            used |= taken[box] if box in taken else bits
        free = grid.static & ~used
        reach = self.access.reach
        for box in moved:
            if not taken[box] & reach:  # it lands on no reachable cell: nothing to take out
                continue
            window = self.obstacle_cells(box).window  # on the floor's grid
            if window[0] == window[1] or window[2] == window[3]:
                continue
            for grow in CUT_TEST_GROWTH:
                wider = grid.widen(window, grow)
                if grid.ring_single(reach, wider) and grid.keeps_a_door(reach, wider):
                    reach &= ~grid.window_plane(wider)
                    break
            else:
                self.labelled += 1
                return grid.reachable(free), taken
        return grid.flood(reach | (grid.seeds & free), free), taken

    def _access_changes(self, boxes: list[int]) -> AccessChanges | None:
        """Reachability after a proposal moved ``boxes``, or None if it cannot have changed."""
        moved = set(boxes)
        obstacles = [b for b in boxes if self.obstacle[b] and self.active[b]]
        if obstacles:
            self.evaluated += 1
            reach, taken = self._reach_after(obstacles)
            return AccessChanges(
                self._evaluate_access(reach, self.access, moved, reach == self.access.reach), taken
            )
        if any(self.needs_access[b] for b in boxes):
            return AccessChanges(
                self._evaluate_access(self.access.reach, self.access, moved, True), {}
            )
        return None

    # -- caches ---------------------------------------------------------------------------

    def fresh(self) -> dict:
        """Every room term recomputed from scratch (no cached value is read or changed;
        only the per-pose memos of rasters, pure functions of the pose, are shared)."""
        problem = self.problem
        n = problem.n_boxes
        walls = [self.wall_energy(b) for b in range(n)]
        square = [self.square_energy(b) for b in range(n)]
        swing = [self.swing_energy(b) for b in range(n)]
        view = [self.view_energy(b) for b in range(n)]
        zone_hits: list[dict[int, float]] = [{} for _ in self.zones]
        hits_of: list[dict[int, float]] = [{} for _ in range(n)]
        zone_wall = [0.0] * len(self.zones)
        for zone, (owner, _, _) in enumerate(self.zones):
            if not self.active[owner]:
                continue
            rect = self.zone(zone)
            zone_wall[zone] = self.zone_wall_energy(zone, rect)
            for other in range(n):
                if self.intrudes(zone, other):
                    value = self.zone_hit_energy(zone, rect, other)
                    if value > 0.0:
                        zone_hits[zone][other] = hits_of[other][zone] = value
        access = NO_ACCESS
        taken = [
            self.obstacle_cells(b).bits if self.obstacle[b] and self.active[b] else 0
            for b in range(n)
        ]
        if self.scored:
            used = 0
            for bits in taken:
                used |= bits
            reach = self.access_grid.label(self.access_grid.static & ~used)
            access = self._evaluate_access(reach, access, set(), False)
        parts = {
            "walls": sum(walls),
            "square": sum(square),
            "clearance": sum(sum(h.values()) for h in zone_hits) + sum(zone_wall),
            "door_swing": sum(swing),
            "windows": sum(view),
            "access": access.total,
        }
        return {
            "walls": walls,
            "square": square,
            "swing": swing,
            "view": view,
            "zone_hits": zone_hits,
            "hits_of": hits_of,
            "zone_wall": zone_wall,
            "taken": taken,
            "access": access,
            "parts": parts,
        }

    def install(self, fresh: dict) -> None:
        """Make freshly computed values the cache."""
        self.walls, self.square, self.swing, self.view = (
            fresh["walls"],
            fresh["square"],
            fresh["swing"],
            fresh["view"],
        )
        self.zone_hits, self.hits_of, self.zone_wall = (
            fresh["zone_hits"],
            fresh["hits_of"],
            fresh["zone_wall"],
        )
        self.taken, self.access = fresh["taken"], fresh["access"]

    def changes(self, boxes: list[int], defer_access: bool = False) -> RoomChanges:
        """New values of the room terms the moved boxes touch (state and broad-phase grid
        already at the proposal), with the part deltas. ``defer_access``: leave the
        access part out (its delta 0 for now) until ``access_changes`` adds it; it can
        fall by at most ``access_total()``."""
        delta = dict.fromkeys(ROOM_PARTS, 0.0)
        moved = set(boxes)
        walls, square, swing, view = {}, {}, {}, {}
        for box in boxes:
            walls[box] = self.wall_energy(box)
            delta["walls"] += walls[box] - self.walls[box]
            square[box] = self.square_energy(box)
            delta["square"] += square[box] - self.square[box]
            swing[box] = self.swing_energy(box)
            delta["door_swing"] += swing[box] - self.swing[box]
            view[box] = self.view_energy(box)
            delta["windows"] += view[box] - self.view[box]

        zones: set[int] = set()
        hits: dict[tuple[int, int], float] = {}
        zone_wall: dict[int, float] = {}
        if self.zones:
            clearance = 0.0
            for box in boxes:  # the zones the moved boxes own: every hit replaced
                for zone in self.zones_of[box]:
                    zones.add(zone)
                    clearance -= sum(self.zone_hits[zone].values()) + self.zone_wall[zone]
                    if not self.active[box]:
                        zone_wall[zone] = 0.0
                        continue
                    rect = self.zone(zone)
                    zone_wall[zone] = value = self.zone_wall_energy(zone, rect)
                    clearance += value
                    for other in sorted(self._zone_candidates(rect)):
                        if self.intrudes(zone, other):
                            value = self.zone_hit_energy(zone, rect, other)
                            if value > 0.0:
                                hits[(zone, other)] = value
                                clearance += value
            for box in boxes:  # the moved boxes standing in zones of boxes that stayed
                if not self.obstacle[box]:
                    continue
                for zone, value in self.hits_of[box].items():
                    if self.zones[zone][0] not in moved:
                        clearance -= value
                if not self.active[box]:
                    continue
                for owner in sorted(self._owners_near(box)):
                    if owner in moved:
                        continue
                    for zone in self.zones_of[owner]:
                        if self.intrudes(zone, box):
                            value = self.zone_hit_energy(zone, self.zone(zone), box)
                            if value > 0.0:
                                hits[(zone, box)] = value
                                clearance += value
            delta["clearance"] = clearance

        if defer_access and self.scored:
            return RoomChanges(
                delta, moved, walls, square, swing, view, zones, hits, zone_wall, None, True
            )
        return self.access_changes(
            RoomChanges(delta, moved, walls, square, swing, view, zones, hits, zone_wall, None),
            boxes,
        )

    def access_changes(self, changes: RoomChanges, boxes: list[int]) -> RoomChanges:
        """``changes`` with the access part evaluated (the state still at the proposal)."""
        access = self._access_changes(boxes) if self.scored else None
        if access is not None:
            changes.delta["access"] = access.state.total - self.access.total
        return changes._replace(access=access, deferred=False)

    def access_total(self) -> float:
        """The access part now, as the deltas reckon it: how far it can fall at most."""
        return self.access.total

    def accept(self, changes: RoomChanges) -> None:
        """Keep a proposal's values."""
        for box, value in changes.walls.items():
            self.walls[box] = value
        for box, value in changes.square.items():
            self.square[box] = value
        for box, value in changes.swing.items():
            self.swing[box] = value
        for box, value in changes.view.items():
            self.view[box] = value
        for zone in changes.zones:
            for other in self.zone_hits[zone]:
                del self.hits_of[other][zone]
            self.zone_hits[zone] = {}
        for box in changes.moved:
            for zone in self.hits_of[box]:
                del self.zone_hits[zone][box]
            self.hits_of[box] = {}
        for (zone, box), value in changes.hits.items():
            self.zone_hits[zone][box] = value
            self.hits_of[box][zone] = value
        for zone, value in changes.zone_wall.items():
            self.zone_wall[zone] = value
        if changes.access is not None:
            self.access = changes.access.state
            for box, bits in changes.access.taken.items():
                self.taken[box] = bits

    # -- what the sampler and the report read ------------------------------------------------

    def unreachable(self) -> list[int]:
        """Boxes that need reaching and cannot be."""
        return sorted(box for box, value in self.access.values.items() if value > 0.0)

    def troubled(self) -> set[int]:
        """Boxes in breach of a room term (a little square-off and a window's view aside:
        soft terms; counting a window's view sent the relocating moves after boxes a
        rule leaves nowhere else, and 60 bedrooms took four times as long): across a wall, in
        a door's swing, in a kept-free zone or owning one that is taken or crosses a
        wall, out of reach, or hemming in a box out of reach."""
        found = {
            b for b in range(self.problem.n_boxes) if self.walls[b] > 0.0 or self.swing[b] > 0.0
        }
        for zone, hits in enumerate(self.zone_hits):
            found.update(hits)
            if hits or self.zone_wall[zone] > 0.0:
                found.add(self.zones[zone][0])
        for box in self.unreachable():
            found.add(box)
            found.update(self.blockers(box))
        found.update(self.cut_blockers())
        return found

    def floor(self) -> tuple[int, FloorVerdict]:
        """The free floor now (a plane: the static floor less every placed obstacle's
        cells, in a room with doors or without) and its verdict (``floor_verdict``)."""
        used = 0
        for box in self.obstacles:
            if self.active[box]:
                used |= self.obstacle_cells(box).bits
        free = self.access_grid.static & ~used
        return free, floor_verdict(self.access_grid, free)

    def cut_blockers(self) -> list[int]:
        """When the floor fails the verdict (a door off its largest part, or less than
        NAVIGABLE_SHARE of it there), the obstacles taking cells next to the free floor
        off that part (the pockets and the parts of the room cut off); else none."""
        grid = self.access_grid
        free, verdict = self.floor()
        if not verdict.cut_doors and verdict.navigability >= NAVIGABLE_SHARE:
            return []
        cut = free & ~verdict.main
        stride = grid.stride
        near = cut | cut << 1 | cut >> 1 | cut << stride | cut >> stride
        return [
            other
            for other in self.obstacles
            if self.active[other] and self.obstacle_cells(other).bits & near
        ]

    def blockers(self, box: int) -> list[int]:
        """The obstacles that hem in an unreachable box: those taking cells next to the
        free floor around its access sides (its pocket) or covering its access cells."""
        grid = self.access_grid
        free = self.free()
        cells = self.access_cells(box).bits
        pocket = grid.flood(cells & free, free) | cells
        stride = grid.stride
        near = pocket | pocket << 1 | pocket >> 1 | pocket << stride | pocket >> stride
        return [
            other
            for other in self.obstacles
            if other != box and self.active[other] and self.obstacle_cells(other).bits & near
        ]

    def problems(self) -> list[str]:
        """The room's problems in words (ROOM_TOLERANCE of slack on every distance)."""
        problem = self.problem
        ids, found = problem.ids, []
        for box in range(problem.n_boxes):
            if self.active[box] and self.wall_excess(box) > ROOM_TOLERANCE:
                found.append(f"{ids[box]} crosses the wall")
        for door, (door_id, _) in enumerate(self.swings):
            for box in self.obstacles:
                if self.active[box] and self.swing_depth(door, box) > ROOM_TOLERANCE:
                    found.append(f"{ids[box]} stands in the swing of {door_id}")
        for zone, (owner, side, _) in enumerate(self.zones):
            if not self.active[owner]:
                continue
            rect = self.zone(zone)
            words = f"the space kept free {SIDE_WORDS[side]} {ids[owner]}"
            for other in range(problem.n_boxes):
                if (
                    self.intrudes(zone, other)
                    and self.zone_depth(zone, rect, other) > ROOM_TOLERANCE
                ):
                    found.append(f"{ids[other]} stands in {words}")
            if self.walls_geometry.excess(rect) > ROOM_TOLERANCE:
                found.append(f"{words} runs into the wall")
        for window, (view, lowest) in enumerate(self.views):
            for box in self.obstacles:
                if (
                    self.active[box]
                    and (box, window) not in self.asked_views
                    and self.state.y[box] + problem.height[box] > lowest
                    and rect_penetration(view.rect, self.state.rects[box]) > ROOM_TOLERANCE
                ):
                    found.append(f"{ids[box]} stands before {self.room.windows[window].id}")
        width = 2.0 * CORRIDOR_HALF
        for box in self.unreachable():
            found.append(f"{ids[box]} cannot be reached from the door (no {width:.1f} m wide way)")
        # SceneEval's own test (``floor_verdict``), so that a layout called ok here passes
        # its navigability (NAVIGABLE_SHARE) and its door clearance; in a room without a
        # door too, whose navigability it measures all the same.
        cell = self.access_grid.cell
        _, verdict = self.floor()
        for door in verdict.cut_doors:
            found.append(
                f"{self.room.doors[door].id} opens onto floor cut off from the rest of"
                f" the room (no {width:.1f} m wide way)"
            )
        if verdict.navigability < NAVIGABLE_SHARE:
            share = 100.0 * (1.0 - verdict.navigability)
            found.append(
                f"{verdict.cut_cells * cell * cell:.1f} m² of the free floor ({share:.0f} %) is"
                f" cut off from the rest of the room (no {width:.1f} m wide way)"
            )
        return found


def _asked_views(problem: Problem, room: Room) -> set[tuple[int, int]]:
    """The (box, window index) pairs whose box a wall relation puts on the window's own
    wall or at the window (``AgainstWall wall #2`` on a wall that is mostly window):
    the rules ask for it there, so standing before the window is no problem."""
    windows = room.windows
    asked = set()
    for term in problem.relations:
        if term.spec.family != "wall" or term.a.kind != "object":
            continue
        for k, window in enumerate(windows):
            if (term.b.kind == "wall" and room.walls[term.b.index].id == window.wall) or (
                term.b.kind == "opening" and room.openings[term.b.index].id == window.id
            ):
                asked.add((term.a.index, k))
    return asked
