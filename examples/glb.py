"""GLB files with one named node per object, as Blender (or ``scenewright export``) writes them.

Every node with a mesh is an object, except room parts. Its type and style come from
the node's name by the pattern ``TYPE[.STYLE][.NNN]``: ``desk.oak.001`` is a desk in
style oak, ``desk.001`` and ``desk`` a desk of no style (``.NNN``, Blender's counter
for copies, is dropped; so is a trailing ``_N``, scenewright's id counter). Type and
style are read in lower case, spaces as underscores (Blender names its copies
``Chair.001``; types are lower-case names everywhere else), so ``Dining Chair.002`` is
a dining_chair. The id is the node name; a mesh node without a name is refused, since
nothing would say what it is. A node's ``extras`` written by ``scenewright export`` (id, type, kind,
style) take precedence over its name.

Size is the mesh's bounds in the node's own frame times the node's scale, position the
base centre of those bounds taken to the world, yaw the node's rotation about +Y (glTF
is Y-up; Blender's exporter turns its Z-up into Y-up). A node tilted more than
``MAX_TILT_DEGREES`` off upright is refused. Nodes of type ``wall``, ``floor``,
``ground`` or ``ceiling`` (or extras kind wall, door, window, path, ground, floor) are the
room, not objects: walls make the room a rectangle (their inner bounding box), a floor
or ground gives the extent; otherwise the extent is the bounding box of the circles
round the objects' footprints (half their diagonal, so any turn stays inside) with
``MARGIN`` around it. The scene is moved so the extent is centred on the origin.
"""

from __future__ import annotations

import io
import math
import re

import numpy as np

from scenewright.core.errors import RoomError
from scenewright.core.room import Room
from scenewright.core.scene import Scene

from .example import ExampleError, ObjectRecord, example_scene
from .glb_check import checked_glb

#: Room parts by node type (without extras) and by extras kind (scenewright's export).
ROOM_TYPES = ("wall", "floor", "ground", "ceiling")
ROOM_KINDS = ("wall", "door", "window", "path", "ground", "floor", "junction", "group")
MAX_TILT_DEGREES = 5.0
#: Free floor (metres) around the objects when nothing gives the extent.
MARGIN = 0.5

_COUNTER = re.compile(r"(\.\d{3,}|_\d+)$")
_NAME = re.compile(r"[^A-Za-z0-9_.-]")


def parse_node_name(name: str) -> tuple[str, str | None]:
    """(type, style) of a node name ``TYPE[.STYLE][.NNN]``, in lower case."""
    base = _COUNTER.sub("", name.strip()) or name.strip()
    parts = [p for p in base.lower().split(".") if p]
    kind = _NAME.sub("_", parts[0]) if parts else "object"
    style = _NAME.sub("_", ".".join(parts[1:])) if len(parts) > 1 else None
    return kind, style


def read_glb(path: str, data: bytes, name: str) -> Scene:
    """The Scene of a GLB file's bytes (``path`` names it in errors)."""
    import trimesh

    order, extras = _nodes(path, data)
    try:
        loaded = trimesh.load(io.BytesIO(data), file_type="glb", force="scene")
    except Exception as error:  # trimesh raises many kinds on a broken file
        raise ExampleError(
            path, "", f"not a readable GLB file ({type(error).__name__}: {error})"
        ) from None
    assert isinstance(loaded, trimesh.Scene)  # force="scene" gives one
    records: list[ObjectRecord] = []
    walls: list[np.ndarray] = []
    floors: list[np.ndarray] = []
    for node, (transform, mesh) in sorted(
        _node_meshes(loaded, order).items(),
        key=lambda item: (order.get(item[0], len(order)), item[0]),
    ):
        if node not in order:  # trimesh names an unnamed node by its index
            raise ExampleError(
                path,
                f"node {node}",
                "has no name: name each object's node TYPE[.STYLE][.NNN], e.g. chair.001",
            )
        meta = extras.get(node, {})
        kind, style = parse_node_name(node)
        if "type" in meta or "style" in meta:  # scenewright's export: names as they were, checked
            kind = _NAME.sub("_", meta.get("type", kind).lower()) or "object"
            style = _NAME.sub("_", meta["style"].lower()) if meta.get("style") else style
        corners = trimesh.transform_points(trimesh.bounds.corners(mesh.bounds), transform)
        if meta.get("kind") in ROOM_KINDS or (not meta and kind in ROOM_TYPES):
            (walls if kind == "wall" or meta.get("kind") == "wall" else floors).append(corners)
            continue
        records.append(
            _record(
                path, node, meta.get("id", node), kind, style, np.asarray(transform), mesh.bounds
            )
        )
    if not records:
        raise ExampleError(
            path,
            "",
            "has no object nodes (a node with a mesh that is not a wall, floor or ceiling)",
        )
    room, lo, hi = _floor(path, records, walls, floors)
    shift = -(lo + hi) / 2.0
    records = [
        ObjectRecord(
            r.id,
            r.type,
            r.size,
            (r.position[0] + shift[0], r.position[1], r.position[2] + shift[1]),
            r.yaw,
            r.style,
        )
        for r in records
    ]
    extent = (float(hi[0] - lo[0]), float(hi[1] - lo[1]))
    return example_scene(records, name=name, source=path, extent=extent, room=room)


def _node_meshes(loaded, order: dict[str, int]) -> dict:
    """Each mesh node's world transform and mesh. trimesh splits a mesh of several
    primitives (one per material: scenewright's export, Blender's with several
    materials) into unnamed child nodes of the named one; their meshes, in the named
    node's frame, are joined back into it."""
    import trimesh

    parts: dict[str, list] = {}
    world: dict[str, np.ndarray] = {}
    parents = loaded.graph.transforms.parents
    for node in loaded.graph.nodes_geometry:
        transform, geometry_name = loaded.graph[node]
        mesh = loaded.geometry[geometry_name]
        if not hasattr(mesh, "bounds") or mesh.bounds is None:
            continue
        owner = node
        if node not in order and parents.get(node) in order:
            owner = parents[node]
            if owner not in world:
                world[owner] = np.asarray(loaded.graph[owner][0])
            local = np.linalg.inv(world[owner]) @ np.asarray(transform)
            mesh = mesh.copy()
            mesh.apply_transform(local)
        else:
            world[owner] = np.asarray(transform)
        parts.setdefault(owner, []).append(mesh)
    return {
        node: (world[node], meshes[0] if len(meshes) == 1 else trimesh.util.concatenate(meshes))
        for node, meshes in parts.items()
    }


def _record(
    path: str, node: str, object_id: str, kind: str, style, transform: np.ndarray, bounds
) -> ObjectRecord:
    linear = transform[:3, :3]
    scale = np.linalg.norm(linear, axis=0)
    if np.any(scale < 1e-9):
        raise ExampleError(path, f"node {node!r}", "has a zero scale")
    rotation = linear / scale
    tilt = math.degrees(math.acos(max(-1.0, min(1.0, rotation[1, 1]))))
    if tilt > MAX_TILT_DEGREES:
        raise ExampleError(
            path,
            f"node {node!r}",
            f"is tilted {tilt:.0f} degrees off upright (at most {MAX_TILT_DEGREES:g})",
        )
    lo, hi = np.asarray(bounds, dtype=float)
    size = (hi - lo) * scale
    base = np.array([(lo[0] + hi[0]) / 2.0, lo[1], (lo[2] + hi[2]) / 2.0, 1.0])
    x, y, z = (transform @ base)[:3]
    yaw = math.atan2(rotation[0, 2], rotation[2, 2])
    object_id = _NAME.sub("_", object_id) or "object"
    width, height, depth = (float(v) for v in np.maximum(size, 1e-3))
    return ObjectRecord(
        object_id,
        kind,
        (width, height, depth),
        (float(x), float(y), float(z)),
        yaw,
        style,
    )


def _floor(path: str, records, walls, floors) -> tuple[Room | None, np.ndarray, np.ndarray]:
    """The room (or None) and the (x, z) corners lo, hi of the extent, in the file's frame."""
    if walls:
        boxes = [(c[:, [0, 2]].min(axis=0), c[:, [0, 2]].max(axis=0)) for c in walls]
        thickness = min(float(np.min(hi - lo)) for lo, hi in boxes)
        lo = np.min([b[0] for b in boxes], axis=0) + thickness
        hi = np.max([b[1] for b in boxes], axis=0) - thickness
        height = max(float(c[:, 1].max()) for c in walls)
        if not np.all(hi > lo):
            raise ExampleError(
                path,
                "walls",
                "enclose no floor (their inner box is empty): a room needs a wall on each side",
            )
        try:
            return Room.rectangle(float(hi[0] - lo[0]), float(hi[1] - lo[1]), height), lo, hi
        except RoomError as error:
            raise ExampleError(path, "walls", str(error)) from None
    if floors:
        points = np.concatenate(floors)[:, [0, 2]]
        return None, points.min(axis=0), points.max(axis=0)
    corners: list[tuple[float, float]] = []
    for r in records:
        reach = math.hypot(r.size[0], r.size[2]) / 2.0
        corners += [
            (r.position[0] - reach, r.position[2] - reach),
            (r.position[0] + reach, r.position[2] + reach),
        ]
    reached = np.array(corners)
    return None, reached.min(axis=0) - MARGIN, reached.max(axis=0) + MARGIN


def _nodes(path: str, data: bytes) -> tuple[dict[str, int], dict[str, dict]]:
    """Node name -> its place in the file, and -> its glTF ``extras`` (trimesh keeps
    neither), from the JSON chunk, once the file has passed ``checked_glb``."""
    document = checked_glb(path, data)
    order: dict[str, int] = {}
    found: dict[str, dict[str, str]] = {}
    for index, node in enumerate(document.get("nodes", [])):
        if isinstance(node.get("name"), str):
            order.setdefault(node["name"], index)
            if isinstance(node.get("extras"), dict):
                found[node["name"]] = {
                    k: v for k, v in node["extras"].items() if isinstance(v, str)
                }
    return order, found
