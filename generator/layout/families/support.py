"""OnTopOf*: A resting on B's top, where on it the label says (anywhere, the middle,
an edge, the front edge), turned as B or by a quarter turn more."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from scenewright.core.frames import to_world
from scenewright.core.geometry import to_local

from ..factors import equals, range_
from ..motion import HALF_PI, rigid, uniform, wrap
from ..params import LayoutParams
from ..relation_terms import EDGE_TOLERANCE, EPSILON, HEIGHT_TOLERANCE, MIDDLE_TOLERANCE, Measure
from ..state import State
from ..terms import RelationTerm
from .entry import LayoutFamily

if TYPE_CHECKING:
    from ..placement import Placer


def place(placer: Placer, term: RelationTerm, keep_heading: bool) -> dict:
    """A on B's top (``place_on_top``)."""
    return place_on_top(placer, term)


def place_on_top(placer: Placer, term: RelationTerm) -> dict:
    problem, state, rng = placer.problem, placer.state, placer.rng
    a, b = term.a.index, term.b.index
    quarter = int(rng.integers(4)) if rng.random() < 0.3 else 0
    yaw = wrap(state.yaw[b] + quarter * HALF_PI)
    # A's half extents along B's axes once turned to ``yaw``.
    ex, ez = (
        (problem.half_width[a], problem.half_depth[a])
        if quarter % 2 == 0
        else (problem.half_depth[a], problem.half_width[a])
    )
    room_x = max(problem.half_width[b] - ex, 0.0)
    room_z = max(problem.half_depth[b] - ez, 0.0)
    placement = term.spec.placement
    if placement == "middle":
        lx = lz = 0.0
    elif placement == "front_edge":
        lx, lz = uniform(rng, -room_x, room_x), room_z
    elif placement == "edge":
        edge = int(rng.integers(4))
        lx = (room_x if edge == 0 else -room_x) if edge < 2 else uniform(rng, -room_x, room_x)
        lz = (room_z if edge == 2 else -room_z) if edge >= 2 else uniform(rng, -room_z, room_z)
    else:
        lx, lz = uniform(rng, -room_x, room_x), uniform(rng, -room_z, room_z)
    x, z = to_world(state.x[b], state.z[b], state.yaw[b], lx, lz)
    return rigid(
        state,
        problem.carried(a),
        (state.x[a], state.z[a]),
        wrap(yaw - state.yaw[a]),
        (x - state.x[a], z - state.z[a]),
    )


# -- its energy, its threshold and its complaint ------------------------------------


def measure(term: RelationTerm, state: State, params: LayoutParams) -> Measure:
    problem = state.problem
    a, b = term.a.index, term.b.index
    top = state.y[b] + problem.height[b]
    height_gap = abs(state.y[a] - top)
    energy = -equals(state.y[a], top, params.sigma2)
    rect_b = state.rects[b]
    lx, lz = to_local(rect_b, state.x[a], state.z[a])
    hw, hd = rect_b.hw, rect_b.hd
    inside = abs(lx) <= hw and abs(lz) <= hd
    within = range_(lx, -hw, hw, params.h) + range_(lz, -hd, hd, params.h)
    placement = term.spec.placement
    if placement == "anywhere":
        return Measure(energy - within, height_gap=height_gap, inside=inside)
    if placement == "middle":
        offset = math.hypot(lx, lz)
        return Measure(
            energy - equals(offset, 0.0, params.sigma2),
            height_gap=height_gap,
            inside=inside,
            offset=offset,
        )
    # A's half extents along B's axes, then the gaps between A's sides and B's edges.
    k1 = abs(state.c[a] * state.c[b] + state.s[a] * state.s[b])
    k2 = abs(state.c[a] * state.s[b] - state.s[a] * state.c[b])
    ex = problem.half_width[a] * k1 + problem.half_depth[a] * k2
    ez = problem.half_width[a] * k2 + problem.half_depth[a] * k1
    front = abs(hd - lz - ez)
    if placement == "front_edge":
        offset = front
    else:
        offset = min(front, abs(hd + lz - ez), abs(hw - lx - ex), abs(hw + lx - ex))
    # Only a centre off the top is penalised here: a soft pull towards the middle would
    # fight the pull towards the edge.
    overhang = math.hypot(max(abs(lx) - hw, 0.0), max(abs(lz) - hd, 0.0))
    energy -= equals(offset, 0.0, params.sigma2) + equals(overhang, 0.0, params.sigma2)
    return Measure(energy, height_gap=height_gap, inside=inside, offset=offset)


def holds(term: RelationTerm, measure: Measure, params: LayoutParams) -> bool:
    on_top = measure.height_gap <= HEIGHT_TOLERANCE and measure.inside
    placement = term.spec.placement
    if placement == "middle":
        return on_top and measure.offset <= MIDDLE_TOLERANCE + EPSILON
    if placement in ("edge", "front_edge"):
        return on_top and measure.offset <= EDGE_TOLERANCE + EPSILON
    return on_top


def complaint(term: RelationTerm, measure: Measure, params: LayoutParams) -> str:
    if (
        term.spec.placement == "anywhere"
        or measure.height_gap > HEIGHT_TOLERANCE
        or not measure.inside
    ):
        return f"{term.source} is not on top of {term.target}"
    return f"{term.source} is not {term.spec.phrase} {term.target} ({measure.offset:.2f} m off)"


FAMILY = LayoutFamily(measure=measure, holds=holds, complaint=complaint, place=place)
