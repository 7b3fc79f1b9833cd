"""Facing*: A turned towards B, away from it, or to a heading relative to B's.

The relation says nothing of where A goes: it turns A in place (or, half the time, the
whole top-level group holding A about its centre) once A has a place. A relation that
asks for a heading only (same, opposite or square to B's) fixes it whatever A's place,
so in a room the initial placement turns A first and places it after.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from scenewright.core.relations import RelationLabel

from ..factors import angle_between, equals, pointing_same_direction
from ..motion import HALF_PI, rigid, wrap
from ..params import LayoutParams
from ..relation_terms import (
    EPSILON,
    FACING_TOLERANCE,
    HEADING_FACINGS,
    Measure,
    anchor,
    blocked_complaint,
    centre,
    forward,
    sight_blocked,
    unit,
)
from ..state import State
from ..terms import Endpoint, RelationTerm
from .entry import LayoutFamily

if TYPE_CHECKING:
    from ..placement import Placer

#: A heading this close (radians) to the one a facing relation asks for already has it.
FACED = 1e-9


def place(placer: Placer, term: RelationTerm, keep_heading: bool) -> dict | None:
    """A turned so the relation holds: half the time the whole top-level group holding
    it (unless something in it is pinned), else A alone."""
    if (
        term.a.kind == "object"
        and term.a.index in placer.top_group_of
        and placer.rng.random() < 0.5
    ):
        if placer.group_whole[placer.top_group_of[term.a.index]]:
            return turn_group_to_face(placer, term)
    return turn_to_face(placer, term)


def turn_group_to_face(placer: Placer, term: RelationTerm) -> dict | None:
    """Turn the whole top-level group holding A about its centre so A faces as ``term``
    wants (None when something in the group is pinned)."""
    group = placer.top_group_of[term.a.index]
    if not placer.group_whole[group]:
        return None
    members = placer.problem.group_members[group]
    pivot = centre(Endpoint("group", group, members), placer.state)
    turn = _facing_turn(placer, term)
    return rigid(placer.state, placer.group_boxes[group], pivot, turn, (0.0, 0.0))


def turn_to_face(placer: Placer, term: RelationTerm) -> dict | None:
    """Turn A (an object, with what it carries) in place so the Facing* ``term`` holds."""
    if term.a.kind != "object":
        return None
    box = term.a.index
    pivot = (placer.state.x[box], placer.state.z[box])
    return rigid(
        placer.state, placer.problem.carried(box), pivot, _facing_turn(placer, term), (0.0, 0.0)
    )


def faces_as_asked(placer: Placer, term: RelationTerm) -> bool:
    """Whether A (an object) already has the heading a facing relation that asks for
    a heading only (same, opposite or square to B's) wants, to FACED (radians): then
    a turn to face would leave it where it is, and the constructive placement makes
    no such proposal. False for the other facing relations."""
    if (
        term.spec.facing not in HEADING_FACINGS
        or term.a.kind != "object"
        or term.b.kind not in ("object", "group")
    ):
        return False
    b_yaw = (
        placer.state.yaw[term.b.index] if term.b.kind == "object" else 0.0
    )  # a group faces the world's forward
    off = wrap(placer.state.yaw[term.a.index] - b_yaw)
    wanted = {"same": 0.0, "opposite": math.pi, "orthogonal": HALF_PI}[term.spec.facing]
    return abs(abs(off) - wanted) < FACED


def _facing_turn(placer: Placer, term: RelationTerm) -> float:
    """The turn of A (an object) after which the Facing* ``term`` holds."""
    state = placer.state
    a, b = term.a, term.b
    ax, az = state.x[a.index], state.z[a.index]
    bx, bz, c, s = anchor(b, state, (ax, az))
    how = term.spec.facing
    if how == "towards":
        yaw = math.atan2(bx - ax, bz - az)
    elif how == "away":
        yaw = math.atan2(ax - bx, az - bz)
    else:
        b_yaw = math.atan2(s, c) if b.kind != "group" else 0.0
        if how == "same":
            yaw = b_yaw
        elif how == "opposite":
            yaw = b_yaw + math.pi
        else:
            yaw = b_yaw + (HALF_PI if placer.rng.random() < 0.5 else -HALF_PI)
    return wrap(yaw - state.yaw[a.index])


def heading_only(term: RelationTerm) -> bool:
    """Whether the relation asks for a heading only (same, opposite or square to B's)."""
    return term.spec.facing in HEADING_FACINGS


def needs_sight(spec: RelationLabel) -> bool:
    """Facing towards or away from B needs a clear view of B."""
    return spec.facing in ("towards", "away")


# -- its energy, its threshold and its complaint ------------------------------------


def measure(term: RelationTerm, state: State, params: LayoutParams) -> Measure:
    fx, fz = forward(term.a, state)
    how = term.spec.facing
    if how in ("towards", "away"):
        ax, az = centre(term.a, state)
        bx, bz, _, _ = anchor(term.b, state, (ax, az))
        dx, dz = unit(bx - ax, bz - az) if how == "towards" else unit(ax - bx, az - bz)
        angle = angle_between(dx, dz, fx, fz)
        energy = -pointing_same_direction(dx, dz, fx, fz, params.sigma2)
        if term.sight:
            penalty, blocker = sight_blocked(term, state)
            return Measure(energy + penalty, angle=angle, blocker=blocker)
        return Measure(energy, angle=angle)
    gx, gz = forward(term.b, state)
    angle = angle_between(fx, fz, gx, gz)
    if how == "opposite":
        angle = math.pi - angle
        return Measure(-equals(angle, 0.0, params.sigma2), angle=angle)
    if how == "same":
        return Measure(-equals(angle, 0.0, params.sigma2), angle=angle)
    off = abs(angle - math.pi / 2.0)  # orthogonal
    return Measure(-equals(angle, math.pi / 2.0, params.sigma2), angle=off)


def holds(term: RelationTerm, measure: Measure, params: LayoutParams) -> bool:
    return measure.angle <= FACING_TOLERANCE + EPSILON and not measure.blocked


def complaint(term: RelationTerm, measure: Measure, params: LayoutParams) -> str:
    if measure.blocked:
        return blocked_complaint(term, measure)
    return f"{term.source} is not {term.spec.phrase} {term.target} ({math.degrees(measure.angle):.0f}° off)"


FAMILY = LayoutFamily(
    measure=measure,
    holds=holds,
    complaint=complaint,
    place=place,
    places=False,
    turn=turn_to_face,
    turn_group=turn_group_to_face,
    turned=faces_as_asked,
    heading_only=heading_only,
    needs_sight=needs_sight,
)
