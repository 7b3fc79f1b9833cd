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
    """Object id -> the id of the object it rests on, for every object that rests on one."""
    supports: dict[str, str] = {}
    for upper in objects:
        below = [lower for lower in objects if rests_on(upper, lower)]
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
