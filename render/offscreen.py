"""Offscreen previews and ground truth images of a scene with pyrender.

``Renderer`` keeps one OpenGL context for many scenes (a dataset renders thousands);
``Renderer.render`` draws a scene from an automatic camera (``render.camera``) and
returns a ``RenderResult``: colour, depth, instance segmentation, per-object 2D boxes
and visible fractions. ``save_render`` writes them as PNGs (atomically) and
``render_metadata`` gives the part that goes into scene.json.

Drawn entities are objects (kind ``object``), junctions (a flat disc) and paths (a
ribbon); groups have no body of their own. Each entity's index in ``RenderResult.ids``
plus one is its value in the segmentation image (0 is background: sky and ground).

The OpenGL backend is chosen before pyrender is imported: the user's
``PYOPENGL_PLATFORM`` if set, else EGL when libEGL is installed, else OSMesa. When none
can start, ``GenerationError`` says what to install.
"""

from __future__ import annotations

import ctypes.util
import io
import json
import os
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import trimesh
from PIL import Image

from scenewright.atomic import write_atomic
from scenewright.errors import GenerationError
from scenewright.scene import Scene

from .camera import Camera, frame_scene
from .meshes import ground_mesh, junction_mesh, object_mesh, object_transform, path_mesh

SKY = (0.62, 0.77, 0.92)
AMBIENT = (0.35, 0.35, 0.38)
SUN_INTENSITY = 2.0
#: Direction the sunlight travels: from high in the south-west towards the north-east,
#: so shadows fall away from the south-east camera but stay visible beside objects.
SUN_DIRECTION = np.array([0.45, -1.0, -0.35])
#: Paths are drawn this much apart in height (by their order) so crossing ribbons do
#: not z-fight, which would make the segmentation at a crossing noisy.
PATH_STEP = 0.002
#: The drawn ground reaches this many times the scene extent, so the perspective view
#: shows grass, not sky, below the horizon.
GROUND_MARGIN = 3.0

_INSTALL_HINT = (
    "install EGL (apt-get install libegl1 libegl-mesa0) and set PYOPENGL_PLATFORM=egl, "
    "or OSMesa (apt-get install libosmesa6) and set PYOPENGL_PLATFORM=osmesa"
)


@dataclass
class RenderResult:
    """One rendered view of a scene.

    ``depth`` is the distance along the camera's viewing axis in metres (0 where only
    sky is seen). ``boxes`` maps each entity seen in the image to its pixel box
    [x0, y0, x1, y1] (x1, y1 exclusive). ``visible`` maps every drawn entity to the
    fraction of its in-frame silhouette not hidden by other entities (1.0 unoccluded,
    0.0 hidden or out of frame); the ground never hides anything (it lies below all).
    """

    colour: np.ndarray
    depth: np.ndarray
    segmentation: np.ndarray
    ids: list[str]
    boxes: dict[str, list[int]]
    visible: dict[str, float]
    camera: dict[str, Any]


@dataclass
class _Entity:
    """A drawn scene entity: its id, world-space mesh pose and pyrender node."""

    id: str
    mesh: trimesh.Trimesh
    pose: np.ndarray
    node: Any


class Renderer:
    """An offscreen renderer of ``width`` x ``height`` pixels; reuse it across scenes.

    ``shadows`` turns on the sun's shadow map (costs one extra pass per frame).
    """

    def __init__(self, width: int = 640, height: int = 480, *, shadows: bool = True):
        self.width, self.height, self.shadows = int(width), int(height), shadows
        self._gl = _load_pyrender()
        try:
            self._renderer = self._gl.OffscreenRenderer(self.width, self.height)
        except Exception as error:  # each backend fails in its own way; all mean the same
            raise _backend_error(error) from None

    def __enter__(self) -> "Renderer":
        return self

    def __exit__(self, *exc_info) -> None:
        self.close()

    def close(self) -> None:
        """Release the OpenGL context (the renderer cannot be used afterwards)."""
        if self._renderer is not None:
            self._renderer.delete()
            self._renderer = None

    def render(self, scene: Scene, view: str = "perspective") -> RenderResult:
        """Render ``scene`` from the automatic ``view`` ("perspective" or "top")."""
        if self._renderer is None:
            raise RuntimeError("this Renderer has been closed")
        gl = self._gl
        camera = frame_scene(scene, view, self.width, self.height)
        world, entities = self._build(scene, camera)

        flags = gl.RenderFlags.SHADOWS_DIRECTIONAL if self.shadows else gl.RenderFlags.NONE
        colour, depth = self._renderer.render(world, flags=flags)
        if camera.orthographic:
            depth = _orthographic_depth(depth, camera)

        seg_map = {entity.node: _index_colour(k + 1) for k, entity in enumerate(entities)}
        seg_colour, _ = self._renderer.render(world, flags=gl.RenderFlags.SEG, seg_node_map=seg_map)
        segmentation = _decode_index(seg_colour)

        ids = [entity.id for entity in entities]
        seen = np.bincount(segmentation.ravel(), minlength=len(ids) + 1)
        alone = self._alone_pixel_counts(world, entities, camera)
        visible = {
            entity_id: float(min(seen[k + 1] / alone[k], 1.0)) if alone[k] else 0.0
            for k, entity_id in enumerate(ids)
        }
        return RenderResult(
            colour=np.ascontiguousarray(colour[..., :3]),
            depth=np.ascontiguousarray(depth, dtype=np.float32),
            segmentation=segmentation,
            ids=ids,
            boxes=_boxes(segmentation, ids),
            visible=visible,
            camera=camera.to_dict(),
        )

    # -- scene building -------------------------------------------------------------

    def _build(self, scene: Scene, camera: Camera):
        gl = self._gl
        world = gl.Scene(bg_color=(*SKY, 1.0), ambient_light=AMBIENT)
        world.add(_pyrender_mesh(gl, ground_mesh(scene, margin=GROUND_MARGIN)))

        entities: list[_Entity] = []
        for obj in scene.objects:
            if obj.kind == "object":
                entities.append(_Entity(obj.id, object_mesh(obj), object_transform(obj), None))
            elif obj.kind == "junction":
                lifted = object_transform(obj)
                lifted[1, 3] += PATH_STEP * len(scene.paths)  # above every path ribbon
                entities.append(_Entity(obj.id, junction_mesh(obj), lifted, None))
        for order, scene_path in enumerate(scene.paths):
            lifted = np.eye(4)
            lifted[1, 3] = PATH_STEP * order
            entities.append(_Entity(scene_path.id, path_mesh(scene_path), lifted, None))
        # A degenerate path (all its points in one place) has no triangles to draw.
        entities = [entity for entity in entities if len(entity.mesh.faces)]
        for entity in entities:
            entity.node = world.add(_pyrender_mesh(gl, entity.mesh), pose=entity.pose, name=entity.id)

        if camera.orthographic:
            lens = gl.OrthographicCamera(camera.xmag, camera.ymag, znear=camera.znear, zfar=camera.zfar)
        else:
            lens = gl.PerspectiveCamera(
                camera.yfov, aspectRatio=camera.width / camera.height, znear=camera.znear, zfar=camera.zfar
            )
        world.add(lens, pose=camera.pose)
        world.add(gl.DirectionalLight(color=np.ones(3), intensity=SUN_INTENSITY), pose=_sun_pose())
        return world, entities

    def _alone_pixel_counts(self, world, entities: list[_Entity], camera: Camera) -> np.ndarray:
        """How many pixels each entity covers when nothing else is drawn.

        Entities whose projected boxes do not overlap cannot hide one another, so they
        share one segmentation pass: a few passes give every entity's unoccluded area.
        """
        counts = np.zeros(len(entities), dtype=np.int64)
        boxes = [_projected_box(entity, camera) for entity in entities]
        for batch in _disjoint_batches(boxes):
            seg_map = {entities[k].node: _index_colour(k + 1) for k in batch}
            seg_colour, _ = self._renderer.render(world, flags=self._gl.RenderFlags.SEG, seg_node_map=seg_map)
            pixels = np.bincount(_decode_index(seg_colour).ravel(), minlength=len(entities) + 1)
            counts[batch] = pixels[np.asarray(batch) + 1]
        return counts


def render_scene(scene: Scene, view: str = "perspective", **renderer_options) -> RenderResult:
    """Render one scene with a renderer made (and closed) for it; see ``Renderer``."""
    with Renderer(**renderer_options) as renderer:
        return renderer.render(scene, view)


def save_render(result: RenderResult, directory: str | os.PathLike, *, stem: str = "preview") -> dict[str, Path]:
    """Write a render's images and id map into ``directory``; return the paths by kind.

    File names and encodings are those of ``encode_render``.
    """
    folder = Path(directory)
    folder.mkdir(parents=True, exist_ok=True)
    paths = {}
    for kind, (name, data) in encode_render(result, stem=stem).items():
        paths[kind] = write_atomic(folder / name, data)
    return paths


def encode_render(result: RenderResult, *, stem: str = "preview") -> dict[str, tuple[str, bytes]]:
    """A render's files as (file name, bytes) by kind, for writers that store them
    elsewhere than a folder (an archive, a dataset shard).

    ``colour``: ``{stem}.png`` (RGB). ``depth``: ``{stem}_depth.png``, 16-bit
    millimetres (0 = sky; clipped at 65.535 m). ``segmentation``: ``{stem}_seg.png``,
    16-bit entity indices (0 = background). ``ids``: ``{stem}_ids.json`` mapping each
    index to its entity id.
    """
    if len(result.ids) > 65535:
        raise GenerationError(f"{len(result.ids)} entities do not fit a 16-bit segmentation image")
    millimetres = np.clip(np.round(result.depth * 1000.0), 0, 65535).astype(np.uint16)
    return {
        "colour": (f"{stem}.png", _png(result.colour)),
        "depth": (f"{stem}_depth.png", _png(millimetres)),
        "segmentation": (f"{stem}_seg.png", _png(result.segmentation.astype(np.uint16))),
        "ids": (f"{stem}_ids.json", _ids_json(result.ids)),
    }


def render_metadata(result: RenderResult) -> dict[str, Any]:
    """scene.json's ``render`` value: the camera and, per drawn entity, its pixel box
    (null when not seen) and visible fraction."""
    return {
        "camera": result.camera,
        "objects": {
            entity_id: {"bbox": result.boxes.get(entity_id), "visible": round(result.visible[entity_id], 4)}
            for entity_id in result.ids
        },
    }


# -- OpenGL backend ------------------------------------------------------------------


def _load_pyrender():
    """Import pyrender with an offscreen platform chosen, or say what to install."""
    if "PYOPENGL_PLATFORM" not in os.environ:
        if ctypes.util.find_library("EGL"):
            os.environ["PYOPENGL_PLATFORM"] = "egl"
        elif ctypes.util.find_library("OSMesa"):
            os.environ["PYOPENGL_PLATFORM"] = "osmesa"
        else:
            raise GenerationError(f"no offscreen OpenGL library found; {_INSTALL_HINT}")
    try:
        import pyrender
    except Exception as error:  # PyOpenGL raises various errors for a broken platform
        raise _backend_error(error) from None
    return pyrender


def _backend_error(error: Exception) -> GenerationError:
    platform = os.environ.get("PYOPENGL_PLATFORM", "")
    reason = " ".join(str(error).split()) or type(error).__name__
    return GenerationError(
        f"offscreen OpenGL backend PYOPENGL_PLATFORM={platform!r} could not start ({reason}); {_INSTALL_HINT}"
    )


# -- helpers -------------------------------------------------------------------------


def _pyrender_mesh(gl, mesh: trimesh.Trimesh):
    """A flat-shaded pyrender mesh with the trimesh's face colours on a matte material.

    Built from one primitive whose triangles own their vertices, so each face keeps
    its colour and normal (pyrender's ``from_trimesh`` drops colours when given a
    material, and otherwise picks a blended, metallic one).
    """
    corners = mesh.vertices[mesh.faces].reshape(-1, 3)
    normals = np.repeat(mesh.face_normals, 3, axis=0)
    colours = np.repeat(mesh.visual.face_colors, 3, axis=0)
    material = gl.MetallicRoughnessMaterial(baseColorFactor=(1.0, 1.0, 1.0, 1.0), metallicFactor=0.0, roughnessFactor=0.9)
    primitive = gl.Primitive(positions=corners, normals=normals, color_0=colours, material=material)
    drawn = gl.Mesh(primitives=[primitive])
    # pyrender 0.1.45 computes Mesh.bounds with ``np.infty``, which numpy 2 removed;
    # the shadow pass needs the bounds, so give them from the trimesh we already have.
    drawn._bounds = np.array(mesh.bounds, dtype=float)
    return drawn


def _sun_pose() -> np.ndarray:
    """A light pose whose local -Z points along ``SUN_DIRECTION``."""
    back = -SUN_DIRECTION / np.linalg.norm(SUN_DIRECTION)
    right = np.cross([0.0, 1.0, 0.0], back)
    right /= np.linalg.norm(right)
    pose = np.eye(4)
    pose[:3, :3] = np.column_stack([right, np.cross(back, right), back])
    return pose


def _index_colour(index: int) -> np.ndarray:
    """Segmentation colour for an entity index: its value in little-endian RGB bytes."""
    return np.array([index & 0xFF, (index >> 8) & 0xFF, (index >> 16) & 0xFF], dtype=np.uint8)


def _decode_index(seg_colour: np.ndarray) -> np.ndarray:
    rgb = seg_colour[..., :3].astype(np.int32)
    return rgb[..., 0] | (rgb[..., 1] << 8) | (rgb[..., 2] << 16)


def _orthographic_depth(depth: np.ndarray, camera: Camera) -> np.ndarray:
    """Undo pyrender 0.1.45's perspective linearisation, which it also applies to
    orthographic cameras, and apply the orthographic (linear) one instead."""
    n, f = camera.znear, camera.zfar
    hit = depth > 0
    ndc = (f + n - 2.0 * n * f / depth[hit]) / (f - n)
    fixed = np.zeros_like(depth)
    fixed[hit] = n + (ndc + 1.0) / 2.0 * (f - n)
    return fixed


def _boxes(segmentation: np.ndarray, ids: list[str]) -> dict[str, list[int]]:
    boxes = {}
    for k, entity_id in enumerate(ids):
        rows, cols = np.nonzero(segmentation == k + 1)
        if len(rows):
            boxes[entity_id] = [int(cols.min()), int(rows.min()), int(cols.max()) + 1, int(rows.max()) + 1]
    return boxes


def _projected_box(entity: _Entity, camera: Camera) -> tuple[float, float, float, float] | None:
    """The entity's screen box clipped to the image (None when it is out of frame)."""
    corners = trimesh.bounds.corners(entity.mesh.bounds)
    world = trimesh.transform_points(corners, entity.pose)
    pixels, depth = camera.project(world)
    if np.any(depth <= 0):  # reaches behind the camera: assume it may cover anything
        return (0.0, 0.0, float(camera.width), float(camera.height))
    x0, y0 = np.maximum(pixels.min(axis=0), 0.0)
    x1, y1 = np.minimum(pixels.max(axis=0), [camera.width, camera.height])
    if x0 >= x1 or y0 >= y1:
        return None
    return (float(x0), float(y0), float(x1), float(y1))


def _disjoint_batches(boxes: list) -> list[list[int]]:
    """Group indices greedily so the boxes within a group do not overlap (a one-pixel
    margin covers rasterisation at shared edges); out-of-frame entities are skipped."""
    batches: list[list[int]] = []
    members: list[list[tuple]] = []
    for k, box in enumerate(boxes):
        if box is None:
            continue
        for batch, taken in zip(batches, members):
            if not any(_overlap(box, other) for other in taken):
                batch.append(k)
                taken.append(box)
                break
        else:
            batches.append([k])
            members.append([box])
    return batches


def _overlap(a, b, margin: float = 1.0) -> bool:
    return a[0] < b[2] + margin and b[0] < a[2] + margin and a[1] < b[3] + margin and b[1] < a[3] + margin


def _png(pixels: np.ndarray) -> bytes:
    buffer = io.BytesIO()
    Image.fromarray(pixels).save(buffer, format="PNG")
    return buffer.getvalue()


def _ids_json(ids: list[str]) -> bytes:
    return (json.dumps({str(k + 1): entity_id for k, entity_id in enumerate(ids)}, indent=1) + "\n").encode()
