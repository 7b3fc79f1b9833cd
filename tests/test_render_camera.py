"""Automatic cameras (pure numpy): framing, projection, north up."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays
from render_fixtures import market_scene

from scenewright.render.camera import (
    FILL,
    Camera,
    frame_scene,
    perspective_camera,
    scene_points,
    top_down_camera,
)

coordinates = st.floats(-50, 50, allow_nan=False)
point_clouds = arrays(
    np.float64, st.tuples(st.integers(1, 30), st.just(3)), elements=coordinates
).map(
    lambda p: p * [1.0, 0.2, 1.0] + [0.0, 10.0, 0.0]  # heights 0..20 m, like a scene's
)


image_sizes = st.sampled_from([(640, 480), (320, 320), (200, 400)])


def framing_reach(camera: Camera, points: np.ndarray) -> float:
    """How far out the points land, as a fraction of the half-image (1 = the edge),
    after checking they all lie between the clipping planes."""
    pixels, depth = camera.project(points)
    assert np.all(depth >= camera.znear) and np.all(depth <= camera.zfar)
    half = np.array([camera.width, camera.height]) / 2
    return float((np.abs(pixels - half) / half).max())


@settings(max_examples=60, deadline=None)
@given(point_clouds, image_sizes)
def test_perspective_camera_frames_every_point_tightly(points, size):
    reach = framing_reach(perspective_camera(points, *size), points)
    assert reach <= FILL + 1e-6
    if np.ptp(points, axis=0).max() > 5.0:  # a real spread: some point touches the margin
        assert reach >= FILL - 1e-6


@settings(max_examples=60, deadline=None)
@given(point_clouds, image_sizes)
def test_top_camera_frames_every_point_with_north_up(points, size):
    camera = top_down_camera(points, *size)
    assert framing_reach(camera, points) <= FILL + 1e-6
    north, south, east = camera.project([[0, 0, -1.0], [0, 0, 1.0], [1.0, 0, 0]])[0]
    assert north[1] < south[1] and east[0] > north[0]


def test_perspective_view_looks_down_from_the_south_east():
    camera = frame_scene(market_scene(), "perspective")
    centre = scene_points(market_scene()).mean(axis=0)
    offset = camera.pose[:3, 3] - centre
    assert offset[0] > 0 and offset[2] > 0 and offset[1] > 0  # east, south, above
    forward = -camera.pose[:3, 2]
    assert math.degrees(math.asin(-forward[1])) == pytest.approx(35.0)


def test_intrinsics_and_projection_agree():
    camera = frame_scene(market_scene(), "perspective", 320, 240)
    point = np.array([1.0, 0.5, -2.0])
    (pixel,), (depth,) = camera.project(point)
    x, y, z = (camera.extrinsics() @ np.append(point, 1.0))[:3]
    assert depth == pytest.approx(-z)
    assert np.allclose((camera.intrinsics() @ [x / depth, y / depth, 1.0])[:2], pixel)


def test_camera_survives_its_dictionary_form():
    for view in ("perspective", "top"):
        camera = frame_scene(market_scene(), view)
        again = Camera.from_dict(camera.to_dict())
        points = scene_points(market_scene())
        assert np.allclose(again.project(points)[0], camera.project(points)[0])
