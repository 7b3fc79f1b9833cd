"""Exact depth, surface normals and 3D ground truth of a render."""

import io
import json

import numpy as np
import pytest
from PIL import Image
from render_fixtures import market_scene, renderer_or_skip, scene_of, thing

from scenewright.render.camera import Camera
from scenewright.render.ground_truth import BOX_CORNERS, GL_TO_CV
from scenewright.render.offscreen import depth_unit, encode_render


@pytest.fixture(scope="module")
def renderer():
    renderer = renderer_or_skip(160, 120)
    yield renderer
    renderer.close()


@pytest.fixture(scope="module")
def market(renderer):
    return renderer.render(market_scene(), normals=True)


def _far_scene():
    """Boxes spread over 400 m: the camera stands far beyond 65.5 m."""
    return scene_of(
        [
            thing(f"tower_{k}", (x, 0, z), (6, 12, 6))
            for k, (x, z) in enumerate(
                [(-200, -200), (200, -200), (-200, 200), (200, 200), (0, 0)], start=1
            )
        ],
        extent=(420.0, 420.0),
    )


def test_deep_scenes_are_not_clipped_in_the_png_and_exact_in_float(renderer):
    result = renderer.render(_far_scene())
    assert result.depth.max() > 65.535 * 2
    files = encode_render(result, kinds=("depth", "depth_metres", "depth_scale"))
    unit = json.loads(files["depth_scale"][1])["metres_per_unit"]
    assert unit == depth_unit(result.depth) > 0.001
    png = np.asarray(Image.open(io.BytesIO(files["depth"][1])))
    assert png.max() < 65535  # nothing clipped
    assert np.abs(png * unit - result.depth).max() <= unit / 2 + 1e-4
    exact = np.load(io.BytesIO(files["depth_metres"][1]))
    assert exact.dtype == np.float32 and np.array_equal(exact, result.depth)


def test_float_depth_is_the_distance_along_the_view_axis(renderer):
    """A box's top face, seen from the camera, lies at the depth its corners project to."""
    result = renderer.render(_far_scene())
    camera = Camera.from_dict(result.camera)
    k = result.ids.index("tower_5") + 1
    rows, cols = np.nonzero(result.segmentation == k)
    _, depths = camera.project(
        np.array([[x, y, z] for x in (-3, 3) for y in (0, 12) for z in (-3, 3)], dtype=float)
    )
    seen = result.depth[rows, cols]
    assert depths.min() - 0.01 <= seen.min() and seen.max() <= depths.max() + 0.01


def test_normals_image_shows_the_ground_facing_up(market):
    camera = Camera.from_dict(market.camera)
    up = (GL_TO_CV @ camera.extrinsics())[:3, :3] @ np.array([0.0, 1.0, 0.0])
    ground = (market.segmentation == 0) & (market.depth > 0)
    decoded = market.normals[ground].astype(float) / 255.0 * 2.0 - 1.0
    assert np.abs(np.median(decoded, axis=0) - up).max() < 0.02
    assert (market.normals[market.depth == 0] == 0).all()
    files = encode_render(market, kinds=("normals",))
    assert np.array_equal(np.asarray(Image.open(io.BytesIO(files["normals"][1]))), market.normals)


def test_box_corners_project_onto_the_object_pixels(market):
    """Each object's 3D box in the OpenCV camera frame, projected with K, frames the
    pixels segmentation gives it; the pose takes the box's base centre to its corners."""
    truth = market.ground_truth
    k = np.array(truth["camera"]["K"])
    assert truth["camera"]["model"] == "pinhole" and truth["camera"]["distortion"] is None
    by_id = {entry["id"]: entry for entry in truth["objects"]}
    assert set(by_id) == {"table_1", "sign_1", "house_1", "crossing_1"}
    for object_id in ("table_1", "house_1"):
        entry = by_id[object_id]
        corners = np.array(entry["corners"])
        pixels = (k @ (corners / corners[:, 2:3]).T).T[:, :2]
        x0, y0, x1, y1 = market.boxes[object_id]
        assert pixels[:, 0].min() <= x0 + 1 and pixels[:, 0].max() >= x1 - 1
        assert pixels[:, 1].min() <= y0 + 1 and pixels[:, 1].max() >= y1 - 1
        rotation, translation = np.array(entry["rotation"]), np.array(entry["translation"])
        w, h, d = entry["size"]
        local = np.array(BOX_CORNERS, dtype=float) * [w / 2, h, d / 2]
        assert np.allclose(local @ rotation.T + translation, corners, atol=1e-6)
        assert np.allclose(rotation @ rotation.T, np.eye(3), atol=1e-9)
        assert entry["visible"] == round(market.visible[object_id], 4)


def test_opencv_and_opengl_extrinsics_agree(market):
    truth = market.ground_truth["camera"]
    cv = np.array(truth["world_to_camera_opencv"])
    gl = np.array(truth["world_to_camera_opengl"])
    assert np.allclose(cv, GL_TO_CV @ gl)
    assert np.allclose(np.array(truth["camera_to_world_opengl"]) @ gl, np.eye(4), atol=1e-7)
