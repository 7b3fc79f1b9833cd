"""Which relation labels hold where, measured by the layout's own predicates.

A learned relation is written with a label of the registry (``core.relations``), and
the label is chosen by where it *holds*: ``generator.layout.measure_layout`` puts
objects at given poses and reports, for every relation edge, whether the layout's
satisfaction threshold is met (``families.satisfied`` of the layout: "in front of" within 45
degrees and 2 m, "facing" within 30 degrees, "on the edge" within 5 cm, ...). Nothing
here restates those thresholds.

``pair_holds`` measures one child type placed at many relative poses about one parent
type (each at its median size, the parent at the origin facing +Z) against the
candidate labels of ``CATEGORIES``; ``wall_holds`` measures every standing object of a
room scene against the wall labels. ``most_specific`` picks, per category, the first
label (the most specific) that holds at a cluster's centre and for most of its members.

Categories, most specific first:

- ``support`` (the child rests on the parent): OnTopOfFrontEdge, OnTopOfMiddle,
  OnTopOfEdge, OnTopOf;
- ``near`` (it stands on the floor): NextToFront, NextToBehind, NextToLeft,
  NextToRight (the parent's own sides), NextTo;
- ``facing`` (floor objects): FacingTowards, FacingAwayFrom, FacingSameDirection,
  FacingOpposite, FacingOrthogonalDirection;
- ``turn`` (objects resting on their parent, for which facing towards the parent's
  centre says nothing): FacingSameDirection, FacingOpposite, FacingOrthogonalDirection,
  written ``Implicit``: the support already places the object, and "the laptop faces
  the same way as the desk" is no sentence a person says;
- ``alignment`` (floor objects only): AlignedWith;
- ``wall`` (per object, in a room): InCorner, AgainstWall;
- ``end`` (objects resting on their parent): NextToLeft, NextToRight, written
  ``Implicit``: which end of the top it stands at (a lamp at the left end of a
  sideboard), so that lamps at either end are two placements drawn with the examples'
  shares, not one left to the layout.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

import numpy as np

from scenewright.core.frames import footprint_reach
from scenewright.core.poses import Pose
from scenewright.core.relations import RELATIONS
from scenewright.core.room import ROOM_NODE, Room
from scenewright.core.scene import SceneObject
from scenewright.core.scene_graph import SceneGraph, SceneParams
from scenewright.generator.catalog import CatalogEntry
from scenewright.generator.layout import measure_layout

#: The candidate labels of each category, most specific first.
CATEGORIES: dict[str, tuple[str, ...]] = {
    "support": ("OnTopOfFrontEdge", "OnTopOfMiddle", "OnTopOfEdge", "OnTopOf"),
    "near": ("NextToFront", "NextToBehind", "NextToLeft", "NextToRight", "NextTo"),
    "facing": (
        "FacingTowards",
        "FacingAwayFrom",
        "FacingSameDirection",
        "FacingOpposite",
        "FacingOrthogonalDirection",
    ),
    "turn": ("FacingSameDirection", "FacingOpposite", "FacingOrthogonalDirection"),
    "alignment": ("AlignedWith",),
    "wall": ("InCorner", "AgainstWall"),
    "end": ("NextToLeft", "NextToRight"),
}
#: The family each category's labels must belong to (checked against the registry at import).
_FAMILIES = {
    "support": "support",
    "near": "next_to",
    "facing": "facing",
    "turn": "facing",
    "alignment": "alignment",
    "wall": "wall",
    "end": "next_to",
}
for _category, _labels in CATEGORIES.items():
    for _label in _labels:
        if RELATIONS[_label].family != _FAMILIES[_category]:
            raise ValueError(
                f"{_label} is registered in family {RELATIONS[_label].family}, not {_FAMILIES[_category]}"
            )

#: The categories measured between a child and its parent, by whether the child rests on it.
RESTING_CATEGORIES = ("support", "turn", "end")
#: The categories whose labels are written ``Implicit``: true of the examples, but no
#: sentence a person says of a thing on its parent ("the laptop faces the same way as
#: the desk", "the lamp is to the left of the sideboard" it stands on).
IMPLICIT_CATEGORIES = ("turn", "end")
STANDING_CATEGORIES = ("near", "facing", "alignment")
#: The least share of a cluster's members a label must hold for (as well as at its centre).
MAJORITY = 0.5
#: Open ground around a measured pair: large enough that no pose is outside it.
_GROUND = 1000.0


def _entry(name: str, size: Sequence[float]) -> CatalogEntry:
    return CatalogEntry(name, "object", name.replace("_", " "), size=tuple(float(v) for v in size))


def pair_holds(
    parent_size: Sequence[float], child_size: Sequence[float], poses: np.ndarray, resting: bool
) -> dict[str, np.ndarray]:
    """For each candidate label of the pair's categories (``RESTING_CATEGORIES`` when
    the child rests on the parent, else ``STANDING_CATEGORIES``), whether ``child
    LABEL parent`` holds at each pose: ``poses`` (n, 3) the child's (x, z, yaw) in the
    parent's frame (x along its left, z along its forward, yaw relative), the parent at
    the origin with yaw 0, a resting child at the parent's height. Returns label ->
    (n,) bool."""
    graph = SceneGraph(params=SceneParams(extent=(_GROUND, _GROUND)))
    parent = graph.add_node(_entry("parent", parent_size))
    child = graph.add_node(_entry("child", child_size))
    labels = [
        label
        for category in (RESTING_CATEGORIES if resting else STANDING_CATEGORIES)
        for label in CATEGORIES[category]
    ]
    for label in labels:
        graph.add_relation(child, parent, label)
    height = float(parent_size[1]) if resting else 0.0
    holds = {label: np.zeros(len(poses), dtype=bool) for label in labels}
    for k, (x, z, yaw) in enumerate(np.asarray(poses, dtype=float).reshape(-1, 3)):
        result = measure_layout(
            graph,
            {parent: Pose(0.0, 0.0, 0.0, 0.0), child: Pose(float(x), height, float(z), float(yaw))},
            {},
        )
        for relation in result.relations:
            holds[relation.label][k] = bool(relation.satisfied)
    return holds


#: Points per side of the grid of poses on a parent's top that ``support_room`` tries.
ROOM_GRID = 9


def support_room(
    parent_size: Sequence[float], child_size: Sequence[float], count: int
) -> dict[str, bool]:
    """Per support label: whether ``count`` children of ``child_size`` fit on one parent
    of ``parent_size`` side by side, each where the label holds (``pair_holds``) and no
    two overlapping. Tried on a ``ROOM_GRID`` x ``ROOM_GRID`` grid of poses over the
    parent's top (the child turned as the parent), packed greedily row by row from the
    back left: "in the middle" of a side table holds one book, not two."""
    width, _, depth = (float(v) for v in parent_size)
    xs = np.linspace(-width / 2.0, width / 2.0, ROOM_GRID)
    zs = np.linspace(-depth / 2.0, depth / 2.0, ROOM_GRID)
    poses = np.array([(x, z, 0.0) for z in zs for x in xs])
    holds = pair_holds(parent_size, child_size, poses, True)
    child_w, child_d = float(child_size[0]), float(child_size[2])
    found = {}
    for label in CATEGORIES["support"]:
        placed: list[tuple[float, float]] = []
        for (x, z, _), held in zip(poses, holds[label], strict=True):
            if held and all(
                abs(x - px) >= child_w - 1e-9 or abs(z - pz) >= child_d - 1e-9 for px, pz in placed
            ):
                placed.append((float(x), float(z)))
        found[label] = len(placed) >= count
    return found


#: A person placing things by hand leaves a few centimetres to a wall, and turns a round
#: thing (a floor lamp, a plant) any way, its box's corners then a little into the walls:
#: before the wall labels are measured, a standing object within HAND_GAP (metres,
#: between footprint and wall, either side of it) of a wall as it stands is set flush to
#: it, as the layout would set it, an object whose footprint is square within
#: SQUARE_ASPECT first turned with its back to the nearest (``hand_placed``).
HAND_GAP = 0.15
SQUARE_ASPECT = 1.2


def square_footprint(width, depth):
    """Whether a footprint ``width`` x ``depth`` is square within ``SQUARE_ASPECT`` (a
    floor lamp, a plant: a person turns such a thing any way); elementwise on arrays."""
    return np.maximum(width, depth) <= SQUARE_ASPECT * np.minimum(width, depth)


def hand_placed(obj: SceneObject, room: Room) -> tuple[float, float, float]:
    """(x, z, yaw) of a standing object as its placer meant it against the walls
    (``HAND_GAP``, ``SQUARE_ASPECT``): unchanged where no wall is that near."""
    return _hand_placed(obj, room)[0]


def hand_gap(obj: SceneObject, room: Room) -> float | None:
    """The gap (metres, at least 0) its placer left between a standing object and the
    nearest wall it was set against (``hand_placed``), a round thing turned with its
    back to it; None where no wall is within ``HAND_GAP``."""
    return _hand_placed(obj, room)[1]


def _hand_placed(obj: SceneObject, room: Room) -> tuple[tuple[float, float, float], float | None]:
    """``hand_placed``'s pose and ``hand_gap``'s gap."""
    x, z, yaw = float(obj.position[0]), float(obj.position[2]), float(obj.yaw)

    def gap(wall, x: float, z: float, yaw: float) -> float | None:
        """The gap between the footprint and ``wall``, None when the object is not beside it."""
        u, v = wall.to_wall(x, z)
        reach_u, reach_v = footprint_reach(
            yaw - wall.facing_yaw, obj.size[0], obj.size[2]
        )  # along it, off it
        if u + reach_u < 0.0 or u - reach_u > wall.length:
            return None
        return v - reach_v

    # The walls it was set against, as it stands (a few centimetres off, or a turned box's
    # corners a little into one); then turned (a round thing) and flush.
    near = sorted(
        (
            (abs(g), k)
            for k, wall in enumerate(room.walls)
            if (g := gap(wall, x, z, yaw)) is not None and abs(g) <= HAND_GAP
        )
    )
    if not near:
        return (x, z, yaw), None
    if square_footprint(obj.size[0], obj.size[2]):
        yaw = room.walls[near[0][1]].facing_yaw  # a round thing's turn means nothing
    kept = None
    for _, k in near:
        wall = room.walls[k]
        g = gap(wall, x, z, yaw)
        if g is not None:
            kept = max(g, 0.0) if kept is None else kept
            nx, nz = wall.normal
            x, z = x - g * nx, z - g * nz
    return (x, z, yaw), kept


def wall_holds(
    objects: Sequence[SceneObject], room: Room, resting: set[str]
) -> dict[str, set[str]]:
    """Object id -> the wall labels of ``CATEGORIES["wall"]`` that hold for it against
    some wall of ``room`` (the layout chooses the wall, as for ``AgainstWall some
    wall``), standing as its placer meant it (``hand_placed``). Objects in ``resting``
    (ids of objects standing on another) are left out."""
    graph = SceneGraph(params=SceneParams(extent=room.extent, ground="floor", room=room))
    node_of: dict[str, str] = {}
    poses: dict[str, Pose] = {}
    for obj in objects:
        node = graph.add_node(_entry(obj.type, obj.size))
        node_of[obj.id] = node
        if obj.id in resting:
            poses[node] = Pose(*(float(v) for v in obj.position), float(obj.yaw))
        else:
            x, z, yaw = hand_placed(obj, room)
            poses[node] = Pose(x, float(obj.position[1]), z, yaw)
    standing = [obj.id for obj in objects if obj.id not in resting]
    for object_id in standing:
        for label in CATEGORIES["wall"]:
            graph.add_relation(node_of[object_id], ROOM_NODE, label)
    by_node = {node: object_id for object_id, node in node_of.items()}
    found: dict[str, set[str]] = {object_id: set() for object_id in standing}
    for relation in measure_layout(graph, poses, {}).relations:
        if relation.satisfied:
            found[by_node[relation.source]].add(relation.label)
    return found


def most_specific(
    category: str,
    holds: dict[str, np.ndarray],
    centre: int,
    members: np.ndarray,
    share: float = MAJORITY,
    allowed: Callable[[str], bool] = lambda label: True,
) -> str | None:
    """The first label of ``category`` that holds at point ``centre`` and for at least
    ``share`` of ``members`` (indices into the (n,) arrays of ``holds``), of those
    ``allowed``, or None."""
    for label in CATEGORIES[category]:
        if not allowed(label):
            continue
        if label in holds and holds[label][centre] and holds[label][members].mean() >= share:
            return label
    return None
