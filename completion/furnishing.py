"""The scene graph of a completed room (step 3 of ``complete``): a ``SceneGraph`` of the
indoor catalog's entries with the relations a room's rules would state. What stands on
or at a piece (a lamp on a night table, night tables by the bed, chairs at a desk or
round a table) goes where the plans put it: its anchor and its side of it, and the
relations, come from the poses learned from the plans (``accessories``). Big pieces
stand against a wall, a desk under the window; in a gym treadmills and bikes in a row
against a wall (console to it), a weight bench before the dumbbell rack, a mat before
the television or the rack. What a piece stands beside is its strongest partner in the
type's relation graph (the weight ``W`` of the plan model).
"""

from __future__ import annotations

from dataclasses import replace

from scenewright.completion.plan_model import PlanModel
from scenewright.core.relations import RELATIONS
from scenewright.core.room import ROOM_NODE, Room
from scenewright.core.scene_graph import SceneGraph, SceneParams

from .accessories import Placement, assign, slot_relations, stands_on
from .contents import Contents

#: Categories that stand with their back to a wall (when they have no place at another
#: piece). The rest stand by a partner (an armchair by the coffee table) or in a corner.
AGAINST_WALL = frozenset(
    {
        "bed",
        "wardrobe",
        "dresser",
        "bookshelf",
        "filing_cabinet",
        "tv_stand",
        "piano",
        "refrigerator",
        "kitchen_counter",
        "sofa",
        "desk",
        "treadmill",
        "exercise_bike",
        "rowing_machine",
        "dumbbell_rack",
    }
)
#: Pieces that stand in a row along a wall: beside the first piece of the first of their
#: categories in the room (not themselves), backs flush: bookshelves side by side,
#: treadmills and bikes in a row facing the same wall (the gyms' cardio rows).
ROWS = {
    "bookshelf": ("bookshelf",),
    "treadmill": ("treadmill",),
    "exercise_bike": ("treadmill", "exercise_bike"),
}
#: What a flat piece lies before, in order of preference: a rug before the bed, sofa or
#: table; an exercise mat before the television or the dumbbell rack.
FLAT_BEFORE = {
    "rug": ("bed", "sofa", "dining_table"),
    "exercise_mat": ("tv_stand", "dumbbell_rack"),
}
#: Free-standing pieces that stand before a piece against a wall (beyond its clearance):
#: a weight bench before the dumbbell rack.
STANDS_BEFORE = {"weight_bench": ("dumbbell_rack",)}
#: What others gather round: it stands free, the relations are theirs.
CENTRE_PIECES = frozenset({"dining_table", "coffee_table"})
#: Why a category the selection chose is not in the room.
NOTHING_TO_STAND_ON = "nothing in the room it fits on"
NO_FLOOR = "no free floor for it at the start"
#: Stand in a corner when nothing in the room is related to them (against a wall in a
#: split room's middle part, which holds no corner of the room).
CORNER_ITEMS = frozenset({"plant", "floor_lamp", "armchair"})


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
        key=lambda n: (stands_on(model, n), n not in AGAINST_WALL, (n, 0) in placements, n),
    )
    made: dict[str, list[str]] = {}
    for name in order:
        made[name] = [graph.add_node(catalog[name], rule="Complete") for _ in range(counts[name])]
    windows = bool(room.windows)
    if contents.regions and "desk" in counts:  # a desk goes under a window of its own region
        windows = bool(contents.regions[contents.region_masks().owners["desk"]].room.windows)
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
                        name, index, made, weights, windows, followers, name in cornerless
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
    name: str,
    index: int,
    made: dict,
    weights: dict,
    windows: bool,
    followers: set,
    cornerless: bool = False,
) -> list[tuple[str, str]]:
    """The relations (label, target) of the ``index``-th piece of category ``name``,
    which has no place on or at another (``accessories.assign``); ``windows``: whether
    the first desk has a window to stand under; ``followers``: the accessory categories,
    which no piece stands beside; ``cornerless``: whether the piece's part of the room
    has no corner of the room (a corner piece stands against a wall there instead)."""
    if name == "desk" and windows and index == 0:
        return [("UnderWindow", ROOM_NODE)]
    if name in ROWS:
        first = next(
            (made[n][0] for n in ROWS[name] if made.get(n) and made[n][0] != made[name][index]),
            None,
        )
        if first is not None:
            return [
                ("NextToChooseSide", first),
                ("ImplicitAlignedWith", first),
                ("ImplicitAgainstWall", ROOM_NODE),
            ]
    if name == "sofa" and made.get("tv_stand"):
        return [("FacingTowards", made["tv_stand"][0]), ("ImplicitAgainstWall", ROOM_NODE)]
    if name == "coffee_table" and made.get("sofa"):
        sofa = made["sofa"][0]
        return [("NextToFront", sofa), ("ImplicitAlignedWith", sofa)]
    if name in AGAINST_WALL:
        return [("AgainstWall", ROOM_NODE)]
    if name in CENTRE_PIECES:
        return []
    if name in FLAT_BEFORE:
        anchor = next((made[n][0] for n in FLAT_BEFORE[name] if made.get(n)), None)
        anchor = anchor or _strongest_partner(name, made, weights, followers)
        return [("NextToFront", anchor), ("ImplicitFacingSameDirection", anchor)] if anchor else []
    before = next(
        (made[n][index % len(made[n])] for n in STANDS_BEFORE.get(name, ()) if made.get(n)), None
    )
    if before is not None:
        return [("NextToFront", before)]
    partner = _strongest_partner(name, made, weights, followers)
    if name == "armchair" and made.get("coffee_table"):
        return [
            ("NextToChooseSide", made["coffee_table"][0]),
            ("FacingTowards", made["coffee_table"][0]),
        ]
    if name in CORNER_ITEMS or partner is None:
        return (
            [("InCorner", ROOM_NODE)]
            if name in CORNER_ITEMS and not cornerless
            else [("AgainstWall", ROOM_NODE)]
        )
    return [("NextToChooseSide", partner)]


def _strongest_partner(name: str, made: dict, weights: dict, followers: set) -> str | None:
    """The first piece of the floor category most strongly related to ``name`` (W > 0),
    accessories and rugs aside (one stands beside furniture, not beside a chair)."""
    best, best_weight = None, 0.0
    for other in sorted(made):
        if other == name or other in followers or other in FLAT_BEFORE:
            continue
        weight = weights.get((min(name, other), max(name, other)), 0.0)
        if weight > best_weight:
            best, best_weight = made[other][0], weight
    return best
