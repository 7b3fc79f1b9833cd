"""The mutable layout: box poses, path control points, and a uniform grid broad phase.

Poses live in plain Python lists (x, z, yaw and its cosine and sine per box) because the
sampler reads and writes single entries every step. Heights never change while sampling:
a box rests on the ground or on its support, and supports carry what rests on them.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from scenewright.core.geometry import Rect

if TYPE_CHECKING:  # the problem's compiler reads the families, which read the state
    from .problem import Problem

_new_rect = tuple.__new__


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
        self.large: dict[
            int, tuple[int, int, int, int]
        ] = {}  # box -> its cell range i0, i1, k0, k1
        self.spans: dict[int, tuple[int, int, int, int]] = {}  # every filed box's cell range

    def _range(self, x0: float, z0: float, x1: float, z1: float) -> tuple[int, int, int, int]:
        cell = self.cell
        return (
            math.floor(x0 / cell),
            math.floor(x1 / cell),
            math.floor(z0 / cell),
            math.floor(z1 / cell),
        )

    @staticmethod
    def _count(span: tuple[int, int, int, int]) -> int:
        i0, i1, k0, k1 = span
        return (i1 - i0 + 1) * (k1 - k0 + 1)

    def _cells_in(self, span: tuple[int, int, int, int]) -> list[tuple[int, int]]:
        i0, i1, k0, k1 = span
        return [(i, k) for i in range(i0, i1 + 1) for k in range(k0, k1 + 1)]

    def _large_meeting(self, span: tuple[int, int, int, int]) -> list[int]:
        i0, i1, k0, k1 = span
        return [
            box
            for box, (a0, a1, b0, b1) in self.large.items()
            if a0 <= i1 and i0 <= a1 and b0 <= k1 and k0 <= b1
        ]

    def insert(self, box: int, x: float, z: float, radius: float) -> None:
        self.insert_area(box, x - radius, z - radius, x + radius, z + radius)

    def insert_area(self, item: int, x0: float, z0: float, x1: float, z1: float) -> None:
        """File an item under the cells meeting the axis-aligned area (a path's bounds)."""
        self._file(item, self._range(x0, z0, x1, z1), None)

    def _file(
        self, item: int, span: tuple[int, int, int, int], keys: list[tuple[int, int]] | None
    ) -> None:
        """File ``item`` under ``span``'s cells, whose keys (in ``_cells_in`` order) may be given."""
        self.spans[item] = span
        if self._count(span) > self.MAX_SPAN:
            self.large[item] = span
            self.keys[item] = []
            return
        if keys is None:
            keys = self._cells_in(span)
        self.keys[item] = keys
        cells = self.cells
        for key in keys:
            if key in cells:
                cells[key].append(item)
            else:
                cells[key] = [item]

    def remove(self, box: int) -> None:
        self.large.pop(box, None)
        self.spans.pop(box, None)
        cells = self.cells
        for key in self.keys.pop(box, ()):
            cells[key].remove(box)

    def filing(self, item: int) -> tuple[tuple[int, int, int, int], list[tuple[int, int]]] | None:
        """Where the item is filed now (its span and keys), for ``move``'s ``previous``."""
        span = self.spans.get(item)
        return None if span is None else (span, self.keys[item])

    def move(self, box: int, x: float, z: float, radius: float, previous=None) -> None:
        """``remove`` then ``insert``, with the same cell lists in the same order after it;
        the keys are not rebuilt when the span is the one the box had, or ``previous``'s
        (a ``filing``: a rejected move puts the box back where it was filed). Written out
        (``_range``, ``remove``, ``_file``): it runs twice a proposal."""
        cell, cells, spans, large = self.cell, self.cells, self.spans, self.large
        i0, i1 = math.floor((x - radius) / cell), math.floor((x + radius) / cell)
        k0, k1 = math.floor((z - radius) / cell), math.floor((z + radius) / cell)
        span = (i0, i1, k0, k1)
        if spans.get(box) == span and box not in large:  # the same cells: it only goes last in each
            for key in self.keys[box]:
                boxes = cells[key]
                if boxes[-1] != box:
                    boxes.remove(box)
                    boxes.append(box)
            return
        large.pop(box, None)
        for key in self.keys.pop(box, ()):
            cells[key].remove(box)
        spans[box] = span
        if (i1 - i0 + 1) * (k1 - k0 + 1) > self.MAX_SPAN:
            large[box] = span
            self.keys[box] = []
            return
        if previous is not None and previous[0] == span:
            keys = previous[1]
        elif i0 == i1 and k0 == k1:
            keys = [(i0, k0)]
        else:
            keys = [(i, k) for i in range(i0, i1 + 1) for k in range(k0, k1 + 1)]
        self.keys[box] = keys
        for key in keys:
            filed = cells.get(key)
            if filed is None:
                cells[key] = [box]
            else:
                filed.append(box)

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

    def in_cells_of(
        self, filing: tuple[tuple[int, int, int, int], list[tuple[int, int]]]
    ) -> set[int]:
        """Items registered in the cells of a ``filing`` of another grid of the same cell
        size (the cells a box of it is filed under): the same as ``in_area`` of the area
        that filing was made for, without working out its cells again."""
        span, keys = filing
        if not keys:  # filed whole (``large``): its cells were never listed
            return self._in_span(span)
        found: set[int] = set()
        cells = self.cells
        for key in keys:
            if key in cells:
                found.update(cells[key])
        if self.large:
            found.update(self._large_meeting(span))
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
        self.rects = [
            Rect(0.0, 0.0, problem.half_width[b], problem.half_depth[b], 1.0, 0.0) for b in range(n)
        ]
        # Heights never change: each box rests on the top of its support's stack.
        self.y = [
            sum((problem.height[below] for below in problem.beneath(box)), 0.0) for box in range(n)
        ]
        self.points: list[list[list[float]]] = [
            [[0.0, 0.0] for _ in range(segments + 1)] for segments in problem.path_segments
        ]

    def set_pose(self, box: int, x: float, z: float, yaw: float) -> None:
        if yaw is self.yaw[box]:  # not turned (the very float it has): its cosine and sine stand
            c, s = self.c[box], self.s[box]
        else:
            c, s = math.cos(yaw), math.sin(yaw)
            self.yaw[box], self.c[box], self.s[box] = yaw, c, s
        self.x[box], self.z[box] = x, z
        rect = self.rects[box]
        self.rects[box] = _new_rect(
            Rect, (x, z, rect.hw, rect.hd, c, s)
        )  # Rect(...) without its Python-level __new__

    def pose(self, box: int) -> tuple[float, float, float]:
        return self.x[box], self.z[box], self.yaw[box]

    def trying(self, poses: dict[int, tuple[float, float, float]]) -> Trying:
        """Put boxes at ``{box: (x, z, yaw)}`` for the ``with`` block only (to measure a candidate)."""
        return Trying(self, poses)


class Trying:
    """``State.trying``'s context: the poses set on entering, the old ones back on leaving
    (a plain class: a generator-made context costs several times as much, and the moves
    measure a candidate this way many times a step)."""

    __slots__ = ("state", "poses", "saved")

    def __init__(self, state: State, poses: dict[int, tuple[float, float, float]]):
        self.saved: list[tuple[int, tuple[float, float, float]]]
        self.state, self.poses, self.saved = state, poses, []

    def __enter__(self) -> None:
        state = self.state
        self.saved = [(box, state.pose(box)) for box in self.poses]
        for box, pose in self.poses.items():
            state.set_pose(box, *pose)

    def __exit__(self, *_) -> None:
        for box, pose in self.saved:
            self.state.set_pose(box, *pose)
