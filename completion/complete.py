"""Complete a room end to end: a request (an empty room and a few categories) -> a
furnished, laid-out scene (``scenewright complete``).

The steps, each a function here:

1. ``parse_request``: the room (``W x D`` or its corners, as the rules language takes
   them), its doors and windows (``WALL:OFFSET:WIDTH[:...]``) and the requested
   categories (``bed,bookshelf``, ``chair=4``) -> a ``Request`` holding a ``core.room.Room``.
2. ``choose_contents``: the room's type(s) (Equation 2, ``selection.choose_types``) and
   per type its categories (Algorithm 1, ``selection.explore_categories``) with the room's
   area shared among the types by their mean areas; the layout mask of the first type
   (Equation 4, ``layout_mask.amalgamated_mask``). A rectangular room of several types
   is split by virtual walls (``regions``): each type's categories and mask come from
   its own region, and the layout keeps its pieces there.
3. ``build_graph``: a ``SceneGraph`` of the indoor catalog's entries with relations a
   room's rules would state: big pieces against a wall, night tables
   either side of the bed, a desk under the window with its chair before it, chairs
   round a table, small things on their supports; in a gym treadmills and bikes in a
   row against a wall (console to it), a weight bench before the dumbbell rack, a mat
   before the television or the rack. What a piece stands beside is its
   strongest partner in the type's relation graph (the weight ``W`` of the plan model).
4. ``starting_poses``: the pieces that stand against a wall go, largest first, to the
   place along the walls whose footprint covers the most of the layout mask, clear of
   the door swings and of what is already placed. The mask is in the room's door-aware
   canonical frame; ``layout_mask.mask_at`` reads it at room positions.
5. ``complete``: the MCMC layout (``generator.layout.layout_scene``) from those poses,
   whose energy holds the walls, clearances, door swings and reachability, and the
   layout mask as a preference for the large pieces (``MASKED``; the energy's ``mask``
   part, ``generator.layout.mask_term``); the scene with its ``completion`` record
   (``completion_record``). While the layout is not ok, the room gives up one added
   piece (``fewer_pieces``: of the added categories its problems name, the one most
   weakly tied to the request) and is laid out again, at most ``FIT_ATTEMPTS`` times:
   Algorithm 1 weighs floor area, not whether the pieces fit round the door and each
   other, so a small room can be chosen more than it holds. A try after a failed one
   first starts one short chain where the failed layout left the remaining pieces
   (``WARM_PARAMS``) and lays the room out afresh only when that is not ok
   (``FIT_PARAMS``: its second chain waits 800 steps for progress).

The mask guides the start and, through its energy part, the chains: a large piece
costs more the less of the mask lies under it. It is a preference: the layout's
verdict does not read it, so it may cost a relation nothing and the chains still move
pieces off the mask where the relations ask for it. Everything is deterministic for
the seed: the selection and the starting poses draw nothing, the layout draws from the
seed's layout streams.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, replace

import numpy as np

from scenewright.core.errors import InputError, RoomError
from scenewright.core.geometry import corners, make_rect, rect_overlap, wrap_angle
from scenewright.core.limits import MAX_EXTENT
from scenewright.core.poses import Pose
from scenewright.core.room import ROOM_NODE, Room
from scenewright.core.scene_graph import SceneGraph, SceneParams
from scenewright.generator.layout.params import LayoutParams

#: Wall letters a door or window may name, besides the words and numbers ``Room.wall`` takes.
WALL_LETTERS = {"N": "north", "E": "east", "S": "south", "W": "west"}
#: A window's sill and height when the request does not give them (metres).
DEFAULT_SILL = 0.9
DEFAULT_WINDOW_HEIGHT = 1.2
#: The most of one category a request may ask for.
MAX_COUNT = 20
#: Starting poses: the step along a wall between candidate places (metres), the samples
#: per side of a footprint read from the mask, the gap kept to a wall.
WALL_STEP = 0.1
FOOTPRINT_SAMPLES = 5
WALL_GAP = 0.02

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
#: Per table side, the table-local (left, forward) directions along it and out of it.
SIDE_DIRECTIONS = {
    "NextToFront": ((1.0, 0.0), (0.0, 1.0)),
    "NextToBehind": ((1.0, 0.0), (0.0, -1.0)),
    "NextToLeft": ((0.0, 1.0), (1.0, 0.0)),
    "NextToRight": ((0.0, 1.0), (-1.0, 0.0)),
}
#: What others gather round: it stands free, the relations are theirs.
CENTRE_PIECES = frozenset({"dining_table", "coffee_table"})
#: Why a category the selection chose is not in the room.
NOTHING_TO_STAND_ON = "nothing in the room it fits on"
NO_FLOOR = "no free floor for it at the start"
#: Pieces at most this tall (metres) lie flat: a rug. The selection counts no floor for
#: them (plans lay rugs under furniture) but the layout keeps every piece apart, so one
#: the starting poses find no free floor for is left out rather than failing the layout.
FLAT = 0.02
#: Stand in a corner when nothing in the room is related to them (against a wall in a
#: split room's middle part, which holds no corner of the room).
CORNER_ITEMS = frozenset({"plant", "floor_lamp", "armchair"})
#: The large furniture the layout mask is for in the layout's energy: what stands
#: against a wall and the free-standing tables (the pieces whose starting poses the mask
#: chooses). Their accessories (night tables, chairs, lamps) follow them by relations,
#: as the paper places accessories after their large furniture.
MASKED = AGAINST_WALL | CENTRE_PIECES
#: Layouts tried with one added piece fewer each (``fewer_pieces``) while the layout is
#: not ok: a room the selection filled past what can be laid out gives up its weakest pieces.
FIT_ATTEMPTS = 4
#: Why a category the selection chose is not in the room: the layout failed with it.
#: The layout's parameters for each try: two chains (one restart), as most rooms are ok
#: on their first chain and one that fails twice is better off with a piece fewer. The
#: restart gives up after 800 steps without progress, not 1200: a restart that rescues a
#: try is mostly ok well within that, and 800 gives up as many pieces on the benchmark's
#: 50 random rooms as 1200 did (11), 600 two more (``benchmarks/bench_complete.py --random 50``).
FIT_PARAMS = LayoutParams(restarts=1, restart_patience=800)
#: A try after a failed one first runs one chain from the failed layout's poses (the
#: pieces still in the room where they stood; a warm start), which gives up after
#: ``patience`` steps without progress: the piece given up mostly was what kept the rest
#: from fitting, so the chain is often ok at once (on the benchmark's 50 random rooms 4
#: of 9 warm tries, in 50-150 steps; 5 of 9 when they waited 400 steps, the fifth after
#: 250, for the same pieces given up). Only when it is not does the try lay the room
#: out afresh with ``FIT_PARAMS``.
WARM_PARAMS = LayoutParams(restarts=0, patience=200)
ROOM_FULL = "no room for it with the rest: the layout failed with it"


@dataclass(frozen=True)
class Request:
    """What the user asked for: the empty ``room`` and ``requested`` category -> count."""

    room: Room
    requested: dict[str, int]


# -- 1. the request -----------------------------------------------------------------


def parse_room(text: str) -> Room:
    """``W x D`` (``5x4``) or corners ``x,z x,z ...`` (at least three) -> a Room."""
    spec = text.strip()
    size = re.fullmatch(r"([0-9.]+)\s*[xX]\s*([0-9.]+)", spec)
    try:
        if size:
            width, depth = (_number(part, "room side") for part in size.groups())
            if not (0.5 <= width <= MAX_EXTENT and 0.5 <= depth <= MAX_EXTENT):
                raise InputError(
                    f"room {spec!r}: each side must lie between 0.5 and {MAX_EXTENT:g} m"
                )
            return Room.rectangle(width, depth)
        corners = []
        for point in spec.replace(";", " ").split():
            parts = point.strip("()").split(",")
            if len(parts) != 2:
                raise InputError(
                    f"room {spec!r}: give W x D (5x4) or corners x,z x,z x,z ... ({point!r} is neither)"
                )
            corners.append(tuple(_number(part, "room corner") for part in parts))
        if any(abs(v) > MAX_EXTENT for corner in corners for v in corner):
            raise InputError(f"room {spec!r}: a corner lies further than {MAX_EXTENT:g} m out")
        return Room.polygon(corners)
    except RoomError as problem:
        raise InputError(f"room {spec!r}: {problem}") from None


def add_opening(room: Room, kind: str, text: str) -> Room:
    """``room`` with the door ``WALL:OFFSET:WIDTH[:HEIGHT]`` or the window
    ``WALL:OFFSET:WIDTH[:SILL[:HEIGHT]]``; WALL is N, E, S, W, a side word or a wall number,
    OFFSET the centre's distance from the wall's start (its west or north end for a
    rectangle's walls, as in a rules file)."""
    parts = text.split(":")
    most = 4 if kind == "door" else 5
    if not 3 <= len(parts) <= most:
        form = (
            "WALL:OFFSET:WIDTH[:HEIGHT]" if kind == "door" else "WALL:OFFSET:WIDTH[:SILL[:HEIGHT]]"
        )
        raise InputError(
            f"{kind} {text!r}: give {form}, e.g. {'S:0.8:0.9' if kind == 'door' else 'N:2.5:1.4'}"
        )
    wall_name = WALL_LETTERS.get(parts[0].strip().upper(), parts[0].strip().lower())
    wall = room.wall(wall_name)
    if wall is None:
        sides = ", ".join(dict.fromkeys(w.side for w in room.walls))
        raise InputError(
            f"{kind} {text!r}: the room has no wall {parts[0]!r} (sides: {sides}; or 1 to {len(room.walls)})"
        )
    numbers = [_number(part, f"{kind} {text!r}") for part in parts[1:]]
    offset, width = numbers[0], numbers[1]
    if kind == "door":
        arguments = dict(height=numbers[2] if len(numbers) > 2 else None)
    else:
        sill = numbers[2] if len(numbers) > 2 else DEFAULT_SILL
        arguments = dict(
            sill=sill, height=numbers[3] if len(numbers) > 3 else DEFAULT_WINDOW_HEIGHT
        )
    try:
        return room.with_opening(kind, wall.id, offset, width, **arguments)
    except RoomError as problem:
        raise InputError(f"{kind} {text!r}: {problem}") from None


def parse_categories(texts: list[str], known) -> dict[str, int]:
    """``["bed,bookshelf", "chair=4"]`` -> ``{"bed": 1, "bookshelf": 1, "chair": 4}``; each
    name must be in ``known`` (the indoor catalog)."""
    requested: dict[str, int] = {}
    for text in texts:
        for item in (part.strip() for part in text.split(",")):
            if not item:
                continue
            name, _, count_text = item.partition("=")
            name = name.strip()
            if name not in known:
                from difflib import get_close_matches

                close = get_close_matches(name, sorted(known), n=1)
                hint = f"; did you mean {close[0]!r}?" if close else ""
                raise InputError(f"--with {item!r}: {name!r} is not an indoor catalog entry{hint}")
            count = 1
            if count_text:
                if not count_text.strip().isdigit() or not 1 <= int(count_text) <= MAX_COUNT:
                    raise InputError(
                        f"--with {item!r}: the count must be a whole number from 1 to {MAX_COUNT}"
                    )
                count = int(count_text)
            requested[name] = requested.get(name, 0) + count
    if not requested:
        raise InputError("--with names no category: ask for at least one (--with bed,bookshelf)")
    return requested


def parse_request(
    room: str, doors: list[str], windows: list[str], categories: list[str], known
) -> Request:
    """The request the command line states (see the functions above for each part)."""
    built = parse_room(room)
    for text in doors:
        built = add_opening(built, "door", text)
    for text in windows:
        built = add_opening(built, "window", text)
    return Request(built, parse_categories(categories, known))


def _number(text: str, what: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise InputError(f"{what}: {text.strip()!r} is not a number") from None
    if not math.isfinite(value):
        raise InputError(f"{what}: {text.strip()!r} is not a finite number")
    return value


# -- 2. what the room holds -----------------------------------------------------------


@dataclass(frozen=True)
class Contents:
    """The room's types, per type Algorithm 1's answer, the merged counts (category ->
    number, requested first) and the layout mask: the first type's ``LayoutMask`` over
    the whole room, or, for a room split by virtual walls (``regions``, one per type),
    a ``layout_mask.RegionMasks``."""

    types: tuple[str, ...]
    owners: dict[str, str]
    explorations: dict
    counts: dict[str, int]
    mask: object
    regions: tuple = ()


def choose_contents(model: dict, request: Request, *, split: bool = True) -> Contents:
    """Equation 2, then Algorithm 1 per type, then Equation 4. One type, or a room
    that is not split (``split`` False, or not a rectangle): the room's area is shared
    among the types by their mean areas, and the mask is the first (largest) type's
    over the whole room. Several types in a rectangle: the room is split by virtual
    walls (``regions.split_room``) and each type's categories and mask are those of
    its own region, as a room of its own."""
    from scenewright.completion.features import room_parts
    from scenewright.completion.layout_mask import RegionMasks, amalgamated_mask
    from scenewright.completion.regions import split_room
    from scenewright.completion.selection import check_counts, choose_types, explore_categories

    room = request.room
    choice = choose_types(
        model, request.requested, room.area
    )  # first: it names a category no plan has
    check_counts(model, request.requested)
    regions = split_room(model, room, choice.types) if split else ()
    region_of = {region.room_type: k for k, region in enumerate(regions)}
    total = sum(model["types"][t]["mean_area"] for t in choice.types)
    explorations = {}
    counts: dict[str, int] = dict(sorted(request.requested.items()))
    for room_type in choice.types:
        owned = {
            name: n for name, n in request.requested.items() if choice.owners[name] == room_type
        }
        if regions:
            part = regions[region_of[room_type]].room
            share, parts = part.area, room_parts(part, model["types"][room_type]["mean_area"])
        else:
            share = room.area * model["types"][room_type]["mean_area"] / total
            parts = room_parts(room, model["types"][room_type]["mean_area"])
        exploration = explore_categories(model, room_type, owned, share, parts)
        explorations[room_type] = exploration
        for name, n in exploration.counts.items():
            if name not in request.requested:
                counts[name] = max(counts.get(name, 0), n)
    if not regions:
        mask = amalgamated_mask(model, choice.types[0], room, counts)
        return Contents(choice.types, choice.owners, explorations, counts, mask)
    owners = category_owners(model, choice.types, choice.owners, explorations, counts)
    masks = tuple(
        amalgamated_mask(
            model,
            region.room_type,
            region.room,
            {name: n for name, n in counts.items() if owners[name] == region.room_type},
        )
        for region in regions
    )
    mask = RegionMasks(regions, masks, {name: region_of[owner] for name, owner in owners.items()})
    return Contents(choice.types, choice.owners, explorations, counts, mask, regions)


def category_owners(
    model: dict, types, requested_owners: dict, explorations: dict, counts
) -> dict[str, str]:
    """Category -> the type (region) it belongs to: a requested one its Equation 2
    owner (``requested_owners``); an added one the type, of those whose Algorithm 1
    chose it, that has it most often (the paper's rule for requested categories,
    ``max P(o | s)``); ties: the earlier of ``types``."""
    owners = {}
    for name in counts:
        if name in requested_owners:
            owners[name] = requested_owners[name]
            continue
        choosers = [t for t in types if name in explorations[t].counts] or list(types)
        owners[name] = max(
            choosers,
            key=lambda t: (
                model["types"][t]["categories"].get(name, {}).get("p", 0.0),
                -list(types).index(t),
            ),
        )
    return owners


def region_boxes(
    types: dict[str, str], relations, owners: dict[str, int], count: int
) -> list[list[str]]:
    """Per region (``count`` of them) the ids of the floor pieces that belong there,
    from the pieces' categories (``types``: id -> category), the ``relations`` (source,
    target) between them and the region of each category (``owners``). A large piece
    (``MASKED``) belongs to its category's region; any other follows the piece its first
    relation to another piece names, up to a large one (a night table stays by its bed,
    a chair at its table, wherever their categories' types would put them); one with no
    such relation goes by its own category. Pieces that stand on others belong nowhere:
    they go with their support."""
    anchor: dict[str, str] = {}
    for source, target in relations:
        if (
            source in types
            and target in types
            and source not in anchor
            and types[source] not in MASKED
        ):
            anchor[source] = target
    out: list[list[str]] = [[] for _ in range(count)]
    for box, category in types.items():
        if category in SUPPORTS:
            continue
        root, seen = box, {box}
        while types[root] not in MASKED and root in anchor and anchor[root] not in seen:
            root = anchor[root]
            seen.add(root)
        out[owners[types[root]]].append(box)
    return out


# -- 3. the scene graph ------------------------------------------------------------------


def build_graph(
    model: dict, contents: Contents, room: Room, catalog, leave_out=()
) -> tuple[SceneGraph, dict[str, str]]:
    """The scene graph of the room holding ``contents.counts`` but the categories in
    ``leave_out`` (``catalog``: the indoor catalog's entries by name), and the categories
    left out with why (also a lamp or a television with nothing in the room to stand on).
    Relations: see the module docstring, step 3."""
    params = SceneParams(name=contents.types[0], extent=room.extent, ground="floor", room=room)
    graph = SceneGraph(params=params)
    weights = _relation_weights(model, contents.types)
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


def _relation_weights(model: dict, types) -> dict[tuple[str, str], float]:
    """Pair (sorted) -> the strongest weight W any of the types gives it."""
    weights: dict[tuple[str, str], float] = {}
    for room_type in types:
        for pair in model["types"][room_type]["pairs"]:
            key = tuple(pair["pair"])
            weights[key] = max(weights.get(key, 0.0), pair["weight"])
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
        side = "NextToLeft" if index % 2 == 0 else "NextToRight"
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
                return [("NextToFront", desk), ("FacingTowards", desk)]
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


# -- 4. starting poses ------------------------------------------------------------------------


def starting_poses(graph: SceneGraph, room: Room, mask) -> dict[str, Pose]:
    """Poses for the pieces that stand against a wall (``AgainstWall``, ``UnderWindow``
    to the room), those under a window first, then the largest first: each at the place along the walls whose footprint
    covers most of the layout ``mask`` and whose footprint and clearance are clear of the
    door swings, the room's outline and the pieces already placed. Under a window a
    piece goes to the window's middle. What flanks a piece along its wall (night tables
    ``NextToLeft``/``NextToRight`` of the bed) is placed with it, one unit."""
    from scenewright.completion.layout_mask import mask_values

    wall_of = {
        r.source: r.label
        for r in graph.edges()
        if r.target == ROOM_NODE and r.label in ("AgainstWall", "UnderWindow")
    }
    flanks: dict[
        str, list[tuple[str, float]]
    ] = {}  # piece -> (flanking piece, side: -1 left, +1 right)
    for relation in graph.edges():
        if relation.label in ("NextToLeft", "NextToRight") and relation.target in wall_of:
            flanks.setdefault(relation.target, []).append(
                (relation.source, -1.0 if relation.label == "NextToLeft" else 1.0)
            )
    # Pieces under a window first: they have one place each; then the largest first.
    nodes = sorted(
        (graph.node(n) for n in wall_of),
        key=lambda n: (wall_of[n.id] != "UnderWindow", -n.size[0] * n.size[2], n.order),
    )
    swings = [_bounding_rect(room.swing_zone(door)) for door in room.doors]
    placed: dict[str, object] = {}  # piece -> its footprint with its front clearance
    poses: dict[str, Pose] = {}
    grid = (np.arange(FOOTPRINT_SAMPLES) + 0.5) / FOOTPRINT_SAMPLES - 0.5
    for node in nodes:
        width, _, depth = node.size
        sides = [(graph.node(other), side) for other, side in flanks.get(node.id, [])]
        left = sum(other.size[0] for other, side in sides if side < 0)
        unit = width + left + sum(other.size[0] for other, side in sides if side > 0)
        reach = depth + dict(node.clearance).get("front", 0.0)
        local = np.array([(a * width, b * depth) for a in grid for b in grid])  # (samples^2, 2)
        others = swings + list(placed.values())
        fitting, points = (
            [],
            [],
        )  # the places clear of the walls and the rest; their footprints' samples
        for wall, u in _wall_places(room, unit, wall_of[node.id] == "UnderWindow"):
            middle = u - unit / 2.0 + left + width / 2.0  # the piece's own centre along the wall
            cx, cz = wall.to_world(u, reach / 2.0 + WALL_GAP)
            rect = make_rect(cx, cz, unit, reach, wall.facing_yaw)
            if room.footprint_excess(corners(rect)) > 1e-6:
                continue
            if any(rect_overlap(rect, other) > 1e-6 for other in others):
                continue
            x, z = wall.to_world(middle, depth / 2.0 + WALL_GAP)
            c, s = math.cos(wall.facing_yaw), math.sin(wall.facing_yaw)
            points.append(
                np.column_stack(
                    [x + local[:, 0] * c + local[:, 1] * s, z - local[:, 0] * s + local[:, 1] * c]
                )
            )
            fitting.append((rect, wall, middle))
        # One read of the mask for every place (elementwise, so each place's values are
        # those a read of its own gives); the first place of the highest mean wins.
        values = mask_values(mask, room, node.type, np.concatenate(points)) if points else ()
        best = None
        for k, (rect, wall, middle) in enumerate(fitting):
            score = float(np.mean(values[k * len(local) : (k + 1) * len(local)]))
            if best is None or score > best[0] + 1e-12:
                best = (score, rect, wall, middle)
        if best is None:
            continue  # no place along the walls: the layout's constructive placement finds one
        _, rect, wall, middle = best
        placed[node.id] = rect
        poses[node.id] = _against(wall, middle, depth)
        for other, side in sides:
            # The piece's local left is the wall's -u when it faces into the room.
            offset = (width + other.size[0]) / 2.0 + WALL_GAP
            poses[other.id] = _against(wall, middle - side * offset, other.size[2])
    _start_tables(graph, room, mask, poses, placed, swings)
    _start_in_front(graph, room, poses, placed, swings)
    return poses


def _start_tables(
    graph: SceneGraph, room: Room, mask, poses: dict, placed: dict, swings: list
) -> None:
    """Start a free-standing table (``CENTRE_PIECES`` with no relation of its own) where
    it and a ring of its chairs' depth round it cover most of the mask, inside the room
    and clear of the rest, and its chairs spread evenly along the sides they sit at,
    facing it."""
    from scenewright.completion.layout_mask import mask_values

    sources = {r.source for r in graph.edges()}
    for table in graph.nodes("object"):
        if table.type not in CENTRE_PIECES or table.id in sources or table.id in poses:
            continue
        seats = [
            (r.source, r.label)
            for r in graph.edges()
            if r.target == table.id
            and r.label in SIDE_DIRECTIONS
            and graph.node(r.source).type in SEAT_TARGETS
        ]
        ring = max((graph.node(seat).size[2] for seat, _ in seats), default=0.3) + 2 * WALL_GAP
        width, _, depth = table.size
        xs, zs = (np.array([c[i] for c in room.corners]) for i in (0, 1))
        grid = [
            (x, z)
            for x in np.arange(xs.min(), xs.max(), WALL_STEP)
            for z in np.arange(zs.min(), zs.max(), WALL_STEP)
        ]
        if not grid:
            continue
        scores = mask_values(mask, room, table.type, np.array(grid))
        # Both turns at every grid point, best mask value first (ties in grid order): the
        # first that fits is the best place, found without testing the whole grid.
        order = np.lexsort((np.arange(2 * len(grid)), -np.concatenate([scores, scores])))
        best = None
        for k in order:
            (x, z), yaw = grid[k % len(grid)], (0.0, math.pi / 2.0)[k // len(grid)]
            rect = make_rect(x, z, width + 2 * ring, depth + 2 * ring, yaw)
            if room.footprint_excess(corners(rect)) > 1e-6:
                continue
            if any(rect_overlap(rect, other) > 1e-6 for other in swings + list(placed.values())):
                continue
            best = (rect, float(x), float(z), yaw)
            break
        if best is None:
            continue
        rect, x, z, yaw = best
        placed[table.id] = rect
        poses[table.id] = Pose(x, 0.0, z, yaw)
        c, s = math.cos(yaw), math.sin(yaw)
        for label, (along, out) in SIDE_DIRECTIONS.items():
            here = [seat for seat, side in seats if side == label]
            span = width if out[1] else depth  # chairs at the front or back spread along the width
            for k, seat in enumerate(here):
                chair = graph.node(seat)
                shift = ((k + 0.5) / len(here) - 0.5) * span
                reach = (depth if out[1] else width) / 2.0 + chair.size[2] / 2.0 + WALL_GAP
                lx, lz = along[0] * shift + out[0] * reach, along[1] * shift + out[1] * reach
                wx, wz = x + lx * c + lz * s, z - lx * s + lz * c  # local (left, forward) -> world
                poses[seat] = Pose(float(wx), 0.0, float(wz), float(math.atan2(x - wx, z - wz)))


def _start_in_front(graph: SceneGraph, room: Room, poses: dict, placed: dict, swings: list) -> None:
    """Start what stands ``NextToFront`` of a started piece (a chair at its desk, a rug
    before the bed, a coffee table before the sofa) just in front of it, turned to it
    when it also faces it, where that is inside the room and clear of the door
    ``swings`` and the ``placed`` pieces' footprints and clearances (but its own
    piece's: a chair stands in the space kept free before its desk)."""
    from scenewright.completion.activity import SEATS

    facing = {(r.source, r.target) for r in graph.edges("FacingTowards")}
    for relation in graph.edges("NextToFront"):
        anchor = poses.get(relation.target)
        if anchor is None or relation.source in poses:
            continue
        node, target = graph.node(relation.source), graph.node(relation.target)
        reach = (target.size[2] + node.size[2]) / 2.0 + WALL_GAP
        if (
            node.type not in SEATS and node.size[1] > FLAT
        ):  # a seat or a rug may stand in the clearance
            reach += dict(target.clearance).get("front", 0.0)
        x, z = anchor.x + reach * math.sin(anchor.yaw), anchor.z + reach * math.cos(anchor.yaw)
        yaw = anchor.yaw + math.pi if (node.id, target.id) in facing else anchor.yaw
        rect = make_rect(x, z, node.size[0], node.size[2], yaw)
        others = swings + [other for key, other in placed.items() if key != target.id]
        if room.footprint_excess(corners(rect)) > 1e-6 or any(
            rect_overlap(rect, other) > 1e-6 for other in others
        ):
            continue
        placed[node.id] = rect
        poses[node.id] = Pose(float(x), 0.0, float(z), float(wrap_angle(yaw)))


def _against(wall, u: float, depth: float) -> Pose:
    """The pose of a piece ``depth`` deep with its back to ``wall`` at ``u`` along it."""
    x, z = wall.to_world(u, depth / 2.0 + WALL_GAP)
    return Pose(float(x), 0.0, float(z), float(wall.facing_yaw))


def _wall_places(room: Room, width: float, under_window: bool):
    """(wall, u) candidates: the middles of the windows, or every ``WALL_STEP`` along
    every wall where a piece ``width`` wide fits."""
    if under_window:
        for window in room.windows:
            yield room.part(window.wall), window.offset
        return
    for wall in room.walls:
        steps = int((wall.length - width) / WALL_STEP)
        for k in range(steps + 1):
            yield wall, width / 2.0 + k * WALL_STEP


def _bounding_rect(points):

    xs, zs = [p[0] for p in points], [p[1] for p in points]
    return make_rect(
        (min(xs) + max(xs)) / 2, (min(zs) + max(zs)) / 2, max(xs) - min(xs), max(zs) - min(zs), 0.0
    )


# -- 5. fitting the contents to the room ------------------------------------------------------


def _graph_and_start(model: dict, contents: Contents, room: Room, catalog):
    """The scene graph of ``contents``, the categories left out with why, and the
    starting poses; a rug the starting poses find no free floor for is left out."""
    graph, dropped = build_graph(model, contents, room, catalog)
    start = starting_poses(graph, room, contents.mask)
    unplaced = sorted(
        {
            n.type
            for n in graph.nodes("object")
            if n.size[1] <= FLAT and n.type not in SUPPORTS and n.id not in start
        }
    )
    if unplaced:
        before = graph
        graph, dropped = build_graph(model, contents, room, catalog, leave_out=unplaced)
        kept = {n.id for n in graph.nodes("object")}
        gone = {n.id for n in before.nodes("object")} - kept
        # A piece with no starting pose took no place another's start depends on: when
        # the rest of the graph is the same, the rest's starts are too.
        if [
            r for r in before.edges() if r.source not in gone and r.target not in gone
        ] == graph.edges():
            start = {box: pose for box, pose in start.items() if box in kept}
        else:
            start = starting_poses(graph, room, contents.mask)
    return graph, dropped, start


def fewer_pieces(
    model: dict, contents: Contents, request: Request, graph: SceneGraph, problems
) -> Contents | None:
    """``contents`` with one added piece fewer after a layout with ``problems`` (its
    report's lines): of the added categories whose pieces the problems name (all added
    ones when they name none), the one most weakly tied to the requested categories
    (summed relation weight ``W``; then the larger footprint, then the name) loses one
    piece, or the whole category at its last. None when nothing was added. Requested
    categories keep their counts: the request is what the room must hold."""
    added = [name for name in contents.counts if name not in request.requested]
    if not added:
        return None
    types = {node.id: node.type for node in graph.nodes("object")}
    named = {
        types[word]
        for line in problems
        for word in re.findall(r"[A-Za-z0-9_]+", line)
        if word in types
    }
    candidates = [name for name in added if name in named] or added
    weights = _relation_weights(model, contents.types)
    sizes = {node.type: node.size[0] * node.size[2] for node in graph.nodes("object")}

    def tie(name: str) -> float:
        return sum(
            weights.get((min(name, r), max(name, r)), 0.0) for r in request.requested if r != name
        )

    weakest = min(candidates, key=lambda name: (tie(name), -sizes.get(name, 0.0), name))
    counts = dict(contents.counts)
    counts[weakest] -= 1
    if not counts[weakest]:
        del counts[weakest]
        # A seat added for the piece just left out goes with it (what stood on it
        # ``build_graph`` leaves out by itself).
        for seat, targets in SEAT_TARGETS.items():
            if seat in added and weakest in targets and not any(counts.get(t) for t in targets):
                counts.pop(seat, None)
    return replace(contents, counts=counts)


# -- 6. the whole -------------------------------------------------------------------------------


def completion_record(
    contents: Contents, dropped, model: dict, masked=(), given_up=None, by_region=()
) -> dict:
    """What scene.json's ``completion`` holds: the types, per type the categories
    Algorithm 1 chose (requested or added, with their count, P(category | type) and the
    summed relation weight to the requested ones), its cost and reference plans, and the
    layout mask's reference plans with their weights and the pieces ``masked`` in the
    layout's energy; ``given_up``: category -> pieces of it the room gave up to be laid
    out (``fewer_pieces``; a category given up whole is also in ``left_out``). A room
    split by virtual walls also has ``regions`` (per region its type, rectangle, whether
    its door is virtual, its layout mask and the pieces that belong there, ``by_region``)
    and ``virtual_walls``; its ``mask`` is the first region's."""
    types = {}
    for room_type, exploration in contents.explorations.items():
        entry = model["types"][room_type]
        weights = {tuple(pair["pair"]): pair["weight"] for pair in entry["pairs"]}
        requested = [n for n, owner in contents.owners.items() if owner == room_type]
        types[room_type] = {
            "categories": [
                {
                    "category": name,
                    "count": count,
                    "requested": name in requested,
                    "p": entry["categories"].get(name, {}).get("p", 0.0),
                    "weight_to_requested": sum(
                        weights.get((min(name, r), max(name, r)), 0.0)
                        for r in requested
                        if r != name
                    ),
                }
                for name, count in exploration.counts.items()
            ],
            "cost": exploration.cost,
            "references": list(exploration.references),
        }
    record = {
        "types": list(contents.types),
        "owners": dict(sorted(contents.owners.items())),
        "selection": types,
        "counts": {name: n for name, n in contents.counts.items() if name not in dropped},
        "left_out": dict(sorted(dropped.items())),
        "given_up": dict(sorted((given_up or {}).items())),
    }
    if not contents.regions:
        record["mask"] = _mask_record(contents.types[0], contents.mask, masked)
        return record
    from scenewright.completion.regions import virtual_walls

    regions = []
    for k, (region, layout) in enumerate(zip(contents.regions, contents.mask.masks, strict=False)):
        pieces = list(by_region[k]) if by_region else []
        entry = {
            **region.to_dict(),
            **_mask_record(region.room_type, layout, [b for b in pieces if b in masked]),
        }
        entry["pieces"] = pieces
        entry["categories"] = sorted(
            name for name, k_ in contents.mask.owners.items() if k_ == k and name not in dropped
        )
        regions.append(entry)
    record["mask"] = {
        key: regions[0][key] for key in ("type", "frame", "references", "cells", "boxes", "bounds")
    }
    record["regions"] = regions
    record["virtual_walls"] = [[list(a), list(b)] for a, b in virtual_walls(contents.regions)]
    return record


def _mask_record(room_type: str, layout, boxes) -> dict:
    return {
        "type": room_type,
        "frame": layout.frame.to_dict(),
        "references": dict(sorted(layout.weights.items())),
        "cells": np.round(layout.mask, 6).tolist(),
        "boxes": list(boxes),
    }


def complete(
    request: Request,
    seed: int,
    *,
    plans=None,
    model: dict | None = None,
    catalog=None,
    mask_term: bool = True,
    split: bool = True,
    keep=None,
):
    """The completed room as a ``Scene`` (laid out, not yet described): ``plans`` is a
    plan set folder (default: the shipped one), or give a built ``model``. A layout that
    could not satisfy everything comes back with ``scene.layout.ok`` false.
    ``mask_term=False`` leaves the mask out of the layout's energy (it then only
    chooses the starting poses), for comparison; ``split=False`` keeps a room of
    several types whole, with the first type's mask (no virtual walls), likewise.
    ``keep``: a furnished room (a ``Scene``) being completed (``existing_request``):
    what it holds is pinned where it stands (``pin_existing``) and the room is not split
    (its pieces stand where they stand, whatever part a split would give them)."""
    import time

    from scenewright.api import timed
    from scenewright.completion import shipped_plans_dir
    from scenewright.completion.layout_mask import floor_mask, region_floor_masks
    from scenewright.completion.model import build_model
    from scenewright.completion.plan import load_plans
    from scenewright.core.scene import assemble_scene
    from scenewright.core.seeds import check_seed
    from scenewright.generator import indoor_catalog
    from scenewright.generator.layout import layout_scene

    seed = check_seed(seed)
    timings: dict[str, float] = {}
    with timed(timings, "complete"):
        model = model or build_model(load_plans(plans or shipped_plans_dir()))
        catalog = catalog or indoor_catalog()
        contents = choose_contents(model, request, split=split and keep is None)
    chosen = dict(contents.counts)
    failed = None  # the last failed try's poses (box id -> Pose), where the next try starts first
    for attempt in range(1 + FIT_ATTEMPTS):
        with timed(timings, "complete"):
            graph, dropped, start = _graph_and_start(model, contents, request.room, catalog)
        masked = [n.id for n in graph.nodes("object") if n.type in MASKED] if mask_term else []
        if contents.regions:
            by_region = region_boxes(
                {n.id: n.type for n in graph.nodes("object")},
                [(r.source, r.target) for r in graph.edges()],
                contents.mask.owners,
                len(contents.regions),
            )
            mask = region_floor_masks(contents.mask, by_region, set(masked)) if mask_term else None
        else:
            by_region = []
            mask = floor_mask(contents.mask, request.room, masked) if masked else None
        pinned = None
        if keep is not None:
            graph, pinned = pin_existing(graph, keep)
            start = {}  # the new pieces go where the layout's own placement finds room among the kept
        with timed(timings, "layout", time.perf_counter):
            layout = None
            if failed is not None:
                boxes = {n.id for n in graph.nodes("object")} - set(pinned or {})
                warm = {box: pose for box, pose in failed.items() if box in boxes}
                layout = layout_scene(
                    graph, seed, start=warm, mask=mask, params=WARM_PARAMS, pinned=pinned
                )
            if layout is None or not layout.ok:
                layout = layout_scene(
                    graph, seed, start=start, mask=mask, params=FIT_PARAMS, pinned=pinned
                )
        if layout.ok or attempt == FIT_ATTEMPTS:
            break
        failed = layout.poses
        smaller = fewer_pieces(model, contents, request, graph, layout.problems)
        if smaller is None:
            break
        contents = smaller
    given_up = {
        name: n - contents.counts.get(name, 0)
        for name, n in chosen.items()
        if contents.counts.get(name, 0) < n
    }
    for name in given_up:
        if name not in contents.counts:
            dropped.setdefault(name, ROOM_FULL)
    scene = assemble_scene(graph, layout, rules=contents.types[0], seed=seed)
    scene.completion = completion_record(contents, dropped, model, masked, given_up, by_region)
    scene.timings.update(timings)
    return scene


def existing_request(scene, added: dict[str, int], known) -> Request:
    """The request that completes a furnished ``scene`` (a scene.json's Scene, indoor):
    its room, its objects' categories as requested (so none is given up) and ``added``
    on top. ``InputError`` for a scene without a room or with an object whose type is no
    category of the indoor catalog ``known``."""
    if scene.room is None:
        raise InputError("the scene has no room (walls): only an indoor scene can be completed")
    requested: dict[str, int] = {}
    for obj in scene.placed_objects():
        if obj.type not in known:
            raise InputError(
                f"the scene's {obj.id} is a {obj.type!r}, which is no category of the indoor catalog"
            )
        requested[obj.type] = requested.get(obj.type, 0) + 1
    for name, count in added.items():
        requested[name] = requested.get(name, 0) + count
    return Request(scene.room, requested)


def pin_existing(graph: SceneGraph, scene) -> tuple[SceneGraph, dict[str, Pose]]:
    """``graph`` with a node for each object of the furnished ``scene`` pinned at its
    pose (a type's nodes in id order for its objects in id order), and between things
    that no longer move (two of those objects, or one and the room) the scene's own
    relations instead of those ``build_graph`` would state: the room had them, or not,
    before it was completed; what is new is placed by its relations to them."""
    from scenewright.core.relations import RELATIONS

    nodes: dict[str, list[str]] = {}
    for node in sorted(graph.nodes("object"), key=lambda n: _id_order(n.id)):
        nodes.setdefault(node.type, []).append(node.id)
    pinned: dict[str, Pose] = {}
    node_of: dict[str, str] = {}
    for obj in sorted(scene.placed_objects(), key=lambda o: _id_order(o.id)):
        node_of[obj.id] = nodes[obj.type].pop(0)
        pinned[node_of[obj.id]] = Pose(*(float(v) for v in obj.position), float(obj.yaw))
    fixed = set(pinned) | {
        n.id for n in graph.nodes() if n.kind in ("room", "wall", "door", "window")
    }
    kept = replace(graph, graph=graph.graph.copy())
    kept.graph.remove_edges_from(
        [(a, b, k) for a, b, k in kept.graph.edges(keys=True) if a in fixed and b in fixed]
    )
    # The scene's own relations among what it holds: a chair's "in front of the desk"
    # also lets it stand in the desk's clearance; what rests on what keeps it on top.
    for relation in scene.relations:
        source, target = node_of.get(relation.source), node_of.get(relation.target, relation.target)
        if source is not None and target in fixed and relation.label in RELATIONS:
            kept.add_relation(source, target, relation.label)
    return kept, pinned


def _id_order(object_id: str) -> tuple[str, int]:
    """``bed_10`` after ``bed_2``."""
    stem, _, number = object_id.rpartition("_")
    return (stem, int(number)) if number.isdigit() else (object_id, 0)


def summary_of(record: dict) -> str:
    """One line for people: the room's types and what was added to the request."""
    added = []
    for entry in record["selection"].values():
        for item in entry["categories"]:
            if not item["requested"] and item["category"] not in record["left_out"]:
                count = record["counts"][item["category"]]
                added.append(item["category"] + (f" x{count}" if count > 1 else ""))
    left = "".join(f"; left out {name} ({why})" for name, why in record["left_out"].items())
    left += "".join(
        f"; {n} {name} fewer (no room for more with the rest)"
        for name, n in record.get("given_up", {}).items()
        if name not in record["left_out"]
    )
    return f"room type {' + '.join(record['types'])}; added {', '.join(dict.fromkeys(added)) or 'nothing'}{left}"


def draw_explanation(scene, target) -> None:
    """Write a PNG to ``target`` (a path or binary file): the layout mask of
    ``scene.completion`` mapped back onto the room (darker: more of the reference plans'
    furniture stood there), with the room's outline, its doors (red) and windows (blue)
    and the laid-out floor pieces' outlines, north up. A room split by virtual walls
    shows each region's mask in its region, the virtual walls dashed (green) and each
    region's type."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.patches import Polygon

    from scenewright.core.frames import corners_of

    record, room = scene.completion, scene.room
    xs, zs = (np.array([c[i] for c in room.corners]) for i in (0, 1))
    grid_x, grid_z = np.meshgrid(
        np.linspace(xs.min(), xs.max(), 200), np.linspace(zs.min(), zs.max(), 160)
    )
    points = np.column_stack([grid_x.ravel(), grid_z.ravel()])
    values = recorded_mask_values(record, room, points).reshape(grid_x.shape)
    inside = np.array([room.contains(x, z) for x, z in points]).reshape(grid_x.shape)
    figure, axis = plt.subplots(figsize=(6.0, 6.0 * float(np.ptp(zs) / np.ptp(xs)) + 0.6))
    axis.imshow(
        np.where(inside, values, np.nan),
        cmap="Greys",
        vmin=0.0,
        vmax=1.0,
        origin="upper",
        extent=(xs.min(), xs.max(), zs.max(), zs.min()),
    )
    outline = list(room.corners) + [room.corners[0]]
    axis.plot([c[0] for c in outline], [c[1] for c in outline], color="0.2", lw=2.5)
    for opening in room.openings:
        start, end = room.opening_ends(opening)
        axis.plot(
            [start[0], end[0]],
            [start[1], end[1]],
            color="#c04040" if opening.kind == "door" else "#4a90c8",
            lw=4,
        )
    for (ax, az), (bx, bz) in record.get("virtual_walls", []):
        axis.plot([ax, bx], [az, bz], color="#2a9a4a", lw=2.5, ls="--")
    for region in record.get("regions", []):
        x0, z0, x1, z1 = region["bounds"]
        axis.annotate(
            region["type"].replace("_", " "),
            ((x0 + x1) / 2.0, z0 + 0.25),
            fontsize=8,
            ha="center",
            va="center",
            color="#2a7a3a",
            weight="bold",
        )
    for obj in scene.placed_objects():
        if obj.position[1] > 0.01:
            continue  # stands on another piece
        corners = corners_of(
            obj.position[0],
            obj.position[2],
            obj.size[0] / 2,
            obj.size[2] / 2,
            math.cos(obj.yaw),
            math.sin(obj.yaw),
        )
        axis.add_patch(Polygon(corners, closed=True, fill=False, ec="#e07020", lw=1.2))
        axis.annotate(
            obj.id,
            (obj.position[0], obj.position[2]),
            fontsize=6,
            ha="center",
            va="center",
            color="#a04000",
        )
    if "regions" in record:
        title = " | ".join(f"{r['type']} ({len(r['references'])} plans)" for r in record["regions"])
        axis.set_title(f"layout masks split by virtual walls: {title}", fontsize=8)
    else:
        mask = record["mask"]
        axis.set_title(
            f"layout mask of {mask['type']} ({len(mask['references'])} reference plans) and the layout",
            fontsize=8,
        )
    axis.set_xlabel("x (east) [m]")
    axis.set_ylabel("z (south) [m]")
    axis.set_aspect("equal")
    figure.tight_layout()
    figure.savefig(target, dpi=90, format="png")
    plt.close(figure)


def recorded_mask_values(record: dict, room: Room, points) -> np.ndarray:
    """(n,) the layout mask a ``completion`` record holds, read at room points (n, 2):
    the room's mask, or for a room split by virtual walls each region's in its region."""
    from scenewright.completion.features import CanonicalFrame
    from scenewright.completion.layout_mask import LayoutMask, mask_at
    from scenewright.completion.regions import region_of_points

    points = np.asarray(points, dtype=float).reshape(-1, 2)
    if "regions" not in record:
        mask = record["mask"]
        layout = LayoutMask(
            np.asarray(mask["cells"]),
            CanonicalFrame(**mask["frame"]),
            np.zeros(4),
            mask["references"],
        )
        return mask_at(layout, room, points)
    values = np.zeros(len(points))
    regions = [recorded_region(entry, room) for entry in record["regions"]]
    where = region_of_points(regions, points)
    for k, entry in enumerate(record["regions"]):
        chosen = where == k
        if chosen.any():
            layout = LayoutMask(
                np.asarray(entry["cells"]), CanonicalFrame(**entry["frame"]), np.zeros(4), {}
            )
            values[chosen] = mask_at(layout, regions[k].room, points[chosen])
    return values


def recorded_region(entry: dict, room: Room):
    """A ``regions.Region`` from its entry in a ``completion`` record (its sub-room's
    walls; the openings, which only the mask's frame needed, are not rebuilt)."""
    from scenewright.completion.regions import Region

    x0, z0, x1, z1 = entry["bounds"]
    sub = Room.polygon([(x0, z0), (x1, z0), (x1, z1), (x0, z1)], room.height, centre=False)
    return Region(entry["type"], (x0, z0, x1, z1), sub, entry["virtual_door"])
