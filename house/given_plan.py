"""A floor plan given by the user as JSON: room polygons with types, and optionally doors and windows.

    {
      "noun": "flat",                                   # optional, default "house"
      "height": 2.6,                                    # optional wall height
      "rooms": [
        {"id": "hall", "type": "hall", "polygon": [[0, 0], [2, 0], [2, 6], [0, 6]]},
        {"type": "bedroom", "polygon": [[2, 0], [6, 0], [6, 4], [2, 4]], "name": "guest room"},
        ...
      ],
      "doors": [                                        # optional
        {"between": ["hall"]},                          # the front door, into the hall
        {"between": ["hall", "bedroom_1"], "center": [2, 2]},
        {"between": ["kitchen", "living_room_1"], "open": true}
      ],
      "windows": [{"room": "bedroom_1", "center": [4, 0], "width": 1.2}]   # optional
    }

Polygons run along the walls' centre lines, corners in order, in metres (x east, z
south); neighbouring rooms share the stretch of outline between them (as shapely
polygons of a partition do). A room's ``type`` names the rule set that furnishes it (a
shipped room rule set, or ``"rules": "FILE.rules"`` beside the plan). Without
``doors``, the front door goes into the first hall or corridor (else the first room)
and doors join rooms that touch until every room can be reached, halls and corridors
first. Without ``windows``, every room but halls and corridors gets windows in its
outside walls. Every mistake is one line naming the place in the file.
"""

from __future__ import annotations

import json
import math
import os
from pathlib import Path
from typing import Any

from scenewright.core.errors import InputError
from scenewright.core.limits import MAX_SCENE_JSON_BYTES as MAX_INPUT_BYTES
from scenewright.generator import load_rules
from scenewright.generator.rules_errors import RulesError, did_you_mean

from .outline import Outlines, PlannedDoor, PlannedRoom, PlannedWindow
from .plan_language import CIRCULATION, MAX_ROOMS, MAX_SIDE, _uses_windows, room_rule_sets

#: The shortest shared wall a door is put in when the plan gives no doors (m).
DOOR_WALL = 1.3


class GivenPlanError(InputError):
    """A given plan that is not valid: the message names the place in the file."""


def is_given_plan(source: str | os.PathLike[str]) -> bool:
    return os.fspath(source).lower().endswith(".json")


def read_given_plan(source: str | os.PathLike[str]) -> Outlines:
    path = Path(os.fspath(source))
    where = path.name
    try:
        if path.stat().st_size > MAX_INPUT_BYTES:
            raise GivenPlanError(f"{where}: larger than {MAX_INPUT_BYTES} bytes")
        data = json.loads(path.read_text(encoding="utf-8"))
    except FileNotFoundError:
        raise GivenPlanError(f"{where}: no such file") from None
    except (OSError, UnicodeDecodeError) as error:
        raise GivenPlanError(f"{where}: cannot be read ({error.__class__.__name__})") from None
    except json.JSONDecodeError as error:
        raise GivenPlanError(
            f"{where}:{error.lineno}:{error.colno}: not JSON: {error.msg}"
        ) from None
    if not isinstance(data, dict):
        raise GivenPlanError(f"{where}: a plan is a JSON object with a list 'rooms'")
    raw_rooms = data.get("rooms")
    if not isinstance(raw_rooms, list) or not raw_rooms:
        raise GivenPlanError(f"{where}: 'rooms' must be a non-empty list")
    if len(raw_rooms) > MAX_ROOMS:
        raise GivenPlanError(f"{where}: {len(raw_rooms)} rooms; at most {MAX_ROOMS}")
    height = _number(data.get("height", 2.6), f"{where}: height", 2.0, 10.0)
    rooms = _rooms(raw_rooms, path, where)
    doors = _doors(data["doors"], rooms, where) if "doors" in data else _default_doors(rooms)
    windows = _windows(data["windows"], rooms, where) if "windows" in data else None
    points = [p for room in rooms for p in room.outline]
    xs, zs = [p[0] for p in points], [p[1] for p in points]
    footprint = ((min(xs), min(zs)), (max(xs), min(zs)), (max(xs), max(zs)), (min(xs), max(zs)))
    noun = data.get("noun", "house")
    if not isinstance(noun, str) or not noun.strip():
        raise GivenPlanError(f'{where}: noun: give a word such as "flat"')
    return Outlines(
        noun=noun,
        footprint=footprint,
        holes=(),
        height=height,
        rooms=rooms,
        doors=doors,
        windows=windows,
        notes={"given": where},
    )


def _rooms(raw_rooms: list, path: Path, where: str) -> list[PlannedRoom]:
    known = list(room_rule_sets())
    rooms: list[PlannedRoom] = []
    counts: dict[str, int] = {}
    types = [r.get("type") if isinstance(r, dict) else None for r in raw_rooms]
    for k, raw in enumerate(raw_rooms):
        at = f"{where}: rooms[{k}]"
        if not isinstance(raw, dict):
            raise GivenPlanError(f"{at}: a room is an object with 'type' and 'polygon'")
        room_type = raw.get("type")
        if not isinstance(room_type, str) or not room_type:
            raise GivenPlanError(f"{at}: 'type' must name the room type (bedroom, kitchen, ...)")
        if "rules" in raw:
            if not isinstance(raw["rules"], str):
                raise GivenPlanError(f"{at}: 'rules' must be a rules file name")
            source = (
                raw["rules"]
                if raw["rules"] in known
                else str((path.parent / raw["rules"]).resolve())
            )
        elif room_type in known:
            source = room_type
        else:
            hint = did_you_mean(room_type, known) or ""
            raise GivenPlanError(
                f"{at}: no shipped rule set furnishes room type '{room_type}'{hint}; "
                f'give one with "rules": "FILE.rules"'
            )
        try:
            loaded = load_rules(source)
        except RulesError as error:
            first = str(error).splitlines()[0]
            raise GivenPlanError(f"{at}: its rule set does not load: {first}") from None
        if loaded.params.room is None:
            raise GivenPlanError(f"{at}: rule set '{loaded.name}' is not a room")
        polygon = raw.get("polygon")
        if not isinstance(polygon, list) or len(polygon) < 3:
            raise GivenPlanError(f"{at}: 'polygon' must list at least three [x, z] corners")
        corners = []
        for j, corner in enumerate(polygon):
            if (
                not isinstance(corner, list)
                or len(corner) != 2
                or not all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in corner)
                or not all(math.isfinite(v) and abs(v) <= MAX_SIDE for v in corner)
            ):
                raise GivenPlanError(
                    f"{at}: polygon[{j}]: a corner is [x, z] in metres (at most {MAX_SIDE:g} out)"
                )
            corners.append((float(corner[0]), float(corner[1])))
        counts[room_type] = counts.get(room_type, 0) + 1
        room_id = raw.get("id", f"{room_type}_{counts[room_type]}")
        if not isinstance(room_id, str) or not room_id or "/" in room_id:
            raise GivenPlanError(f"{at}: 'id' must be a name without '/'")
        if any(r.id == room_id for r in rooms):
            raise GivenPlanError(f"{at}: a second room with id '{room_id}'")
        name = raw.get("name", _default_name(room_type, counts[room_type], types.count(room_type)))
        first_window = next(iter(loaded.params.room.windows), None)
        rooms.append(
            PlannedRoom(
                id=room_id,
                type=room_type,
                name=str(name),
                rules=source,
                outline=tuple(corners),
                wants_window=_uses_windows(loaded) or room_type not in CIRCULATION,
                window=(first_window.width, first_window.height, first_window.sill)
                if first_window is not None
                else None,
            )
        )
    return rooms


def _default_name(room_type: str, index: int, of: int) -> str:
    from scenewright.describer.english import ordinal_word

    words = room_type.replace("_", " ")
    return f"{ordinal_word(index)} {words}" if of > 1 else words


def _doors(raw_doors: Any, rooms: list[PlannedRoom], where: str) -> list[PlannedDoor]:
    if not isinstance(raw_doors, list):
        raise GivenPlanError(f"{where}: 'doors' must be a list")
    ids = [room.id for room in rooms]
    doors = []
    for k, raw in enumerate(raw_doors):
        at = f"{where}: doors[{k}]"
        between = raw.get("between") if isinstance(raw, dict) else None
        if not isinstance(between, list) or not 1 <= len(between) <= 2:
            raise GivenPlanError(f"{at}: 'between' lists one room (a front door) or two")
        for room_id in between:
            if room_id not in ids:
                hint = did_you_mean(str(room_id), ids) or ""
                raise GivenPlanError(f"{at}: there is no room '{room_id}'{hint}")
        center = raw.get("center")
        if center is not None and not (
            isinstance(center, list)
            and len(center) == 2
            and all(isinstance(v, (int, float)) for v in center)
        ):
            raise GivenPlanError(f"{at}: 'center' is [x, z] on the wall's centre line")
        width = raw.get("width")
        if width is not None:
            width = _number(width, f"{at}: width", 0.6, 3.0)
        doors.append(
            PlannedDoor(
                rooms=tuple(between),
                open=bool(raw.get("open", False)),
                center=(float(center[0]), float(center[1])) if center is not None else None,
                width=width,
            )
        )
    if not any(len(d.rooms) == 1 for d in doors):
        raise GivenPlanError(f'{where}: doors: no front door ({{"between": [ROOM]}})')
    return doors


def _windows(raw_windows: Any, rooms: list[PlannedRoom], where: str) -> list[PlannedWindow]:
    if not isinstance(raw_windows, list):
        raise GivenPlanError(f"{where}: 'windows' must be a list")
    ids = [room.id for room in rooms]
    windows = []
    for k, raw in enumerate(raw_windows):
        at = f"{where}: windows[{k}]"
        if not isinstance(raw, dict) or raw.get("room") not in ids:
            raise GivenPlanError(f"{at}: 'room' must name a room of the plan")
        center = raw.get("center")
        if not (
            isinstance(center, list)
            and len(center) == 2
            and all(isinstance(v, (int, float)) for v in center)
        ):
            raise GivenPlanError(f"{at}: 'center' is [x, z] on an outside wall's centre line")
        windows.append(
            PlannedWindow(
                room=raw["room"],
                center=(float(center[0]), float(center[1])),
                width=_number(raw.get("width", 1.2), f"{at}: width", 0.3, 6.0),
                height=_number(raw.get("height", 1.3), f"{at}: height", 0.3, 3.0),
                sill=_number(raw.get("sill", 0.9), f"{at}: sill", 0.0, 2.5),
            )
        )
    return windows


def _default_doors(rooms: list[PlannedRoom]) -> list[PlannedDoor]:
    """A front door and doors that make every room reachable, halls and corridors first."""
    from .walls import _pieces

    shared: dict[tuple[int, int], float] = {}
    outside: dict[int, float] = {}
    for piece in _pieces(rooms):
        if piece.other is None:
            outside[piece.room] = max(outside.get(piece.room, 0.0), piece.length)
        else:
            key = (min(piece.room, piece.other), max(piece.room, piece.other))
            shared[key] = max(shared.get(key, 0.0), piece.length)
    entrance = next(
        (
            k
            for k, r in enumerate(rooms)
            if r.type in CIRCULATION and outside.get(k, 0) >= DOOR_WALL
        ),
        None,
    )
    if entrance is None:
        entrance = next((k for k in range(len(rooms)) if outside.get(k, 0) >= DOOR_WALL), None)
    if entrance is None:
        raise GivenPlanError("no room has an outside wall long enough for the front door")
    doors = [PlannedDoor((rooms[entrance].id,))]
    reached = {entrance}
    while len(reached) < len(rooms):
        options = [
            ((rooms[r].type in CIRCULATION, length, -r, -k), r, k)
            for (a, b), length in shared.items()
            if length >= DOOR_WALL
            for r, k in ((a, b), (b, a))
            if r in reached and k not in reached
        ]
        if not options:
            missing = [rooms[k].id for k in range(len(rooms)) if k not in reached]
            raise GivenPlanError(
                f"no wall of {DOOR_WALL:g} m or more joins {', '.join(missing)} to the rest of the plan"
            )
        _key, r, k = max(options)
        doors.append(PlannedDoor((rooms[r].id, rooms[k].id)))
        reached.add(k)
    return doors


def _number(value: Any, what: str, low: float, high: float) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise GivenPlanError(f"{what}: a number, {low:g} to {high:g}")
    if not low <= value <= high:
        raise GivenPlanError(f"{what}: {value:g} is not between {low:g} and {high:g}")
    return float(value)
