"""The scene relationship graph: what grammar expansion produces and layout consumes.

A ``SceneGraph`` wraps a networkx ``MultiDiGraph``. Each node is one instance of a
catalog type (object, group, path or junction) with a stable id such as
``market_stand_2`` (type name and a 1-based counter per type, in creation order). Each
edge is one relation label of the registry (``core.relations``) pointing from A to B; an edge
whose target a ``some TYPE`` drew also has ``some=True`` (the layout may give a relation
to ``some road`` another road of the type, ``layout.lots``; scene.json records the road
it used). Every node
records the production that made it (its derivation) and its parent group, so the
describer can follow the derivation and a group's extent can be taken from its members.

Node attributes are plain values copied from the catalog entry after the style was
chosen, so later stages never need the catalog itself.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Iterator
from dataclasses import dataclass, field, fields
from typing import Any, Protocol

import networkx as nx

from .relations import RELATIONS, Relation, UnknownLabel
from .room import ROOM_KINDS, ROOM_NODE, WALL_THICKNESS, Room

#: The colour room nodes carry (plaster); the renderer draws the room from ``params.room``.
ROOM_COLOUR = (0.86, 0.84, 0.8)

Vec3 = tuple[float, float, float]


def _vec3(values: Iterable[float]) -> Vec3:
    """Three numbers as a tuple of floats."""
    x, y, z = (float(v) for v in values)
    return x, y, z


def _network(entry: CatalogLike) -> str | None:
    """A node's ``network``: "grid" for a junction that starts a grid, else None."""
    return entry.network if entry.kind == "junction" and entry.network != "organic" else None


def _node_dict(node: SceneNode) -> dict:
    """A node as plain data; ``network`` and ``wall_gap`` only where they are set (a
    grid's junction, an object kept off its wall), so the graphs of rule sets that name
    neither read as before."""
    # A shallow copy: every field is immutable (strings, numbers, tuples), and asdict's
    # deep copy was most of the cost of writing a graph out.
    data = {name: getattr(node, name) for name in _NODE_FIELDS}
    for name in OPTIONAL_NODE_FIELDS:
        if data[name] is None:
            del data[name]
    return data


class NodeLooks(Protocol):
    """What a node copies from its catalog entry once a style is applied (read only)."""

    @property
    def noun(self) -> str: ...
    @property
    def plural(self) -> str | None: ...
    @property
    def size(self) -> Vec3: ...
    @property
    def shape(self) -> str | None: ...
    @property
    def mesh(self) -> str | None: ...
    @property
    def colour(self) -> Vec3: ...
    @property
    def clearance(self) -> tuple[tuple[str, float], ...]: ...
    @property
    def access(self) -> tuple[str, ...]: ...


class CatalogLike(NodeLooks, Protocol):
    """A catalog entry as the graph reads it (the rules loader's ``CatalogEntry``)."""

    @property
    def name(self) -> str: ...
    @property
    def kind(self) -> str: ...
    @property
    def width(self) -> float: ...
    @property
    def max_length(self) -> float: ...
    @property
    def segments(self) -> int: ...
    @property
    def wall_gap(self) -> float | None: ...
    @property
    def network(self) -> str: ...

    def with_style(self, style: Any) -> NodeLooks: ...


@dataclass(frozen=True)
class SceneParams:
    """Scene-wide parameters from a rules file's ``scene`` block.

    ``extent`` is (width along x, depth along z) in metres, centred on the origin.
    ``room``: the walls, doors and windows of an indoor scene (``core.room``), or None
    for open ground; the extent is then the room's bounding box.
    ``templates``: the absolute path of the rule set's own description templates
    folder (the scene block's ``templates``), or None for the package's templates.
    """

    name: str = "scene"
    extent: tuple[float, float] = (40.0, 40.0)
    ground: str = "grass"
    room: Room | None = None
    templates: str | None = None
    #: In a room: furniture stands square to the walls unless a relation turns it.
    square: bool = True
    #: In a room: "in front of" and facing relations do not hold through a tall object.
    line_of_sight: bool = True

    @property
    def walls(self) -> bool:
        """Whether the scene is a room bounded by walls."""
        return self.room is not None

    def to_dict(self) -> dict:
        """Plain data: the room as scene.json writes it."""
        return {
            "name": self.name,
            "extent": list(self.extent),
            "ground": self.ground,
            "room": self.room.to_dict() if self.room else None,
            "templates": self.templates,
            "square": self.square,
            "line_of_sight": self.line_of_sight,
        }

    @classmethod
    def from_dict(cls, params: dict) -> SceneParams:
        """The parameters ``to_dict`` gave; missing ones take their defaults (an old
        ``walls: true`` is a bare rectangular room the size of the extent)."""
        extent = tuple(params.get("extent", cls.extent))
        room = params.get("room")
        if room:
            room = Room.from_dict(room)
        elif params.get("walls"):
            room = Room.rectangle(*extent)
        return cls(
            name=params.get("name", cls.name),
            extent=extent,
            ground=params.get("ground", cls.ground),
            room=room or None,
            templates=params.get("templates", cls.templates),
            square=bool(params.get("square", cls.square)),
            line_of_sight=bool(params.get("line_of_sight", cls.line_of_sight)),
        )


@dataclass(frozen=True)
class SceneNode:
    """One node of the scene graph, as plain data."""

    id: str
    type: str
    kind: str
    noun: str
    plural: str | None
    size: Vec3
    shape: str | None
    mesh: str | None
    colour: Vec3
    style: str | None = None
    parent: str | None = None
    rule: str | None = None  # the production that created the node ("MarketStand", ...)
    order: int = 0  # creation order; the derivation is depth-first in statement order
    width: float | None = None  # paths only
    max_length: float | None = None  # paths only
    segments: int | None = None  # paths only
    #: Free floor to keep beside the object, by side: (("front", 0.8),) keeps 0.8 m
    #: clear in front of it (a wardrobe's doors, where a desk chair pulls out).
    clearance: tuple[tuple[str, float], ...] = ()
    #: The sides a person uses it from ("front", "back", "left", "right"), ("any",) for
    #: any side, () for an object nobody needs to reach (a plant, a rug).
    access: tuple[str, ...] = ("any",)
    #: Junctions only: "grid" when the junction starts a grid of roads (square blocks);
    #: None for the default, an organic network (``catalog.NETWORKS``).
    network: str | None = None
    #: Objects only: how far its back stands off a wall that a wall label puts it
    #: against (metres); None: flush.
    wall_gap: float | None = None


def descendants_in(members: dict[str | None, list[SceneNode]], group_id: str) -> list[SceneNode]:
    """All members of a group by ``members`` (``SceneGraph.by_parent``), nested groups'
    members included (each after its group): one ``by_parent`` serves every group."""
    found: list[SceneNode] = []

    def collect(parent: str) -> None:
        for child in members.get(parent, []):
            found.append(child)
            collect(child.id)

    collect(group_id)
    return found


#: The node fields written out only where set (a grid's junction, an object kept off its
#: wall), so that graphs and scenes of rule sets that set neither read as before.
OPTIONAL_NODE_FIELDS = ("network", "wall_gap")

#: The attribute names a node is stored under in the networkx graph.
_NODE_FIELDS = tuple(f.name for f in fields(SceneNode))
_NODE_FIELD_SET = frozenset(_NODE_FIELDS)


def _node_of(data: dict) -> SceneNode:
    """The node whose stored fields are ``data``. A node stored whole (``_store``) gets
    its fields in one step: the frozen dataclass's ``__init__`` sets each of its twenty
    fields through ``object.__setattr__``, which made reading nodes cost a sixth of as
    much as expanding the rules that made them."""
    if data.keys() != _NODE_FIELD_SET:  # stored by other code: the defaults fill the rest
        return SceneNode(**data)
    node = object.__new__(SceneNode)
    node.__dict__.update(data)
    return node


@dataclass
class SceneGraph:
    """A scene relationship graph plus its scene parameters."""

    params: SceneParams = field(default_factory=SceneParams)
    graph: nx.MultiDiGraph = field(default_factory=nx.MultiDiGraph)
    #: Every random choice expansion made, in the order it made them (see
    #: ``generator.derivation``); empty for a graph not made by expansion.
    derivation: list[dict] = field(default_factory=list)
    _counters: dict[str, int] = field(default_factory=dict, repr=False)

    def __post_init__(self) -> None:
        if self.params.room is not None and ROOM_NODE not in self.graph:
            self._add_room(self.params.room)

    def _add_room(self, room: Room) -> None:
        """The room's nodes: ``room`` (any wall or window), then each wall, door and window."""
        height = room.height
        width, depth = room.extent
        self._store(
            SceneNode(
                ROOM_NODE,
                ROOM_NODE,
                ROOM_NODE,
                "room",
                "rooms",
                (width, height, depth),
                None,
                None,
                ROOM_COLOUR,
                order=len(self.graph),
                access=(),
            )
        )
        for wall in room.walls:
            self._store(
                SceneNode(
                    wall.id,
                    "wall",
                    "wall",
                    "wall",
                    "walls",
                    (wall.length, wall.height, WALL_THICKNESS),
                    None,
                    None,
                    ROOM_COLOUR,
                    order=len(self.graph),
                    access=(),
                )
            )
        for opening in room.openings:
            self._store(
                SceneNode(
                    opening.id,
                    opening.kind,
                    opening.kind,
                    opening.kind,
                    opening.kind + "s",
                    (opening.width, opening.height, WALL_THICKNESS),
                    None,
                    None,
                    ROOM_COLOUR,
                    order=len(self.graph),
                    access=(),
                )
            )
        for kind in ("wall", "door", "window"):
            self._counters[kind] = sum(1 for n in self.graph.nodes.values() if n["kind"] == kind)

    # -- building -----------------------------------------------------------------

    def add_node(
        self,
        entry: CatalogLike,
        *,
        style=None,
        parent: str | None = None,
        rule: str | None = None,
    ) -> str:
        """Add an instance of ``entry`` (in ``style``, one of its styles) and return its new id."""
        if parent is not None and parent not in self.graph:
            raise KeyError(f"unknown parent node {parent!r}")
        count = self._counters.get(entry.name, 0) + 1
        self._counters[entry.name] = count
        node_id = f"{entry.name}_{count}"
        looks = entry.with_style(style)
        is_path = entry.kind == "path"
        # A path has a width, a group the box of its members: neither a box nor a mesh of its own.
        has_box = entry.kind in ("object", "junction")
        # The stored fields, every one in SceneNode's order, without building the node:
        # a frozen dataclass sets each field through object.__setattr__, and building
        # nodes then reading their fields back was a tenth of grammar expansion.
        self.graph.add_node(
            node_id,
            id=node_id,
            type=entry.name,
            kind=entry.kind,
            noun=looks.noun,
            plural=looks.plural,
            size=_vec3(looks.size)
            if has_box
            else (float(entry.width) if is_path else 0.0, 0.0, 0.0),
            shape=looks.shape if has_box else None,
            mesh=looks.mesh if has_box else None,
            colour=_vec3(looks.colour),
            style=style.name if style else None,
            parent=parent,
            rule=rule,
            order=self.graph.number_of_nodes(),
            width=entry.width if is_path else None,
            max_length=entry.max_length if is_path else None,
            segments=entry.segments if is_path else None,
            clearance=tuple((side, float(metres)) for side, metres in looks.clearance)
            if has_box
            else (),
            access=tuple(looks.access) if has_box else (),
            network=_network(entry),
            wall_gap=float(entry.wall_gap)
            if entry.kind == "object" and entry.wall_gap is not None
            else None,
        )
        return node_id

    def _store(self, node: SceneNode) -> None:
        # A shallow copy of the fields: they are immutable, and asdict's deep copy made
        # node creation most of the cost of grammar expansion.
        self.graph.add_node(node.id, **{name: getattr(node, name) for name in _NODE_FIELDS})

    def add_relation(self, source: str, target: str, label: str, some: bool = False) -> None:
        """Add the edge ``source`` -label-> ``target`` (both must exist, the label
        registered); ``some``: the target was drawn by ``some TYPE`` (module docstring)."""
        if label not in RELATIONS:
            raise UnknownLabel(label)
        for node_id in (source, target):
            if node_id not in self.graph:
                raise KeyError(f"unknown node {node_id!r}")
        if source == target:
            raise ValueError(f"relation {label} from {source!r} to itself")
        if some:
            self.graph.add_edge(source, target, label=label, some=True)
        else:
            self.graph.add_edge(source, target, label=label)

    # -- reading ------------------------------------------------------------------

    def node(self, node_id: str) -> SceneNode:
        return _node_of(self.graph.nodes[node_id])

    def nodes(self, kind: str | None = None) -> list[SceneNode]:
        """Nodes in creation order, optionally only those of one kind."""
        return self._nodes_where(lambda data: kind is None or data["kind"] == kind)

    def _nodes_where(self, wanted: Callable[[dict], bool]) -> list[SceneNode]:
        """The nodes whose stored fields pass ``wanted``, in creation order. Filtering the
        stored fields first builds a node only for what is returned: a loop over a town's
        groups asking each for its children built every node once a group."""
        found = [_node_of(data) for _, data in self.graph.nodes(data=True) if wanted(data)]
        found.sort(key=lambda n: n.order)
        return found

    def edges(self, label: str | None = None) -> list[Relation]:
        """Relations (without a verdict) grouped by source, each source's in insertion order."""
        return [
            Relation(s, t, data["label"])
            for s, t, data in self.graph.edges(data=True)
            if label is None or data["label"] == label
        ]

    def by_parent(self) -> dict[str | None, list[SceneNode]]:
        """Each group's direct members (``None``: the top level), in creation order."""
        members: dict[str | None, list[SceneNode]] = {}
        for node in self.nodes():
            members.setdefault(node.parent, []).append(node)
        return members

    def children(self, group_id: str) -> list[SceneNode]:
        """Direct members of a group, in creation order."""
        return self._nodes_where(lambda data: data["parent"] == group_id)

    def descendants(self, group_id: str) -> list[SceneNode]:
        """All members of a group, nested groups' members included (each after its group)."""
        return descendants_in(self.by_parent(), group_id)

    def __len__(self) -> int:
        return self.graph.number_of_nodes()

    def __iter__(self) -> Iterator[SceneNode]:
        return iter(self.nodes())

    # -- plain data ---------------------------------------------------------------

    def to_dict(self) -> dict:
        """A JSON-ready dict: parameters, nodes (creation order), edges and the derivation."""
        return {
            "params": self.params.to_dict(),
            "nodes": [_node_dict(n) for n in self.nodes()],
            "edges": [
                {"source": e.source, "target": e.target, "label": e.label} for e in self.edges()
            ],
            "derivation": [dict(record) for record in self.derivation],
        }

    @classmethod
    def from_dict(cls, data: dict) -> SceneGraph:
        """The graph ``to_dict`` gave; missing parameters take their defaults, a missing
        derivation is empty."""
        scene_graph = cls(
            params=SceneParams.from_dict(data.get("params", {})),
            derivation=[dict(record) for record in data.get("derivation", [])],
        )
        for raw in data["nodes"]:
            if raw["kind"] in ROOM_KINDS:
                continue  # made from the room in the parameters
            node = SceneNode(
                **{
                    **raw,
                    "size": tuple(raw["size"]),
                    "colour": tuple(raw["colour"]),
                    "clearance": tuple((side, float(m)) for side, m in raw.get("clearance", ())),
                    "access": tuple(
                        raw.get("access", ("any",) if raw["kind"] in ("object", "junction") else ())
                    ),
                }
            )
            scene_graph._store(node)
            # new nodes of the type continue its numbering (``table_3`` after ``table_2``)
            suffix = node.id.rsplit("_", 1)[-1]
            counter = int(suffix) if suffix.isdigit() else 0
            scene_graph._counters[node.type] = max(scene_graph._counters.get(node.type, 0), counter)
        for raw in data["edges"]:
            scene_graph.add_relation(raw["source"], raw["target"], raw["label"])
        return scene_graph
