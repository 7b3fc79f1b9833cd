"""The scene graph of a completed room (step 3 of ``complete``): a ``SceneGraph`` of the
indoor catalog's entries with the relations a room's rules would state. What stands on
or at a piece (a lamp on a night table, night tables by the bed, chairs at a desk or
round a table) goes where the plans put it: its anchor and its side of it, and the
relations, come from the poses learned from the plans (``accessories``). Every other
piece stands the way most of its category's plan pieces stood (``stances``): in a row
with a piece of a category it stood in a row with (bookshelves side by side), before
one (a bench before the dumbbell rack; a rug or a mat lies before what it lay before
most often), in a corner, with its back against a wall, or free in the middle (a
table). The first piece of a category that stood under a window goes under one (a
desk); one that faced a piece turns to it (a sofa to the television stand, against its
wall), and one with no place by the room stands beside what it stood beside (an
armchair beside the coffee table, facing it) (``neighbours``). A piece the plans place
by none of these stands beside its strongest partner in the type's relation graph (the
weight ``W`` of the plan model), or against a wall. No rule is written per category.
"""

from __future__ import annotations

from dataclasses import replace

from scenewright.completion.plan_model import PlanModel
from scenewright.core.relations import RELATIONS
from scenewright.core.room import ROOM_NODE, Room
from scenewright.core.scene_graph import SceneGraph, SceneParams

from . import stances
from .accessories import Placement, assign, slot_relations, stands_on
from .contents import Contents

#: Why a category the selection chose is not in the room.
NOTHING_TO_STAND_ON = "nothing in the room it fits on"
NO_FLOOR = "no free floor for it at the start"


def build_graph(
    model: PlanModel, contents: Contents, room: Room, catalog, leave_out=()
) -> tuple[SceneGraph, dict[str, str], dict[str, Placement]]:
    """The scene graph of the room holding ``contents.counts`` but the categories in
    ``leave_out`` (``catalog``: the indoor catalog's entries by name), the categories
    left out with why (also a lamp or a television added with nothing in the room to
    stand on), and each accessory's ``accessories.Placement`` by node id (its anchor a node id
    too). Relations: see the module docstring, step 3."""
    params = SceneParams(name=contents.types[0], extent=room.extent, ground="floor", room=room)
    graph = SceneGraph(params=params)
    weights = relation_weights(model, contents.types)
    counts = {name: n for name, n in contents.counts.items() if name not in leave_out}
    dropped = {name: NO_FLOOR for name in leave_out}
    placements = assign(model, counts, catalog)
    for name in list(counts):
        # A requested one stays, on the floor by the room's other rules (a kept lamp).
        if stands_on(model, name) and (name, 0) not in placements and name not in contents.owners:
            dropped[name] = NOTHING_TO_STAND_ON
            del counts[name]
    placements = assign(model, counts, catalog)
    # Floor pieces first (anchors before what relates to them), then what stands on them.
    order = sorted(
        counts,
        key=lambda n: (
            stands_on(model, n),
            stances.base_stance(model, n) != stances.WALL,
            (n, 0) in placements,
            n,
        ),
    )
    made: dict[str, list[str]] = {}
    for name in order:
        made[name] = [graph.add_node(catalog[name], rule="Complete") for _ in range(counts[name])]
    windowed = {  # categories whose part of the room has a window to stand under
        name
        for name in counts
        if (
            contents.regions[contents.region_masks().owners[name]].room
            if contents.regions
            else room
        ).windows
    }
    cornerless = {  # categories whose region is a strip between virtual walls: no room corner in it
        name
        for name in counts
        if contents.regions
        and not contents.regions[contents.region_masks().owners[name]].has_room_corner(room)
    }
    followers = {name for name in counts if name in model.accessories}
    by_node: dict[str, Placement] = {}
    at_wall: set[str] = set()  # the pieces that stand against a wall
    # The pieces with no place of their own first, so an accessory knows whether its
    # anchor stands against a wall.
    for anchored in (False, True):
        for name in order:
            for index, node in enumerate(made[name]):
                placement = placements.get((name, index))
                if (placement is not None) != anchored:
                    continue
                if placement is None:
                    relations = _relations_of(
                        model,
                        name,
                        index,
                        made,
                        weights,
                        name in windowed,
                        followers,
                        name in cornerless,
                    )
                else:
                    anchor = made[placement.anchor][placement.anchor_index]
                    by_node[node] = replace(placement, anchor=anchor)
                    relations = [
                        (label, anchor if target is None else target)
                        for label, target in slot_relations(
                            placement, name, model, anchor in at_wall
                        )
                    ]
                for label, target in relations:
                    graph.add_relation(node, target, label)
                    if target == ROOM_NODE and RELATIONS[label].family == "wall":
                        at_wall.add(node)
    return graph, dropped, by_node


def relation_weights(model: PlanModel, types) -> dict[tuple[str, str], float]:
    """Pair (sorted) -> the strongest weight W any of the types gives it."""
    weights: dict[tuple[str, str], float] = {}
    for room_type in types:
        for pair in model.types[room_type].pairs:
            key = (pair.pair[0], pair.pair[1])
            weights[key] = max(weights.get(key, 0.0), pair.weight)
    return weights


def _relations_of(
    model: PlanModel,
    name: str,
    index: int,
    made: dict,
    weights: dict,
    windows: bool,
    followers: set,
    cornerless: bool = False,
) -> list[tuple[str, str]]:
    """The relations (label, target) of the ``index``-th piece of category ``name``,
    which has no place on or at another (``accessories.assign``), by its ``stances.stance``
    in the room and what it faces or stands beside; ``windows``:
    whether its part of the room has a window to stand under; ``followers``: the
    accessory categories, which no piece stands beside; ``cornerless``: whether the
    piece's part of the room has no corner of the room (a corner piece stands against a
    wall there instead)."""
    if index == 0 and windows and stances.under_window(model, name):
        return [("UnderWindow", ROOM_NODE)]  # the first one: a window is no row
    kind, by = stances.stance(model, name, made)
    if kind == stances.ROW:
        first = next((made[n][0] for n in by if made[n][0] != made[name][index]), None)
        if first is not None:
            return [
                ("NextToChooseSide", first),
                ("ImplicitAlignedWith", first),
                ("ImplicitAgainstWall", ROOM_NODE),
            ]
        kind = stances.base_stance(model, name)  # the first of its row stands by the room
    if kind == stances.BEFORE and stances.learned_stance(model, name).flat:
        anchor = made[by[0]][0] if by else _strongest_partner(model, name, made, weights, followers)
        return [("NextToFront", anchor), ("ImplicitFacingSameDirection", anchor)] if anchor else []
    if kind == stances.BEFORE:
        return [("NextToFront", made[by[0]][index % len(made[by[0]])])]
    faces = stances.facing_target(model, name, made)
    facing = [("FacingTowards", made[faces][0])] if faces is not None else []
    beside = stances.beside_target(model, name, made)
    if beside is not None:  # more stood beside it than where the room alone puts them
        return [("NextToChooseSide", made[beside][0]), *facing]
    if kind == stances.WALL:
        return [*facing, ("ImplicitAgainstWall" if facing else "AgainstWall", ROOM_NODE)]
    if kind == stances.FREE:
        return facing
    partner = _strongest_partner(model, name, made, weights, followers)
    if kind == stances.CORNER:
        return [("AgainstWall" if cornerless else "InCorner", ROOM_NODE)]
    if partner is None:
        return [("AgainstWall", ROOM_NODE)]
    return [("NextToChooseSide", partner)]


def _strongest_partner(
    model: PlanModel, name: str, made: dict, weights: dict, followers: set
) -> str | None:
    """The first piece of the floor category most strongly related to ``name`` (W > 0),
    accessories and rugs aside (one stands beside furniture, not beside a chair)."""
    best, best_weight = None, 0.0
    for other in sorted(made):
        flat = other in model.stances and model.stances[other].flat
        if other == name or other in followers or flat:
            continue
        weight = weights.get((min(name, other), max(name, other)), 0.0)
        if weight > best_weight:
            best, best_weight = made[other][0], weight
    return best
