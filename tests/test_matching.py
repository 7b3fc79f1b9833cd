"""Graph matching: the quadratic assignment, its spectral solution, confidence, partial matches."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays
from scipy.optimize import linear_sum_assignment

from scenewright.api import build_scene
from scenewright.examples.example import ObjectRecord, example_scene
from scenewright.variation import structure_graph
from scenewright.variation.matching import (
    EdgeTable,
    Problem,
    discretise,
    edge_similarity,
    exhaustive_solution,
    interchangeable,
    layout_problem,
    match_graphs,
    solve,
    spectral_solution,
)
from scenewright.variation.perturb import perturbed_copy


def scene_of(records, extent=(8.0, 8.0)):
    return example_scene(list(records), name="t", source="t", extent=extent, room=None)


def box(object_id, kind, x, z, yaw_degrees, size, y=0.0):
    return ObjectRecord(object_id, kind, size, (x, y, z), math.radians(yaw_degrees))


#: A hand-built room: a bed between two nightstands, a desk with a chair, a wardrobe
#: beside a dresser, a lamp on the desk.
BEDROOM = [
    box("bed", "bed", 0.0, 0.0, 0.0, (1.6, 0.5, 2.0)),
    box("left_stand", "nightstand", 1.05, -0.75, 0.0, (0.5, 0.55, 0.5)),
    box("right_stand", "nightstand", -1.05, -0.75, 0.0, (0.5, 0.55, 0.5)),
    box("desk", "desk", 2.8, 2.5, -90.0, (1.2, 0.75, 0.6)),
    box("chair", "chair", 2.05, 2.5, 90.0, (0.45, 0.9, 0.45)),
    box("lamp", "lamp", 2.8, 2.8, 0.0, (0.2, 0.4, 0.2), y=0.75),
    box("wardrobe", "wardrobe", -2.5, 2.0, 90.0, (1.2, 2.0, 0.6)),
    box("dresser", "dresser", -2.5, 0.6, 90.0, (1.0, 0.8, 0.5)),
]


def test_a_scene_matches_itself_with_full_confidence():
    graph = structure_graph(scene_of(BEDROOM))
    matching = match_graphs(graph, graph)
    assert matching.mapping() == {
        i: i for i in ["bed", "left_stand", "right_stand", "desk", "chair", "wardrobe", "dresser"]
    }
    assert all(p.confidence == pytest.approx(1.0) for p in matching.pairs)
    assert matching.unmatched_a == [] and matching.withdrawn == []


@pytest.mark.parametrize("seed", range(6))
def test_disguised_copy_matches_each_object_to_its_original(seed):
    scene = scene_of(BEDROOM)
    copy, truth = perturbed_copy(scene, np.random.default_rng(seed))
    first, second = structure_graph(scene), structure_graph(copy)
    survivors = [i for i in truth if i != "lamp"]
    # Every surviving object is assigned its copy ...
    assigned = match_graphs(first, second, threshold=0.0).mapping()
    assert {i: assigned.get(i) for i in survivors} == {i: truth[i] for i in survivors}
    # ... and the confident pairs are right; an object whose neighbour was removed or
    # got the added box beside it may be withdrawn, the removed and added ones are.
    kept = match_graphs(first, second)
    assert all(truth.get(p.a) == p.b for p in kept.pairs)
    assert len(kept.pairs) >= len(survivors) - 2


def test_different_names_same_role():
    # A desk in one study and a dresser in the other, each with a chair in front and a
    # cabinet touching its right side: roles, not names, are matched.
    first = scene_of(
        [
            box("d", "desk", 0.0, 0.0, 0.0, (1.4, 0.75, 0.7)),
            box("c", "chair", 0.0, 0.8, 180.0, (0.5, 0.9, 0.5)),
            box("k", "cabinet", -0.95, 0.0, 0.0, (0.5, 0.7, 0.6)),
        ]
    )
    second = scene_of(
        [
            box("x", "stool", 1.0, 1.8, 90.0, (0.45, 0.8, 0.45)),  # far, unrelated
            box("y", "drawers", 0.0, -0.9, 0.0, (0.4, 0.8, 0.5)),
            box("z", "dresser", 0.85, -0.9, 0.0, (1.2, 0.8, 0.6)),
            box("w", "seat", 0.85, -0.2, 180.0, (0.5, 0.9, 0.5)),
        ]
    )
    matching = match_graphs(structure_graph(first), structure_graph(second))
    assert matching.mapping() == {"d": "z", "c": "w", "k": "y"}


def test_matching_does_not_depend_on_object_order():
    graph = structure_graph(scene_of(BEDROOM))
    shuffled = structure_graph(scene_of([BEDROOM[k] for k in (6, 3, 0, 7, 1, 5, 4, 2)]))
    forward, backward = match_graphs(graph, shuffled), match_graphs(shuffled, graph)
    assert forward.mapping() == {a: a for a in forward.mapping()} and len(forward.pairs) == 7
    assert backward.mapping() == forward.mapping()
    assert forward.energy == pytest.approx(backward.energy)


def test_type_prior_breaks_a_tie_between_identical_boxes():
    first = scene_of(
        [
            box("a", "plant", -2.0, 0.0, 0.0, (0.4, 1.0, 0.4)),
            box("b", "bin", 2.0, 0.0, 0.0, (0.4, 1.0, 0.4)),
        ]
    )
    second = scene_of(
        [
            box("p", "bin", -2.0, 0.0, 0.0, (0.4, 1.0, 0.4)),
            box("q", "plant", 2.0, 0.0, 0.0, (0.4, 1.0, 0.4)),
        ]
    )
    assert match_graphs(
        structure_graph(first), structure_graph(second), type_prior=0.5
    ).mapping() == {"a": "q", "b": "p"}


def test_identical_boxes_with_the_same_relations_are_interchangeable():
    # Two identical stools standing alone, a third against the table and a bin of the
    # same box alone too: the lone stools and the bin cannot be told apart; the stool at
    # the table can, and so can the table.
    stool = (0.4, 0.5, 0.4)
    graph = structure_graph(
        scene_of(
            [
                box("s1", "stool", -3.0, -3.0, 0.0, stool),
                box("s2", "stool", 3.0, 3.0, 90.0, stool),
                box("bin", "bin", -3.0, 3.0, 0.0, stool),
                box("table", "table", 0.0, 0.0, 0.0, (1.2, 0.75, 0.8)),
                box("s3", "stool", 0.0, 0.62, 0.0, stool),
            ]
        )
    )
    group = interchangeable(graph)
    assert group["s1"] == group["s2"] == group["bin"]
    assert len({group["s1"], group["s3"], group["table"]}) == 3
    # Put beside the table, s2's relations tell it from s1.
    beside = structure_graph(
        scene_of(
            [
                box("s1", "stool", -3.0, -3.0, 0.0, stool),
                box("s2", "stool", 0.9, 0.0, 0.0, stool),
                box("table", "table", 0.0, 0.0, 0.0, (1.2, 0.75, 0.8)),
            ]
        )
    )
    assert interchangeable(beside)["s1"] != interchangeable(beside)["s2"]


@pytest.mark.parametrize("reverse", [False, True])
def test_place_breaks_a_tie_between_identical_boxes_alone(reverse):
    # Two identical stools standing alone, renamed in the second room and moved a
    # little: nothing but their places tells them apart (without the tie-break, one of
    # the two orders came out swapped).
    stool = (0.4, 0.5, 0.4)
    first = scene_of(
        [box("a", "stool", -2.0, 1.0, 0.0, stool), box("b", "stool", 2.0, -1.0, 0.0, stool)]
    )
    others = [box("p", "stool", 2.1, -1.0, 0.0, stool), box("q", "stool", -2.0, 0.9, 0.0, stool)]
    second = scene_of(others[::-1] if reverse else others)
    matching = match_graphs(structure_graph(first), structure_graph(second))
    assert matching.mapping() == {"a": "q", "b": "p"}
    assert all(p.confidence == pytest.approx(1.0) for p in matching.pairs)


random_scenes = st.lists(
    st.tuples(
        st.floats(-2.5, 2.5),
        st.floats(-2.5, 2.5),
        st.sampled_from([0.0, 90.0, 180.0, -90.0]),
        st.floats(0.3, 1.5),
        st.floats(0.3, 1.5),
    ),
    min_size=2,
    max_size=6,
)


def graph_of_tuples(boxes):
    return structure_graph(
        scene_of(
            [box(f"o{k}", "t", x, z, yaw, (w, 0.8, d)) for k, (x, z, yaw, w, d) in enumerate(boxes)]
        )
    )


@settings(max_examples=25, deadline=None)
@given(random_scenes, random_scenes)
def test_energy_is_the_quadratic_form_of_the_affinity(first, second):
    problem, _, _ = layout_problem(graph_of_tuples(first), graph_of_tuples(second))
    assignment = solve(problem)
    assert sorted(assignment) == list(range(problem.size))  # one-to-one over the padded size
    vector = np.zeros(problem.size**2)
    vector[np.arange(problem.size) * problem.size + assignment] = 1.0
    assert vector @ (problem.affinity() @ vector) == pytest.approx(problem.energy(assignment))


@settings(max_examples=20, deadline=None)
@given(random_scenes, random_scenes)
def test_solution_is_near_the_exhaustive_optimum(first, second):
    problem, _, _ = layout_problem(graph_of_tuples(first), graph_of_tuples(second))
    _, best = exhaustive_solution(problem)
    spectral = problem.energy(solve(problem, refined=False))
    refined = problem.energy(solve(problem))
    assert spectral <= best + 1e-9 and refined <= best + 1e-9
    assert refined >= spectral - 1e-9
    assert refined >= 0.9 * best


@pytest.mark.parametrize("seed", range(6))
def test_spectral_solution_alone_reaches_the_optimum_on_a_disguised_copy(seed):
    # Seven standing objects against a renamed, jittered copy with one removed and one
    # added: the relaxation itself, with no refinement, finds the best of all 7!.
    scene = scene_of(BEDROOM)
    copy, _ = perturbed_copy(scene, np.random.default_rng(seed))
    problem, _, _ = layout_problem(structure_graph(scene), structure_graph(copy))
    _, best = exhaustive_solution(problem)
    assert problem.energy(solve(problem, refined=False)) == pytest.approx(best)


@settings(max_examples=20, deadline=None)
@given(random_scenes, random_scenes)
def test_unlifted_relaxation_takes_the_better_sign_and_spectral_the_better_relaxation(
    first, second
):
    problem, _, _ = layout_problem(graph_of_tuples(first), graph_of_tuples(second))
    affinity = problem.affinity()
    relaxed = spectral_solution(affinity, problem.size, lifted=False)
    assert np.allclose(relaxed.sum(axis=0), relaxed.sum(axis=0)[0]) and np.allclose(
        relaxed.sum(axis=1), relaxed.sum(axis=1)[0]
    )
    assert problem.energy(discretise(relaxed)) >= problem.energy(discretise(-relaxed)) - 1e-9
    # The spectral solution alone is the better of the two relaxations' assignments.
    lifted = discretise(spectral_solution(affinity, problem.size))
    best = max(problem.energy(lifted), problem.energy(discretise(relaxed)))
    assert problem.energy(solve(problem, refined=False)) == pytest.approx(best)


@pytest.mark.slow
def test_rows_of_identical_desks_reach_the_true_matching_energy():
    # Classrooms against their disguised copies: rows of identical desks, where the
    # lifted relaxation alone stops short of the true matching and the start from the
    # unlifted relaxation reaches it. The solver is a local search: on one classroom of
    # these eight (seed 2) it stops 0.4 % short, on the others it reaches the truth or
    # finds a matching of higher energy.
    short = []
    for seed in range(8):
        scene = build_scene("classroom", seed)
        copy, truth = perturbed_copy(scene, np.random.default_rng(2))
        first, second = structure_graph(scene), structure_graph(copy)
        problem, nodes_a, nodes_b = layout_problem(first, second)
        where = {second.ids[k]: position for position, k in enumerate(nodes_b)}
        true = [where[truth[first.ids[i]]] for i in nodes_a if first.ids[i] in truth]
        rows = [p for p, i in enumerate(nodes_a) if first.ids[i] in truth]
        found, expected = problem.energy(solve(problem)), _completed_energy(problem, rows, true)
        assert found >= 0.995 * expected, seed
        short += [seed] if found < expected - 1e-9 else []
    assert len(short) <= 1, short


def _completed_energy(problem, rows, columns):
    """The energy of the partial assignment rows -> columns, the rest (the removed
    object, the added one, padding) paired by their best one-to-one object similarity."""
    assignment = -np.ones(problem.size, dtype=int)
    assignment[rows] = columns
    free_rows = [p for p in range(problem.size) if assignment[p] < 0]
    free_columns = sorted(set(range(problem.size)) - set(columns))
    unary = np.zeros((problem.size, problem.size))
    unary[: problem.unary.shape[0], : problem.unary.shape[1]] = problem.unary
    r, c = linear_sum_assignment(-unary[np.ix_(free_rows, free_columns)])
    assignment[np.array(free_rows)[r]] = np.array(free_columns)[c]
    return problem.energy(assignment)


NO_EDGES = EdgeTable.from_rows([])


@settings(max_examples=60, deadline=None)
@given(
    st.tuples(st.integers(1, 6), st.integers(1, 6)).flatmap(
        lambda shape: arrays(float, shape, elements=st.floats(0.01, 1.0))
    )
)
def test_without_edges_the_spectral_solution_is_the_best_linear_assignment(unary):
    # The object similarities enter the relaxation as a linear term (lifted with a
    # homogeneous coordinate), so with no edges the relaxed solution is the unary
    # matrix plus constants per row and column, whose Hungarian assignment is exact.
    # On W's diagonal they would only count x_ik^2, and the relaxation could miss it.
    problem = Problem(unary, NO_EDGES, NO_EDGES, np.zeros((0, 0)))
    rows, columns = linear_sum_assignment(-unary)
    assert problem.energy(solve(problem, refined=False)) == pytest.approx(
        unary[rows, columns].sum()
    )


@pytest.mark.parametrize("gaps", [(0.04, 0.06), (0.03, 0.07), (0.62, 0.66)])
def test_a_small_move_across_a_threshold_keeps_most_of_the_edge_score(gaps):
    # A cabinet beside a desk, 2 cm either side of the contact gap (a contact, then a
    # close pair), and either side of near (0.64 m, the desk's half diagonal): as
    # relations they differ, as graded memberships they nearly agree.
    def table(gap):
        graph = structure_graph(
            scene_of(
                [
                    box("d", "desk", 0.0, 0.0, 0.0, (1.1, 0.75, 0.7)),
                    box("k", "cabinet", -0.8 - gap, 0.0, 0.0, (0.5, 0.7, 0.7)),
                ]
            )
        )
        return EdgeTable.of(graph, graph.layout_nodes())

    first, second = table(gaps[0]), table(gaps[1])
    own = min(first.self_scores(2).min(), second.self_scores(2).min())
    assert own > 0.0
    assert edge_similarity(first, second).diagonal().min() >= 0.75 * own


def test_an_object_that_gained_a_neighbour_without_counterpart_is_kept():
    # A lone table; in the other scene a box (the added object) stands against it and a
    # plant (the removed object) is gone. The box is paired with the plant, far below the
    # threshold: their edges say nothing about the table's own pair.
    table = box("t", "table", 0.0, 0.0, 0.0, (1.2, 0.75, 0.8))
    first = scene_of([table, box("p", "plant", 3.0, 3.0, 0.0, (0.3, 1.5, 0.3))])
    second = scene_of([table, box("b", "box", 0.0, 0.85, 0.0, (1.2, 0.4, 0.9))])
    matching = match_graphs(structure_graph(first), structure_graph(second))
    assert matching.mapping() == {"t": "t"}
    assert [(p.a, p.b) for p in matching.withdrawn] == [("p", "b")]
