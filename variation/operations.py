"""The three reshuffling operations on a variant, and their compatibility values.

A ``Variant`` is a Scene being changed plus where each of its objects came from (the
example and the object id), so every object maps to its Augmented Graph node. Each
operation proposes new or moved objects (``Change``) with the paper's compatibility:

- ``replace``: object u gives way to w, another member of u's node (from another
  example). w takes u's facing and is anchored on the face u shares with its
  strongest neighbour (touching, then aligned, then facing, then close; against a
  wall, its back), not on u's centre. What u carried moves onto w, its placement on
  the top scaled. zeta_r = the object similarity of u and w (``box_similarity``) at
  the paper's scale: sigma = the variant's scene diagonal in metres (the matching
  itself keeps sigma = 1, where only the ranking of pairs counts).
- ``grow``: a node absent from the variant joins it next to a present neighbour: a
  member w of the node is placed at its pose relative to its largest neighbour m in
  its own example that has a counterpart in the variant, taken to m's counterpart in the variant (the gap to the neighbour's face
  kept when the two neighbours differ in size), with what w carries. zeta_g is the
  mean over w's neighbours that have a counterpart of exp(-|d - d'| / diagonal), d the
  centre distance in w's example and d' in the variant (the paper sums the signed
  differences; a mean of absolute ones stays in [0, 1]). w brings its wall relations:
  those its example states, or, for an example read from geometry alone (which states
  none), the most specific of InCorner and AgainstWall that holds where w stood.
- ``transfer``: what another member w of a supporter u's node carries in its example
  replaces what u carries, each item at the same place relative to the top (scaled to
  u's top). Refused when u's top cannot carry them: below ``MIN_CARRY_HEIGHT`` or above
  ``MAX_CARRY_HEIGHT``, or an item larger than the top. zeta_t = the object similarity
  of u and w, at the scale of zeta_r.

Applying a change is the caller's (``synthesis``): it lays the variant out with every
untouched object pinned.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np

from scenewright.core.frames import to_local, to_world
from scenewright.core.poses import Pose
from scenewright.core.relations import RELATIONS, Relation
from scenewright.core.room import ROOM_NODE
from scenewright.core.scene import Scene, SceneObject
from scenewright.core.scene_graph import SceneGraph, SceneParams
from scenewright.examples import scene_supports
from scenewright.examples.example import SUPPORT_LABEL
from scenewright.generator.catalog import CatalogEntry
from scenewright.generator.layout import measure_layout

from .augmented import AugmentedGraph, Member
from .matching import box_similarity
from .structure import structure_graph

#: A top surface carries things between these heights (metres).
MIN_CARRY_HEIGHT = 0.2
MAX_CARRY_HEIGHT = 1.9
#: The order in which a neighbour's relation anchors a replacement.
ANCHOR_ORDER = ("V", "A", "F", "C")
#: How close (metres) a back must be to a wall to be anchored on it.
WALL_CONTACT = 0.1


@dataclass
class Variant:
    """A scene being varied: ``origin`` maps each object id to (example index, object id)."""

    scene: Scene
    origin: dict[str, Member]
    operations: list[dict] = field(default_factory=list)
    compatibility: float = 1.0

    def objects(self) -> dict[str, SceneObject]:
        return {o.id: o for o in self.scene.placed_objects()}

    def node_of(self, ag: AugmentedGraph, object_id: str) -> str:
        return ag.node_of[self.origin[object_id]]

    def counterpart(self, ag: AugmentedGraph, node_id: str) -> str | None:
        """The variant's object in AG node ``node_id`` (the first in scene order), or None."""
        for obj in self.scene.placed_objects():
            if ag.node_of.get(self.origin[obj.id]) == node_id:
                return obj.id
        return None

    def fresh_id(self, type_name: str, taken: set[str] | None = None) -> str:
        used = {o.id for o in self.scene.objects} | (taken or set())
        count = 1
        while f"{type_name}_{count}" in used:
            count += 1
        return f"{type_name}_{count}"


@dataclass
class Change:
    """An operation's proposal: objects to remove, objects to add (with their origin and
    the relations they bring), the compatibility, and a record for ``synthesis``."""

    kind: str
    compatibility: float
    removed: list[str]
    added: list[tuple[SceneObject, Member]]
    relations: list[Relation]
    record: dict


def top_of(obj: SceneObject) -> float:
    return obj.position[1] + obj.size[1]


def carried_by(scene: Scene, object_id: str) -> list[str]:
    """Ids of the objects resting on ``object_id``, directly or through others, in scene order."""
    supports = scene_supports(scene)
    found: list[str] = []
    frontier = [object_id]
    while frontier:
        below = frontier.pop()
        above = [o.id for o in scene.placed_objects() if supports.get(o.id) == below]
        found += above
        frontier += above
    order = {o.id: k for k, o in enumerate(scene.objects)}
    return sorted(found, key=order.__getitem__)


def _source_object(ag: AugmentedGraph, member: Member) -> SceneObject:
    return ag.examples[member[0]].scene.object(member[1])


def scene_diagonal(scene: Scene) -> float:
    """The diagonal (metres) of the scene's box: its extent, and a room's height."""
    height = scene.room.height if scene.room is not None else 0.0
    return math.sqrt(scene.extent[0] ** 2 + scene.extent[1] ** 2 + height**2)


def _similarity(first: SceneObject, second: SceneObject, scene: Scene) -> float:
    """The compatibility of putting one box for the other: the matching's object
    similarity with the paper's scale, sigma = the scene's diagonal in metres. With
    sigma 1 (the matching's, where only the ranking counts) a chair and an office
    chair scored 0.71 and a double and a single bed 0.76, under ``KEEP``, so like
    pieces were never put for each other; at a room's diagonal (about 5 m) they score
    about 0.93 while a bed for a chair stays under it."""
    return float(
        box_similarity(np.array([first.size]), np.array([second.size]), scene_diagonal(scene))[0, 0]
    )


def _moved_items(
    variant: Variant,
    ag: AugmentedGraph,
    items: list[tuple[SceneObject, Member]],
    old: SceneObject,
    new: SceneObject,
    new_id: str,
    taken: set[str],
) -> tuple[list[tuple[SceneObject, Member]], list[Relation]]:
    """Items resting on ``old`` (objects of any scene, with their origins) placed on
    ``new`` (id ``new_id``) at the same place relative to the top, scaled, with new ids."""
    placed, relations = [], []
    ids: dict[str, str] = {}
    for item, _ in items:  # one at a time: two books of one shelf need two ids
        ids[item.id] = variant.fresh_id(item.type, taken)
        taken.add(ids[item.id])
    for item, origin in items:
        lx, lz = to_local(
            old.position[0], old.position[2], old.yaw, item.position[0], item.position[2]
        )
        sx, sz = new.size[0] / max(old.size[0], 1e-9), new.size[2] / max(old.size[2], 1e-9)
        lx = float(
            np.clip(
                lx * sx, -(new.size[0] - item.size[0]) / 2.0, (new.size[0] - item.size[0]) / 2.0
            )
        )
        lz = float(
            np.clip(
                lz * sz, -(new.size[2] - item.size[2]) / 2.0, (new.size[2] - item.size[2]) / 2.0
            )
        )
        x, z = to_world(new.position[0], new.position[2], new.yaw, lx, lz)
        height = item.position[1] - top_of(old) + top_of(new)
        placed.append(
            (
                replace(
                    item,
                    id=ids[item.id],
                    position=[x, height, z],
                    yaw=item.yaw - old.yaw + new.yaw,
                    parent=None,
                ),
                origin,
            )
        )
    supports = {item.id: below for item, _ in items for below in [_supporter_in(items, item, old)]}
    for item, _ in items:
        below = supports[item.id]
        relations.append(
            Relation(
                ids[item.id], new_id if below == old.id else ids[below], SUPPORT_LABEL, 0.0, True
            )
        )
    return placed, relations


def _supporter_in(
    items: list[tuple[SceneObject, Member]], item: SceneObject, base: SceneObject
) -> str:
    """What ``item`` rests on among ``items`` (or ``base``): one whose top is at its base
    and whose footprint holds its centre. Height alone is not enough: a lamp beside a
    laptop on a desk stands 2 cm below the laptop's top, on the desk."""

    def holds(other: SceneObject) -> bool:
        lx, lz = to_local(
            other.position[0], other.position[2], other.yaw, item.position[0], item.position[2]
        )
        return abs(lx) <= other.size[0] / 2.0 and abs(lz) <= other.size[2] / 2.0

    below = [
        other
        for other, _ in items
        if other.id != item.id and abs(top_of(other) - item.position[1]) < 0.03 and holds(other)
    ]
    return below[0].id if below else base.id


def replace_object(variant: Variant, ag: AugmentedGraph, object_id: str, member: Member) -> Change:
    """Replace ``object_id`` by ``member`` (see the module docstring)."""
    old = variant.objects()[object_id]
    source = _source_object(ag, member)
    new_id = variant.fresh_id(source.type)
    direction = _anchor_direction(variant, object_id)
    lx = lz = 0.0
    if direction is not None:
        lx = direction[0] * (old.size[0] - source.size[0]) / 2.0
        lz = direction[1] * (old.size[2] - source.size[2]) / 2.0
    x, z = to_world(old.position[0], old.position[2], old.yaw, lx, lz)
    new = replace(
        source,
        id=new_id,
        position=[x, old.position[1], z],
        yaw=old.yaw,
        parent=old.parent,
        order=old.order,
    )
    carried = carried_by(variant.scene, object_id)
    items = [(variant.objects()[i], variant.origin[i]) for i in carried]
    placed, relations = _moved_items(variant, ag, items, old, new, new_id, {new_id})
    relations += [
        _retarget(r, object_id, new_id)
        for r in variant.scene.relations
        if object_id in (r.source, r.target) and r.source not in carried
    ]
    return Change(
        "replace",
        _similarity(old, source, variant.scene),
        [object_id, *carried],
        [(new, member), *placed],
        relations,
        {
            "operation": "replace",
            "object": object_id,
            "by": new_id,
            "from": {"example": ag.examples[member[0]].name, "object": member[1]},
        },
    )


def _retarget(relation: Relation, old: str, new: str) -> Relation:
    return Relation(
        new if relation.source == old else relation.source,
        new if relation.target == old else relation.target,
        relation.label,
        0.0,
        True,
        relation.chosen,
    )


def _anchor_direction(variant: Variant, object_id: str) -> tuple[float, float] | None:
    """The local (x, z) unit axis of the face of ``object_id`` to keep in place: towards
    its strongest neighbour, or its back against a wall; None: keep the centre."""
    graph = structure_graph(variant.scene)
    i = graph.index(object_id)
    obj = variant.objects()[object_id]
    for code in ANCHOR_ORDER:
        for j in graph.neighbours(i, set(graph.layout_nodes())):
            if code in graph.relation_set(i, j):
                other = graph.centres[j]
                lx, lz = to_local(
                    obj.position[0], obj.position[2], obj.yaw, float(other[0]), float(other[1])
                )
                if abs(lx) / max(obj.size[0], 1e-9) >= abs(lz) / max(obj.size[2], 1e-9):
                    return (math.copysign(1.0, lx), 0.0)
                return (0.0, math.copysign(1.0, lz))
    room = variant.scene.room
    if room is not None:
        bx, bz = to_world(obj.position[0], obj.position[2], obj.yaw, 0.0, -obj.size[2] / 2.0)
        if room.boundary_distance(bx, bz) <= WALL_CONTACT:
            return (0.0, -1.0)
    return None


def grow_node(variant: Variant, ag: AugmentedGraph, node_id: str, member: Member) -> Change | None:
    """Add ``member`` of absent node ``node_id`` next to a present neighbour, or None when
    none of its neighbours in its own example has a counterpart in the variant."""
    example = ag.examples[member[0]].scene
    graph = ag.graphs[member[0]]
    source = example.object(member[1])
    i = graph.index(member[1])
    anchors = []
    for j in graph.neighbours(i, set(graph.layout_nodes())):
        present = variant.counterpart(ag, ag.node_of[(member[0], graph.ids[j])])
        if present is not None:
            anchors.append((example.object(graph.ids[j]), variant.objects()[present]))
    if not anchors:
        return None
    # The largest neighbour is the surest anchor (of four alike chairs, the counterpart
    # may be another one than in the example).
    near, there = max(anchors, key=lambda pair: pair[0].size[0] * pair[0].size[2])
    lx, lz = to_local(
        near.position[0], near.position[2], near.yaw, source.position[0], source.position[2]
    )
    # Keep the gap to the neighbour's face when the neighbours differ in size.
    if abs(lx) > near.size[0] / 2.0:
        lx += math.copysign(1.0, lx) * (there.size[0] - near.size[0]) / 2.0
    if abs(lz) > near.size[2] / 2.0:
        lz += math.copysign(1.0, lz) * (there.size[2] - near.size[2]) / 2.0
    x, z = to_world(there.position[0], there.position[2], there.yaw, lx, lz)
    new_id = variant.fresh_id(source.type)
    new = replace(
        source,
        id=new_id,
        position=[x, 0.0, z],
        yaw=source.yaw - near.yaw + there.yaw,
        parent=None,
        order=max((o.order for o in variant.scene.objects), default=0) + 1,
    )
    carried = carried_by(example, member[1])
    items = [(example.object(c), (member[0], c)) for c in carried]
    placed, relations = _moved_items(variant, ag, items, source, new, new_id, {new_id})
    relations += _brought_relations(variant, ag, member, new_id)
    if not any(r.source == new_id and r.target == there.id for r in relations):
        relations.append(Relation(new_id, there.id, "NextTo", 0.0, True))
    return Change(
        "grow",
        1.0,
        [],
        [(new, member), *placed],
        relations,
        {
            "operation": "grow",
            "node": node_id,
            "object": new_id,
            "next_to": there.id,
            "from": {"example": ag.examples[member[0]].name, "object": member[1]},
        },
    )


def _brought_relations(
    variant: Variant, ag: AugmentedGraph, member: Member, new_id: str
) -> list[Relation]:
    """The grown object's relations in its example whose other end has a counterpart in
    the variant (or is the room, when the variant has one), and a plain NextTo to the
    neighbour it was placed by so the layout keeps it there."""
    example = ag.examples[member[0]].scene
    brought = []
    stated = any(
        r.source == member[1] and r.label in RELATIONS and RELATIONS[r.label].family == "wall"
        for r in example.relations
    )
    if not stated and variant.scene.room is not None and example.room is not None:
        # An example read from geometry states no wall relations: measure them, so an
        # armchair grown from a corner goes to a corner, not mid-room by its neighbour.
        brought += [
            Relation(new_id, "room", label, 0.0, True)
            for label in measured_walls(example, member[1])
        ]
    for relation in example.relations:
        if (
            relation.source != member[1]
            or relation.label not in RELATIONS
            or RELATIONS[relation.label].support
        ):
            continue
        if RELATIONS[relation.label].by_room:  # a wall label or AwayFromWall
            if variant.scene.room is not None:
                brought.append(Relation(new_id, "room", relation.label, 0.0, True))
            continue
        if (member[0], relation.target) in ag.node_of:
            present = variant.counterpart(ag, ag.node_of[(member[0], relation.target)])
            if present is not None:
                brought.append(Relation(new_id, present, relation.label, 0.0, True))
    return brought


def grow_compatibility(variant: Variant, ag: AugmentedGraph, member: Member, new_id: str) -> float:
    """zeta_g of a grown object now at its place in the variant (see the module docstring)."""
    example = ag.examples[member[0]].scene
    graph = ag.graphs[member[0]]
    source = example.object(member[1])
    grown = variant.objects()[new_id]
    diagonal = math.hypot(*variant.scene.extent)
    terms = []
    for j in graph.neighbours(graph.index(member[1]), set(graph.layout_nodes())):
        present = variant.counterpart(ag, ag.node_of[(member[0], graph.ids[j])])
        if present is None or present == new_id:
            continue
        there, near = variant.objects()[present], example.object(graph.ids[j])
        before = math.hypot(
            source.position[0] - near.position[0], source.position[2] - near.position[2]
        )
        after = math.hypot(
            grown.position[0] - there.position[0], grown.position[2] - there.position[2]
        )
        terms.append(math.exp(-abs(before - after) / diagonal))
    return float(np.mean(terms)) if terms else 0.0


def can_carry(obj: SceneObject, items: list[SceneObject]) -> bool:
    """Whether ``obj``'s top can carry ``items`` (see ``transfer``)."""
    if not MIN_CARRY_HEIGHT <= top_of(obj) <= MAX_CARRY_HEIGHT:
        return False
    return all(item.size[0] <= obj.size[0] and item.size[2] <= obj.size[2] for item in items)


def transfer_items(
    variant: Variant, ag: AugmentedGraph, object_id: str, member: Member
) -> Change | None:
    """Put what ``member`` carries in its example on ``object_id`` in place of what it
    carries now; None when its top cannot carry them."""
    target = variant.objects()[object_id]
    example = ag.examples[member[0]].scene
    source = example.object(member[1])
    carried = carried_by(example, member[1])
    items = [(example.object(c), (member[0], c)) for c in carried]
    if not items or not can_carry(target, [item for item, _ in items]):
        return None
    placed, relations = _moved_items(variant, ag, items, source, target, object_id, set())
    return Change(
        "transfer",
        _similarity(target, source, variant.scene),
        carried_by(variant.scene, object_id),
        placed,
        relations,
        {
            "operation": "transfer",
            "onto": object_id,
            "items": [p.id for p, _ in placed],
            "from": {"example": ag.examples[member[0]].name, "object": member[1]},
        },
    )


#: The wall labels a grown object may bring, most specific first: only the first that
#: holds is brought (a thing in a corner is against a wall too).
WALL_LABELS = ("InCorner", "AgainstWall")


def measured_walls(example: Scene, object_id: str) -> list[str]:
    """The most specific of ``WALL_LABELS`` that holds for ``object_id`` standing where
    it stands in ``example`` (a room scene), measured by the layout's own predicates;
    [] for none, or for an object resting on another."""
    if example.room is None or object_id in scene_supports(example):
        return []
    obj = example.object(object_id)
    graph = SceneGraph(
        params=SceneParams(
            extent=(float(example.extent[0]), float(example.extent[1])),
            ground="floor",
            room=example.room,
        )
    )
    node = graph.add_node(
        CatalogEntry(
            obj.type,
            "object",
            obj.noun or obj.type,
            size=(float(obj.size[0]), float(obj.size[1]), float(obj.size[2])),
        )
    )
    for label in WALL_LABELS:
        graph.add_relation(node, ROOM_NODE, label)
    x, y, z = (float(v) for v in obj.position)
    pose = Pose(x, y, z, float(obj.yaw))
    held = {r.label for r in measure_layout(graph, {node: pose}, {}).relations if r.satisfied}
    return next(([label] for label in WALL_LABELS if label in held), [])
