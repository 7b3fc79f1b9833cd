"""The mutable layout: box poses, path control points, and a uniform grid broad phase.

Poses live in plain Python lists (x, z, yaw and its cosine and sine per box) because the
sampler reads and writes single entries every step. Heights never change while sampling:
a box rests on the ground or on its support, and supports carry what rests on them.
"""

from __future__ import annotations

import math
from collections.abc import Iterator
from contextlib import contextmanager

from .geometry import Rect
from .problem import Problem


class Grid:
    """Boxes bucketed by the cells their bounding circle's square covers.

    A box's neighbours are those sharing a cell with it; any two boxes that overlap
    share a cell, so collision tests need only look there. Cost per query is the
    number of boxes nearby, not the number in the scene.

    Work never grows with the area a box or a query covers: a box spanning more than
    ``MAX_SPAN`` cells (a 1 km field among 10 cm cups) is kept once, with its cell range,
    and compared by range with every query; an area query wider than the cells in use
    (a road across a 10 km extent) looks through the cells in use instead of the area's.
    """

    #: Cells a box may be filed under one by one; a larger box is kept in ``large``.
    MAX_SPAN = 1024

    def __init__(self, cell: float):
        self.cell = cell
        self.cells: dict[tuple[int, int], list[int]] = {}
        self.keys: dict[int, list[tuple[int, int]]] = {}
        self.large: dict[int, tuple[int, int, int, int]] = {}  # box -> its cell range i0, i1, k0, k1

    def _range(self, x0: float, z0: float, x1: float, z1: float) -> tuple[int, int, int, int]:
        cell = self.cell
        return math.floor(x0 / cell), math.floor(x1 / cell), math.floor(z0 / cell), math.floor(z1 / cell)

    @staticmethod
    def _count(span: tuple[int, int, int, int]) -> int:
        i0, i1, k0, k1 = span
        return (i1 - i0 + 1) * (k1 - k0 + 1)

    def _cells_in(self, span: tuple[int, int, int, int]) -> list[tuple[int, int]]:
        i0, i1, k0, k1 = span
        return [(i, k) for i in range(i0, i1 + 1) for k in range(k0, k1 + 1)]

    def _large_meeting(self, span: tuple[int, int, int, int]) -> list[int]:
        i0, i1, k0, k1 = span
        return [box for box, (a0, a1, b0, b1) in self.large.items() if a0 <= i1 and i0 <= a1 and b0 <= k1 and k0 <= b1]

    def insert(self, box: int, x: float, z: float, radius: float) -> None:
        span = self._range(x - radius, z - radius, x + radius, z + radius)
        if self._count(span) > self.MAX_SPAN:
            self.large[box] = span
            self.keys[box] = []
            return
        keys = self._cells_in(span)
        self.keys[box] = keys
        for key in keys:
            self.cells.setdefault(key, []).append(box)

    def remove(self, box: int) -> None:
        self.large.pop(box, None)
        for key in self.keys.pop(box, ()):
            self.cells[key].remove(box)

    def near_box(self, box: int) -> set[int]:
        """Boxes sharing a cell with ``box`` (itself included)."""
        if box in self.large:
            return self._in_span(self.large[box])
        found: set[int] = set()
        cells = self.cells
        for key in self.keys.get(box, ()):
            found.update(cells[key])
        if self.large and box in self.keys:
            found.update(self._large_meeting(self._span_of(self.keys[box])))
        return found

    def in_area(self, x0: float, z0: float, x1: float, z1: float) -> set[int]:
        """Boxes registered in any cell meeting the axis-aligned area."""
        return self._in_span(self._range(x0, z0, x1, z1))

    def _in_span(self, span: tuple[int, int, int, int]) -> set[int]:
        found: set[int] = set()
        if self._count(span) <= len(self.cells):
            for key in self._cells_in(span):
                found.update(self.cells.get(key, ()))
        else:
            i0, i1, k0, k1 = span
            for (i, k), boxes in self.cells.items():
                if i0 <= i <= i1 and k0 <= k <= k1:
                    found.update(boxes)
        found.update(self._large_meeting(span))
        return found

    @staticmethod
    def _span_of(keys: list[tuple[int, int]]) -> tuple[int, int, int, int]:
        """The cell range of a box filed cell by cell (its keys run from corner to corner)."""
        (i0, k0), (i1, k1) = keys[0], keys[-1]
        return i0, i1, k0, k1


class State:
    """Current poses of all boxes and control points of all paths."""

    def __init__(self, problem: Problem):
        n = problem.n_boxes
        self.problem = problem
        self.x = [0.0] * n
        self.z = [0.0] * n
        self.yaw = [0.0] * n
        self.c = [1.0] * n
        self.s = [0.0] * n
        # Each box's footprint at its current pose, rebuilt by set_pose: the geometry reads it every step.
        self.rects = [Rect(0.0, 0.0, problem.half_width[b], problem.half_depth[b], 1.0, 0.0) for b in range(n)]
        # Heights never change: each box rests on the top of its support's stack.
        self.y = [sum((problem.height[below] for below in problem.beneath(box)), 0.0) for box in range(n)]
        self.points: list[list[list[float]]] = [
            [[0.0, 0.0] for _ in range(segments + 1)] for segments in problem.path_segments
        ]

    def set_pose(self, box: int, x: float, z: float, yaw: float) -> None:
        c, s = math.cos(yaw), math.sin(yaw)
        self.x[box], self.z[box], self.yaw[box], self.c[box], self.s[box] = x, z, yaw, c, s
        rect = self.rects[box]
        self.rects[box] = Rect(x, z, rect.hw, rect.hd, c, s)

    def pose(self, box: int) -> tuple[float, float, float]:
        return self.x[box], self.z[box], self.yaw[box]

    @contextmanager
    def trying(self, poses: dict[int, tuple[float, float, float]]) -> Iterator[None]:
        """Put boxes at ``{box: (x, z, yaw)}`` for the ``with`` block only (to measure a candidate)."""
        saved = [(box, self.pose(box)) for box in poses]
        for box, pose in poses.items():
            self.set_pose(box, *pose)
        try:
            yield
        finally:
            for box, pose in saved:
                self.set_pose(box, *pose)
