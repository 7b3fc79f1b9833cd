"""The poses the relation tests compare. Each role's objects per scene (``TypePoses``:
poses, footprints and holding groups; a path as points along it), the roles themselves
(``Role``: a type and the kind of group holding it), and the pose of the nearest
partner in an object's frame: (x, z) along its left and forward and the relative yaw as
(cos, sin), a point of R^4. Every random draw of a pair comes from ``pair_stream``.
Design notes: docs/notes/design.md, "Relation finding".
"""

from __future__ import annotations

import hashlib
import math
from collections import defaultdict
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from scenewright.core.frames import footprint_reach_many, to_local_many
from scenewright.core.scene import Scene
from scenewright.core.seeds import stream

from .pose_labels import square_footprint
from .relation_thresholds import MAX_SCENES, PATH_STEP


@dataclass(frozen=True)
class TypePoses:
    """Where the objects of one type stand in each of S scenes: ``poses`` (S, K, 3) as
    (x, z, yaw) in the scene's frame, K the most objects of the type in one scene, NaN
    past ``counts`` (S,), the objects of the type in each scene; ``footprints`` (S, K, 2)
    their (width, depth) in their own frame, NaN past ``counts``; ``holders`` (S, K) the
    group that holds each object, numbered within its scene (-1 at the top level and
    past ``counts``)."""

    poses: np.ndarray
    counts: np.ndarray
    footprints: np.ndarray
    holders: np.ndarray


def type_poses(
    scenes: Sequence[Scene], names: Sequence[dict[str, str]] | None = None
) -> dict[str, TypePoses]:
    """Every placed object type of ``scenes`` with its poses, in type order; with
    ``names`` (per scene, object id -> name), every name instead (the roles' names)."""
    per_type: dict[str, list[list[tuple[float, ...]]]] = defaultdict(lambda: [[] for _ in scenes])
    for index, scene in enumerate(scenes):
        groups = holding_groups(scene)
        numbers = {
            group: number for number, group in enumerate(sorted(set(groups.values()) - {""}))
        }
        for obj in scene.placed_objects():
            name = obj.type if names is None else names[index][obj.id]
            holder = numbers.get(groups[obj.id], -1)
            per_type[name][index].append(
                (obj.position[0], obj.position[2], obj.yaw, obj.size[0], obj.size[2], holder)
            )
    return {name: padded(per_type[name]) for name in sorted(per_type)}


def padded(per_scene: Sequence[Sequence[Sequence[float]]]) -> TypePoses:
    """``TypePoses`` of rows (x, z, yaw, width, depth, holder) listed per scene, NaN past
    each scene's count (holder -1)."""
    counts = np.array([len(rows) for rows in per_scene])
    table = np.full((len(per_scene), int(counts.max()), 6), np.nan)
    for index, rows in enumerate(per_scene):
        if len(rows):
            table[index, : len(rows)] = rows
    holders = np.nan_to_num(table[..., 5], nan=-1.0).astype(int)
    return TypePoses(table[..., :3], counts, table[..., 3:5], holders)


@dataclass(frozen=True, order=True)
class Role:
    """What an object is when relations are found: its ``type`` and the kind of the
    innermost group that holds it, ``group`` ("" at the top level; design notes,
    "Roles")."""

    type: str
    group: str = ""

    @property
    def name(self) -> str:
        """The type alone at the top level, else "<type> in <group>"."""
        return f"{self.type} in {self.group}" if self.group else self.type


def object_roles(scene: Scene) -> dict[str, Role]:
    """The role of every placed object of ``scene``, by id: the group is the type of the
    nearest group among the object's parents (an object a hand-written example puts on
    another has that one as parent, and no group)."""
    groups = holding_groups(scene)
    kinds = {obj.id: obj.type for obj in scene.objects}
    return {
        obj.id: Role(obj.type, kinds[groups[obj.id]] if groups[obj.id] else "")
        for obj in scene.placed_objects()
    }


def holding_groups(scene: Scene) -> dict[str, str]:
    """The id of the innermost group holding each placed object of ``scene``, by id (""
    at the top level)."""
    entities = {obj.id: obj for obj in scene.objects}
    holders = {}
    for obj in scene.placed_objects():
        parent = entities.get(obj.parent) if obj.parent else None
        while parent is not None and parent.kind != "group":
            parent = entities.get(parent.parent) if parent.parent else None
        holders[obj.id] = parent.id if parent is not None else ""
    return holders


def path_poses(scenes: Sequence[Scene]) -> dict[str, TypePoses]:
    """Every path type of ``scenes`` (named "<type> path") as points ``PATH_STEP``
    apart along its paths' centre lines, each turned along its segment, with the
    path's width and the step as footprint."""
    per_type: dict[str, list[list[np.ndarray]]] = defaultdict(lambda: [[] for _ in scenes])
    for index, scene in enumerate(scenes):
        for path in scene.paths:
            corners = np.asarray(path.points, dtype=float)
            for start, end in zip(corners[:-1], corners[1:], strict=False):
                length = float(np.hypot(*(end - start)))
                points = start + np.arange(0.0, length, PATH_STEP)[:, None] / max(length, 1e-12) * (
                    end - start
                )
                yaw = math.atan2(end[0] - start[0], end[1] - start[1])  # forward is +z at yaw 0
                rows = np.column_stack(
                    [points, np.tile([yaw, path.width, PATH_STEP, -1], (len(points), 1))]
                )
                per_type[f"{path.type} path"][index].append(rows)
    return {
        name: padded([np.vstack(chunks) if chunks else () for chunks in per_type[name]])
        for name in sorted(per_type)
    }


def holding_both(first: TypePoses, second: TypePoses, same: bool) -> np.ndarray:
    """Indices of the scenes holding an a and a b (two a's when ``same``)."""
    if same:
        return np.flatnonzero(first.counts >= 2)
    return np.flatnonzero((first.counts >= 1) & (second.counts >= 1))


def relative_poses(centres: np.ndarray, others: np.ndarray) -> np.ndarray:
    """Poses ``others`` (n, k, 3) in the frames of ``centres`` (n, 3), both (x, z, yaw)
    -> (n, k, 4): x, z in the centre's frame, cos and sin of the relative yaw."""
    local = to_local_many(centres[:, :2], centres[:, 2], others[..., :2])
    turn = others[..., 2] - centres[:, None, 2]
    return np.concatenate([local, np.cos(turn)[..., None], np.sin(turn)[..., None]], axis=-1)


def nearest_indices(
    centres: np.ndarray,
    others: TypePoses,
    scenes: np.ndarray,
    left_out: np.ndarray | None = None,
    holders: np.ndarray | None = None,
) -> np.ndarray:
    """The index of the object of ``others`` nearest each of ``centres`` (n, 3) in the
    scene ``scenes[k]``, leaving out its object ``left_out[k]`` when given, and only
    among those the group ``holders[k]`` holds when given -> (n,)."""
    rows = np.arange(len(scenes))
    candidates = others.poses[scenes]  # (n, K, 3)
    valid = np.arange(candidates.shape[1])[None, :] < others.counts[scenes][:, None]
    if left_out is not None:
        valid[rows, left_out] = False
    if holders is not None:
        valid &= others.holders[scenes] == holders[:, None]
    distance = np.where(
        valid, np.hypot(*(candidates[..., :2] - centres[:, None, :2]).transpose(2, 0, 1)), np.inf
    )
    return np.argmin(distance, axis=1)


def nearest_objects(
    centres: np.ndarray,
    others: TypePoses,
    scenes: np.ndarray,
    left_out: np.ndarray | None = None,
    holders: np.ndarray | None = None,
) -> np.ndarray:
    """The pose (x, z, yaw) of the object of ``others`` nearest each of ``centres`` (n,
    3), in the scene ``scenes[k]``, leaving out its object ``left_out[k]`` when given and
    only among those the group ``holders[k]`` holds when given -> (n, 3)."""
    return others.poses[scenes, nearest_indices(centres, others, scenes, left_out, holders)]


def fellows_held(frame: TypePoses, *others: TypePoses) -> np.ndarray:
    """(S, K) whether each object of ``frame`` stands in a group that also holds an
    object of each of ``others`` (False past the counts and at the top level)."""
    held = frame.holders >= 0
    for other in others:
        held &= (frame.holders[:, :, None] == other.holders[:, None, :]).any(axis=2)
    return held


def nearest_poses(
    first: TypePoses,
    second: TypePoses,
    a_scenes: np.ndarray,
    b_scenes: np.ndarray,
    same: bool,
    rng: np.random.Generator,
    chosen: np.ndarray | None = None,
) -> np.ndarray:
    """One pose per scene: a random a of scene ``a_scenes[k]`` (the ``chosen[k]``-th
    when given) and the nearest b of scene ``b_scenes[k]`` in its frame -> (n, 4). When
    ``same``, the a itself is no candidate in its own scene, and in another scene one
    random a is left out."""
    if chosen is None:
        chosen = np.floor(rng.random(len(a_scenes)) * first.counts[a_scenes]).astype(int)
    centres = first.poses[a_scenes, chosen]
    left_out = counterparts(second, b_scenes, chosen, rng) if same else None
    nearest = nearest_objects(centres, second, b_scenes, left_out)
    return relative_poses(centres, nearest[:, None])[:, 0]


def counterparts(
    others: TypePoses, scenes: np.ndarray, chosen: np.ndarray, rng: np.random.Generator
) -> np.ndarray:
    """For two objects of one type: the object of scene ``scenes[k]`` left out as the
    counterpart of the ``chosen[k]``-th a (the a itself in its own scene) -> (n,). The
    object of the same index, which in a scene made from rules plays the same part (the
    left counter, not the right one); where that scene has no such index, a random one."""
    counts = others.counts[scenes]
    at_random = np.floor(rng.random(len(scenes)) * counts).astype(int)
    return np.where(chosen < counts, chosen, at_random)


def framed(
    first: TypePoses, second: TypePoses, together: np.ndarray
) -> tuple[TypePoses, TypePoses]:
    """The two types with the frame first: the one with fewer objects in the scenes
    ``together`` (``first`` on a tie; design notes)."""
    if second.counts[together].sum() < first.counts[together].sum():
        return second, first
    return first, second


def pair_poses(
    first: TypePoses, second: TypePoses, same: bool, together: np.ndarray, rng: np.random.Generator
) -> tuple[np.ndarray, np.ndarray]:
    """The within- and across-scene poses of the scene-pair test (design notes) on
    the scenes ``together``, at most ``MAX_SCENES`` of them: (2K, 4) each, the pose of
    pair k's first scene in row k and of its second in row K + k."""
    order = rng.permutation(together)[:MAX_SCENES]
    pairs = len(order) // 2
    ones, twos = order[:pairs], order[pairs : 2 * pairs]
    if same:  # one index for both scenes of a pair: each a's counterpart is left out in the other
        index = np.floor(
            rng.random(pairs) * np.minimum(first.counts[ones], first.counts[twos])
        ).astype(int)
        chosen = np.concatenate([index, index])
    else:
        chosen = np.floor(
            rng.random(2 * pairs) * first.counts[np.concatenate([ones, twos])]
        ).astype(int)
    a_scenes = np.concatenate([ones, twos])
    within = nearest_poses(first, second, a_scenes, a_scenes, same, rng, chosen=chosen)
    across = nearest_poses(
        first, second, a_scenes, np.concatenate([twos, ones]), same, rng, chosen=chosen
    )
    return within, across


def footprint_gaps(pose: np.ndarray, a_sizes: np.ndarray, b_sizes: np.ndarray) -> np.ndarray:
    """The gap between an a's footprint and a b's, b at ``pose`` (n, 4) in a's frame,
    footprints (n, 2) each -> (n,): along a's axes, with b's reach there once turned, as
    the layout measures two boxes square to each other."""
    reach = footprint_reach_many(np.arctan2(pose[:, 3], pose[:, 2]), b_sizes)
    return np.hypot(*np.maximum(np.abs(pose[:, :2]) - a_sizes / 2.0 - reach, 0.0).T)


def pair_stream(seed: int, *names: str) -> np.random.Generator:
    """The stream of the pair (a, b), or of the triangle (a, c, b) when three names are
    given: child k of the ``relations`` stage, k a hash of the names."""
    key = int.from_bytes(hashlib.sha256("\0".join(names).encode()).digest()[:4], "big")
    return stream(seed, "relations", key)


def square(poses: TypePoses) -> bool:
    """Whether the type's median footprint is square within ``SQUARE_ASPECT`` (a floor
    lamp, a plant: a person turns such a thing any way)."""
    valid = poses.footprints[np.arange(poses.footprints.shape[1])[None, :] < poses.counts[:, None]]
    if len(valid) == 0:
        return False
    width, depth = np.median(valid, axis=0)
    return bool(square_footprint(width, depth))


def hand_placed_poses(poses: np.ndarray, square_b: bool) -> np.ndarray:
    """Relative poses (..., 4) with either side of a alike: a pose on a's right
    (x < 0) mirrored to its left (x and the turn's sine negated), and the turn of a
    square b (``square``) left out. A lamp on an armchair's left in some examples and
    on its right in others stands one way here; as the examples hold it, the two sides
    spread the within-scene poses as far as the room does."""
    found = poses.copy()
    right = found[..., 0] < 0
    found[..., 0] = np.abs(found[..., 0])
    found[..., 3] = np.where(right, -found[..., 3], found[..., 3])
    if square_b:
        found[..., 2], found[..., 3] = 1.0, 0.0
    return found
