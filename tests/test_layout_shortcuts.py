"""The layout's shortcuts for speed give what the long way gives, number for number.

The grid's ``move`` against ``remove`` then ``insert``, the path index against testing
every path, the relation measures ``Energy`` keeps against measuring anew, the overlap
report's bounding-circle skip against measuring every pair,
``polyline_rects_distance`` against sorting every bound, ``rect_distance`` against
``point_rect_distance`` from every corner, the segment-to-box distances against their
step-by-step form, ``polyline_rect_penetration``'s skip by a lower bound against testing
every segment, ``rect_overlap`` and ``rect_distance`` (square) against their forms by field names, and ``moves.uniform`` and ``moves.draw_index`` against the numpy
calls they stand for.
"""

import math
import random

import numpy as np
import pytest

from scenewright.core.geometry import (
    _local_overlap,
    capsule_rect_penetration,
    corners,
    make_rect,
    nearest_on_segment,
    point_rect_distance,
    polyline_rect_penetration,
    polyline_rects_distance,
    rect_distance,
    rect_overlap,
    segment_rect_distance,
    to_local,
)
from scenewright.generator.layout import LayoutParams
from scenewright.generator.layout.energy import PATH_GRID_MIN, Energy
from scenewright.generator.layout.families import evaluate
from scenewright.generator.layout.motion import draw_index, uniform
from scenewright.generator.layout.problem import compile_problem
from scenewright.generator.layout.report import OVERLAP_TOLERANCE, _overlaps, assess
from scenewright.generator.layout.sampler import start_chain
from scenewright.generator.layout.state import Grid
from scenewright.generator.layout.synthetic import village_graph


def test_uniform_draws_what_generator_uniform_draws_and_leaves_the_stream_alike():
    ours, numpys, ranges = (
        np.random.default_rng(5),
        np.random.default_rng(5),
        np.random.default_rng(6),
    )
    edges = [0.0, -0.0, 5e-324, 1e-300, 0.05, 0.8, 1.0, math.pi, 1e300]
    for k in range(20_000):
        if k % 3 == 0:
            low, high = sorted(
                (float(ranges.choice(edges)) * ranges.choice([-1, 1]), float(ranges.choice(edges)))
            )
        else:
            low, high = sorted(
                float(v) for v in ranges.normal(0.0, 10.0 ** int(ranges.integers(-4, 5)), 2)
            )
        if math.copysign(1.0, high - low) < 0.0:  # 0.0 to -0.0: refused (the test below)
            continue
        if k % 5 == 0:  # other draws between, as the moves make them
            assert ours.integers(7) == numpys.integers(7)
        drawn, expected = uniform(ours, low, high), numpys.uniform(low, high)
        assert drawn == expected and math.copysign(1.0, drawn) == math.copysign(1.0, expected)
    assert ours.random() == numpys.random()


def test_draw_index_draws_what_generator_integers_draws_and_leaves_the_stream_alike():
    ours, numpys, counts = np.random.default_rng(7), np.random.default_rng(7), random.Random(7)
    for _ in range(5000):
        count = counts.choice([1, 1, 1, 2, 3, 4, 7, 1000])
        assert draw_index(ours, count) == int(numpys.integers(count))
        if counts.random() < 0.3:
            assert ours.random() == numpys.random()
    assert ours.bit_generator.state == numpys.bit_generator.state
    with pytest.raises(ValueError):
        draw_index(ours, 0)


@pytest.mark.parametrize("low, high", [(1.0, 0.0), (0.0, -0.0), (-1e308, 1e308)])
def test_uniform_refuses_what_generator_uniform_refuses(low, high):
    with pytest.raises((ValueError, OverflowError)) as numpys:
        np.random.default_rng(0).uniform(low, high)
    with pytest.raises(numpys.type):
        uniform(np.random.default_rng(0), low, high)


def test_grid_move_leaves_the_cells_as_remove_then_insert_does():
    rng = random.Random(3)
    moved, plain = Grid(0.5), Grid(0.5)
    where = {}
    for box in range(40):
        x, z, radius = rng.uniform(-20, 20), rng.uniform(-20, 20), rng.choice([0.1, 0.4, 1.5, 30.0])
        moved.insert(box, x, z, radius)
        plain.insert(box, x, z, radius)
        where[box] = (x, z, radius)
    for _step in range(400):
        box = rng.randrange(40)
        x, z, radius = where[box]
        before = moved.filing(box)
        new = (x + rng.gauss(0.0, rng.choice([0.01, 0.3, 5.0])), z + rng.gauss(0.0, 0.3), radius)
        moved.move(box, *new)
        plain.remove(box)
        plain.insert(box, *new)
        if rng.random() < 0.5:  # rejected: back where it was filed
            moved.move(box, x, z, radius, before)
            plain.remove(box)
            plain.insert(box, x, z, radius)
        else:
            where[box] = new
        assert moved.keys[box] == plain.keys[box] and moved.large == plain.large
        assert all(
            moved.cells[key] == plain.cells[key] for key in plain.keys[box]
        )  # same order too
    assert moved.cells == plain.cells and moved.keys == plain.keys
    # Neighbours in the same order as well: the energy sums over them in that order.
    assert [list(moved.near_box(b)) for b in range(40)] == [
        list(plain.near_box(b)) for b in range(40)
    ]


def chain(seed: int, size: int):
    return start_chain(
        compile_problem(village_graph(size, seed)), LayoutParams(), np.random.default_rng(seed)
    )


def random_walk(energy: Energy, mover, steps: int, reject_every: int):
    """The mover's proposals, each kept but every ``reject_every``-th; yields the step
    number after each."""
    for step in range(steps):
        proposal = mover.propose(energy.relation)
        if proposal is None:
            continue
        energy.propose(*proposal)
        energy.reject() if step % reject_every == 0 else energy.accept()
        yield step


def test_the_path_index_finds_every_path_a_box_may_touch_as_the_energy_moves():
    energy, mover = chain(1, 220)
    problem = energy.problem
    assert energy.path_grid is not None and problem.n_paths >= PATH_GRID_MIN
    for step in random_walk(energy, mover, 300, reject_every=3):
        if step % 25 == 0:
            for box in range(problem.n_boxes):
                every = [
                    path for path in range(problem.n_paths) if energy.may_touch_path(box, path)
                ]
                assert energy.paths_near(box) == every
            hit = [
                {path for path, hits in enumerate(energy.path_hits) if box in hits}
                for box in range(problem.n_boxes)
            ]
            assert energy.hit_paths == hit
    parts = energy.full()
    assert energy.parts["paths"] == pytest.approx(parts["paths"], abs=1e-9)


def test_the_measures_the_energy_keeps_are_those_measured_anew():
    energy, mover = chain(3, 60)
    problem, state, params = energy.problem, energy.state, energy.params
    kept = 0
    for step in random_walk(energy, mover, 400, reject_every=2):
        if step % 40 == 0:
            kept += len(energy.measures)
            for term, measure in energy.measures.items():
                assert measure == evaluate(problem.relations[term], state, params)
            assert assess(energy) == assess(fresh_copy(energy))
    assert kept > 0


def fresh_copy(energy: Energy) -> Energy:
    """An energy over the same poses and paths that has measured nothing yet."""
    copy = Energy(energy.problem, energy.state, energy.params)
    copy.activate([box for box in range(energy.problem.n_boxes) if energy.active[box]])
    return copy


def test_the_overlap_report_skips_no_pair_that_overlaps():
    energy, _ = chain(2, 120)
    problem, state, rng = energy.problem, energy.state, random.Random(2)
    for box in range(0, problem.n_boxes, 3):  # onto another box, partly
        other = rng.randrange(problem.n_boxes)
        pose = (
            state.x[other] + rng.uniform(-2.0, 2.0),
            state.z[other] + rng.uniform(-2.0, 2.0),
            rng.uniform(-3.0, 3.0),
        )
        energy.propose({box: pose}, {})
        energy.accept()
    every = []
    for box in range(problem.n_boxes):
        for other in range(box + 1, problem.n_boxes):
            depth = energy.pair_penetration(box, other)
            if depth > OVERLAP_TOLERANCE:
                every.append(
                    f"{problem.ids[box]} overlaps {problem.ids[other]} by {100 * depth:.0f} cm"
                )
    reported = [
        line
        for line in _overlaps(energy)
        if not any(path_id in line for path_id in problem.path_ids)
    ]
    assert every and reported == every


def sorting_every_bound(points: list, rects: list) -> float:
    """``polyline_rects_distance`` as it was: every (rectangle, segment) bound sorted."""
    radii = [math.hypot(rect.hw, rect.hd) for rect in rects]
    bounds = sorted(
        (nearest_on_segment(rect.cx, rect.cz, *points[i], *points[i + 1])[0] - radii[k], k, i)
        for k, rect in enumerate(rects)
        for i in range(len(points) - 1)
    )
    best = math.inf
    for bound, k, i in bounds:
        if bound >= best:
            break
        (ax, az), (bx, bz) = points[i], points[i + 1]
        best = min(best, segment_rect_distance(ax, az, bx, bz, rects[k]))
    return best


def test_polyline_rects_distance_is_the_sorted_search_to_the_last_bit():
    rng = random.Random(8)
    for _ in range(3000):
        points = [[rng.uniform(-20, 20), rng.uniform(-20, 20)] for _ in range(rng.randint(1, 5))]
        if rng.random() < 0.1:
            points.append(list(points[-1]))  # a segment of length 0
        rects = [
            make_rect(
                rng.uniform(-25, 25),
                rng.uniform(-25, 25),
                rng.uniform(0.1, 8),
                rng.uniform(0.1, 8),
                rng.uniform(-4, 4),
            )
            for _ in range(rng.randint(0, 5))
        ]
        assert polyline_rects_distance(points, rects) == sorting_every_bound(points, rects)


def test_rect_distance_is_the_least_corner_distance_to_the_last_bit():
    rng = random.Random(9)
    for _ in range(5000):
        a, b = (
            make_rect(
                rng.uniform(-6, 6),
                rng.uniform(-6, 6),
                rng.uniform(0.1, 5),
                rng.uniform(0.1, 5),
                rng.uniform(-4, 4),
            )
            for _ in range(2)
        )
        expected = min(
            [point_rect_distance(px, pz, b) for px, pz in corners(a)]
            + [point_rect_distance(px, pz, a) for px, pz in corners(b)]
        )
        if (
            rect_overlap(a, b) < 0.0
            and abs(a.c * b.s - a.s * b.c) > 1e-6
            and abs(a.c * b.c + a.s * b.s) > 1e-6
        ):
            assert rect_distance(a, b) == expected


def step_by_step_distance(ax, az, bx, bz, hw, hd):
    """``geometry._local_distance`` as it was, a call per corner."""

    def point_segment(px, pz, ex, ez, length2):
        t = 0.0 if length2 <= 0.0 else ((px - ax) * ex + (pz - az) * ez) / length2
        t = 0.0 if t < 0.0 else (1.0 if t > 1.0 else t)
        return math.hypot(px - ax - t * ex, pz - az - t * ez)

    best = min(
        math.hypot(max(abs(ax) - hw, 0.0), max(abs(az) - hd, 0.0)),
        math.hypot(max(abs(bx) - hw, 0.0), max(abs(bz) - hd, 0.0)),
    )
    ex, ez = bx - ax, bz - az
    for px, pz in ((hw, hd), (-hw, hd), (hw, -hd), (-hw, -hd)):
        best = min(best, point_segment(px, pz, ex, ez, ex * ex + ez * ez))
    return best


def test_segment_to_box_distances_are_the_step_by_step_ones_to_the_last_bit():
    rng = random.Random(10)
    for _ in range(5000):
        rect = make_rect(
            rng.uniform(-5, 5),
            rng.uniform(-5, 5),
            rng.uniform(0.1, 6),
            rng.uniform(0.1, 6),
            rng.uniform(-4, 4),
        )
        ax, az = rng.uniform(-9, 9), rng.uniform(-9, 9)
        bx, bz = (ax, az) if rng.random() < 0.05 else (rng.uniform(-9, 9), rng.uniform(-9, 9))
        (lax, laz), (lbx, lbz) = to_local(rect, ax, az), to_local(rect, bx, bz)
        overlap = _local_overlap(lax, laz, lbx, lbz, rect.hw, rect.hd)
        gap = step_by_step_distance(lax, laz, lbx, lbz, rect.hw, rect.hd)
        assert segment_rect_distance(ax, az, bx, bz, rect) == (0.0 if overlap >= 0.0 else gap)
        deepest = 1.5 + overlap if overlap >= 0.0 else (1.5 - gap if gap < 1.5 else 0.0)
        assert capsule_rect_penetration(ax, az, bx, bz, 1.5, rect) == deepest


def test_polyline_rect_penetration_skips_no_segment_that_reaches_the_rectangle():
    # Random polylines, and segments square to the line from a rectangle's centre to
    # one of its corners whose gap to that corner is the buffer give or take a hair
    # (where the bound is tightest), near the origin and 10 km from it.
    rng = random.Random(11)
    for case in range(6000):
        offset = 0.0 if case % 2 else 1.0e4
        rect = make_rect(
            offset + rng.uniform(-5, 5),
            rng.uniform(-5, 5),
            rng.uniform(0.1, 6),
            rng.uniform(0.1, 6),
            rng.uniform(-4, 4),
        )
        radius = rng.uniform(0.05, 3.0)
        if case % 3:
            points = [
                [offset + rng.uniform(-15, 15), rng.uniform(-15, 15)]
                for _ in range(rng.randint(2, 6))
            ]
        else:
            (cx, cz), (px, pz) = (rect.cx, rect.cz), corners(rect)[rng.randrange(4)]
            circumradius = math.hypot(rect.hw, rect.hd)
            ux, uz = (px - cx) / circumradius, (pz - cz) / circumradius
            hair = rng.choice([0.0, 1e-15, -1e-15, 1e-12, -1e-12, 1e-9, 1e-6, 1e-3]) * (
                1.0 + offset
            )
            reach = circumradius + radius + hair
            mx, mz, half = cx + ux * reach, cz + uz * reach, rng.uniform(0.0, 4.0)
            points = [[mx - uz * half, mz + ux * half], [mx + uz * half, mz - ux * half]]
        every_segment = max(
            [0.0]
            + [
                capsule_rect_penetration(*points[i], *points[i + 1], radius, rect)
                for i in range(len(points) - 1)
            ]
        )
        assert polyline_rect_penetration(points, radius, rect) == every_segment


def test_rect_overlap_is_its_form_by_field_names_to_the_last_bit():
    rng = random.Random(12)
    for _ in range(5000):
        a, b = (
            make_rect(
                rng.uniform(-6, 6),
                rng.uniform(-6, 6),
                rng.uniform(0.1, 5),
                rng.uniform(0.1, 5),
                rng.choice([0.0, rng.uniform(-4, 4)]),
            )
            for _ in range(2)
        )
        dx, dz = b.cx - a.cx, b.cz - a.cz
        k1, k2 = abs(a.c * b.c + a.s * b.s), abs(a.c * b.s - a.s * b.c)
        expected = min(
            a.hw + b.hw * k1 + b.hd * k2 - abs(dx * a.c - dz * a.s),
            a.hd + b.hw * k2 + b.hd * k1 - abs(dx * a.s + dz * a.c),
            b.hw + a.hw * k1 + a.hd * k2 - abs(dx * b.c - dz * b.s),
            b.hd + a.hw * k2 + a.hd * k1 - abs(dx * b.s + dz * b.c),
        )
        assert rect_overlap(a, b) == expected


def test_rect_distance_between_square_rectangles_is_its_form_by_field_names_to_the_last_bit():
    rng = random.Random(13)
    for _ in range(5000):
        a, b = (
            make_rect(
                rng.uniform(-6, 6),
                rng.uniform(-6, 6),
                rng.uniform(0.1, 5),
                rng.uniform(0.1, 5),
                rng.randrange(4) * math.pi / 2,
            )
            for _ in range(2)
        )
        k2 = a.c * b.s - a.s * b.c
        bw, bd = (b.hw, b.hd) if abs(k2) < 1e-9 else (b.hd, b.hw)
        dx, dz = b.cx - a.cx, b.cz - a.cz
        gx = abs(dx * a.c - dz * a.s) - a.hw - bw
        gz = abs(dx * a.s + dz * a.c) - a.hd - bd
        expected = 0.0 if gx <= 0.0 and gz <= 0.0 else math.hypot(max(gx, 0.0), max(gz, 0.0))
        assert rect_distance(a, b) == expected
