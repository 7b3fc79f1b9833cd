"""A rule set induced from example scenes alone: what ``scenewright learn`` writes.

``induce(examples, seed=..., test=...)`` reads the examples' objects and returns an
``Induction`` (``learning.induction``): the catalog, the groups and the loose objects,
each with the numbers it rests on; ``rules_text.rules_text(induction)`` is the rules
file and ``Induction.to_dict()`` the report.

1. **Catalog.** Every type seen (its name made a rules identifier: lower case,
   ``_`` for anything else) with its median size (W x H x D), its styles weighted by how
   often each was seen (a style's own median size where it differs by more than
   ``STYLE_SIZE_TOLERANCE``), and its looks as the examples carry them: noun, shape,
   colour (a scene.json keeps the rule set's; the hand-written format and GLB give the
   type name as noun, the shape of that name if there is one, a colour per type). A
   type whose examples carry only those defaults and whose name is an entry of the
   shipped indoor catalog takes that entry's noun, plural, shape and colour
   (``borrowed``). Every type is declared in the output, so it is one self-contained
   file (a rule set reads no file outside its folder).
2. **Relations.** The type pairs ``learning.relation_finding`` finds related (by the chosen
   test, indirect relations pruned), and the pairs of which one type rests on the other
   in at least half the scenes holding both (``relation_pruning.resting_pairs``: support
   measured from the boxes), which are written even when the test has too few scenes.
   Pairs of one type (two books) are reported, not written.
3. **Groups.** Connected components of the graph of those pairs. The *anchor* is the
   type, among those resting on no other type of the group, in whose scenes the most of
   the group's objects stand (then the one with the most related types, then the
   largest footprint): a group's production makes its members only where it makes its
   anchor, so an anchor missing from some examples (a rug under the reading chair in
   9 of 14 reading corners) would leave its members there to stand alone, without
   their own partners. The rest hang off it along a maximum spanning tree
   (support pairs first, then the test's strength), so each member is placed relative
   to its parent in the tree. A group is a production named after its anchor.
4. **Placements.** For each tree edge parent -> child, every child object is paired
   with the parent object it rests on (through others: a book on a book on a desk) or
   else the nearest one of its scene; its pose in that parent's frame (x along the
   parent's left, z along its front, the turn between them, and whether it rests on
   it) is a point. The points are clustered by density peaks (``density_peaks``;
   ``POSE_SCALE``, ``POSE_SEPARATION``, ``TURN_METRES``, ``RESTING_METRES`` set the
   distances); outliers are left out. Each cluster's labels are those whose measured
   predicate holds at its centre and for most of its members (``pose_labels``): one
   placement label, one facing label, AlignedWith (measured with each object's own size and its
   parent's). Clusters with the same labels are
   one alternative; several alternatives become a production of weighted alternatives
   (weights: the objects of each). Members whose placements the examples chose together
   (a lamp on the armchair's left whenever the side table is on its right) are found by
   ``sides_together`` once the group's tree is built, and drawn together.
5. **Counts.** How many children each parent object had (``0.85? 1..3 {6 4 1}``: with
   85 % of the parents, one to three, weighted as seen); how many anchors each scene
   had; types related to no other type, and children seen in scenes without their
   parent type, stand alone in the start production with their counts per scene (a
   child with members of its own brings them: ``rules_text`` writes it a production
   of its own, ``SideTableAlone``).
6. **Walls.** In examples with a room, each standing object is measured against the
   wall labels; a type for which one holds in at least ``WALL_SHARE`` of its objects
   gets it (``AgainstWall some wall``: the layout chooses the wall), and a member's
   placement gets the one held by more than ``PLACEMENT_WALL_SHARE`` of its own
   objects, else ``AgainstWall`` where it held for any (``Placement.wall``), which
   ``rules_text`` writes. The gap a type's
   placers left to the wall where a label held (``WallShare.gap``: the median) is
   written as its ``wall_gap``, so the layout sets it as far off as they did. A type
   related to no other and a group's anchor get their label as a draw of its share
   where under 1 (``WallShare.drawn``), and so does a placement whose label held for
   some of its objects only (``Placement.wall_share``): the label, or else kept off
   the walls (``ImplicitAwayFromWall``), so that the share at the wall is the
   examples' whatever the layout would do with the rest. Such a type none of whose
   objects stood at a wall, and a standing placement none of whose objects did by a
   parent type that does, are kept off the walls outright: beside an armchair at the
   wall, a side table could otherwise come within a wall label's reach of it.
7. **Scene.** The room of the example whose room is nearest the median size (its walls,
   doors and windows), or the median extent of open ground.
"""

from __future__ import annotations

import math
from collections import Counter, defaultdict
from collections.abc import Sequence
from dataclasses import dataclass, replace

import networkx as nx
import numpy as np

from scenewright.core.errors import InputError
from scenewright.core.frames import to_local
from scenewright.core.geometry import wrap_angle
from scenewright.core.relations import IMPLICIT_PREFIX
from scenewright.core.room import Room
from scenewright.core.scene import Scene, SceneObject
from scenewright.examples import Example, scene_supports
from scenewright.examples.example import default_looks

from .density_peaks import density_peaks
from .induction import (
    PLACEMENT_WALL_SHARE,
    Cluster,
    Group,
    Induction,
    Loose,
    Member,
    Placement,
    StyleStats,
    TypeEntry,
    WallShare,
)
from .pose_labels import (
    CATEGORIES,
    IMPLICIT_CATEGORIES,
    RESTING_CATEGORIES,
    STANDING_CATEGORIES,
    hand_gap,
    hand_placed,
    most_specific,
    pair_holds,
    square_footprint,
    support_room,
    wall_holds,
)
from .relation_finding import find_relations
from .relation_poses import type_poses
from .relation_pruning import resting_pairs, typical_gap
from .rule_names import camel, identifier, unique_name
from .sides_together import sides_together

#: A style's median size is written when it differs from its type's by more than this share.
STYLE_SIZE_TOLERANCE = 0.05
#: Relative poses closer than this (metres) are one place; centres stand at least
#: POSE_SEPARATION apart.
POSE_SCALE = 0.1
POSE_SEPARATION = 0.25
#: Metres a unit of (cos, sin) of the turn counts as: a quarter turn (|d| = 1.41) is 0.7 m.
TURN_METRES = 0.5
#: A pose resting on the parent and one standing on the floor are never one cluster.
RESTING_METRES = 100.0
#: A resting child's turn is written when it holds for at least this share of a placement's objects.
TURN_SHARE = 0.8
#: Names a type may not have in a room scene (its parts), nor anywhere (``room``).
RESERVED_TYPES = frozenset({"wall", "door", "window", "room"})


def _median_size(objects: Sequence[SceneObject]) -> tuple[float, float, float]:
    values = np.median(np.array([o.size for o in objects], dtype=float), axis=0)
    return tuple(round(float(v), 3) for v in values)  # type: ignore[return-value]


def _most_common(values):
    counted = Counter(values)
    return max(counted, key=lambda value: (counted[value], repr(value)))


def _colour_key(colour: Sequence[float]) -> tuple[float, ...]:
    return tuple(round(float(v), 3) for v in colour)


def _differs(size: Sequence[float], base: Sequence[float]) -> bool:
    return any(abs(a - b) > STYLE_SIZE_TOLERANCE * b for a, b in zip(size, base, strict=False))


def catalog_entry(
    name: str, objects: Sequence[SceneObject], sources: Sequence[str], scenes: int, shipped: dict
) -> TypeEntry:
    """The catalog entry of one type from all its objects (``sources``: its names in
    the examples; ``shipped``: the indoor catalog's entries by name)."""
    size = _median_size(objects)
    noun = _most_common([o.noun for o in objects])
    plural = _most_common([o.plural for o in objects])
    shape = _most_common([o.shape for o in objects])
    colour = _most_common([_colour_key(o.colour) for o in objects])
    borrowed = None
    defaults = all(
        o.noun == looks.noun and _colour_key(o.colour) == _colour_key(looks.colour)
        for o, source in zip(objects, _sources_of(objects, sources), strict=False)
        for looks in [default_looks(source, o.style)]
    )  # the looks the examples' reader gives a type its file says nothing of
    if defaults and name in shipped:
        entry = shipped[name]
        noun, plural, shape, colour, borrowed = (
            entry.noun,
            entry.plural,
            entry.shape,
            _colour_key(entry.colour),
            "indoor catalog",
        )
    by_style: dict[str | None, list[SceneObject]] = defaultdict(list)
    for obj in objects:
        by_style[obj.style].append(obj)
    styles: list[StyleStats] = []
    if any(style is not None for style in by_style):
        taken: set[str] = set()
        ordered = sorted(by_style.items(), key=lambda item: (-len(item[1]), item[0] or ""))
        named = {style: identifier(style, taken) for style, _ in ordered if style is not None}
        for style, members in ordered:
            style_name = named[style] if style is not None else identifier("plain", taken)
            style_size = _median_size(members)
            style_noun = _most_common([o.noun for o in members])
            style_shape = _most_common([o.shape for o in members])
            style_colour = _most_common([_colour_key(o.colour) for o in members])
            if (
                borrowed
            ):  # the shipped style of the same name, if there is one, else the entry's looks
                like = {s.name: s for s in shipped[name].styles}.get(style_name)
                style_noun = like.noun if like and like.noun else noun
                style_shape = like.shape if like and like.shape else shape
                style_colour = _colour_key(like.colour) if like and like.colour else colour
            styles.append(
                StyleStats(
                    style_name,
                    style,
                    len(members),
                    style_size if _differs(style_size, size) else None,
                    style_noun if style_noun != noun else None,
                    style_shape if style_shape != shape and style_shape is not None else None,
                    style_colour if style_colour != colour else None,
                )
            )
    return TypeEntry(
        name,
        tuple(sources),
        len(objects),
        scenes,
        size,
        noun,
        plural,
        shape,
        colour,
        tuple(styles),
        borrowed,
    )


def _sources_of(objects: Sequence[SceneObject], sources: Sequence[str]) -> list[str]:
    """Each object's type as the examples named it (kept in ``SceneObject.rule`` while
    inducing; see ``renamed_scenes``)."""
    return [o.rule or (sources[0] if sources else o.type) for o in objects]


def renamed_scenes(examples: Sequence[Example]) -> tuple[list[Scene], dict[str, list[str]]]:
    """The examples' scenes with every type and style made a rules identifier (the
    name as written kept in the object's ``rule`` field, which examples leave empty),
    and each new type name's names in the examples."""
    rooms = any(example.scene.room is not None for example in examples)
    reserved = RESERVED_TYPES if rooms else frozenset({"room"})
    raw_types = sorted({o.type for example in examples for o in example.scene.placed_objects()})
    taken: set[str] = set()
    name_of = {raw: identifier(raw, taken, reserved) for raw in raw_types}
    sources: dict[str, list[str]] = defaultdict(list)
    for raw, name in name_of.items():
        sources[name].append(raw)
    scenes = []
    for example in examples:
        objects = [
            replace(o, type=name_of[o.type], rule=o.type) if o.kind == "object" else o
            for o in example.scene.objects
        ]
        scenes.append(replace(example.scene, objects=objects))
    return scenes, dict(sources)


# -- relative poses of a parent type and a child type -------------------------------------


@dataclass(frozen=True)
class EdgeInstances:
    """The child objects of one tree edge paired with parent objects.

    ``poses`` (n, 3): each child's (x, z, turn) in its parent's frame; ``resting`` (n,):
    whether it rests on that parent (directly or on something that does);
    ``per_parent``: how many children each parent object had -> how many parent
    objects had that many; ``orphans`` (S,): children in each scene holding no parent."""

    poses: np.ndarray
    resting: np.ndarray
    per_parent: Counter
    orphans: np.ndarray
    parent_sizes: np.ndarray  # (n, 3) each pose's parent's size
    child_sizes: np.ndarray  # (n, 3) each pose's child's size
    #: Each pose's parent object and child object: (scene index, its id).
    hosts: tuple[tuple[int, str], ...] = ()
    children: tuple[tuple[int, str], ...] = ()

    def holds(self, rests: bool) -> tuple[np.ndarray, dict[str, np.ndarray]]:
        """The indices (m,) of the poses that rest on their parent (or stand, when not
        ``rests``) and, per candidate label, whether it holds at each of them (m,),
        measured with each pose's own parent and child sizes (``pose_labels.pair_holds``)."""
        chosen = np.flatnonzero(self.resting == rests)
        found: dict[str, np.ndarray] = {}
        sizes = np.hstack([self.parent_sizes[chosen], self.child_sizes[chosen]])
        for key in sorted({tuple(row) for row in sizes.tolist()}):
            rows = np.flatnonzero(np.all(sizes == key, axis=1))
            for label, held in pair_holds(
                key[:3], key[3:], self.poses[chosen[rows]], rests
            ).items():
                found.setdefault(label, np.zeros(len(chosen), dtype=bool))[rows] = held
        return chosen, found


def _supporters(object_id: str, supports: dict[str, str]) -> list[str]:
    """What ``object_id`` rests on, and what that rests on, and so on."""
    chain, current = [], object_id
    while current in supports and supports[current] not in chain and len(chain) < len(supports):
        current = supports[current]
        chain.append(current)
    return chain


def edge_instances(
    scenes: Sequence[Scene],
    supports: Sequence[dict[str, str]],
    parent: str,
    child: str,
    *,
    resting_only: bool = False,
    against_wall: bool = False,
) -> EdgeInstances:
    """Every ``child`` object of ``scenes`` in the frame of its ``parent`` object (the
    one it rests on, else the nearest; with ``resting_only`` only the children resting
    on a parent object), and the children per parent object. With ``against_wall`` (the
    child's type is written with a wall label), a standing child whose footprint is
    square within ``SQUARE_ASPECT`` is turned as ``pose_labels.hand_placed`` turns it
    for that label (its back to the wall it stands against, as the layout will set
    it), so that the facing label chosen for it agrees with the wall label: a plant
    given any turn by the wall is not "facing away from" the cabinet beside it."""
    poses, resting, parent_sizes, child_sizes, hosts, ids = [], [], [], [], [], []
    per_parent: Counter = Counter()
    orphans = np.zeros(len(scenes), dtype=int)
    for index, (scene, support) in enumerate(zip(scenes, supports, strict=False)):
        objects = scene.placed_objects()
        parents = [o for o in objects if o.type == parent]
        children = [o for o in objects if o.type == child]
        if not parents:
            orphans[index] = len(children)
            continue
        by_id = {o.id: o for o in parents}
        counts = dict.fromkeys(by_id, 0)
        for obj in children:
            below = [i for i in _supporters(obj.id, support) if i in by_id]
            if below:
                host, rests = by_id[below[0]], True
            elif resting_only:
                continue
            else:
                host = min(
                    parents,
                    key=lambda p: (
                        math.hypot(
                            p.position[0] - obj.position[0], p.position[2] - obj.position[2]
                        ),
                        p.id,
                    ),
                )
                rests = False
            x, z = to_local(
                host.position[0], host.position[2], host.yaw, obj.position[0], obj.position[2]
            )
            yaw = obj.yaw
            if (
                against_wall
                and not rests
                and scene.room is not None
                and square_footprint(obj.size[0], obj.size[2])
            ):
                yaw = hand_placed(obj, scene.room)[2]
            poses.append((x, z, wrap_angle(yaw - host.yaw)))
            resting.append(rests)
            parent_sizes.append(host.size)
            child_sizes.append(obj.size)
            hosts.append((index, host.id))
            ids.append((index, obj.id))
            counts[host.id] += 1
        per_parent.update(counts.values())
    return EdgeInstances(
        np.array(poses, dtype=float).reshape(-1, 3),
        np.array(resting, dtype=bool),
        per_parent,
        orphans,
        np.array(parent_sizes, dtype=float).reshape(-1, 3),
        np.array(child_sizes, dtype=float).reshape(-1, 3),
        tuple(hosts),
        tuple(ids),
    )


def pose_features(
    poses: np.ndarray, resting: np.ndarray, child_sizes: np.ndarray | None = None
) -> np.ndarray:
    """(n, 5) points to cluster: x, z, TURN_METRES * (cos, sin) of the turn, and
    RESTING_METRES for a resting pose. The turn of a child whose footprint is square
    within ``SQUARE_ASPECT`` (a floor lamp, a plant; ``child_sizes`` (n, 3)) counts
    nothing: a person turns such a thing any way, so its turn tells no modes apart
    (a lamp at either end of a sideboard, turned with the room, would otherwise make
    four modes of two)."""
    turn = poses[:, 2]
    weight = np.full(len(poses), TURN_METRES)
    if child_sizes is not None and len(child_sizes):
        weight[square_footprint(child_sizes[:, 0], child_sizes[:, 2])] = 0.0
    return np.column_stack(
        [
            poses[:, 0],
            poses[:, 1],
            weight * np.cos(turn),
            weight * np.sin(turn),
            RESTING_METRES * resting,
        ]
    )


def written_labels(category_labels: dict[str, str | None], resting: bool) -> tuple[str, ...]:
    """The labels of one cluster as written: placement, then facing (the turn of a
    resting child, and the end of its parent's top it stands at, written ``Implicit``:
    ``IMPLICIT_CATEGORIES``), then alignment."""
    found = []
    for category in RESTING_CATEGORIES if resting else STANDING_CATEGORIES:
        label = category_labels.get(category)
        if label is None:
            continue
        found.append(IMPLICIT_PREFIX + label if category in IMPLICIT_CATEGORIES else label)
    return tuple(found)


def placements_of(
    instances: EdgeInstances,
) -> tuple[list[Placement], list[Cluster], int, np.ndarray]:
    """The placements of one tree edge, its clusters, how many poses were outliers, and
    each pose's placement (an index into the placements; -1: an outlier, or in a
    cluster no placement was written for).

    Clusters whose labels differ only in the turn of a resting child (the laptop
    turned like the desk, or across it) are one placement: a turn is written for it
    only when one holds for at least ``TURN_SHARE`` of its objects (and at the largest
    cluster's centre); otherwise the layout turns it freely."""
    if len(instances.poses) == 0:
        return [], [], 0, np.zeros(0, dtype=int)
    features = pose_features(instances.poses, instances.resting, instances.child_sizes)
    peaks = density_peaks(features, scale=POSE_SCALE, min_separation=POSE_SEPARATION)
    holds: dict[bool, dict[str, np.ndarray]] = {}
    index_in: dict[bool, np.ndarray] = {}
    for rests in (True, False):
        chosen, holds[rests] = instances.holds(rests)
        index_in[rests] = np.full(len(instances.poses), -1)
        index_in[rests][chosen] = np.arange(len(chosen))
    room = _room_on_top(instances)
    clusters: list[Cluster] = []
    merged: dict[
        tuple[bool, tuple[tuple[str, str | None], ...]], list[int]
    ] = {}  # (rests, (category, label) but the turn) -> cluster numbers
    for number_, centre in enumerate(peaks.centres):
        members = peaks.members(number_)
        rests = bool(instances.resting[centre])
        local = index_in[rests]
        categories = RESTING_CATEGORIES if rests else STANDING_CATEGORIES
        chosen = {
            c: most_specific(
                c, holds[rests], int(local[centre]), local[members], allowed=room.__getitem__
            )
            for c in categories
        }
        x, z, turn = instances.poses[centre]
        clusters.append(
            Cluster(
                len(members),
                (float(x), float(z), math.degrees(turn)),
                rests,
                written_labels(chosen, rests),
            )
        )
        if rests and chosen.get("support") is None:
            chosen["support"] = CATEGORIES["support"][
                -1
            ]  # no label with room holds: anywhere on top
        if chosen.get("support") or chosen.get("near") or chosen.get("facing"):
            key = tuple((c, label) for c, label in chosen.items() if c != "turn")
            merged.setdefault((rests, key), []).append(number_)
    placements = []
    members_of = []
    for (rests, key), numbers in merged.items():
        labels = written_labels(dict(key), rests)
        if rests:
            members = np.concatenate([peaks.members(k) for k in numbers])
            largest = max(numbers, key=lambda k: (len(peaks.members(k)), -k))
            local = index_in[rests]
            turn = most_specific(
                "turn", holds[rests], int(local[peaks.centres[largest]]), local[members], TURN_SHARE
            )
            labels = written_labels({**dict(key), "turn": turn}, rests)
        placements.append(Placement(labels, sum(len(peaks.members(k)) for k in numbers)))
        members_of.append(np.concatenate([peaks.members(k) for k in numbers]))
    order = sorted(
        range(len(placements)), key=lambda k: (-placements[k].weight, placements[k].labels)
    )
    assigned = np.full(len(instances.poses), -1)
    for rank, k in enumerate(order):
        assigned[members_of[k]] = rank
    return [placements[k] for k in order], clusters, len(peaks.outliers), assigned


def _room_on_top(instances: EdgeInstances) -> defaultdict[str, bool]:
    """Per label: False for a support label under which as many children as one parent
    object held at most do not fit on it side by side (``pose_labels.support_room``, at
    the median sizes of the resting poses); True for every other. Several books stacked
    in the middle of a side table each hold "in the middle"; written so, the layout
    must put them side by side in the middle, where two do not fit."""
    resting = np.flatnonzero(instances.resting)
    most = max((count for count, parents in instances.per_parent.items() if parents), default=0)
    room: defaultdict[str, bool] = defaultdict(lambda: True)
    if len(resting) and most > 1:
        room.update(
            support_room(
                np.median(instances.parent_sizes[resting], axis=0),
                np.median(instances.child_sizes[resting], axis=0),
                most,
            )
        )
    return room


# -- inducing -------------------------------------------------------------------------


def _support_counts(
    scenes: Sequence[Scene], supports: Sequence[dict[str, str]]
) -> dict[tuple[str, str], tuple[int, int]]:
    """(upper, lower) -> (scenes where an upper rests on a lower, scenes holding both)."""
    rests: Counter = Counter()
    both: Counter = Counter()
    for scene, support in zip(scenes, supports, strict=False):
        types = {o.id: o.type for o in scene.placed_objects()}
        present = set(types.values())
        rests.update(
            {
                (types[upper], types[lower])
                for upper, lower in support.items()
                if upper in types and lower in types and types[upper] != types[lower]
            }
        )
        both.update({(upper, lower) for upper in present for lower in present if upper != lower})
    return {pair: (count, both[pair]) for pair, count in rests.items()}


def carried_routes(
    related: Sequence[tuple[str, str]],
    resting: set[tuple[str, str]],
    counts: dict[tuple[str, str], tuple[int, int]],
) -> dict[tuple[str, str], tuple[str, str] | None]:
    """Each related pair -> the pair its relation is written between (None: not written).

    What rests on a thing is carried by it, so a relation with it is a relation with
    its carrier (followed down to what stands on the floor): a chair related to the
    monitor on a desk is placed by the desk, and two things on one desk are placed
    through the desk alone. A pair of which one rests (through others) on the other
    stays as it is, and so does a resting pair whose upper type is carried by another
    type in more scenes (books on the desk in most, on the bookshelf in some)."""
    carrier: dict[str, str] = {}
    for upper, lower in sorted(resting, key=lambda pair: (-counts.get(pair, (0, 0))[0], pair)):
        carrier.setdefault(upper, lower)

    def chain(type_name: str) -> list[str]:
        found = [type_name]
        while found[-1] in carrier and carrier[found[-1]] not in found:
            found.append(carrier[found[-1]])
        return found

    routes: dict[tuple[str, str], tuple[str, str] | None] = {}
    for a, b in related:
        below_a, below_b = chain(a), chain(b)
        if a in below_b or b in below_a or (a, b) in resting or (b, a) in resting:
            routes[(a, b)] = (a, b)
            continue
        root_a, root_b = below_a[-1], below_b[-1]
        routes[(a, b)] = tuple(sorted((root_a, root_b))) if root_a != root_b else None  # type: ignore[assignment]
    return routes


def _walls(scenes: Sequence[Scene], supports: Sequence[dict[str, str]]) -> dict[str, WallShare]:
    """Per type, how many of its standing objects each wall label held for."""
    return _type_walls(scenes, _object_walls(scenes, supports))


def _object_walls(
    scenes: Sequence[Scene], supports: Sequence[dict[str, str]]
) -> dict[tuple[int, str], set[str]]:
    """(scene index, object id) -> the wall labels that hold for that standing object."""
    found: dict[tuple[int, str], set[str]] = {}
    for index, (scene, support) in enumerate(zip(scenes, supports, strict=False)):
        if scene.room is None:
            continue
        held = wall_holds(scene.placed_objects(), scene.room, set(support))
        found.update({(index, object_id): labels for object_id, labels in held.items()})
    return found


def _type_walls(
    scenes: Sequence[Scene], held: dict[tuple[int, str], set[str]]
) -> dict[str, WallShare]:
    objects = {(k, o.id): o for k, scene in enumerate(scenes) for o in scene.placed_objects()}
    shares: dict[str, WallShare] = defaultdict(WallShare)
    for key, labels in held.items():
        obj = objects[key]
        share = shares[obj.type]
        share.objects += 1
        share.held.update(labels)
        room = scenes[key[0]].room
        if labels and room is not None and (gap := hand_gap(obj, room)) is not None:
            share.gaps.append(gap)
    return dict(shares)


def _placement_walls(
    placements: list[Placement],
    assigned: np.ndarray,
    children: Sequence[tuple[int, str]],
    held: dict[tuple[int, str], set[str]],
) -> list[Placement]:
    """``placements`` with the wall label each one's objects held (``Placement.wall``):
    the first of the wall labels that held for more than ``PLACEMENT_WALL_SHARE`` of
    them, else ``AgainstWall`` where it held for any (a corner is against a wall too),
    and the share it held for (``Placement.wall_share``; 0 with no label)."""
    walled = []
    for number_, placement in enumerate(placements):
        objects = [held.get(children[k], set()) for k in np.flatnonzero(assigned == number_)]
        share = {
            label: sum(label in labels for labels in objects) / len(objects) if objects else 0.0
            for label in CATEGORIES["wall"]
        }
        wall = next(
            (label for label in CATEGORIES["wall"] if share[label] > PLACEMENT_WALL_SHARE),
            "AgainstWall" if share["AgainstWall"] > 0.0 else None,
        )
        walled.append(replace(placement, wall=wall, wall_share=share[wall] if wall else 0.0))
    return walled


def _anchor(
    component: set[str],
    graph: nx.Graph,
    catalog: dict[str, TypeEntry],
    counts: dict[str, np.ndarray],
) -> str:
    """The type of ``component`` whose scenes hold the most of the component's objects
    (module docstring), then related to the most others, then with the largest
    footprint; ``counts``: each type's objects per scene."""
    held = sum(counts[u] for u in component)  # (scenes,): the component's objects

    def covered(t: str) -> int:
        return int(held[counts[t] > 0].sum())

    return max(
        sorted(component),
        key=lambda t: (
            covered(t),
            graph.degree(t),
            catalog[t].size[0] * catalog[t].size[2],
            [-ord(c) for c in t],
        ),
    )


def _tree(component: set[str], graph: nx.Graph, anchor: str) -> dict[str, list[str]]:
    """Parent type -> its child types along the spanning tree from ``anchor`` that takes
    the pairs standing closest first (each edge's ``gap``, the median gap between their
    footprints to 0.1 m), then the strongest: a waste bin beside a desk, with a filing
    cabinet on the desk's other side, is placed by the desk, since a placement label
    says little of where a thing stands far from its parent (NextTo reaches 2 m)."""
    edges = sorted(
        graph.subgraph(component).edges(data=True),
        key=lambda edge: (edge[2]["gap"], -edge[2]["weight"], sorted(edge[:2])),
    )
    tree = nx.Graph()
    tree.add_nodes_from(component)
    joined = nx.utils.UnionFind(sorted(component))
    for u, v, _ in edges:
        if joined[u] != joined[v]:
            joined.union(u, v)
            tree.add_edge(u, v)
    children: dict[str, list[str]] = defaultdict(list)
    seen, queue = {anchor}, [anchor]
    while queue:
        current = queue.pop(0)
        for neighbour in sorted(tree.neighbors(current)):
            if neighbour not in seen:
                seen.add(neighbour)
                children[current].append(neighbour)
                queue.append(neighbour)
    return children


def _medoid_room(scenes: Sequence[Scene], names: Sequence[str]) -> tuple[Room | None, str | None]:
    rooms = [
        (scene.room, name)
        for scene, name in zip(scenes, names, strict=False)
        if scene.room is not None
    ]
    if not rooms or 2 * len(rooms) < len(scenes):
        return None, None
    extents = np.array([room.extent for room, _ in rooms])
    median = np.median(extents, axis=0)
    best = int(np.argmin(np.abs(extents - median).sum(axis=1)))
    return rooms[best]


def induce(
    examples: Sequence[Example], *, name: str = "induced", seed: int = 0, test: str = "permutation"
) -> Induction:
    """Induce a rule set from ``examples`` (module docstring). ``InputError`` when they
    cannot be learned from (fewer than two, no two objects in one scene)."""
    if len(examples) < 2:
        raise InputError(
            f"learning a rule set needs at least 2 example scenes, got {len(examples)}"
        )
    scenes, sources = renamed_scenes(examples)
    names = [example.name for example in examples]
    if not any(scene.placed_objects() for scene in scenes):
        raise InputError("the example scenes hold no objects")
    relations = find_relations(scenes, test=test, seed=seed)
    supports = [scene_supports(scene) for scene in scenes]
    poses = type_poses(scenes)
    resting = resting_pairs(scenes, poses)
    resting_counts = _support_counts(scenes, supports)

    by_type: dict[str, list[SceneObject]] = defaultdict(list)
    scenes_of: Counter = Counter()
    for scene in scenes:
        present = set()
        for obj in scene.placed_objects():
            by_type[obj.type].append(obj)
            present.add(obj.type)
        scenes_of.update(present)
    from scenewright.generator import indoor_catalog

    shipped = indoor_catalog()
    catalog = {
        t: catalog_entry(t, by_type[t], sources[t], scenes_of[t], shipped) for t in sorted(by_type)
    }
    object_walls = _object_walls(scenes, supports)
    walls = _type_walls(scenes, object_walls)

    # Types that rest on others hang off what carries them (each of its carriers: books on
    # desks and on shelves); the others are grouped by their relations.
    lowers: dict[str, list[str]] = defaultdict(list)
    for upper, lower in sorted(
        resting, key=lambda pair: (-resting_counts.get(pair, (0, 0))[0], pair)
    ):
        lowers[upper].append(lower)
    uppers_of: dict[str, list[str]] = defaultdict(list)
    for upper, below in sorted(lowers.items()):
        for lower in below:
            uppers_of[lower].append(upper)
    routes = carried_routes(
        [(p.a, p.b) for p in relations.pairs if p.related and p.a != p.b], resting, resting_counts
    )
    graph = nx.Graph()
    graph.add_nodes_from(t for t in sorted(catalog) if t not in lowers)
    strength: dict[tuple[str, str], float] = {}
    for pair in relations.pairs:
        route = routes.get((pair.a, pair.b))
        if route is not None and route[0] not in lowers and route[1] not in lowers:
            strength[route] = max(strength.get(route, 0.0), pair.strength or 0.0)
    for (a, b), weight in sorted(strength.items()):
        graph.add_edge(a, b, weight=weight, gap=typical_gap(poses[a], poses[b], False)[0])

    counts = {t: poses[t].counts for t in poses}  # each type's objects per scene

    def count_per_scene(type_name: str) -> Counter:
        return Counter(counts[type_name].tolist())

    rule_names: set[str] = {"Scene"}
    groups: list[Group] = []
    loose: list[Loose] = []
    tree: dict[str, list[str]] = {}

    def member(parent: str, child: str, carried: bool, depth: int = 0) -> Member:
        instances = edge_instances(
            scenes,
            supports,
            parent,
            child,
            resting_only=carried,
            against_wall=not carried and walls.get(child, WallShare()).label() is not None,
        )
        placements, clusters, outliers, assigned = placements_of(instances)
        if not carried:
            placements = _placement_walls(placements, assigned, instances.children, object_walls)
        per_host = Counter(instances.hosts)
        alone = [k for k, host in enumerate(instances.hosts) if per_host[host] == 1]
        chosen = {instances.hosts[k]: int(assigned[k]) for k in alone}
        objects = {instances.hosts[k]: instances.children[k] for k in alone}
        orphans = None
        if not carried and instances.orphans.any():
            orphans = Loose(
                child,
                Counter(instances.orphans.tolist()),
                walls.get(child, WallShare()).label(),
                parent,
            )
            loose.append(orphans)
        below = (
            []
            if depth > len(catalog)
            else (
                [member(child, c, False, depth + 1) for c in tree.get(child, [])]
                + [member(child, u, True, depth + 1) for u in uppers_of.get(child, [])]
            )
        )
        made = Member(
            child,
            parent,
            len(instances.poses),
            instances.per_parent,
            placements,
            clusters,
            outliers,
            None if carried else walls.get(child, WallShare()).label(),
            below,
            carried,
            chosen=chosen,
            objects=objects,
        )
        if orphans is not None:
            orphans.member = made
        return made

    components = sorted((set(c) for c in nx.connected_components(graph)), key=lambda c: sorted(c))
    for component in components:
        if len(component) == 1 and not uppers_of.get(next(iter(component))):
            (only,) = component
            drawn = walls.get(only, WallShare()).drawn()
            loose.append(
                Loose(
                    only,
                    count_per_scene(only),
                    drawn[0] if drawn else None,
                    wall_share=drawn[1] if drawn else 1.0,
                )
            )
            continue
        anchor = _anchor(component, graph, catalog, counts)
        tree = _tree(component, graph, anchor)
        members = [member(anchor, child, False) for child in tree.get(anchor, [])]
        members += [member(anchor, upper, True) for upper in uppers_of.get(anchor, [])]
        tree_pairs = {tuple(sorted((p, c))) for p, cs in tree.items() for c in cs}
        unwritten = sorted(
            pair for pair in strength if pair[0] in component and pair not in tree_pairs
        )
        written = set(component)
        pending = list(members)
        while pending:
            current = pending.pop()
            written.add(current.type)
            pending += current.children
        groups.append(
            Group(
                unique_name(camel(anchor), rule_names),
                anchor,
                count_per_scene(anchor),
                walls.get(anchor, WallShare()).label(),
                members,
                sorted(written),
                unwritten,
            )
        )
        sides_together(groups[-1], seed)
    for upper, below in sorted(lowers.items()):
        unsupported = Counter(
            sum(
                o.type == upper
                and not ({types[i] for i in _supporters(o.id, support)} & set(below))
                for o in scene.placed_objects()
            )
            for scene, support, types in (
                (s, sup, {o.id: o.type for o in s.placed_objects()})
                for s, sup in zip(scenes, supports, strict=False)
            )
        )
        if set(unsupported) != {0}:
            loose.append(
                Loose(
                    upper,
                    unsupported,
                    walls.get(upper, WallShare()).label(),
                    " or ".join(below),
                    True,
                )
            )
    loose.sort(key=lambda item: (item.without is not None, item.type))

    room, room_source = _medoid_room(scenes, names)
    extents = np.median(np.array([scene.extent for scene in scenes], dtype=float), axis=0)
    ground = _most_common([scene.ground for scene in scenes]) if room is None else "floor"
    return Induction(
        name=name,
        examples=names,
        seed=seed,
        relations=relations,
        resting=resting,
        resting_counts=resting_counts,
        routes=routes,
        catalog=catalog,
        groups=groups,
        loose=loose,
        walls=walls,
        room=room,
        room_source=room_source,
        extent=(float(extents[0]), float(extents[1])),
        ground=ground,
        scenes=len(scenes),
    )
