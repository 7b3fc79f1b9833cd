"""How each category stands in the room, learned from the plans (completion.stances)."""

from __future__ import annotations

import pytest
from test_plans_model import EAST, SOUTH, _plan, _room

from scenewright.completion.furnishing import build_graph
from scenewright.completion.model_builder import build_model
from scenewright.completion.request import parse_request
from scenewright.completion.stances import (
    BEFORE,
    CORNER,
    FREE,
    PARTNER,
    ROW,
    WALL,
    base_stance,
    learned_stance,
    stance,
    stands_by_room,
)


def _tiny():
    """A study with two bookshelves side by side against the west wall and a plant in
    the north-east corner; a dining room with its table free in the middle; a living
    room with its sofa against the west wall and a rug before it (4 x 3 m rooms, the
    door in the middle of the south wall)."""
    study = _plan(
        "a_study",
        "study",
        _room(),
        ("bookshelf", -1.84, -0.5, (0.9, 0.32), EAST),
        ("bookshelf", -1.84, 0.45, (0.9, 0.32), EAST),  # 5 cm beside the first, backs in line
        ("plant", 1.75, -1.25, (0.4, 0.4), SOUTH),  # 5 cm from the north and east walls
    )
    dining = _plan("b_dining", "dining_room", _room(), ("dining_table", 0.0, 0.0, (1.6, 0.9), 0.0))
    living = _plan(
        "c_living",
        "living_room",
        _room(),
        ("sofa", -1.55, 0.0, (2.0, 0.9), EAST),
        ("rug", -0.2, 0.0, (2.0, 1.4), EAST),  # its centre 0.9 m before the sofa's front
    )
    return [study, dining, living]


@pytest.fixture(scope="module")
def tiny_model():
    return build_model(_tiny())


def test_a_small_plan_set_teaches_wall_row_corner_free_and_before(tiny_model):
    shelf = tiny_model.stances["bookshelf"]
    assert (shelf.pieces, shelf.wall, shelf.corner, shelf.free) == (2, 1.0, 0.0, 0.0)
    assert shelf.row == {"bookshelf": 1.0} and shelf.before == {}
    plant = tiny_model.stances["plant"]
    assert (plant.corner, plant.wall, plant.free) == (1.0, 0.0, 0.0)
    table = tiny_model.stances["dining_table"]
    assert (table.free, table.wall, table.row) == (1.0, 0.0, {})
    rug = tiny_model.stances["rug"]
    assert rug.flat and rug.before == {"sofa": 1.0}
    assert tiny_model.stances["sofa"].wall == 1.0 and not tiny_model.stances["sofa"].flat


def test_each_category_is_placed_the_way_most_of_its_plan_pieces_stand(tiny_model):
    present = {"bookshelf", "plant", "dining_table", "sofa", "rug"}
    assert stance(tiny_model, "bookshelf", present) == (ROW, ("bookshelf",))
    assert stance(tiny_model, "plant", present) == (CORNER, ())
    assert stance(tiny_model, "dining_table", present) == (FREE, ())
    assert stance(tiny_model, "sofa", present) == (WALL, ())
    assert stance(tiny_model, "rug", present) == (BEFORE, ("sofa",))
    assert stance(tiny_model, "rug", {"rug"}) == (BEFORE, ())  # nothing it lay before: its partner
    # The mask and a split room's regions go by the large pieces against a wall or free.
    assert stands_by_room(tiny_model, "bookshelf") and stands_by_room(tiny_model, "dining_table")
    assert not stands_by_room(tiny_model, "plant") and not stands_by_room(tiny_model, "rug")


def test_a_category_the_plans_never_show_takes_the_pooled_shares(tiny_model):
    # Of the five pieces neither flat nor accessories: 3 against a wall, 1 in a corner, 1 free.
    pooled = learned_stance(tiny_model, "wardrobe")
    assert pooled.pieces == 0 and not pooled.flat and (pooled.row, pooled.before) == ({}, {})
    assert (pooled.wall, pooled.corner, pooled.free) == pytest.approx((0.6, 0.2, 0.2))
    assert base_stance(tiny_model, "wardrobe") == WALL


def test_the_shipped_plans_teach_where_the_big_pieces_stand(model):
    stances = model.stances
    for name in ("bed", "wardrobe", "dresser", "bookshelf", "tv_stand", "dumbbell_rack"):
        assert stances[name].wall + stances[name].corner == 1.0, name
        assert base_stance(model, name) == WALL, name
    for name in ("sofa", "desk", "treadmill", "exercise_bike", "rowing_machine"):
        assert base_stance(model, name) == WALL, name
    for name in ("dining_table", "coffee_table"):
        assert stances[name].free == 1.0 and base_stance(model, name) == FREE, name
    for name in ("plant", "floor_lamp"):
        assert stances[name].corner > 0.5 and base_stance(model, name) == CORNER, name
    assert stances["bookshelf"].row["bookshelf"] > 0.8
    assert stances["treadmill"].row["treadmill"] == 1.0
    assert stances["rug"].flat and min(stances["rug"].before[n] for n in ("sofa", "bed")) > 0.5
    assert stances["exercise_mat"].flat
    # Half the weight benches stand at a wall, 4 in 10 free: by the room alone neither is
    # most, so what they stand before decides.
    assert base_stance(model, "weight_bench") == PARTNER
    assert stance(model, "weight_bench", {"dumbbell_rack"}) == (BEFORE, ("dumbbell_rack",))
    assert stance(model, "weight_bench", {"weight_bench"}) == (WALL, ())  # as many at a wall


def test_learned_stances_make_the_relations_of_a_completed_room(model, catalog):
    from scenewright.completion.contents import choose_contents

    request = parse_request("6x5", ["S:1:0.9"], ["N:3:1.4"], ["bookshelf=2,plant,rug,bed"], catalog)
    contents = choose_contents(model, request)
    graph, _, _ = build_graph(model, contents, request.room, catalog)
    labels = {}
    for relation in graph.edges():
        source = graph.node(relation.source).type
        target = "room" if relation.target == "room" else graph.node(relation.target).type
        labels.setdefault(relation.source, set()).add((source, relation.label, target))
    every = set().union(*labels.values())
    assert ("bed", "AgainstWall", "room") in every
    assert ("plant", "InCorner", "room") in every
    # The selection adds a sofa: the rug lies before it (the plans' rugs, most often).
    assert ("rug", "NextToFront", "sofa") in every
    assert ("armchair", "NextToChooseSide", "coffee_table") in every
    shelves = [ids for ids in labels.values() if any(s == "bookshelf" for s, _, _ in ids)]
    assert {("bookshelf", "AgainstWall", "room")} in shelves  # the first stands by the room
    assert any(("bookshelf", "NextToChooseSide", "bookshelf") in ids for ids in shelves)


def test_the_mask_term_is_for_the_pieces_that_stand_by_the_room(model, catalog):
    from scenewright.completion.complete import masked
    from scenewright.completion.contents import choose_contents

    request = parse_request("5x4", ["S:0.8:0.9"], ["E:2:1.2"], ["sofa,armchair"], catalog)
    contents = choose_contents(model, request)
    graph, _, _ = build_graph(model, contents, request.room, catalog)
    types = {box: graph.node(box).type for box in masked(model, graph)}
    assert "sofa" in types.values()  # against a wall (facing the television stand)
    # Beside the coffee table, not by the room: the armchair follows the table.
    assert "armchair" not in types.values() and "coffee_table" in contents.counts
    assert not {"tv", "rug", "plant"} & set(types.values())  # accessory, flat, corner
