"""The laid-out scene as plain data, and its scene.json form.

A ``Scene`` is what the describer, the renderer and the exporter read: every object,
group and junction with its pose and size, every path with its control points, every
relation (``PathConnectedTo`` included) with its layout verdict, the layout's
statistics, and (once made) the description and render metadata. ``assemble_scene``
builds one from a scene graph and a layout result; ``Scene.to_json`` /
``Scene.from_json`` are the scene.json contract documented by
``core/schema/scene.schema.json``. A Scene is data: the stages that describe,
render or export it take it as an argument and return their results as values.
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field, fields, is_dataclass
from typing import Any

import numpy as np

from . import VERSION
from .frames import footprint_corners_many
from .house import House
from .poses import LayoutResult
from .relations import Relation
from .room import ROOM_KINDS, Room
from .scene_graph import (
    OPTIONAL_NODE_FIELDS,
    SceneGraph,
    SceneNode,
    SceneParams,
    descendants_in,
)

#: Bumped when scene.json changes shape or meaning. 2: relations keep PathConnectedTo,
#: seeds are split into per-stage streams, ``derivation`` records every random choice.
#: 3: ``room`` (walls, doors, windows) replaces the ``walls`` flag.
SCENE_FORMAT_VERSION = 3
#: Decimal places of the floats in scene.json: micrometres.
JSON_DIGITS = 6


@dataclass
class SceneObject:
    """An object, group or junction with its pose.

    ``position`` is the base centre [x, y, z]; ``size`` is [w, h, d] along the object's
    local axes. A group's pose is the axis-aligned box around its members (yaw 0).
    """

    id: str
    type: str
    kind: str
    noun: str
    plural: str | None
    parent: str | None
    style: str | None
    position: list[float]
    yaw: float
    size: list[float]
    shape: str | None = None
    mesh: str | None = None
    colour: list[float] = field(default_factory=lambda: [0.6, 0.6, 0.6])
    rule: str | None = None
    order: int = 0
    #: Free floor kept beside it and the sides it is used from (``SceneNode``).
    clearance: list[list] = field(default_factory=list)
    access: list[str] = field(default_factory=list)
    #: Junctions only: "grid" for a grid's junction; None (left out of scene.json) else.
    network: str | None = None
    #: Objects only: how far its wall label keeps its back off the wall (``SceneNode``);
    #: None (left out of scene.json): flush.
    wall_gap: float | None = None


@dataclass
class ScenePath:
    """A path (road, trail): control points [[x, z], ...] and a width in metres."""

    id: str
    type: str
    noun: str
    plural: str | None
    parent: str | None
    points: list[list[float]]
    width: float
    start: str | None = None  # the junction it starts at, or the path it branches from
    colour: list[float] = field(default_factory=lambda: [0.55, 0.45, 0.3])
    rule: str | None = None
    order: int = 0
    max_length: float = 30.0  # the longest it may be, in metres
    segments: int = 3  # straight pieces of its polyline


#: One relation a description states: (subject id, label, object id).
Fact = tuple[str, str, str]


@dataclass
class SceneDescription:
    """scene.json's ``description``: the text, every relation it states, and the style
    and paraphrase variant that made it. The describer makes one (its ``Description``
    adds the text sentence by sentence and the phrases that name things)."""

    text: str
    facts: list[Fact] = field(default_factory=list)
    style: str = "full"
    variant: int = 0

    def to_dict(self) -> dict[str, Any]:
        """The JSON-ready form stored in scene.json's ``description``."""
        return {
            "text": self.text,
            "facts": [list(fact) for fact in self.facts],
            "style": self.style,
            "variant": self.variant,
        }

    @classmethod
    def from_dict(cls, data: dict[str, Any]) -> SceneDescription:
        """The record ``to_dict`` gave (only ``text`` is required)."""
        return cls(
            text=data["text"],
            facts=[(subject, label, target) for subject, label, target in data.get("facts", [])],
            style=data.get("style", "full"),
            variant=int(data.get("variant", 0)),
        )


@dataclass
class LayoutStats:
    energy: float = 0.0
    parts: dict[str, float] = field(default_factory=dict)
    steps: int = 0
    acceptance: float = 0.0
    seconds: float = 0.0
    ok: bool = True
    problems: list[str] = field(default_factory=list)


@dataclass
class Scene:
    """A generated scene: the plain data every later stage reads."""

    rules: str
    seed: int
    extent: list[float]
    objects: list[SceneObject]
    paths: list[ScenePath]
    relations: list[Relation]
    layout: LayoutStats = field(default_factory=LayoutStats)
    #: The walls, doors and windows of an indoor scene (``core.room``); None outdoors.
    room: Room | None = None
    #: The floor plan of a house of several rooms (``core.house``); None for one room or
    #: open ground. Its rooms' furniture is in ``objects``, ids ``ROOM/OBJECT``.
    house: House | None = None
    ground: str = "grass"
    name: str = "scene"
    #: The folder of description templates the rule set brings (absolute path), which
    #: ``describe`` reads unless told otherwise; None: the package's own templates.
    templates: str | None = None
    #: In a room: furniture kept square to the walls; relations need a line of sight.
    square: bool = True
    line_of_sight: bool = True
    #: Every random choice of the grammar expansion, in order (see ``generator.derivation``).
    derivation: list[dict[str, Any]] = field(default_factory=list)
    description: SceneDescription | None = None
    render: dict[str, Any] | None = None
    #: How ``scenewright complete`` chose the room's contents (``completion.complete``);
    #: None (and absent from scene.json) for a scene made from rules.
    completion: dict[str, Any] | None = None
    timings: dict[str, float] = field(default_factory=dict)
    version: str = ""

    # -- lookups ------------------------------------------------------------------

    def object(self, object_id: str) -> SceneObject:
        for obj in self.objects:
            if obj.id == object_id:
                return obj
        raise KeyError(object_id)

    def path(self, path_id: str) -> ScenePath:
        for path in self.paths:
            if path.id == path_id:
                return path
        raise KeyError(path_id)

    def entity(self, entity_id: str) -> SceneObject | ScenePath:
        """The object, group, junction or path with this id."""
        try:
            return self.object(entity_id)
        except KeyError:
            return self.path(entity_id)

    def placed_objects(self) -> list[SceneObject]:
        """Objects with a body (kind ``object``), the ones that are drawn and collide."""
        return [o for o in self.objects if o.kind == "object"]

    # -- scene.json ---------------------------------------------------------------

    @property
    def walls(self) -> bool:
        """Whether the scene is a room bounded by walls."""
        return self.room is not None

    def to_dict(self) -> dict[str, Any]:
        return self._as_dict(None)

    def to_json(self, indent: int | None = 1, *, reproducible: bool = False) -> str:
        """scene.json text: deterministic (keys in field order, floats rounded to 1e-6).

        ``reproducible`` leaves out the wall-clock times (``timings``, ``layout.seconds``),
        the only values that differ between two runs with the same rules and seed.
        """
        data = self._as_dict(JSON_DIGITS)
        if reproducible:
            del data["timings"]
            del data["layout"]["seconds"]
        return json.dumps(data, indent=indent, ensure_ascii=False) + "\n"

    def _as_dict(self, digits: int | None) -> dict[str, Any]:
        """The fields as plain data (``_plain``; floats rounded to ``digits`` when given),
        the room as its own dict, an absent ``completion`` left out, and the format's
        version: scene.json's content, in one pass over the scene."""
        own = {
            "room": self.room.to_dict() if self.room is not None else None,
            "house": self.house.to_dict() if self.house is not None else None,
        }
        data = {
            f.name: _plain(own[f.name] if f.name in own else getattr(self, f.name), digits)
            for f in fields(self)
        }
        if data["completion"] is None:
            del data["completion"]
        if data["house"] is None:
            del data["house"]
        for obj in data["objects"]:  # a network or wall gap only where set
            for name in OPTIONAL_NODE_FIELDS:
                if obj[name] is None:
                    del obj[name]
        data["format"] = SCENE_FORMAT_VERSION
        return data

    @classmethod
    def from_dict(cls, data: dict[str, Any]) -> Scene:
        def build(kind, raw):
            names = {f.name for f in fields(kind)}
            return kind(**{k: v for k, v in raw.items() if k in names})

        return cls(
            rules=data["rules"],
            seed=int(data["seed"]),
            extent=list(data["extent"]),
            objects=[build(SceneObject, o) for o in data["objects"]],
            paths=[build(ScenePath, p) for p in data.get("paths", [])],
            relations=[build(Relation, r) for r in data.get("relations", [])],
            layout=build(LayoutStats, data.get("layout", {})),
            room=SceneParams.from_dict(data).room,
            house=House.from_dict(data["house"]) if data.get("house") else None,
            ground=data.get("ground", "grass"),
            name=data.get("name", "scene"),
            templates=data.get("templates"),
            square=bool(data.get("square", True)),
            line_of_sight=bool(data.get("line_of_sight", True)),
            derivation=list(data.get("derivation", [])),
            description=SceneDescription.from_dict(data["description"])
            if data.get("description") is not None
            else None,
            render=data.get("render"),
            completion=data.get("completion"),
            timings=dict(data.get("timings", {})),
            version=data.get("version", ""),
        )

    @classmethod
    def from_json(cls, text: str) -> Scene:
        return cls.from_dict(json.loads(text))

    # -- back to a graph ----------------------------------------------------------

    def graph(self) -> SceneGraph:
        """The scene relationship graph this scene was laid out from (every node, every
        relation, the scene parameters, the derivation); a relation to ``some road``
        names the road the layout gave it, and is no longer marked as drawn."""
        nodes = [_node_of(o) for o in self.objects] + [_node_of_path(p) for p in self.paths]
        nodes.sort(key=lambda n: n["order"])
        return SceneGraph.from_dict(
            {
                "params": SceneParams(
                    name=self.name,
                    extent=(self.extent[0], self.extent[1]),
                    ground=self.ground,
                    room=self.room,
                    templates=self.templates,
                    square=self.square,
                    line_of_sight=self.line_of_sight,
                ).to_dict(),
                "nodes": nodes,
                "edges": [
                    {"source": r.source, "target": r.target, "label": r.label}
                    for r in self.relations
                ],
                "derivation": self.derivation,
            }
        )


def assemble_scene(graph: SceneGraph, layout: LayoutResult, *, rules: str, seed: int) -> Scene:
    """Join a scene graph and its layout into a ``Scene`` (groups get their members' box)."""
    objects: list[SceneObject] = []
    paths: list[ScenePath] = []
    starts = {e.source: e.target for e in graph.edges("PathConnectedTo")}
    for node in graph.nodes():
        if node.kind == "path":
            # expansion gives every path node its width, length and segments
            assert node.width is not None and node.max_length is not None
            assert node.segments is not None
            paths.append(
                ScenePath(
                    id=node.id,
                    type=node.type,
                    noun=node.noun,
                    plural=node.plural,
                    parent=node.parent,
                    points=np.asarray(layout.paths[node.id], dtype=float).tolist(),
                    width=float(node.width),
                    start=starts.get(node.id),
                    colour=list(node.colour),
                    rule=node.rule,
                    order=node.order,
                    max_length=float(node.max_length),
                    segments=int(node.segments),
                )
            )
        elif node.kind == "group":
            continue  # placed below, once its members are
        elif node.kind in ROOM_KINDS:
            continue  # the room is the scene's ``room``
        else:
            pose = layout.poses[node.id]
            objects.append(_object_of(node, [pose.x, pose.y, pose.z], pose.yaw, list(node.size)))

    placed = {o.id: o for o in objects}
    by_parent = graph.by_parent()
    for group in graph.nodes("group"):
        members = [placed[m.id] for m in descendants_in(by_parent, group.id) if m.id in placed]
        position, size = _union_box(members)
        objects.append(_object_of(group, position, 0.0, size))
    objects.sort(key=lambda o: o.order)

    relations = [
        Relation(r.source, r.target, r.label, _measured(r.value), bool(r.satisfied), r.chosen)
        for r in layout.relations
    ]
    stats = LayoutStats(
        energy=float(layout.energy),
        parts={k: float(v) for k, v in layout.parts.items()},
        steps=int(layout.steps),
        acceptance=float(layout.acceptance),
        seconds=float(layout.seconds),
        ok=bool(layout.ok),
        problems=list(layout.problems),
    )
    return Scene(
        rules=rules,
        seed=seed,
        extent=list(graph.params.extent),
        objects=objects,
        paths=paths,
        relations=relations,
        layout=stats,
        room=graph.params.room,
        ground=graph.params.ground,
        name=graph.params.name,
        templates=graph.params.templates,
        square=graph.params.square,
        line_of_sight=graph.params.line_of_sight,
        derivation=list(graph.derivation),
        version=VERSION,
    )


def object_corners(objects: list[SceneObject]) -> np.ndarray:
    """(n, 4, 2) corners (x, z) of the objects' turned footprints (``frames`` order)."""
    centres = np.array([[o.position[0], o.position[2]] for o in objects], dtype=float).reshape(
        -1, 2
    )
    yaw = np.array([o.yaw for o in objects], dtype=float)
    sizes = np.array([[o.size[0], o.size[2]] for o in objects], dtype=float).reshape(-1, 2)
    return footprint_corners_many(centres, yaw, sizes)


def _union_box(members: list[SceneObject]) -> tuple[list[float], list[float]]:
    if not members:
        return [0.0, 0.0, 0.0], [0.0, 0.0, 0.0]
    corners = object_corners(members).reshape(-1, 2)
    lo, hi = corners.min(axis=0), corners.max(axis=0)
    top = max(m.position[1] + m.size[1] for m in members)
    bottom = min(m.position[1] for m in members)
    centre = (lo + hi) / 2.0
    return [float(centre[0]), float(bottom), float(centre[1])], [
        float(hi[0] - lo[0]),
        float(top - bottom),
        float(hi[1] - lo[1]),
    ]


def _measured(value: float | None) -> float:
    """A laid-out relation's value: the layout measures every relation it returns."""
    assert value is not None
    return float(value)


def _object_of(
    node: SceneNode, position: list[float], yaw: float, size: list[float]
) -> SceneObject:
    return SceneObject(
        id=node.id,
        type=node.type,
        kind=node.kind,
        noun=node.noun,
        plural=node.plural,
        parent=node.parent,
        style=node.style,
        position=[float(v) for v in position],
        yaw=float(yaw),
        size=[float(v) for v in size],
        shape=node.shape,
        mesh=node.mesh,
        colour=list(node.colour),
        rule=node.rule,
        order=node.order,
        clearance=[[side, float(metres)] for side, metres in node.clearance],
        access=list(node.access),
        network=node.network,
        wall_gap=node.wall_gap,
    )


def _node_of(obj: SceneObject) -> dict[str, Any]:
    return {
        "id": obj.id,
        "type": obj.type,
        "kind": obj.kind,
        "noun": obj.noun,
        "plural": obj.plural,
        "size": (0.0, 0.0, 0.0) if obj.kind == "group" else tuple(obj.size),
        "shape": obj.shape,
        "mesh": obj.mesh,
        "colour": tuple(obj.colour),
        "style": obj.style,
        "parent": obj.parent,
        "rule": obj.rule,
        "order": obj.order,
        "clearance": obj.clearance,
        "access": obj.access,
        "network": obj.network,
        "wall_gap": obj.wall_gap,
    }


def _node_of_path(path: ScenePath) -> dict[str, Any]:
    return {
        "id": path.id,
        "type": path.type,
        "kind": "path",
        "noun": path.noun,
        "plural": path.plural,
        "size": (path.width, 0.0, 0.0),
        "shape": None,
        "mesh": None,
        "colour": tuple(path.colour),
        "parent": path.parent,
        "rule": path.rule,
        "order": path.order,
        "width": path.width,
        "max_length": path.max_length,
        "segments": path.segments,
    }


def _plain(value: Any, digits: int | None) -> Any:
    """``value`` as JSON data: a dataclass as the dict of its fields (as ``asdict``
    makes it), tuples as lists, floats rounded to ``digits`` when given (scene.json keeps
    micrometres, so it is stable and readable)."""
    if isinstance(value, float):
        if digits is None:
            return value
        rounded = round(value, digits)
        return 0.0 if rounded == 0 else rounded
    if isinstance(value, dict):
        return {k: _plain(v, digits) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_plain(v, digits) for v in value]
    if is_dataclass(value) and not isinstance(value, type):
        return {f.name: _plain(getattr(value, f.name), digits) for f in fields(value)}
    return value
