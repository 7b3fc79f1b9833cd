"""Variations of example scenes: reshuffle through the Augmented Graph, lay out with
everything untouched pinned, keep what is compatible.

``vary(examples, count, seed)`` starts from each example in turn (variant k from
example k mod n) and applies one to ``max_operations`` operations (``operations``),
each drawn at random from those possible: replacing an object by another member of its
node, growing a node the variant lacks, transferring what a supporter carries. An
operation whose compatibility is at most ``KEEP`` (0.8, the paper's) is not applied; one
that would bring the variant's product K below ``STOP`` (0.2) ends it. After each
operation the variant is checked where the operation put the new objects
(``measure_layout``); when that is not ok (an overlap, a broken relation) it is laid
out again (``layout_scene``) with every object the operation did not touch pinned
(exactly where it was) and the new ones starting where the operation put them; an
operation whose layout is still not ok is undone, and within one ``vary`` the same
change on the same variant is not laid out again (``layout_key``): a failing layout
runs every chain to its patience, and a change the examples' matching makes impossible
(a second bed grown where the variant's bed stands, when the matching left the two beds
apart) comes up again in later variants of the same example. Variants that look like an example
or an earlier variant (``signature``) are dropped. Variants are ranked by K (then by the order they were made).

Deterministic: variant attempt k draws from the ``variation`` child stream k of the
seed, and its layouts from children of that stream.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from scenewright.core.errors import InputError
from scenewright.core.scene import Scene, assemble_scene
from scenewright.core.seeds import STAGE_KEYS, stream
from scenewright.examples import Example

from .augmented import AugmentedGraph, augment
from .operations import (
    Change,
    Variant,
    carried_by,
    grow_compatibility,
    grow_node,
    replace_object,
    transfer_items,
)

# The variation stage's spawn key (core.seeds: new stages take new numbers).
STAGE_KEYS.setdefault("variation", 4)

KEEP = 0.8
STOP = 0.2
#: Layouts tried per operation slot before the slot is given up.
TRIES = 3


@dataclass
class Result:
    """A finished variant: its scene, K, the operations and each object's source."""

    scene: Scene
    compatibility: float
    operations: list[dict]
    origin: dict[str, tuple[str, str]]  # object id -> (example name, object id)
    base: str
    attempt: int

    def synthesis(self) -> dict:
        """scene.json's ``synthesis`` record."""
        return {
            "base": self.base,
            "compatibility": round(self.compatibility, 6),
            "operations": self.operations,
            "sources": {
                object_id: {"example": name, "object": source}
                for object_id, (name, source) in self.origin.items()
            },
        }


def start_variant(example_index: int, example: Example) -> Variant:
    scene = replace(example.scene, description=None, render=None, timings={}, derivation=[])
    return Variant(scene, {o.id: (example_index, o.id) for o in scene.placed_objects()})


def proposals(variant: Variant, ag: AugmentedGraph) -> list[tuple]:
    """Every operation possible on the variant: (kind, argument, member)."""
    found: list[tuple] = []
    present = {variant.node_of(ag, object_id) for object_id in variant.objects()}
    for object_id, obj in variant.objects().items():
        node = ag.node(variant.node_of(ag, object_id))
        for member in node.members:
            if member == variant.origin[object_id]:
                continue
            if not node.supported and _looks(_source(ag, member)) != _looks(
                obj
            ):  # not a swap for an identical one
                found.append(("replace", object_id, member))
            if carried_by(ag.examples[member[0]].scene, member[1]):
                found.append(("transfer", object_id, member))
    for node in ag.layout_nodes():
        if node.id not in present:
            found += [("grow", node.id, member) for member in node.members]
    return found


def _source(ag: AugmentedGraph, member) -> object:
    return ag.examples[member[0]].scene.object(member[1])


def _looks(obj) -> tuple:
    return obj.type, obj.style, tuple(round(v, 3) for v in obj.size)


def propose(
    variant: Variant, ag: AugmentedGraph, kind: str, argument: str, member
) -> Change | None:
    if kind == "replace":
        return replace_object(variant, ag, argument, member)
    if kind == "grow":
        return grow_node(variant, ag, argument, member)
    return transfer_items(variant, ag, argument, member)


def layout_key(variant: Variant, change: Change) -> tuple:
    """What decides the layout ``apply_change`` asks for: the variant's room, objects and
    relations and the change's (exact reprs, so equal keys mean the same problem)."""
    scene = variant.scene
    return (
        repr(scene.room),
        tuple(scene.extent),
        tuple(map(repr, scene.objects)),
        tuple(map(repr, scene.paths)),
        tuple(map(repr, scene.relations)),
        tuple(change.removed),
        tuple(repr(obj) for obj, _ in change.added),
        tuple(map(repr, change.relations)),
    )


def apply_change(
    variant: Variant,
    ag: AugmentedGraph,
    change: Change,
    rng: np.random.Generator,
    *,
    unplaceable: set | None = None,
) -> Variant | None:
    """The variant with ``change`` applied and laid out (untouched objects pinned), or
    None when its layout is not ok or a grown object's compatibility is too low. A
    layout that is not ok adds the change's ``layout_key`` to ``unplaceable``."""
    from scenewright.generator.layout import layout_scene, measure_layout
    from scenewright.generator.layout.pinning import scene_layout

    removed = set(change.removed)
    added = {obj.id for obj, _ in change.added}
    objects = [o for o in variant.scene.objects if o.id not in removed] + [
        obj for obj, _ in change.added
    ]
    relations = [
        r for r in variant.scene.relations if r.source not in removed and r.target not in removed
    ]
    seen = {(r.source, r.target, r.label) for r in relations}
    relations += [r for r in change.relations if (r.source, r.target, r.label) not in seen]
    scene = replace(variant.scene, objects=objects, relations=relations)
    graph = scene.graph()
    poses, paths = scene_layout(scene)
    pinned = {object_id: pose for object_id, pose in poses.items() if object_id not in added}
    start = {object_id: poses[object_id] for object_id in added}
    layout = measure_layout(graph, poses, paths)  # where the operation put them may do as it is
    if not layout.ok:
        layout = layout_scene(graph, rng, pinned=pinned, pinned_paths=paths, start=start)
    if not layout.ok:
        if unplaceable is not None:
            unplaceable.add(layout_key(variant, change))
        return None
    laid = assemble_scene(graph, layout, rules=scene.rules, seed=scene.seed)
    laid = replace(laid, derivation=[], templates=scene.templates, version=scene.version)
    origin = {k: v for k, v in variant.origin.items() if k not in removed}
    origin.update({obj.id: member for obj, member in change.added})
    result = Variant(laid, origin, list(variant.operations), variant.compatibility)
    compatibility = change.compatibility
    if change.kind == "grow":
        compatibility = grow_compatibility(result, ag, change.added[0][1], change.added[0][0].id)
        if compatibility <= KEEP:
            return None
    result.operations.append({**change.record, "compatibility": round(compatibility, 6)})
    result.compatibility *= compatibility
    return result


def vary_one(
    variant: Variant,
    ag: AugmentedGraph,
    rng: np.random.Generator,
    max_operations: int,
    unplaceable: set | None = None,
) -> Variant:
    """Up to ``max_operations`` operations on ``variant`` (see the module docstring);
    changes in ``unplaceable`` (``layout_key``s whose layout failed) are passed over
    without counting as a try, and new failures join it."""
    unplaceable = set() if unplaceable is None else unplaceable
    wanted = int(rng.integers(1, max_operations + 1))
    for _ in range(wanted):
        options = proposals(variant, ag)
        order = rng.permutation(len(options))
        tries = 0
        for index in order:
            change = propose(variant, ag, *options[index])
            if change is None or (change.kind != "grow" and change.compatibility <= KEEP):
                continue
            if variant.compatibility * change.compatibility < STOP:
                return variant
            if layout_key(variant, change) in unplaceable:
                continue
            tries += 1
            done = apply_change(variant, ag, change, rng.spawn(1)[0], unplaceable=unplaceable)
            if done is not None:
                variant = done
                break
            if tries >= TRIES:
                break
        if variant.compatibility < STOP:
            break
    return variant


def signature(variant: Variant) -> tuple:
    """What makes two variants look the same: the same kinds of object (type, style,
    size to 1 cm) at the same places (5 cm, 0.1 rad), wherever they came from."""
    return tuple(
        sorted(
            (
                o.type,
                o.style or "",
                *(round(v / 0.01) for v in o.size),
                round(o.position[0] / 0.05),
                round(o.position[1] / 0.05),
                round(o.position[2] / 0.05),
                round(o.yaw / 0.1) % 63,
            )
            for o in variant.scene.placed_objects()
        )
    )


def vary(
    examples: list[Example],
    count: int,
    seed: int,
    *,
    max_operations: int = 3,
    ag: AugmentedGraph | None = None,
    attempts: int | None = None,
) -> list[Result]:
    """Up to ``count`` distinct variants of ``examples``, best K first. ``InputError``
    for fewer than two examples: every operation brings in what another example has."""
    if len(examples) < 2:
        raise InputError(
            f"varying needs at least 2 example scenes, got {len(examples)}: every operation brings in objects "
            "from another example"
        )
    ag = ag or augment(examples)
    seen = {signature(start_variant(k, e)) for k, e in enumerate(examples)}
    made: list[Result] = []
    unplaceable: set[tuple] = set()  # layout_keys of changes no layout was found for
    for attempt in range(attempts if attempts is not None else 6 * count):
        if len(made) >= count:
            break
        base = attempt % len(examples)
        rng = stream(seed, "variation", attempt)
        variant = vary_one(
            start_variant(base, examples[base]), ag, rng, max_operations, unplaceable
        )
        key = signature(variant)
        if not variant.operations or key in seen:
            continue
        seen.add(key)
        origin = {k: (examples[e].name, o) for k, (e, o) in variant.origin.items()}
        made.append(
            Result(
                variant.scene,
                variant.compatibility,
                variant.operations,
                origin,
                examples[base].name,
                attempt,
            )
        )
    return sorted(made, key=lambda r: (-r.compatibility, r.attempt))
