"""layout_scene end to end: determinism, a satisfiable scene, an unsatisfiable one, the plan."""

import math

import numpy as np
import pytest
from PIL import Image

from scenewright.core.errors import InputError
from scenewright.core.scene import assemble_scene
from scenewright.core.scene_graph import SceneGraph, SceneParams
from scenewright.generator.catalog import CatalogEntry
from scenewright.generator.layout import LayoutParams, layout_scene
from scenewright.generator.layout.synthetic import village_graph
from scenewright.render.plan_image import draw_plan

TABLE = CatalogEntry("table", "object", "table", size=(1.6, 0.8, 0.9))
SIGN = CatalogEntry("sign", "object", "sign", size=(0.6, 1.6, 0.2))
POT = CatalogEntry("pot", "object", "pot", size=(0.4, 0.3, 0.4))
CHAIR = CatalogEntry("chair", "object", "chair", size=(0.5, 0.9, 0.5))
STAND = CatalogEntry("market_stand", "group", "market stand")
ROAD = CatalogEntry("road", "path", "road", width=3.0, max_length=20.0, segments=2)

FAST = LayoutParams(steps=600, restarts=1)


def small_stand() -> SceneGraph:
    graph = SceneGraph(params=SceneParams(extent=(20.0, 20.0)))
    road = graph.add_node(ROAD)
    stand = graph.add_node(STAND)
    table = graph.add_node(TABLE, parent=stand)
    sign = graph.add_node(SIGN, parent=stand)
    pot = graph.add_node(POT, parent=stand)
    chair = graph.add_node(CHAIR)
    graph.add_relation(sign, table, "NextToRight")
    graph.add_relation(pot, table, "OnTopOfMiddle")
    graph.add_relation(stand, road, "NextTo")
    graph.add_relation(chair, table, "NextToChooseDirection")
    graph.add_relation(chair, table, "FacingTowards")
    return graph


def test_small_satisfiable_scene_is_ok_with_every_relation_satisfied():
    result = layout_scene(small_stand(), seed=1, params=FAST)
    assert result.ok, result.problems
    assert result.problems == []
    assert all(r.satisfied for r in result.relations)
    chosen = [r.chosen for r in result.relations if r.label == "NextToChooseDirection"]
    assert chosen[0] in ("north", "east", "south", "west")
    pot, table = result.poses["pot_1"], result.poses["table_1"]
    assert pot.y == pytest.approx(0.8)
    assert math.hypot(pot.x - table.x, pot.z - table.z) <= 0.1


def test_same_seed_same_result_and_other_seed_differs():
    first = layout_scene(small_stand(), seed=5, params=FAST)
    second = layout_scene(small_stand(), seed=5, params=FAST)
    assert first.poses == second.poses
    assert all(np.array_equal(first.paths[k], second.paths[k]) for k in first.paths)
    assert (first.energy, first.steps) == (second.energy, second.steps)
    assert layout_scene(small_stand(), seed=6, params=FAST).poses != first.poses


def test_contradictory_relations_are_reported_not_hidden_and_drawn_red(tmp_path):
    graph = SceneGraph(params=SceneParams(extent=(10.0, 10.0)))
    a, b = graph.add_node(TABLE), graph.add_node(CHAIR)
    graph.add_relation(b, a, "NextToNorth")
    graph.add_relation(b, a, "NextToSouth")
    result = layout_scene(graph, seed=0, params=LayoutParams(steps=300, restarts=0))
    assert not result.ok
    assert any(
        p.startswith("chair_1 is not north of table_1")
        or p.startswith("chair_1 is not south of table_1")
        for p in result.problems
    )
    assert sum(not r.satisfied for r in result.relations) >= 1
    image = draw_plan(assemble_scene(graph, result, rules="test", seed=0), tmp_path / "plan.png")
    pixels = np.asarray(Image.open(image).convert("RGB")).astype(int)
    red = (pixels[..., 0] > 200) & (pixels[..., 1] < 60) & (pixels[..., 2] < 60)
    assert red.sum() > 20  # the unsatisfied relation's dashed line


def test_village_graph_reaches_ok_and_plan_is_drawn(tmp_path):
    graph = village_graph(30, seed=3)
    result = layout_scene(graph, seed=3)
    assert result.ok, result.problems
    assert set(result.poses) == {n.id for n in graph.nodes() if n.kind in ("object", "junction")}
    for road in graph.nodes("path"):
        assert result.paths[road.id].shape == (road.segments + 1, 2)
    scene = assemble_scene(graph, result, rules="synthetic", seed=3)
    image = draw_plan(scene, tmp_path / "plan.png")
    assert image.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    pixels = np.asarray(Image.open(image).convert("RGB")).astype(int)
    red = (pixels[..., 0] > 200) & (pixels[..., 1] < 60) & (pixels[..., 2] < 60)
    assert red.sum() == 0  # nothing unsatisfied, nothing red


def test_support_between_non_objects_is_an_input_error():
    graph = SceneGraph()
    road, table = graph.add_node(ROAD), graph.add_node(TABLE)
    graph.add_relation(table, road, "OnTopOf")
    with pytest.raises(InputError, match="only objects can rest on objects"):
        layout_scene(graph, seed=0)


def test_empty_graph_and_lone_paths_are_fine():
    assert layout_scene(SceneGraph(), seed=0, params=FAST).ok
    graph = SceneGraph(params=SceneParams(extent=(30.0, 30.0)))
    graph.add_node(ROAD)
    result = layout_scene(graph, seed=0, params=FAST)
    assert result.ok
    assert np.all(np.abs(result.paths["road_1"]) <= 15.0)


def test_impossible_scenes_say_why():
    crowded = SceneGraph(params=SceneParams(extent=(3.0, 3.0)))
    for _ in range(12):
        crowded.add_node(TABLE)
    result = layout_scene(crowded, seed=0, params=LayoutParams(steps=300, restarts=0))
    assert not result.ok
    assert any(" overlaps " in p or "outside the scene" in p for p in result.problems)

    hollow = SceneGraph()
    stand, chair = hollow.add_node(STAND), hollow.add_node(CHAIR)
    hollow.add_relation(chair, stand, "NextTo")
    result = layout_scene(hollow, seed=0, params=FAST)
    assert not result.ok
    assert result.problems == [
        "chair_1 NextTo market_stand_1: a group with nothing in it cannot be placed"
    ]
