"""The shipped city rule set and the layout's lots along roads: the city's object
budget and its notes, a town written from the docs laid out ok, and a scene whose roads
are too short for what must stand beside them says by how many metres."""

import re
from pathlib import Path

from test_shipped_rules import noted_bounds, object_bounds

from scenewright.generator.expand import expand
from scenewright.generator.layout import LayoutParams, layout_scene
from scenewright.generator.layout.lots import CLUSTER_TYPE, wrap_clusters
from scenewright.generator.rules import check_rules, load_rules, shipped_rule_sets

USER_TOWN = Path(__file__).resolve().parent.parent / "benchmarks" / "town_rules" / "user_town.rules"

SHORT_ROADS = """
scene short { extent 120 x 120 ground grass start T max_depth 8 max_nodes 400 }
path road { noun "road" width 3 max_length 30 segments 2 }
junction crossroads { noun "crossroads" size 4 x 0.05 x 4 }
object house { noun "house" size 6 x 5 x 5 shape house }
object bush { noun "bush" plural "bushes" size 1.6 x 1.2 x 1.6 shape bush }
T -> { crossroads as x; 3 road PathConnectedTo x; 40 H NextTo some road }
H -> { house as h; bush NextToChooseSide h }
"""


def test_city_is_shipped_validates_and_its_notes_say_its_budget():
    assert "city" in shipped_rule_sets()
    assert [str(d) for d in check_rules("city") if d.is_error] == []
    rules = load_rules("city")
    bounds = object_bounds(rules)
    assert bounds[rules.start] == (1103, 2225)
    assert noted_bounds(rules) == bounds
    counts = [len(expand(rules, seed).nodes("object")) for seed in range(3)]
    assert all(1103 <= count <= 2225 for count in counts)


def test_loose_houses_and_gardens_are_grouped_for_the_layout_only():
    graph = expand(load_rules(USER_TOWN), 1000)
    wrapped = wrap_clusters(graph)
    clusters = [n for n in wrapped.nodes("group") if n.type == CLUSTER_TYPE]
    houses = [n for n in graph.nodes("object") if n.type == "house"]
    assert len(clusters) >= len(houses) == 70
    # the boxes, their order and the relations are the same; only parents are added
    assert [n.id for n in wrapped.nodes() if n.kind == "object"] == [
        n.id for n in graph.nodes("object")
    ]
    assert wrapped.edges() == graph.edges()
    assert all(n.type != CLUSTER_TYPE for n in graph.nodes())


def test_a_town_written_from_the_docs_lays_out_ok_with_houses_beside_their_roads():
    graph = expand(load_rules(USER_TOWN), 1003)
    result = layout_scene(graph, 1003)
    assert result.ok, result.problems[:3]
    beside = [r for r in result.relations if r.label == "NextTo" and r.target.startswith("road_")]
    assert len(beside) >= 70 and all(r.satisfied for r in beside)


def test_too_little_frontage_is_said_road_by_road_in_metres(tmp_path):
    rules = tmp_path / "short.rules"
    rules.write_text(SHORT_ROADS)
    graph = expand(load_rules(rules), 1)
    result = layout_scene(graph, 1, params=LayoutParams(restarts=0))
    assert not result.ok
    first = result.problems[0]
    assert re.search(
        r"\d+ houses need \d+ m of road frontage beside road_\d; its sides give \d+ m", first
    )


def test_the_layout_is_the_same_whatever_the_number_of_workers():
    graph = expand(load_rules(USER_TOWN), 1000)
    one = layout_scene(graph, 1000, params=LayoutParams(workers=1))
    two = layout_scene(graph, 1000, params=LayoutParams(workers=2))
    assert one.poses == two.poses
    assert all((one.paths[path] == two.paths[path]).all() for path in one.paths)
