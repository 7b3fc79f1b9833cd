"""The shipped city rule set and the layout's lots along roads: the city's object
budget and its notes, a town written from the docs laid out ok, items whose road `some
road` drew given another road when theirs is full, and a scene whose roads are too
short for what must stand beside them says by how many metres."""

import re
from pathlib import Path

import numpy as np
import pytest
from test_shipped_rules import noted_bounds, object_bounds

from scenewright.core.scene_graph import SceneGraph
from scenewright.generator.expand import expand
from scenewright.generator.layout import LayoutParams, layout_scene
from scenewright.generator.layout.lots import CLUSTER_TYPE, wrap_clusters
from scenewright.generator.layout.problem import compile_problem
from scenewright.generator.rules import check_rules, load_rules, shipped_rule_sets

TOWN_RULES = Path(__file__).resolve().parent.parent / "benchmarks" / "town_rules"
USER_TOWN = TOWN_RULES / "user_town.rules"
CROSSROADS_TOWN = TOWN_RULES / "crossroads_town.rules"

SHORT_ROADS = """
scene short { extent 120 x 120 ground grass start T max_depth 8 max_nodes 400 }
path road { noun "road" width 3 max_length 30 segments 2 }
junction crossroads { noun "crossroads" size 4 x 0.05 x 4 }
object house { noun "house" size 6 x 5 x 5 shape house }
object bush { noun "bush" plural "bushes" size 1.6 x 1.2 x 1.6 shape bush }
T -> { crossroads as x; 3 road PathConnectedTo x; 40 H NextTo some road }
H -> { house as h; bush NextToChooseSide h }
"""

# The first road exists alone when the homes draw theirs: `some road` gives all 40 the
# first, whose sides hold about 12; three more roads are made after them.
ONE_ROAD_DRAWN = """
scene spill {{ extent 160 x 160 ground grass start T max_depth 8 max_nodes 400 }}
path road {{ noun "road" width 3 max_length 60 segments 3 }}
junction crossroads {{ noun "crossroads" size 4 x 0.05 x 4 }}
object house {{ noun "house" size 6 x 5 x 5 shape house }}
object bush {{ noun "bush" plural "bushes" size 1.6 x 1.2 x 1.6 shape bush }}
T -> {{ crossroads as x; road PathConnectedTo x; 40 H NextTo {target}; 3 road PathConnectedTo x }}
H -> {{ house as h; bush NextToChooseSide h }}
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


@pytest.mark.parametrize(
    "rules, seed, homes",
    [
        (USER_TOWN, 1003, 70),
        (USER_TOWN, 1079, 70),  # a road drawn by 21 houses
        (CROSSROADS_TOWN, 1001, 52),  # roads drawn by 11 homes and lamps, a lane by 11 cottages
    ],
)
def test_a_town_written_from_the_docs_lays_out_ok_with_houses_beside_their_roads(
    rules, seed, homes
):
    assert [str(d) for d in check_rules(str(rules)) if d.is_error] == []
    graph = expand(load_rules(rules), seed)
    result = layout_scene(graph, seed)
    assert result.ok, result.problems[:3]
    beside = [
        r
        for r in result.relations
        if r.label == "NextTo" and r.target.startswith(("road_", "lane_"))
    ]
    assert len(beside) >= homes and all(r.satisfied for r in beside)


def test_items_whose_road_some_road_drew_take_another_road_when_theirs_is_full(tmp_path):
    rules = tmp_path / "spill.rules"
    rules.write_text(ONE_ROAD_DRAWN.format(target="some road"))
    graph = expand(load_rules(rules), 1)
    assert {e.target for e in graph.edges("NextTo") if e.target.startswith("road")} == {"road_1"}
    result = layout_scene(graph, 1, params=LayoutParams(restarts=0))
    assert result.ok, result.problems[:3]
    beside = [r for r in result.relations if r.label == "NextTo" and r.target.startswith("road_")]
    assert len(beside) == 40 and all(r.satisfied for r in beside)
    used = {r.target for r in beside}
    assert len(used) == 4  # spread over every road, each named in the verdict
    for r in beside:  # and the house stands beside the road named
        house = result.poses[r.source]
        road = result.paths[r.target]
        assert min(float(np.hypot(*(p - (house.x, house.z)))) for p in _dense(road)) < 6.0
    again = layout_scene(graph, 1, params=LayoutParams(restarts=0))
    assert again.poses == result.poses and again.relations == result.relations
    # the same homes tied to road #1 by the rule set stay there: not enough frontage
    rules.write_text(ONE_ROAD_DRAWN.format(target="road #1"))
    fixed = layout_scene(expand(load_rules(rules), 1), 1, params=LayoutParams(restarts=0))
    assert not fixed.ok
    assert {
        r.target for r in fixed.relations if r.label == "NextTo" and r.source.startswith("house")
    } == {"road_1"}
    assert re.match(
        r"40 houses need \d+ m of road frontage beside road_1; its sides", fixed.problems[0]
    )


def _dense(points, step: float = 0.5):
    """Points every ``step`` metres along a polyline."""
    for a, b in zip(points, points[1:], strict=False):
        count = max(1, int(np.hypot(*(b - a)) / step))
        for k in range(count + 1):
            yield a + (b - a) * k / count


def test_retargeting_a_relation_is_compiling_it_to_that_road(tmp_path):
    rules = tmp_path / "spill.rules"
    rules.write_text(ONE_ROAD_DRAWN.format(target="some road"))
    graph = expand(load_rules(rules), 1)
    problem = compile_problem(graph)
    term = next(t for t, term in enumerate(problem.relations) if term.target == "road_1")
    assert problem.free_paths[term] == (0, 1, 2, 3)  # every road may take it
    own = problem.with_own_relations()
    own.retarget(term, 2)
    # as if the rule set had written road_3: the graph with that edge moved, compiled
    moved = graph.graph.copy()
    source = problem.relations[term].source
    key = next(k for k, d in moved[source]["road_1"].items() if d["label"] == "NextTo")
    data = moved[source]["road_1"][key]
    edges = list(moved.edges(keys=True, data=True))
    moved.remove_edges_from([(u, v, k) for u, v, k, _ in edges])
    for u, v, k, d in edges:  # in the same order, the one edge now to road_3
        moved.add_edge(u, "road_3" if (u, v, k) == (source, "road_1", key) else v, **d)
    assert data["some"] is True
    expected = compile_problem(SceneGraph(params=graph.params, graph=moved))
    assert own.relations == expected.relations
    assert own.edges == expected.edges
    assert own.terms_of_path == expected.terms_of_path
    assert own.outgoing == expected.outgoing and own.incoming == expected.incoming
    # the problem it was copied from is untouched
    assert problem.relations[term].target == "road_1"
    assert term in problem.terms_of_path[0] and term not in problem.terms_of_path[2]


def test_too_little_frontage_is_said_in_metres_over_the_roads_some_road_may_take(tmp_path):
    rules = tmp_path / "short.rules"
    rules.write_text(SHORT_ROADS)
    graph = expand(load_rules(rules), 1)
    result = layout_scene(graph, 1, params=LayoutParams(restarts=0))
    assert not result.ok
    first = result.problems[0]
    found = re.match(
        r"40 houses need (\d+) m of road frontage beside road_1, road_2 and road_3; "
        r"their sides give (\d+) m \((\d+) found no room\)",
        first,
    )
    assert found, first
    need, given, left = (int(v) for v in found.groups())
    assert need > given and 0 < left < 40


def test_the_layout_is_the_same_whatever_the_number_of_workers():
    graph = expand(load_rules(USER_TOWN), 1000)
    one = layout_scene(graph, 1000, params=LayoutParams(workers=1))
    two = layout_scene(graph, 1000, params=LayoutParams(workers=2))
    assert one.poses == two.poses
    assert all((one.paths[path] == two.paths[path]).all() for path in one.paths)
