"""Road networks a rule set chooses: a grid's roads run straight and square (small scenes
and the fitted networks of a town) and its junction's network survives scene.json;
roads that branch from roads start on them and stay there; a road short of frontage
grows and bends within its maximum; the towns written from the docs with a grid and
with branches lay out as they promise."""

import math
import re
from pathlib import Path

import numpy as np
import pytest

from scenewright.core.errors import InputError
from scenewright.core.geometry import nearest_on_polyline
from scenewright.core.scene import Scene, assemble_scene
from scenewright.generator.expand import expand
from scenewright.generator.layout import LayoutParams, initial, layout_scene
from scenewright.generator.layout.branches import branch_angle
from scenewright.generator.layout.energy import Energy
from scenewright.generator.layout.problem import compile_problem
from scenewright.generator.layout.state import State
from scenewright.generator.rules import load_rules

SMALL_GRID = """
scene g { extent 80 x 80 ground grass start T }
path road { noun "road" width 3 max_length 30 segments 3 }
junction crossing { noun "crossing" size 4 x 0.05 x 4 network grid }
object house { noun "house" size 6 x 5 x 5 shape house }
T -> { crossing as x; 4 road PathConnectedTo x; 6 house NextTo some road }
"""

# Two grid junctions and 40 homes of two objects each: large enough for lots along the
# roads and fitted networks (group decomposition).
TOWN_GRID = """
scene t { extent 160 x 160 ground grass start T max_nodes 400 }
path road { noun "road" width 3 max_length 60 segments 3 }
junction crossing { noun "crossing" size 4 x 0.05 x 4 network grid }
group home { noun "home" }
object house { noun "house" size 6 x 5 x 5 shape house }
object bush { noun "bush" plural "bushes" size 1.6 x 1.2 x 1.6 shape bush }
T -> { crossing as a; 4 road PathConnectedTo a; crossing as b; 3 road PathConnectedTo b
       40 Home NextTo some road }
Home -> { home { house as h; bush NextToChooseSide h } }
"""


def _headings(points) -> list[float]:
    points = np.asarray(points, dtype=float)
    steps = np.diff(points, axis=0)
    return [math.atan2(dz, dx) for dx, dz in steps]


def _square(angle: float, tolerance: float = 1e-6) -> bool:
    """Whether an angle is a whole number of right angles."""
    quarter = angle / (math.pi / 2)
    return abs(quarter - round(quarter)) < tolerance


@pytest.fixture
def rules_file(tmp_path):
    def write(text: str, name: str = "roads.rules"):
        path = tmp_path / name
        path.write_text(text)
        return load_rules(path)

    return write


def test_a_grid_junctions_roads_leave_at_right_angles_and_run_straight(rules_file):
    rules = rules_file(SMALL_GRID)
    graph = expand(rules, 3)
    result = layout_scene(graph, 3, params=LayoutParams(restarts=0))
    junction = result.poses["crossing_1"]
    firsts = []
    for road in (f"road_{k}" for k in range(1, 5)):
        points = result.paths[road]
        assert np.allclose(points[0], (junction.x, junction.z))
        headings = _headings(points)
        assert all(abs(h - headings[0]) < 1e-9 for h in headings)  # straight
        firsts.append(headings[0])
    firsts.sort()
    gaps = [b - a for a, b in zip(firsts, firsts[1:], strict=False)]
    assert all(abs(gap - math.pi / 2) < 1e-9 for gap in gaps)


def test_the_fitted_grids_of_a_town_are_square_to_each_other(rules_file):
    rules = rules_file(TOWN_GRID)
    graph = expand(rules, 1)
    result = layout_scene(graph, 1, params=LayoutParams(restarts=0))
    assert result.ok, result.problems[:3]
    headings = [h for road in result.paths.values() for h in _headings(road)]
    assert len(headings) == 7 * 3
    # every segment of every road runs parallel or square to the first road
    assert all(_square(h - headings[0]) for h in headings)
    for junction, roads in (("crossing_1", range(1, 5)), ("crossing_2", range(5, 8))):
        pose = result.poses[junction]
        for road in roads:
            assert np.allclose(result.paths[f"road_{road}"][0], (pose.x, pose.z))


def test_a_grid_junction_keeps_its_network_in_scene_json(rules_file):
    rules = rules_file(SMALL_GRID)
    graph = expand(rules, 3)
    assert graph.node("crossing_1").network == "grid"
    assert graph.node("road_1").network is None
    assert "network" in graph.to_dict()["nodes"][0]  # the junction, the first node
    scene = assemble_scene(graph, layout_scene(graph, 3), rules="g", seed=3)
    data = scene.to_dict()
    assert [o.get("network") for o in data["objects"] if o["kind"] == "junction"] == ["grid"]
    assert all("network" not in o for o in data["objects"] if o["kind"] != "junction")
    again = Scene.from_json(scene.to_json()).graph()
    assert again.node("crossing_1").network == "grid"


def test_an_organic_networks_graph_and_scene_json_say_nothing_of_networks():
    graph = expand(load_rules("village"), 1000)
    assert all("network" not in node for node in graph.to_dict()["nodes"])


BRANCHES = """
scene b { extent 90 x 90 ground grass start T }
path road { noun "road" width 3 max_length 40 segments 3 }
path lane { noun "lane" width 2.5 max_length 25 segments 2 }
junction crossing { noun "crossing" size 4 x 0.05 x 4 NETWORK }
object house { noun "house" size 6 x 5 x 5 shape house }
T -> { crossing as x; road as r PathConnectedTo x; 2 road PathConnectedTo x
       2 lane PathConnectedTo r; 5 house NextTo some road; 3 house NextTo some lane }
"""


def _on(point, polyline) -> float:
    """How far a point is from a polyline (metres)."""
    return nearest_on_polyline([list(p) for p in polyline], float(point[0]), float(point[1]))[0]


def _leaving_angle(parent, branch) -> float:
    return branch_angle([list(p) for p in parent], [list(p) for p in branch])


@pytest.mark.parametrize("network", ["", "network grid"])
def test_a_branch_starts_on_its_road_and_leaves_it_square_or_nearly(rules_file, network):
    rules = rules_file(BRANCHES.replace("NETWORK", network))
    graph = expand(rules, 1000)
    result = layout_scene(graph, 1000, params=LayoutParams(restarts=0))
    assert result.ok, result.problems[:3]
    road = result.paths["road_1"]
    for lane in ("lane_1", "lane_2"):
        points = result.paths[lane]
        assert _on(points[0], road) < 1e-6  # annealed with the road, still on it
        assert _on(points[0], road[:1]) > 5.0  # along it, not at the junction
        angle = _leaving_angle(road, points)
        if network:
            assert abs(angle - math.pi / 2) < 1e-9
        else:
            assert angle >= math.radians(60)
    scene = assemble_scene(graph, result, rules="b", seed=1000)
    assert scene.path("lane_1").start == "road_1"


def test_moving_a_road_carries_its_branches_along(rules_file):

    problem = compile_problem(expand(rules_file(BRANCHES.replace("NETWORK", "")), 1000))
    energy = Energy(problem, State(problem), LayoutParams())
    road = [[0.0, 0.0], [10.0, 0.0], [20.0, 0.0], [30.0, 0.0]]
    energy.propose({}, {0: road})
    energy.accept()
    lanes = problem.branches_of[0]
    for lane, x in zip(lanes, (15.0, 25.0), strict=True):
        energy.propose({}, {lane: [[x, 0.0], [x, 10.0], [x, 20.0]]})
        energy.accept()
    moved = [[0.0, 0.0], [10.0, 5.0], [20.0, 6.0], [30.0, 12.0]]
    energy.propose({}, {0: moved})
    energy.accept()
    # each lane's start is where it was along its segment of the road, the rest as it was
    assert energy.state.points[lanes[0]] == [[15.0, 5.5], [15.0, 10.0], [15.0, 20.0]]
    assert energy.state.points[lanes[1]] == [[25.0, 9.0], [25.0, 10.0], [25.0, 20.0]]
    energy.propose({}, {0: road})
    energy.reject()  # and back with the road when the move is rejected
    assert energy.state.points[lanes[0]][0] == [15.0, 5.5]
    # the incremental change (the lanes' angles to the road included) is the full one
    full = Energy(problem, State(problem), LayoutParams(incremental=False))
    for path in problem.path_order:
        full.propose({}, {path: energy.state.points[path]})
        full.accept()
    bent = [[0.0, 0.0], [10.0, -4.0], [20.0, 3.0], [30.0, 0.0]]
    assert energy.propose({}, {0: bent}) == pytest.approx(full.propose({}, {0: bent}))


def test_branches_that_start_on_each_other_are_refused(rules_file):

    rules = rules_file(
        BRANCHES.replace("NETWORK", "").replace(
            "2 lane PathConnectedTo r;",
            "lane as a; lane as b PathConnectedTo a; a PathConnectedTo b;",
        )
    )
    with pytest.raises(
        InputError, match=r"in a circle: lane_1 -> lane_2 -> lane_1|lane_2 -> lane_1 -> lane_2"
    ):
        compile_problem(expand(rules, 1))


# One road of up to 150 m from a crossing in 80 x 80 m, and 40 homes that must stand
# beside it: a straight road meets the scene's edge long before its maximum.
CRAMPED = """
scene bend { extent 80 x 80 ground grass start T max_nodes 400 }
path road { noun "road" width 3 max_length 150 segments 4 }
junction crossing { noun "crossing" size 4 x 0.05 x 4 }
group home { noun "home" }
object house { noun "house" size 6 x 5 x 5 shape house }
object bush { noun "bush" plural "bushes" size 1.6 x 1.2 x 1.6 shape bush }
T -> { crossing as x; road PathConnectedTo x; 40 Home NextTo road #1 }
Home -> { home { house as h; bush NextToChooseSide h } }
"""


def _frontage_line(problems) -> tuple[int, int]:
    found = re.match(
        r"40 homes need \d+ m .* its sides give (\d+) m \((\d+) found no room\)", problems[0]
    )
    assert found, problems[0]
    return int(found.group(1)), int(found.group(2))


def test_a_road_short_of_frontage_bends_into_free_space_within_its_length(rules_file, monkeypatch):

    graph = expand(rules_file(CRAMPED), 3)
    longer = layout_scene(graph, 3, params=LayoutParams(restarts=0))
    monkeypatch.setattr(initial, "lengthen", lambda energy, paths: {})
    straight = layout_scene(graph, 3, params=LayoutParams(restarts=0))
    given, left = _frontage_line(longer.problems)
    given_before, left_before = _frontage_line(straight.problems)
    assert given > given_before and left < left_before
    road = np.asarray(longer.paths["road_1"])
    length = float(np.sum(np.hypot(*np.diff(road, axis=0).T)))
    assert 2 * length == pytest.approx(given, abs=1.0) and length <= 150
    assert np.allclose(road[0], straight.paths["road_1"][0])  # from the same junction
    assert np.all(np.abs(road) <= 40)
    turns = np.abs(np.remainder(np.diff(_headings(road)) + math.pi, 2 * math.pi) - math.pi)
    assert turns.max() > 0.1 and turns.max() < math.radians(60)  # bent, within gamma


TOWN_RULES = Path(__file__).resolve().parent.parent / "benchmarks" / "town_rules"


def test_a_grid_town_written_from_the_docs_has_square_blocks_and_square_side_streets():
    graph = expand(load_rules(TOWN_RULES / "grid_town.rules"), 1000)
    result = layout_scene(graph, 1000)
    assert result.ok, result.problems[:3]
    headings = [h for road in result.paths.values() for h in _headings(road)]
    assert all(_square(h - headings[0]) for h in headings)
    starts = {e.source: e.target for e in graph.edges("PathConnectedTo")}
    streets = [path for path in result.paths if path.startswith("street_")]
    assert len(streets) >= 7
    for street in streets:
        avenue = result.paths[starts[street]]
        assert _on(result.paths[street][0], avenue) < 1e-6
        assert abs(_leaving_angle(avenue, result.paths[street]) - math.pi / 2) < 1e-9


def test_a_branching_town_written_from_the_docs_lays_out_with_lanes_on_their_roads():
    graph = expand(load_rules(TOWN_RULES / "branch_town.rules"), 1000)
    result = layout_scene(graph, 1000)
    assert result.ok, result.problems[:3]
    starts = {e.source: e.target for e in graph.edges("PathConnectedTo")}
    lanes = [path for path in result.paths if "lane_" in path]
    assert len(lanes) >= 11  # two or three a road, and the farm lane
    for lane in lanes:
        parent = result.paths[starts[lane]]
        assert _on(result.paths[lane][0], parent) < 1e-6
        assert _leaving_angle(parent, result.paths[lane]) >= math.radians(60)
