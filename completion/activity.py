"""How each category is used, and the activity prior A(o_i, o_j) that follows from it.

The paper's activity prior is a binary matrix over categories (Section 4.2). Two
categories are related when

- both have the functional purpose *stay* (a person stays at it a long time: a bed, a
  chair, a sofa, a piano), or one stays and the other has the purpose *fetch* (a short
  visit to take something: a wardrobe, a bookshelf, a refrigerator), since fetching
  serves an activity one then does staying (a book from the shelf, read in bed); or
- in some plan a person using one of them has the other in their *touch area* (within
  arm's reach, ``TOUCH_REACH``) or *visual area* (in front of them: within
  ``VISUAL_HALF_ANGLE`` of where they face and ``VISUAL_RANGE``), as the bed's sleeper
  has the night table in reach and the television in view.

The paper labels each plan's people by hand. Here each stay or fetch category has one
use pose, read off its shape's "used from" convention (``core.shapes``): a person lies
on a bed with their head at the headboard, sits on a seat facing its front, sits on the
bench before a piano, stands before a wardrobe facing it, walks on a treadmill or rides
a bike facing its console. A seated person's body is
0.25 m behind the seat's front edge, whatever the seat's depth, so the coffee table
0.45 m before a deep sofa is within their reach. The paper's "all regions in
front of the agent" would relate nearly everything in a room to a bed; a 60-degree
cone is the field one watches a television or a desk in, so that is the visual area.
Things nobody stays at or fetches from (a table, a night table, a television) have no
pose: they are reached through the people at the others.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from scenewright.core.frames import to_local, to_world, yaw_of

#: Metres from where a person is to what their hand reaches.
TOUCH_REACH = 0.8
#: Half the angle of the visual area, and how far it reaches (metres).
VISUAL_HALF_ANGLE = math.radians(30.0)
VISUAL_RANGE = 6.0

STAY, FETCH = "stay", "fetch"


@dataclass(frozen=True)
class UsePose:
    """Where a person is when using a piece, in the piece's frame: ``anchor`` is the
    face measured from (``back``, ``centre`` or ``front``), ``distance`` metres from it
    along the piece's forward (+Z) axis; ``towards`` says they face the piece (-Z)
    rather than where it faces (+Z)."""

    anchor: str
    distance: float
    towards: bool


#: Seated with the knees at the seat's front edge: the body 0.25 m behind it.
_SEATED = UsePose("front", -0.25, towards=False)
_STANDING_BEFORE = UsePose("front", 0.4, towards=True)

#: Category -> (functional purpose, use pose): the categories people are placed at.
USES: dict[str, tuple[str, UsePose]] = {
    "bed": (STAY, UsePose("back", 0.35, towards=False)),
    "sofa": (STAY, _SEATED),
    "armchair": (STAY, _SEATED),
    "chair": (STAY, _SEATED),
    "office_chair": (STAY, _SEATED),
    "piano": (STAY, UsePose("front", 0.35, towards=True)),
    "wardrobe": (FETCH, _STANDING_BEFORE),
    "dresser": (FETCH, _STANDING_BEFORE),
    "bookshelf": (FETCH, _STANDING_BEFORE),
    "filing_cabinet": (FETCH, _STANDING_BEFORE),
    "refrigerator": (FETCH, _STANDING_BEFORE),
    "kitchen_counter": (FETCH, _STANDING_BEFORE),
    # Gym equipment is stayed at (the paper's gym: one exercises on a machine a while):
    # on a treadmill's belt, a bike's saddle or a rower's seat one faces the console or
    # flywheel at the back; one sits on a bench's seat end, lies on a mat; the weights
    # are fetched from their rack.
    "treadmill": (STAY, UsePose("front", -0.7, towards=True)),
    "exercise_bike": (STAY, UsePose("front", -0.3, towards=True)),
    "rowing_machine": (STAY, UsePose("front", -1.0, towards=True)),
    "weight_bench": (STAY, _SEATED),
    "exercise_mat": (STAY, UsePose("centre", 0.0, towards=False)),
    "dumbbell_rack": (FETCH, _STANDING_BEFORE),
}

#: Categories that may stand in another piece's clearance: one sits on them at it.
SEATS = frozenset({"chair", "office_chair"})


def purpose(category: str) -> str | None:
    """``"stay"``, ``"fetch"`` or None."""
    use = USES.get(category)
    return use[0] if use else None


def purposes_relate(first: str, second: str) -> bool:
    """The paper's functional-purpose rule: both stay, or one stays and one is fetched from."""
    kinds = {purpose(first), purpose(second)}
    return kinds == {STAY} or kinds == {STAY, FETCH}


def person_at(piece) -> tuple[tuple[float, float], tuple[float, float]] | None:
    """Where a person using ``piece`` (a ``plan.Furniture``) is and the unit direction
    they face, both (x, z); None for a category nobody is placed at."""
    use = USES.get(piece.category)
    if use is None:
        return None
    pose = use[1]
    half_depth = piece.size[1] / 2.0
    start = {"back": -half_depth, "centre": 0.0, "front": half_depth}[pose.anchor]
    position = to_world(piece.center[0], piece.center[1], piece.yaw, 0.0, start + pose.distance)
    sign = -1.0 if pose.towards else 1.0
    return position, (sign * math.sin(piece.yaw), sign * math.cos(piece.yaw))


def interactions(plan) -> list[tuple[str, str, str]]:
    """Each (category of the piece used, category of the piece reached, ``"touch"`` or
    ``"visual"``) found in ``plan``, once each, sorted."""
    found = set()
    for user in plan.furniture:
        person = person_at(user)
        if person is None:
            continue
        (px, pz), (fx, fz) = person
        for other in plan.furniture:
            if other.id == user.id:
                continue
            if _distance_to_footprint(other, px, pz) <= TOUCH_REACH:
                found.add((user.category, other.category, "touch"))
            elif _in_view(other, px, pz, yaw_of(fx, fz)):
                found.add((user.category, other.category, "visual"))
    return sorted(found)


def activity_prior(plans) -> dict[tuple[str, str], str]:
    """A(o_i, o_j) = 1 pairs over every category of ``plans``: each related pair (the
    two names sorted) with why (``purpose``, ``touch`` or ``visual``, the first found in
    that order). A category is not related to itself."""
    categories = sorted({piece.category for plan in plans for piece in plan.furniture})
    prior: dict[tuple[str, str], str] = {}
    for k, first in enumerate(categories):
        for second in categories[k + 1 :]:
            if purposes_relate(first, second):
                prior[(first, second)] = "purpose"
    seen: dict[tuple[str, str], str] = {}
    for plan in plans:
        for used, reached, area in interactions(plan):
            if used != reached:
                pair = (min(used, reached), max(used, reached))
                if seen.get(pair) != "touch":
                    seen[pair] = area
    for pair, area in sorted(seen.items()):
        prior.setdefault(pair, area)
    return dict(sorted(prior.items()))


def _distance_to_footprint(piece, x: float, z: float) -> float:
    lx, lz = to_local(piece.center[0], piece.center[1], piece.yaw, x, z)
    dx = max(abs(lx) - piece.size[0] / 2.0, 0.0)
    dz = max(abs(lz) - piece.size[1] / 2.0, 0.0)
    return math.hypot(dx, dz)


#: Points of a footprint tested for being in view, as fractions of its half sizes.
_VIEW_SAMPLES = np.array([(a, b) for a in (-1.0, -0.5, 0.0, 0.5, 1.0) for b in (-1.0, 0.0, 1.0)])


def _in_view(piece, x: float, z: float, facing_yaw: float) -> bool:
    """Whether some of ``piece``'s footprint lies in the visual area of a person at
    (x, z) facing ``facing_yaw``."""
    half = np.array(piece.size) / 2.0
    for lx, lz in _VIEW_SAMPLES * half:
        wx, wz = to_world(piece.center[0], piece.center[1], piece.yaw, lx, lz)
        ahead_x, ahead_z = to_local(x, z, facing_yaw, wx, wz)  # (left, forward) of the person
        distance = math.hypot(ahead_x, ahead_z)
        if (
            0.0 < distance <= VISUAL_RANGE
            and ahead_z > 0.0
            and math.atan2(abs(ahead_x), ahead_z) <= VISUAL_HALF_ANGLE
        ):
            return True
    return False
