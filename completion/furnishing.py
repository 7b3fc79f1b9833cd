"""The scene graph of a completed room (step 3 of ``complete``): a ``SceneGraph`` of the
indoor catalog's entries with the relations a room's rules would state. Big pieces
stand against a wall, night tables either side of the bed, a desk under the window with
its chair before it, chairs round a table, small things on their supports; in a gym
treadmills and bikes in a row against a wall (console to it), a weight bench before the
dumbbell rack, a mat before the television or the rack. What a piece stands beside is
its strongest partner in the type's relation graph (the weight ``W`` of the plan model).
"""

from __future__ import annotations

from scenewright.completion.plan_model import PlanModel
from scenewright.core.room import ROOM_NODE, Room
from scenewright.core.scene_graph import SceneGraph, SceneParams

from .contents import Contents

#: What stands on what: a category that stands on another, with the supports it takes in
#: order of preference and the relation it uses. One with none of its supports in the
#: room is left out (and recorded as such).
SUPPORTS = {
    "lamp": (("nightstand", "dresser", "desk"), "OnTopOf"),
    "desk_lamp": (("desk",), "OnTopOfEdge"),
    "laptop": (("desk", "dining_table"), "OnTopOfMiddle"),
    "tv": (("tv_stand", "dresser"), "OnTopOfMiddle"),
    "book": (("bookshelf", "desk", "nightstand"), "OnTopOf"),
}
#: Categories that stand with their back to a wall. The rest stand by a partner (a chair
#: at its desk or table, an armchair by the coffee table) or in a corner.
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
#: Seats and what they are pulled up to, in order of preference.
SEAT_TARGETS = {"office_chair": ("desk", "dining_table"), "chair": ("dining_table", "desk")}
#: The sides of a table its chairs take in turn, each with how a chair there faces the
#: table: turned to its centre at the ends, square to it along the long sides (where two
#: chairs side by side cannot both point at the centre).
TABLE_SIDES = (
    ("NextToFront", "FacingOpposite"),
    ("NextToBehind", "FacingSameDirection"),
    ("NextToLeft", "FacingTowards"),
    ("NextToRight", "FacingTowards"),
)
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
) -> tuple[SceneGraph, dict[str, str]]:
    """The scene graph of the room holding ``contents.counts`` but the categories in
    ``leave_out`` (``catalog``: the indoor catalog's entries by name), and the categories
    left out with why (also a lamp or a television with nothing in the room to stand on).
    Relations: see the module docstring, step 3."""
    params = SceneParams(name=contents.types[0], extent=room.extent, ground="floor", room=room)
    graph = SceneGraph(params=params)
    weights = relation_weights(model, contents.types)
    counts = {name: n for name, n in contents.counts.items() if name not in leave_out}
    dropped = {name: NO_FLOOR for name in leave_out}
    supports = {}  # what stands on something -> the support categories present that it fits on
    for name in list(counts):
        if name in SUPPORTS:
            supports[name] = [
                s
                for s in SUPPORTS[name][0]
                if counts.get(s) and _fits_on(catalog[name], catalog[s])
            ]
            if not supports[name]:
                dropped[name] = NOTHING_TO_STAND_ON
                del counts[name]
    # Floor pieces first (anchors before what relates to them), then what stands on them.
    order = sorted(
        counts, key=lambda n: (n in SUPPORTS, n not in AGAINST_WALL, n in SEAT_TARGETS, n)
    )
    made: dict[str, list[str]] = {}
    for name in order:
        made[name] = [graph.add_node(catalog[name], rule="Complete") for _ in range(counts[name])]
    windows = bool(room.windows)
    if contents.regions and "desk" in counts:  # a desk goes under a window of its own region
        windows = bool(contents.regions[contents.mask.owners["desk"]].room.windows)
    cornerless = {  # categories whose region is a strip between virtual walls: no room corner in it
        name
        for name in counts
        if contents.regions
        and not contents.regions[contents.mask.owners[name]].has_room_corner(room)
    }
    for name in order:
        for index, node in enumerate(made[name]):
            for label, target in _relations_of(
                name, index, made, weights, windows, supports, name in cornerless
            ):
                graph.add_relation(node, target, label)
    return graph, dropped


def relation_weights(model: PlanModel, types) -> dict[tuple[str, str], float]:
    """Pair (sorted) -> the strongest weight W any of the types gives it."""
    weights: dict[tuple[str, str], float] = {}
    for room_type in types:
        for pair in model.types[room_type].pairs:
            key = tuple(pair.pair)
            weights[key] = max(weights.get(key, 0.0), pair.weight)
    return weights


def _fits_on(item, support) -> bool:
    """Whether ``item``'s footprint fits on ``support``'s top (a television wider than a
    dresser would hang off it)."""
    return item.size[0] <= support.size[0] + 1e-9 and item.size[2] <= support.size[2] + 1e-9


def _relations_of(
    name: str,
    index: int,
    made: dict,
    weights: dict,
    windows: bool,
    supports: dict,
    cornerless: bool = False,
) -> list[tuple[str, str]]:
    """The relations (label, target) of the ``index``-th piece of category ``name``;
    ``windows``: whether the first desk has a window to stand under; ``supports``: per
    category that stands on another, the support categories it fits on; ``cornerless``:
    whether the piece's part of the room has no corner of the room (a corner piece
    stands against a wall there instead)."""
    if name in SUPPORTS:
        label = SUPPORTS[name][1]
        holders = [node for support in supports[name] for node in made[support]]
        return [(label, holders[index % len(holders)])]
    if name == "nightstand" and made.get("bed"):
        bed = made["bed"][index // 2 % len(made["bed"])]
        side = "BesideLeft" if index % 2 == 0 else "BesideRight"
        return [(side, bed), ("ImplicitAlignedWith", bed), ("ImplicitAgainstWall", ROOM_NODE)]
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
    if name in SEAT_TARGETS:
        seat = _seat_relations(name, index, made)
        if seat:
            return seat
    if name in AGAINST_WALL:
        return [("AgainstWall", ROOM_NODE)]
    if name in CENTRE_PIECES:
        return []
    if name in FLAT_BEFORE:
        anchor = next((made[n][0] for n in FLAT_BEFORE[name] if made.get(n)), None)
        anchor = anchor or _strongest_partner(name, made, weights)
        return [("NextToFront", anchor), ("ImplicitFacingSameDirection", anchor)] if anchor else []
    before = next(
        (made[n][index % len(made[n])] for n in STANDS_BEFORE.get(name, ()) if made.get(n)), None
    )
    if before is not None:
        return [("NextToFront", before)]
    partner = _strongest_partner(name, made, weights)
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


def _seat_relations(name: str, index: int, made: dict) -> list[tuple[str, str]]:
    """A seat pulled up to its desk or table: the first office chair (or, without one,
    chair) at each desk, chairs round a dining table side by side in turn."""
    for target in SEAT_TARGETS[name]:
        tables = made.get(target, [])
        if not tables:
            continue
        if target == "desk":
            taken = len(made.get("office_chair", [])) if name == "chair" else 0
            if index + taken < len(tables):
                desk = tables[index + taken]
                return [("SeatedAt", desk)]
            continue
        table = tables[index % len(tables)]
        side, facing = TABLE_SIDES[index // len(tables) % len(TABLE_SIDES)]
        return [(side, table), (facing, table)]
    return []


def _strongest_partner(name: str, made: dict, weights: dict) -> str | None:
    """The first piece of the floor category most strongly related to ``name`` (W > 0),
    seats and rugs aside (one stands beside furniture, not beside a chair)."""
    best, best_weight = None, 0.0
    for other in sorted(made):
        if other == name or other in SUPPORTS or other in SEAT_TARGETS or other in FLAT_BEFORE:
            continue
        weight = weights.get((min(name, other), max(name, other)), 0.0)
        if weight > best_weight:
            best, best_weight = made[other][0], weight
    return best
