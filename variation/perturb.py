"""A disguised copy of a scene, with the truth, for measuring how well matching works.

``perturbed_copy`` renames every type (and id) to a new name, moves each standing
object by ``jitter`` metres in a random direction (what stands on it moves along),
removes ``remove`` standing objects (with what they carry), adds ``add`` boxes of random
size on free floor, and shuffles the order. It returns the copy and the truth: each
surviving object's id -> its id in the copy. Only the support relations are kept (the
renamed types mean nothing to the grammar's). Draws from the ``rng`` it is given.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from scenewright.core.relations import Relation
from scenewright.core.scene import Scene, SceneObject, object_corners
from scenewright.examples import scene_supports
from scenewright.examples.example import SUPPORT_LABEL


def perturbed_copy(
    scene: Scene, rng: np.random.Generator, *, jitter: float = 0.05, remove: int = 1, add: int = 1
) -> tuple[Scene, dict[str, str]]:
    """The disguised copy and the truth (original id -> copy id); see the module docstring."""
    objects = scene.placed_objects()
    supports = scene_supports(scene)
    standing = [o.id for o in objects if o.id not in supports]
    removed = (
        set(rng.choice(standing, size=min(remove, len(standing)), replace=False).tolist())
        if remove
        else set()
    )
    changed = True
    while changed:  # what stands on a removed object goes too
        grown = removed | {upper for upper, lower in supports.items() if lower in removed}
        changed, removed = grown != removed, grown
    offsets = {}
    for obj in objects:
        angle = rng.uniform(0.0, 2.0 * math.pi)
        offsets[obj.id] = (jitter * math.cos(angle), jitter * math.sin(angle))

    def offset(object_id: str) -> tuple[float, float]:
        while object_id in supports:  # moves with the object at the bottom of its stack
            object_id = supports[object_id]
        return offsets[object_id]

    names = {o.type: f"kind_{k}" for k, o in enumerate(sorted(objects, key=lambda o: o.type))}
    kept = [o for o in objects if o.id not in removed]
    truth = {o.id: f"thing_{k}" for k, o in enumerate(kept)}
    copies = []
    for obj in kept:
        dx, dz = offset(obj.id)
        copies.append(
            replace(
                obj,
                id=truth[obj.id],
                type=names[obj.type],
                noun=names[obj.type],
                shape=None,
                parent=None,
                position=[obj.position[0] + dx, obj.position[1], obj.position[2] + dz],
            )
        )
    for k in range(add):
        extra = _free_box(copies, scene.extent, rng, f"added_{k}")
        if extra is not None:
            copies.append(extra)
    order = rng.permutation(len(copies))
    copies = [replace(copies[i], order=position) for position, i in enumerate(order)]
    relations = [
        Relation(truth[upper], truth[lower], SUPPORT_LABEL, 0.0, True)
        for upper, lower in supports.items()
        if upper in truth and lower in truth
    ]
    return replace(scene, objects=copies, paths=[], relations=relations, derivation=[]), truth


def _free_box(
    objects: list[SceneObject], extent, rng: np.random.Generator, object_id: str
) -> SceneObject | None:
    """A box of random size on floor no other object's footprint touches, or None."""
    boxes = object_corners(objects)
    for _ in range(200):
        width, height, depth = rng.uniform(0.3, 1.2, size=3)
        x, z = (
            rng.uniform(-extent[0] / 2 + width, extent[0] / 2 - width),
            rng.uniform(-extent[1] / 2 + depth, extent[1] / 2 - depth),
        )
        candidate = SceneObject(
            object_id,
            "added",
            "object",
            "added",
            None,
            None,
            None,
            [float(x), 0.0, float(z)],
            float(rng.choice([0.0, math.pi / 2, math.pi, -math.pi / 2])),
            [float(width), float(height), float(depth)],
        )
        corners = object_corners([candidate])[0]
        if not any(_overlap(corners, other) for other in boxes):
            return candidate
    return None


def _overlap(first: np.ndarray, second: np.ndarray) -> bool:
    """Whether two convex footprints (4, 2) overlap (separating axis test)."""
    for corners in (first, second):
        for k in range(4):
            edge = corners[(k + 1) % 4] - corners[k]
            axis = np.array([-edge[1], edge[0]])
            a, b = first @ axis, second @ axis
            if a.max() <= b.min() or b.max() <= a.min():
                return False
    return True
