"""The layout mask as an energy part: a preference for where some boxes stand.

A ``FloorMask`` is a grid of values in [0, 1] laid over an axis-aligned rectangle of
the ground (a room's bounding box): ``values`` (rows, cols), row i along z, column k
along x, and the ids of the boxes it is for. ``layout_scene(..., mask=)`` and
``measure_layout(..., mask=)`` take one, or a sequence of them for different boxes
(a room split into parts, each with its own mask over its own rectangle; a box named
by several pays each); without it the layout has no ``mask`` part at all (its
parts and results are what they were).

The part: per listed box that is placed,

    mask_weight * sum over its masks of weight * (1 - mean of the grid at SAMPLES x SAMPLES points of its footprint)

(``LayoutParams.mask_weight``), a point reading the cell it falls in. Points off the
rectangle read the nearest edge cell, or the mask's ``outside`` value when it has one:
a mask over one part of a room with ``outside=0`` costs a box the full weight for the
share of its footprint beyond that part. It is 0 where the grid says 1 under the whole
footprint and ``mask_weight`` where it says 0, so it ranks places by how much of the
footprint stands where the grid is high. Fu et al. (2017), whose layout masks this is
for, give no energy: they put each large piece, largest first, where its footprint
covers the mask's highest values. Read at the same 5 x 5 points as the starting poses
of ``complete`` score a place, the part is that score turned into a cost for the whole
chain.

A mask may weigh its boxes more (``weight``, times ``mask_weight``). It is a
preference, not a constraint: ``report.assess`` does not read it, so it never makes a
layout ok or not ok; it only changes which moves the chain prefers. The one exception
is a mask that ``confine``s its boxes: one whose footprint's centre lies beyond the
mask's rectangle is a problem of the verdict (``stands outside its part of the room``)
and a troubled box the chain works on; a room split by virtual walls keeps each
part's pieces in their part this way. Each
box's value depends on its own pose alone, so a move re-evaluates the moved boxes'
values only (``Energy`` caches them per box).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from scenewright.core.errors import InputError
from scenewright.core.geometry import Rect

#: Sample points per side of a footprint (SAMPLES x SAMPLES in all).
SAMPLES = 5
#: The samples' local coordinates in units of the footprint's sides, centred: (SAMPLES,).
_OFFSETS = tuple((k + 0.5) / SAMPLES - 0.5 for k in range(SAMPLES))


@dataclass(frozen=True)
class FloorMask:
    """``values`` (rows, cols) in [0, 1] over the rectangle ``bounds`` (x0, z0, x1, z1),
    row i covering z in [z0 + i * (z1 - z0) / rows, ...), column k likewise along x; and
    ``boxes``, the ids of the boxes the layout should prefer to stand where it is high."""

    values: np.ndarray
    bounds: tuple[float, float, float, float]
    boxes: tuple[str, ...]
    #: What points off the rectangle read: None for the nearest edge cell, else this value in [0, 1].
    outside: float | None = None
    #: This mask's cost per box, times ``LayoutParams.mask_weight``.
    weight: float = 1.0
    #: Whether its boxes must stand in the rectangle: one whose centre lies beyond it is a problem.
    confine: bool = False


@dataclass(frozen=True)
class CompiledGrid:
    """One ``FloorMask``'s grid for one problem: nested lists (pure-Python reads are
    quicker than numpy's for 25 points), its origin, cell sides and ``outside`` value."""

    rows: tuple[tuple[float, ...], ...]
    x0: float
    z0: float
    cell_x: float
    cell_z: float
    outside: float | None = None
    weight: float = 1.0
    confine: bool = False

    def holds(self, rect: Rect) -> bool:
        """Whether a footprint's centre lies in the rectangle (what ``confine`` asks)."""
        k = math.floor((rect[0] - self.x0) / self.cell_x)
        i = math.floor((rect[1] - self.z0) / self.cell_z)
        return 0 <= k < len(self.rows[0]) and 0 <= i < len(self.rows)

    def mean_under(self, rect: Rect) -> float:
        """The grid's mean at SAMPLES x SAMPLES points of a footprint."""
        cx, cz, hw, hd, c, s = rect
        rows, n_rows, n_cols = self.rows, len(self.rows), len(self.rows[0])
        outside = self.outside
        total = 0.0
        for a in _OFFSETS:
            la = 2.0 * a * hw  # along the footprint's left (c, -s)
            for b in _OFFSETS:
                lb = 2.0 * b * hd  # along its forward (s, c)
                x = cx + la * c + lb * s
                z = cz - la * s + lb * c
                k = math.floor((x - self.x0) / self.cell_x)
                i = math.floor((z - self.z0) / self.cell_z)
                if outside is not None and not (0 <= k < n_cols and 0 <= i < n_rows):
                    total += outside
                    continue
                total += rows[min(max(i, 0), n_rows - 1)][min(max(k, 0), n_cols - 1)]
        return total / (SAMPLES * SAMPLES)


@dataclass(frozen=True)
class CompiledMask:
    """The ``FloorMask`` (or masks) of one problem: their ``grids``, per box the indices
    of the grids that are for it and whether any is (``listed``, read on every move)."""

    grids: tuple[CompiledGrid, ...]
    grids_of: tuple[tuple[int, ...], ...]
    listed: tuple[bool, ...]

    def cost(self, box: int, rect: Rect) -> float:
        """Box ``box``'s cost at the footprint ``rect``: over its grids, the weight times
        1 less the grid's mean under the footprint, summed."""
        total = 0.0
        for index in self.grids_of[box]:
            grid = self.grids[index]
            total += grid.weight * (1.0 - grid.mean_under(rect))
        return total

    def strays(self, box: int, rect: Rect) -> bool:
        """Whether the footprint's centre lies beyond a confining grid of the box."""
        return any(
            self.grids[index].confine and not self.grids[index].holds(rect)
            for index in self.grids_of[box]
        )


def compile_mask(mask, ids: list[str]) -> CompiledMask:
    """Check a ``FloorMask`` (or a sequence of them) against a problem's box ids;
    ``InputError`` when one is not a 2-D grid of finite values in [0, 1] over a rectangle
    of positive size, has an ``outside`` value off [0, 1], names a box the problem does
    not have, or has a weight that is not a positive number. A box several masks name
    pays each of them."""
    masks = (mask,) if isinstance(mask, FloorMask) else tuple(mask)
    index = {box_id: box for box, box_id in enumerate(ids)}
    grids_of: list[list[int]] = [[] for _ in ids]
    grids = []
    for number, each in enumerate(masks):
        grids.append(_compile_grid(each))
        for box_id in each.boxes:
            if box_id not in index:
                raise InputError(f"mask: {box_id!r} is not an object of the scene graph")
            if number not in grids_of[index[box_id]]:
                grids_of[index[box_id]].append(number)
    return CompiledMask(
        tuple(grids), tuple(map(tuple, grids_of)), tuple(bool(found) for found in grids_of)
    )


def _compile_grid(mask: FloorMask) -> CompiledGrid:
    values = np.asarray(mask.values, dtype=float)
    if values.ndim != 2 or values.size == 0:
        raise InputError(f"mask: the values must be a non-empty 2-D grid, not shape {values.shape}")
    if not np.isfinite(values).all() or values.min() < 0.0 or values.max() > 1.0:
        raise InputError("mask: the values must be finite numbers from 0 to 1")
    x0, z0, x1, z1 = (float(v) for v in mask.bounds)
    if not (x1 > x0 and z1 > z0):
        raise InputError(f"mask: the bounds {mask.bounds} are not a rectangle of positive size")
    outside = mask.outside
    if outside is not None and not (math.isfinite(outside) and 0.0 <= outside <= 1.0):
        raise InputError(f"mask: the outside value {outside!r} must be a number from 0 to 1")
    weight = float(mask.weight)
    if not (math.isfinite(weight) and weight > 0.0):
        raise InputError(f"mask: the weight {mask.weight!r} must be a positive number")
    rows, cols = values.shape
    return CompiledGrid(
        tuple(tuple(float(v) for v in row) for row in values),
        x0,
        z0,
        (x1 - x0) / cols,
        (z1 - z0) / rows,
        None if outside is None else float(outside),
        weight,
        bool(mask.confine),
    )
