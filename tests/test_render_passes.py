"""The renderer's cheaper passes (``gl_backend.pyrender_classes``, ``offscreen._posed_node``)
draw exactly what pyrender's own Renderer, Scene and nodes draw: every array and
value of a RenderResult byte for byte, outdoors and in a room, from both views (with
pyrender's own shadow map size, the one size its shadow pass draws right, and its own
shadow filter); and the one shadow filter changes only the edges of shadows."""

from __future__ import annotations

import pytest
import trimesh
from render_fixtures import or_skip_without_opengl

from scenewright.api import build_scene
from scenewright.core.errors import GenerationError
from scenewright.render import gl_backend, offscreen

SIZE = (256, 256)  # the dataset's image size
VIEWS = ("perspective", "top")


def renders(scene, *, plain: bool, monkeypatch) -> list[offscreen.RenderResult]:
    """The scene from both views, drawn through pyrender's own classes and
    ``Scene.add``'s nodes if ``plain``, else through the renderer's own."""
    with monkeypatch.context() as patch:
        patch.setattr(offscreen, "shadow_map_size", lambda width, height: offscreen.MAX_SHADOW_MAP)
        patch.setattr(gl_backend, "shader_source", lambda name, text: text)
        if plain:
            patch.setattr(
                offscreen,
                "pyrender_classes",
                lambda gl: gl_backend.PyrenderClasses(gl.Renderer, gl.Scene),
            )
            patch.setattr(
                offscreen,
                "_posed_node",
                lambda gl, mesh, pose, name: gl.Node(name=name, matrix=pose, mesh=mesh),
            )
        with or_skip_without_opengl(lambda: offscreen.Renderer(*SIZE)) as renderer:
            chosen = offscreen.pyrender_classes(renderer._gl).renderer
            assert (type(renderer._renderer._renderer) is chosen) and (
                chosen.__module__ == "pyrender.renderer"
            ) == plain
            return [renderer.render(scene, view) for view in VIEWS]


@pytest.mark.parametrize("rules, seed", [("village", 0), ("village", 3), ("bedroom", 1)])
def test_same_pixels_as_pyrenders_own_classes(monkeypatch, rules, seed):
    scene = build_scene(rules, seed)
    expected = renders(scene, plain=True, monkeypatch=monkeypatch)
    got = renders(scene, plain=False, monkeypatch=monkeypatch)
    for view, want, have in zip(VIEWS, expected, got, strict=False):
        for name in ("colour", "depth", "segmentation"):
            a, b = getattr(want, name), getattr(have, name)
            assert (a.dtype, a.shape, a.tobytes()) == (b.dtype, b.shape, b.tobytes()), (view, name)
        assert (have.ids, have.boxes, have.visible, have.camera) == (
            want.ids,
            want.boxes,
            want.visible,
            want.camera,
        )
        assert len(have.ids) > 3 and have.boxes  # something to see


def test_one_shadow_lookup_changes_only_the_edges_of_shadows():
    from pathlib import Path

    import numpy as np
    import pyrender

    text = (Path(pyrender.__file__).parent / "shaders" / "mesh.frag").read_text()
    assert gl_backend.PYRENDER_SHADOW_FILTER in text  # the pinned pyrender's filter
    assert (
        gl_backend.shader_source("mesh.frag", text).count("texture2DShadowLerp(") == 2
    )  # defined, used once
    with pytest.raises(GenerationError, match="mesh.frag"):
        gl_backend.shader_source("mesh.frag", text.replace("result/9.0", "result/4.0"))

    scene = build_scene("village", 3)
    colours = {}
    for ours in (True, False):
        with pytest.MonkeyPatch.context() as patch:
            if not ours:
                patch.setattr(gl_backend, "shader_source", lambda name, text: text)
            gl_backend.pyrender_classes.cache_clear()
            with or_skip_without_opengl(lambda: offscreen.Renderer(*SIZE)) as renderer:
                colours[ours] = renderer.render(scene).colour.astype(int)
        gl_backend.pyrender_classes.cache_clear()
    changed = np.abs(colours[True] - colours[False]).max(axis=-1)
    # Soft edges a little sharper: a few levels on a few percent of the pixels.
    assert (
        0 < (changed > 0).mean() < 0.1
        and np.median(changed[changed > 0]) <= 8
        and (changed > 20).mean() < 0.01
    )


#: A new process in which eight threads load pyrender at once, as a dask worker's
#: threads each start a renderer; it prints how many could not.
RACE = """
import threading
from scenewright.render.gl_backend import load_pyrender
errors = []
barrier = threading.Barrier(8)
def load():
    barrier.wait()
    try:
        load_pyrender().OffscreenRenderer
    except Exception as error:
        errors.append(repr(error))
threads = [threading.Thread(target=load) for _ in range(8)]
for thread in threads:
    thread.start()
for thread in threads:
    thread.join()
print(len(errors), errors[:1])
"""


@pytest.mark.slow
def test_threads_loading_pyrender_at_once_each_get_all_of_it():
    """pyrender is imported with a stand-in for its viewer; before the import took a
    lock, 7 of 8 threads got the module half imported ("no attribute
    'OffscreenRenderer'") and a dask dataset failed."""
    import subprocess
    import sys

    done = subprocess.run([sys.executable, "-c", RACE], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    assert done.stdout.split()[0] == "0", done.stdout
    # and the viewer pyrender offers is still its own, imported when asked for
    viewer = subprocess.run(
        [
            sys.executable,
            "-c",
            "import sys; from scenewright.render.gl_backend import load_pyrender;"
            "load_pyrender(); print('pyglet' in sys.modules);"
            "from pyrender.viewer import Viewer; print(Viewer.__module__)",
        ],
        capture_output=True,
        text=True,
    )
    assert viewer.stdout.split() == ["False", "pyrender.viewer"], viewer.stderr


def test_meshes_as_far_from_the_camera_are_drawn_in_the_order_they_were_added():
    """pyrender orders meshes by their distance from the camera, starting from a set of
    nodes (ordered by address in memory): meshes at one distance, a window's pane and its
    frame, were drawn in either order from run to run, and a pixel where both blend
    changed between runs of the same scene. The renderer's scene draws them as added."""
    with or_skip_without_opengl(lambda: offscreen.Renderer(*SIZE)) as renderer:
        gl = renderer._gl
        scene = offscreen.pyrender_classes(gl).scene(ambient_light=[0.1, 0.1, 0.1])
        camera = gl.Node(camera=gl.PerspectiveCamera(yfov=1.0), translation=[0, 0, 5])
        scene.add_node(camera)
        scene.main_camera_node = camera
        box = gl.Mesh.from_trimesh(trimesh.creation.box((0.1, 0.1, 0.1)))
        glass = gl.Mesh.from_trimesh(
            trimesh.creation.box((0.1, 0.1, 0.1)),
            material=gl.MetallicRoughnessMaterial(
                baseColorFactor=[1, 1, 1, 0.5], alphaMode="BLEND"
            ),
        )
        added = [gl.Node(name=f"n{k}", mesh=glass if k % 3 == 0 else box) for k in range(60)]
        for node in added:
            scene.add_node(node)
        scene.remove_node(added[10])
        order = renderer._renderer._renderer._sorted_mesh_nodes(scene)
        kept = [node for node in added if node is not added[10]]
        solid = [node for node in kept if not node.mesh.is_transparent]
        clear = [node for node in kept if node.mesh.is_transparent]
        assert order == solid + clear
