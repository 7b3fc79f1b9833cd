"""One relation edge ready to score (``RelationTerm``) and its two ends (``Endpoint``).

The compiled problem (``problem.compile_problem``) makes them; the energy, the family
entries (``families``) and the moves read them. They depend on nothing of the layout,
so every module of it may name them.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

from scenewright.core.relations import RelationLabel

#: Endpoint kinds that stand for a room's parts (fixed: they have no boxes).
ROOM_ENDS = ("wall", "opening", "room")


@dataclass(frozen=True)
class Endpoint:
    """One end of a relation: a box (``object``), a group of boxes, or a path."""

    kind: str  # "object", "group", "path", or a room's "wall", "opening" or "room"
    index: int  # box, path or group index; a wall's or opening's index in the room (0 for "room")
    members: tuple[int, ...]  # the boxes whose poses it depends on (empty for paths and room parts)


@dataclass(frozen=True)
class RelationTerm:
    """One relation edge, ready to score: ``a`` -label-> ``b``."""

    source: str
    target: str
    label: str  # as written (may be Implicit*)
    spec: RelationLabel  # the registry's record: the geometry it asks for
    a: Endpoint
    b: Endpoint
    #: Line of sight: the tall ground boxes that may stand between A and B (empty when
    #: the relation does not need a clear view, outdoors, or with line of sight off).
    sight: tuple[int, ...] = ()

    @cached_property
    def reads_fixed_geometry(self) -> bool:
        """Whether the term reads geometry that does not move with its own boxes: a path,
        a room's wall, window or door, or (``sight``) tall boxes that may stand between
        its ends. A shared translation of its boxes can change such a term, so the
        energy re-evaluates it after one (``Energy._changes``)."""
        return bool(self.sight) or self.a.kind in _FIXED_ENDS or self.b.kind in _FIXED_ENDS

    @property
    def placeable(self) -> bool:
        """False when an end is a group with nothing in it: there is nothing to place."""
        return all(end.kind != "group" or end.members for end in (self.a, self.b))


_FIXED_ENDS = ("path",) + ROOM_ENDS
