"""Export a laid-out scene as a binary glTF (GLB) file, written atomically, that looks
in any viewer (Blender, Godot, three.js) as the preview does.

Nodes:

- one per object, junction and path (node name = its id; id, type, kind and noun in the
  node's ``extras``). What rests on something (a support relation: ``on``, ...) is that
  thing's child, so moving a desk in a 3D tool moves the lamp on it; the rest are
  children of their group (a parent node with no mesh), or at the top. A node whose
  parent is not its group records the group in ``extras["group"]``, and one resting on
  another records it in ``extras["on"]``;
- a room adds one node per wall (``wall_1``, ...: openings cut; extras id, kind "wall",
  side, and ``cutaway`` true for the walls the preview leaves out because they face
  away from its camera) and per door and window (extras id, kind, the wall it is in,
  ``cutaway`` as its wall); ``cutaway=True`` leaves those walls and openings out;
- a house (``scene.house``) has one node per room at the top (named by its room id,
  placed at the room's offset; extras id, kind "room", type, name) holding that room's
  objects (their ids ``bedroom_2/bed_1``), its walls, its doors and windows and its
  floor (``bedroom_2/floor``). Each wall of the house is one node (``wall_1``, ... in
  ``house.walls`` order, on its centre line; extras id, kind "wall", rooms, cutaway),
  under the first room it borders, so a wall two rooms share is there once; each door
  or window (the house's ids, ``door_3``; extras id, kind, rooms, open, wall, cutaway)
  is under its first room. ``cutaway`` marks what the preview cuts low
  (``render.house_view``); ``cutaway=True`` exports the walls and openings as cut;
- ``ground``: the room's floor (node ``floor``, extras kind "floor") or the outdoor
  ground (node ``ground``, kind "ground"), as large as the preview draws it;
- ``camera``: the preview's camera (scene.json's ``render.camera`` when the scene was
  rendered, else the automatic perspective view), node ``camera``;
- ``light``: the preview's sun as a KHR_lights_punctual directional light, node ``sun``.

Node transforms carry the poses (translation and rotation), meshes stay in their local
frame, so a tool moves an object as a whole. Each mesh has one PBR material per colour
(shared across the file) and per-vertex normals, flat as the preview shades. Paths and
junctions are lifted as the preview lifts them, so crossing ribbons do not z-fight, and
a ribbon is one layer of triangles (``render.ribbon``). A scene with nothing to draw is
a valid GLB with no meshes.
"""

from __future__ import annotations

import math
import os
from pathlib import Path
from typing import Any

import numpy as np

from scenewright.core import VERSION
from scenewright.core.atomic import write_atomic
from scenewright.core.frames import transform_matrix
from scenewright.core.house import House, in_room, room_of
from scenewright.core.relations import RELATIONS
from scenewright.core.room import Room
from scenewright.core.scene import Scene, SceneObject, ScenePath

from .camera import Camera, frame_scene, walls_in_view
from .gltf_file import Node, glb
from .house_meshes import house_opening_mesh, house_wall_mesh, room_floor
from .house_view import (
    opening_height,
    opening_pose,
    opening_wall,
    wall_heights,
    wall_name,
    wall_openings,
    wall_owner,
)
from .meshes import (
    ground_mesh,
    junction_mesh,
    object_transform,
    opening_mesh,
    opening_transform,
    shaped_mesh,
    wall_mesh,
    wall_transform,
)
from .offscreen import GROUND_MARGIN, PATH_STEP, ROOM_LIGHT_DIRECTION, SUN_DIRECTION, sun_pose
from .ribbon import ribbon_mesh

#: Name of the ground's node outdoors, and of a room's floor's.
GROUND_NODE = "ground"
FLOOR_NODE = "floor"
CAMERA_NODE = "camera"
SUN_NODE = "sun"
#: The preview's default size, for the camera of a scene that was never rendered.
DEFAULT_CAMERA_SIZE = (640, 480)
#: The sun's illuminance (lux): Blender takes it as its sun strength (W/m²), where
#: 3 lights the preview's colours about as the preview does with its ambient light.
SUN_LUX = 3.0


def export_glb(
    scene: Scene,
    path: str | os.PathLike,
    *,
    ground: bool = True,
    camera: bool = True,
    light: bool = True,
    cutaway: bool = False,
) -> Path:
    """Write ``scene`` to ``path`` as GLB and return the path (options as ``glb_bytes``)."""
    data = glb_bytes(scene, ground=ground, camera=camera, light=light, cutaway=cutaway)
    target = Path(path)
    target.parent.mkdir(parents=True, exist_ok=True)
    return write_atomic(target, data)


def glb_bytes(
    scene: Scene,
    *,
    ground: bool = True,
    camera: bool = True,
    light: bool = True,
    cutaway: bool = False,
) -> bytes:
    """The GLB encoding of ``scene`` (module docstring): with the ground (or floor), the
    preview's camera and its sun unless told otherwise; ``cutaway`` leaves out the walls
    the preview cuts away."""
    return glb(
        scene_nodes(scene, ground=ground, camera=camera, light=light, cutaway=cutaway),
        f"scenewright {VERSION}",
    )


def preview_camera(scene: Scene) -> Camera:
    """The camera of the scene's preview: the one recorded in scene.json's ``render``,
    else the automatic perspective view at the default size."""
    if scene.render and scene.render.get("camera"):
        return Camera.from_dict(scene.render["camera"])
    return frame_scene(scene, "perspective", *DEFAULT_CAMERA_SIZE)


def scene_nodes(
    scene: Scene,
    *,
    ground: bool = True,
    camera: bool = True,
    light: bool = True,
    cutaway: bool = False,
) -> list[Node]:
    """The top-level node trees of the scene's file (module docstring)."""
    view = preview_camera(scene)
    by_id = {obj.id: obj for obj in scene.objects}
    support = _supports(scene, by_id)
    nodes: dict[str, Node] = {}
    world: dict[str, np.ndarray] = {}
    order: list[str] = []
    for obj in scene.objects:
        if obj.kind == "group":
            world[obj.id] = _translation(obj.position)
            mesh = None
        elif obj.kind == "junction":
            world[obj.id] = object_transform(obj)
            mesh = junction_mesh(obj)
            mesh.apply_translation([0.0, PATH_STEP * len(scene.paths), 0.0])  # above every path
        elif obj.kind == "object":
            world[obj.id] = object_transform(obj)
            mesh = shaped_mesh(obj.shape, obj.mesh, tuple(obj.size), tuple(obj.colour))
        else:
            continue
        nodes[obj.id] = Node(obj.id, world[obj.id], _extras(obj, support), mesh)
        order.append(obj.id)
    for step, scene_path in enumerate(scene.paths):
        world[scene_path.id] = np.eye(4)
        mesh = ribbon_mesh(scene_path, lift=PATH_STEP * step)
        nodes[scene_path.id] = Node(scene_path.id, np.eye(4), _path_extras(scene_path), mesh)
        order.append(scene_path.id)

    roots: list[Node] = []
    for entity_id in order:
        parent = support.get(entity_id) or _group_of(entity_id, by_id, scene)
        if parent is not None and parent in nodes:
            nodes[entity_id].matrix = np.linalg.inv(world[parent]) @ world[entity_id]
            nodes[parent].children.append(nodes[entity_id])
        else:
            roots.append(nodes[entity_id])
    if scene.room is not None:
        roots += _room_nodes(scene.room, view, cutaway)
    if scene.house is not None:
        roots = _house_nodes(scene.house, roots, view, cutaway=cutaway, ground=ground)
    elif ground:
        name, kind = (FLOOR_NODE, "floor") if scene.room is not None else (GROUND_NODE, "ground")
        roots.append(
            Node(name, np.eye(4), {"kind": kind}, ground_mesh(scene, margin=GROUND_MARGIN))
        )
    if camera:
        roots.append(Node(CAMERA_NODE, view.pose, {"kind": "camera"}, camera=_gltf_camera(view)))
    if light:
        indoors = scene.room is not None or scene.house is not None
        direction = ROOM_LIGHT_DIRECTION if indoors else SUN_DIRECTION
        sun = {"name": SUN_NODE, "type": "directional", "color": [1.0, 1.0, 1.0]}
        sun["intensity"] = SUN_LUX
        roots.append(Node(SUN_NODE, sun_pose(direction), {"kind": "light"}, light=sun))
    return roots


def _supports(scene: Scene, by_id: dict[str, SceneObject]) -> dict[str, str]:
    """Object id -> the object it rests on (its first support relation), leaving out any
    that would close a loop (a hand-edited scene.json may hold one)."""
    support: dict[str, str] = {}
    for relation in scene.relations:
        label = relation.label
        if label not in RELATIONS or not RELATIONS[label].support:
            continue
        source, target = by_id.get(relation.source), by_id.get(relation.target)
        if source is None or target is None or source.id in support:
            continue
        if source.kind != "object" or target.kind != "object":
            continue
        below: str | None = target.id
        while below is not None and below != source.id:
            below = support.get(below)
        if below is None:
            support[source.id] = target.id
    return support


def _group_of(entity_id: str, by_id: dict[str, SceneObject], scene: Scene) -> str | None:
    if entity_id in by_id:
        parent = by_id[entity_id].parent
    else:
        parent = scene.path(entity_id).parent
    return parent if parent in by_id and by_id[parent].kind == "group" else None


def _room_nodes(room: Room, view: Camera, cutaway: bool) -> list[Node]:
    """A node per wall, door and window of ``room`` (module docstring)."""
    kept = {wall.id for wall in walls_in_view(room, view.pose[:3, 2])}
    nodes = []
    for wall in room.walls:
        if cutaway and wall.id not in kept:
            continue
        world = wall_transform(wall)
        mesh = wall_mesh(room, wall)  # built in world coordinates: bring it into the wall's frame
        mesh.apply_transform(np.linalg.inv(world))
        extras = {"id": wall.id, "kind": "wall", "side": wall.side, "cutaway": wall.id not in kept}
        nodes.append(Node(wall.id, world, extras, mesh))
    for opening in room.openings:
        if cutaway and opening.wall not in kept:
            continue
        extras = {
            "id": opening.id,
            "kind": opening.kind,
            "wall": opening.wall,
            "cutaway": opening.wall not in kept,
        }
        nodes.append(
            Node(opening.id, opening_transform(room, opening), extras, opening_mesh(opening))
        )
    return nodes


def _house_nodes(
    house: House, roots: list[Node], view: Camera, *, cutaway: bool, ground: bool
) -> list[Node]:
    """A node per room of ``house`` (module docstring) holding the top-level ``roots``
    of its objects, its walls, openings and floor; the roots of no room stay on top."""
    towards = view.pose[:3, 2]
    rooms: dict[str, Node] = {}
    for room in house.rooms:
        extras = {"id": room.id, "kind": "room", "type": room.type, "name": room.name}
        rooms[room.id] = Node(room.id, _translation([room.offset[0], 0.0, room.offset[1]]), extras)
    top: list[Node] = []
    for root in roots:
        owner = room_of(root.name)
        if owner in rooms:
            _adopt(rooms[owner], root, root.matrix)
        else:
            top.append(root)
    shown = wall_heights(house, towards)
    holes = wall_openings(house)
    for index, wall in enumerate(house.walls):
        height = shown[index] if cutaway else wall.height
        mesh = house_wall_mesh(house, index, height, holes[index])
        (sx, sz), (ex, ez) = wall.start, wall.end
        world = transform_matrix(
            (sx + ex) / 2.0, 0.0, (sz + ez) / 2.0, math.atan2(-(ez - sz), ex - sx)
        )
        mesh.apply_transform(np.linalg.inv(world))  # built in world coordinates
        name = wall_name(index)
        extras = {
            "id": name,
            "kind": "wall",
            "rooms": [room for room in wall.rooms if room is not None],
            "outside": wall.outside,
            "cutaway": shown[index] < wall.height,
        }
        _adopt(rooms[wall_owner(wall)], Node(name, world, extras, mesh), world)
    for opening in house.openings:
        height = opening_height(house, opening, towards)
        if cutaway and opening.sill >= height:
            continue  # its wall is cut below it
        extras = {
            "id": opening.id,
            "kind": opening.kind,
            "rooms": list(opening.rooms),
            "open": opening.open,
            "cutaway": height < opening.sill + opening.height,
        }
        index = opening_wall(house, opening)
        if index is not None:
            extras["wall"] = wall_name(index)
        mesh = house_opening_mesh(opening, height if cutaway else None)
        world = opening_pose(house, opening)
        _adopt(rooms[opening.rooms[0]], Node(opening.id, world, extras, mesh), world)
    if ground:
        for room in house.rooms:
            extras = {"kind": "floor", "room": room.id}
            floor = Node(
                in_room(room.id, FLOOR_NODE), np.eye(4), extras, room_floor(house, room.id)
            )
            _adopt(rooms[room.id], floor, np.eye(4))
    return list(rooms.values()) + top


def _adopt(parent: Node, child: Node, world: np.ndarray) -> None:
    """Make ``child`` (at ``world``) a child of ``parent`` (a top-level node)."""
    child.matrix = np.linalg.inv(parent.matrix) @ world
    parent.children.append(child)


def _gltf_camera(view: Camera) -> dict[str, Any]:
    if view.orthographic:
        return {
            "type": "orthographic",
            "orthographic": {
                "xmag": float(view.xmag),
                "ymag": float(view.ymag),
                "znear": float(view.znear),
                "zfar": float(view.zfar),
            },
        }
    return {
        "type": "perspective",
        "perspective": {
            "yfov": float(view.yfov),
            "aspectRatio": view.width / view.height,
            "znear": float(view.znear),
            "zfar": float(view.zfar),
        },
    }


def _extras(obj: SceneObject, support: dict[str, str]) -> dict:
    extras: dict[str, Any] = {"id": obj.id, "type": obj.type, "kind": obj.kind, "noun": obj.noun}
    if obj.style is not None:
        extras["style"] = obj.style
    if obj.id in support:
        extras["on"] = support[obj.id]
        if obj.parent is not None:
            extras["group"] = obj.parent
    return extras


def _path_extras(scene_path: ScenePath) -> dict:
    return {"id": scene_path.id, "type": scene_path.type, "kind": "path", "noun": scene_path.noun}


def _translation(position) -> np.ndarray:
    matrix = np.eye(4)
    matrix[:3, 3] = position
    return matrix
