"""The energy's single terms: one pair of boxes, one box and path, one path, one junction.

``SingleTerms`` scores one term of the ``collisions``, ``paths``, ``path_shape`` and
``extent`` parts (and of ``mask`` and ``learned``) at the current state, with the quick
tests that skip a box and a path that cannot touch. ``energy.Energy`` is one: it adds
the caches of every term and their incremental update; ``report`` reads the same
terms for its verdicts.
"""

from __future__ import annotations

import math
from collections.abc import Iterable

from scenewright.core.geometry import (
    polyline_length,
    polyline_rect_penetration,
    polyline_turns,
    rect_overlap,
)

from .branches import branch_angle
from .factors import greater, less
from .params import LayoutParams
from .problem import Problem
from .room_terms import RoomTerms
from .state import Grid, State

#: Depths are clipped below 1 so the log penalty stays finite.
MAX_DEPTH = 0.99


class SingleTerms:
    """Scores single terms of a problem's state (``Energy`` sets what it reads)."""

    problem: Problem
    state: State
    params: LayoutParams
    #: Whether each box is in the energy yet (placed).
    active: list[bool]
    #: The boxes' broad phase.
    grid: Grid
    #: Per path, its control points' bounding box grown by half its width (x0, x1, z0, z1).
    path_bounds: list[tuple[float, float, float, float]]
    #: With many paths, the paths filed by those bounds (None with few).
    path_grid: Grid | None
    #: Per box, the paths it is caching a hit with.
    hit_paths: list[set[int]]
    #: The room's terms; None outdoors.
    room: RoomTerms | None

    def penalty(self, depth: float) -> float:
        return -self.params.collision_intensity * math.log1p(-min(depth, MAX_DEPTH))

    def pair_depth(self, first: int, second: int) -> float:
        """Normalised penetration depth of two boxes (0 when apart or stacked)."""
        return self.pair_penetration(first, second) / (
            self.problem.size[first] + self.problem.size[second]
        )

    def pair_penetration(self, first: int, second: int) -> float:
        """How far (metres) two boxes run into each other: the planar penetration, or
        the vertical overlap where it is smaller and one is stacked; 0 when apart, when
        one rests on the other, or when exactly one is a floor covering (furniture
        stands on a rug)."""
        problem, state = self.problem, self.state
        if problem.support[first] == second or problem.support[second] == first:
            return 0.0
        if problem.covering and problem.covering[first] != problem.covering[second]:
            return 0.0
        planar = rect_overlap(
            state.rects[first], state.rects[second]
        )  # its penetration when positive
        if not planar > 0.0:
            return 0.0
        if problem.support[first] >= 0 or problem.support[second] >= 0:
            vertical = min(
                state.y[first] + problem.height[first], state.y[second] + problem.height[second]
            ) - max(state.y[first], state.y[second])
            if vertical <= 1e-9:
                return 0.0
            planar = min(planar, vertical)
        return planar

    def pair_energy(self, first: int, second: int) -> float:
        depth = self.pair_depth(first, second)
        return self.penalty(depth) if depth > 0.0 else 0.0

    def _path_bounds(self, path: int) -> tuple[float, float, float, float]:
        points, reach = self.state.points[path], self.problem.path_width[path] / 2.0
        xs = [p[0] for p in points]
        zs = [p[1] for p in points]
        return min(xs) - reach, max(xs) + reach, min(zs) - reach, max(zs) + reach

    def may_touch_path(self, box: int, path: int) -> bool:
        """False when the box's bounding circle misses the path's grown bounding box."""
        x0, x1, z0, z1 = self.path_bounds[path]
        x, z, radius = self.state.x[box], self.state.z[box], self.problem.size[box] / 2.0
        return x + radius >= x0 and x - radius <= x1 and z + radius >= z0 and z - radius <= z1

    def paths_near(self, box: int) -> list[int]:
        """The paths the box may touch (``may_touch_path``), in order."""
        return [path for path in self._paths_to_test(box) if self.may_touch_path(box, path)]

    def _paths_to_test(self, box: int) -> Iterable[int]:
        """In order, every path the box may touch (``may_touch_path``) or is caching a hit
        with (``hit_paths``), and perhaps a few more: those ``path_grid`` files in the
        cells the box's bounding circle's square meets, or every path without the grid."""
        if self.path_grid is None:
            return range(self.problem.n_paths)
        filing = self.grid.filing(box) if self.active[box] else None
        if filing is not None:  # filed at its current pose: the same cells
            near = self.path_grid.in_cells_of(filing)
        else:
            x, z, radius = self.state.x[box], self.state.z[box], self.problem.size[box] / 2.0
            near = self.path_grid.in_area(x - radius, z - radius, x + radius, z + radius)
        near.update(self.hit_paths[box])
        return sorted(near)

    def _file_path(self, path: int) -> None:
        """(Re)file a path in ``path_grid`` under its current ``path_bounds``."""
        if self.path_grid is not None:
            x0, x1, z0, z1 = self.path_bounds[path]
            self.path_grid.remove(path)
            self.path_grid.insert_area(path, x0, z0, x1, z1)

    def path_depth(self, box: int, path: int) -> float:
        """Normalised depth of a ground box into a path's buffered polyline."""
        return self.path_penetration(box, path) / (
            self.problem.size[box] + self.problem.path_width[path]
        )

    def path_penetration(self, box: int, path: int) -> float:
        """How far (metres) a ground box reaches into a path's buffered polyline."""
        if not self.may_touch_path(box, path):
            return 0.0
        return polyline_rect_penetration(
            self.state.points[path], self.problem.path_width[path] / 2.0, self.state.rects[box]
        )

    def path_energy(self, box: int, path: int) -> float:
        depth = self.path_depth(box, path)
        return self.penalty(depth) if depth > 0.0 else 0.0

    def box_excess(self, box: int) -> float:
        """How far (metres) the box's footprint reaches beyond the scene extent."""
        problem, state = self.problem, self.state
        half_x, half_z = problem.extent[0] / 2.0, problem.extent[1] / 2.0
        hw, hd, c, s = problem.half_width[box], problem.half_depth[box], state.c[box], state.s[box]
        reach_x = hw * abs(c) + hd * abs(s)
        reach_z = hw * abs(s) + hd * abs(c)
        return max(abs(state.x[box]) + reach_x - half_x, abs(state.z[box]) + reach_z - half_z, 0.0)

    def box_extent_energy(self, box: int) -> float:
        if not self.active[box] or self.room is not None:  # in a room: the walls term instead
            return 0.0
        return self.params.collision_intensity * self.box_excess(box) / self.problem.size[box]

    def path_excess(self, path: int) -> float:
        """Summed distance (metres) by which a path's control points leave the extent."""
        half_x, half_z = self.problem.extent[0] / 2.0, self.problem.extent[1] / 2.0
        return sum(max(abs(x) - half_x, abs(z) - half_z, 0.0) for x, z in self.state.points[path])

    def path_extent_energy(self, path: int) -> float:
        return (
            self.params.collision_intensity * self.path_excess(path) / self.problem.path_width[path]
        )

    def path_shape_energy(self, path: int) -> float:
        points, params = self.state.points[path], self.params
        energy = -less(polyline_length(points), self.problem.path_max_length[path], params.h)
        for turn in polyline_turns(points):
            energy -= less(turn, params.gamma, params.h)
        parent = self.problem.path_parent[path]
        if parent >= 0:  # a branch leaves its road at least gamma from it
            angle = branch_angle(self.state.points[parent], points)
            energy -= greater(angle, params.gamma, params.h)
        return energy

    def junction_angles(self, junction: int) -> list[float]:
        """Angles between neighbouring outgoing paths of a junction (radians)."""
        headings = []
        for path in self.problem.paths_of_junction[junction]:
            first, second = self.state.points[path][0], self.state.points[path][1]
            headings.append(math.atan2(second[1] - first[1], second[0] - first[0]))
        if len(headings) < 2:
            return []
        headings.sort()
        gaps = [b - a for a, b in zip(headings, headings[1:], strict=False)]
        gaps.append(2.0 * math.pi - (headings[-1] - headings[0]))
        return gaps

    def junction_energy(self, junction: int) -> float:
        params = self.params
        return -sum(
            greater(angle, params.gamma, params.h) for angle in self.junction_angles(junction)
        )

    def mask_energy(self, box: int) -> float:
        """The ``mask`` part's term of a box: 0 unless the mask is for it and it is placed."""
        mask = self.problem.mask
        if mask is None or not mask.listed[box] or not self.active[box]:
            return 0.0
        return self.params.mask_weight * mask.cost(box, self.state.rects[box])

    def balance_energy(self) -> float:
        """The learned visual-balance term over the placed floor pieces."""
        learned = self.problem.learned
        assert learned is not None and learned.balance is not None
        return learned.balance_value(self.problem, self.state, self.active)

    def learned_energy(self, pair: int) -> float:
        """A learned pair's term: 0 until both its boxes are placed."""
        learned = self.problem.learned
        assert learned is not None  # the part exists with a context only
        source, target, _ = learned.pairs[pair]
        if not (self.active[source] and self.active[target]):
            return 0.0
        return learned.value(pair, self.state)
