"""The entry a relation family has in the layout's table (``families.LAYOUT_FAMILIES``)."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING

from scenewright.core.errors import InputError
from scenewright.core.relations import Relation, RelationLabel
from scenewright.core.room import Room

from ..params import LayoutParams
from ..relation_terms import Measure
from ..state import State
from ..terms import ROOM_ENDS, Endpoint, RelationTerm

if TYPE_CHECKING:  # the placer dispatches on the table; an entry only calls it back
    from ..placement import Placer

#: A proposal's new box poses, {box: (x, z, yaw)}, or None when there is none.
Poses = dict | None


def no_sight(spec: RelationLabel) -> bool:
    """A label that needs no clear view between A and B."""
    return False


def where(edge: Relation) -> str:
    """The edge as its errors name it."""
    return f"{edge.source} {edge.label} {edge.target}"


def any_ends(
    edge: Relation, spec: RelationLabel, a: Endpoint, b: Endpoint, room: Room | None
) -> None:
    """A family that takes any ends (but a room's part as A: ``room_is_fixed``)."""


def room_is_fixed(
    edge: Relation, spec: RelationLabel, a: Endpoint, b: Endpoint, room: Room | None
) -> None:
    """Refuse a room's part as A: walls, doors and windows are fixed, never placed."""
    if a.kind in ROOM_ENDS:
        raise InputError(
            f"{where(edge)}: {edge.source} is part of the room and cannot be placed; "
            "write the relation from the object"
        )


@dataclass(frozen=True)
class LayoutFamily:
    """The layout's side of one relation family."""

    #: Table 1: the relation's energy (>= 0) and the geometric measures its threshold reads.
    measure: Callable[[RelationTerm, State, LayoutParams], Measure]
    #: Whether the relation holds, by those measures (the thresholds of ``report``).
    holds: Callable[[RelationTerm, Measure, LayoutParams], bool]
    #: What is wrong with a relation that does not hold, in words.
    complaint: Callable[[RelationTerm, Measure, LayoutParams], str]
    #: A (with all it carries) placed where the relation holds, or None; the flag asks a
    #: placement beside a road to keep A's heading (``keep_heading``).
    place: Callable[[Placer, RelationTerm, bool], Poses]
    #: Whether the relation says where A goes; one that only turns A (``turn``) is left
    #: out of the relations an item is placed by, and turns it once it has a place.
    places: bool = True
    #: Whether it places A only where no relation of another family does: otherwise A is
    #: placed by those and snapped to hold this one too (``snap``), so that a lamp kept
    #: off the walls is still drawn beside its armchair, not anywhere in the room.
    places_alone: bool = False
    #: A data-driven move of B instead: B placed so the relation holds (None: B is not
    #: moved for it).
    place_target: Callable[[Placer, RelationTerm], Poses] | None = None
    #: Whether the initial placement may place B by the relation, beside an A already
    #: placed, and lend its B as the anchor of an item nothing anchors.
    anchors_target: bool = False
    #: Whether the road or junction B of a pinned A is brought to A (``Placer.pull``).
    pulls_roads: bool = False
    #: Whether A stands with its back to a wall: random shifts slide it along the wall,
    #: and the initial placement places it before the rest (``placing_rank``).
    stands_against_wall: bool = False
    #: How few places the relation leaves A (higher first), for the initial placement's
    #: order of furniture against walls; None: it does not order.
    placing_rank: Callable[[RelationTerm], int] | None = None
    #: A moved to the nearest pose at which the relation holds, from where a placement by
    #: another relation put it (``Placer.place_by``); None: nothing snaps onto it.
    snap: Callable[[Placer, RelationTerm], Poses] | None = None
    #: A placed by the relation with the items tied to A that are in place carried
    #: along (a bed to another wall with its nightstands); None: no such move.
    carry: Callable[[Placer, RelationTerm], Poses] | None = None
    #: For a relation that only turns A: the turn of A alone, of the top-level group
    #: holding A, whether A already has the heading asked for, and whether the heading
    #: is fixed whatever A's place (then, in a room, it is taken before the place).
    turn: Callable[[Placer, RelationTerm], Poses] | None = None
    turn_group: Callable[[Placer, RelationTerm], Poses] | None = None
    turned: Callable[[Placer, RelationTerm], bool] | None = None
    heading_only: Callable[[RelationTerm], bool] | None = None
    #: Whether the label needs a clear view from A to B (``problem``'s line of sight).
    needs_sight: Callable[[RelationLabel], bool] = no_sight
    #: The compiler's check of the relation's ends (raises ``InputError``), before the
    #: check every relation gets (``room_is_fixed``).
    check_ends: Callable[[Relation, RelationLabel, Endpoint, Endpoint, Room | None], None] = (
        any_ends
    )
