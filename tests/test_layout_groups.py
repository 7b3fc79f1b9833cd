"""Group decomposition (``decompose``) and restarts that keep what was fine (``repair``).

Scenes are made here, not read from the shipped rules: farms (a house with a shed
beside it and a barrel on a cart) along roads from two junctions, and loose lamps.
"""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from scenewright.core.poses import Pose
from scenewright.core.scene_graph import SceneGraph, SceneParams
from scenewright.core.seeds import stage_stream
from scenewright.generator.catalog import CatalogEntry
from scenewright.generator.layout import LayoutParams, layout_scene, measure_layout
from scenewright.generator.layout.decompose import (
    decomposes,
    frame_extent,
    frame_streams,
    framed_groups,
    group_scenes,
    lay_out_frames,
    run_decomposed_chain,
)
from scenewright.generator.layout.energy import Energy
from scenewright.generator.layout.initial import place_initial
from scenewright.generator.layout.moves import Mover
from scenewright.generator.layout.pinning import Pins, compile_pins
from scenewright.generator.layout.problem import compile_problem
from scenewright.generator.layout.repair import repair_pins, troubled_items
from scenewright.generator.layout.sampler import run_chain
from scenewright.generator.layout.state import State
from scenewright.generator.layout.synthetic import village_graph

HOUSE = CatalogEntry("house", "object", "house", size=(5.0, 4.0, 4.0))
SHED = CatalogEntry("shed", "object", "shed", size=(2.5, 2.5, 2.0))
CART = CatalogEntry("cart", "object", "cart", size=(1.5, 1.0, 2.5))
BARREL = CatalogEntry("barrel", "object", "barrel", size=(0.6, 0.9, 0.6))
LAMP = CatalogEntry("lamp", "object", "lamp", size=(0.3, 3.0, 0.3))
FARM = CatalogEntry("farm", "group", "farm")
ROAD = CatalogEntry("road", "path", "road", width=3.0, max_length=40.0, segments=3)
CROSSING = CatalogEntry("crossing", "junction", "crossing", size=(4.0, 0.05, 4.0))


def hamlet(farms: int, lamps: int = 4, side: float = 110.0) -> SceneGraph:
    """``farms`` farms (four objects each) beside the roads of two crossings, and lamps."""
    graph = SceneGraph(params=SceneParams(name="hamlet", extent=(side, side)))
    roads = []
    for _ in range(2):
        crossing = graph.add_node(CROSSING)
        for _ in range(3):
            road = graph.add_node(ROAD)
            graph.add_relation(road, crossing, "PathConnectedTo")
            roads.append(road)
    for k in range(farms):
        farm = graph.add_node(FARM)
        house = graph.add_node(HOUSE, parent=farm)
        shed = graph.add_node(SHED, parent=farm)
        cart = graph.add_node(CART, parent=farm)
        barrel = graph.add_node(BARREL, parent=farm)
        graph.add_relation(shed, house, "NextToChooseSide")
        graph.add_relation(shed, house, "FacingSameDirection")
        graph.add_relation(cart, shed, "NextToFront")
        graph.add_relation(barrel, cart, "OnTopOf")
        graph.add_relation(farm, roads[k % len(roads)], "NextTo")
    for k in range(lamps):
        lamp = graph.add_node(LAMP)
        graph.add_relation(lamp, roads[k % len(roads)], "NextTo")
    return graph


def test_the_rule_decomposes_large_grouped_outdoor_scenes_only():
    assert decomposes(compile_problem(hamlet(24)), Pins.none(compile_problem(hamlet(24))))
    small = compile_problem(hamlet(10))  # 44 objects: below the size
    assert not decomposes(small, Pins.none(small))
    loose = compile_problem(hamlet(20, lamps=90))  # 170 objects, most of them loose lamps
    assert not decomposes(loose, Pins.none(loose))
    big = compile_problem(hamlet(24))
    pins = compile_pins(big, start={"lamp_1": Pose(0.0, 0.0, 0.0, 0.0)})
    assert not decomposes(big, pins)  # pinned or started scenes are laid out as given


def test_a_group_scene_holds_the_group_and_only_the_relations_inside_it():
    graph = hamlet(3)
    problem = compile_problem(graph)
    scenes = group_scenes(graph, problem, framed_groups(problem))
    own = scenes[1]
    assert [n.id for n in own.nodes()] == ["farm_2", "house_2", "shed_2", "cart_2", "barrel_2"]
    assert [(e.source, e.label, e.target) for e in own.edges()] == [
        ("shed_2", "NextToChooseSide", "house_2"),
        ("shed_2", "FacingSameDirection", "house_2"),
        ("cart_2", "NextToFront", "shed_2"),
        ("barrel_2", "OnTopOf", "cart_2"),
    ]
    assert own.params.extent == (frame_extent(problem, problem.group_members[1]),) * 2
    assert len(scenes) == 3 and all(len(scene.nodes()) == 5 for scene in scenes)


def frames_of(graph: SceneGraph, seed: int, workers: int = 1):
    problem = compile_problem(graph)
    params = LayoutParams(workers=workers)
    return problem, lay_out_frames(
        graph, problem, params, frame_streams(stage_stream(seed, "layout", 0), problem)
    )


def test_frames_are_ok_and_the_same_for_any_number_of_workers():
    graph = hamlet(24)
    problem, alone = frames_of(graph, 3)
    _, shared = frames_of(graph, 3, workers=2)
    assert sorted(alone.poses) == framed_groups(problem) and all(alone.ok.values())
    assert alone.poses == shared.poses and alone.steps == shared.steps


def test_rigid_placement_keeps_each_group_as_laid_out_in_its_frame():
    graph = hamlet(24)
    problem, frames = frames_of(graph, 4)
    state = State(problem)
    energy = Energy(problem, state, LayoutParams())
    rng = stage_stream(4, "layout", 0)
    place_initial(
        energy,
        Mover(problem, state, rng, LayoutParams(), rigid_groups=list(frames.poses)),
        rng,
        frames=frames.poses,
    )
    for group, frame in frames.poses.items():
        first, *rest = problem.group_members[group]
        turn = state.yaw[first] - frame[first][2]
        c, s = math.cos(turn), math.sin(turn)
        for box in rest:  # every member where the frame puts it, relative to the first
            fx, fz = frame[box][0] - frame[first][0], frame[box][1] - frame[first][1]
            assert state.x[box] - state.x[first] == pytest.approx(fx * c + fz * s, abs=1e-9)
            assert state.z[box] - state.z[first] == pytest.approx(-fx * s + fz * c, abs=1e-9)


def test_a_decomposed_layout_is_reported_honestly_and_deterministically():
    graph = hamlet(22)
    first = layout_scene(graph, 6)
    again = layout_scene(graph, 6, params=LayoutParams(workers=2))
    assert first.poses == again.poses and (first.steps, first.energy) == (again.steps, again.energy)
    measured = measure_layout(graph, first.poses, first.paths)
    assert (measured.ok, measured.problems) == (first.ok, first.problems)
    assert [r.satisfied for r in measured.relations] == [r.satisfied for r in first.relations]
    assert first.ok, first.problems


def test_decomposition_can_be_turned_off():
    graph = village_graph(90, 2)
    problem = compile_problem(graph)
    assert decomposes(problem, Pins.none(problem))
    plain = layout_scene(graph, 2, params=LayoutParams(decompose=False, restarts=0))
    one = run_chain(
        problem, LayoutParams(decompose=False, restarts=0), stage_stream(2, "layout", 0)
    )
    assert plain.steps == one.steps


# -- repair restarts ---------------------------------------------------------------------


def failed_run():
    """A chain stopped after one step from a one-candidate placement of a hamlet, so some
    relations still fail."""
    graph = hamlet(12, side=60.0)
    problem = compile_problem(graph)
    run = run_chain(
        problem,
        LayoutParams(steps=1, steps_per_box=0, min_steps=0, initial_candidates=1),
        stage_stream(0, "layout", 0),
    )
    return problem, run


def test_troubled_items_are_whole_groups_holding_both_ends_of_what_fails():
    problem, run = failed_run()
    again = troubled_items(problem, run)
    assert again and not run.ok
    for (_, _, _, index), relation in zip(problem.edges, run.relations, strict=False):
        if index is not None and not relation.satisfied:
            term = problem.relations[index]
            assert set(term.a.members + term.b.members) <= again
    for group in problem.top_groups:
        members = set(problem.group_members[group])
        assert members <= again or not members & again


def test_a_repair_starts_from_everything_that_was_fine():
    problem, run = failed_run()
    pins = repair_pins(problem, run, Pins.none(problem))
    again = troubled_items(problem, run)
    state = run.energy.state
    assert set(pins.start_poses) == set(range(problem.n_boxes)) - again
    for box, pose in pins.start_poses.items():
        assert (pose.x, pose.z, pose.yaw) == (state.x[box], state.z[box], state.yaw[box])
    assert set(pins.start_points) == set(range(problem.n_paths))
    again_run = run_chain(problem, LayoutParams(restarts=0), stage_stream(0, "layout", 1), pins)
    assert len(again_run.problems) < len(run.problems)


@settings(max_examples=3, deadline=None)
@given(farms=st.integers(20, 23), seed=st.integers(0, 10_000))
def test_decomposed_layouts_repeat_exactly(farms, seed):
    graph = hamlet(farms)
    problem = compile_problem(graph)
    _, frames = frames_of(graph, seed)
    runs = [
        run_decomposed_chain(problem, LayoutParams(), stage_stream(seed, "layout", 0), frames)
        for _ in range(2)
    ]
    first, second = (run.energy.state for run in runs)
    assert (first.x, first.z, first.yaw) == (second.x, second.z, second.yaw)
    assert np.array_equal(np.array(first.points), np.array(second.points))
