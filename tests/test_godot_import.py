"""The GLB opened in a game engine: Godot 3 imports it into a throwaway project and
renders it from the file's camera (``scripts/godot_render.py``). Skipped where ``godot3``
or ``xvfb-run`` is missing (``apt-get install godot3 xvfb``)."""

import importlib.util
import json
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from PIL import Image
from render_fixtures import assert_preview_hues, market_scene, renderer_or_skip

from scenewright.render.export import export_glb

#: Opens a real client on exported files: one of the slow end-to-end tests.
pytestmark = pytest.mark.slow

SCRIPT = Path(__file__).resolve().parent.parent / "scripts" / "godot_render.py"
WIDTH, HEIGHT = 160, 120


def _script():
    spec = importlib.util.spec_from_file_location("godot_render", SCRIPT)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.fixture(scope="module")
def godot(tmp_path_factory):
    for tool, package in (("godot3", "godot3"), ("xvfb-run", "xvfb")):
        if shutil.which(tool) is None:
            pytest.skip(f"{tool} is not installed (apt-get install {package})")
    renderer = renderer_or_skip(WIDTH, HEIGHT)  # the preview to compare with
    scene = market_scene()
    preview = renderer.render(scene, normals=True)
    renderer.close()
    scene.render = {"camera": preview.camera}  # the GLB's camera is the preview's
    folder = tmp_path_factory.mktemp("godot")
    glb = export_glb(scene, folder / "market.glb")
    image = folder / "market.png"
    done = subprocess.run(
        [sys.executable, str(SCRIPT), str(glb), str(image), str(WIDTH), str(HEIGHT)],
        capture_output=True,
        text=True,
        timeout=300,
    )
    lines = [line for line in done.stdout.splitlines() if line.startswith("PROBE")]
    assert done.returncode == 0 and lines, done.stdout[-2000:] + done.stderr[-2000:]
    probe = json.loads(lines[0][len("PROBE") :])
    document = _script().document(glb)
    return probe, np.asarray(Image.open(image).convert("RGB")), preview, document


def _rotation(quaternion) -> np.ndarray:
    x, y, z, w = quaternion
    return np.array(
        [
            [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
            [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
            [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
        ]
    )


def test_node_names_and_parents_survive_the_import(godot):
    probe, _, _, _ = godot
    nodes = probe["nodes"]
    for path in (
        "scene/market_stand_1/table_1",
        "scene/market_stand_1/sign_1",
        "scene/house_1",
        "scene/road_1",
        "scene/ground",
    ):
        assert nodes.get(path) == "MeshInstance", path
    assert nodes["scene/camera"] == "Camera"
    # the KHR_lights_punctual sun arrives as Godot's own light
    assert probe["lights"] == 1 and "DirectionalLight" in nodes.values()


def test_faces_turned_to_the_sun_are_brighter(godot):
    """Lit, not flat: over the objects and the ground, the pixels whose surface (the
    preview's normals) faces the file's sun are brighter in Godot than those turned away."""
    _, picture, preview, document = godot
    nodes = {node.get("name"): node for node in document["nodes"]}
    camera = _rotation(nodes["camera"]["rotation"])
    towards_sun = _rotation(nodes["sun"]["rotation"]) @ [0.0, 0.0, 1.0]  # lights shine along -Z
    drawn = preview.depth > 0
    normals_cv = preview.normals.astype(float) / 255.0 * 2.0 - 1.0
    # the OpenCV camera frame is glTF's camera frame with y and z turned round
    normals = normals_cv @ np.diag([1.0, -1.0, -1.0]) @ camera.T
    facing = normals @ towards_sun
    brightness = picture.astype(float).mean(axis=2)
    ground = (preview.segmentation == 0) & drawn
    assert facing[ground].mean() > 0.3  # the sun stands above the ground
    # Within one object (one colour), lit faces against faces turned away.
    compared = 0
    for k, entity_id in enumerate(preview.ids, start=1):
        region = (preview.segmentation == k) & drawn
        lit, away = region & (facing > 0.4), region & (facing < 0.05)
        if lit.sum() < 10 or away.sum() < 10:
            continue
        assert brightness[lit].mean() > 1.25 * brightness[away].mean(), (
            entity_id,
            brightness[lit].mean(),
            brightness[away].mean(),
        )
        compared += 1
    assert compared >= 2


def test_godot_shows_the_preview_colours(godot):
    """In each object's region of the preview, Godot's mean colour has the preview's hue
    (the same share of red, green and blue), neither black nor blown out nor grey."""
    _, picture, preview, _ = godot
    assert picture.shape == (HEIGHT, WIDTH, 3)
    assert_preview_hues(picture, preview)
    ground = (preview.segmentation == 0) & (preview.depth > 0)
    green = picture[ground].astype(float).mean(axis=0)
    assert green[1] > 1.1 * max(green[0], green[2])  # the ground's green, not grey
    sign = preview.segmentation == preview.ids.index("sign_1") + 1
    blue = picture[sign].astype(float).mean(axis=0)
    assert blue[2] > 1.5 * max(blue[0], blue[1])  # the sign's own colour, blue


def test_a_missing_file_is_one_line_and_exit_2(tmp_path):
    out = tmp_path / "out.png"
    done = subprocess.run(
        [sys.executable, str(SCRIPT), str(tmp_path / "none.glb"), str(out)],
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert done.returncode == 2
    assert done.stderr.count("\n") == 1 and "no such file" in done.stderr
    assert not out.exists()
