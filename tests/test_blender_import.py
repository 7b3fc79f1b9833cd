"""The GLB opened in a real client: Blender imports it in background mode and renders it
with Cycles from the file's camera. Skipped where ``blender`` is not installed; on
Debian 12: ``apt-get install blender python3-numpy`` (about 75 MB to download, some
minutes to install, so ``scripts/setup.sh`` leaves it out)."""

import json
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest
from PIL import Image
from render_fixtures import market_scene, preview_and_glb, thing

from scenewright.core.relations import Relation
from scenewright.render.export import export_glb

#: Opens a real client on exported files: one of the slow end-to-end tests.
pytestmark = pytest.mark.slow

PROBE = Path(__file__).resolve().parent.parent / "scripts" / "blender_render.py"
WIDTH, HEIGHT = 160, 120


def _scene():
    scene = market_scene()
    scene.objects.append(
        thing(
            "pot_1", (2, 0.8, 0), (0.4, 0.3, 0.4), parent="market_stand_1", colour=(0.9, 0.8, 0.1)
        )
    )
    scene.relations = [Relation("pot_1", "table_1", "OnTopOf")]
    return scene


@pytest.fixture(scope="module")
def blender(tmp_path_factory):
    executable = shutil.which("blender")
    if executable is None:
        pytest.skip("Blender is not installed (apt-get install blender python3-numpy)")
    folder = tmp_path_factory.mktemp("blender")
    preview, glb = preview_and_glb(_scene(), folder / "market.glb", WIDTH, HEIGHT)
    image = folder / "market.png"
    done = subprocess.run(
        [executable, "-b", "--factory-startup", "--python", str(PROBE), "--", str(glb), str(image)]
        + [str(WIDTH), str(HEIGHT)],
        capture_output=True,
        text=True,
        timeout=300,
    )
    lines = [line for line in done.stdout.splitlines() if line.startswith("PROBE")]
    assert done.returncode == 0 and lines, done.stdout[-2000:] + done.stderr[-2000:]
    info = json.loads(lines[0][len("PROBE") :])
    return info, np.asarray(Image.open(image).convert("RGB")), preview


def test_names_parents_and_transforms(blender):
    info, _, _ = blender
    assert {"table_1", "sign_1", "house_1", "pot_1", "road_1", "ground", "sun"} <= set(info)
    assert info["pot_1"]["parent"] == "table_1"
    assert info["table_1"]["parent"] == "market_stand_1"
    assert info["camera"]["type"] == "CAMERA" and info["sun"]["type"] == "LIGHT"
    # Blender is Z-up: glTF's (x, y, z) is Blender's (x, -z, y).
    for object_id in ("house_1", "table_1", "pot_1"):
        x, y, z = _scene().object(object_id).position
        assert np.allclose(info[object_id]["location"], [x, -z, y], atol=1e-4)


def test_every_mesh_has_its_materials(blender):
    info, _, _ = blender
    assert info["sign_1"]["materials"] == ["colour_3333e6"]
    for name, entry in info.items():
        if entry["type"] == "MESH":
            assert entry["materials"], name


def test_cycles_shows_the_preview_colours_lit(blender):
    """In each object's region of the preview, Blender's mean colour has the preview's
    hue (the same share of red, green and blue), and is neither black nor blown out."""
    _, picture, preview = blender
    compared = 0
    for k, entity_id in enumerate(preview.ids, start=1):
        region = preview.segmentation == k
        if region.sum() < 30:
            continue
        ours = picture[region].astype(float).mean(axis=0)
        theirs = preview.colour[region].astype(float).mean(axis=0)
        assert 25 < ours.mean() < 250, entity_id
        assert np.abs(ours / ours.sum() - theirs / theirs.sum()).max() < 0.06, (
            entity_id,
            ours,
            theirs,
        )
        compared += 1
    assert compared >= 4
    ground = (preview.segmentation == 0) & (preview.depth > 0)
    assert picture[ground].mean() > 25  # lit ground, no black patches
    road = preview.segmentation == preview.ids.index("road_1") + 1
    assert (picture[road].max(axis=1) > 20).all()  # no black pixel on the road


def test_moving_a_table_in_blender_moves_what_rests_on_it(blender, tmp_path):
    """Round trip: export, move the table in Blender, export from Blender, read the file
    as an example scene (as validate, learn and vary do): the pot moved with it."""
    from scenewright.examples.glb import read_glb

    source = export_glb(_scene(), tmp_path / "market.glb")
    moved = tmp_path / "moved.glb"
    script = Path(__file__).resolve().parent / "blender_move.py"
    done = subprocess.run(
        [shutil.which("blender"), "-b", "--factory-startup", "--python", str(script), "--"]
        + [str(source), str(moved), "table_1", "1.5"],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert done.returncode == 0 and moved.is_file(), done.stdout[-2000:] + done.stderr[-2000:]
    before = read_glb("market.glb", source.read_bytes(), "market")
    after = read_glb("moved.glb", moved.read_bytes(), "market")
    for object_id in ("table_1", "pot_1"):
        step = np.subtract(after.object(object_id).position, before.object(object_id).position)
        assert np.allclose(step, [1.5, 0.0, 0.0], atol=1e-4), object_id
    for object_id in ("house_1", "sign_1"):
        assert np.allclose(after.object(object_id).position, before.object(object_id).position)
