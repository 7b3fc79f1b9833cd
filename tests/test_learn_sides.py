"""Sides chosen together (``learning.sides_together``): two things by one armchair whose
sides the examples chose together are learned as one choice over both, and made so
(also when one of them is placed by the other); sides the examples chose apart stay
apart; a placement that says no side is not coupled; the test of association itself."""

from __future__ import annotations

import json
import math
import re
from collections import Counter
from pathlib import Path

import numpy as np

from scenewright.api import build_scene, load_rules
from scenewright.core.frames import to_local, to_world
from scenewright.examples import load_examples
from scenewright.generator.expand import expand
from scenewright.learning.induce import induce
from scenewright.learning.induction import Group, Member, Placement
from scenewright.learning.rules_text import rules_text
from scenewright.learning.sides_together import ALPHA, association, sides_together

CHAIR = (0.85, 0.95, 0.85)
LAMP = (0.35, 1.6, 0.35)
TABLE = (0.5, 0.6, 0.5)
STOOL = (0.5, 0.4, 0.4)
#: The lamp's side of the armchair in each example: 12 on its left (+1), 6 on its right.
LAMP_SIDES = [1, 1, -1] * 6
#: The side table always on the lamp's other side.
OPPOSED = [-side for side in LAMP_SIDES]


def corners(
    folder: Path,
    table_sides: list[int],
    footstool: bool = False,
    lamp_sides: list[int] = LAMP_SIDES,
) -> list[Path]:
    """Reading corners in the hand-written format: an armchair against some wall of a
    4 x 3.6 m room (with a footstool in front of it), a floor lamp on its left or right
    (``lamp_sides``) and a side table on its left (+1) or right (-1) as ``table_sides``
    says, further out than the lamp when both are on one side."""
    folder.mkdir(parents=True, exist_ok=True)
    draw = np.random.default_rng(5)
    room = (4.0, 3.6)
    paths = []
    for index, (lamp_side, table_side) in enumerate(zip(lamp_sides, table_sides, strict=True)):
        yaw = float(draw.choice([0.0, 90.0, 180.0, -90.0]))  # its back to the N, W, S, E wall
        reach = (room[1] if yaw in (0.0, 180.0) else room[0]) / 2
        turn = math.radians(yaw)
        x, z = to_world(0, 0, turn, float(draw.uniform(-0.4, 0.4)), CHAIR[2] / 2 + 0.04 - reach)
        lamp_out = CHAIR[0] / 2 + float(draw.uniform(0.08, 0.15)) + LAMP[0] / 2
        table_out = CHAIR[0] / 2 + float(draw.uniform(0.05, 0.12)) + TABLE[0] / 2
        if table_side == lamp_side:
            table_out = lamp_out + LAMP[0] / 2 + 0.1 + TABLE[0] / 2
        placed = [
            ("chair", "armchair", CHAIR, (x, z)),
            ("lamp", "floor_lamp", LAMP, to_world(x, z, turn, lamp_side * lamp_out, -0.15)),
            (
                "table",
                "side_table",
                TABLE,
                to_world(x, z, turn, table_side * table_out, 0.0),
            ),
        ]
        if footstool:
            forward = CHAIR[2] / 2 + float(draw.uniform(0.3, 0.4))
            placed.append(("stool", "footstool", STOOL, to_world(x, z, turn, 0.0, forward)))
        objects = [
            {"id": ident, "type": kind, "size": list(size), "position": list(at), "yaw": yaw}
            for ident, kind, size, at in placed
        ]
        path = folder / f"corner_{index:02d}.json"
        path.write_text(
            json.dumps({"room": {"width": room[0], "depth": room[1]}, "objects": objects})
        )
        paths.append(path)
    return paths


def learned(tmp_path: Path, table_sides: list[int], **how):
    """The induction, its rules text and the rules loaded, from ``corners``."""
    paths = corners(tmp_path / "corners", table_sides, **how)
    induction = induce(load_examples(paths), name="corners", seed=0)
    text = rules_text(induction)
    output = tmp_path / "corners.rules"
    output.write_text(text)
    return induction, text, load_rules(output)


def same_side_share(scenes) -> float:
    """The share of ``scenes`` with the lamp and the side table on one side of the armchair."""
    same = []
    for scene in scenes:
        objects = {o.type: o for o in scene.placed_objects()}
        chair = objects["armchair"]
        left = [
            to_local(*chair.position[::2], chair.yaw, *objects[t].position[::2])[0] > 0
            for t in ("floor_lamp", "side_table")
        ]
        same.append(left[0] == left[1])
    return float(np.mean(same))


def drawn_sides(rules, seeds: int = 300) -> Counter:
    """How often each combination of the lamp's and the table's side labels is drawn
    (each the label by which it is placed) in ``seeds`` expansions."""
    drawn: Counter = Counter()
    for seed in range(seeds):
        labels = {
            (e.source.rsplit("_", 1)[0], e.label)
            for e in expand(rules, seed).edges()
            if e.label in ("NextToLeft", "NextToRight")
        }
        drawn[tuple(sorted(labels))] += 1
    return drawn


def test_sides_the_examples_chose_together_are_one_choice_and_made_together(tmp_path):
    induction, text, rules = learned(tmp_path, OPPOSED, footstool=False)
    (group,) = induction.groups
    assert group.anchor == "armchair"
    (joint,) = group.joints
    assert joint.types == ("floor_lamp", "side_table")
    assert [m.parent for m in joint.members] == ["armchair", "armchair"]
    assert joint.parents == joint.complete == 18
    ways = {
        tuple(m.placements[k].labels[0] for m, k in zip(joint.members, way, strict=True)): n
        for way, n in joint.ways
    }
    assert ways == {("NextToLeft", "NextToRight"): 12, ("NextToRight", "NextToLeft"): 6}
    (test,) = group.side_tests
    assert test.coupled and test.p_value <= ALPHA
    assert "FloorLampAndSideTableAtArmchair(the_armchair) -> 12: {" in text, text
    # No production draws either on its own.
    assert not re.search(r"^(FloorLamp|SideTable)At", text, re.M), text
    # Made together: never on one side, each way in about the examples' share (12 of 18).
    assert same_side_share([build_scene(rules, seed) for seed in range(12)]) == 0.0
    drawn = drawn_sides(rules)
    lamp_left = (("floor_lamp", "NextToLeft"), ("side_table", "NextToRight"))
    lamp_right = (("floor_lamp", "NextToRight"), ("side_table", "NextToLeft"))
    assert set(drawn) == {lamp_left, lamp_right}
    assert 0.58 <= drawn[lamp_left] / 300 <= 0.75
    # The same examples and seed give the same text.
    paths = sorted((tmp_path / "corners").glob("*.json"))
    assert rules_text(induce(load_examples(paths), name="corners", seed=0)) == text


def test_a_member_and_what_it_places_take_their_sides_together():
    # A side table by the armchair and a floor lamp placed by the table, on the table's
    # far side from the armchair: which side of the table the lamp stands on follows
    # which side of the armchair the table does (12 corners one way, 6 the other).
    sides = [Placement(("NextToLeft",), 1), Placement(("NextToRight",), 1)]
    table_sides = [1] * 12 + [0] * 6
    table = Member(
        "side_table",
        "armchair",
        18,
        Counter({1: 18}),
        sides,
        [],
        0,
        None,
        chosen={(k, "chair"): side for k, side in enumerate(table_sides)},
        objects={(k, "chair"): (k, "table") for k in range(18)},
    )
    lamp = Member(
        "floor_lamp",
        "side_table",
        18,
        Counter({1: 18}),
        sides,
        [],
        0,
        None,
        chosen={(k, "table"): 1 - side for k, side in enumerate(table_sides)},
        objects={(k, "table"): (k, "lamp") for k in range(18)},
    )
    table.children = [lamp]
    group = Group("Armchair", "armchair", Counter({1: 18}), None, [table], [], [])
    sides_together(group, seed=0)
    (joint,) = group.joints
    assert [(m.type, m.parent) for m in joint.members] == [
        ("side_table", "armchair"),
        ("floor_lamp", "side_table"),
    ]
    assert dict(joint.ways) == {(1, 0): 12.0, (0, 1): 6.0}


def test_eighteen_corners_relate_the_lamp_and_the_table_to_the_armchair_and_oppose_them(
    tmp_path,
):
    # With a footstool before the armchair too: the lamp and the side table each stand
    # by the armchair (the relation test finds both), on its opposite sides as drawn
    # together, the lamp on its left in about the examples' 12 of 18.
    induction, text, rules = learned(tmp_path, OPPOSED, footstool=True)
    (group,) = induction.groups
    (joint,) = group.joints
    assert sorted((m.type, m.parent) for m in joint.members) == [
        ("floor_lamp", "armchair"),
        ("side_table", "armchair"),
    ]
    assert "FloorLampAndSideTableAtArmchair(the_armchair) -> 12: {" in text, text
    drawn = drawn_sides(rules)
    right = (("floor_lamp", "NextToRight"), ("side_table", "NextToLeft"))
    left = (("floor_lamp", "NextToLeft"), ("side_table", "NextToRight"))
    assert set(drawn) == {right, left} and 0.58 <= drawn[left] / 300 <= 0.75


def test_sides_the_examples_chose_apart_stay_apart(tmp_path):
    # Thirty corners (with fewer the relation test ties the lamp to the table, not to
    # the armchair). Where the lamp is on the left (20) the table is on the left in 10
    # and the right in 10; where it is on the right (10), on the left in 5 and the right
    # in 5: the joint table is the product of its margins.
    lamp_sides, table_sides = [1, 1, -1] * 10, [1, -1, 1, -1, 1, -1] * 5
    pairs = list(zip(lamp_sides, table_sides, strict=True))
    assert [pairs.count(p) for p in ((1, 1), (1, -1), (-1, 1), (-1, -1))] == [10, 10, 5, 5]
    induction, text, rules = learned(tmp_path, table_sides, lamp_sides=lamp_sides)
    (group,) = induction.groups
    assert {(m.type, m.parent) for m in group.members} == {
        ("floor_lamp", "armchair"),
        ("side_table", "armchair"),
    }
    # Tested, and left apart.
    (test,) = group.side_tests
    assert test.parents == 30 and not test.coupled and test.p_value > 0.5
    assert group.joints == []
    assert not re.search(r"^\w+And\w+\(", text, re.M), text
    assert "FloorLampAtArmchair(the_armchair) -> 20:" in text, text
    # Drawn apart: every combination of the two sides is drawn, and laid out.
    assert len(drawn_sides(rules)) == 4
    assert 0.2 <= same_side_share([build_scene(rules, seed) for seed in range(12)]) <= 0.8


def test_the_association_test_couples_a_table_beyond_chance_only():
    rng = np.random.default_rng(0)
    # Nine parents, the first thing on the left of six, the other always opposite:
    # Fisher's exact p is 1 / C(9, 3) = 1/84.
    first = np.array([0, 0, 0, 0, 0, 0, 1, 1, 1])
    statistic, p_value = association(first, 1 - first, rng)
    assert statistic > 10 and 0.005 <= p_value <= 0.025
    # Three parents always opposite: a third of the relabellings are as extreme.
    _, p_three = association(np.array([0, 0, 1]), np.array([1, 1, 0]), rng)
    assert p_three > ALPHA and abs(p_three - 1 / 3) < 0.05
    # A table that is the product of its margins.
    statistic, p_value = association(
        np.array([0, 0, 0, 0, 1, 1]), np.array([0, 0, 1, 1, 0, 1]), rng
    )
    assert statistic < 1e-9 and p_value == 1.0
    # One side only: nothing to tell.
    assert association(np.zeros(5, dtype=int), np.array([0, 1, 0, 1, 1]), rng) == (0.0, 1.0)


def member(type_name: str, labels: list[tuple[str, ...]], sides: list[int | None]) -> Member:
    """A member by the armchair of each of ``len(sides)`` scenes: its placement index
    there (-1: in none of them; None: not there)."""
    chosen = {(k, "chair"): side for k, side in enumerate(sides) if side is not None}
    return Member(
        type_name,
        "armchair",
        len(chosen),
        Counter({1: len(chosen), 0: len(sides) - len(chosen)}),
        [Placement(label, 1) for label in labels],
        [],
        0,
        None,
        chosen=chosen,
        objects={host: (host[0], type_name) for host in chosen},
    )


def test_a_joint_keeps_each_member_s_shares_and_leaves_out_what_says_no_side():
    sides = [("NextToLeft",), ("NextToRight",)]
    # The table opposite the lamp in 12 corners; two more have no table, one a lamp in no
    # placement (too far for any label).
    lamp = member("floor_lamp", sides, [0] * 8 + [1] * 4 + [0, 1, -1])
    table = member("side_table", sides, [1] * 8 + [0] * 4 + [None, None, 1])
    # A plant whose placements say only which way it faces: no side to couple.
    plant = member("plant", [("FacingTowards",), ("FacingAwayFrom",)], [0] * 8 + [1] * 7)
    group = Group("Armchair", "armchair", Counter({1: 15}), None, [lamp, table, plant], [], [])
    sides_together(group, seed=0)
    (test,) = group.side_tests
    assert test.first[0] == "floor_lamp" and test.second[0] == "side_table"
    assert test.parents == 12 and test.coupled
    (joint,) = group.joints
    assert joint.types == ("floor_lamp", "side_table") and joint.tops == (lamp, table)
    assert (joint.parents, joint.complete, joint.missing) == (15, 12, 2)
    # The corners without a table count in the way their lamp fits; the lamp in no
    # placement is a way of its own (drawn on its own), so the lamp's shares are kept.
    assert dict(joint.ways) == {(0, 1): 9.0, (1, 0): 5.0, (-1, 1): 1.0}


def test_a_placement_with_no_side_is_left_out_of_the_test_and_kept_as_a_way():
    # A plant opposite the lamp in eight corners, and in two more too far for a side
    # label, with only a facing one: those two tell nothing of the sides, so the test
    # counts the eight, and the joint keeps the two as ways of their own, placed so.
    lamp = member("floor_lamp", [("NextToLeft",), ("NextToRight",)], [0] * 5 + [1] * 3 + [0, 1])
    plant = member(
        "plant",
        [("NextToRight",), ("NextToLeft",), ("FacingSameDirection",)],
        [0] * 5 + [1] * 3 + [2, 2],
    )
    group = Group("Armchair", "armchair", Counter({1: 10}), None, [lamp, plant], [], [])
    sides_together(group, seed=0)
    (test,) = group.side_tests
    assert test.parents == 8 and test.coupled
    (joint,) = group.joints
    assert dict(joint.ways) == {(0, 0): 5.0, (1, 1): 3.0, (0, 2): 1.0, (1, 2): 1.0}


def test_a_member_in_no_placement_is_drawn_on_its_own_beside_the_others(tmp_path):
    # One corner's lamp stands across the room, by no label of the armchair: that corner
    # is a way of its own, in which the lamp takes one of its placements as drawn alone.
    paths = corners(tmp_path / "corners", OPPOSED)
    document = json.loads(paths[0].read_text())
    chair, lamp = document["objects"][:2]
    lamp["position"] = [-1.7 if chair["position"][0] > 0 else 1.7, 0.0]
    paths[0].write_text(json.dumps(document))
    induction = induce(load_examples(paths), name="corners", seed=0)
    (joint,) = induction.groups[0].joints
    assert (joint.parents, joint.complete, joint.missing) == (18, 17, 0)
    assert sorted(count for _, count in joint.ways) == [1.0, 6.0, 11.0]
    text = rules_text(induction)
    alone = text[text.index("| 1: {    # 1 of 18; the floor lamp in no placement") :]
    assert "FloorLampAtArmchair(the_armchair)" in alone.split("}")[0], text
    (tmp_path / "corners.rules").write_text(text)
    drawn = drawn_sides(load_rules(tmp_path / "corners.rules"))
    # The examples' two ways, and now and then (the lamp drawn alone) both on the right.
    both_right = (("floor_lamp", "NextToRight"), ("side_table", "NextToRight"))
    assert len(drawn) == 3 and 0 < drawn[both_right] < 15


def test_too_few_examples_to_test_keep_their_own_ways(tmp_path):
    # Six corners, the lamp on the left of three and the table always opposite: the
    # most extreme table of six split three to three and its mirror image are 2 of the
    # 20 relabellings, p = 0.1, so the test cannot couple; the examples' own ways are
    # kept rather than drawn apart.
    lamp_sides = [1, 1, 1, -1, -1, -1]
    induction, text, rules = learned(
        tmp_path, [-side for side in lamp_sides], lamp_sides=lamp_sides
    )
    (group,) = induction.groups
    (test,) = group.side_tests
    assert test.parents == 6 and test.p_value > ALPHA and test.coupled
    assert len(group.joints) == 1
    assert set(drawn_sides(rules, seeds=100)) == {
        (("floor_lamp", "NextToLeft"), ("side_table", "NextToRight")),
        (("floor_lamp", "NextToRight"), ("side_table", "NextToLeft")),
    }


def test_three_examples_split_two_to_one_give_two_weighted_alternatives(tmp_path):
    # Three corners, the lamp on the armchair's left in two and on its right in one, the
    # side table always on its other side: too few scenes for any test to reach its
    # level, yet the lamp and the table stand beside the armchair at one place, either
    # side alike, in each, so both are placed by the armchair (the lamp and the table,
    # the pair farthest apart, relate through it), each side a placement of its own, and
    # the two drawn together with the examples' shares, 2/3 and 1/3.
    lamp_sides = [1, -1, 1]
    induction, text, rules = learned(
        tmp_path, [-side for side in lamp_sides], lamp_sides=lamp_sides
    )
    (group,) = induction.groups
    assert group.anchor == "armchair"
    assert {m.type: m.parent for m in group.members} == {
        "floor_lamp": "armchair",
        "side_table": "armchair",
    }
    lamp = next(m for m in group.members if m.type == "floor_lamp")
    assert [(p.labels[0], p.weight) for p in lamp.placements] == [
        ("NextToLeft", 2),
        ("NextToRight", 1),
    ]
    (joint,) = group.joints
    assert sorted(weight for _, weight in joint.ways) == [1.0, 2.0]
    assert re.search(r"-> 2: \{", text) and re.search(r"\| 1: \{", text)
    drawn = drawn_sides(rules, seeds=300)
    left = (("floor_lamp", "NextToLeft"), ("side_table", "NextToRight"))
    right = (("floor_lamp", "NextToRight"), ("side_table", "NextToLeft"))
    assert set(drawn) == {left, right}
    assert abs(drawn[left] / 300 - 2 / 3) < 0.08
    scenes = [build_scene(rules, seed) for seed in range(12)]
    assert same_side_share(scenes) == 0.0


def sideboards(folder: Path, ends: list[int]) -> list[Path]:
    """Dining rooms of 4 x 3.6 m: a sideboard against some wall, a table lamp on its top
    at its left end (+1: the sideboard's own left) or its right end (-1)."""
    folder.mkdir(parents=True, exist_ok=True)
    draw = np.random.default_rng(7)
    board, lamp = (1.6, 0.85, 0.45), (0.3, 0.5, 0.3)
    paths = []
    for index, end in enumerate(ends):
        yaw = float(draw.choice([0.0, 90.0, 180.0, -90.0]))
        reach = (3.6 if yaw in (0.0, 180.0) else 4.0) / 2
        turn = math.radians(yaw)
        along = float(draw.uniform(-0.5, 0.5))
        bx, bz = to_world(0, 0, turn, along, board[2] / 2 + 0.03 - reach)
        lx, lz = to_world(bx, bz, turn, end * float(draw.uniform(0.5, 0.6)), 0.0)
        objects = [
            {
                "id": "board",
                "type": "sideboard",
                "size": list(board),
                "position": [bx, bz],
                "yaw": yaw,
            },
            {
                "id": "lamp",
                "type": "table_lamp",
                "size": list(lamp),
                "position": [lx, lz],
                "yaw": yaw,
                "parent": "board",
            },
        ]
        path = folder / f"dining_{index:02d}.json"
        path.write_text(json.dumps({"room": {"width": 4.0, "depth": 3.6}, "objects": objects}))
        paths.append(path)
    return paths


def test_a_lamp_at_either_end_of_its_sideboard_is_two_placements_with_their_shares(tmp_path):
    """Lamps on a sideboard's top, at its left end in 8 rooms and its right end in 4:
    which end is a label of each placement (``ImplicitNextToLeft``/``Right``, the
    sideboard's own sides), drawn 8 to 4, and the lamps made stand on the top at their
    end in about that share; one placement left the end to the layout."""
    paths = sideboards(tmp_path / "rooms", [1, 1, -1] * 4)
    text = rules_text(induce(load_examples(paths), name="dining", seed=0))
    assert re.search(
        r"-> 8: \{ table_lamp OnTopOf\w* the_sideboard[^}]* ImplicitNextToLeft the_sideboard \}",
        text,
    ), text
    assert re.search(
        r"\| 4: \{ table_lamp OnTopOf\w* the_sideboard[^}]* ImplicitNextToRight the_sideboard \}",
        text,
    ), text
    output = tmp_path / "dining.rules"
    output.write_text(text)
    rules = load_rules(output)
    left = 0
    scenes = [build_scene(rules, seed) for seed in range(40)]
    for scene in scenes:
        assert scene.layout.ok, scene.layout.problems
        board = next(o for o in scene.placed_objects() if o.type == "sideboard")
        lamp = next(o for o in scene.placed_objects() if o.type == "table_lamp")
        x, _ = to_local(
            board.position[0], board.position[2], board.yaw, lamp.position[0], lamp.position[2]
        )
        assert abs(x) <= 0.8 and lamp.position[1] > 0.8  # on the top, not beside it
        left += x > 0
    assert abs(left / len(scenes) - 8 / 12) <= 0.15
