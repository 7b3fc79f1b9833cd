"""Export a laid-out scene as a binary glTF (GLB) file, written atomically.

One named node per object, junction and path (node name = its id; id, type, kind and
noun in the node's ``extras``), groups as parent nodes of their members so a 3D tool
shows the scene's hierarchy, and optionally the ground (a room's floor). A room adds
one node per wall (``wall_1``, ...: every wall, with its doors' and windows' holes cut;
extras id, kind "wall" and side) and per door and window (``door_1``, ``window_1``, ...;
extras id, kind "door" or "window" and the wall it is in). Node transforms carry the
poses, meshes stay in their local frame, so a tool can move an object as a whole.
Colours are per-vertex on unshared vertices (flat shaded, one colour per face). A scene
with nothing to draw (no objects, or only groups) is a valid GLB with no meshes.
"""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np
import trimesh
from trimesh.exchange.gltf import export_glb as trimesh_glb

from scenewright.core.atomic import write_atomic
from scenewright.core.room import Room
from scenewright.core.scene import Scene, SceneObject, ScenePath

from .meshes import (
    ground_mesh,
    junction_mesh,
    object_mesh,
    object_transform,
    opening_mesh,
    opening_transform,
    path_mesh,
    wall_mesh,
    wall_transform,
)

#: Name of the ground's node when the ground is exported.
GROUND_NODE = "ground"


def export_glb(scene: Scene, path: str | os.PathLike, *, ground: bool = False) -> Path:
    """Write ``scene`` to ``path`` as GLB and return the path."""
    data = glb_bytes(scene, ground=ground)
    target = Path(path)
    target.parent.mkdir(parents=True, exist_ok=True)
    return write_atomic(target, data)


def glb_bytes(scene: Scene, *, ground: bool = False) -> bytes:
    """The GLB encoding of ``scene`` (see the module docstring for its structure)."""
    return _without_empty_bin(trimesh_glb(build_trimesh_scene(scene, ground=ground)))


def build_trimesh_scene(scene: Scene, *, ground: bool = False) -> trimesh.Scene:
    """The scene as a ``trimesh.Scene`` with one named node per entity."""
    out = trimesh.Scene()
    groups = {o.id: o for o in scene.objects if o.kind == "group"}
    world_of: dict[str, np.ndarray] = {}  # group id -> its node's world transform

    def attach(
        node_name: str, entity_parent: str | None, world: np.ndarray, extras: dict, mesh=None
    ) -> None:
        parent = entity_parent if entity_parent in groups else None
        local = world if parent is None else np.linalg.inv(world_of[parent]) @ world
        if mesh is None or not len(mesh.faces):  # a group, or a degenerate path: node only
            out.graph.update(
                node_name, frame_from=parent or out.graph.base_frame, matrix=local, metadata=extras
            )
        else:
            out.add_geometry(
                _flat_shaded(mesh),
                node_name=node_name,
                geom_name=node_name,
                parent_node_name=parent,
                transform=local,
                metadata=extras,
            )

    for group in _parents_first(list(groups.values()), groups):
        world_of[group.id] = _translation(group.position)
        attach(group.id, group.parent, world_of[group.id], _extras(group))
    for obj in scene.objects:
        if obj.kind == "object":
            attach(obj.id, obj.parent, object_transform(obj), _extras(obj), object_mesh(obj))
        elif obj.kind == "junction":
            attach(obj.id, obj.parent, object_transform(obj), _extras(obj), junction_mesh(obj))
    for scene_path in scene.paths:
        attach(
            scene_path.id,
            scene_path.parent,
            np.eye(4),
            _path_extras(scene_path),
            path_mesh(scene_path),
        )
    if scene.room is not None:
        for node_name, world, extras, mesh in _room_parts(scene.room):
            attach(node_name, None, world, extras, mesh)
    if ground:
        attach(GROUND_NODE, None, np.eye(4), {"kind": "ground"}, ground_mesh(scene))
    return out


def _room_parts(room: Room):
    """(node name, world transform, extras, mesh in its local frame) for each wall, door
    and window of ``room``, in that order."""
    for wall in room.walls:
        world = wall_transform(wall)
        mesh = wall_mesh(room, wall)  # built in world coordinates: bring it into the wall's frame
        mesh.apply_transform(np.linalg.inv(world))
        yield wall.id, world, {"id": wall.id, "kind": "wall", "side": wall.side}, mesh
    for opening in room.openings:
        extras = {"id": opening.id, "kind": opening.kind, "wall": opening.wall}
        yield opening.id, opening_transform(room, opening), extras, opening_mesh(opening)


def _without_empty_bin(glb: bytes) -> bytes:
    """``glb`` without a trailing BIN chunk of no bytes (what a scene without meshes
    gets), which the glTF specification says to leave out."""
    end_of_json = 20 + int.from_bytes(glb[12:16], "little")  # 12-byte header, then the JSON chunk
    if glb[end_of_json:] != (0).to_bytes(4, "little") + b"BIN\x00":
        return glb
    return glb[:8] + end_of_json.to_bytes(4, "little") + glb[12:end_of_json]


def _extras(obj: SceneObject) -> dict:
    extras = {"id": obj.id, "type": obj.type, "kind": obj.kind, "noun": obj.noun}
    if obj.style is not None:
        extras["style"] = obj.style
    return extras


def _path_extras(scene_path: ScenePath) -> dict:
    return {"id": scene_path.id, "type": scene_path.type, "kind": "path", "noun": scene_path.noun}


def _parents_first(groups: list[SceneObject], by_id: dict[str, SceneObject]) -> list[SceneObject]:
    """Groups ordered so every group comes after the group that contains it."""

    def depth(group: SceneObject) -> int:
        steps, parent = 0, group.parent
        while parent in by_id:
            steps, parent = steps + 1, by_id[parent].parent
        return steps

    return sorted(groups, key=depth)  # stable: scene order within one depth


def _translation(position) -> np.ndarray:
    matrix = np.eye(4)
    matrix[:3, 3] = position
    return matrix


def _flat_shaded(mesh: trimesh.Trimesh) -> trimesh.Trimesh:
    """A copy whose faces own their vertices, so per-face colours survive as glTF's
    per-vertex COLOR_0 and normals stay flat."""
    flat = mesh.copy()
    flat.unmerge_vertices()
    return flat
