"""Rooms in the rules language: the room block, doors, windows, clearance and access,
wall relations, and the errors a rules author meets there, each at its place."""

import math

import pytest

from scenewright.core.room import ROOM_NODE
from scenewright.generator import check_rules, format_diagnostics, load_rules
from scenewright.generator.expand import expand

ROOM = """\
scene s {
    room 5 x 4 {
        height 2.7
        door south 1.0 0.9
        window north 2.5 1.4 0.9 1.2
    }
    start S
}
object wardrobe { noun "wardrobe" size 1.2 x 2 x 0.6 clearance front 0.8 clearance left 0.1 access front wall_gap 0.03 }
object plant { noun "plant" size 0.4 x 1 x 0.4 access none }
"""


def diagnostics(tmp_path, text: str) -> str:
    (tmp_path / "room.rules").write_text(text)
    return format_diagnostics(check_rules(tmp_path / "room.rules"))


def test_a_room_block_builds_walls_doors_and_windows(tmp_path):
    (tmp_path / "room.rules").write_text(
        ROOM + "S -> { wardrobe AgainstWall some wall; plant UnderWindow window #1 }\n"
    )
    rules = load_rules(tmp_path / "room.rules")
    room = rules.params.room
    assert [wall.side for wall in room.walls] == ["north", "east", "south", "west"]
    assert rules.params.extent == (5.0, 4.0) and all(wall.height == 2.7 for wall in room.walls)
    door, window = room.openings
    assert (door.id, door.kind, door.wall, door.width, door.sill) == (
        "door_1",
        "door",
        "wall_3",
        0.9,
        0.0,
    )
    assert door.center == (1.5, 2.0)  # 1 m along the south wall from its east end
    assert (window.wall, window.sill, window.height, window.width) == ("wall_1", 0.9, 1.2, 1.4)
    wardrobe = rules.catalog["wardrobe"]
    assert wardrobe.clearance == (("front", 0.8), ("left", 0.1)) and wardrobe.access == ("front",)
    assert wardrobe.wall_gap == 0.03 and rules.catalog["plant"].wall_gap is None
    assert rules.catalog["plant"].access == ()
    assert rules.params.square and rules.params.line_of_sight


def test_some_wall_targets_the_room_and_an_ordinal_names_one(tmp_path):
    (tmp_path / "room.rules").write_text(
        ROOM + "S -> { wardrobe AgainstWall some wall; plant UnderWindow window #1 }\n"
    )
    graph = expand(load_rules(tmp_path / "room.rules"), 3)
    edges = {(edge.source, edge.label): edge.target for edge in graph.edges()}
    assert edges == {
        ("wardrobe_1", "AgainstWall"): ROOM_NODE,
        ("plant_1", "UnderWindow"): "window_1",
    }
    kinds = [node.kind for node in graph.nodes()]
    assert kinds[:7] == ["room", "wall", "wall", "wall", "wall", "door", "window"]
    assert graph.derivation == []  # the layout picks the wall: expansion draws nothing


def test_room_nodes_do_not_count_against_max_nodes(tmp_path):
    text = ROOM.replace("start S", "start S\n    max_nodes 2") + "S -> { 2 plant }\n"
    (tmp_path / "room.rules").write_text(text)
    assert len(expand(load_rules(tmp_path / "room.rules"), 0).nodes("object")) == 2


def test_an_l_shaped_room_by_its_corners(tmp_path):
    text = """\
scene s {
    room (0, 0) (6, 0) (6, 3) (3, 3) (3, 5) (0, 5) { door 4 1 0.8; window 1 3 2 1 1 }
    square off
    line_of_sight off
    start S
}
object desk { noun "desk" size 1.2 x 0.75 x 0.6 }
S -> { desk AgainstWall wall #4 }
"""
    (tmp_path / "room.rules").write_text(text)
    rules = load_rules(tmp_path / "room.rules")
    room = rules.params.room
    assert len(room.walls) == 6 and rules.params.extent == (6.0, 5.0)
    assert room.corners[0] == (-3.0, -2.5)  # moved so the bounding box is centred
    assert (
        room.openings[0].wall == "wall_4"
        and not rules.params.square
        and not rules.params.line_of_sight
    )
    assert math.isclose(room.area, 6 * 3 + 3 * 2)


def test_walls_is_still_a_bare_rectangular_room(tmp_path):
    (tmp_path / "room.rules").write_text(
        'scene s { extent 4 x 3\n walls\n start S }\nobject a { noun "a" }\nS -> { a }\n'
    )
    room = load_rules(tmp_path / "room.rules").params.room
    assert room.extent == (4.0, 3.0) and room.openings == ()


@pytest.mark.parametrize(
    ("body", "where", "message"),
    [
        (
            "room 5 x 4 { door east 2 4.5 }",
            "2:18",
            "the door (4.5 m wide) is wider than wall 2 (the east wall) (4 m)",
        ),
        (
            "room 5 x 4 { door south 4.8 0.9 }",
            "2:18",
            "runs past the end of wall 3 (the south wall)",
        ),
        (
            "room 5 x 4 { window up 2 1 1 1 }",
            "2:25",
            "the room has no wall 'up'; name a wall by its side",
        ),
        (
            "room 5 x 4 { window 7 2 1 1 1 }",
            "2:25",
            "or its number (1 to 4, in the order of the corners)",
        ),
        (
            "room 5 x 4 { window north 2 1 1.5 1.5 }",
            "2:18",
            "the window's top (3 m) is above the wall (2.6 m)",
        ),
        (
            "room 5 x 4 { door south 1 0.9; door south 1.5 0.9 }",
            "2:36",
            "the door overlaps door 1 on wall 3",
        ),
        ("room (0, 0) (4, 4) (4, 0) (0, 4)", "2:5", "walls 1 and 3 cross"),
        ("room (0, 0) (4, 0)", "2:5", "a room needs at least 3 corners"),
        ("room 5 x 4 { height 0 }", "2:25", "wall height 0 is not a positive number"),
        ("extent 5 x 4\n    room 5 x 4", "2:5", "'extent' and 'room' both set the scene's floor"),
        ("room 3 x 3\n    square maybe", "3:12", "'square' is 'on' or 'off', not 'maybe'"),
    ],
)
def test_bad_rooms_are_reported_where_they_are_written(tmp_path, body, where, message):
    text = f'scene s {{\n    {body}\n    start S\n}}\nobject a {{ noun "a" }}\nS -> {{ a }}\n'
    printed = diagnostics(tmp_path, text)
    assert f"room.rules:{where}: error: " in printed and message in printed, printed


@pytest.mark.parametrize(
    ("statements", "where", "message"),
    [
        (
            "wardrobe UnderWindow some wall",
            "12:29",
            "UnderWindow stands by a window: write 'some window'",
        ),
        ("wardrobe AgainstWall each wall", "12:29", "AgainstWall stands by a wall"),
        ("wardrobe UnderWindow window #2", "12:29", "'window #2': the room has 1 window"),
        ("plant AwayFromWall some window", "12:27", "AwayFromWall stands by a wall"),
        ("plant AwayFromWall wall #5", "12:27", "'wall #5': the room has 4 walls"),
        (
            "wardrobe; wall",
            "12:18",
            "the room's walls come from its room block and cannot be created",
        ),
    ],
)
def test_bad_wall_relations_are_reported_where_they_are_written(
    tmp_path, statements, where, message
):
    printed = diagnostics(tmp_path, ROOM + f"\nS -> {{ {statements} }}\n")
    assert f"room.rules:{where}: error: " in printed and message in printed, printed


def test_a_wall_label_needs_a_room(tmp_path):
    text = 'scene s { extent 4 x 4\n start S }\nobject a { noun "a" }\nS -> { a AgainstWall some wall }\n'
    printed = diagnostics(tmp_path, text)
    assert "room.rules:4:10: error: AgainstWall needs a room" in printed
    assert printed.count("error:") == 1, printed  # not also "unknown type 'wall'"


def test_away_from_wall_needs_a_room_too(tmp_path):
    text = 'scene s { extent 4 x 4\n start S }\nobject a { noun "a" }\nS -> { a AwayFromWall some wall }\n'
    printed = diagnostics(tmp_path, text)
    assert "room.rules:4:10: error: AwayFromWall needs a room" in printed
    assert printed.count("error:") == 1, printed


def test_away_from_some_wall_targets_the_room_and_keeps_off_every_wall(tmp_path):
    """A lamp beside an armchair at a wall, kept off the walls: the layout keeps it at
    least 15 cm off (aiming at 20), the text says so of the nearest wall, and the
    Implicit form constrains the layout without a sentence."""
    from scenewright.api import build_scene, describe_scene
    from scenewright.core.frames import footprint_corners

    text = ROOM + (
        'object armchair { noun "armchair" size 0.8 x 0.9 x 0.8 }\n'
        'object floor_lamp { noun "floor lamp" size 0.35 x 1.6 x 0.35 }\n'
        "S -> { armchair as a AgainstWall some wall; floor_lamp NextToLeft a AwayFromWall some wall;"
        " plant ImplicitAwayFromWall some wall }\n"
    )
    (tmp_path / "room.rules").write_text(text)
    rules = load_rules(tmp_path / "room.rules")
    edges = {(edge.source, edge.label): edge.target for edge in expand(rules, 0).edges()}
    assert edges[("floor_lamp_1", "AwayFromWall")] == ROOM_NODE
    for seed in range(8):
        scene = build_scene(rules, seed)
        assert scene.layout.ok, (seed, scene.layout.problems)
        for obj in scene.placed_objects():
            if obj.type in ("floor_lamp", "plant"):
                corners = footprint_corners(
                    obj.position[0], obj.position[2], obj.yaw, obj.size[0], obj.size[2]
                )
                gap = min(scene.room.boundary_distance(x, z) for x, z in corners)
                assert gap > 0.15, (seed, obj.id, gap)
        words = describe_scene(scene).description.text
        assert "The floor lamp is to the left of the armchair and stands away from the" in words
        assert "plant stands away" not in words


def test_a_catalog_entry_may_not_take_a_room_part_name(tmp_path):
    printed = diagnostics(tmp_path, ROOM + 'object door { noun "door" }\nS -> { plant }\n')
    assert "room.rules:11:8: error: 'door' names the room's doors in a scene with a room" in printed


@pytest.mark.parametrize(
    ("fields", "message"),
    [
        ("clearance up 1", "clearance side 'up' is not one of front, back, left, right"),
        ("clearance front 1 clearance front 2", "a second clearance front"),
        ("clearance front 0", "a clearance must be more than 0"),
        ("access front none", "'access any' and 'access none' stand alone"),
        (
            "access frnt",
            "access 'frnt' is not one of any, none, front, back, left, right; did you mean 'front'?",
        ),
    ],
)
def test_bad_clearance_and_access_fields(tmp_path, fields, message):
    text = f'scene s {{ room 3 x 3\n start S }}\nobject a {{ noun "a" {fields} }}\nS -> {{ a }}\n'
    printed = diagnostics(tmp_path, text)
    assert "room.rules:3:" in printed and message in printed, printed


def test_clearance_is_for_objects_only(tmp_path):
    text = 'scene s { room 3 x 3\n start S }\ngroup g { noun "g" clearance front 1 }\nS -> { g }\n'
    assert "'clearance' applies to objects only, not to a group" in diagnostics(tmp_path, text)
