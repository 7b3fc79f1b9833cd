"""The layout mask as an energy part: a preference for where some boxes stand.

A ``FloorMask`` is a grid of values in [0, 1] laid over an axis-aligned rectangle of
the ground (a room's bounding box): ``values`` (rows, cols), row i along z, column k
along x, and the ids of the boxes it is for. ``layout_scene(..., mask=)`` and
``measure_layout(..., mask=)`` take one; without it the layout has no ``mask`` part at
all (its parts and results are what they were).

The part: per listed box that is placed,

    mask_weight * (1 - mean of the grid at SAMPLES x SAMPLES points of its footprint)

(``LayoutParams.mask_weight``), a point reading the cell it falls in (points off the
rectangle read the nearest edge cell). It is 0 where the grid says 1 under the whole
footprint and ``mask_weight`` where it says 0, so it ranks places by how much of the
footprint stands where the grid is high. Fu et al. (2017), whose layout masks this is
for, give no energy: they put each large piece, largest first, where its footprint
covers the mask's highest values. Read at the same 5 x 5 points as the starting poses
of ``complete`` score a place, the part is that score turned into a cost for the whole
chain.

It is a preference, not a constraint: ``report.assess`` does not read it, so it never
makes a layout ok or not ok; it only changes which moves the chain prefers. Each
box's value depends on its own pose alone, so a move re-evaluates the moved boxes'
values only (``Energy`` caches them per box).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from scenewright.core.errors import InputError

from .geometry import Rect

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


@dataclass(frozen=True)
class CompiledMask:
    """A ``FloorMask`` for one problem: the grid as nested lists (pure-Python reads are
    quicker than numpy's for 25 points), its origin and cell sides, and per box whether
    the mask is for it."""

    rows: tuple[tuple[float, ...], ...]
    x0: float
    z0: float
    cell_x: float
    cell_z: float
    listed: tuple[bool, ...]

    def mean_under(self, rect: Rect) -> float:
        """The grid's mean at SAMPLES x SAMPLES points of a footprint."""
        cx, cz, hw, hd, c, s = rect
        rows, n_rows, n_cols = self.rows, len(self.rows), len(self.rows[0])
        total = 0.0
        for a in _OFFSETS:
            la = 2.0 * a * hw  # along the footprint's left (c, -s)
            for b in _OFFSETS:
                lb = 2.0 * b * hd  # along its forward (s, c)
                x = cx + la * c + lb * s
                z = cz - la * s + lb * c
                k = min(max(math.floor((x - self.x0) / self.cell_x), 0), n_cols - 1)
                i = min(max(math.floor((z - self.z0) / self.cell_z), 0), n_rows - 1)
                total += rows[i][k]
        return total / (SAMPLES * SAMPLES)


def compile_mask(mask: FloorMask, ids: list[str]) -> CompiledMask:
    """Check a ``FloorMask`` against a problem's box ids; ``InputError`` when it is not
    a 2-D grid of finite values in [0, 1] over a rectangle of positive size, or names a
    box the problem does not have."""
    values = np.asarray(mask.values, dtype=float)
    if values.ndim != 2 or values.size == 0:
        raise InputError(f"mask: the values must be a non-empty 2-D grid, not shape {values.shape}")
    if not np.isfinite(values).all() or values.min() < 0.0 or values.max() > 1.0:
        raise InputError("mask: the values must be finite numbers from 0 to 1")
    x0, z0, x1, z1 = (float(v) for v in mask.bounds)
    if not (x1 > x0 and z1 > z0):
        raise InputError(f"mask: the bounds {mask.bounds} are not a rectangle of positive size")
    index = {box_id: box for box, box_id in enumerate(ids)}
    listed = [False] * len(ids)
    for box_id in mask.boxes:
        if box_id not in index:
            raise InputError(f"mask: {box_id!r} is not an object of the scene graph")
        listed[index[box_id]] = True
    rows, cols = values.shape
    return CompiledMask(
        tuple(tuple(float(v) for v in row) for row in values), x0, z0, (x1 - x0) / cols, (z1 - z0) / rows, tuple(listed)
    )
