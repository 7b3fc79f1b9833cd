"""How a piece stands to the windows and to other pieces, learned from the plans
(completion.neighbours), and the relations a completed room takes from it."""

from __future__ import annotations

import math

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from test_plans_model import EAST, SOUTH, WEST, _plan, _room

from scenewright.completion.contents import Contents
from scenewright.completion.floor_plan import Furniture
from scenewright.completion.furnishing import build_graph
from scenewright.completion.layout_mask import amalgamated_mask
from scenewright.completion.model_builder import build_model
from scenewright.completion.neighbours import faced, gap_before, is_beside, is_under_window
from scenewright.completion.stances import (
    BEFORE,
    beside_target,
    facing_target,
    stance,
    touched_walls,
    under_window,
)
from scenewright.core.room import Room


def _living(plan_id, armchair_at_wall=False):
    """A 5 x 5 m living room: the television stand against the west wall, the sofa
    facing it (against the east wall, or 0.65 m off it), the coffee table 0.35 m before
    the sofa and an armchair beside the table, facing it (free, or with its back to the
    north wall)."""
    x, table_z, chair_z = (-0.6, -0.7, -2.1) if armchair_at_wall else (0.0, 0.0, -1.35)
    return _plan(
        plan_id,
        "living_room",
        _room(5.0, 5.0),
        ("tv_stand", -2.275, 0.0, (1.6, 0.45), EAST),
        ("sofa", 2.0 + x, 0.0, (2.0, 0.9), WEST),
        ("coffee_table", 0.9 + x, table_z, (1.1, 0.6), WEST),
        ("armchair", 0.7 + x, chair_z, (0.8, 0.8), SOUTH),
    )


def _tiny():
    """Five living rooms (``_living``: a share needs five pieces behind it), one with
    its armchair at a wall, and a study whose desk stands under the window of the north
    wall, a bookshelf against the west wall."""
    study = _plan(
        "d_study",
        "study",
        _room(5.0, 5.0),
        ("desk", 0.0, -2.2, (1.2, 0.6), SOUTH),
        ("bookshelf", -2.34, 0.0, (0.9, 0.32), EAST),
    )
    living = [_living(f"living_{k}", armchair_at_wall=k == 0) for k in range(5)]
    return [*living, study]


@pytest.fixture(scope="module")
def tiny_model():
    return build_model(_tiny())


def test_the_tests_a_plan_piece_is_measured_by():
    plan = _living("a_living")
    tv_stand, sofa, table, armchair = plan.furniture
    # The sofa looks past the coffee table standing before it to the television stand.
    assert faced(sofa, [tv_stand, table, armchair], {table.id: sofa.id}) is tv_stand
    assert faced(sofa, [tv_stand, table, armchair], {}) is table
    assert faced(armchair, [tv_stand, sofa, table], {table.id: sofa.id}) is table
    assert faced(tv_stand, [sofa, table, armchair], {table.id: sofa.id}) is table
    assert gap_before(table, sofa) == pytest.approx(0.35)
    assert is_beside(armchair, table) and not is_beside(table, sofa)
    room = _room(5.0, 5.0)
    desk = Furniture("desk_1", "desk", (0.0, -2.2), (1.2, 0.6), SOUTH)
    off = Furniture("desk_2", "desk", (1.6, -2.2), (1.2, 0.6), SOUTH)  # beside the window's span
    assert is_under_window(desk, room, touched_walls(desk, room).get("back"))
    assert not is_under_window(off, room, touched_walls(off, room).get("back"))
    assert not is_under_window(table, room, touched_walls(table, room).get("back"))


def test_a_small_plan_set_teaches_window_facing_beside_and_close(tiny_model):
    stances = tiny_model.stances
    assert stances["desk"].window == 1.0 and stances["bookshelf"].window == 0.0
    assert stances["sofa"].facing == {"tv_stand": 1.0}
    assert stances["armchair"].facing == {"coffee_table": 1.0}
    assert stances["armchair"].beside == {"coffee_table": 1.0}
    assert stances["coffee_table"].close == {"sofa": 1.0}
    assert (stances["armchair"].free, stances["armchair"].wall) == pytest.approx((0.8, 0.2))
    # Nothing is named: what the plans show decides.
    present = {"tv_stand", "sofa", "coffee_table", "armchair", "desk"}
    assert under_window(tiny_model, "desk") and not under_window(tiny_model, "sofa")
    assert facing_target(tiny_model, "sofa", present) == "tv_stand"
    assert facing_target(tiny_model, "sofa", present - {"tv_stand"}) is None
    assert facing_target(tiny_model, "tv_stand", present) is None  # always at its wall
    assert beside_target(tiny_model, "armchair", present) == "coffee_table"
    assert stance(tiny_model, "coffee_table", present) == (BEFORE, ("sofa",))


def _relations(model, catalog, counts, room):
    """(category, label, target category or room) of the room holding exactly ``counts``."""
    mask = amalgamated_mask(model, "living_room", room, counts)
    contents = Contents(("living_room",), {}, {}, counts, mask)
    graph, _, _ = build_graph(model, contents, room, catalog)
    out = set()
    for relation in graph.edges():
        source = graph.node(relation.source).type
        target = "room" if relation.target == "room" else graph.node(relation.target).type
        out.add((source, relation.label, target))
    return out


def test_the_learned_neighbours_make_the_relations(tiny_model, catalog):
    room = _room(5.0, 5.0)
    counts = {"tv_stand": 1, "sofa": 1, "coffee_table": 1, "armchair": 1, "desk": 1}
    every = _relations(tiny_model, catalog, counts, room)
    assert ("desk", "UnderWindow", "room") in every
    assert {("sofa", "FacingTowards", "tv_stand"), ("sofa", "ImplicitAgainstWall", "room")} <= every
    assert ("coffee_table", "NextToFront", "sofa") in every
    assert {
        ("armchair", "NextToChooseSide", "coffee_table"),
        ("armchair", "FacingTowards", "coffee_table"),
    } <= every
    # Without a window the desk stands by the room as most of its pieces did.
    windowless = Room.rectangle(5.0, 5.0).with_opening("door", "wall_3", 2.5, 0.9)
    assert ("desk", "UnderWindow", "room") not in _relations(
        tiny_model, catalog, {"desk": 1}, windowless
    )
    # Without what they face or stand by, they stand by the room.
    alone = _relations(tiny_model, catalog, {"sofa": 1, "armchair": 1}, room)
    assert ("sofa", "AgainstWall", "room") in alone
    assert not any(label in ("FacingTowards", "NextToChooseSide") for _, label, _ in alone)


def test_the_shipped_plans_teach_the_living_room_and_the_study(model):
    present = {"tv_stand", "sofa", "coffee_table", "armchair", "desk", "dining_table", "dresser"}
    assert under_window(model, "desk")
    assert not any(under_window(model, name) for name in present - {"desk"})
    assert facing_target(model, "sofa", present) == "tv_stand"
    assert beside_target(model, "armchair", present) == "coffee_table"
    assert facing_target(model, "armchair", present) == "coffee_table"
    assert stance(model, "coffee_table", present) == (BEFORE, ("sofa",))
    # A dining table a metre or more from the sideboard stands free, not before it.
    assert stance(model, "dining_table", present)[0] != BEFORE
    # Pieces always at a wall take their heading from it.
    assert facing_target(model, "tv_stand", present) is None
    assert facing_target(model, "dresser", present) is None


@settings(max_examples=20, deadline=None)
@given(turn=st.sampled_from([0.0, math.pi / 2, math.pi, -math.pi / 2]), dx=st.floats(-5, 5))
def test_the_tests_do_not_depend_on_where_the_room_is_or_which_way_it_turns(turn, dx):
    plan = _living("a_living")

    def moved(piece):
        c, s = math.cos(turn), math.sin(turn)
        x, z = piece.center
        return Furniture(
            piece.id,
            piece.category,
            (x * c + z * s + dx, -x * s + z * c),
            piece.size,
            piece.yaw + turn,
        )

    tv_stand, sofa, table, armchair = (moved(piece) for piece in plan.furniture)
    assert faced(sofa, [tv_stand, table], {table.id: sofa.id}) is tv_stand
    assert faced(armchair, [tv_stand, sofa, table], {}) is table
    assert is_beside(armchair, table) and not is_beside(sofa, table)
    assert gap_before(table, sofa) == pytest.approx(0.35)
