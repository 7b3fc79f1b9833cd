"""Every relation label on hand-built configurations that do and do not satisfy it."""

import math

import pytest

from scenewright.core.scene_graph import SceneGraph, SceneParams
from scenewright.generator.catalog import CatalogEntry
from scenewright.generator.layout import LayoutParams
from scenewright.generator.layout.energy import Energy
from scenewright.generator.layout.families import evaluate
from scenewright.generator.layout.problem import compile_problem
from scenewright.generator.layout.report import assess, satisfied
from scenewright.generator.layout.state import State

BOX = CatalogEntry("box", "object", "box", size=(1.0, 1.0, 1.0))
TABLE = CatalogEntry("table", "object", "table", size=(2.0, 1.0, 1.0))
CUP = CatalogEntry("cup", "object", "cup", size=(0.2, 0.1, 0.2))
GROUP = CatalogEntry("stand", "group", "stand")
ROAD = CatalogEntry("road", "path", "road", width=2.0, segments=1)
PARAMS = LayoutParams()
EAST, SOUTH, WEST, NORTH = math.pi / 2, 0.0, -math.pi / 2, math.pi


def scene(label, a_entry=BOX, b_entry=BOX):
    graph = SceneGraph(params=SceneParams(extent=(40.0, 40.0)))
    b = graph.add_node(b_entry)
    a = graph.add_node(a_entry)
    graph.add_relation(a, b, label)
    problem = compile_problem(graph)
    return problem, State(problem)


def measure(label, a_pose, b_pose=(0.0, 0.0, 0.0), a_entry=BOX, b_entry=BOX):
    """(energy, satisfied, chosen) of ``A label B`` with A and B at (x, z, yaw)."""
    problem, state = scene(label, a_entry, b_entry)
    state.set_pose(0, *b_pose)
    state.set_pose(1, *a_pose)
    term = problem.relations[0]
    result = evaluate(term, state, PARAMS)
    return result.energy, satisfied(term, result, PARAMS), result.chosen


def test_next_to_is_within_two_metres():
    near, holds, _ = measure("NextTo", (2.5, 0.0, 0.0))  # 1.5 m gap
    far, fails, _ = measure("NextTo", (4.0, 0.0, 0.0))  # 3 m gap
    assert holds and not fails
    assert near == pytest.approx(-math.log(1 / (1 + math.exp(-3 * 0.5))))
    assert far > near


@pytest.mark.parametrize(
    "label, position",
    [
        ("NextToNorth", (0.0, -2.0)),
        ("NextToSouth", (0.0, 2.0)),
        ("NextToEast", (2.0, 0.0)),
        ("NextToWest", (-2.0, 0.0)),
    ],
)
def test_compass_directions(label, position):
    energy, holds, _ = measure(label, (*position, 0.0))
    assert holds and energy == pytest.approx(math.log1p(math.exp(-3.0)))  # 1 m gap, straight on
    _, opposite, _ = measure(label, (-position[0], -position[1], 0.0))
    assert not opposite


@pytest.mark.parametrize(
    "label, local",
    [
        ("NextToLeft", (2.0, 0.0)),
        ("NextToRight", (-2.0, 0.0)),
        ("NextToFront", (0.0, 2.0)),
        ("NextToBehind", (0.0, -2.0)),
    ],
)
def test_directions_of_b_follow_its_yaw(label, local):
    # B turned to face east: its forward is +X, its left (local +X) is world -Z.
    yaw = EAST
    x = local[0] * math.cos(yaw) + local[1] * math.sin(yaw)
    z = -local[0] * math.sin(yaw) + local[1] * math.cos(yaw)
    _, holds, _ = measure(label, (x, z, 0.0), (0.0, 0.0, yaw))
    assert holds
    _, unturned, _ = measure(label, (x, z, 0.0), (0.0, 0.0, 0.0))
    assert not unturned


def test_direction_tolerance_is_45_degrees():
    _, inside, _ = measure("NextToEast", (2.0, -1.5, 0.0))  # 37 degrees off
    _, outside, _ = measure("NextToEast", (1.5, -2.0, 0.0))  # 53 degrees off
    assert inside and not outside


def test_choose_direction_and_side_record_their_choice():
    _, holds, chosen = measure("NextToChooseDirection", (0.3, -2.0, 0.0))
    assert holds and chosen == "north"
    _, holds, chosen = measure("NextToChooseSide", (-2.0, 0.2, 0.0))
    assert holds and chosen == "right"
    _, fails, chosen = measure("NextToChooseSide", (0.0, 2.0, 0.0))  # in front: neither side
    assert not fails


@pytest.mark.parametrize("label", ["OnTopOf", "IsPartOf", "ImplicitOnTopOf"])
def test_on_top_needs_the_centre_over_the_top(label):
    _, holds, _ = measure(label, (0.5, 0.2, 0.0), a_entry=CUP, b_entry=TABLE)
    _, off, _ = measure(label, (1.3, 0.0, 0.0), a_entry=CUP, b_entry=TABLE)
    assert holds and not off


@pytest.mark.parametrize("prefix", ["IsPartOf", "ImplicitIsPartOf"])
@pytest.mark.parametrize("suffix", ["", "Middle", "Edge", "FrontEdge"])
def test_is_part_of_has_the_geometry_of_on_top_of(prefix, suffix):
    for pose in ((0.05, 0.0, 0.0), (-0.9, 0.1, 0.0), (0.2, 0.4, 0.3), (1.3, 0.0, 0.0)):
        on_top = measure("OnTopOf" + suffix, pose, a_entry=CUP, b_entry=TABLE)
        assert measure(prefix + suffix, pose, a_entry=CUP, b_entry=TABLE) == on_top


def test_support_sets_the_height():
    problem, state = scene("OnTopOf", CUP, TABLE)
    assert state.y == [0.0, 1.0]


def test_a_stack_rests_on_the_top_of_everything_beneath():
    graph = SceneGraph(params=SceneParams(extent=(40.0, 40.0)))
    table = graph.add_node(TABLE)
    box = graph.add_node(BOX)
    cup = graph.add_node(CUP)
    graph.add_relation(cup, box, "OnTopOfMiddle")
    graph.add_relation(box, table, "IsPartOf")
    problem = compile_problem(graph)
    assert problem.beneath(2) == [1, 0]
    assert State(problem).y == [0.0, 1.0, 2.0]


def test_middle_and_edges():
    _, middle, _ = measure("OnTopOfMiddle", (0.05, 0.0, 0.0), a_entry=CUP, b_entry=TABLE)
    _, aside, _ = measure("OnTopOfMiddle", (0.5, 0.0, 0.0), a_entry=CUP, b_entry=TABLE)
    assert middle and not aside
    _, edge, _ = measure(
        "OnTopOfEdge", (-0.9, 0.1, 0.0), a_entry=CUP, b_entry=TABLE
    )  # left side flush
    _, inner, _ = measure("OnTopOfEdge", (0.3, 0.0, 0.0), a_entry=CUP, b_entry=TABLE)
    assert edge and not inner
    _, front, _ = measure(
        "OnTopOfFrontEdge", (0.2, 0.4, 0.0), a_entry=CUP, b_entry=TABLE
    )  # forward is +Z
    _, back, _ = measure("OnTopOfFrontEdge", (0.2, -0.4, 0.0), a_entry=CUP, b_entry=TABLE)
    assert front and not back


def test_facing_labels():
    # A at the origin of its own frame, B 3 m east of A (A is scene node 1, B node 0).
    _, towards, _ = measure("FacingTowards", (-3.0, 0.0, EAST))
    _, not_towards, _ = measure("FacingTowards", (-3.0, 0.0, WEST))
    assert towards and not not_towards
    _, away, _ = measure("FacingAwayFrom", (-3.0, 0.0, WEST))
    assert away
    _, same, _ = measure("FacingSameDirection", (-3.0, 0.0, 0.2), (0.0, 0.0, 0.0))
    _, other, _ = measure("FacingSameDirection", (-3.0, 0.0, NORTH), (0.0, 0.0, 0.0))
    assert same and not other
    _, across, _ = measure("FacingOrthogonalDirection", (-3.0, 0.0, EAST), (0.0, 0.0, 0.0))
    _, parallel, _ = measure("FacingOrthogonalDirection", (-3.0, 0.0, 0.0), (0.0, 0.0, 0.0))
    assert across and not parallel


def test_facing_tolerance_is_30_degrees():
    _, inside, _ = measure("FacingSameDirection", (-3.0, 0.0, math.radians(25)))
    _, outside, _ = measure("FacingSameDirection", (-3.0, 0.0, math.radians(35)))
    assert inside and not outside


def test_group_and_path_endpoints():
    graph = SceneGraph(params=SceneParams(extent=(40.0, 40.0)))
    road = graph.add_node(ROAD)
    stand = graph.add_node(GROUP)
    graph.add_node(BOX, parent=stand)
    graph.add_node(BOX, parent=stand)
    graph.add_relation(stand, road, "NextTo")
    problem = compile_problem(graph)
    state = State(problem)
    state.points[0] = [[-10.0, 0.0], [10.0, 0.0]]  # 2 m wide along x: edge at z = 1
    state.set_pose(0, 0.0, 5.0, 0.0)  # far member
    state.set_pose(1, 3.0, 2.5, 0.0)  # near member: 1 m from the road's edge
    term = problem.relations[0]
    result = evaluate(term, state, PARAMS)
    assert result.distance == pytest.approx(1.0)
    assert satisfied(term, result, PARAMS)


def test_assess_names_the_failures_in_words():
    problem, state = scene("NextToNorth")
    state.set_pose(0, 0.0, 0.0, 0.0)
    state.set_pose(1, 0.0, 4.0, 0.0)
    energy = Energy(problem, state, PARAMS)
    energy.activate([0, 1])
    results, problems = assess(energy)
    assert not results[0].satisfied
    assert problems == ["box_2 is not north of box_1 (distance 3.0 m)"]
    state.set_pose(1, 0.3, 0.0, 0.0)
    energy = Energy(problem, state, PARAMS)
    energy.activate([0, 1])
    _, problems = assess(energy)
    # 0.7 m of overlap, in centimetres whatever the boxes' sizes
    assert problems == ["box_2 is not north of box_1 (90° off)", "box_1 overlaps box_2 by 70 cm"]
