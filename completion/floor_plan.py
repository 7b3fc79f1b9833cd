"""The plan format: one furnished room as a designer drew it, read from JSON and checked.

A plan file (``plan.schema.json``, package data) holds the room exactly as scene.json
writes one (``Room.to_dict``: walls and openings), its furniture as labelled
footprints (category, centre, size, yaw, and for a lamp or a television the piece it
stands ``on``) and optional free areas. ``read_plan`` reads one file and
``load_plans`` a folder of them (searched recursively, in sorted path order); anything
wrong raises ``PlanError``, an ``InputError`` whose one line names the file and the
JSON path (``bedroom_01.json: $.furniture[3].category: ...``). The checks are, in
order: JSON, the schema, the room (it must build: ``core.room``), the furniture's
categories (entries of the indoor catalog) and ids, then the drawing itself
(``plan_checks``: inside the walls, no overlaps, doors free to swing, clearances kept).

Frames are scene.json's: metres, x east, z south, yaw radians with 0 facing south.
"""

from __future__ import annotations

import difflib
import json
from dataclasses import dataclass
from functools import cached_property, lru_cache
from importlib import resources
from pathlib import Path
from typing import Any

import jsonschema
import referencing
from jsonschema.exceptions import best_match

from scenewright.core.errors import InputError, RoomError
from scenewright.core.files import UnusableFile, load_json, read_regular_file
from scenewright.core.frames import footprint_corners
from scenewright.core.geometry import Rect, make_rect
from scenewright.core.room import Room
from scenewright.core.schema_check import json_path, load_schema, schema_message

SCHEMA_FILE = "plan.schema.json"
#: A plan is a room's worth of furniture: a larger file is not one.
MAX_PLAN_BYTES = 1024 * 1024
#: The most plan files one set may hold.
MAX_PLANS = 5000


class PlanError(InputError):
    """A plan that cannot be used: ``source`` (its file), ``path`` (JSON path), ``reason``."""

    def __init__(self, source: str, path: str, reason: str):
        self.source, self.path, self.reason = source, path, reason
        super().__init__(f"{source}: {path}: {reason}" if path else f"{source}: {reason}")


@dataclass(frozen=True)
class Furniture:
    """One piece: its footprint ``size`` (width, depth) at ``center`` (x, z), turned ``yaw``."""

    id: str
    category: str
    center: tuple[float, float]
    size: tuple[float, float]
    yaw: float
    on: str | None = None

    @property
    def area(self) -> float:
        return self.size[0] * self.size[1]

    @cached_property
    def rect(self) -> Rect:
        """The footprint as ``core.geometry`` measures it."""
        return make_rect(*self.center, *self.size, self.yaw)

    @cached_property
    def corners(self) -> list[tuple[float, float]]:
        """Footprint corners (x, z), in ``core.frames.footprint_corners`` order."""
        return footprint_corners(
            self.center[0], self.center[1], self.yaw, self.size[0], self.size[1]
        )

    def to_dict(self) -> dict:
        data = {
            "id": self.id,
            "category": self.category,
            "center": list(self.center),
            "size": list(self.size),
            "yaw": self.yaw,
        }
        if self.on is not None:
            data["on"] = self.on
        return data


@dataclass(frozen=True)
class FreeArea:
    """An axis-aligned rectangle of free floor: ``size`` is its (x, z) extent."""

    center: tuple[float, float]
    size: tuple[float, float]
    suits: tuple[str, ...] = ()

    def to_dict(self) -> dict:
        data: dict[str, list] = {"center": list(self.center), "size": list(self.size)}
        if self.suits:
            data["suits"] = list(self.suits)
        return data


@dataclass(frozen=True)
class Plan:
    """A furnished room of a type; ``source`` is the file it was read from."""

    id: str
    type: str
    room: Room
    furniture: tuple[Furniture, ...]
    free_areas: tuple[FreeArea, ...] = ()
    title: str = ""
    source: str = "<plan>"

    def to_dict(self) -> dict:
        """The plan's JSON form (what ``plan_from_dict`` reads back)."""
        data: dict[str, Any] = {"id": self.id, "type": self.type}
        if self.title:
            data["title"] = self.title
        data["room"] = self.room.to_dict()
        data["furniture"] = [piece.to_dict() for piece in self.furniture]
        if self.free_areas:
            data["free_areas"] = [area.to_dict() for area in self.free_areas]
        return data

    def piece(self, piece_id: str) -> Furniture:
        return next(piece for piece in self.furniture if piece.id == piece_id)


def read_plan(path: str | Path) -> Plan:
    """The checked plan in the JSON file ``path``; ``PlanError`` if anything is wrong."""
    source = str(path)
    try:
        text = read_regular_file(path, MAX_PLAN_BYTES, "a plan").decode("utf-8")
    except UnusableFile as problem:
        raise PlanError(source, "", f"cannot read: it {problem}") from None
    except OSError as error:
        raise PlanError(source, "", f"cannot read: {error.strerror or error}") from None
    except UnicodeDecodeError:
        raise PlanError(source, "", "not UTF-8 text") from None
    try:
        data = load_json(text, parse_constant=_refuse_constant)
    except ValueError as error:
        raise PlanError(source, "", f"not JSON: {error}") from None
    return plan_from_dict(data, source)


def plan_from_dict(data: Any, source: str = "<plan>") -> Plan:
    """A checked ``Plan`` from its JSON document (see the module docstring)."""
    from scenewright.completion.plan_checks import plan_problems
    from scenewright.generator import indoor_catalog

    error = best_match(_validator().iter_errors(data))
    if error is not None:
        raise PlanError(source, json_path(error.absolute_path), schema_message(error))
    try:
        room = Room.from_dict(data["room"])
    except RoomError as problem:
        raise PlanError(source, "$.room", str(problem)) from None
    known = indoor_catalog()
    seen: set[str] = set()
    for index, raw in enumerate(data["furniture"]):
        where = f"$.furniture[{index}]"
        if raw["category"] not in known:
            nearest = difflib.get_close_matches(raw["category"], sorted(known), n=1)
            hint = f"; did you mean {nearest[0]!r}?" if nearest else ""
            raise PlanError(
                source,
                f"{where}.category",
                f"{raw['category']!r} is not an indoor catalog entry{hint}",
            )
        if raw["id"] in seen:
            raise PlanError(source, f"{where}.id", f"the id {raw['id']!r} is used twice")
        seen.add(raw["id"])
    for index, raw in enumerate(data["furniture"]):
        if raw.get("on") is not None and (raw["on"] not in seen or raw["on"] == raw["id"]):
            raise PlanError(
                source,
                f"$.furniture[{index}].on",
                f"{raw['on']!r} is not another piece of this plan",
            )
    for index, area in enumerate(data.get("free_areas", [])):
        for k, name in enumerate(area.get("suits", [])):
            if name not in known:
                raise PlanError(
                    source,
                    f"$.free_areas[{index}].suits[{k}]",
                    f"{name!r} is not an indoor catalog entry",
                )
    plan = Plan(
        id=data["id"],
        type=data["type"],
        room=room,
        furniture=tuple(
            Furniture(
                raw["id"],
                raw["category"],
                _pair(raw["center"]),
                _pair(raw["size"]),
                float(raw["yaw"]),
                raw.get("on"),
            )
            for raw in data["furniture"]
        ),
        free_areas=tuple(
            FreeArea(_pair(area["center"]), _pair(area["size"]), tuple(area.get("suits", ())))
            for area in data.get("free_areas", [])
        ),
        title=data.get("title", ""),
        source=source,
    )
    problems = plan_problems(plan)
    if problems:
        raise PlanError(source, *problems[0])
    return plan


def load_plans(folder: str | Path) -> list[Plan]:
    """Every plan under ``folder`` (``*.json``, recursively, sorted by path); plan ids
    must be unique in the set. ``PlanError`` for the first bad file, and for a file
    whose links lead outside the folder (``ReadScope``: nothing outside is read unless
    the user allows it with ``SCENEWRIGHT_ALLOW_OUTSIDE``)."""
    from scenewright.generator.rules_scope import ReadScope

    root = Path(folder)
    if not root.is_dir():
        raise PlanError(str(root), "", "not a folder of plans")
    scope = ReadScope.of_folder(root)  # a plan set reads its own folder, as a rule set does
    files = sorted(path for path in root.rglob("*.json") if path.is_file())
    if not files:
        raise PlanError(str(root), "", "holds no plan files (*.json)")
    if len(files) > MAX_PLANS:
        raise PlanError(str(root), "", f"holds {len(files)} plan files, more than {MAX_PLANS}")
    plans: list = []
    first_seen: dict = {}
    for path in files:
        why = scope.outside(path, "plan set")
        if why is not None:
            raise PlanError(str(path), "", f"not read: it {why}")
        plan = read_plan(path)
        if plan.id in first_seen:
            raise PlanError(
                str(path), "$.id", f"the plan id {plan.id!r} is also used by {first_seen[plan.id]}"
            )
        first_seen[plan.id] = str(path)
        plans.append(plan)
    return plans


def rounded(value, decimals: int):
    """``value`` with every float in its nested lists and dicts rounded to ``decimals``
    (files written from floats carry no noise such as 1.4500000000000002; no -0.0)."""
    if isinstance(value, float):
        return round(value, decimals) + 0.0
    if isinstance(value, list):
        return [rounded(item, decimals) for item in value]
    if isinstance(value, dict):
        return {key: rounded(item, decimals) for key, item in value.items()}
    return value


def _pair(values) -> tuple[float, float]:
    return float(values[0]), float(values[1])


def _refuse_constant(name: str):
    raise ValueError(f"{name} is not a number a plan may hold")


@lru_cache(maxsize=1)
def _validator() -> jsonschema.Draft202012Validator:
    scene_schema = load_schema()
    plan_schema = json.loads(
        resources.files("scenewright.completion").joinpath(SCHEMA_FILE).read_text("utf-8")
    )
    registry = referencing.Registry().with_resources(
        [
            (schema["$id"], referencing.Resource.from_contents(schema))
            for schema in (scene_schema, plan_schema)
        ]
    )
    jsonschema.Draft202012Validator.check_schema(plan_schema)
    return jsonschema.Draft202012Validator(plan_schema, registry=registry)
