"""Offscreen previews and ground truth images of a scene with pyrender.

``Renderer`` keeps one OpenGL context for many scenes (a dataset renders thousands);
``Renderer.render`` draws a scene from an automatic camera (``render.camera``) and
returns a ``RenderResult``: colour, depth, instance segmentation, per-object 2D boxes
and visible fractions. ``save_render`` writes them as PNGs (atomically) and
``render_metadata`` gives the part that goes into scene.json.

Drawn entities are objects (kind ``object``), junctions (a flat disc), paths (a
ribbon) and a room's doors and windows; groups have no body of their own. The ground
(a room's floor) and a room's walls are drawn as backdrop, not entities. Each entity's
index in ``RenderResult.ids`` plus one is its value in the segmentation image (0 is
background: sky, ground, floor, walls). Every door and window of a room is an entity
in every view, but one in a wall the view cuts away (``camera.walls_in_view``) is not
drawn: it has no pixels, so no box, and a visible fraction of 0.

A house (``scene.house``) is drawn as its rooms' floors and its walls as backdrop
(``render.house_meshes``; walls cut down as ``render.house_view`` says), and its doors
and windows as entities under the house's own ids (``door_3``, ``window_2``: an interior
door is one entity, not one per room), cut down as their walls are; a window whose wall
is cut below its sill is not drawn. Its objects are entities under their house ids
(``bedroom_2/bed_1``).

Which OpenGL backend draws, and with which pyrender classes, is ``render.gl_backend``'s
to choose.
"""

from __future__ import annotations

import io
import json
import math
import os
from collections.abc import Iterable
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path
from typing import Any

import numpy as np
import trimesh
from PIL import Image

from scenewright.core.atomic import write_atomic
from scenewright.core.errors import GenerationError
from scenewright.core.house import HouseOpening
from scenewright.core.room import Opening
from scenewright.core.scene import Scene

from .camera import Camera, frame_scene, walls_in_view
from .gl_backend import (
    backend_error,
    keep_display_on_delete,
    load_pyrender,
    pyrender_classes,
    release,
)
from .ground_truth import GL_TO_CV, camera_matrices, entity_boxes
from .house_meshes import house_opening_mesh, scene_ground, scene_walls
from .house_view import opening_height, opening_pose
from .meshes import (
    junction_mesh,
    object_transform,
    opening_mesh,
    opening_transform,
    path_mesh,
    shaped_mesh,
)

SKY = (0.62, 0.77, 0.92)
#: A room is drawn without its surroundings, in front of a plain light grey.
INDOOR_BACKGROUND = (0.9, 0.9, 0.9)
AMBIENT = (0.35, 0.35, 0.38)
SUN_INTENSITY = 2.0
#: Direction the sunlight travels: from high in the south-west towards the north-east,
#: so shadows fall away from the south-east camera but stay visible beside objects.
SUN_DIRECTION = np.array([0.45, -1.0, -0.35])
#: In a room the light comes from nearly overhead (as from a ceiling), from the same
#: side, so a wall's shadow is a narrow band along its foot rather than half the floor.
ROOM_LIGHT_DIRECTION = np.array([0.12, -1.0, -0.09])
#: ...and more light bounces about indoors: the walls, lit at a grazing angle by the
#: light from above, stay light.
ROOM_AMBIENT = (0.5, 0.5, 0.52)
#: Paths are drawn this much apart in height (by their order) so crossing ribbons do
#: not z-fight, which would make the segmentation at a crossing noisy.
PATH_STEP = 0.002
#: The drawn ground reaches this many times the scene extent, so the perspective view
#: shows grass, not sky, below the horizon.
GROUND_MARGIN = 3.0
#: The most GPU meshes of shared looks a renderer keeps between scenes (as many as the
#: per-process caches of looks hold).
SHARED_MESHES = 1024 + 256

#: The sun's shadow map has at most pyrender's own size, 2048 texels a side.
MAX_SHADOW_MAP = 2048


@dataclass
class RenderResult:
    """One rendered view of a scene.

    ``depth`` is the distance along the camera's viewing axis in metres (0 where only
    sky, or a room's background, is seen). ``boxes`` maps each entity seen in the image
    to its pixel box [x0, y0, x1, y1] (x1, y1 exclusive). ``visible`` maps every entity
    to the fraction of its in-frame silhouette not hidden by other entities (1.0
    unoccluded, 0.0 hidden, out of frame or not drawn); paths and junctions lie in one
    ground layer and do not count as hiding one another where they meet; the ground
    hides nothing, and what a wall hides is not part of the silhouette.
    """

    colour: np.ndarray
    depth: np.ndarray
    segmentation: np.ndarray
    ids: list[str]
    boxes: dict[str, list[int]]
    visible: dict[str, float]
    camera: dict[str, Any]
    #: H x W x 3 uint8 surface normals (``encode_render``'s ``normals``), when asked for.
    normals: np.ndarray | None = None
    #: The camera as matrices and each entity's 3D box (``render.ground_truth``).
    ground_truth: dict[str, Any] | None = None


@dataclass(frozen=True)
class _Drawable:
    """Triangle soup ready for the GPU: every triangle owns its three vertices, so
    each keeps its face's colour and normal (flat shading)."""

    positions: np.ndarray
    normals: np.ndarray
    colours: np.ndarray
    bounds: np.ndarray


@dataclass
class _Entity:
    """A scene entity: its id, its look, its local-to-world pose and its node (None for
    a door or window in a wall the view cuts away, which is not drawn)."""

    id: str
    drawable: _Drawable
    pose: np.ndarray
    flat: bool = False  # a path or junction: part of the ground layer
    drawn: bool = True
    node: Any = None
    shared: bool = False  # its drawable comes from a per-process cache (many scenes share it)


class Renderer:
    """An offscreen renderer of ``width`` x ``height`` pixels; reuse it across scenes.

    ``shadows`` turns on the sun's shadow map (costs one extra pass per frame).
    """

    def __init__(self, width: int = 640, height: int = 480, *, shadows: bool = True):
        self.width, self.height, self.shadows = int(width), int(height), shadows
        self._gl = load_pyrender()
        try:
            self._renderer = self._gl.OffscreenRenderer(self.width, self.height)
        except Exception as error:  # each backend fails in its own way; all mean the same
            raise backend_error(error) from None
        keep_display_on_delete(self._renderer)
        # pyrender's own renderer holds no OpenGL object until its first frame, so it can
        # be swapped for ours now, while the new context is current.
        self._classes = pyrender_classes(self._gl)
        self._renderer._renderer = self._classes.renderer(self.width, self.height)
        # One sun for every scene: pyrender keeps a light's shadow map on the GPU while
        # the light stays in use, instead of allocating a new one per scene.
        self._sun = self._gl.DirectionalLight(color=np.ones(3), intensity=SUN_INTENSITY)
        from OpenGL.GL import GL_FLOAT  # only now: the backend is chosen by load_pyrender

        side = shadow_map_size(self.width, self.height)
        self._sun.shadow_texture = self._gl.Texture(
            width=side, height=side, source_channels="D", data_format=GL_FLOAT
        )
        # The GPU meshes of shared drawables (id -> (drawable, mesh); the drawable is held
        # so its id stays its own): a mesh used by consecutive scenes stays uploaded.
        self._shared_meshes: dict[int, tuple[_Drawable, Any]] = {}

    def __enter__(self) -> Renderer:
        return self

    def __exit__(self, *exc_info) -> None:
        self.close()

    def close(self) -> None:
        """Release the OpenGL context (the renderer cannot be used afterwards)."""
        if self._renderer is not None:
            release(self._renderer)
            self._renderer = None

    def render(
        self,
        scene: Scene,
        view: str = "perspective",
        *,
        camera: Camera | None = None,
        normals: bool = False,
    ) -> RenderResult:
        """Render ``scene`` from the automatic ``view`` ("perspective" or "top"), or from
        ``camera`` (of this renderer's size; ``camera.aimed_camera``, say) when given;
        ``normals``: also draw the surface normals image (one more pass)."""
        if self._renderer is None:
            raise RuntimeError("this Renderer has been closed")
        if camera is not None and (camera.width, camera.height) != (self.width, self.height):
            raise ValueError(
                f"a {camera.width}x{camera.height} camera for a {self.width}x{self.height} renderer"
            )
        gl = self._gl
        camera = camera or frame_scene(scene, view, self.width, self.height)
        entities = _entities(scene, camera)
        world, merged, occluders = self._build(scene, camera, entities)

        _show_merged(merged, entities, True)
        flags = gl.RenderFlags.SHADOWS_DIRECTIONAL if self.shadows else gl.RenderFlags.NONE
        colour, depth = self._renderer.render(world, flags=flags)
        if camera.orthographic:
            depth = _orthographic_depth(depth, camera)
        normal_image = self._normals(world, scene, entities, camera, depth) if normals else None

        _show_merged(merged, entities, False)
        seg_map = _segmentation_map(entities, range(len(entities)), occluders)
        seg_colour, _ = self._renderer.render(world, flags=gl.RenderFlags.SEG, seg_node_map=seg_map)
        segmentation = _decode_index(seg_colour)

        ids = [entity.id for entity in entities]
        seen = np.bincount(segmentation.ravel(), minlength=len(ids) + 1)
        alone = self._alone_pixel_counts(world, entities, occluders, camera, seen)
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
            normals=normal_image,
            ground_truth={
                "camera": camera_matrices(camera),
                "objects": entity_boxes(scene, camera, visible),
            },
        )

    def _normals(
        self, world, scene: Scene, entities: list[_Entity], camera: Camera, depth: np.ndarray
    ) -> np.ndarray:
        """The surface normals image (``encode_render``): every surface drawn (the
        entities, the ground, the walls in view) in one mesh whose colours are its faces'
        normals in the OpenCV camera frame, drawn unlit; sky pixels 0."""
        parts = [entity for entity in entities if entity.drawn]
        backdrop = [_drawable(scene_ground(scene, margin=GROUND_MARGIN))]
        walls = scene_walls(scene, towards_viewer=camera.pose[:3, 2])
        if walls is not None:
            backdrop.append(_drawable(walls))
        surfaces = _merged(parts + [_Entity("", look, np.eye(4)) for look in backdrop])
        turn = (GL_TO_CV @ camera.extrinsics())[:3, :3]
        encoded = np.clip((surfaces.normals @ turn.T + 1.0) / 2.0, 0.0, 1.0)
        look = _Drawable(surfaces.positions, surfaces.normals, encoded, surfaces.bounds)
        shown = {id(node.mesh): node.mesh.is_visible for node in world.mesh_nodes}
        for node in world.mesh_nodes:
            node.mesh.is_visible = False
        node = world.add(_pyrender_mesh(self._gl, look))
        try:
            image, _ = self._renderer.render(world, flags=self._gl.RenderFlags.FLAT)
        finally:
            world.remove_node(node)
            for other in world.mesh_nodes:
                other.mesh.is_visible = shown.get(id(other.mesh), True)
        image = np.ascontiguousarray(image[..., :3])
        image[depth <= 0] = 0
        return image

    # -- scene building -------------------------------------------------------------
    #
    # pyrender's cost is per drawn primitive (a dozen uniforms set from Python, the
    # lights bound again), in the colour pass and again in the shadow pass, and a
    # village has a hundred entities. They all share one matte material, so the colour
    # and shadow passes draw them as one mesh in world coordinates (``_merged``). The
    # segmentation passes need one node per entity, each in its own index colour: the
    # frame holds both, and each pass shows only its own (``_show``). One pyrender
    # scene rather than two, because pyrender drops from the GPU every mesh that the
    # scene it draws lacks: the entities' meshes, most of them shared with the scenes
    # before, stay uploaded.

    def _build(self, scene: Scene, camera: Camera, entities: list[_Entity]):
        """The pyrender scene of a frame, its merged entities' mesh (None if nothing is
        drawn) and the nodes that hide what is behind them: a room's walls in view.

        The walls are backdrop like the ground, not entities (no index, box or visible
        fraction), but unlike the ground they can stand in front of an entity (a wall's
        lintel over its door, seen from above), so the segmentation passes draw them
        too, as background. Sets each drawn entity's ``node``."""
        gl = self._gl
        indoors = scene.room is not None or scene.house is not None
        background = INDOOR_BACKGROUND if indoors else SKY
        ambient = ROOM_AMBIENT if indoors else AMBIENT
        world = self._classes.scene(bg_color=(*background, 1.0), ambient_light=ambient)
        world.add(_pyrender_mesh(gl, _drawable(scene_ground(scene, margin=GROUND_MARGIN))))
        occluders = []
        walls = scene_walls(scene, towards_viewer=camera.pose[:3, 2])
        if walls is not None:
            occluders.append(world.add(_pyrender_mesh(gl, _drawable(walls))))
        drawn = [entity for entity in entities if entity.drawn]
        merged = _pyrender_mesh(gl, _merged(drawn)) if drawn else None
        if merged is not None:
            world.add(merged)
        uploaded: dict[int, Any] = {}  # entities that look alike share one GPU mesh
        for entity in drawn:
            key = id(entity.drawable)
            if key not in uploaded:
                look = entity.drawable
                uploaded[key] = (
                    self._shared_mesh(look) if entity.shared else _pyrender_mesh(gl, look)
                )
            entity.node = _posed_node(gl, uploaded[key], entity.pose, entity.id)
            world.add_node(entity.node)

        if camera.orthographic:
            lens = gl.OrthographicCamera(
                camera.xmag, camera.ymag, znear=camera.znear, zfar=camera.zfar
            )
        else:
            lens = gl.PerspectiveCamera(
                camera.yfov,
                aspectRatio=camera.width / camera.height,
                znear=camera.znear,
                zfar=camera.zfar,
            )
        world.add(lens, pose=camera.pose)
        world.add(self._sun, pose=sun_pose(ROOM_LIGHT_DIRECTION if indoors else SUN_DIRECTION))
        return world, merged, occluders

    def _shared_mesh(self, drawable: _Drawable):
        """The GPU mesh of a drawable many scenes share, made once per renderer (the
        cache is emptied when it outgrows the drawables' own)."""
        key = id(drawable)
        if key not in self._shared_meshes:
            if len(self._shared_meshes) >= SHARED_MESHES:
                self._shared_meshes.clear()
            self._shared_meshes[key] = (drawable, _pyrender_mesh(self._gl, drawable))
        return self._shared_meshes[key][1]

    def _alone_pixel_counts(
        self, world, entities: list[_Entity], occluders: list, camera: Camera, seen: np.ndarray
    ) -> np.ndarray:
        """How many pixels each entity covers when drawn alone.

        "Alone" means without the other entities (the walls, ``occluders``, stay, as
        in the image); for paths and junctions, without the objects but with the other
        paths and junctions, since they share one layer on the ground and cover one
        another only where they meet, as they do in the image. An entity that nothing
        can hide (no nearer entity's screen box overlaps its own) covers alone what it
        covers in the full image (``seen``); so does one that is not drawn (none). The
        others are drawn in extra segmentation passes: one for the ground layer, and a
        few for the rest, each holding entities whose screen boxes do not overlap (so
        they cannot hide one another). Every count is exact.
        """
        counts = np.asarray(seen[1:], dtype=np.int64).copy()
        boxes, near, far = _screen_extents(entities, camera)
        boxes[[not entity.drawn for entity in entities]] = 0.0  # no pixels: overlaps nothing
        overlap = _overlaps(boxes)
        may_hide = overlap & (near[:, None] < far[None, :])  # [j, k]: j may be in front of k
        np.fill_diagonal(may_hide, False)
        hidden_maybe = may_hide.any(axis=0) & (boxes[:, 0] < boxes[:, 2])
        flat = np.array([entity.flat for entity in entities], dtype=bool)
        batches = _disjoint_batches(np.flatnonzero(hidden_maybe & ~flat), boxes, overlap)
        if np.any(hidden_maybe & flat):
            batches.append(np.flatnonzero(flat).tolist())
        for batch in batches:
            seg_map = _segmentation_map(entities, batch, occluders)
            seg_colour, _ = self._renderer.render(
                world, flags=self._gl.RenderFlags.SEG, seg_node_map=seg_map
            )
            pixels = np.bincount(_decode_index(seg_colour).ravel(), minlength=len(entities) + 1)
            counts[batch] = pixels[np.asarray(batch) + 1]
        return counts


def shadow_map_size(width: int, height: int) -> int:
    """Texels a side of the sun's shadow map for a ``width`` x ``height`` image: the
    power of two that gives about one texel per image pixel (the map spans the drawn
    ground, ``GROUND_MARGIN`` times the scene, which the image about fills), at most
    ``MAX_SHADOW_MAP``. A 256x256 dataset image gets 1024 rather than pyrender's 2048,
    whose rasterizing a software OpenGL pays for and which adds nothing seen at that
    size."""
    needed = GROUND_MARGIN * max(width, height)
    return int(min(MAX_SHADOW_MAP, 2 ** math.ceil(math.log2(max(needed, 1.0)))))


def _entities(scene: Scene, camera: Camera) -> list[_Entity]:
    """The scene's entities in ``RenderResult.ids`` order: objects and junctions, paths,
    then a room's doors and windows (those in a wall the view cuts away not drawn);
    a degenerate path (all its points in one place) has no triangles and is left out."""
    entities: list[_Entity] = []
    for obj in scene.objects:
        if obj.kind == "object":
            look = _object_drawable(obj.shape, obj.mesh, tuple(obj.size), tuple(obj.colour))
            entities.append(_Entity(obj.id, look, object_transform(obj), shared=True))
        elif obj.kind == "junction":
            lifted = object_transform(obj)
            lifted[1, 3] += PATH_STEP * len(scene.paths)  # above every path ribbon
            entities.append(_Entity(obj.id, _drawable(junction_mesh(obj)), lifted, flat=True))
    for order, scene_path in enumerate(scene.paths):
        lifted = np.eye(4)
        lifted[1, 3] = PATH_STEP * order
        entities.append(_Entity(scene_path.id, _drawable(path_mesh(scene_path)), lifted, flat=True))
    if scene.room is not None:
        in_view = {wall.id for wall in walls_in_view(scene.room, camera.pose[:3, 2])}
        for opening in scene.room.openings:
            look = _opening_drawable(opening.kind, opening.width, opening.height, opening.sill)
            pose = opening_transform(scene.room, opening)
            entities.append(
                _Entity(opening.id, look, pose, drawn=opening.wall in in_view, shared=True)
            )
    entities = [entity for entity in entities if len(entity.drawable.positions)]
    if scene.house is not None:
        towards = camera.pose[:3, 2]
        for opening in scene.house.openings:
            height = opening_height(scene.house, opening, towards)
            # A window whose wall is cut below its sill is an entity still, not drawn.
            drawn = opening.sill < height - 1e-9
            look = _house_opening_drawable(opening, height if drawn else None)
            pose = opening_pose(scene.house, opening)
            entities.append(_Entity(opening.id, look, pose, drawn=drawn, shared=True))
    return entities


def _show_merged(merged, entities: list[_Entity], shown: bool) -> None:
    """Show the ``merged`` mesh of the entities (colour and shadow passes) or, if not
    ``shown``, their own meshes instead (segmentation passes)."""
    if merged is not None:
        merged.is_visible = shown
    for entity in entities:
        if entity.node is not None:
            entity.node.mesh.is_visible = not shown


def _merged(entities: list[_Entity]) -> _Drawable:
    """The entities' triangles in world coordinates as one drawable (their poses are
    rigid: rotation and translation only, so normals turn with the rotation)."""
    positions, normals = [], []
    for entity in entities:
        rotation, offset = entity.pose[:3, :3], entity.pose[:3, 3]
        positions.append(entity.drawable.positions @ rotation.T + offset)
        normals.append(entity.drawable.normals @ rotation.T)
    points = np.concatenate(positions)
    return _Drawable(
        points,
        np.concatenate(normals),
        np.concatenate([entity.drawable.colours for entity in entities]),
        np.array([points.min(axis=0), points.max(axis=0)]),
    )


def save_render(
    result: RenderResult, directory: str | os.PathLike, *, stem: str = "preview"
) -> dict[str, Path]:
    """Write a render's images and id map into ``directory``; return the paths by kind.

    File names and encodings are those of ``encode_render``.
    """
    folder = Path(directory)
    folder.mkdir(parents=True, exist_ok=True)
    paths = {}
    for kind, (name, data) in encode_render(result, stem=stem).items():
        paths[kind] = write_atomic(folder / name, data)
    return paths


#: What ``encode_render`` can encode, in the order it returns them (``normals`` only
#: for a render that made them, ``Renderer.render(normals=True)``).
RENDER_KINDS = (
    "colour",
    "depth",
    "depth_metres",
    "depth_scale",
    "segmentation",
    "ids",
    "normals",
    "ground_truth",
)
#: The 16-bit depth PNG's unit: millimetres while the farthest depth fits.
DEPTH_UNIT = 0.001


def encode_render(
    result: RenderResult, *, stem: str = "preview", kinds: Iterable[str] = RENDER_KINDS
) -> dict[str, tuple[str, bytes]]:
    """A render's files as (file name, bytes) by kind, for writers that store them
    elsewhere than a folder (an archive, a dataset shard); only the ``kinds`` asked for
    are encoded (PNG encoding is a good part of the cost of a small image).

    ``colour``: ``{stem}.png`` (RGB). ``depth``: ``{stem}_depth.png``, 16-bit, in units
    of ``depth_unit(result.depth)`` metres (millimetres unless the farthest depth is over
    65.535 m; 0 = sky), never clipped. ``depth_metres``: ``{stem}_depth.npy``, the depth
    buffer itself, float32 metres (numpy's ``.npy``). ``depth_scale``:
    ``{stem}_depth.json``, ``{"metres_per_unit": ...}`` of the PNG. ``segmentation``:
    ``{stem}_seg.png``, 16-bit entity indices (0 = background). ``ids``:
    ``{stem}_ids.json`` mapping each index to its entity id. ``normals``:
    ``{stem}_normals.png``, RGB, each surface's normal in the OpenCV camera frame as
    ``(n + 1) / 2 * 255`` (0, 0, 0 = sky). ``ground_truth``: ``{stem}_3d.json``, the
    camera as matrices and each entity's pose and 3D box (``render.ground_truth``).
    """
    asked = set(kinds)
    if "segmentation" in asked and len(result.ids) > 65535:
        raise GenerationError(f"{len(result.ids)} entities do not fit a 16-bit segmentation image")
    files = {}
    for kind in (kind for kind in RENDER_KINDS if kind in asked):
        if kind == "colour":
            files[kind] = (f"{stem}.png", _png(result.colour))
        elif kind == "depth":
            units = np.round(result.depth * (1000.0 / _depth_millimetres(result.depth)))
            files[kind] = (f"{stem}_depth.png", _png(np.clip(units, 0, 65535).astype(np.uint16)))
        elif kind == "depth_metres":
            files[kind] = (f"{stem}_depth.npy", _npy(result.depth.astype(np.float32)))
        elif kind == "depth_scale":
            scale = {"metres_per_unit": depth_unit(result.depth), "sky": 0}
            files[kind] = (f"{stem}_depth.json", (json.dumps(scale) + "\n").encode())
        elif kind == "segmentation":
            files[kind] = (f"{stem}_seg.png", _png(result.segmentation.astype(np.uint16)))
        elif kind == "ids":
            files[kind] = (f"{stem}_ids.json", _ids_json(result.ids))
        elif kind == "normals" and result.normals is not None:
            files[kind] = (f"{stem}_normals.png", _png(result.normals))
        elif kind == "ground_truth" and result.ground_truth is not None:
            text = json.dumps(result.ground_truth, indent=1) + "\n"
            files[kind] = (f"{stem}_3d.json", text.encode())
    return files


def depth_unit(depth: np.ndarray) -> float:
    """Metres per unit of the 16-bit depth PNG: ``DEPTH_UNIT`` (a millimetre) while the
    farthest depth fits 65 535 of them, else the smallest whole number of millimetres
    that fits it, so no pixel is clipped."""
    return round(_depth_millimetres(depth) * DEPTH_UNIT, 6)


def _depth_millimetres(depth: np.ndarray) -> int:
    farthest = float(depth.max()) if depth.size else 0.0
    return max(1, math.ceil(farthest / (65535 * DEPTH_UNIT) - 1e-9))


def render_metadata(result: RenderResult) -> dict[str, Any]:
    """scene.json's ``render`` value: the camera and, per drawn entity, its pixel box
    (null when not seen) and visible fraction."""
    return {
        "camera": result.camera,
        "objects": {
            entity_id: {
                "bbox": result.boxes.get(entity_id),
                "visible": round(result.visible[entity_id], 4),
            }
            for entity_id in result.ids
        },
    }


# -- helpers -------------------------------------------------------------------------


@lru_cache(maxsize=1024)
def _object_drawable(
    shape: str | None, mesh_file: str | None, size: tuple, colour: tuple
) -> _Drawable:
    """An object's look, built once per process: a dataset draws the same catalog
    entries thousands of times, and builders are pure functions of these arguments."""
    return _drawable(shaped_mesh(shape, mesh_file, size, colour))


@lru_cache(maxsize=256)
def _house_opening_drawable(opening: HouseOpening, height: float | None) -> _Drawable:
    """A house's door or window in its frame, cut down to ``height`` (None: whole),
    built once per process."""
    return _drawable(house_opening_mesh(opening, height))


@lru_cache(maxsize=256)
def _opening_drawable(kind: str, width: float, height: float, sill: float) -> _Drawable:
    """A door's or window's look in its opening's frame, built once per process."""
    return _drawable(opening_mesh(Opening("", kind, "", 0.0, width, height, sill)))


def _segmentation_map(entities: list[_Entity], indices, occluders: list) -> dict:
    """pyrender's ``seg_node_map`` for a segmentation pass: the drawn entities among
    ``indices`` in their index colours, the ``occluders`` in the background's (0), so
    what they hide is hidden in segmentation as in colour."""
    seg_map = {node: _index_colour(0) for node in occluders}
    seg_map.update({entities[k].node: _index_colour(k + 1) for k in indices if entities[k].drawn})
    return seg_map


def _drawable(mesh: trimesh.Trimesh) -> _Drawable:
    arrays = (
        mesh.vertices[mesh.faces].reshape(-1, 3),
        np.repeat(mesh.face_normals, 3, axis=0),
        np.repeat(mesh.visual.face_colors, 3, axis=0),
        np.array(mesh.bounds, dtype=float),
    )
    for array in arrays:
        array.setflags(write=False)  # shared through the cache
    return _Drawable(*arrays)


def _pyrender_mesh(gl, drawable: _Drawable):
    """A pyrender mesh of one flat-shaded primitive on a matte, non-metal material
    (pyrender's ``from_trimesh`` drops colours when given a material, and otherwise
    picks a blended, metallic one)."""
    material = gl.MetallicRoughnessMaterial(
        baseColorFactor=(1.0, 1.0, 1.0, 1.0), metallicFactor=0.0, roughnessFactor=0.9
    )
    primitive = gl.Primitive(
        positions=drawable.positions,
        normals=drawable.normals,
        color_0=drawable.colours,
        material=material,
    )
    mesh = gl.Mesh(primitives=[primitive])
    # pyrender 0.1.45 computes Mesh.bounds with ``np.infty``, which numpy 2 removed;
    # the shadow pass needs the bounds, so give them from the trimesh we already have.
    mesh._bounds = drawable.bounds.copy()
    return mesh


def _posed_node(gl, mesh, pose: np.ndarray, name: str):
    """A pyrender node of ``mesh`` at ``pose`` (4, 4), the very node ``Scene.add`` makes.

    pyrender turns a node's matrix into a quaternion and back (through trimesh, slowly),
    and draws with the matrix that comes back; that part
    depends on the rotation only, and entities share a few rotations (most villages'
    objects stand square), so it is computed once per rotation (``_node_rotation``)."""
    quaternion, scale, rotation_scale = _node_rotation(gl, pose[:3, :3].tobytes())
    node = gl.Node(name=name, mesh=mesh, rotation=quaternion, scale=scale, translation=pose[:3, 3])
    translation = np.eye(4)
    translation[:3, 3] = node.translation
    node._matrix = translation.dot(rotation_scale)  # what pyrender's Node.matrix computes from them
    return node


@lru_cache(maxsize=4096)
def _node_rotation(gl, rotation: bytes) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """pyrender's quaternion (4,) and scale (3,) of a node whose matrix has this
    rotation part (3, 3 float64 bytes), and the product of their matrices (4, 4), as
    pyrender's ``Node`` computes them."""
    matrix = np.eye(4)
    matrix[:3, :3] = np.frombuffer(rotation, dtype=float).reshape(3, 3)
    node = gl.Node(matrix=matrix)
    rotation_matrix, scale_matrix = np.eye(4), np.eye(4)
    rotation_matrix[:3, :3] = gl.Node._r_from_q(node.rotation)
    scale_matrix[:3, :3] = np.diag(node.scale)
    arrays = (node.rotation, node.scale, rotation_matrix.dot(scale_matrix))
    for array in arrays:
        array.setflags(write=False)  # shared through the cache
    return arrays


def sun_pose(direction: np.ndarray) -> np.ndarray:
    """A light pose whose local -Z points along ``direction`` (3,), where the light travels
    (as pyrender's and glTF's directional lights shine)."""
    back = -direction / np.linalg.norm(direction)
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
    """Pixel box of each entity seen, from one sweep over the labelled pixels."""
    rows, cols = np.nonzero(segmentation)
    labels = segmentation[rows, cols]
    count = len(ids) + 1
    lo_x, lo_y = np.full(count, np.iinfo(np.int64).max), np.full(count, np.iinfo(np.int64).max)
    hi_x, hi_y = np.full(count, -1), np.full(count, -1)
    np.minimum.at(lo_x, labels, cols)
    np.minimum.at(lo_y, labels, rows)
    np.maximum.at(hi_x, labels, cols)
    np.maximum.at(hi_y, labels, rows)
    return {
        entity_id: [int(lo_x[k]), int(lo_y[k]), int(hi_x[k]) + 1, int(hi_y[k]) + 1]
        for k, entity_id in enumerate(ids, start=1)
        if hi_x[k] >= 0
    }


def _screen_extents(
    entities: list[_Entity], camera: Camera
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Each entity's screen box (N, 4) clipped to the image (empty, x0 >= x1, when out
    of frame) and its nearest and farthest depth, from its bounding box's corners
    (projected all at once: a village has a hundred entities per frame)."""
    count = len(entities)
    if not count:
        return np.zeros((0, 4)), np.zeros(0), np.zeros(0)
    local = np.stack(
        [trimesh.bounds.corners(entity.drawable.bounds) for entity in entities]
    )  # (N, 8, 3)
    poses = np.stack([entity.pose for entity in entities])
    world = np.einsum("nij,nkj->nki", poses[:, :3, :3], local) + poses[:, None, :3, 3]
    with np.errstate(
        divide="ignore", invalid="ignore"
    ):  # corners behind the camera: replaced below
        pixels, depth = camera.project(world.reshape(-1, 3))
    pixels, depth = pixels.reshape(count, 8, 2), depth.reshape(count, 8)
    near, far = depth.min(axis=1), depth.max(axis=1)
    limit = np.array([camera.width, camera.height], dtype=float)
    boxes = np.column_stack(
        [np.maximum(pixels.min(axis=1), 0.0), np.minimum(pixels.max(axis=1), limit)]
    )
    behind = near <= 0  # reaches behind the camera: it may cover anything
    boxes[behind] = [0.0, 0.0, *limit]
    near[behind] = -np.inf
    return boxes, near, far


def _overlaps(boxes: np.ndarray, margin: float = 1.0) -> np.ndarray:
    """[j, k]: the boxes of j and k overlap or lie within ``margin`` pixels (which
    covers rasterisation at shared edges). Empty boxes overlap nothing."""
    x0, y0, x1, y1 = (boxes[:, i] for i in range(4))
    apart = (
        (x0[:, None] >= x1[None, :] + margin)
        | (x0[None, :] >= x1[:, None] + margin)
        | (y0[:, None] >= y1[None, :] + margin)
        | (y0[None, :] >= y1[:, None] + margin)
    )
    present = (x0 < x1) & (y0 < y1)
    return ~apart & present[:, None] & present[None, :]


def _disjoint_batches(
    indices: np.ndarray, boxes: np.ndarray, overlap: np.ndarray
) -> list[list[int]]:
    """Split ``indices`` into groups whose boxes do not overlap, greedily, largest box
    first (big boxes constrain most; placing them first needs fewer groups)."""
    area = (boxes[:, 2] - boxes[:, 0]) * (boxes[:, 3] - boxes[:, 1])
    order = sorted(indices.tolist(), key=lambda k: (-area[k], k))
    batches: list[list[int]] = []
    for k in order:
        for batch in batches:
            if not overlap[k, batch].any():
                batch.append(k)
                break
        else:
            batches.append([k])
    return [sorted(batch) for batch in batches]


def _png(pixels: np.ndarray) -> bytes:
    buffer = io.BytesIO()
    Image.fromarray(pixels).save(buffer, format="PNG")
    return buffer.getvalue()


def _npy(array: np.ndarray) -> bytes:
    buffer = io.BytesIO()
    np.save(buffer, array, allow_pickle=False)
    return buffer.getvalue()


def _ids_json(ids: list[str]) -> bytes:
    return (
        json.dumps({str(k + 1): entity_id for k, entity_id in enumerate(ids)}, indent=1) + "\n"
    ).encode()
