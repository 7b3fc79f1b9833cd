"""What stands on what, measured from the boxes alone.

An object rests on another when its base is above the floor, within ``CONTACT`` of the
other's top, and its base centre lies over the other's footprint. Of several such
supporters the one whose top is nearest its base wins (a lamp on a book on a desk
rests on the book). Flat objects (a rug) lie on the floor and carry nothing: an object
whose base is within ``CONTACT`` of the floor rests on the floor, whatever is under
it. Used by the importers for files that do not say what stands on what, and by the
structure graph's support relation.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Protocol

from scenewright.core.frames import to_local
from scenewright.core.scene import SceneObject

#: How far (metres) a base may be from a top, or from the floor, and still touch it.
CONTACT = 0.03


class Boxed(Protocol):
    """A box: a SceneObject, or a record read from an example file."""

    @property
    def id(self) -> str: ...
    @property
    def position(self) -> Sequence[float]:  # base centre (x, y, z)
        ...
    @property
    def size(self) -> Sequence[float]:  # width, height, depth
        ...
    @property
    def yaw(self) -> float: ...


def touches_top(upper: Boxed, lower: Boxed) -> bool:
    """Whether ``upper``'s base is within ``CONTACT`` of ``lower``'s top."""
    return abs(upper.position[1] - (lower.position[1] + lower.size[1])) <= CONTACT


def over_footprint(upper: Boxed, lower: Boxed) -> bool:
    """Whether ``upper``'s base centre lies over ``lower``'s footprint."""
    lx, lz = to_local(
        lower.position[0], lower.position[2], lower.yaw, upper.position[0], upper.position[2]
    )
    return abs(lx) <= lower.size[0] / 2.0 + 1e-6 and abs(lz) <= lower.size[2] / 2.0 + 1e-6


def rests_on(upper: Boxed, lower: Boxed) -> bool:
    """Whether ``upper``'s base touches ``lower``'s top over ``lower``'s footprint."""
    if upper.id == lower.id or upper.position[1] <= CONTACT:
        return False
    return touches_top(upper, lower) and over_footprint(upper, lower)


def infer_supports(objects: Sequence[SceneObject]) -> dict[str, str]:
    """Object id -> the id of the object it rests on, for every object that rests on one.

    Each upper is tested against the objects whose footprint can reach its base centre
    (a grid of ``_CELL`` metre cells holding each object in the cells its footprint's
    circle covers; one that covers more than ``_MAX_CELLS`` is tried for every upper),
    so the work follows the number of objects, not its square."""
    grid: dict[tuple[int, int], list[int]] = {}
    everywhere: list[int] = []
    for k, lower in enumerate(objects):
        reach = math.hypot(lower.size[0], lower.size[2]) / 2.0 + 1e-6
        x, z = lower.position[0], lower.position[2]
        x0, x1 = math.floor((x - reach) / _CELL), math.floor((x + reach) / _CELL)
        z0, z1 = math.floor((z - reach) / _CELL), math.floor((z + reach) / _CELL)
        if (x1 - x0 + 1) * (z1 - z0 + 1) > _MAX_CELLS:
            everywhere.append(k)
            continue
        for i in range(x0, x1 + 1):
            for j in range(z0, z1 + 1):
                grid.setdefault((i, j), []).append(k)
    supports: dict[str, str] = {}
    for upper in objects:
        if upper.position[1] <= CONTACT:
            continue  # on the floor: carried by nothing
        cell = (math.floor(upper.position[0] / _CELL), math.floor(upper.position[2] / _CELL))
        below = [
            objects[k]
            for k in sorted({*grid.get(cell, ()), *everywhere})
            if rests_on(upper, objects[k])
        ]
        if below:
            nearest = min(
                below,
                key=lambda lower: (
                    abs(upper.position[1] - lower.position[1] - lower.size[1]),
                    lower.id,
                ),
            )
            supports[upper.id] = nearest.id
    return supports


#: The side of a cell of ``infer_supports``' grid, in metres (about a piece of furniture).
_CELL = 1.0
#: The most cells an object is filed in; a larger one (a 1 km field) is tried everywhere.
_MAX_CELLS = 1024
