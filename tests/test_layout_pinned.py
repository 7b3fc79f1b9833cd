"""Pinned and warm-started layouts, and measuring a layout without sampling."""

from __future__ import annotations

import math

import numpy as np
import pytest

from scenewright.api import build_scene
from scenewright.core.errors import InputError
from scenewright.core.poses import Pose
from scenewright.core.scene_graph import SceneGraph, SceneParams
from scenewright.generator.catalog import CatalogEntry
from scenewright.generator.layout import LayoutParams, layout_scene, measure_layout
from scenewright.generator.layout.moves import Mover
from scenewright.generator.layout.pinning import compile_pins, pins_from_scene, scene_layout
from scenewright.generator.layout.problem import compile_problem
from scenewright.generator.layout.state import State

TABLE = CatalogEntry("table", "object", "table", size=(1.6, 0.8, 0.9))
SIGN = CatalogEntry("sign", "object", "sign", size=(0.6, 1.6, 0.2))
POT = CatalogEntry("pot", "object", "pot", size=(0.4, 0.3, 0.4))
CHAIR = CatalogEntry("chair", "object", "chair", size=(0.5, 0.9, 0.5))
STAND = CatalogEntry("market_stand", "group", "market stand")
CROSSING = CatalogEntry("crossing", "junction", "crossing", size=(3.0, 0.0, 3.0))
ROAD = CatalogEntry("road", "path", "road", width=3.0, max_length=12.0, segments=2)

FAST = LayoutParams(steps=600, restarts=1)
#: No sampling at all: the result is the initial placement (the warm start).
NO_STEPS = LayoutParams(steps=0, steps_per_box=0, restarts=0)

TABLE_POSE = Pose(2.123456789, 0.0, -1.987654321, 0.4321)
CROSSING_POSE = Pose(-1.25, 0.0, 0.75, 0.0)


def market() -> SceneGraph:
    """A crossing with two roads; a stand (table, sign, pot on the table) by the first; a chair."""
    graph = SceneGraph(params=SceneParams(extent=(24.0, 24.0)))
    crossing = graph.add_node(CROSSING)
    roads = [graph.add_node(ROAD), graph.add_node(ROAD)]
    for road in roads:
        graph.add_relation(road, crossing, "PathConnectedTo")
    stand = graph.add_node(STAND)
    table = graph.add_node(TABLE, parent=stand)
    sign = graph.add_node(SIGN, parent=stand)
    pot = graph.add_node(POT, parent=stand)
    chair = graph.add_node(CHAIR)
    graph.add_relation(sign, table, "NextToRight")
    graph.add_relation(pot, table, "OnTopOf")
    graph.add_relation(stand, roads[0], "NextTo")
    graph.add_relation(chair, table, "NextToChooseDirection")
    graph.add_relation(chair, table, "FacingTowards")
    return graph


@pytest.fixture(scope="module")
def village():
    """``build_scene("village", 7)``, its graph and its poses (shared: built once)."""
    scene = build_scene("village", 7)
    return scene, scene.graph(), *scene_layout(scene)


# -- pinned ------------------------------------------------------------------------------


def test_pinned_poses_are_kept_bit_for_bit_while_the_others_move(village):
    scene, graph, poses, paths = village
    pinned = {box_id: poses[box_id] for box_id in ("tower_1", "house_1", "street_lamp_2")}
    result = layout_scene(graph, 2, pinned=pinned)
    for box_id, pose in pinned.items():
        got = result.poses[box_id]
        assert (got.x, got.y, got.z, got.yaw) == (pose.x, pose.y, pose.z, pose.yaw), box_id
    others = [box_id for box_id in poses if box_id not in pinned]
    moved = [box_id for box_id in others if result.poses[box_id] != poses[box_id]]
    assert len(moved) == len(others)
    assert result.ok, result.problems
    assert result.steps > 0


def test_same_pins_and_seed_give_the_same_layout(village):
    _, graph, poses, _ = village
    pinned = {"tower_2": poses["tower_2"]}
    first, second = (layout_scene(graph, 4, pinned=pinned, params=FAST) for _ in range(2))
    assert first.poses == second.poses and first.energy == second.energy
    assert all(np.array_equal(first.paths[k], second.paths[k]) for k in first.paths)


def test_no_pins_is_the_plain_layout():
    plain = layout_scene(market(), 3, params=FAST)
    empty = layout_scene(market(), 3, params=FAST, pinned={}, pinned_paths={}, start={})
    assert plain.poses == empty.poses and plain.energy == empty.energy


def test_the_mover_never_proposes_a_pinned_box_or_path():
    graph = market()
    problem = compile_problem(graph)
    table, crossing = problem.ids.index("table_1"), problem.ids.index("crossing_1")
    road = problem.path_ids.index("road_1")
    points = [[CROSSING_POSE.x, CROSSING_POSE.z], [5.0, 0.75], [9.0, 2.0]]
    pins = compile_pins(
        problem, {"table_1": TABLE_POSE, "crossing_1": CROSSING_POSE}, {"road_1": points}
    )
    assert pins.box[table] and pins.box[crossing] and pins.path[road]
    assert pins.anchored[problem.ids.index("pot_1")]
    state = State(problem)
    mover = Mover(problem, state, np.random.default_rng(0), LayoutParams(), pins)
    for box in range(problem.n_boxes):
        state.set_pose(box, 0.5 * box, -0.3 * box, 0.1 * box)
    energies = [1.0] * len(problem.relations)
    proposed: set[int] = set()
    for _ in range(4000):
        proposal = mover.propose(energies)
        if proposal is None:
            continue
        boxes, paths = proposal
        assert table not in boxes and crossing not in boxes
        assert road not in paths
        proposed.update(boxes)
    # everything not pinned is proposed, the pot on the pinned table included
    assert proposed == set(range(problem.n_boxes)) - {table, crossing}
    # the stand holds the pinned table: it never moves as a whole, and its rigid moves
    # carry the sign only (the pot stays on the table)
    stand = problem.group_ids.index("market_stand_1")
    assert not mover.group_whole[stand]
    assert mover.group_boxes[stand] == [problem.ids.index("sign_1")]


def test_a_road_comes_to_the_pinned_things_that_must_be_next_to_it():
    far = {
        "table_1": Pose(8.0, 0.0, 8.0, 0.3),
        "sign_1": Pose(8.0 + 0.8 * math.cos(0.3) + 0.6, 0.0, 7.5, 0.3),
    }
    for seed in (1, 2):
        result = layout_scene(market(), seed, params=FAST, pinned=far)
        assert result.poses["table_1"] == far["table_1"] and result.poses["sign_1"] == far["sign_1"]
        by_road = next(r for r in result.relations if r.source == "market_stand_1")
        assert by_road.satisfied, result.problems


def test_something_on_a_pinned_table_stays_on_top_and_may_move():
    results = [
        layout_scene(market(), seed, params=FAST, pinned={"table_1": TABLE_POSE}) for seed in (1, 2)
    ]
    for result in results:
        assert result.poses["table_1"] == TABLE_POSE
        pot = result.poses["pot_1"]
        assert pot.y == TABLE_POSE.y + 0.8
        on_top = next(r for r in result.relations if r.source == "pot_1")
        assert on_top.satisfied
        assert result.ok, result.problems
    assert results[0].poses["pot_1"] != results[1].poses["pot_1"]


def test_a_pinned_junction_keeps_its_roads_starting_there():
    result = layout_scene(market(), 5, params=FAST, pinned={"crossing_1": CROSSING_POSE})
    assert result.poses["crossing_1"] == CROSSING_POSE
    for road in ("road_1", "road_2"):
        assert tuple(result.paths[road][0]) == (CROSSING_POSE.x, CROSSING_POSE.z)


def test_pinned_paths_keep_every_point_and_the_others_avoid_them():
    points = [[CROSSING_POSE.x, CROSSING_POSE.z], [5.0, 0.75], [9.0, 2.0]]
    result = layout_scene(
        market(),
        6,
        params=FAST,
        pinned={"crossing_1": CROSSING_POSE},
        pinned_paths={"road_1": points},
    )
    assert result.paths["road_1"].tolist() == points
    assert result.ok, result.problems  # road_2 leaves the crossing at least 60 degrees from road_1


def test_a_pinned_group_member_stays_and_the_rest_of_the_group_still_fits(village):
    _, graph, poses, _ = village
    pinned = {"windmill_1": poses["windmill_1"]}
    result = layout_scene(graph, 3, pinned=pinned)
    assert result.poses["windmill_1"] == poses["windmill_1"]
    mill = [r for r in result.relations if r.target == "windmill_1"]
    assert mill and all(r.satisfied for r in mill)


# -- warm start ----------------------------------------------------------------------------


def test_a_warm_start_begins_at_the_given_poses(village):
    _, graph, poses, paths = village
    start = {**poses, **paths}
    result = layout_scene(graph, 1, params=NO_STEPS, start=start)
    assert result.steps == 0
    for box_id, pose in poses.items():
        got = result.poses[box_id]
        assert (got.x, got.z, got.yaw) == (pose.x, pose.z, pose.yaw), box_id
        assert got.y == pytest.approx(pose.y)
    for path_id, points in paths.items():
        assert result.paths[path_id].tolist() == points
    # and a short chain from there moves things (the start is not pinned)
    moved = layout_scene(
        graph, 1, params=LayoutParams(steps=200, restarts=0, min_steps=400), start=start
    )
    assert any(moved.poses[k] != poses[k] for k in poses)


def test_a_partial_warm_start_places_the_rest_around_it():
    start = {"table_1": TABLE_POSE}
    result = layout_scene(market(), 2, params=NO_STEPS, start=start)
    table = result.poses["table_1"]
    assert (table.x, table.z, table.yaw) == (TABLE_POSE.x, TABLE_POSE.z, TABLE_POSE.yaw)
    pot, sign = result.poses["pot_1"], result.poses["sign_1"]
    assert math.hypot(pot.x - table.x, pot.z - table.z) < 1.0  # on the table
    assert math.hypot(sign.x - table.x, sign.z - table.z) < 3.0  # beside it


# -- bad input -------------------------------------------------------------------------------


def one_line(error: pytest.ExceptionInfo) -> str:
    text = str(error.value)
    assert "\n" not in text
    return text


@pytest.mark.parametrize(
    "kwargs, fragments",
    [
        ({"pinned": {"tabel_1": TABLE_POSE}}, ["tabel_1", "did you mean 'table_1'"]),
        ({"start": {"nowhere_3": TABLE_POSE}}, ["start", "nowhere_3"]),
        ({"pinned_paths": {"road_9": [[0, 0], [1, 1], [2, 2]]}}, ["road_9"]),
        (
            {"pinned": {"market_stand_1": TABLE_POSE}},
            ["market_stand_1 is a group", "table_1, sign_1, pot_1"],
        ),
        ({"pinned": {"road_1": TABLE_POSE}}, ["road_1 is a path", "pinned_paths"]),
        ({"pinned": {"pot_1": TABLE_POSE}}, ["pot_1 rests on table_1", "pin table_1 too"]),
        (
            {"pinned_paths": {"road_1": [[0, 0], [1, 1], [2, 2]]}},
            ["starts at crossing_1", "pin crossing_1 too"],
        ),
        ({"pinned_paths": {"road_2": [[0, 0], [1, 1]]}}, ["road_2", "expected 3 control points"]),
        ({"pinned": {"table_1": (1.0, 0.0, 2.0, 0.0)}}, ["table_1", "expected a Pose"]),
        ({"pinned": {"table_1": Pose(math.nan, 0.0, 0.0)}}, ["table_1", "finite"]),
        (
            {
                "pinned": {"crossing_1": CROSSING_POSE},
                "pinned_paths": {"road_1": [[5, 5], [6, 6], [7, 7]]},
            },
            ["road_1 starts at (5, 5)", "crossing_1 is pinned at (-1.25, 0.75)"],
        ),
    ],
)
def test_bad_pins_are_one_line_input_errors(kwargs, fragments):
    with pytest.raises(InputError) as error:
        layout_scene(market(), 0, params=FAST, **kwargs)
    text = one_line(error)
    for fragment in fragments:
        assert fragment in text


def test_pins_from_a_scene_add_what_the_named_ids_need(village):
    scene, graph, poses, paths = village
    problem = compile_problem(graph)
    pins = pins_from_scene(scene, problem, ["market_stand_1", "road_2"])
    assert set(pins.poses) == {"table_1", "sign_1", "pot_of_stew_1", "intersection_1"}
    assert set(pins.paths) == {"road_2"} and pins.paths["road_2"] == paths["road_2"]
    assert pins.poses["table_1"] == poses["table_1"]
    with pytest.raises(InputError) as error:
        pins_from_scene(scene, problem, ["tower_7"])
    assert "tower_7" in one_line(error)


# -- measuring -------------------------------------------------------------------------------


def test_measuring_a_generated_scene_reproduces_its_verdicts(village):
    scene, graph, poses, paths = village
    measured = measure_layout(graph, poses, paths)
    assert measured.steps == 0 and measured.acceptance == 0.0
    assert measured.ok == scene.layout.ok
    assert measured.problems == scene.layout.problems
    assert [(r.source, r.target, r.label, r.satisfied, r.chosen) for r in measured.relations] == [
        (r.source, r.target, r.label, r.satisfied, r.chosen) for r in scene.relations
    ]
    assert [r.value for r in measured.relations] == pytest.approx(
        [r.value for r in scene.relations]
    )
    assert measured.energy == pytest.approx(scene.layout.energy)
    assert set(measured.parts) == set(scene.layout.parts)
    # group poses (as a scene lists them) are accepted and ignored
    with_groups = {o.id: Pose(*o.position, o.yaw) for o in scene.objects}
    assert measure_layout(graph, with_groups, paths).relations == measured.relations


def test_measuring_reports_what_does_not_hold():
    graph = market()
    laid = layout_scene(graph, 1, params=FAST)
    assert laid.ok, laid.problems
    poses = dict(laid.poses)
    chair = poses["chair_1"]
    poses["chair_1"] = Pose(chair.x + 30.0, chair.y, chair.z, chair.yaw)  # far away and outside
    measured = measure_layout(graph, poses, laid.paths)
    assert not measured.ok and measured.steps == 0
    assert any(p.startswith("chair_1 is outside the scene") for p in measured.problems)
    verdicts = {(r.source, r.label): r.satisfied for r in measured.relations}
    assert verdicts[("chair_1", "NextToChooseDirection")] is False
    assert measured.parts["extent"] > 0.0


def test_measuring_needs_every_pose_and_knows_every_id():
    graph = market()
    laid = layout_scene(graph, 1, params=FAST)
    poses = dict(laid.poses)
    del poses["sign_1"]
    with pytest.raises(InputError) as error:
        measure_layout(graph, poses, laid.paths)
    assert "sign_1" in one_line(error)
    with pytest.raises(InputError) as error:
        measure_layout(graph, {**laid.poses, "ghost_1": Pose(0, 0, 0)}, laid.paths)
    assert "ghost_1" in one_line(error)
