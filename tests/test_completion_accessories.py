"""What stands on or at a piece, learned from the plans (completion.accessories)."""

from __future__ import annotations

import json
import math

import pytest
from test_plans_model import NORTH, SOUTH, _plan, _room

from scenewright.completion.accessories import assign, slot_pose, slot_relations
from scenewright.completion.floor_plan import Furniture, plan_from_dict
from scenewright.completion.model_builder import build_model, model_json
from scenewright.completion.plan_model import MODEL_VERSION, PlanModel
from scenewright.core.poses import Pose


def _tiny():
    """Two bedrooms, each with a night table 5 cm left of the bed (its own left, backs
    in line against the north wall), and a study whose chair stands 10 cm before its
    desk, facing it; one bedroom's lamp stands in the middle of its night table."""
    bed = ("bed", -0.6, -0.5, (1.4, 2.0), SOUTH)
    table = ("nightstand", 0.4, -1.3, (0.5, 0.4), SOUTH)
    first = _plan("a_bed", "bedroom", _room(), bed, table)
    lamp = Furniture("lamp_9", "lamp", (0.4, -1.3), (0.25, 0.25), SOUTH, on="nightstand_1")
    data = first.to_dict()
    data["furniture"].append(lamp.to_dict())
    first = plan_from_dict(data)
    second = _plan(
        "b_bed", "bedroom", _room(), bed, table, ("wardrobe", 1.4, 1.15, (1.2, 0.6), NORTH)
    )
    study = _plan(
        "c_study",
        "study",
        _room(),
        ("desk", 0.0, -1.2, (1.2, 0.6), SOUTH),
        ("office_chair", 0.0, -0.55, (0.5, 0.5), NORTH),
    )
    return [first, second, study]


@pytest.fixture(scope="module")
def tiny_model():
    return build_model(_tiny())


def test_a_pair_the_plans_show_keeps_its_side_offset_and_yaw(tiny_model):
    accessories = tiny_model.accessories
    assert set(accessories) == {"nightstand", "office_chair", "lamp"}  # not the bed, desk, wardrobe
    night = accessories["nightstand"]
    assert not night.on and night.pieces == 2 and night.anchored == 1.0
    (bed,) = night.anchors
    assert (bed.anchor, bed.pieces, bed.most) == ("bed", 2, 1)
    (slot,) = bed.slots
    # the bed's left is +x (it faces south): centre 1.0 m left of the bed's, 0.8 m behind
    assert slot.side == "left" and slot.offset == pytest.approx([1.0, -0.8])
    assert slot.yaw == 0.0 and slot.gap == pytest.approx(0.05) and slot.flush == 1.0
    chair = accessories["office_chair"].anchors[0]
    assert chair.anchor == "desk" and chair.slots[0].side == "front"
    assert chair.slots[0].offset == pytest.approx([0.0, 0.65])
    assert abs(chair.slots[0].yaw) == pytest.approx(math.pi) and chair.slots[
        0
    ].gap == pytest.approx(0.1)
    lamp = accessories["lamp"]
    assert lamp.on and lamp.anchors[0].anchor == "nightstand"
    assert lamp.anchors[0].slots[0].side == "middle"


def test_learned_poses_place_and_relate_the_pieces_as_the_plans_had_them(tiny_model, catalog):
    counts = {"bed": 1, "nightstand": 1, "lamp": 1, "desk": 1, "office_chair": 1}
    placed = assign(tiny_model, counts, catalog)
    night, lamp, chair = placed["nightstand", 0], placed["lamp", 0], placed["office_chair", 0]
    assert (night.anchor, night.slot.side, lamp.anchor, chair.anchor) == (
        "bed",
        "left",
        "nightstand",
        "desk",
    )
    assert slot_relations(night, "nightstand", tiny_model, True) == [
        ("BesideLeft", None),
        ("ImplicitAlignedWith", None),
        ("ImplicitAgainstWall", "room"),
    ]
    assert slot_relations(chair, "office_chair", tiny_model, True) == [("SeatedAt", None)]
    assert slot_relations(lamp, "lamp", tiny_model, False) == [
        ("OnTopOfMiddle", None),
        ("ImplicitFacingSameDirection", None),
    ]
    # The start reproduces the plans' offset beside a bed of their size, however it stands.
    bed = Pose(2.0, 0.0, -1.0, math.pi / 2)
    pose = slot_pose(night, bed, (1.4, 2.0), (0.5, 0.4))
    lx = (pose.x - bed.x) * math.cos(bed.yaw) - (pose.z - bed.z) * math.sin(bed.yaw)
    lz = (pose.x - bed.x) * math.sin(bed.yaw) + (pose.z - bed.z) * math.cos(bed.yaw)
    assert (lx, lz) == pytest.approx((1.0, -0.8)) and pose.yaw == pytest.approx(bed.yaw)


def test_pairs_the_plans_do_not_show_fall_back(tiny_model, model, catalog):
    # No desk: the office chair has no place at anything (the room's other rules place it).
    assert assign(tiny_model, {"bed": 1, "office_chair": 1}, catalog) == {}
    # Two night tables, one place the plans show by one bed: the second has none.
    placed = assign(tiny_model, {"bed": 1, "nightstand": 2}, catalog)
    assert list(placed) == [("nightstand", 0)]
    # A lamp with no night table stands on the smallest other surface the plans show
    # something on that it fits on, as it stands on a night table: in the middle.
    placed = assign(model, {"bed": 1, "lamp": 1, "dresser": 1, "desk": 1}, catalog)
    surfaces = sorted(("dresser", "desk"), key=lambda n: catalog[n].size[0] * catalog[n].size[2])
    assert placed["lamp", 0].anchor == surfaces[0] and placed["lamp", 0].slot.side == "middle"
    # Nothing to stand on: none; nor on a desk for a television, larger than anything
    # the plans stand on a desk (it fits on its top).
    assert ("lamp", 0) not in assign(model, {"bed": 1, "lamp": 1}, catalog)
    assert catalog["tv"].size[0] <= catalog["desk"].size[0]
    assert ("tv", 0) not in assign(model, {"bed": 1, "tv": 1, "desk": 1}, catalog)


def test_the_shipped_plans_teach_the_usual_accessories(model):
    anchors = {name: entry.anchors[0].anchor for name, entry in model.accessories.items()}
    assert anchors == {
        "chair": "dining_table",
        "desk_lamp": "desk",
        "lamp": "nightstand",
        "laptop": "desk",
        "nightstand": "bed",
        "office_chair": "desk",
        "refrigerator": "kitchen_counter",
        "tv": "tv_stand",
    }
    beside_bed = {slot.side for slot in model.accessories["nightstand"].anchors[0].slots}
    table = model.accessories["chair"].anchors[0]
    assert beside_bed == {"left", "right"} and table.most == 8
    assert {slot.side for slot in table.slots} == {"front", "behind", "left", "right"}


def test_the_model_file_holds_the_accessories_and_is_the_same_in_any_plan_order(tiny_model):
    text = model_json(tiny_model)
    assert model_json(build_model(_tiny()[::-1])) == text
    data = json.loads(text)
    assert data["version"] == MODEL_VERSION
    assert data["accessories"]["nightstand"]["anchors"][0]["slots"][0]["offset"] == [1.0, -0.8]
    assert model_json(PlanModel.from_dict(data)) == text  # it reads back as it was written
