"""Rows of furniture in a room: how the layout builds and mends them.

A row is a group of desks side by side (NextToLeft), lined up (AlignedWith), each facing
away from a board on the wall (FacingOpposite), with a chair behind each. Covered: the
constructive placement builds the row as a row (every relation inside it holds right
after it, whatever spot the row gets), ``alignment.snap_aligned`` mends a desk a few
centimetres out of line where it stands, ``next_to.kept_free`` leaves a board's free
space in front of it when what stands by a desk may not stand there and a way to a
desk's only used side, ``_push_off_walls`` shifts rows off a wall, a room's clusters
are not tied by heading-only facing relations, and ``rect_distance``'s shortcut for
rectangles square to each other.
"""

import math

import numpy as np
import pytest

from scenewright.core.geometry import (
    Rect,
    corners,
    point_rect_distance,
    rect_distance,
    rect_overlap,
)
from scenewright.core.room import Room
from scenewright.core.scene_graph import SceneGraph, SceneParams
from scenewright.generator import expand, load_rules
from scenewright.generator.catalog import CatalogEntry
from scenewright.generator.layout import LayoutParams
from scenewright.generator.layout.energy import Energy
from scenewright.generator.layout.families import alignment, evaluate, facing, next_to, satisfied
from scenewright.generator.layout.initial import _best_of, _push_off_walls
from scenewright.generator.layout.moves import Mover
from scenewright.generator.layout.problem import compile_problem
from scenewright.generator.layout.reachability import CORRIDOR_HALF, access_grid
from scenewright.generator.layout.sampler import start_chain
from scenewright.generator.layout.state import State

PARAMS = LayoutParams()
BOARD = CatalogEntry(
    "whiteboard", "object", "whiteboard", size=(2.4, 2.0, 0.5), clearance=(("front", 0.8),)
)
DESK = CatalogEntry("student_desk", "object", "desk", size=(0.7, 0.72, 0.5), access=("back",))
TEACHER = CatalogEntry("teacher_desk", "object", "teacher's desk", size=(1.4, 0.76, 0.7))
CHAIR = CatalogEntry("chair", "object", "chair", size=(0.45, 0.9, 0.5))
ROW = CatalogEntry("row", "group", "row")


def classroom(desks: int = 4) -> tuple[SceneGraph, str, list[str]]:
    """A 7.5 x 7 room, door east: a board on the north wall, one row of ``desks`` desks
    facing it, a chair behind each."""
    room = Room.rectangle(7.5, 7).with_opening("door", "east", 1.4, 1.0)
    graph = SceneGraph(SceneParams(extent=room.extent, room=room, line_of_sight=True))
    board = graph.add_node(BOARD)
    graph.add_relation(board, "wall_1", "AgainstWall")
    row = graph.add_node(ROW)
    placed: list[str] = []
    for _ in range(desks):
        desk = graph.add_node(DESK, parent=row)
        graph.add_relation(desk, board, "FacingOpposite")
        if placed:
            graph.add_relation(desk, placed[-1], "NextToLeft")
            graph.add_relation(desk, placed[-1], "AlignedWith")
        chair = graph.add_node(CHAIR, parent=row)
        graph.add_relation(chair, desk, "NextToBehind")
        graph.add_relation(chair, desk, "FacingSameDirection")
        placed.append(desk)
    return graph, row, placed


def holds(problem, state, source: str, label: str) -> list[bool]:
    return [
        satisfied(term, evaluate(term, state, PARAMS), PARAMS)
        for term in problem.relations
        if term.source == source and term.label == label
    ]


@pytest.mark.parametrize("seed", [0, 1, 2, 3, 4])
def test_the_initial_placement_builds_a_row_whose_relations_all_hold(seed):
    graph, row, desks = classroom()
    problem = compile_problem(graph)
    energy, _ = start_chain(problem, PARAMS, np.random.default_rng(seed))
    inside = [
        term
        for term in problem.relations
        if term.a.kind == "object"
        and term.b.kind == "object"
        and problem.ids[term.b.index] != "whiteboard_1"
    ]
    assert len(inside) == 3 * 2 + 4 * 2  # NextToLeft and AlignedWith per later desk, two per chair
    broken = [
        f"{t.source} {t.label} {t.target}"
        for t in inside
        if not satisfied(t, evaluate(t, energy.state, PARAMS), PARAMS)
    ]
    assert not broken
    for desk in desks:  # every desk took its heading from the board before its place
        assert holds(problem, energy.state, desk, "FacingOpposite") == [True]


def placed_pair(offset: float, tilt: float):
    """Two desks of the row, the second beside the first (to its left, 10 cm apart) but
    ``offset`` metres forward and turned ``tilt`` radians."""
    graph, _, (first, second, *_) = classroom(2)
    problem = compile_problem(graph)
    state = State(problem)
    index = {box_id: box for box, box_id in enumerate(problem.ids)}
    a, b = index[second], index[first]
    state.set_pose(b, 0.0, 0.0, math.pi)
    hw = problem.half_width[a] + problem.half_width[b]
    state.set_pose(a, -(hw + 0.1), -offset, math.pi + tilt)  # facing north: its left is west (-x)
    return problem, state, a, b, second


def test_snap_aligned_lines_a_desk_up_where_it_stands_and_keeps_it_beside():
    problem, state, a, b, second = placed_pair(offset=0.07, tilt=math.radians(3.0))
    assert holds(problem, state, second, "AlignedWith") == [False]  # 7 cm out of line
    before = state.pose(a)
    mover = Mover(problem, state, np.random.default_rng(0), PARAMS)
    proposal = alignment.snap_aligned(mover, a, b)
    with state.trying(proposal):
        assert holds(problem, state, second, "AlignedWith") == [True]
        assert holds(problem, state, second, "NextToLeft") == [True]
        moved = math.hypot(state.x[a] - before[0], state.z[a] - before[1])
    assert moved == pytest.approx(0.07, abs=0.01)  # the smallest correction, not a new place


def test_snap_aligned_falls_back_to_a_new_place_when_a_lies_across_b():
    problem, state, a, b, second = placed_pair(offset=0.0, tilt=0.0)
    state.set_pose(a, 0.05, 0.0, math.pi + 0.3)  # on top of B: no single shift makes a face flush
    proposal = alignment.snap_aligned(Mover(problem, state, np.random.default_rng(0), PARAMS), a, b)
    with state.trying(proposal):
        assert holds(problem, state, second, "AlignedWith") == [True]


def placed_beside(graph: SceneGraph, *sources: str):
    """The problem, a fresh state and its mover, the source end of each of ``sources``'
    first relation, and the target of the first one's."""
    problem = compile_problem(graph)
    state = State(problem)
    mover = Mover(problem, state, np.random.default_rng(0), PARAMS)
    ends = {name: next(t.a for t in problem.relations if t.source == name) for name in sources}
    target = next(t.b for t in problem.relations if t.source == sources[0])
    return problem, state, mover, ends, target


def test_kept_free_only_when_what_stands_by_a_may_not_stand_in_the_space():
    room = Room.rectangle(7.5, 7).with_opening("door", "east", 1.4, 1.0)
    graph = SceneGraph(SceneParams(extent=room.extent, room=room))
    board = graph.add_node(BOARD)
    graph.add_relation(board, "wall_1", "AgainstWall")
    teacher = graph.add_node(TEACHER)
    graph.add_relation(teacher, board, "NextToFront")
    alone = graph.add_node(TEACHER)
    graph.add_relation(alone, board, "NextToFront")
    chair = graph.add_node(CHAIR)
    graph.add_relation(chair, teacher, "NextToBehind")
    problem, state, mover, ends, target = placed_beside(graph, teacher, alone)
    index = {box_id: box for box, box_id in enumerate(problem.ids)}
    assert target.index == index[board]
    # The board faces +z (yaw 0): its front is +z, where the kept space is.
    # Its chair would stand there: the space, and room for the chair (its shorter side) before it.
    assert next_to.kept_free(mover, ends[teacher], target, 0.0, 1.0) == pytest.approx(0.8 + 0.45)
    assert (
        next_to.kept_free(mover, ends[teacher], target, 1.0, 0.0) == 0.0
    )  # no space kept to the side
    assert (
        next_to.kept_free(mover, ends[alone], target, 0.0, 1.0) == 0.0
    )  # nothing of its own: it may stand there
    # The data-driven placement in front of the board leaves the space for the chair.
    for _ in range(20):
        proposal = mover.place_for_relation(
            next(t for t in problem.relations if t.source == teacher)
        )
        box = index[teacher]
        back = proposal[box][1] - problem.half_depth[box]
        assert back - (state.z[index[board]] + problem.half_depth[index[board]]) >= 0.8 + 0.45


def test_kept_free_leaves_a_way_to_the_only_side_a_box_is_used_from():
    """A chair placed behind a desk used from its back stands a way's width (two half
    corridors and a cell) off it; not beside it, not a flat box, not a chair at a desk
    wide enough to be reached past it, not in a room without a door, where nothing is
    reached from."""
    rug = CatalogEntry("rug", "object", "rug", size=(0.45, 0.01, 0.5))
    for door in (True, False):
        room = Room.rectangle(7.5, 7)
        room = room.with_opening("door", "east", 1.4, 1.0) if door else room
        graph = SceneGraph(SceneParams(extent=room.extent, room=room))
        desk = graph.add_node(DESK)
        chair = graph.add_node(CHAIR)
        graph.add_relation(chair, desk, "NextToBehind")
        mat = graph.add_node(rug)
        graph.add_relation(mat, desk, "NextToBehind")
        problem, state, mover, ends, target = placed_beside(graph, chair, mat)
        # The desk faces +z (yaw 0): its back is -z.
        way = 2 * CORRIDOR_HALF + access_grid(room).cell if door else 0.0
        assert next_to.kept_free(mover, ends[chair], target, 0.0, -1.0) == pytest.approx(way)
        assert next_to.kept_free(mover, ends[chair], target, 1.0, 0.0) == 0.0
        assert next_to.kept_free(mover, ends[mat], target, 0.0, -1.0) == 0.0
        wide = graph.add_node(
            CatalogEntry("desk", "object", "desk", size=(1.2, 0.75, 0.6), access=("back",))
        )
        graph.add_relation(graph.add_node(CHAIR), wide, "NextToBehind")
        problem_wide, _, mover_wide, ends_wide, target_wide = placed_beside(
            graph, graph.nodes()[-1].id
        )
        # A chair at a 1.2 m desk leaves its ends free: no way kept behind it.
        assert (
            next_to.kept_free(mover_wide, ends_wide[graph.nodes()[-1].id], target_wide, 0.0, -1.0)
            == 0.0
        )
        if door:  # every placement behind the desk leaves the way
            term = next(t for t in problem.relations if t.source == chair)
            for _ in range(20):
                proposal = mover.place_for_relation(term)
                gap = (state.z[target.index] - problem.half_depth[target.index]) - (
                    proposal[ends[chair].index][1] + problem.half_depth[ends[chair].index]
                )
                assert gap >= way


def test_heading_only_facings_tie_no_cluster_in_a_room():
    graph, _, desks = classroom(3)
    problem = compile_problem(graph)
    mover = Mover(problem, State(problem), np.random.default_rng(0), PARAMS)
    board = problem.ids.index("whiteboard_1")
    assert all(board not in cluster for cluster in mover.clusters)


def test_rect_distance_of_square_rectangles_matches_the_corner_walk():
    rng = np.random.default_rng(5)
    apart = 0
    for _ in range(2000):
        yaw_a = float(rng.choice([0.0, math.pi / 2, math.pi, 0.4]))
        yaw_b = yaw_a + float(rng.choice([0.0, math.pi / 2, math.pi, -math.pi / 2]))
        a = Rect(
            *rng.uniform(-2, 2, 2), *rng.uniform(0.1, 1.0, 2), math.cos(yaw_a), math.sin(yaw_a)
        )
        b = Rect(
            *rng.uniform(-2, 2, 2), *rng.uniform(0.1, 1.0, 2), math.cos(yaw_b), math.sin(yaw_b)
        )
        walk = 0.0  # the general way: separating axes, then the nearest corner of either
        if rect_overlap(a, b) < 0.0:
            walk = min(
                [point_rect_distance(x, z, b) for x, z in corners(a)]
                + [point_rect_distance(x, z, a) for x, z in corners(b)]
            )
            apart += 1
        assert rect_distance(a, b) == pytest.approx(walk, abs=1e-12)
    assert 500 < apart < 2000  # both cases were met


def test_a_row_across_the_wall_is_pushed_off_it_with_the_row_it_hangs_on():
    """Two rows, the second south of the first, the first so far south that the second
    crosses the south wall: ``_push_off_walls`` shifts both north together, by as far as
    it crosses, and the energy falls."""
    room = Room.rectangle(7.5, 7).with_opening("door", "east", 1.4, 1.0)
    graph = SceneGraph(SceneParams(extent=room.extent, room=room))
    rows = []
    for _ in range(2):
        row = graph.add_node(ROW)
        desks = [graph.add_node(DESK, parent=row) for _ in range(2)]
        graph.add_relation(desks[1], desks[0], "NextToLeft")
        rows.append((row, desks))
    graph.add_relation(rows[1][0], rows[0][0], "NextToSouth")
    problem = compile_problem(graph)
    state = State(problem)
    index = {box_id: box for box, box_id in enumerate(problem.ids)}
    for (_, desks), z in zip(rows, (2.4, 3.4), strict=False):  # the room runs from z -3.5 to 3.5
        for k, desk in enumerate(desks):
            state.set_pose(index[desk], 1.0 - 0.8 * k, z, 0.0)
    energy = Energy(problem, state, PARAMS)
    energy.activate(list(range(problem.n_boxes)))
    mover = Mover(problem, state, np.random.default_rng(0), PARAMS)
    group = problem.group_ids.index(rows[1][0])
    anchors = [t for t in problem.relations if t.a.kind == "group" and t.a.index == group]
    before, poses = energy.total, [state.pose(b) for b in range(problem.n_boxes)]
    assert max(energy.room.wall_excess(b) for b in range(problem.n_boxes)) > 0.1
    _push_off_walls(energy, mover, group, anchors)
    assert max(energy.room.wall_excess(b) for b in range(problem.n_boxes)) == 0.0
    assert energy.total < before
    shifts = {
        (round(state.x[b] - poses[b][0], 9), round(state.z[b] - poses[b][1], 9))
        for b in range(problem.n_boxes)
    }
    assert len(shifts) == 1 and next(iter(shifts))[1] < 0.0  # all together, north


def test_faces_as_asked_only_when_the_heading_is_already_the_one_asked_for():
    """The constructive placement makes no turn proposal for a desk already facing
    opposite to the board (it would leave it where it is); it does for one turned."""
    graph, _, desks = classroom(1)
    problem = compile_problem(graph)
    state = State(problem)
    mover = Mover(problem, state, np.random.default_rng(0), PARAMS)
    index = {box_id: box for box, box_id in enumerate(problem.ids)}
    opposite = next(
        t for t in problem.relations if t.source == desks[0] and t.label == "FacingOpposite"
    )
    same = next(
        t for t in problem.relations if t.label == "FacingSameDirection"
    )  # the chair and its desk
    state.set_pose(index["whiteboard_1"], 0.0, -3.0, 0.0)
    state.set_pose(index[desks[0]], 0.0, 0.0, -math.pi)
    assert facing.faces_as_asked(mover, opposite)
    state.set_pose(
        index[desks[0]], 0.0, 0.0, math.pi
    )  # the same heading, the other end of the range
    assert facing.faces_as_asked(mover, opposite)
    state.set_pose(index[desks[0]], 0.0, 0.0, math.pi / 2.0)
    assert not facing.faces_as_asked(mover, opposite)
    state.set_pose(same.a.index, 0.0, 1.0, math.pi / 2.0 + 1e-6)
    assert not facing.faces_as_asked(mover, same)
    state.set_pose(same.a.index, 0.0, 1.0, math.pi / 2.0)
    assert facing.faces_as_asked(mover, same)


def test_best_of_skips_reachability_only_for_candidates_that_cannot_win():
    """``_best_of`` in a room leaves out the access part of a candidate whose other parts,
    less all the access part there is, already do not beat the best so far: the same
    picks, on the same draws, as evaluating every candidate whole."""
    problem = compile_problem(expand(load_rules("classroom"), 2))
    chains = [start_chain(problem, PARAMS, np.random.default_rng(2)) for _ in range(2)]
    whole_energy = chains[1][0]
    whole_energy.access_floor = lambda: math.inf  # no candidate can be ruled out early
    evaluated = []
    for k, (energy, mover) in enumerate(chains):
        original = energy.room._access_changes
        energy.room._access_changes = lambda boxes, k=k, original=original: (
            evaluated.append(k) or original(boxes)
        )
        mover.rng = np.random.default_rng(9)
        for _ in range(12):
            _best_of(energy, lambda energy=energy, mover=mover: mover.propose(energy.relation), 8)
    (first, _), (second, _) = chains
    assert [first.state.pose(b) for b in range(problem.n_boxes)] == [
        second.state.pose(b) for b in range(problem.n_boxes)
    ]
    assert first.total == second.total
    assert evaluated.count(0) < evaluated.count(1)  # some candidates were ruled out without it
