"""OnTopOf*: A resting on B's top, where on it the label says (anywhere, the middle,
an edge, the front edge), turned as B or by a quarter turn more."""

from __future__ import annotations

from typing import TYPE_CHECKING

from scenewright.core.frames import to_world

from ..motion import HALF_PI, rigid, uniform, wrap
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


FAMILY = LayoutFamily(place=place)
