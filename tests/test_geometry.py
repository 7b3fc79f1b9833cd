"""Planar geometry: angle wrapping, segments, edge normals, SAT penetration, exact
distances, buffered paths."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from scenewright.core.geometry import (
    capsule_rect_penetration,
    corners,
    left_normal,
    make_rect,
    nearest_on_polyline,
    nearest_on_segment,
    point_segment_distance,
    polyline_length,
    polyline_rect_penetration,
    polyline_rects_distance,
    polyline_turns,
    rect_distance,
    rect_penetration,
    segment_distance,
    segment_rect_distance,
    turn_angle,
    wrap_angle,
    wrap_angles,
)
from scenewright.core.scene import SceneObject, object_corners

coordinate = st.floats(-10, 10, allow_nan=False)
extent = st.floats(0.1, 4, allow_nan=False)
angle = st.floats(-math.pi, math.pi, allow_nan=False)
rects = st.tuples(coordinate, coordinate, extent, extent, angle)


def moved(rect_args, turn, dx, dz):
    """The same rectangle after the whole plane turns by ``turn`` about 0 and shifts."""
    x, z, w, d, yaw = rect_args
    c, s = math.cos(turn), math.sin(turn)
    return make_rect(x * c + z * s + dx, -x * s + z * c + dz, w, d, yaw + turn)


def boundary_samples(rect, count=60):
    points = corners(rect) + corners(rect)[:1]
    samples = []
    for (ax, az), (bx, bz) in zip(points, points[1:], strict=False):
        for t in np.linspace(0.0, 1.0, count):
            samples.append((ax + t * (bx - ax), az + t * (bz - az)))
    return np.array(samples)


def test_corners_match_the_scene_convention():
    obj = SceneObject(
        "a", "t", "object", "a", None, None, None, [1.0, 0.0, 2.0], 0.7, [2.0, 1.0, 1.0]
    )
    mine = sorted(corners(make_rect(1.0, 2.0, 2.0, 1.0, 0.7)))
    theirs = sorted(map(tuple, object_corners([obj])[0]))
    assert np.allclose(mine, theirs)


def test_axis_aligned_overlap_and_gap():
    a = make_rect(0.0, 0.0, 2.0, 2.0, 0.0)
    assert rect_penetration(a, make_rect(1.5, 0.0, 2.0, 2.0, 0.0)) == pytest.approx(0.5)
    assert rect_distance(a, make_rect(3.0, 0.0, 2.0, 2.0, 0.0)) == pytest.approx(1.0)
    assert rect_distance(a, make_rect(3.0, 3.0, 2.0, 2.0, 0.0)) == pytest.approx(math.sqrt(2.0))


def test_rotated_square_corner_reaches_in():
    a = make_rect(0.0, 0.0, 2.0, 2.0, 0.0)
    diamond = make_rect(1.0 + math.sqrt(2.0) - 0.25, 0.0, 2.0, 2.0, math.pi / 4)
    assert rect_penetration(a, diamond) == pytest.approx(0.25)
    far = make_rect(1.0 + math.sqrt(2.0) + 0.5, 0.0, 2.0, 2.0, math.pi / 4)
    assert rect_penetration(a, far) == 0.0
    assert rect_distance(a, far) == pytest.approx(0.5)


@given(rects, rects)
def test_penetration_and_distance_are_symmetric(first, second):
    a, b = make_rect(*first), make_rect(*second)
    assert rect_penetration(a, b) == pytest.approx(rect_penetration(b, a), abs=1e-9)
    assert rect_distance(a, b) == pytest.approx(rect_distance(b, a), abs=1e-9)
    assert rect_penetration(a, b) == 0.0 or rect_distance(a, b) == 0.0


@given(rects, rects, angle, coordinate, coordinate)
def test_invariant_under_joint_rotation_and_translation(first, second, turn, dx, dz):
    a, b = make_rect(*first), make_rect(*second)
    a2, b2 = moved(first, turn, dx, dz), moved(second, turn, dx, dz)
    assert rect_penetration(a2, b2) == pytest.approx(rect_penetration(a, b), abs=1e-7)
    assert rect_distance(a2, b2) == pytest.approx(rect_distance(a, b), abs=1e-7)


@given(rects, st.floats(0.01, 5), angle)
def test_zero_penetration_when_separated(first, gap, direction):
    a = make_rect(*first)
    radius = math.hypot(first[2], first[3]) / 2
    x = first[0] + math.sin(direction) * (2 * radius + gap)
    z = first[1] + math.cos(direction) * (2 * radius + gap)
    b = make_rect(x, z, first[2], first[3], first[4] + 0.3)
    assert rect_penetration(a, b) == 0.0
    assert rect_distance(a, b) >= gap - 1e-9


@settings(max_examples=40)
@given(rects, rects)
def test_distance_matches_dense_boundary_sampling(first, second):
    a, b = make_rect(*first), make_rect(*second)
    exact = rect_distance(a, b)
    if exact == 0.0:
        return
    pa, pb = boundary_samples(a), boundary_samples(b)
    sampled = np.min(np.hypot(pa[:, None, 0] - pb[None, :, 0], pa[:, None, 1] - pb[None, :, 1]))
    step = max(first[2], first[3], second[2], second[3]) / 59
    assert exact <= sampled + 1e-9
    assert sampled <= exact + step


@settings(max_examples=40)
@given(coordinate, coordinate, coordinate, coordinate, rects)
def test_segment_distance_matches_sampling(ax, az, bx, bz, rect_args):
    rect = make_rect(*rect_args)
    exact = segment_rect_distance(ax, az, bx, bz, rect)
    ts = np.linspace(0, 1, 400)
    seg = np.stack([ax + ts * (bx - ax), az + ts * (bz - az)], axis=1)
    c, s = rect.c, rect.s
    dx, dz = seg[:, 0] - rect.cx, seg[:, 1] - rect.cz
    lx, lz = dx * c - dz * s, dx * s + dz * c
    outside = np.hypot(np.maximum(np.abs(lx) - rect.hw, 0), np.maximum(np.abs(lz) - rect.hd, 0))
    length = math.hypot(bx - ax, bz - az)
    assert exact <= outside.min() + 1e-9
    assert outside.min() <= exact + length / 399 + 1e-9


def test_capsule_penetration_grows_continuously_through_the_centre_line():
    depths = [
        capsule_rect_penetration(-5.0, 0.0, 5.0, 0.0, 1.5, make_rect(0.0, z, 1.0, 1.0, 0.0))
        for z in (3.0, 2.0, 1.5, 1.0, 0.5, 0.0)
    ]
    assert depths == pytest.approx([0.0, 0.0, 0.5, 1.0, 1.5, 2.0])
    assert depths == sorted(depths)


def test_polyline_takes_the_worst_segment_and_the_nearest_point():
    road = [[0.0, 0.0], [10.0, 0.0], [10.0, 10.0]]
    beside = make_rect(11.0, 5.0, 1.0, 1.0, 0.0)
    assert polyline_rect_penetration(road, 1.5, beside) == pytest.approx(1.0)
    assert polyline_rects_distance(road, [beside]) == pytest.approx(0.5)
    across = make_rect(10.2, 5.0, 1.0, 1.0, 0.0)  # pushed out east: 0.3 past the line + 1.5
    assert polyline_rect_penetration(road, 1.5, across) == pytest.approx(1.8)
    assert polyline_rects_distance(road, [across]) == 0.0
    far = make_rect(5.0, 5.0, 1.0, 1.0, 0.0)
    assert polyline_rects_distance(road, [far]) == pytest.approx(4.5)
    distance, x, z, segment = nearest_on_polyline(road, 5.0, -2.0)
    assert (distance, x, z, segment) == pytest.approx((2.0, 5.0, 0.0, 0))


def test_segments_and_turns():
    assert segment_distance((0, 0), (2, 2), (0, 2), (2, 0)) == 0.0
    assert segment_distance((0, 0), (1, 0), (0, 1), (1, 1)) == pytest.approx(1.0)
    assert turn_angle((0, 0), (1, 0), (2, 0)) == pytest.approx(0.0)
    assert turn_angle((0, 0), (1, 0), (1, 1)) == pytest.approx(math.pi / 2)
    road = [[0.0, 0.0], [3.0, 4.0], [3.0, 10.0], [-3.0, 10.0]]
    assert polyline_length(road) == pytest.approx(5.0 + 6.0 + 6.0)
    assert polyline_turns(road) == pytest.approx([math.atan2(3.0, 4.0), math.pi / 2])
    assert polyline_turns(road[:2]) == []


@settings(max_examples=40)
@given(
    st.lists(st.tuples(coordinate, coordinate), min_size=2, max_size=5),
    st.lists(rects, min_size=1, max_size=4),
)
def test_polyline_to_several_rects_is_the_exhaustive_minimum(points, rect_args):
    shapes = [make_rect(*args) for args in rect_args]
    exhaustive = min(
        segment_rect_distance(*points[i], *points[i + 1], rect)
        for rect in shapes
        for i in range(len(points) - 1)
    )
    assert polyline_rects_distance([list(p) for p in points], shapes) == exhaustive


@given(st.floats(-50, 50, allow_nan=False))
def test_a_wrapped_angle_points_the_same_way_within_one_turn(value):
    wrapped = wrap_angle(value)
    assert -math.pi <= wrapped <= math.pi
    assert math.cos(wrapped) == pytest.approx(math.cos(value), abs=1e-9)
    assert math.sin(wrapped) == pytest.approx(math.sin(value), abs=1e-9)
    assert wrap_angles(np.array([value]))[0] == pytest.approx(wrapped, abs=1e-9)


def test_wrapping_keeps_both_ends_as_atan2_gives_them():
    assert wrap_angle(math.pi) == math.pi
    assert wrap_angle(-math.pi) == -math.pi


@given(coordinate, coordinate, coordinate, coordinate, coordinate, coordinate)
def test_point_segment_distance_is_the_distance_to_its_nearest_point(px, pz, ax, az, bx, bz):
    expected = nearest_on_segment(px, pz, ax, az, bx, bz)[0]
    assert point_segment_distance(px, pz, ax, az, bx, bz) == pytest.approx(expected, abs=1e-9)


def test_left_normal_turns_a_quarter_counter_clockwise_without_negative_zeros():
    assert left_normal(0.0, 0.0, 2.0, 0.0) == (0.0, 1.0)
    assert math.copysign(1.0, left_normal(0.0, 0.0, 2.0, 0.0)[0]) == 1.0
    assert left_normal(0.0, 0.0, 0.0, 3.0) == (-1.0, 0.0)
    assert left_normal(1.0, 1.0, 1.0, 1.0) is None
