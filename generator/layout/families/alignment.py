"""AlignedWith: A parallel to B with a face flush (rooms).

A is put beside B (backs or fronts in line) or in front of or behind it (a side in
line), or, for an A not held by a wall, half the time only corrected where it stands
(``snap_aligned``), so a desk a few centimetres out of its row is pushed back into
line instead of moved away. The relation is symmetric: a data-driven move may line B
up with A instead, and a placement of A by another relation may be snapped into line.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from scenewright.core.errors import InputError
from scenewright.core.frames import to_local, to_world
from scenewright.core.geometry import to_local as in_rect_frame
from scenewright.core.relations import Relation, RelationLabel
from scenewright.core.room import Room

from ..factors import angle_between, equals
from ..motion import uniform, wrap
from ..params import LayoutParams
from ..relation_terms import (
    ALIGN_TOLERANCE,
    EPSILON,
    WALL_ANGLE_SIGMA2,
    WALL_SIGMA2,
    WALL_TOLERANCE,
    Measure,
)
from ..state import State
from ..terms import Endpoint, RelationTerm
from .entry import LayoutFamily, where

if TYPE_CHECKING:
    from ..placement import Placer

#: Gaps (metres) a data-driven AlignedWith proposal leaves between A and B.
ALIGN_GAP = (0.02, 0.3)

#: Share of data-driven AlignedWith placements of an A without a wall relation that only
#: correct A where it stands (``snap_aligned``) rather than draw a new place beside B
#: (``place_aligned``).
SNAP_ALIGN_SHARE = 0.5


def place(placer: Placer, term: RelationTerm, keep_heading: bool) -> dict | None:
    """A lined up with B. Not snapped for an A held by a wall: standing against B's
    wall lines its back up with B's already, and a shift in B's frame could take it
    off the wall."""
    if term.a.index not in placer.wall_terms and placer.rng.random() < SNAP_ALIGN_SHARE:
        return snap_aligned(placer, term.a.index, term.b.index)
    return place_aligned(placer, term.a.index, term.b.index)


def place_target(placer: Placer, term: RelationTerm) -> dict | None:
    """B lined up with A (the relation is symmetric)."""
    return place_aligned(placer, term.b.index, term.a.index)


def snap(placer: Placer, term: RelationTerm) -> dict | None:
    """A lined up with B by the smallest correction from where it stands."""
    return snap_aligned(placer, term.a.index, term.b.index)


def place_aligned(placer: Placer, mover: int, other: int) -> dict | None:
    """Box ``mover`` parallel to box ``other`` with a face flush: beside it (to its left
    or right) with the backs or the fronts in one line, or in front of or behind it
    with a side in line with its side, at a small gap. A box already parallel keeps
    its way round (same or opposite heading); another takes ``other``'s heading."""
    problem, state, rng = placer.problem, placer.state, placer.rng
    if problem.support[mover] >= 0 or not placer.movable_box[mover]:
        return None
    b_yaw = state.yaw[other]
    dot = state.s[mover] * state.s[other] + state.c[mover] * state.c[other]
    yaw = b_yaw + math.pi if dot < -0.5 else b_yaw
    ex, ez = problem.half_width[mover], problem.half_depth[mover]  # parallel: its axes are B's
    hw, hd = problem.half_width[other], problem.half_depth[other]
    gap = uniform(rng, *ALIGN_GAP)
    side = 1.0 if rng.random() < 0.5 else -1.0
    if rng.random() < 0.75:  # beside B, backs (mostly) or fronts flush
        lx = side * (hw + ex + gap)
        lz = ez - hd if rng.random() < 0.7 else hd - ez
    else:  # in front of or behind B, a side flush
        lz = side * (hd + ez + gap)
        lx = hw - ex if rng.random() < 0.5 else ex - hw
    x, z = to_world(state.x[other], state.z[other], b_yaw, lx, lz)
    return placer.pose_box(mover, x, z, wrap(yaw))


def snap_aligned(placer: Placer, mover: int, other: int) -> dict | None:
    """Box ``mover`` lined up with box ``other`` by the smallest correction: turned
    parallel to it (whichever way round is nearer) about its own centre, then shifted
    along one of ``other``'s axes until the nearest pair of faces that can be flush
    without the two overlapping is flush. A desk 6 cm out of line with its neighbour
    in a row is pushed back into line where it stands, still beside it, where
    ``place_aligned`` would draw a new place (and break what holds there)."""
    problem, state = placer.problem, placer.state
    if problem.support[mover] >= 0 or not placer.movable_box[mover]:
        return None
    b_yaw = state.yaw[other]
    dot = state.s[mover] * state.s[other] + state.c[mover] * state.c[other]
    yaw = wrap(b_yaw + math.pi if dot < 0.0 else b_yaw)
    ex, ez = problem.half_width[mover], problem.half_depth[mover]  # parallel: its axes are B's
    hw, hd = problem.half_width[other], problem.half_depth[other]
    lx, lz = to_local(state.x[other], state.z[other], b_yaw, state.x[mover], state.z[mover])
    best = None
    for axis, flush in ((0, hw - ex), (0, ex - hw), (1, hd - ez), (1, ez - hd)):
        nx, nz = (flush, lz) if axis == 0 else (lx, flush)
        if abs(nx) < hw + ex - 1e-9 and abs(nz) < hd + ez - 1e-9:
            continue  # the two would overlap
        shift = abs(nx - lx) + abs(nz - lz)
        if best is None or shift < best[0]:
            best = (shift, nx, nz)
    if best is None:  # A lies across B: no face can be made flush by one shift
        return place_aligned(placer, mover, other)
    x, z = to_world(state.x[other], state.z[other], b_yaw, best[1], best[2])
    return placer.pose_box(mover, x, z, yaw)


def check_ends(
    edge: Relation, spec: RelationLabel, a: Endpoint, b: Endpoint, room: Room | None
) -> None:
    """Only two objects can be lined up."""
    if a.kind != "object" or b.kind != "object":
        raise InputError(f"{where(edge)}: only two objects can be lined up")


# -- its energy, its threshold and its complaint ------------------------------------


def measure(term: RelationTerm, state: State, params: LayoutParams) -> Measure:
    """A parallel to B (facing the same or the opposite way) with one of its faces in
    the plane of B's face on the same side: ``angle`` off parallel, ``offset`` the gap
    between the nearest pair of flush faces."""
    problem = state.problem
    a, b = term.a.index, term.b.index
    angle = angle_between(state.s[a], state.c[a], state.s[b], state.c[b])
    angle = min(angle, math.pi - angle)
    rect_b = state.rects[b]
    lx, lz = in_rect_frame(rect_b, state.x[a], state.z[a])
    k1 = abs(state.c[a] * state.c[b] + state.s[a] * state.s[b])
    k2 = abs(state.c[a] * state.s[b] - state.s[a] * state.c[b])
    ex = problem.half_width[a] * k1 + problem.half_depth[a] * k2
    ez = problem.half_width[a] * k2 + problem.half_depth[a] * k1
    hw, hd = rect_b.hw, rect_b.hd
    offset = min(abs(lz + ez - hd), abs(lz - ez + hd), abs(lx + ex - hw), abs(lx - ex + hw))
    energy = -equals(angle, 0.0, WALL_ANGLE_SIGMA2) - equals(offset, 0.0, WALL_SIGMA2)
    return Measure(energy, angle=angle, offset=offset)


def holds(term: RelationTerm, measure: Measure, params: LayoutParams) -> bool:
    return measure.angle <= ALIGN_TOLERANCE + EPSILON and measure.offset <= WALL_TOLERANCE + EPSILON


def complaint(term: RelationTerm, measure: Measure, params: LayoutParams) -> str:
    return (
        f"{term.source} is not {term.spec.phrase} {term.target} "
        f"({math.degrees(measure.angle):.0f}° off parallel, faces {measure.offset:.2f} m apart)"
    )


FAMILY = LayoutFamily(
    measure=measure,
    holds=holds,
    complaint=complaint,
    place=place,
    place_target=place_target,
    snap=snap,
    check_ends=check_ends,
)
