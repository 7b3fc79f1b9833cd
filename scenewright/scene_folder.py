"""One scene as a folder of files: what ``scenewright generate`` writes, for every command
and library user that writes a scene.

``write_scene(scene, directory)`` renders the preview (unless ``render=False``) and
writes the folder: scene.json (reproducible: no wall-clock times), timings.json,
description.txt, preview.png with its depth, segmentation and id map, scene.glb and
plan.png. The folder is replaced as a whole (``core.atomic.staged_outputs``): all its
files appear together or not at all, and files of an earlier run that this one does not
write are removed. ``write_variants`` writes a folder of such folders for ``vary``, with
its index, replaced as a whole too.

The scene is described beforehand (``api.describe_scene``); what the writing adds to it
(the render's metadata, the time of the render and the export) comes back in a new
Scene, as every step of the API returns one.
"""

from __future__ import annotations

import json
import os
from collections.abc import Callable, Collection, Mapping
from dataclasses import dataclass, replace
from pathlib import Path
from typing import TYPE_CHECKING, Any

from scenewright.api import DEFAULT_SIZE, export, render_scene, reproducible_json, timings_of
from scenewright.core.atomic import check_output_directory, staged_outputs, write_atomic, writing
from scenewright.core.errors import InputError
from scenewright.core.timing import timed

if TYPE_CHECKING:
    from scenewright.core.scene import Scene
    from scenewright.examples import Example
    from scenewright.render.views import CameraRanges
    from scenewright.variation.synthesis import Result

#: Files ``write_scene`` writes; stale ones from an earlier run into the same directory
#: (say a preview, before --no-render) are removed so the directory shows one scene.
SCENE_FILES = (
    "scene.json",
    "timings.json",
    "description.txt",
    "preview.png",
    "preview_depth.png",
    "preview_depth.npy",
    "preview_depth.json",
    "preview_seg.png",
    "preview_ids.json",
    "preview_3d.json",
    "scene.glb",
    "plan.png",
)
#: ``complete`` writes a scene's files and, with --explain, its layout mask.
COMPLETE_FILES = SCENE_FILES + ("mask.png",)

#: A file written beside the scene's own: name -> function writing it to a path.
ExtraFiles = Mapping[str, Callable[[Path], object]]


@dataclass(frozen=True)
class WrittenScene:
    """A scene as written: with its render metadata and the time of every stage, the
    folder, and the names of the files in it."""

    scene: Scene
    directory: Path
    files: list[str]


def check_scene_folder(
    directory: str | os.PathLike[str], outputs: Collection[str] = SCENE_FILES
) -> Path:
    """Refuse, before any work, a directory that ``write_scene`` could not replace
    (``core.atomic.check_output_directory``)."""
    return check_output_directory(directory, outputs)


def write_scene(
    scene: Scene,
    directory: str | os.PathLike[str],
    *,
    render: bool = True,
    size: tuple[int, int] = DEFAULT_SIZE,
    view: str = "perspective",
    camera: CameraRanges | None = None,
    extra: Callable[[Scene], ExtraFiles] | None = None,
    outputs: Collection[str] = SCENE_FILES,
) -> WrittenScene:
    """Render the described ``scene`` (unless ``render`` is false; ``size``, ``view``,
    ``camera`` as ``api.render_scene``) and write its folder (module docstring).

    ``extra(scene)`` names more files to write, for the scene as rendered; ``outputs``
    names every file the folder may hold (those not written this time are removed).
    """
    if camera is not None and not render:
        raise InputError("a camera places the preview's camera; it needs the preview (render)")
    scene, images = _rendered(scene, render, size, view, camera)
    with staged_outputs(directory, outputs) as stage:
        scene = write_scene_files(scene, stage, images, extra=extra(scene) if extra else None)
        files = sorted(path.name for path in stage.iterdir())
    return WrittenScene(scene, Path(directory), files)


def write_scene_files(
    scene: Scene,
    folder: Path,
    images=None,
    *,
    extra: ExtraFiles | None = None,
    records: Mapping[str, Any] | None = None,
) -> Scene:
    """Write the files of a described, rendered ``scene`` into ``folder`` as they are,
    each whole (``write_scene`` stages the folder around this); ``images``: the render,
    or None for no preview; ``records``: keys added to scene.json. Returns the scene
    with the time its export took."""
    from scenewright.render.offscreen import save_render
    from scenewright.render.plan_image import draw_plan

    timings = dict(scene.timings)
    write_atomic(folder / "description.txt", scene.description.text + "\n")
    for name, write in (extra or {}).items():
        with writing(folder / name):
            write(folder / name)
    if images is not None:
        save_render(images, folder, stem="preview")
    with timed(timings, "export"):
        export(scene, folder / "scene.glb")
    scene = replace(scene, timings=timings)
    with writing(folder / "plan.png"):
        draw_plan(scene, folder / "plan.png")
    text = reproducible_json(scene)
    if records:
        data = json.loads(text)
        data.update(records)
        text = json.dumps(data, indent=1, ensure_ascii=False) + "\n"
    write_atomic(folder / "scene.json", text)
    write_atomic(folder / "timings.json", json.dumps(timings_of(scene), indent=1) + "\n")
    return scene


def _rendered(scene: Scene, render: bool, size, view: str, camera: CameraRanges | None):
    if not render:
        return scene, None
    return render_scene(scene, size=size, view=view, camera=camera)


def write_variants(
    results: list[Result],
    examples: list[Example],
    directory: str | os.PathLike[str],
    seed: int,
    *,
    render: bool = True,
    size: tuple[int, int] = DEFAULT_SIZE,
    view: str = "perspective",
) -> dict:
    """Write ``vary``'s variants into ``directory`` (replaced as a whole): one scene
    folder each, ``variant_001/``, ``variant_002/``, ... in rank order (best first), its
    scene.json with the ``synthesis`` record (the base example, the operations with
    their compatibilities, K, each object's source), and index.json listing them
    (``variation.index``). Returns the index."""
    from scenewright.api import describe_scene
    from scenewright.variation.index import FOLDERS, new_index, variant_entry

    index = new_index(examples, seed)
    with staged_outputs(directory, FOLDERS) as stage:
        for rank, result in enumerate(results, start=1):
            folder = stage / f"variant_{rank:03d}"
            folder.mkdir()
            scene, images = _rendered(describe_scene(result.scene), render, size, view, None)
            write_scene_files(scene, folder, images, records={"synthesis": result.synthesis()})
            index["variants"].append(variant_entry(result, examples, folder.name, scene))
        write_atomic(stage / "index.json", json.dumps(index, indent=1) + "\n")
    return index
