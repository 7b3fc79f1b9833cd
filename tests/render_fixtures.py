"""Small hand-built scenes and the OpenGL availability rule shared by the render and
export tests."""

from __future__ import annotations

import os
import subprocess
import sys

import numpy as np
import pytest

from scenewright.core.errors import GenerationError
from scenewright.core.room import Room
from scenewright.core.scene import Scene, SceneObject, ScenePath


def thing(
    object_id: str,
    position=(0.0, 0.0, 0.0),
    size=(1.0, 1.0, 1.0),
    *,
    yaw: float = 0.0,
    kind: str = "object",
    parent: str | None = None,
    colour=(0.8, 0.3, 0.2),
    shape: str | None = "box",
) -> SceneObject:
    """A scene object whose type is its id without the counter (``house_1`` -> house)."""
    type_name = object_id.rsplit("_", 1)[0]
    return SceneObject(
        id=object_id,
        type=type_name,
        kind=kind,
        noun=type_name.replace("_", " "),
        plural=None,
        parent=parent,
        style=None,
        position=[float(v) for v in position],
        yaw=yaw,
        size=[float(v) for v in size],
        shape=shape,
        colour=list(colour),
    )


def road(path_id: str, points, width: float = 3.0, start: str | None = None) -> ScenePath:
    return ScenePath(
        id=path_id,
        type="road",
        noun="road",
        plural=None,
        parent=None,
        points=[list(map(float, p)) for p in points],
        width=width,
        start=start,
    )


def scene_of(
    objects, paths=(), extent=(30.0, 20.0), *, walls: bool = False, room: Room | None = None
) -> Scene:
    """A scene of these objects and paths: outdoors, or in a bare rectangular room the
    size of the extent (``walls``), or in ``room`` (whose size is then the extent)."""
    if room is None and walls:
        room = Room.rectangle(*extent)
    if room is not None:
        extent = room.extent
    return Scene(
        rules="test",
        seed=1,
        extent=list(extent),
        objects=list(objects),
        paths=list(paths),
        relations=[],
        room=room,
    )


def market_scene() -> Scene:
    """A market stand (group of a table and a sign), a house, a junction and a road."""
    return scene_of(
        [
            thing("market_stand_1", (3, 0, 0), (4, 2, 2), kind="group", shape=None),
            thing("table_1", (2, 0, 0), (1.6, 0.8, 0.9), parent="market_stand_1"),
            thing(
                "sign_1",
                (4, 0, 0),
                (0.5, 2.0, 0.2),
                parent="market_stand_1",
                colour=(0.2, 0.2, 0.9),
            ),
            thing("house_1", (-5, 0, -4), (4, 3, 5), yaw=0.5, colour=(0.9, 0.9, 0.8)),
            thing(
                "crossing_1",
                (0, 0, 4),
                (3, 0, 3),
                kind="junction",
                colour=(0.5, 0.4, 0.3),
                shape=None,
            ),
        ],
        [road("road_1", [[0, 4], [8, 4], [12, 8]], start="crossing_1")],
    )


def renderer_or_skip(width: int = 160, height: int = 120):
    """A started ``Renderer``; skips when no OpenGL backend exists, unless under CI
    (where a missing backend is a failure: CI must exercise rendering)."""
    from scenewright.render.offscreen import Renderer

    return or_skip_without_opengl(lambda: Renderer(width, height))


def or_skip_without_opengl(make):
    """``make()``; skips when it finds no OpenGL backend, unless under CI."""
    try:
        return make()
    except GenerationError as error:
        if os.environ.get("CI"):
            raise
        pytest.skip(f"no offscreen OpenGL backend: {error}")


def run_without_opengl(code: str) -> subprocess.CompletedProcess:
    """Python ``code`` run in a fresh interpreter whose OpenGL platform cannot load
    (``PYOPENGL_PLATFORM`` names none), its output captured as text."""
    env = dict(os.environ, PYOPENGL_PLATFORM="no-such-platform")
    return subprocess.run(
        [sys.executable, "-c", code], env=env, capture_output=True, text=True, timeout=60
    )


def preview_and_glb(scene: Scene, path, width: int, height: int):
    """The preview of ``scene`` at ``width`` x ``height`` (skipping without OpenGL) and
    its GLB written to ``path`` with the preview's camera, for the tests that open the
    file in another program and compare what it shows with the preview."""
    from scenewright.render.export import export_glb

    renderer = renderer_or_skip(width, height)
    preview = renderer.render(scene)
    renderer.close()
    scene.render = {"camera": preview.camera}  # the GLB's camera is the preview's
    return preview, export_glb(scene, path)


def assert_preview_hues(picture, preview, tolerance: float = 0.06) -> None:
    """In each object's region of ``preview`` (30 pixels or more, at least four of
    them), ``picture``'s mean colour has the preview's hue (each of red, green and blue
    the same share within ``tolerance``), is neither black nor blown out, and has no
    black face (98 % of its pixels lit)."""
    compared = 0
    for k, entity_id in enumerate(preview.ids, start=1):
        region = preview.segmentation == k
        if region.sum() < 30:
            continue
        ours = picture[region].astype(float).mean(axis=0)
        theirs = preview.colour[region].astype(float).mean(axis=0)
        assert 25 < ours.mean() < 250, entity_id
        assert (picture[region].max(axis=1) > 20).mean() > 0.98, entity_id
        assert np.abs(ours / ours.sum() - theirs / theirs.sum()).max() < tolerance, (
            entity_id,
            ours,
            theirs,
        )
        compared += 1
    assert compared >= 4
