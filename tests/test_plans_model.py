"""The plan model on a tiny plan set one can check by hand, the canonical mask frame, the CLI."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from scenewright.cli import main
from scenewright.completion.activity import activity_prior, interactions
from scenewright.completion.features import canonical_frame, door_window_angle, occupancy_mask
from scenewright.completion.floor_plan import Furniture, Plan, plan_from_dict
from scenewright.completion.model_builder import (
    build_model,
    model_json,
    relation_graph,
    shipped_model,
)
from scenewright.completion.plan_model import MODEL_VERSION
from scenewright.core.room import Room

SOUTH, EAST, NORTH, WEST = 0.0, math.pi / 2, math.pi, -math.pi / 2


def _room(width=4.0, depth=3.0) -> Room:
    """Door in the middle of the south wall, window in the middle of the north wall."""
    room = Room.rectangle(width, depth).with_opening("door", "wall_3", width / 2, 0.9)
    return room.with_opening("window", "wall_1", width / 2, 1.2, 1.2, 0.9)


def _plan(plan_id, room_type, room, *pieces, free_areas=()) -> Plan:
    furniture = tuple(
        Furniture(f"{c}_{k}", c, (x, z), size, yaw) for k, (c, x, z, size, yaw) in enumerate(pieces)
    )
    data = Plan(plan_id, room_type, room, furniture).to_dict()
    if free_areas:
        data["free_areas"] = list(free_areas)
    return plan_from_dict(data)  # checked like any plan


@pytest.fixture(scope="module")
def tiny():
    """Two bedrooms and a study, 4 x 3 m each (12 m^2)."""
    bed = ("bed", -0.6, -0.5, (1.4, 2.0), SOUTH)  # head on the north wall, west of the window
    wardrobe = ("wardrobe", 1.7, 0.6, (1.2, 0.6), WEST)  # back to the east wall, facing west
    first = _plan(
        "a_bed", "bedroom", _room(), bed, ("nightstand", 0.4, -1.3, (0.5, 0.4), SOUTH), wardrobe
    )
    second = _plan(
        "b_bed",
        "bedroom",
        _room(),
        bed,
        wardrobe,
        ("desk", -1.7, 1.0, (1.0, 0.6), EAST),
        ("office_chair", -1.05, 1.0, (0.5, 0.5), WEST),
        free_areas=[{"center": [0.9, -1.2], "size": [1.6, 0.6], "suits": ["piano"]}],
    )
    study = _plan(
        "c_study",
        "study",
        _room(),
        ("desk", 0.0, -1.2, (1.2, 0.6), SOUTH),
        ("office_chair", 0.0, -0.55, (0.5, 0.5), NORTH),
        ("bookshelf", -1.84, 0.5, (0.9, 0.32), EAST),
    )
    return [first, second, study]


@pytest.fixture(scope="module")
def tiny_model(tiny):
    return build_model(tiny)


def test_category_statistics_of_a_type(tiny_model):
    model = tiny_model
    bedroom = model.types["bedroom"]
    assert bedroom.plans == 2 and bedroom.mean_area == 12.0
    p = {name: entry.p for name, entry in bedroom.categories.items()}
    # the piano is no plan's, but b_bed's free area fits it: exp(-((0.6-0.6)^2 + (1.6-1.5)^2) / 0.5^2) / 2
    assert p == {
        "bed": 1.0,
        "wardrobe": 1.0,
        "nightstand": 0.5,
        "desk": 0.5,
        "office_chair": 0.5,
        "piano": round(math.exp(-0.01 / 0.25) / 2, 6),
    }
    assert all(
        entry.max_count == (0 if name == "piano" else 1)
        for name, entry in bedroom.categories.items()
    )
    assert model.categories["bed"].to_dict() == {
        "purpose": "stay",
        "size": [1.4, 2.0],
        "floor_area": 2.8,
    }
    assert model.categories["desk"].size == [0.6, 1.1]  # the mean of 1.0 x 0.6 and 1.2 x 0.6


def test_cooccurrence_is_weighted_by_the_activity_prior(tiny_model):
    pairs = {tuple(p.pair): p.to_dict() for p in tiny_model.types["bedroom"].pairs}
    assert pairs[("bed", "wardrobe")] == {
        "pair": ["bed", "wardrobe"],
        "cooccurrence": 1.0,
        "activity": "purpose",
        "weight": 1.0,
    }
    assert (
        pairs[("bed", "nightstand")]["activity"] == "touch"
        and pairs[("bed", "nightstand")]["weight"] == 0.5
    )
    assert pairs[("desk", "office_chair")]["activity"] == "touch"
    assert pairs[("bed", "office_chair")]["activity"] == "purpose"  # both stay
    assert ("desk", "nightstand") not in pairs  # never in one plan
    # together in half the plans, but nobody at the one uses the other: no edge
    assert pairs[("nightstand", "wardrobe")] == {
        "pair": ["nightstand", "wardrobe"],
        "cooccurrence": 0.5,
        "activity": None,
        "weight": 0.0,
    }
    graph = relation_graph(tiny_model, "bedroom")
    assert {tuple(e["pair"]) for e in graph["edges"]} >= {
        ("bed", "nightstand"),
        ("bed", "wardrobe"),
    }
    assert all(edge["weight"] > 0 for edge in graph["edges"])


def test_touch_and_visual_areas_come_from_use_poses(tiny):
    first = tiny[0]
    assert ("bed", "nightstand", "touch") in interactions(first)
    television = _plan(
        "tv",
        "bedroom",
        _room(5.0, 4.0),
        ("bed", 0.0, -0.95, (1.6, 2.1), SOUTH),
        ("tv_stand", 1.5, 1.775, (1.2, 0.45), NORTH),
    )
    assert ("bed", "tv_stand", "visual") in interactions(television)
    assert activity_prior([television])[("bed", "tv_stand")] == "visual"
    # seated at a deep sofa's front edge, the coffee table 0.45 m before it is within reach
    sitting = _plan(
        "sit",
        "living_room",
        _room(5.0, 4.0),
        ("sofa", 0.0, -1.55, (2.2, 0.9), SOUTH),
        ("coffee_table", 0.0, -0.35, (1.1, 0.6), SOUTH),
    )
    assert ("sofa", "coffee_table", "touch") in interactions(sitting)


def test_room_feature_and_mask(tiny_model):
    entry = next(plan for plan in tiny_model.plans if plan.id == "a_bed")
    occupancy = (2.8 + 0.2 + 0.72) / 12.0
    assert entry.feature == pytest.approx(
        [1.0, occupancy, 0.75, 0.5], abs=1e-6
    )  # door opposite the window
    mask = np.array(entry.mask)
    assert mask.shape == (10, 10) and mask.sum() / 100 == pytest.approx(occupancy, abs=0.01)
    # Door and window on the centre line x = 0: the furniture's barycentre (x -0.1) decides
    # x, flipped to the right; the door is on the south wall, flipped to the top.
    assert entry.frame == {"transpose": False, "flip_x": True, "flip_z": True}
    assert (
        mask[9, 5:8].min() == 1.0 and mask[0, 5:8].max() == 0.0
    )  # the bed (x -1.3..0.1) at the bottom


def test_door_window_angle():
    assert door_window_angle(_room()) == pytest.approx(math.pi)
    side = (
        Room.rectangle(4.0, 3.0)
        .with_opening("door", "wall_2", 1.5, 0.9)
        .with_opening("window", "wall_1", 2.0, 1.0)
    )
    assert door_window_angle(side) == pytest.approx(
        math.pi / 2
    )  # door east (2, 0), window north (0, -1.5)
    assert (
        door_window_angle(Room.rectangle(4.0, 3.0).with_opening("door", "wall_2", 1.5, 0.9))
        == math.pi / 2
    )


def _mirrored_or_turned(plan: Plan, turn: int, mirror: bool) -> Plan:
    """``plan`` turned ``turn`` quarter turns and, if ``mirror``, mirrored in x."""

    def move(x, z):
        for _ in range(turn):
            x, z = -z, x
        return (-x if mirror else x), z

    data = plan.to_dict()
    for wall in data["room"]["walls"]:
        wall["from"], wall["to"] = list(move(*wall["from"])), list(move(*wall["to"]))
    for opening in data["room"]["openings"]:
        opening["center"] = list(move(*opening["center"]))
    for piece in data["furniture"]:
        piece["center"] = list(move(*piece["center"]))
        yaw = (
            piece["yaw"] - turn * math.pi / 2
        )  # a quarter turn (x, z) -> (-z, x) turns forward by -90 degrees
        piece["yaw"] = (
            math.atan2(-math.sin(yaw), math.cos(yaw))
            if mirror
            else math.atan2(math.sin(yaw), math.cos(yaw))
        )
    return plan_from_dict(data)


@settings(max_examples=25, deadline=None)
@given(
    width=st.sampled_from([3.0, 3.6, 4.4, 5.0]),
    depth=st.sampled_from([2.8, 3.2, 4.0]),
    door_offset=st.sampled_from([0.2, 0.3, 0.4]),
    turn=st.integers(0, 3),
    mirror=st.booleans(),
)
def test_the_canonical_mask_is_the_same_however_the_room_is_turned_or_mirrored(
    width, depth, door_offset, turn, mirror
):
    """Door-aware: the frame comes from the door, so the same design drawn turned or
    mirrored gives the same mask, and the door always lands in the top-left."""
    room = Room.rectangle(width, depth).with_opening(
        "door", "wall_2", door_offset * depth + 0.45, 0.9
    )
    room = room.with_opening("window", "wall_4", depth / 2, 1.0, 1.2, 0.9)
    plan = _plan(
        "p",
        "bedroom",
        room,
        ("bed", -width / 2 + 1.05, 0.0, (1.6, 2.1), EAST),
        ("plant", width / 2 - 0.25, depth / 2 - 0.25, (0.4, 0.4), SOUTH),
    )
    moved = _mirrored_or_turned(plan, turn, mirror)
    frames = [canonical_frame(p.room, p.furniture) for p in (plan, moved)]
    masks = [
        occupancy_mask(p.room, p.furniture, f) for p, f in zip((plan, moved), frames, strict=False)
    ]
    np.testing.assert_allclose(masks[0], masks[1], atol=0.04)
    door = frames[1].apply(np.array([moved.room.doors[0].center]))[0]
    assert door[0] <= 0.0 + 1e-9 and door[1] <= 0.0 + 1e-9


def test_the_model_does_not_depend_on_the_order_of_the_plans(tiny, tiny_model):
    assert model_json(build_model(tiny[::-1])) == model_json(tiny_model)


def test_the_shipped_model_is_built_once_a_process_from_the_shipped_plans(model):
    """What completions without plans of their own share (the suite's ``model`` too):
    one object, the model of the shipped plan set."""
    from scenewright.completion import shipped_plans_dir
    from scenewright.completion.floor_plan import load_plans

    assert shipped_model() is shipped_model() is model
    assert model_json(model) == model_json(build_model(load_plans(shipped_plans_dir())))


def test_shipped_model_statistics(tmp_path, capsys):
    from scenewright.completion import shipped_plans_dir

    target = tmp_path / "model.json"
    assert main(["plans", "build", str(shipped_plans_dir()), "-o", str(target), "-q"]) == 0
    first = target.read_bytes()
    assert main(["plans", "build", str(shipped_plans_dir()), "-o", str(target), "-q"]) == 0
    assert target.read_bytes() == first
    model = json.loads(first)
    for room_type, essential in (
        ("bedroom", "bed"),
        ("living_room", "sofa"),
        ("study", "desk"),
        ("dining_room", "dining_table"),
    ):
        assert model["types"][room_type]["categories"][essential]["p"] == 1.0
        assert sum(len(c["plans"]) for c in model["types"][room_type]["clusters"]) == 16
    assert (
        model["types"]["dining_room"]["categories"]["chair"]["max_count"] == 8
    )  # the eight-seat tables
    gym = model["types"]["gym"]
    machines = {"treadmill", "exercise_bike", "rowing_machine", "weight_bench", "exercise_mat"}
    assert gym["plans"] == 16 and machines | {"dumbbell_rack"} <= set(gym["categories"])
    assert not machines & {
        name for t, entry in model["types"].items() if t != "gym" for name in entry["categories"]
    }
    assert {model["categories"][name]["purpose"] for name in machines} == {
        "stay"
    }  # the paper's gym: stay objects
    assert model["categories"]["dumbbell_rack"]["purpose"] == "fetch"
    assert gym["categories"]["treadmill"]["max_count"] >= 3
    assert main(["plans", "graph", "--type", "bedroom", "--model", str(target)]) == 0
    dot = capsys.readouterr().out
    assert dot.startswith('graph "bedroom" {') and '"bed" -- "nightstand" [label="1.00"' in dot


def test_plans_commands_refuse_bad_input_in_one_line(tmp_path, capsys):
    folder = tmp_path / "plans"
    folder.mkdir()
    (folder / "x.json").write_text('{"id": "x"}')
    assert main(["plans", "build", str(folder), "-o", str(tmp_path / "m.json")]) == 2
    error = capsys.readouterr().err
    assert error == f"scenewright: error: {folder / 'x.json'}: $: 'type' is a required property\n"
    assert not (tmp_path / "m.json").exists()
    assert main(["plans", "graph", "--type", "garage"]) == 2
    assert (
        "the plans have no type 'garage' (they have bedroom, dining_room, gym, living_room, study)"
        in capsys.readouterr().err
    )
    (tmp_path / "m.json").write_text('{"format": "other"}')
    assert main(["plans", "graph", "--type", "bedroom", "--model", str(tmp_path / "m.json")]) == 2
    assert "not a plan model" in capsys.readouterr().err


def test_plans_draw_writes_one_png_sheet(tmp_path, capsys):
    target = tmp_path / "sheet.png"
    assert (
        main(["plans", "draw", "--only", "bedroom_01,study_06", "--masks", "-o", str(target), "-q"])
        == 0
    )
    assert target.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert main(["plans", "draw", "--only", "bedroom_99", "-o", str(tmp_path / "other.png")]) == 2
    assert capsys.readouterr().err == "scenewright: error: no plan 'bedroom_99' in the plan set\n"
    assert not (tmp_path / "other.png").exists()


@pytest.mark.slow
def test_the_model_file_is_the_same_whatever_the_hash_seed(tmp_path):
    """Sets of category names change order with PYTHONHASHSEED; the model must not.

    Four plans of each shipped room type hold every type's sets of categories; the
    whole plan set would only build the same statistics from more rooms."""
    import os
    import shutil
    import subprocess
    import sys

    from scenewright.completion import shipped_plans_dir

    plans = tmp_path / "plans"
    for room_type in sorted(shipped_plans_dir().iterdir()):
        for plan in sorted(room_type.glob("*.json"))[:4]:
            (plans / room_type.name).mkdir(parents=True, exist_ok=True)
            shutil.copy(plan, plans / room_type.name / plan.name)
    outputs = []
    for seed in ("1", "2"):
        target = tmp_path / f"model_{seed}.json"
        env = dict(os.environ, PYTHONHASHSEED=seed)
        command = [
            sys.executable,
            "-m",
            "scenewright.cli",
            "plans",
            "build",
            str(plans),
            "-o",
            str(target),
        ]
        subprocess.run(command, check=True, env=env, capture_output=True)
        outputs.append(target.read_bytes())
    assert outputs[0] == outputs[1]


def test_a_damaged_model_file_is_refused_in_one_line(tmp_path, capsys):
    target = tmp_path / "m.json"
    target.write_text(
        json.dumps(
            {
                "format": "scenewright-plan-model",
                "version": MODEL_VERSION,
                "categories": {},
                "activity": [],
                "types": {"bedroom": {"pairs": "?"}},
                "plans": [],
                "accessories": {},
                "stances": {},
            }
        )
    )
    assert main(["plans", "graph", "--type", "bedroom", "--model", str(target)]) == 2
    assert (
        capsys.readouterr().err
        == f"scenewright: error: {target}: $.types.bedroom: not a type entry of a plan model\n"
    )


def test_every_shipped_plan_has_its_door_top_left_in_its_frame(shipped_plans):
    for plan in shipped_plans:
        frame = canonical_frame(plan.room)
        door = frame.apply(np.array([plan.room.doors[0].center]))[0]
        assert door[0] <= 1e-9 and door[1] <= 1e-9, plan.id


def test_an_l_shaped_room_without_a_window_builds_a_model():
    room = Room.polygon([(0, 0), (5, 0), (5, 2), (2.5, 2), (2.5, 4), (0, 4)]).with_opening(
        "door", "wall_5", 1.0, 0.9
    )
    plan = _plan(
        "l",
        "study",
        room,
        ("desk", 0.0, -1.7, (1.2, 0.6), SOUTH),
        ("office_chair", 0.0, -1.05, (0.5, 0.5), NORTH),
    )
    entry = build_model([plan]).plans[0]
    assert (
        entry.frame["transpose"] is False and entry.feature[0] == 0.5
    )  # no window: the middle angle
    mask = np.array(entry.mask)
    assert mask.sum() > 0 and mask.shape == (10, 10)


@pytest.fixture(scope="module")
def shipped_plans():
    from scenewright.completion import shipped_plans_dir
    from scenewright.completion.floor_plan import load_plans

    return load_plans(shipped_plans_dir())
