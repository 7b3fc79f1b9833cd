"""3D ground truth of one rendered view: the camera as matrices in both conventions, and
each drawn entity's pose and 3D box in the camera's frame with its visible share.

Conventions (``docs/render.md``, "3D ground truth"):

- **OpenCV** camera frame: x right, y down, z forward (into the scene); a pixel
  (u right, v down, the top-left pixel covering [0, 1) x [0, 1)) of a point (x, y, z)
  is ``K @ (x / z, y / z, 1)`` for the perspective camera, the distortion-free pinhole
  model (no lens distortion); ``K = [[fx, 0, cx], [0, fy, cy], [0, 0, 1]]``. An
  orthographic camera's K is affine: ``K @ (x, y, 1)``, fx and fy in pixels per metre.
- **OpenGL** camera frame (glTF's, pyrender's, Blender's): x right, y up, looking down
  -z. The two differ by ``diag(1, -1, -1)``.

``world_to_camera_opencv`` and ``world_to_camera_opengl`` (4x4) take world points
(metres, Y up) into those frames; ``camera_to_world_opengl`` is the camera's pose (its
node in the GLB).

Per entity (objects, junctions, doors and windows, a house's as a room's: the
entities with a body in
``RenderResult.ids``; paths have no box of their own and are left out): ``rotation``
(3x3) and ``translation`` (3) take the entity's local frame (base centre origin, +Y up,
as ``meshes.object_transform``) into the OpenCV camera frame; ``size`` [w, h, d] along
its local axes; ``corners`` (8 x 3) of its box in the OpenCV camera frame, in the order
of ``BOX_CORNERS``; ``visible``: the share of its in-frame silhouette the image shows
(``RenderResult.visible``).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from scenewright.core.room import WALL_THICKNESS
from scenewright.core.scene import Scene

from .camera import Camera

#: OpenGL camera axes -> OpenCV's.
GL_TO_CV = np.diag([1.0, -1.0, -1.0, 1.0])
#: The box corners' order: signs of (x, y, z) from the box's centre, y from the base
#: (0) to the top (1): the four base corners counter-clockwise seen from above
#: (local x right, z towards the viewer), then the four top ones.
BOX_CORNERS = (
    (-1, 0, -1),
    (1, 0, -1),
    (1, 0, 1),
    (-1, 0, 1),
    (-1, 1, -1),
    (1, 1, -1),
    (1, 1, 1),
    (-1, 1, 1),
)


def camera_matrices(camera: Camera) -> dict[str, Any]:
    """K (OpenCV), the model and the extrinsics in both conventions, as plain lists."""
    k = camera.intrinsics() @ np.diag([1.0, -1.0, 1.0])  # camera.intrinsics takes (x, y, -z)
    world_to_gl = camera.extrinsics()
    return {
        "model": "orthographic" if camera.orthographic else "pinhole",
        "distortion": None,
        "K": _rounded(k),
        "world_to_camera_opencv": _rounded(GL_TO_CV @ world_to_gl),
        "world_to_camera_opengl": _rounded(world_to_gl),
        "camera_to_world_opengl": _rounded(camera.pose),
    }


def entity_boxes(scene: Scene, camera: Camera, visible: dict[str, float]) -> list[dict]:
    """The 3D box of each entity of ``visible`` that has a body, in ``visible``'s order,
    in the OpenCV camera frame (module docstring)."""
    world_to_cv = GL_TO_CV @ camera.extrinsics()
    bodies = _bodies(scene)
    boxes = []
    for entity_id, share in visible.items():
        if entity_id not in bodies:
            continue
        kind, local_to_world, size = bodies[entity_id]
        pose = world_to_cv @ local_to_world
        half = np.array([size[0] / 2.0, size[1], size[2] / 2.0])
        local = np.array(BOX_CORNERS, dtype=float) * half
        corners = local @ pose[:3, :3].T + pose[:3, 3]
        boxes.append(
            {
                "id": entity_id,
                "kind": kind,
                "rotation": _rounded(pose[:3, :3]),
                "translation": _rounded(pose[:3, 3]),
                "size": _rounded(np.asarray(size, dtype=float)),
                "corners": _rounded(corners),
                "visible": round(float(share), 4),
            }
        )
    return boxes


def _bodies(scene: Scene) -> dict[str, tuple[str, np.ndarray, list[float]]]:
    """Entity id -> (kind, local-to-world matrix, size) for everything with a body."""
    # Here, not at the top: render.views, which the dataset command's parent process
    # imports, needs only camera_matrices, and meshes brings trimesh, whose import
    # swallows a Ctrl-C that arrives during it.
    from .meshes import object_transform, opening_transform

    bodies = {
        obj.id: (obj.kind, object_transform(obj), list(obj.size))
        for obj in scene.objects
        if obj.kind in ("object", "junction")
    }
    if scene.room is not None:
        for opening in scene.room.openings:
            # The hole through the wall: sill to top, the wall's thickness behind its
            # inner face (a door or window stays within it).
            base = np.eye(4)
            base[1, 3], base[2, 3] = opening.sill, -WALL_THICKNESS / 2.0
            size = [opening.width, opening.height, WALL_THICKNESS]
            bodies[opening.id] = (opening.kind, opening_transform(scene.room, opening) @ base, size)
    if scene.house is not None:
        from .house_view import opening_pose, opening_wall

        for house_opening in scene.house.openings:
            index = opening_wall(scene.house, house_opening)
            thickness = scene.house.walls[index].thickness if index is not None else WALL_THICKNESS
            base = np.eye(4)
            base[1, 3], base[2, 3] = house_opening.sill, -thickness / 2.0
            size = [house_opening.width, house_opening.height, thickness]
            pose = opening_pose(scene.house, house_opening) @ base
            bodies[house_opening.id] = (house_opening.kind, pose, size)
    return bodies


def _rounded(array) -> list:
    """Plain nested lists rounded to 1e-9 (JSON-ready, no negative zeros)."""
    return (np.round(np.asarray(array, dtype=float), 9) + 0.0).tolist()
