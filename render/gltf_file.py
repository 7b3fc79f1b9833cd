"""The glTF 2.0 binary container (GLB): a node tree with meshes, materials, a camera
and a directional light encoded into one file, deterministically.

``render.export`` decides what the nodes are; this module only encodes them. Each mesh
is one primitive per material, non-indexed triangles whose vertices each carry their
face's normal (flat shading, as the preview draws). Materials are metallic-roughness
PBR, one per distinct colour, shared by every mesh that uses it; the colour goes in as
the base colour factor unchanged, since the preview's renderer also takes the colours as
linear values and gamma-encodes its output, as glTF viewers do.
"""

from __future__ import annotations

import json
import math
import struct
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import trimesh

#: Matte, non-metal surfaces, as the preview's renderer draws them.
ROUGHNESS = 0.9
#: glTF buffer view targets.
ARRAY_BUFFER = 34962
FLOAT = 5126
TRIANGLES = 4


@dataclass
class Node:
    """One glTF node: ``matrix`` is its transform relative to its parent (rigid)."""

    name: str
    matrix: np.ndarray
    extras: dict[str, Any] = field(default_factory=dict)
    mesh: trimesh.Trimesh | None = None
    camera: dict[str, Any] | None = None  # a glTF camera object
    light: dict[str, Any] | None = None  # a KHR_lights_punctual light
    children: list[Node] = field(default_factory=list)


def glb(roots: list[Node], generator: str) -> bytes:
    """The GLB file of the node trees ``roots``."""
    writer = _Writer()
    top = [writer.node(root) for root in roots]
    document: dict[str, Any] = {"asset": {"version": "2.0", "generator": generator}}
    document["scene"] = 0
    document["scenes"] = [{"nodes": top}] if top else [{}]
    document["nodes"] = writer.nodes
    for key in ("meshes", "materials", "cameras", "accessors", "bufferViews"):
        if getattr(writer, key):
            document[key] = getattr(writer, key)
    if writer.lights:
        document["extensionsUsed"] = ["KHR_lights_punctual"]
        document["extensions"] = {"KHR_lights_punctual": {"lights": writer.lights}}
    binary = bytes(writer.binary)
    if binary:
        document["buffers"] = [{"byteLength": len(binary)}]
    if not writer.nodes:
        del document["nodes"]
    text = json.dumps(document, separators=(",", ":"), sort_keys=False).encode()
    text += b" " * (-len(text) % 4)
    chunks = struct.pack("<I4s", len(text), b"JSON") + text
    if binary:
        chunks += struct.pack("<I4s", len(binary), b"BIN\x00") + binary
    return struct.pack("<4sII", b"glTF", 2, 12 + len(chunks)) + chunks


class _Writer:
    def __init__(self) -> None:
        self.nodes: list[dict[str, Any]] = []
        self.meshes: list[dict[str, Any]] = []
        self.materials: list[dict[str, Any]] = []
        self.cameras: list[dict[str, Any]] = []
        self.lights: list[dict[str, Any]] = []
        self.accessors: list[dict[str, Any]] = []
        self.bufferViews: list[dict[str, Any]] = []
        self.binary = bytearray()
        self._material_of: dict[tuple[int, ...], int] = {}

    def node(self, node: Node) -> int:
        index = len(self.nodes)
        entry: dict[str, Any] = {"name": node.name}
        self.nodes.append(entry)
        entry.update(_trs(node.matrix))
        if node.mesh is not None and len(node.mesh.faces):
            entry["mesh"] = self.mesh(node.name, node.mesh)
        if node.camera is not None:
            entry["camera"] = len(self.cameras)
            self.cameras.append(node.camera)
        if node.light is not None:
            entry["extensions"] = {"KHR_lights_punctual": {"light": len(self.lights)}}
            self.lights.append(node.light)
        if node.extras:
            entry["extras"] = node.extras
        children = [self.node(child) for child in node.children]
        if children:
            entry["children"] = children
        return index

    def mesh(self, name: str, mesh: trimesh.Trimesh) -> int:
        faces = np.asarray(mesh.faces)
        corners = np.asarray(mesh.vertices, dtype=float)[faces]  # (n, 3, 3)
        normals = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
        length = np.linalg.norm(normals, axis=1)
        keep = length > 1e-12  # a triangle of no area has no normal; it draws nothing
        colours = np.asarray(mesh.visual.face_colors, dtype=np.uint8)[keep]
        corners, normals = corners[keep], normals[keep] / length[keep, None]
        primitives = []
        looks, which = np.unique(colours, axis=0, return_inverse=True)
        for k, look in enumerate(looks):
            chosen = np.asarray(which).ravel() == k
            positions = corners[chosen].reshape(-1, 3).astype(np.float32)
            vertex_normals = np.repeat(normals[chosen], 3, axis=0).astype(np.float32)
            attributes = {
                "POSITION": self.accessor(positions, bounds=True),
                "NORMAL": self.accessor(vertex_normals),
            }
            primitives.append(
                {"attributes": attributes, "material": self.material(look), "mode": TRIANGLES}
            )
        self.meshes.append({"name": name, "primitives": primitives})
        return len(self.meshes) - 1

    def material(self, rgba: np.ndarray) -> int:
        key = tuple(int(v) for v in rgba)
        if key not in self._material_of:
            r, g, b, a = (v / 255.0 for v in key)
            material: dict[str, Any] = {
                "name": "colour_{:02x}{:02x}{:02x}".format(*key[:3]),
                "pbrMetallicRoughness": {
                    "baseColorFactor": [round(v, 6) for v in (r, g, b, a)],
                    "metallicFactor": 0.0,
                    "roughnessFactor": ROUGHNESS,
                },
            }
            if key[3] < 255:
                material["name"] += f"{key[3]:02x}"
                material["alphaMode"] = "BLEND"
            self._material_of[key] = len(self.materials)
            self.materials.append(material)
        return self._material_of[key]

    def accessor(self, data: np.ndarray, *, bounds: bool = False) -> int:
        raw = np.ascontiguousarray(data, dtype="<f4").tobytes()
        self.binary += b"\x00" * (-len(self.binary) % 4)
        view = {
            "buffer": 0,
            "byteOffset": len(self.binary),
            "byteLength": len(raw),
            "target": ARRAY_BUFFER,
        }
        self.binary += raw
        self.bufferViews.append(view)
        accessor: dict[str, Any] = {
            "bufferView": len(self.bufferViews) - 1,
            "componentType": FLOAT,
            "count": len(data),
            "type": "VEC3",
        }
        if bounds:
            accessor["min"] = [float(v) for v in data.min(axis=0)]
            accessor["max"] = [float(v) for v in data.max(axis=0)]
        self.accessors.append(accessor)
        return len(self.accessors) - 1


def _trs(matrix: np.ndarray) -> dict[str, Any]:
    """A rigid transform as glTF's translation and rotation (identity parts left out)."""
    out: dict[str, Any] = {}
    rotation = _quaternion(np.asarray(matrix, dtype=float)[:3, :3])
    if rotation != [0.0, 0.0, 0.0, 1.0]:
        out["rotation"] = rotation
    translation = [_clean(v) for v in matrix[:3, 3]]
    if any(translation):
        out["translation"] = translation
    return out


def _quaternion(rotation: np.ndarray) -> list[float]:
    """Unit quaternion [x, y, z, w] (w >= 0) of a rotation matrix."""
    m = rotation
    trace = m[0, 0] + m[1, 1] + m[2, 2]
    if trace > 0:
        s = 2.0 * math.sqrt(trace + 1.0)
        q = [(m[2, 1] - m[1, 2]) / s, (m[0, 2] - m[2, 0]) / s, (m[1, 0] - m[0, 1]) / s, s / 4]
    elif m[0, 0] > m[1, 1] and m[0, 0] > m[2, 2]:
        s = 2.0 * math.sqrt(1.0 + m[0, 0] - m[1, 1] - m[2, 2])
        q = [s / 4, (m[0, 1] + m[1, 0]) / s, (m[0, 2] + m[2, 0]) / s, (m[2, 1] - m[1, 2]) / s]
    elif m[1, 1] > m[2, 2]:
        s = 2.0 * math.sqrt(1.0 + m[1, 1] - m[0, 0] - m[2, 2])
        q = [(m[0, 1] + m[1, 0]) / s, s / 4, (m[1, 2] + m[2, 1]) / s, (m[0, 2] - m[2, 0]) / s]
    else:
        s = 2.0 * math.sqrt(1.0 + m[2, 2] - m[0, 0] - m[1, 1])
        q = [(m[0, 2] + m[2, 0]) / s, (m[1, 2] + m[2, 1]) / s, s / 4, (m[1, 0] - m[0, 1]) / s]
    norm = math.sqrt(sum(v * v for v in q))
    sign = -1.0 if q[3] < 0 else 1.0
    return [_clean(sign * v / norm) for v in q]


def _clean(value: float) -> float:
    """``value`` rounded to 1e-12 (noise of the matrix arithmetic) without negative zero."""
    return round(float(value), 12) + 0.0
