"""The checks a GLB file passes before any reader touches it (``checked_glb``).

A GLB file's JSON says how to read its binary chunk: accessors of so many elements in
buffer views of so many bytes, nodes with children, meshes with triangle indices.
Nothing forces those numbers to agree with the file, and a mesh library trusts them: an
accessor of 50 million elements with no data behind it is allocated as zeros, a node
that is its own grandchild is walked forever, a triangle index past the last vertex
reads memory that is not the mesh's. So the whole document is checked first, each
problem an ``ExampleError`` at the place in the file: the header and chunk lengths;
every list a list; at most ``MAX_GLB_NODES`` nodes; every buffer inside the file's own
binary chunk (no external or ``data:`` URI, for buffers and images: an example file
holds its data itself); every buffer view inside its buffer and every accessor inside
its buffer view, with a known component type and element type; every index (of a
node, mesh, accessor, view, buffer) naming one that exists; the nodes a forest (one
parent each, no cycles); transforms and vertex positions finite and within
``MAX_COORDINATE`` of the origin; triangle indices below their primitive's vertex
count; names and extras without control or bidirectional-control characters (what
scene.json accepts). The work is linear in the file's size.
"""

from __future__ import annotations

import math
import struct
from typing import Any

import numpy as np

from scenewright.core.files import load_json
from scenewright.core.limits import MAX_COORDINATE, MAX_NODES, forbidden_character

from .example import ExampleError

#: The most nodes a GLB example may have (as many as a scene may have objects).
MAX_GLB_NODES = MAX_NODES
#: The largest scale factor of a node's transform.
MAX_SCALE = 1e6

_COMPONENT_TYPES = {5120: "i1", 5121: "u1", 5122: "<i2", 5123: "<u2", 5125: "<u4", 5126: "<f4"}
_ELEMENT_SIZES = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4, "MAT2": 4, "MAT3": 9, "MAT4": 16}
_LISTS = ("nodes", "meshes", "accessors", "bufferViews", "buffers", "scenes", "images")


def checked_glb(path: str, data: bytes) -> dict[str, Any]:
    """The glTF JSON document of a GLB file's bytes, once the file has passed every
    check of the module docstring; ``ExampleError`` naming the first problem."""
    document, binary = _chunks(path, data)
    for key in _LISTS:
        if not isinstance(document.get(key, []), list):
            raise ExampleError(path, f'"{key}"', "must be a list")
    nodes = document.get("nodes", [])
    if len(nodes) > MAX_GLB_NODES:
        raise ExampleError(
            path, '"nodes"', f"{len(nodes)} nodes; a GLB example may have at most {MAX_GLB_NODES}"
        )
    _check_buffers(path, document, binary)
    _check_accessors(path, document)
    _check_meshes(path, document, binary)
    _check_nodes(path, document)
    if "scenes" in document:
        _need(path, '"scenes"', bool(document["scenes"]), "is empty: the file shows nothing")
    for k, scene in enumerate(document.get("scenes", [])):
        where = f"scenes[{k}]"
        _need(path, where, isinstance(scene, dict), "must be an object")
        for child in _list(path, where, scene, "nodes"):
            _index(path, f"{where}.nodes", child, len(nodes), "node")
    if "scene" in document:
        _index(path, '"scene"', document["scene"], len(document.get("scenes", [])), "scene")
    return document


def _chunks(path: str, data: bytes) -> tuple[dict[str, Any], bytes]:
    """The JSON document and the binary chunk (empty when there is none)."""
    if len(data) < 20:
        raise ExampleError(
            path, "", f"not a GLB file: only {len(data)} bytes, less than a GLB header's 20"
        )
    version, total = struct.unpack("<II", data[4:12])
    if version != 2:
        raise ExampleError(path, "", f"a GLB file of version {version}; only glTF 2 is read")
    if total > len(data):
        raise ExampleError(
            path,
            "",
            f"not a whole GLB file: its header says {total} bytes, the file has {len(data)} (cut short?)",
        )
    length, kind = struct.unpack("<I4s", data[12:20])
    if kind != b"JSON" or 20 + length > total:
        raise ExampleError(path, "", "not a GLB file (no whole JSON chunk after the header)")
    try:
        document = load_json(data[20 : 20 + length].decode("utf-8"))
    except UnicodeDecodeError:
        raise ExampleError(path, "", "the GLB's JSON chunk is not UTF-8 text") from None
    except ValueError as error:
        raise ExampleError(path, "", f"the GLB's JSON chunk is not usable JSON: {error}") from None
    if not isinstance(document, dict):
        raise ExampleError(path, "", "the GLB's JSON chunk is not a JSON object")
    start = 20 + length + (-length % 4)  # chunks start on 4-byte boundaries
    binary = b""
    if start + 8 <= total:
        size, kind = struct.unpack("<I4s", data[start : start + 8])
        if kind == b"BIN\x00":
            if start + 8 + size > total:
                raise ExampleError(path, "", "not a whole GLB file: its binary chunk is cut short")
            binary = data[start + 8 : start + 8 + size]
    return document, binary


def _need(path: str, where: str, condition: bool, message: str) -> None:
    if not condition:
        raise ExampleError(path, where, message)


def _whole(value: Any) -> bool:
    return isinstance(value, int) and not isinstance(value, bool) and value >= 0


def _index(path: str, where: str, value: Any, count: int, what: str) -> int:
    _need(
        path,
        where,
        _whole(value) and value < count,
        f"{_shown(value)} is not a {what} of the file (it has {count})",
    )
    return value


def _list(path: str, where: str, owner: dict, key: str) -> list:
    value = owner.get(key, [])
    _need(path, f"{where}.{key}", isinstance(value, list), "must be a list")
    return value


def _shown(value: Any) -> str:
    text = repr(value)
    return text if len(text) <= 40 else text[:37] + "..."


def _check_buffers(path: str, document: dict, binary: bytes) -> None:
    for key in ("buffers", "images"):
        for k, item in enumerate(document.get(key, [])):
            _need(path, f"{key}[{k}]", isinstance(item, dict), "must be an object")
            _need(
                path,
                f"{key}[{k}]",
                "uri" not in item,
                "refers to data outside the file (a uri); an example GLB must hold its data itself "
                "(export it with the data embedded)",
            )
    buffers = document.get("buffers", [])
    for k, buffer in enumerate(buffers):
        length = buffer.get("byteLength")
        _need(path, f"buffers[{k}].byteLength", _whole(length), "must be a whole number")
        _need(
            path,
            f"buffers[{k}]",
            k == 0 and length <= len(binary),
            f"needs {length} bytes, more than the file's binary chunk holds ({len(binary)})"
            if k == 0
            else "only the first buffer of a GLB file can hold data (its binary chunk)",
        )
    for k, view in enumerate(document.get("bufferViews", [])):
        where = f"bufferViews[{k}]"
        _need(path, where, isinstance(view, dict), "must be an object")
        buffer = _index(path, f"{where}.buffer", view.get("buffer"), len(buffers), "buffer")
        offset, length = view.get("byteOffset", 0), view.get("byteLength")
        _need(path, f"{where}.byteOffset", _whole(offset), "must be a whole number")
        _need(path, f"{where}.byteLength", _whole(length), "must be a whole number")
        _need(
            path,
            where,
            offset + length <= buffers[buffer]["byteLength"],
            f"bytes {offset} to {offset + length} lie beyond its buffer's {buffers[buffer]['byteLength']}",
        )
        stride = view.get("byteStride")
        _need(
            path,
            f"{where}.byteStride",
            stride is None or (_whole(stride) and 4 <= stride <= 252),
            "must be a whole number from 4 to 252",
        )


def _check_accessors(path: str, document: dict) -> None:
    views = document.get("bufferViews", [])
    for k, accessor in enumerate(document.get("accessors", [])):
        where = f"accessors[{k}]"
        _need(path, where, isinstance(accessor, dict), "must be an object")
        _need(
            path,
            where,
            "bufferView" in accessor and "sparse" not in accessor,
            "has no bufferView (or is sparse); an example GLB's accessors must point at their data",
        )
        view = views[
            _index(path, f"{where}.bufferView", accessor["bufferView"], len(views), "buffer view")
        ]
        component = accessor.get("componentType")
        _need(
            path,
            f"{where}.componentType",
            component in _COMPONENT_TYPES,
            f"{_shown(component)} is not a glTF component type",
        )
        element = accessor.get("type")
        _need(
            path,
            f"{where}.type",
            element in _ELEMENT_SIZES,
            f"{_shown(element)} is not a glTF type",
        )
        count, offset = accessor.get("count"), accessor.get("byteOffset", 0)
        _need(path, f"{where}.count", _whole(count) and count >= 1, "must be a whole number >= 1")
        _need(path, f"{where}.byteOffset", _whole(offset), "must be a whole number")
        size = int(_COMPONENT_TYPES[component][-1]) * _ELEMENT_SIZES[element]
        stride = view.get("byteStride") or size
        needed = offset + stride * (count - 1) + size
        _need(
            path,
            where,
            needed <= view["byteLength"],
            f"{count} elements need {needed} bytes of its buffer view, which has {view['byteLength']}",
        )


def _values(document: dict, binary: bytes, index: int) -> np.ndarray:
    """An accessor's elements (count, components), read in place from the binary chunk."""
    accessor = document["accessors"][index]
    view = document["bufferViews"][accessor["bufferView"]]
    dtype = np.dtype(_COMPONENT_TYPES[accessor["componentType"]])
    components = _ELEMENT_SIZES[accessor["type"]]
    stride = view.get("byteStride") or dtype.itemsize * components
    return np.ndarray(
        shape=(accessor["count"], components),
        dtype=dtype,
        buffer=binary,
        offset=view.get("byteOffset", 0) + accessor.get("byteOffset", 0),
        strides=(stride, dtype.itemsize),
    )


def _check_meshes(path: str, document: dict, binary: bytes) -> None:
    accessors = document.get("accessors", [])
    for m, mesh in enumerate(document.get("meshes", [])):
        _need(path, f"meshes[{m}]", isinstance(mesh, dict), "must be an object")
        for p, primitive in enumerate(_list(path, f"meshes[{m}]", mesh, "primitives")):
            where = f"meshes[{m}].primitives[{p}]"
            _need(path, where, isinstance(primitive, dict), "must be an object")
            attributes = primitive.get("attributes", {})
            _need(path, f"{where}.attributes", isinstance(attributes, dict), "must be an object")
            for name, value in attributes.items():
                _index(path, f"{where}.attributes.{name}", value, len(accessors), "accessor")
            _need(
                path,
                f"{where}.attributes",
                "POSITION" in attributes,
                "has no POSITION (the vertices that give the object its size)",
            )
            vertices = None
            if "POSITION" in attributes:
                positions = _values(document, binary, attributes["POSITION"])
                _need(
                    path,
                    f"{where}.attributes.POSITION",
                    positions.dtype.kind == "f" and positions.shape[1] == 3,
                    "must be an accessor of 3 floats per vertex",
                )
                _need(
                    path,
                    f"{where}.attributes.POSITION",
                    bool(np.all(np.abs(positions) <= MAX_COORDINATE)),  # False for NaN too
                    f"holds a vertex that is not a finite number within {MAX_COORDINATE:g} m of the origin",
                )
                vertices = positions.shape[0]
            if "indices" in primitive:
                index = _index(
                    path, f"{where}.indices", primitive["indices"], len(accessors), "accessor"
                )
                values = _values(document, binary, index)
                _need(
                    path,
                    f"{where}.indices",
                    values.dtype.kind == "u" and values.shape[1] == 1,
                    "must be an accessor of unsigned whole numbers",
                )
                if vertices is not None and values.size:
                    largest = int(values.max())
                    _need(
                        path,
                        f"{where}.indices",
                        largest < vertices,
                        f"index {largest} names a vertex past the last of {vertices}",
                    )


def _check_nodes(path: str, document: dict) -> None:
    nodes = document.get("nodes", [])
    meshes = len(document.get("meshes", []))
    parent: dict[int, int] = {}
    for k, node in enumerate(nodes):
        where = f"nodes[{k}]"
        _need(path, where, isinstance(node, dict), "must be an object")
        if "mesh" in node:
            _index(path, f"{where}.mesh", node["mesh"], meshes, "mesh")
        for child in _list(path, where, node, "children"):
            _index(path, f"{where}.children", child, len(nodes), "node")
            _need(
                path,
                f"{where}.children",
                child not in parent and child != k,
                f"node {child} has more than one parent, or is its own child",
            )
            parent[child] = k
        name = node.get("name")
        if name is not None:
            _need(path, f"{where}.name", isinstance(name, str), "must be text")
            _text(path, f"{where}.name", name)
        extras = node.get("extras")
        if isinstance(extras, dict):
            for key, value in extras.items():
                if isinstance(value, str):
                    _text(path, f"{where}.extras.{_shown(key)}", value)
        for key, count, bound in (
            ("translation", 3, MAX_COORDINATE),
            ("rotation", 4, 1.0 + 0.01),
            ("scale", 3, MAX_SCALE),
            ("matrix", 16, MAX_COORDINATE),
        ):
            if key in node:
                _numbers(path, f"{where}.{key}", node[key], count, bound)
    names: dict[str, int] = {}
    for k, node in enumerate(nodes):
        name = node.get("name")
        if isinstance(name, str) and name:
            _need(
                path,
                f"nodes[{k}].name",
                name not in names,
                f"{_shown(name)} also names node {names.get(name)}; a node's name is the object's id, "
                "so each must be unique",
            )
            names[name] = k
        rotation = node.get("rotation")
        if rotation is not None:
            norm = math.sqrt(sum(v * v for v in rotation))
            _need(
                path,
                f"nodes[{k}].rotation",
                abs(norm - 1.0) <= 0.01,
                f"is not a unit quaternion (its length is {norm:g})",
            )
    rooted: set[int] = set()  # nodes whose walk up ends at a root
    for k in range(len(nodes)):  # one parent each: a cycle is a walk up that comes back
        seen, current = {k}, k
        while current in parent and current not in rooted:
            current = parent[current]
            _need(
                path,
                f"nodes[{k}]",
                current not in seen,
                "is its own ancestor (the nodes form a cycle)",
            )
            seen.add(current)
        rooted |= seen


def _numbers(path: str, where: str, value: Any, count: int, bound: float) -> None:
    _need(
        path,
        where,
        isinstance(value, list)
        and len(value) == count
        and all(
            isinstance(v, (int, float))
            and not isinstance(v, bool)
            and math.isfinite(v)
            and abs(v) <= bound
            for v in value
        ),
        f"must be {count} finite numbers of size at most {bound:g}",
    )


def _text(path: str, where: str, text: str) -> None:
    bad = forbidden_character(text)
    _need(
        path,
        where,
        bad is None,
        f"holds the character {bad}, which a scene may not carry (no control, line-separator or "
        "bidirectional-control characters)",
    )
    _need(path, where, len(text) <= 200, f"is {len(text)} characters long; it may have at most 200")
