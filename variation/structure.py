"""The structure graph of a scene: objects with their boxes and facing, and between two
objects the set of relations the geometry shows.

The relation set is the one of "Structure-guided 3D interior scene synthesis" (the
scene-variation method this package implements), each measured from the boxes:

- ``S`` support: A carries B (the scene's support relations: given by the grammar or
  the file, or measured from stacking by the importer);
- ``F`` facing: A's front looks at B: the axis separating the two footprints is within
  ``FACING_CONE`` of A's forward and B is near. Records the signed relative yaw
  ``facing_angle`` (B's yaw minus A's) and the gap;
- ``V`` vertical contact: side by side, touching (gap at most ``CONTACT``) with
  overlapping heights. Records the signed contact angles: from A's forward and from
  B's forward to the contact normal (A towards B), which tell a left contact from a
  right one. The paper keeps their mean; the mean of two angles is undefined when they
  are opposite (two boxes facing opposite ways), so both are kept and the similarity
  compares each (``matching``);
- ``A`` aligned: parallel (yaws equal modulo 90 degrees within ``PARALLEL``) and near,
  with one side of A's box flush with the same side of B's (within ``FLUSH``);
- ``C`` close: near but not touching; records the gap.

"Near" is a gap of at most ``NEAR_FACTOR`` times the larger of the two footprints' half
diagonals, so closeness scales with the furniture (a chair pulled 0.7 m out from a
1.4 m desk is near it; a lamp 0.7 m from a plant is not). The gap and the contact normal come
from the separating axes of the two turned footprints (the largest separation along
the four box axes: the true distance for boxes face to face, a lower bound corner to
corner).

Each relation is a threshold, and a move of a few centimetres carries a pair across
one. So every edge also holds *graded memberships* (``Edge.grades``) of V, A, F and C:
each threshold is the middle of a smooth fall-off (``fade``: 1 well inside, 1/2 at the
threshold, 0 well outside), near's a share ``NEAR_BAND`` of its own limit (scale-free),
contact's from touching to twice ``CONTACT``, flush's, parallel's and the facing
cone's a half or a quarter of theirs. C is near and not touching, V near and touching.
Pairs just outside every threshold, with no relation but a membership above 0, are kept
apart in ``fringe``: the matching compares them, nothing else reads them.

Edges are stored per ordered pair, both ways: ``edges[(i, j)]`` is A = i, B = j,
measured from i's side: the reverse holds the other object's facing, the negated facing
angle and the contact angle turned by pi, so matching an edge in reverse compares the
right quantities. Supported objects are left out of the layout subgraph
(``layout_nodes``); they travel with their supporter.

Arrays (n objects): ``centres`` (n, 2) x, z; ``bottoms`` (n,); ``sizes`` (n, 3) width,
height, depth along the local axes; ``yaws`` (n,); ``forwards`` (n, 2).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from scenewright.core.frames import footprint_corners
from scenewright.core.geometry import wrap_angle
from scenewright.core.scene import Scene
from scenewright.examples import scene_supports

#: Relation codes, in the order they are printed.
RELATION_CODES = ("S", "F", "V", "A", "C")
#: Gap (metres) at or below which two footprints touch.
CONTACT = 0.05
#: Two objects are near when their gap is at most this times the larger half diagonal.
NEAR_FACTOR = 1.0
#: Half-angle of the cone in front of an object in which what is near is faced.
FACING_CONE = math.radians(45.0)
#: Yaw difference modulo 90 degrees below which two boxes are parallel.
PARALLEL = math.radians(5.0)
#: Distance (metres) within which two parallel sides are flush.
FLUSH = 0.1
#: Graded relations (``Edge.grades``): each threshold above is the middle of a smooth
#: fall-off this wide on either side (membership 1 below it, 1/2 at the threshold, 0
#: above it). Near's is a share of its own limit, so it scales with the furniture; the
#: others are half their threshold (contact: from touching to twice the contact gap).
NEAR_BAND = 0.05
CONTACT_BAND = CONTACT
FLUSH_BAND = FLUSH / 2.0
PARALLEL_BAND = PARALLEL / 2.0
FACING_BAND = FACING_CONE / 4.0
#: The relations that have a graded membership, in the order of ``Edge.grades``.
GRADED_CODES = ("V", "A", "F", "C")


def wrap(angle: float) -> float:
    """``angle`` in (-pi, pi]."""
    wrapped = wrap_angle(angle)
    return math.pi if wrapped == -math.pi else wrapped


@dataclass(frozen=True)
class Edge:
    """The relations from object A to object B (``relations`` holds codes of
    ``RELATION_CODES``; ``S`` here means A supports B, ``s`` that B supports A)."""

    relations: frozenset[str]
    gap: float
    facing_angle: float  # B's yaw minus A's, wrapped
    contact_angles: tuple[float, float]  # from A's and from B's forward to the normal A -> B
    scale: (
        float  # the pair's mean footprint half diagonal (metres): the length unit of similarities
    )
    grades: tuple[float, float, float, float] = (
        0.0,
        0.0,
        0.0,
        0.0,
    )  # memberships of GRADED_CODES in [0, 1]


@dataclass
class StructureGraph:
    """Objects (by index) and the relation sets between them (see the module docstring)."""

    ids: list[str]
    types: list[str]
    styles: list[str | None]
    centres: np.ndarray
    bottoms: np.ndarray
    sizes: np.ndarray
    yaws: np.ndarray
    supporter: dict[int, int]  # supported object -> the object it rests on
    edges: dict[tuple[int, int], Edge] = field(default_factory=dict)
    #: Pairs where no relation holds but one is within its fall-off (a graded membership
    #: above 0): the matching compares them, nothing else reads them.
    fringe: dict[tuple[int, int], Edge] = field(default_factory=dict)
    name: str = ""
    extent: tuple[float, float] | None = None  # the room's floor (x, z), centred on the origin

    @property
    def forwards(self) -> np.ndarray:
        return np.stack([np.sin(self.yaws), np.cos(self.yaws)], axis=-1)

    @property
    def places(self) -> np.ndarray:
        """(n, 2) the centres as shares of the room's extent (in [-0.5, 0.5] inside it),
        comparable between rooms of different sizes; the centres when there is no extent."""
        if not self.extent or min(self.extent) <= 0.0:
            return self.centres
        return self.centres / np.asarray(self.extent, dtype=float)

    def __len__(self) -> int:
        return len(self.ids)

    def index(self, object_id: str) -> int:
        return self.ids.index(object_id)

    def layout_nodes(self) -> list[int]:
        """Objects that stand on the floor (not supported): the layout subgraph's nodes."""
        return [i for i in range(len(self)) if i not in self.supporter]

    def carried(self, i: int) -> list[int]:
        """The objects resting on object i, directly or through others."""
        found, frontier = [], [i]
        while frontier:
            below = frontier.pop()
            above = [j for j, s in self.supporter.items() if s == below]
            found += above
            frontier += above
        return sorted(found)

    def neighbours(self, i: int, nodes: set[int] | None = None) -> list[int]:
        """Objects with an edge to i (within ``nodes`` when given)."""
        return sorted(j for (a, j) in self.edges if a == i and (nodes is None or j in nodes))

    def relation_set(self, i: int, j: int) -> frozenset[str]:
        edge = self.edges.get((i, j))
        return edge.relations if edge else frozenset()

    def to_dict(self) -> dict:
        """Plain data: objects and each edge once (A before B in object order)."""
        return {
            "objects": [
                {
                    "id": self.ids[i],
                    "type": self.types[i],
                    "style": self.styles[i],
                    "supported_by": self.ids[self.supporter[i]] if i in self.supporter else None,
                }
                for i in range(len(self))
            ],
            "edges": [
                {
                    "a": self.ids[i],
                    "b": self.ids[j],
                    "relations": sorted(e.relations, key=_code_order),
                    "gap": round(e.gap, 4),
                    "facing_angle": round(e.facing_angle, 4),
                    "contact_angles": [round(a, 4) for a in e.contact_angles],
                }
                for (i, j), e in sorted(self.edges.items())
                if i < j
            ],
        }


def _code_order(code: str) -> int:
    return RELATION_CODES.index(code.upper()) * 2 + code.islower()


def structure_graph(scene: Scene) -> StructureGraph:
    """The structure graph of a scene's placed objects (kind ``object``)."""
    objects = scene.placed_objects()
    index = {o.id: k for k, o in enumerate(objects)}
    supporter = {index[a]: index[b] for a, b in scene_supports(scene).items()}
    graph = StructureGraph(
        ids=[o.id for o in objects],
        types=[o.type for o in objects],
        styles=[o.style for o in objects],
        centres=np.array([[o.position[0], o.position[2]] for o in objects], dtype=float).reshape(
            -1, 2
        ),
        bottoms=np.array([o.position[1] for o in objects], dtype=float),
        sizes=np.array([o.size for o in objects], dtype=float).reshape(-1, 3),
        yaws=np.array([o.yaw for o in objects], dtype=float),
        supporter=supporter,
        name=scene.name,
        extent=(float(scene.extent[0]), float(scene.extent[1])),
    )
    measure_edges(graph)
    return graph


def measure_edges(graph: StructureGraph) -> None:
    """Fill ``graph.edges`` from the boxes (both directions of every related pair), and
    ``graph.fringe`` with the pairs only a graded membership relates."""
    graph.edges.clear()
    graph.fringe.clear()
    n = len(graph)
    radii = np.hypot(graph.sizes[:, 0], graph.sizes[:, 2]) / 2.0
    on_floor = [k not in graph.supporter for k in range(n)]
    for i in range(n):
        for j in range(i + 1, n):
            supported = graph.supporter.get(i) == j or graph.supporter.get(j) == i
            if not supported and not (on_floor[i] and on_floor[j]):
                continue  # only a support relates a pair off the floor (measure_pair)
            # Skip pairs surely farther apart than the end of near's fall-off (most pairs of
            # a large scene): one of i's axes is within 45 degrees of the line between the
            # centres, and along it the separation is at least distance / sqrt(2) minus the
            # two radii.
            lower_gap = (
                float(np.hypot(*(graph.centres[i] - graph.centres[j]))) / math.sqrt(2.0)
                - radii[i]
                - radii[j]
            )
            if not supported and lower_gap > (1.0 + NEAR_BAND) * NEAR_FACTOR * max(
                radii[i], radii[j]
            ):
                continue
            forward, backward = measure_pair(graph, i, j), measure_pair(graph, j, i)
            if forward.relations or backward.relations:  # F may hold one way only
                graph.edges[(i, j)], graph.edges[(j, i)] = forward, backward
            elif max(forward.grades + backward.grades) > 0.0:
                graph.fringe[(i, j)], graph.fringe[(j, i)] = forward, backward


def fade(value: float, threshold: float, band: float) -> float:
    """Membership of ``value <= threshold`` with a smooth fall-off: 1 up to
    threshold - band, 0 from threshold + band, 1/2 at the threshold (smoothstep between)."""
    share = min(max((threshold + band - value) / (2.0 * band), 0.0), 1.0)
    return share * share * (3.0 - 2.0 * share)


def measure_pair(graph: StructureGraph, i: int, j: int) -> Edge:
    """The relations from i to j (F: i faces j; none when they are unrelated) and their
    graded memberships (``Edge.grades``)."""
    relations: set[str] = set()
    if graph.supporter.get(j) == i:
        relations.add("S")
    if graph.supporter.get(i) == j:
        relations.add("s")
    gap, normal, facing_angle, contact_angles, scale = _measures(graph, i, j)
    limit = (
        NEAR_FACTOR * float(np.hypot(graph.sizes[[i, j], 0], graph.sizes[[i, j], 2]).max()) / 2.0
    )
    floor_pair = i not in graph.supporter and j not in graph.supporter
    heights_overlap = min(
        graph.bottoms[i] + graph.sizes[i, 1], graph.bottoms[j] + graph.sizes[j, 1]
    ) > max(graph.bottoms[i], graph.bottoms[j])
    turn, offset = _alignment(graph, i, j)
    off_axis = abs(_signed_angle(graph.forwards[i], normal))
    if gap <= limit and floor_pair:
        if gap <= CONTACT and heights_overlap:
            relations.add("V")
        elif gap > CONTACT:
            relations.add("C")
        if turn <= PARALLEL and offset <= FLUSH:
            relations.add("A")
        if off_axis <= FACING_CONE:
            relations.add("F")
    grades = (0.0, 0.0, 0.0, 0.0)
    if floor_pair:
        near, touching = fade(gap, limit, NEAR_BAND * limit), fade(gap, CONTACT, CONTACT_BAND)
        grades = (
            near * touching * float(heights_overlap),
            near * fade(turn, PARALLEL, PARALLEL_BAND) * fade(offset, FLUSH, FLUSH_BAND),
            near * fade(off_axis, FACING_CONE, FACING_BAND),
            near * (1.0 - touching),
        )
    return Edge(frozenset(relations), gap, facing_angle, contact_angles, scale, grades)


def _measures(
    graph: StructureGraph, i: int, j: int
) -> tuple[float, np.ndarray, float, tuple[float, float], float]:
    """Gap, the separating normal i -> j, facing angle (j's yaw minus i's), contact
    angles (from i's and j's forwards to the normal) and the pair's mean half diagonal."""
    gap, normal = separation(graph, i, j)
    contact_angles = (
        _signed_angle(graph.forwards[i], normal),
        _signed_angle(graph.forwards[j], normal),
    )
    facing_angle = wrap(float(graph.yaws[j] - graph.yaws[i]))
    half_diagonals = np.hypot(graph.sizes[[i, j], 0], graph.sizes[[i, j], 2]) / 2.0
    return gap, normal, facing_angle, contact_angles, float(half_diagonals.mean())


def separation(graph: StructureGraph, i: int, j: int) -> tuple[float, np.ndarray]:
    """The gap between two footprints (negative: overlap depth) and the unit normal
    (x, z) of the separating axis, pointing from i towards j."""
    corners_i = np.array(_corners(graph, i))
    corners_j = np.array(_corners(graph, j))
    best_gap, best_normal = -math.inf, np.array([0.0, 1.0])
    for yaw in (graph.yaws[i], graph.yaws[j]):
        for axis in _axes(yaw):
            pi, pj = corners_i @ axis, corners_j @ axis
            forward_gap, backward_gap = pj.min() - pi.max(), pi.min() - pj.max()
            gap, normal = (
                (forward_gap, axis) if forward_gap >= backward_gap else (backward_gap, -axis)
            )
            if gap > best_gap + 1e-12:
                best_gap, best_normal = gap, normal
    return float(best_gap), best_normal


def _corners(graph: StructureGraph, i: int) -> list[tuple[float, float]]:
    return footprint_corners(
        graph.centres[i, 0],
        graph.centres[i, 1],
        graph.yaws[i],
        graph.sizes[i, 0],
        graph.sizes[i, 2],
    )


def _signed_angle(a: np.ndarray, b: np.ndarray) -> float:
    """The angle turning direction a onto direction b in the ground plane, in (-pi, pi]
    (positive turns forward towards +X, as yaw does)."""
    return wrap(math.atan2(b[0], b[1]) - math.atan2(a[0], a[1]))


def _alignment(graph: StructureGraph, i: int, j: int) -> tuple[float, float]:
    """How far two boxes are from aligned: the yaw difference modulo 90 degrees (radians,
    0 when parallel) and the smallest distance between a side of i's box and the same
    side of j's (metres), along either box's axes (the same answer both ways round)."""
    turn = (graph.yaws[j] - graph.yaws[i]) % (math.pi / 2.0)
    corners_i, corners_j = np.array(_corners(graph, i)), np.array(_corners(graph, j))
    offset = math.inf
    for yaw in (graph.yaws[i], graph.yaws[j]):
        for axis in _axes(yaw):
            pi, pj = corners_i @ axis, corners_j @ axis
            offset = min(offset, abs(pi.min() - pj.min()), abs(pi.max() - pj.max()))
    return float(min(turn, math.pi / 2.0 - turn)), float(offset)


def _axes(yaw: float) -> tuple[np.ndarray, np.ndarray]:
    """A box's left and forward (x, z) unit vectors."""
    return np.array([math.cos(yaw), -math.sin(yaw)]), np.array([math.sin(yaw), math.cos(yaw)])
