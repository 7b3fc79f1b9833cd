"""Scene graph building and the scene.json round trip."""

from dataclasses import FrozenInstanceError, fields

import pytest

from scenewright.core.poses import LayoutResult, Pose
from scenewright.core.relations import Relation, UnknownLabel
from scenewright.core.scene import Scene, assemble_scene
from scenewright.core.scene_graph import SceneGraph, SceneNode, SceneParams
from scenewright.generator.catalog import CatalogEntry, Style

TABLE = CatalogEntry("table", "object", "table", size=(1.6, 0.8, 0.9), shape="box")
COMPUTER = CatalogEntry(
    "computer",
    "object",
    "computer",
    size=(0.5, 0.4, 0.3),
    styles=(
        Style("laptop", 0.6, noun="laptop", size=(0.35, 0.02, 0.25)),
        Style("tablet", 0.4, noun="tablet"),
    ),
)
STAND = CatalogEntry("market_stand", "group", "market stand")
ROAD = CatalogEntry("road", "path", "road", width=3.0)


def small_graph() -> SceneGraph:
    graph = SceneGraph(params=SceneParams(extent=(20.0, 10.0)))
    stand = graph.add_node(STAND, rule="MarketStand")
    table = graph.add_node(TABLE, parent=stand, rule="MarketStand")
    laptop = graph.add_node(COMPUTER, style=COMPUTER.styles[0], parent=stand, rule="Goods")
    road = graph.add_node(ROAD, rule="Roads")
    graph.add_relation(laptop, table, "OnTopOfMiddle")
    graph.add_relation(stand, road, "NextTo")
    return graph


def test_ids_are_type_and_counter_in_creation_order():
    graph = small_graph()
    assert [n.id for n in graph.nodes()] == ["market_stand_1", "table_1", "computer_1", "road_1"]
    assert graph.add_node(TABLE) == "table_2"


def test_style_overrides_noun_and_size():
    laptop = small_graph().node("computer_1")
    assert (laptop.noun, laptop.style, laptop.size) == ("laptop", "laptop", (0.35, 0.02, 0.25))


def test_nodes_read_back_are_the_nodes_stored():
    """A node is stored as every field, in order; reading it back fills the fields in
    at once, with the same value, hash and frozenness as the dataclass built field by
    field. A node stored with only some fields (by code other than the graph's own)
    gets the defaults for the rest."""
    graph = small_graph()
    for node in graph.nodes():
        assert list(graph.graph.nodes[node.id]) == [field.name for field in fields(SceneNode)]
        built = SceneNode(**graph.graph.nodes[node.id])
        assert node == built and hash(node) == hash(built) and repr(node) == repr(built)
        assert graph.node(node.id) == built
    with pytest.raises(FrozenInstanceError):
        graph.node("table_1").noun = "desk"  # type: ignore[misc]
    graph.graph.add_node(
        "lamp_9",
        **{"id": "lamp_9", "type": "lamp", "kind": "object", "noun": "lamp", "plural": None},
        **{"size": (0.3, 1.5, 0.3), "shape": "box", "mesh": None, "colour": (1.0, 1.0, 1.0)},
    )
    lamp = graph.node("lamp_9")
    assert (lamp.noun, lamp.access, lamp.clearance, lamp.order) == ("lamp", ("any",), (), 0)


def test_members_of_a_group():
    graph = small_graph()
    assert [n.id for n in graph.children("market_stand_1")] == ["table_1", "computer_1"]
    crate = graph.add_node(STAND, parent="market_stand_1")
    graph.add_node(TABLE, parent=crate)
    assert [n.id for n in graph.children("market_stand_1")] == [
        "table_1",
        "computer_1",
        "market_stand_2",
    ]
    assert [n.id for n in graph.descendants("market_stand_1")] == [
        "table_1",
        "computer_1",
        "market_stand_2",
        "table_2",
    ]
    assert {parent: [n.id for n in members] for parent, members in graph.by_parent().items()} == {
        None: ["market_stand_1", "road_1"],
        "market_stand_1": ["table_1", "computer_1", "market_stand_2"],
        "market_stand_2": ["table_2"],
    }
    assert graph.children("road_1") == []


def test_unknown_label_and_node_are_refused():
    graph = small_graph()
    with pytest.raises(UnknownLabel, match="unknown relation label"):
        graph.add_relation("table_1", "road_1", "Besides")
    with pytest.raises(KeyError):
        graph.add_relation("table_1", "nowhere_1", "NextTo")
    with pytest.raises(ValueError, match="to itself"):
        graph.add_relation("table_1", "table_1", "NextTo")
    with pytest.raises(KeyError, match="unknown parent"):
        graph.add_node(TABLE, parent="nowhere_1")
    assert len(graph) == 4  # nothing was added


def test_graph_dict_round_trip():
    graph = small_graph()
    again = SceneGraph.from_dict(graph.to_dict())
    assert again.to_dict() == graph.to_dict()
    assert again.add_node(TABLE) == "table_2"


def test_templates_folder_travels_from_params_to_scene_and_back():
    graph = SceneGraph(params=SceneParams(templates="/rules/stall/templates"))
    graph.add_node(TABLE)
    assert SceneGraph.from_dict(graph.to_dict()).params == graph.params
    layout = LayoutResult(
        poses={"table_1": Pose(0.0, 0.0, 0.0, 0.0)},
        paths={},
        relations=[],
        energy=0.0,
        parts={},
        steps=1,
        acceptance=1.0,
        seconds=0.0,
        ok=True,
    )
    scene = assemble_scene(graph, layout, rules="test", seed=0)
    assert scene.templates == "/rules/stall/templates"
    assert Scene.from_json(scene.to_json()).templates == "/rules/stall/templates"
    assert scene.graph().params.templates == "/rules/stall/templates"


def test_scene_json_round_trip_and_group_box():
    graph = small_graph()
    layout = LayoutResult(
        poses={"table_1": Pose(1.0, 0.0, 2.0, 0.0), "computer_1": Pose(1.0, 0.8, 2.0, 0.0)},
        paths={"road_1": [[-10.0, 0.0], [10.0, 0.0]]},
        relations=[
            Relation("computer_1", "table_1", "OnTopOfMiddle", 0.0, True),
            Relation("market_stand_1", "road_1", "NextTo", -0.01, True),
        ],
        energy=0.01,
        parts={"relations": 0.01},
        steps=10,
        acceptance=0.5,
        seconds=0.1,
        ok=True,
    )
    scene = assemble_scene(graph, layout, rules="test", seed=3)
    stand = scene.object("market_stand_1")
    assert stand.position == pytest.approx([1.0, 0.0, 2.0])
    assert stand.size == pytest.approx([1.6, 0.82, 0.9])
    text = scene.to_json()
    assert Scene.from_json(text).to_json() == text
    assert scene.graph().to_dict()["edges"] == graph.to_dict()["edges"]
