"""AwayFromWall: A (an object on the ground) with its footprint kept off a wall (rooms).

The complement of the wall labels: where ``AgainstWall`` puts A's back within a few
centimetres of a wall, ``AwayFromWall`` keeps every side of A at least ``HOLDS_FROM``
off it (the layout aims for ``CLEARANCE``). Against a named wall (``wall #2``) only that
wall counts; against the room (``some wall``) every wall does, and the nearest is
recorded as ``chosen``. A wall counts only where A stands beside it (its footprint
overlaps the wall's stretch): the far side of an L-shaped room's inner corner is not
a wall A stands near.

A placement of A by this relation alone draws a place in the room clear of the walls.
Where A has relations of other families that place it (a lamp beside its armchair), it
is placed by those only (``places_alone``), half the time then pushed straight off the
walls it came too close to (``snap``), so "beside the armchair, away from the wall"
lands where both hold.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from scenewright.core.errors import InputError
from scenewright.core.relations import Relation, RelationLabel
from scenewright.core.room import Room, Wall

from ..factors import equals
from ..motion import reach, uniform
from ..params import LayoutParams
from ..relation_terms import EPSILON, WALL_SIGMA2, WALL_TOLERANCE, Measure
from ..state import State
from ..terms import Endpoint, RelationTerm
from .entry import LayoutFamily, where

if TYPE_CHECKING:
    from ..placement import Placer

#: The gap (metres) the layout aims for between A's footprint and the walls it is kept
#: off; the relation holds from ``HOLDS_FROM`` (within the wall labels' tolerance of it).
#: An object with its back within 15 cm of a wall counts as set against it when examples
#: are read (``learning.pose_labels.HAND_GAP``), so the two labels never both hold.
CLEARANCE = 0.2
HOLDS_FROM = CLEARANCE - WALL_TOLERANCE
#: Random places in the room tried before the best of them is taken anyway.
PLACE_TRIES = 12


def _walls(term: RelationTerm, room: Room) -> list[Wall]:
    """The walls A is kept off: B's, or every wall for the room."""
    return list(room.walls) if term.b.kind == "room" else [room.walls[term.b.index]]


def _gap(box: int, wall: Wall, state: State, x: float, z: float) -> float:
    """The gap (metres) between box ``box``'s footprint at (x, z) and ``wall``; infinite
    where the footprint does not overlap the wall's stretch."""
    reach_u = reach(state.problem, state, box, *wall.direction)
    reach_v = reach(state.problem, state, box, *wall.normal)
    u, v = wall.to_wall(x, z)
    if u + reach_u < 0.0 or u - reach_u > wall.length:
        return math.inf
    return v - reach_v


def measure(term: RelationTerm, state: State, params: LayoutParams) -> Measure:
    """The gap to the nearest of the walls A is kept off (``distance``; that wall as
    ``chosen`` when B is the room); the energy grows with the square of how far A is
    short of ``CLEARANCE``, 0 beyond it."""
    box = term.a.index
    nearest, gap = None, math.inf
    for wall in _walls(term, state.problem.indoors()):
        found = _gap(box, wall, state, state.x[box], state.z[box])
        if found < gap:
            nearest, gap = wall, found
    energy = -equals(min(gap, CLEARANCE), CLEARANCE, WALL_SIGMA2)
    chosen = nearest.id if nearest is not None and term.b.kind == "room" else None
    return Measure(energy, distance=gap, chosen=chosen)


def holds(term: RelationTerm, measure: Measure, params: LayoutParams) -> bool:
    return measure.distance >= HOLDS_FROM - EPSILON


def complaint(term: RelationTerm, measure: Measure, params: LayoutParams) -> str:
    target = measure.chosen or term.target
    return (
        f"{term.source} is not {term.spec.phrase} {target} (it stands {measure.distance:.2f} m "
        f"from it, under {HOLDS_FROM:.2f} m)"
    )


def place(placer: Placer, term: RelationTerm, keep_heading: bool) -> dict | None:
    """A at a random place in the room, as it is turned, clear of the walls it is kept
    off: the first of ``PLACE_TRIES`` draws inside the room's bounding box that is, else
    the draw nearest to it."""
    problem, state, rng = placer.problem, placer.state, placer.rng
    box = term.a.index
    if problem.support[box] >= 0:
        return None  # it moves with what it rests on
    room = problem.indoors()
    x0, z0, x1, z1 = room.bounds
    walls = _walls(term, room)
    best, best_gap = None, -math.inf
    for _ in range(PLACE_TRIES):
        x, z = uniform(rng, x0, x1), uniform(rng, z0, z1)
        if not room.contains(x, z):
            continue
        gap = min(_gap(box, wall, state, x, z) for wall in walls)
        if gap > best_gap:
            best, best_gap = (x, z), gap
        if gap >= CLEARANCE:
            break
    if best is None:
        return None
    return placer.pose_box(box, best[0], best[1], state.yaw[box])


def snap(placer: Placer, term: RelationTerm) -> dict | None:
    """A pushed straight off each wall it stands closer to than ``CLEARANCE``, as it
    is turned; None when it is clear already."""
    problem, state = placer.problem, placer.state
    box = term.a.index
    if problem.support[box] >= 0:
        return None
    x, z = state.x[box], state.z[box]
    moved = False
    for wall in _walls(term, problem.indoors()):
        gap = _gap(box, wall, state, x, z)
        if gap < CLEARANCE:
            nx, nz = wall.normal  # into the room
            x, z = x + (CLEARANCE - gap) * nx, z + (CLEARANCE - gap) * nz
            moved = True
    return placer.pose_box(box, x, z, state.yaw[box]) if moved else None


def check_ends(
    edge: Relation, spec: RelationLabel, a: Endpoint, b: Endpoint, room: Room | None
) -> None:
    """Only an object is kept off a wall, and it is kept off a wall or the room's walls."""
    if a.kind != "object":
        raise InputError(
            f"{where(edge)}: only an object can stand away from a wall ({edge.source} is a {a.kind})"
        )
    if b.kind not in ("wall", "room"):
        raise InputError(f"{where(edge)}: the target must be a wall or the room")


FAMILY = LayoutFamily(
    measure=measure,
    holds=holds,
    complaint=complaint,
    place=place,
    snap=snap,
    places_alone=True,
    check_ends=check_ends,
)
