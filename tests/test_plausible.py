"""Plausible, not only satisfied: seats at their tables, paired furniture close, rugs as
a layer under furniture, overlaps in centimetres, and SceneEval's four metrics on
configurations with known answers (``scenewright evaluate``)."""

import json
import math

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from scenewright.cli import main
from scenewright.core.poses import Pose
from scenewright.core.relations import RELATIONS
from scenewright.core.room import Room
from scenewright.core.scene import Scene, SceneObject
from scenewright.core.scene_graph import SceneGraph, SceneParams
from scenewright.generator import expand, load_rules
from scenewright.generator.catalog import CatalogEntry
from scenewright.generator.layout import layout_scene, measure_layout
from scenewright.generator.scene_metrics import evaluate_scene, summarise

DESK = dict(size=(1.2, 0.75, 0.6), clearance=(("front", 0.7),), access=("front",))
CHAIR = dict(size=(0.5, 0.9, 0.5))
BED = dict(size=(1.6, 0.9, 2.1), access=("any",))
RUG = dict(size=(2.0, 0.01, 1.4), access=())


def room() -> Room:
    """5 x 4 centred on the origin; a 0.9 m door in the south wall at x = 1.5, a 1.4 m
    window in the north wall at x = 0 (sill 1.2 m... top 2.1 m)."""
    return (
        Room.rectangle(5, 4)
        .with_opening("door", "south", 1.0, 0.9)
        .with_opening("window", "north", 2.5, 1.4, 0.9, 0.9)
    )


def graph_of(the_room: Room | None, *objects, relations=()) -> SceneGraph:
    params = (
        SceneParams(extent=the_room.extent, room=the_room)
        if the_room
        else SceneParams(extent=(20.0, 20.0))
    )
    graph = SceneGraph(params)
    for name, fields in objects:
        graph.add_node(CatalogEntry(name, "object", name, **fields))
    for source, target, label in relations:
        graph.add_relation(source, target, label)
    return graph


def measured(graph: SceneGraph, poses: dict):
    return measure_layout(
        graph, {k: Pose(x, 0.0, z, math.radians(yaw)) for k, (x, z, yaw) in poses.items()}, {}
    )


# -- seats and paired furniture ----------------------------------------------------------


def seat_verdict(gap: float, yaw: float = 180.0, slide: float = 0.0):
    """A desk against the north wall facing south (+Z); the chair ``gap`` metres off its
    front, turned ``yaw`` degrees (180: facing the desk)."""
    graph = graph_of(
        room(),
        ("desk", DESK),
        ("chair", CHAIR),
        relations=[("chair_1", "desk_1", "SeatedAt")],
    )
    result = measured(
        graph, {"desk_1": (-1.5, -1.7, 0.0), "chair_1": (-1.5 + slide, -1.4 + gap + 0.25, yaw)}
    )
    return next(r for r in result.relations if r.label == "SeatedAt"), result


def test_a_seat_holds_within_reach_of_the_edge_and_square_to_it():
    held, result = seat_verdict(0.2)
    assert held.satisfied and result.ok, result.problems
    far, result = seat_verdict(0.6)
    assert not far.satisfied
    assert "chair_1 is not at desk_1 (distance 0.60 m)" in result.problems
    turned, result = seat_verdict(0.2, yaw=160.0)
    assert not turned.satisfied
    assert "chair_1 is not at desk_1 (turned 20° off facing it)" in result.problems
    assert seat_verdict(0.2, yaw=172.0)[0].satisfied  # 8 degrees off: square enough


def test_a_seated_desk_needs_no_way_to_its_front_of_its_own():
    """The chair stands where the desk's way in would be: the desk is used from the
    chair, which is reachable, so nothing is out of reach."""
    _, result = seat_verdict(0.05)
    assert not any("cannot be reached" in p for p in result.problems), result.problems


def test_every_label_has_its_documented_reach():
    assert RELATIONS["NextToLeft"].reach is None  # the layout's 2 m
    for name in ("Beside", "BesideLeft", "BesideRight"):
        assert RELATIONS[name].reach == 0.15
    for name in ("SeatedAt", "SeatedAtBack", "SeatedAround"):
        assert RELATIONS[name].reach == 0.35 and RELATIONS[name].seat


def test_the_close_labels_have_words_of_their_own():
    """ "just to the left of" says the nightstand is close; "to the left of" (within
    2 m) stays NextToLeft's, so text read back gives the label it was made from."""
    assert RELATIONS["SeatedAround"].wordings_for("left") == ("is at",)
    assert RELATIONS["SeatedAt"].wordings[0] == "is pulled up to"
    assert RELATIONS["Beside"].wordings_for("left") == RELATIONS["BesideLeft"].wordings
    assert RELATIONS["BesideLeft"].wordings[0] == "is just to the left of"
    assert RELATIONS["BesideRight"].wordings[0] == "is just to the right of"
    assert RELATIONS["Beside"].wordings_for(None) == RELATIONS["NextTo"].wordings
    assert not set(RELATIONS["BesideLeft"].wordings) & set(RELATIONS["NextToLeft"].wordings)


@pytest.mark.parametrize("seed", [1, 2])
def test_the_study_chair_is_drawn_up_to_the_desk(seed):
    graph = expand(load_rules("study"), seed)
    result = layout_scene(graph, seed)
    assert result.ok, result.problems
    seats = [r for r in result.relations if r.label == "SeatedAt"]
    assert seats and all(r.satisfied for r in seats)


def test_chairs_seated_around_a_table_spread_over_its_sides():
    graph = graph_of(
        room(),
        ("table", dict(size=(1.6, 0.75, 0.9))),
        *[("chair", CHAIR)] * 4,
        relations=[(f"chair_{k}", "table_1", "SeatedAround") for k in range(1, 5)],
    )
    result = layout_scene(graph, 3)
    assert result.ok, result.problems
    sides = {r.chosen for r in result.relations if r.label == "SeatedAround"}
    assert len(sides) >= 2


# -- rugs and overlaps in centimetres ---------------------------------------------------


def test_a_bed_on_a_rug_is_ok_and_two_rugs_overlapping_are_not():
    graph = graph_of(room(), ("bed", BED), ("rug", RUG), ("rug", RUG))
    on_rug = measured(
        graph, {"bed_1": (-1.0, -0.9, 0.0), "rug_1": (-1.0, 0.2, 0.0), "rug_2": (1.4, -1.0, 90.0)}
    )
    assert on_rug.ok, on_rug.problems
    rugs = measured(
        graph, {"bed_1": (-1.0, -0.9, 0.0), "rug_1": (-1.0, 0.2, 0.0), "rug_2": (0.9, 0.2, 0.0)}
    )
    assert "rug_1 overlaps rug_2 by 10 cm" in rugs.problems


def test_a_lamp_post_five_centimetres_into_a_basin_is_not_ok():
    """Outdoors, with a large basin: a share of the larger object would let it pass."""
    graph = graph_of(
        None, ("basin", dict(size=(12.0, 0.5, 8.0))), ("lamp_post", dict(size=(0.3, 4.0, 0.3)))
    )
    into = measured(graph, {"basin_1": (0.0, 0.0, 0.0), "lamp_post_1": (6.1, 0.0, 0.0)})
    assert not into.ok
    assert into.problems == ["basin_1 overlaps lamp_post_1 by 5 cm"]
    touching = measured(graph, {"basin_1": (0.0, 0.0, 0.0), "lamp_post_1": (6.145, 0.0, 0.0)})
    assert touching.ok, touching.problems  # 5 mm: within the 1 cm tolerance


# -- SceneEval's metrics, with known answers -------------------------------------------


def obj(ident: str, x: float, z: float, size, yaw: float = 0.0, y: float = 0.0) -> SceneObject:
    kind = ident.rsplit("_", 1)[0]
    return SceneObject(ident, kind, "object", kind, None, None, None, [x, y, z], yaw, list(size))


def scene_of(objects, the_room: Room | None = None) -> Scene:
    the_room = room() if the_room is None else the_room
    return Scene("test", 0, list(the_room.extent), objects, [], [], room=the_room)


def test_two_boxes_overlapping_by_three_centimetres_collide():
    metrics = evaluate_scene(
        scene_of([obj("box_1", 0.0, 0.0, (1, 1, 1)), obj("box_2", 0.97, 0.0, (1, 1, 1))])
    )
    assert metrics.colliding == ["box_1", "box_2"] and metrics.collision_rate == 1.0
    assert metrics.collisions[0][2] == pytest.approx(0.03)
    apart = evaluate_scene(
        scene_of([obj("box_1", 0.0, 0.0, (1, 1, 1)), obj("box_2", 1.005, 0.0, (1, 1, 1))])
    )
    assert apart.collision_rate == 0.0


def test_a_lamp_on_a_nightstand_and_a_bed_on_a_rug_do_not_collide():
    metrics = evaluate_scene(
        scene_of(
            [
                obj("nightstand_1", 0.1, 0.0, (0.5, 0.55, 0.4)),
                obj("lamp_1", 0.1, 0.0, (0.3, 0.5, 0.3), y=0.55),
                obj("bed_1", -1.0, 0.5, (1.6, 0.9, 2.1)),
                obj("rug_1", -1.0, 0.5, (2.0, 0.01, 1.4)),
            ]
        )
    )
    assert metrics.collisions == []


def test_a_box_five_centimetres_through_a_wall_is_out_of_bounds():
    # the east wall is at x = 2.5: a 1 m box centred at x = 2.05 reaches 2.55
    metrics = evaluate_scene(scene_of([obj("box_1", 2.05, 0.0, (1, 1, 1))]))
    assert [i for i, _ in metrics.out_of_bounds] == ["box_1"]
    assert metrics.out_of_bounds[0][1] == pytest.approx(0.05)
    assert evaluate_scene(scene_of([obj("box_1", 1.995, 0.0, (1, 1, 1))])).out_of_bounds == []


def test_furniture_walling_off_the_door_blocks_it():
    """Wardrobes across the room at z = 0.8 leave the door (south wall, x = 1.5) a
    pocket of its own: navigability falls below 1 and the door counts as blocked."""
    wall_of_wardrobes = [
        obj(f"wardrobe_{k}", -2.0 + k * 1.0, 0.8, (1.0, 2.0, 0.6)) for k in range(5)
    ]
    metrics = evaluate_scene(scene_of(wall_of_wardrobes))
    assert metrics.blocked_doors == ["door_1"]
    assert metrics.navigability is not None and metrics.navigability < 0.9
    open_room = evaluate_scene(scene_of(wall_of_wardrobes[:3]))
    assert open_room.blocked_doors == [] and open_room.navigability == 1.0


def test_a_bookshelf_before_a_window_blocks_it_and_a_desk_does_not():
    # the north wall is at z = -2; the window is 1.4 m wide round x = 0, sill 0.9 m
    shelf = evaluate_scene(scene_of([obj("bookshelf_1", 0.0, -1.8, (1.0, 1.8, 0.35))]))
    assert shelf.blocked_windows == [("window_1", "bookshelf_1")]
    desk = evaluate_scene(scene_of([obj("desk_1", 0.0, -1.7, (1.2, 0.75, 0.6))]))
    assert desk.blocked_windows == []
    summary = summarise([shelf, desk])
    assert (summary.windows, summary.blocked_windows) == (2, 1)


def test_outdoors_only_collision_and_bounds_apply():
    metrics = evaluate_scene(
        Scene("test", 0, [10.0, 10.0], [obj("house_1", 4.8, 0.0, (1, 1, 1))], [], [])
    )
    assert metrics.navigability is None and metrics.doors == 0
    assert metrics.out_of_bounds[0][1] == pytest.approx(0.3)


def test_evaluate_prints_a_table_and_json(tmp_path, capsys):
    path = tmp_path / "scene.json"
    scene = scene_of([obj("box_1", 0.0, 0.0, (1, 1, 1)), obj("box_2", 0.97, 0.0, (1, 1, 1))])
    path.write_text(scene.to_json())
    assert main(["evaluate", str(path)]) == 0
    out = capsys.readouterr().out
    assert "100.0 %" in out and "box_1 runs 3 cm into box_2" in out
    assert main(["evaluate", str(path), "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["summary"]["scenes_with_collision"] == 1
    assert data["scenes"][0]["collision"]["pairs"][0]["depth_m"] == pytest.approx(0.03)


def test_evaluate_refuses_a_missing_file_in_one_line(tmp_path, capsys):
    assert main(["evaluate", str(tmp_path / "none.json")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "cannot read" in err


def test_validate_warns_of_an_example_whose_objects_run_into_each_other(tmp_path, capsys):
    from pathlib import Path

    source = Path(__file__).parent.parent / "examples" / "sets" / "desks" / "desk_01.json"
    data = json.loads(source.read_text())
    chair = next(o for o in data["objects"] if o["id"] == "chair")
    chair["position"] = [0.3, -0.85]  # its back 0.25 m into the desk's front
    path = tmp_path / "desk.json"
    path.write_text(json.dumps(data))
    assert main(["validate", str(path)]) == 0
    out = capsys.readouterr().out
    assert (
        "warning: chair runs 25 cm into desk" in out or "warning: desk runs 25 cm into chair" in out
    )
    assert "1 warning)" in out
    assert main(["validate", str(source)]) == 0
    assert "warning" not in capsys.readouterr().out


@settings(max_examples=60, deadline=None)
@given(
    gap=st.floats(-0.3, 0.3),
    width=st.floats(0.2, 3.0),
    turn=st.sampled_from([0.0, math.pi / 2, math.pi, -math.pi / 2]),
)
def test_a_collision_is_a_depth_in_centimetres_whatever_the_sizes(gap, width, turn):
    """Two square-to-each-other boxes side by side: they collide exactly when one runs
    more than 1 cm into the other, and the depth is that overlap, however large."""
    first = obj("box_1", 0.0, 0.0, (width, 1.0, width), yaw=turn)
    second = obj("box_2", width / 2.0 + 0.25 + gap, 0.0, (0.5, 1.0, 0.5))
    metrics = evaluate_scene(scene_of([first, second], Room.rectangle(12, 12)))
    overlap = -gap
    if overlap > 0.01 + 1e-9:
        assert metrics.collisions and metrics.collisions[0][2] == pytest.approx(overlap)
    elif overlap < 0.01 - 1e-9:
        assert metrics.collisions == []
