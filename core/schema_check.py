"""Check a scene.json document: its numbers and text, the shipped JSON Schema, its references.

The schema (``core/schema/scene.schema.json``, package data) documents every
key ``Scene.to_dict()`` writes, with the bounds of ``scenewright.core.limits`` on
coordinates, sizes, extents and counts; tools reading scene.json can use it too.
``parse_scene_json`` reads the text, keeping NaN, Infinity and numbers too large for a
float (which ``json.loads`` would accept) as markers so the check can locate them.
``scene_problems`` lists what is wrong, each as (JSON path, message), in three passes,
each run only when the one before found nothing: every number finite, no text with
control or bidirectional-control characters, nesting at most ``MAX_JSON_DEPTH`` deep;
then the schema (its most relevant error); then the references: ids unique, parents
that are other groups of the scene (no cycles, at most ``MAX_GROUP_DEPTH`` deep), paths
starting at junctions or on other paths, relations between ids of the scene with registered labels.
``validate_scene_dict`` raises ``SceneSchemaError`` (an ``InputError``) naming the
JSON path of the first problem, e.g. ``$.objects[2].position``; with ``check_files``
(for ``validate``) the folders and files a scene names must exist too.
"""

from __future__ import annotations

import difflib
import json
import math
from functools import cache
from importlib import resources
from pathlib import Path
from typing import Any

import jsonschema
from jsonschema.exceptions import best_match

from scenewright.core.errors import InputError, RoomError
from scenewright.core.house import in_room
from scenewright.core.limits import MAX_GROUP_DEPTH, MAX_JSON_DEPTH, forbidden_character
from scenewright.core.relations import RELATIONS
from scenewright.core.room import ROOM_NODE, Room

SCHEMA_FILE = "scene.schema.json"

#: One problem: the JSON path where it is, and what it is.
Problem = tuple[str, str]
#: The most problems listed for one document (a broken file may have a million).
MAX_PROBLEMS = 100


class SceneSchemaError(InputError):
    """A scene.json document with problems; ``path`` locates the first, ``problems``
    lists them all as (JSON path, message)."""

    def __init__(self, path: str, message: str, problems: list[Problem] | None = None):
        self.problems = problems or [(path, message)]
        more = len(self.problems) - 1
        also = (
            f" (and {more} more problem{'s' * (more != 1)}: 'scenewright validate' lists them)"
            if more
            else ""
        )
        super().__init__(f"scene.json {path}: {message}{also}")
        self.path = path


class NotFinite:
    """A number of the JSON text that is not a finite float (NaN, Infinity, 1e999)."""

    def __init__(self, text: str):
        self.text = text


def load_schema() -> dict[str, Any]:
    """The scene.json JSON Schema (draft 2020-12) as a dict (a fresh copy each call)."""
    return json.loads(_schema_text())


def parse_scene_json(text: str) -> Any:
    """The JSON document of ``text``, non-finite numbers kept as ``NotFinite``.

    Raises ``ValueError`` (``json.JSONDecodeError``) for text that is not JSON, and
    ``SceneSchemaError`` for a document nested too deeply for the parser.
    """
    try:
        return json.loads(text, parse_constant=NotFinite, parse_float=_finite_or_marker)
    except RecursionError:
        raise SceneSchemaError("$", f"nested deeper than {MAX_JSON_DEPTH} levels") from None


def validate_scene_dict(data: Any, *, check_files: bool = False) -> None:
    """Raise ``SceneSchemaError`` for the problems of ``data`` (see ``scene_problems``), if any."""
    problems = scene_problems(data, check_files=check_files)
    if problems:
        raise SceneSchemaError(*problems[0], problems)


def scene_problems(data: Any, *, check_files: bool = False) -> list[Problem]:
    """What is wrong with a scene.json document, in document order (see the module
    docstring); with ``check_files``, also the files it names that do not exist."""
    problems = _value_problems(data)
    if problems:
        return problems
    error = best_match(_validator().iter_errors(data))
    if error is not None:
        return [(json_path(error.absolute_path), schema_message(error))]
    problems = _reference_problems(data) + (_file_problems(data) if check_files else [])
    return problems[:MAX_PROBLEMS]


def _file_problems(data: dict[str, Any]) -> list[Problem]:
    """The folders and files a scene.json names that do not exist where it says: its
    description templates folder and its objects' mesh files."""
    problems: list[Problem] = []
    templates = data.get("templates")
    if templates is not None and not Path(templates).is_dir():
        problems.append(
            ("$.templates", f"the description templates folder {templates!r} does not exist")
        )
    for index, obj in enumerate(data["objects"]):
        if obj.get("mesh") is not None and not Path(obj["mesh"]).is_file():
            problems.append(
                (f"$.objects[{index}].mesh", f"the mesh file {obj['mesh']!r} does not exist")
            )
    return problems


def json_path(parts) -> str:
    """``$.objects[2].size`` style text for a sequence of keys and indices (a key that is
    not a plain name is written quoted, with its odd characters escaped)."""
    text = "$"
    for part in parts:
        if isinstance(part, int):
            text += f"[{part}]"
        elif part.isidentifier() and part.isascii():
            text += f".{part}"
        else:
            text += f"[{json.dumps(part)}]"
    return text


# -- numbers, text, nesting --------------------------------------------------------


def _finite_or_marker(text: str) -> float | NotFinite:
    number = float(text)
    return number if math.isfinite(number) else NotFinite(text)


def _value_problems(data: Any) -> list[Problem]:
    """Non-finite numbers, text with forbidden characters, and nesting beyond
    ``MAX_JSON_DEPTH``, found without recursion (so any depth can be reported)."""
    problems: list[Problem] = []
    pending: list[tuple[tuple, Any]] = [((), data)]
    while pending and len(problems) < MAX_PROBLEMS:
        parts, value = pending.pop()
        if len(parts) > MAX_JSON_DEPTH:
            problems.append((json_path(parts), f"nested deeper than {MAX_JSON_DEPTH} levels"))
        elif isinstance(value, NotFinite) or (
            isinstance(value, float) and not math.isfinite(value)
        ):
            shown = value.text if isinstance(value, NotFinite) else repr(value)
            problems.append((json_path(parts), f"{_clipped(shown)} is not a finite number"))
        elif isinstance(value, str):
            if (bad := forbidden_character(value)) is not None:
                problems.append(
                    (
                        json_path(parts),
                        f"the text contains the character {bad}; text may not hold "
                        "control or bidirectional-control characters",
                    )
                )
        elif isinstance(value, dict):
            for key, item in reversed(value.items()):
                if (bad := forbidden_character(key)) is not None:
                    problems.append((json_path(parts), f"a key contains the character {bad}"))
                pending.append((parts + (key,), item))
        elif isinstance(value, list):
            pending.extend(
                (parts + (index,), item) for index, item in reversed(list(enumerate(value)))
            )
    return problems


# -- references ------------------------------------------------------------------


def _reference_problems(data: dict[str, Any]) -> list[Problem]:
    problems: list[Problem] = []
    entities: dict[str, tuple[str, dict]] = {}  # id -> (where, entry)
    for section in ("objects", "paths"):
        for index, entry in enumerate(data[section]):
            where = f"$.{section}[{index}]"
            if entry["id"] in entities:
                problems.append(
                    (
                        f"{where}.id",
                        f"duplicate id {entry['id']!r} (also at {entities[entry['id']][0]}.id)",
                    )
                )
            else:
                entities[entry["id"]] = (where, entry)
    kinds = {
        entity_id: entry["kind"] if where.startswith("$.objects") else "path"
        for entity_id, (where, entry) in entities.items()
    }
    for section in ("objects", "paths"):
        for index, entry in enumerate(data[section]):
            parent = entry.get("parent")
            where = f"$.{section}[{index}].parent"
            if parent is None:
                continue
            if parent == entry["id"]:
                problems.append((where, f"{parent!r} is its own parent"))
            elif parent not in kinds:
                problems.append((where, f"the parent {parent!r} is not an id of this scene"))
            elif kinds[parent] != "group":
                problems.append(
                    (where, f"the parent {parent!r} is {_article(kinds[parent])}, not a group")
                )
    if not problems:
        problems += _nesting_problems(data, entities)
    for index, path in enumerate(data["paths"]):
        start = path.get("start")
        if start is not None and start == path["id"]:
            problems.append((f"$.paths[{index}].start", f"the path starts on itself ({start!r})"))
        elif start is not None and kinds.get(start) not in ("junction", "path"):
            what = (
                f"is {_article(kinds[start])}" if start in kinds else "is not an id of this scene"
            )
            problems.append(
                (
                    f"$.paths[{index}].start",
                    f"the path starts at {start!r}, which {what}, not a junction or a path",
                )
            )
    room_ids, room_problems = _room_parts(data.get("room"))
    problems += room_problems
    house = data.get("house")
    if isinstance(house, dict):  # a house's rooms' parts, named ROOM/PART (core.house)
        for index, house_room in enumerate(house.get("rooms", [])):
            parts, part_problems = _room_parts(house_room.get("room"))
            problems += [
                (f"$.house.rooms[{index}]" + where[1:], what) for where, what in part_problems
            ]
            room_ids |= {in_room(str(house_room.get("id")), part) for part in parts}
    for index, relation in enumerate(data["relations"]):
        for end in ("source", "target"):
            if relation[end] not in kinds and relation[end] not in room_ids:
                problems.append(
                    (f"$.relations[{index}].{end}", f"{relation[end]!r} is not an id of this scene")
                )
        if relation["label"] not in RELATIONS:
            problems.append(
                (
                    f"$.relations[{index}].label",
                    f"unknown relation label {relation['label']!r}"
                    + _nearest(relation["label"], RELATIONS.names()),
                )
            )
    return problems


def _room_parts(room: dict[str, Any] | None) -> tuple[set[str], list[Problem]]:
    """The ids relations may name in a room (its walls, doors, windows and ``room``), and
    what is wrong with the room: walls that do not join up, openings in no wall."""
    if not room:
        return set(), []
    problems: list[Problem] = []
    walls = room["walls"]
    for index, wall in enumerate(walls):
        following = walls[(index + 1) % len(walls)]
        if any(abs(a - b) > 1e-6 for a, b in zip(wall["to"], following["from"], strict=False)):
            problems.append(
                (
                    f"$.room.walls[{index}].to",
                    f"wall {wall['id']!r} ends where the next wall does not start",
                )
            )
    wall_ids = {wall["id"] for wall in walls}
    for index, opening in enumerate(room["openings"]):
        if opening["wall"] not in wall_ids:
            problems.append(
                (
                    f"$.room.openings[{index}].wall",
                    f"{opening['wall']!r} is not a wall of this room",
                )
            )
    if not problems:
        try:
            Room.from_dict(room)
        except RoomError as problem:
            problems.append(("$.room", str(problem)))
    ids = wall_ids | {opening["id"] for opening in room["openings"]} | {ROOM_NODE}
    return ids, problems


def _nesting_problems(data: dict[str, Any], entities: dict[str, tuple[str, dict]]) -> list[Problem]:
    """Groups whose parents lead round in a cycle or nest deeper than ``MAX_GROUP_DEPTH``."""
    problems: list[Problem] = []
    depth: dict[str, int] = {}  # id -> how many groups hold it
    for entity_id, (where, _entry) in entities.items():
        chain: list[str] = []
        current: str | None = entity_id
        while current is not None and current not in depth:
            if current in chain:
                cycle = " -> ".join(chain[chain.index(current) :] + [current])
                problems.append(
                    (f"{where}.parent", f"its parents lead round in a cycle ({_clipped(cycle)})")
                )
                break
            chain.append(current)
            current = entities[current][1].get("parent")
        else:
            base = -1 if current is None else depth[current]
            for step, member in enumerate(reversed(chain), start=1):
                depth[member] = base + step
            if depth[entity_id] > MAX_GROUP_DEPTH:
                problems.append(
                    (
                        f"{where}.parent",
                        f"it lies {depth[entity_id]} groups deep; groups may nest "
                        f"at most {MAX_GROUP_DEPTH} deep",
                    )
                )
            continue
        for member in chain:
            depth[member] = 0  # reported once: do not follow the cycle again
    return problems


def _nearest(word: str, known) -> str:
    close = difflib.get_close_matches(word, sorted(known), n=1)
    return f"; did you mean {close[0]!r}?" if close else ""


def _article(kind: str) -> str:
    return ("an " if kind[:1] in "aeiou" else "a ") + kind


# -- schema ----------------------------------------------------------------------


@cache
def packaged_schema_text(package: str, *path: str) -> str:
    """The text of a JSON Schema shipped as package data (``package``, then its path)."""
    return resources.files(package).joinpath(*path).read_text(encoding="utf-8")


@cache
def packaged_validator(package: str, *path: str) -> jsonschema.Draft202012Validator:
    """A checked draft 2020-12 validator of a JSON Schema shipped as package data."""
    schema = json.loads(packaged_schema_text(package, *path))
    jsonschema.Draft202012Validator.check_schema(schema)
    return jsonschema.Draft202012Validator(schema)


def _schema_text() -> str:
    return packaged_schema_text("scenewright.core", "schema", SCHEMA_FILE)


def _validator() -> jsonschema.Draft202012Validator:
    return packaged_validator("scenewright.core", "schema", SCHEMA_FILE)


def schema_message(error: jsonschema.ValidationError, limit: int = 300) -> str:
    """A schema error's message on one line, the value it quotes shortened to 60
    characters first, so what is wrong with the value (which follows it) is never cut off."""
    message = error.message
    shown = repr(error.instance)
    if len(shown) > 60 and shown in message:
        message = message.replace(shown, shown[:56] + "...", 1)
    return _one_line(message, limit)


def _one_line(message: str, limit: int = 200) -> str:
    """Error messages quote the offending value, which may be long or span lines."""
    return _clipped(" ".join(message.split()), limit)


def _clipped(text: str, limit: int = 200) -> str:
    return text if len(text) <= limit else text[: limit - 3] + "..."
