"""The hand-written example format: a JSON file a person writes (schema
``examples/schema/example.schema.json``, documented in docs/examples.md).

Checked in three passes, each naming the first problem with the file and the place in
it: JSON syntax (``file:line:col``), the schema (``$.objects[2].size`` and the
object's id), then references and places (unique ids, parents that exist and do not
stand on themselves, a room that can be built, every object's base centre inside the
room or extent, an object given a parent touching its top over its footprint). Yaw is in degrees in this format; the Scene
keeps radians as everywhere else. A room given by corners is moved so its bounding box
is centred on the origin, and its objects with it.
"""

from __future__ import annotations

import json
import math
from typing import Any

import jsonschema
from jsonschema.exceptions import best_match

from scenewright.core.errors import RoomError
from scenewright.core.files import load_json
from scenewright.core.room import DEFAULT_WALL_HEIGHT, Room
from scenewright.core.scene import Scene
from scenewright.core.schema_check import (
    packaged_schema_text,
    packaged_validator,
    schema_message,
)

from .example import ExampleError, ObjectRecord, example_scene
from .stacking import over_footprint, touches_top

SCHEMA_FILE = "example.schema.json"


def load_schema() -> dict[str, Any]:
    """The hand-written example format's JSON Schema (draft 2020-12)."""
    return json.loads(_schema_text())


def read_handwritten(path: str, text: str, name: str) -> Scene:
    """The Scene of a hand-written example's ``text`` (``path`` names it in errors)."""
    data = parse_json(path, text)
    errors = list(_validator().iter_errors(data))
    error = best_match(errors)
    if error is not None:
        more = f" (and {len(errors) - 1} more)" if len(errors) > 1 else ""
        raise ExampleError(path, _where(data, list(error.absolute_path)), _message(error) + more)
    raw_objects = data["objects"]
    ids = [raw["id"] for raw in raw_objects]
    seen: set[str] = set()
    for index, object_id in enumerate(ids):
        if object_id in seen:
            raise ExampleError(
                path, f"$.objects[{index}].id", f"id {object_id!r} is used by an earlier object too"
            )
        seen.add(object_id)
    parents = {raw["id"]: raw["parent"] for raw in raw_objects if raw.get("parent") is not None}
    for index, raw in enumerate(raw_objects):
        parent = raw.get("parent")
        if parent is not None and parent not in seen:
            raise ExampleError(
                path,
                f"$.objects[{index}].parent",
                f"{raw['id']!r} stands on {parent!r}, which is not an object of the file",
            )
        if parent is not None and _stands_on_itself(raw["id"], parents):
            raise ExampleError(
                path,
                f"$.objects[{index}].parent",
                f"{raw['id']!r} stands on itself (through parents)",
            )
    room, shift = _room(path, data)
    extent = room.extent if room is not None else tuple(data["extent"])
    by_id = {raw["id"]: raw for raw in raw_objects}
    records = [
        ObjectRecord(
            id=raw["id"],
            type=raw["type"],
            size=tuple(raw["size"]),
            position=_position(raw, by_id, shift),
            yaw=math.radians(raw.get("yaw", 0.0)),
            style=raw.get("style"),
        )
        for raw in raw_objects
    ]
    records_by_id = {record.id: record for record in records}
    for index, record in enumerate(records):
        _check_place(path, index, record, records_by_id, parents, room, extent)
    return example_scene(
        records, name=data.get("name", name), source=path, extent=extent, room=room, parents=parents
    )


def _check_place(
    path: str,
    index: int,
    record: ObjectRecord,
    records: dict[str, ObjectRecord],
    parents: dict[str, str],
    room: Room | None,
    extent: tuple[float, float],
) -> None:
    """Refuse an object that stands outside the room (or extent), or that the file says
    stands on a parent it does not touch: every stage after reading trusts both."""
    where = f"$.objects[{index}].position (object {record.id!r})"
    x, y, z = record.position
    if room is not None:
        outside = not room.contains(x, z)
    else:
        outside = abs(x) > extent[0] / 2.0 or abs(z) > extent[1] / 2.0
    if outside:
        raise ExampleError(
            path,
            where,
            f"its base centre ({x:g}, {z:g}) is outside the {'room' if room else 'extent'}",
        )
    parent = parents.get(record.id)
    if parent is None:
        return
    below = records[parent]
    if not touches_top(record, below):
        top = below.position[1] + below.size[1]
        raise ExampleError(
            path,
            where,
            f"stands on {parent!r}, whose top is at height {top:g}, but its base is at {y:g}"
            " (give the position as [x, z] to put it on top)",
        )
    if not over_footprint(record, below):
        raise ExampleError(
            path,
            where,
            f"stands on {parent!r}, but its base centre is not over the footprint of {parent!r}",
        )


def parse_json(path: str, text: str) -> Any:
    """The JSON document of ``text``; ``ExampleError`` at ``file:line:col`` if it is not
    JSON, or holds NaN or Infinity."""

    try:
        return load_json(text)
    except json.JSONDecodeError as error:
        raise ExampleError(
            f"{path}:{error.lineno}:{error.colno}", "", f"not JSON: {error.msg}"
        ) from None
    except ValueError as error:
        raise ExampleError(path, "", f"not usable JSON: {error}") from None


def _where(data: Any, parts: list) -> str:
    """``$.objects[2].size (object 'lamp')`` for a JSON path into the document."""
    text = "$" + "".join(f"[{p}]" if isinstance(p, int) else f".{p}" for p in parts)
    if len(parts) >= 2 and parts[0] == "objects" and isinstance(parts[1], int):
        raw = data["objects"][parts[1]]
        if isinstance(raw, dict) and isinstance(raw.get("id"), str):
            shown = repr(raw["id"])
            text += f" (object {shown if len(shown) <= 40 else shown[:36] + '...' + shown[0]})"
    return text


def _message(error: jsonschema.ValidationError) -> str:
    """The schema's complaint in one short line (a ``oneOf`` of required keys said as such)."""
    choices = (
        [sub.get("required") for sub in error.schema.get("oneOf", [])]
        if error.validator == "oneOf"
        else []
    )
    if choices and all(choices):
        return "needs exactly one of " + " or ".join("/".join(map(repr, keys)) for keys in choices)
    return schema_message(error)


def _stands_on_itself(object_id: str, parents: dict[str, str]) -> bool:
    seen, current = set(), object_id
    while current in parents:
        if current in seen:
            return True
        seen.add(current)
        current = parents[current]
        if current == object_id:
            return True
    return False


def _room(path: str, data: dict) -> tuple[Room | None, tuple[float, float]]:
    """The room (or None) and the (x, z) shift that centres its bounding box."""
    raw = data.get("room")
    if raw is None:
        return None, (0.0, 0.0)
    height = float(raw.get("height", DEFAULT_WALL_HEIGHT))
    try:
        if "corners" in raw:
            xs, zs = [c[0] for c in raw["corners"]], [c[1] for c in raw["corners"]]
            shift = (-(min(xs) + max(xs)) / 2.0, -(min(zs) + max(zs)) / 2.0)
            return Room.polygon(raw["corners"], height), shift
        return Room.rectangle(float(raw["width"]), float(raw["depth"]), height), (0.0, 0.0)
    except RoomError as error:
        raise ExampleError(path, "$.room", str(error)) from None


def _position(
    raw: dict, by_id: dict[str, dict], shift: tuple[float, float]
) -> tuple[float, float, float]:
    """Base centre (x, y, z) moved by ``shift``; a 2-number position stands on the
    floor or on its parent's top."""
    position = raw["position"]
    if len(position) == 3:
        x, y, z = position
    else:
        (x, z), y = position, _base_height(raw, by_id)
    return float(x) + shift[0], float(y), float(z) + shift[1]


def _base_height(raw: dict, by_id: dict[str, dict]) -> float:
    """The height of the top ``raw`` stands on: down the chain of parents to one with a
    3-number position or to the floor (a loop, not a recursion: a stack may be
    thousands of objects high)."""
    chain = []
    current = raw
    while current.get("parent") is not None:
        current = by_id[current["parent"]]
        chain.append(current)
        if len(current["position"]) == 3:
            break
    height = float(chain[-1]["position"][1]) if chain and len(chain[-1]["position"]) == 3 else 0.0
    for below in reversed(chain):
        height += float(below["size"][1])
    return height


def _schema_text() -> str:
    return packaged_schema_text("scenewright.examples", "schema", SCHEMA_FILE)


def _validator() -> jsonschema.Draft202012Validator:
    return packaged_validator("scenewright.examples", "schema", SCHEMA_FILE)
