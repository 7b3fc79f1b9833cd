"""The GLB opened in a web client: three.js's GLTFLoader in headless Chromium renders it
from the file's camera (``scripts/threejs_render.py``). Skipped where ``chromium`` or the
npm package ``three`` is missing (``apt-get install chromium``;
``npm install --prefix .tools-three three``)."""

import importlib.util
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from PIL import Image
from render_fixtures import assert_preview_hues, market_scene, preview_and_glb

#: Opens a real client on exported files: one of the slow end-to-end tests.
pytestmark = pytest.mark.slow

SCRIPT = Path(__file__).resolve().parent.parent / "scripts" / "threejs_render.py"
WIDTH, HEIGHT = 160, 120


def _script():
    spec = importlib.util.spec_from_file_location("threejs_render", SCRIPT)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.fixture(scope="module")
def threejs(tmp_path_factory):
    if shutil.which("chromium") is None:
        pytest.skip("Chromium is not installed (apt-get install chromium)")
    if _script().default_three() is None:
        pytest.skip("three.js is not installed (npm install --prefix .tools-three three)")
    folder = tmp_path_factory.mktemp("threejs")
    preview, glb = preview_and_glb(market_scene(), folder / "market.glb", WIDTH, HEIGHT)
    image = folder / "market.png"
    done = subprocess.run(
        [sys.executable, str(SCRIPT), str(glb), str(image), str(WIDTH), str(HEIGHT)],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert done.returncode == 0, done.stderr[-2000:]
    return np.asarray(Image.open(image).convert("RGB")), preview


def test_threejs_shows_the_preview_colours_lit(threejs):
    """In each object's region of the preview, three.js's mean colour has the preview's
    hue (the same share of red, green and blue), and is neither black nor blown out; the
    ground is lit and the road has no black pixel."""
    picture, preview = threejs
    assert picture.shape == (HEIGHT, WIDTH, 3)
    # no black faces: the sides turned away from the sun are lit by the sky
    assert_preview_hues(picture, preview)
    ground = (preview.segmentation == 0) & (preview.depth > 0)
    assert picture[ground].mean() > 25
    road = preview.segmentation == preview.ids.index("road_1") + 1
    assert (picture[road].max(axis=1) > 20).all()
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
