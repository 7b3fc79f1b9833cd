"""What stands on or at a piece, learned from the plans: for each accessory category
the pieces it stood on or at (its anchors) and where (the relative pose distribution,
``plan_model.AccessoryCategory``), and the relations and starting poses a completed
room's accessories take from them, with no rule written per category.

In a plan a piece's *anchor* (``anchor_of``) is the piece it stands ``on``, or else the
nearest larger piece on the floor (by footprint area; not flat) whose footprint comes
within ``ACCESSORY_GAP`` of its own: a night table 5 cm from the bed, a chair 5 cm from
its table. A flat piece (a rug) has none: the plans lay it under others. A category is
an *accessory* when more than ``ANCHORED_SHARE`` of its pieces over all the plans have
an anchor; it stands *on* others when most of those stand on theirs (only those
examples are kept, or only the others).

For each (accessory, anchor category) pair the model keeps the pieces seen, the most at
one anchor in one plan, and per side of the anchor they stood at (a *slot*: ``middle``
of its top, or its ``left``, ``right``, ``front`` or ``behind``, the anchor's own
sides): the pieces, the most at that side of one anchor in one plan, the mean centre
offset (left, forward) in the anchor's frame, the circular mean yaw relative to the
anchor's, the mean gap between the footprints (0 on top) and the share *flush* with the
anchor (on top: at an edge of its top, within ``FLUSH``; beside: parallel, the backs in
line within ``FLUSH``).

``assign`` chooses each accessory's anchor and slot in a room (falling back, for what
stands on others, to the smallest other surface it fits on that the plans show
carrying something as large). ``slot_relations`` turns
a slot into the registry's labels (``core.relations``): on top, ``OnTopOfMiddle`` /
``OnTopOfEdge`` / ``OnTopOfFrontEdge`` / ``OnTopOf`` by where the pieces stood; beside,
a piece one stays at that faced the anchor squarely within a seat's reach is seated at
that side (``SeatedAt``, ``SeatedAtBack``, ``SeatedAround``), another within
``BESIDE_REACH`` of a left or right side stands ``BesideLeft`` / ``BesideRight`` of
it, any other ``NextTo`` that side; then it faces the anchor (``FacingTowards``) when it
faced it, is aligned with it (and against the wall the anchor stands against) when
flush, or else turned as the slot's yaw says when that is near a quarter turn.
``slot_pose`` is its starting pose at its started anchor, at the slot's offset.
"""

from __future__ import annotations

import math
from collections import Counter, defaultdict
from collections.abc import Sequence
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Any

import numpy as np

from scenewright.completion.plan_model import AccessorySlot, PlanModel
from scenewright.core.frames import to_local, to_world
from scenewright.core.geometry import rect_distance, wrap_angle
from scenewright.core.poses import Pose
from scenewright.core.relations import BESIDE_REACH, SEAT_REACH

if TYPE_CHECKING:
    from scenewright.completion.floor_plan import Furniture

#: Metres between two footprints within which a piece stands at another.
ACCESSORY_GAP = 0.3
#: A category is an accessory when more than this share of its pieces stand on or at
#: an anchor.
ANCHORED_SHARE = 0.5
#: Metres from the centre of its anchor's top within which a piece stands in its middle,
#: and within which a piece counts as flush with an edge or a back.
MIDDLE = 0.1
FLUSH = 0.05
#: Radians within which a slot's yaw counts as facing its anchor, or as parallel to it.
FACING = math.radians(30.0)
PARALLEL = math.radians(5.0)
#: The sides of an anchor, as (left, forward) unit vectors in its frame.
SIDE_VECTORS = {
    "left": (1.0, 0.0),
    "right": (-1.0, 0.0),
    "front": (0.0, 1.0),
    "behind": (0.0, -1.0),
}
#: The next-to label of each side, the close one of the sides beside, and the seat's.
NEXT_TO = {
    "left": "NextToLeft",
    "right": "NextToRight",
    "front": "NextToFront",
    "behind": "NextToBehind",
}
CLOSE = {"left": "BesideLeft", "right": "BesideRight"}
SEATED = {
    "front": "SeatedAt",
    "behind": "SeatedAtBack",
    "left": "SeatedAround",
    "right": "SeatedAround",
}
#: The yaw, relative to its anchor's, at which a piece at each side faces the anchor.
FACING_YAW = {"front": math.pi, "behind": 0.0, "left": -math.pi / 2.0, "right": math.pi / 2.0}
#: Facing relations by the turn from the anchor they hold at, and how far off that turn
#: a slot's yaw may be for one to hold.
TURNS = (
    ("ImplicitFacingSameDirection", 0.0),
    ("ImplicitFacingOpposite", math.pi),
    ("ImplicitFacingOrthogonalDirection", math.pi / 2.0),
)
SQUARE = math.radians(15.0)


# -- learning -----------------------------------------------------------------------------


def anchor_of(
    piece: Furniture, pieces: Sequence[Furniture], catalog
) -> tuple[Furniture, bool] | None:
    """``piece``'s anchor among ``pieces`` (one plan's) and whether it stands on it, or
    None (module docstring)."""
    from scenewright.completion.plan_checks import is_flat

    if piece.on is not None:
        support = next((other for other in pieces if other.id == piece.on), None)
        return (support, True) if support is not None else None
    if is_flat(piece, catalog):
        return None
    own = piece.rect
    best = None
    for other in pieces:
        if other.id == piece.id or other.on is not None or other.area <= piece.area:
            continue
        if is_flat(other, catalog):
            continue
        gap = rect_distance(own, other.rect)
        if gap <= ACCESSORY_GAP and (best is None or (gap, other.id) < best[0]):
            best = ((gap, other.id), other)
    return (best[1], False) if best is not None else None


def relative_pose(piece: Furniture, anchor: Furniture, on: bool) -> dict:
    """Where ``piece`` stands relative to ``anchor``: its slot's side, its centre's
    offset (left, forward) in the anchor's frame, its relative yaw, the gap between
    the footprints and whether it is flush with the anchor (module docstring)."""
    lx, lz = to_local(*anchor.center, anchor.yaw, *piece.center)
    yaw = wrap_angle(piece.yaw - anchor.yaw)
    half_w, half_d = anchor.size[0] / 2.0, anchor.size[1] / 2.0
    # The piece's corners in the anchor's frame.
    corners = [to_local(*anchor.center, anchor.yaw, x, z) for x, z in piece.corners]
    if on:
        if math.hypot(lx, lz) <= MIDDLE:
            side = "middle"
        else:
            side = _side_of(abs(lx) / half_w >= abs(lz) / half_d, lx, lz)
        margin = min(
            half_w - max(x for x, _ in corners),
            half_w + min(x for x, _ in corners),
            half_d - max(z for _, z in corners),
            half_d + min(z for _, z in corners),
        )
        return {
            "side": side,
            "offset": (lx, lz),
            "yaw": yaw,
            "gap": 0.0,
            "flush": margin <= FLUSH,
        }
    side = _side_of(abs(lx) - half_w >= abs(lz) - half_d, lx, lz)
    gap = rect_distance(
        piece.rect,
        anchor.rect,
    )
    back = min(z for _, z in corners)
    flush = abs(yaw) <= PARALLEL and abs(back + half_d) <= FLUSH
    return {"side": side, "offset": (lx, lz), "yaw": yaw, "gap": gap, "flush": flush}


def _side_of(along_x: bool, lx: float, lz: float) -> str:
    """The anchor's side towards the offset (lx, lz): left or right when ``along_x``,
    else front or behind."""
    if along_x:
        return "left" if lx > 0.0 else "right"
    return "front" if lz > 0.0 else "behind"


def learn_accessories(plans, catalog) -> dict:
    """The model's ``accessories`` (JSON form): per accessory category (module
    docstring) its pieces, the share with an anchor, whether it stands on others, and
    per anchor category the pieces and slots; categories in name order, anchors by
    pieces (most first, then name), slots likewise (most first, then side)."""
    pieces: Counter = Counter()
    examples: dict[str, list] = defaultdict(list)  # category -> (anchor category, on, pose, key)
    for plan in plans:
        for piece in plan.furniture:
            pieces[piece.category] += 1
            found = anchor_of(piece, plan.furniture, catalog)
            if found is None:
                continue
            anchor, on = found
            pose = relative_pose(piece, anchor, on)
            examples[piece.category].append((anchor.category, on, pose, (plan.id, anchor.id)))
    out = {}
    for name in sorted(examples):
        seen = examples[name]
        anchored = len(seen) / pieces[name]
        if anchored <= ANCHORED_SHARE:
            continue
        on = 2 * sum(1 for _, stands_on, _, _ in seen if stands_on) > len(seen)
        kept = [example for example in seen if example[1] == on]
        by_anchor: dict[str, list] = defaultdict(list)
        for anchor, _, pose, key in kept:
            by_anchor[anchor].append((pose, key))
        anchors: list[dict[str, Any]] = [
            {
                "anchor": anchor,
                "pieces": len(found),
                "most": max(Counter(key for _, key in found).values()),
                "slots": _slots(found),
            }
            for anchor, found in by_anchor.items()
        ]
        anchors.sort(key=lambda entry: (-entry["pieces"], entry["anchor"]))
        out[name] = {
            "pieces": pieces[name],
            "anchored": anchored,
            "on": on,
            "anchors": anchors,
        }
    return out


def _slots(found: list) -> list[dict]:
    """The slots of one pair's examples (pose, (plan id, anchor id)): see the module docstring."""
    by_side: dict[str, list] = defaultdict(list)
    for pose, key in found:
        by_side[pose["side"]].append((pose, key))
    slots = []
    for side, members in by_side.items():
        poses = [pose for pose, _ in members]
        yaws = np.array([pose["yaw"] for pose in poses])
        slots.append(
            {
                "side": side,
                "pieces": len(poses),
                "most": max(Counter(key for _, key in members).values()),
                "offset": np.mean([pose["offset"] for pose in poses], axis=0).tolist(),
                "yaw": float(math.atan2(np.sin(yaws).mean(), np.cos(yaws).mean())),
                "gap": float(np.mean([pose["gap"] for pose in poses])),
                "flush": float(np.mean([pose["flush"] for pose in poses])),
            }
        )
    slots.sort(key=lambda slot: (-slot["pieces"], slot["side"]))
    return slots


# -- placing ------------------------------------------------------------------------------


@dataclass(frozen=True)
class Placement:
    """Where one accessory of a room goes: its anchor (category, and which of its pieces),
    whether it stands on it, the slot, and its place among the pieces at that slot of
    that anchor (``index`` of ``count``, filled in by ``assign``). ``overflow``: every
    place the plans show was taken, so it stands anywhere on a support."""

    anchor: str
    anchor_index: int
    on: bool
    slot: AccessorySlot
    index: int = 0
    count: int = 1
    overflow: bool = False


def stands_on(model: PlanModel, category: str) -> bool:
    """Whether the plans show ``category`` standing on other pieces."""
    entry = model.accessories.get(category)
    return entry is not None and entry.on


def surfaces(model: PlanModel) -> dict[str, float]:
    """The categories the plans show something standing on, in name order, each with
    the largest footprint area (square metres, from the mean sides) of what stood on it."""
    carried: dict[str, float] = {}
    for name, entry in model.accessories.items():
        if not entry.on:
            continue
        short, long = model.categories[name].size
        for anchor in entry.anchors:
            carried[anchor.anchor] = max(carried.get(anchor.anchor, 0.0), short * long)
    return dict(sorted(carried.items()))


def assign(model: PlanModel, counts: dict[str, int], catalog) -> dict[tuple[str, int], Placement]:
    """Each accessory piece's ``Placement`` in a room holding ``counts`` (category ->
    pieces; ``catalog``: the indoor catalog's entries by name), keyed by (category,
    index). The pairs the plans show are filled most pieces first (a night table by the
    bed before anything else by it); each piece goes to the anchor of its pair holding
    fewest of it, to the slot of highest average (its pieces over 2 x those placed
    there + 1, so both sides of a bed before a second on one), up to the most the plans
    show at one anchor and at each side of it; a side's places are shared by every
    category (a desk's chair takes the place before it). What stands on others and finds
    no place goes on another surface present that it fits on and that the plans show
    carrying something as large (``surfaces``: a lamp on a desk, which carries laptops,
    but not a television), the smallest first, in the slot it takes most often, one a
    surface; with none left, anywhere on the first support it fits on (``overflow``). Floor pieces with no place have none: they stand
    by the room's other rules. A category that stands on others with nothing in the
    room it fits on is absent from the answer."""
    pairs = []
    for name in sorted(counts):
        entry = model.accessories.get(name)
        if entry is None:
            continue
        for anchor in entry.anchors:
            if counts.get(anchor.anchor) and (
                not entry.on or _fits_on(catalog, name, anchor.anchor)
            ):
                pairs.append((anchor.pieces, name, anchor))
    pairs.sort(key=lambda pair: (-pair[0], pair[1], pair[2].anchor))
    side_taken: Counter = Counter()  # (anchor category, index, side) -> pieces there
    pair_taken: Counter = Counter()  # (category, anchor category, index) -> its pieces there
    slot_taken: Counter = Counter()  # (category, anchor category, index, side)
    placed: dict[tuple[str, int], Placement] = {}
    waiting = {
        name: list(range(counts[name])) for name in sorted(counts) if name in model.accessories
    }
    for _, name, anchor in pairs:
        entry = model.accessories[name]
        for k in list(waiting[name]):
            best = None
            for index in range(counts[anchor.anchor]):
                if pair_taken[name, anchor.anchor, index] >= anchor.most:
                    continue
                for order, slot in enumerate(anchor.slots):
                    if side_taken[anchor.anchor, index, slot.side] >= slot.most:
                        continue
                    average = slot.pieces / (
                        2 * slot_taken[name, anchor.anchor, index, slot.side] + 1
                    )
                    rank = (pair_taken[name, anchor.anchor, index], -average, index, order)
                    if best is None or rank < best[0]:
                        best = (rank, index, slot)
            if best is None:
                break
            _, index, slot = best
            placed[name, k] = Placement(anchor.anchor, index, entry.on, slot)
            pair_taken[name, anchor.anchor, index] += 1
            slot_taken[name, anchor.anchor, index, slot.side] += 1
            side_taken[anchor.anchor, index, slot.side] += 1
            waiting[name].remove(k)
    for name, left in waiting.items():
        entry = model.accessories[name]
        if not left or not entry.on:
            continue
        learned = {anchor.anchor for anchor in entry.anchors}
        width, _, depth = catalog[name].size
        others = sorted(
            (
                surface
                for surface, largest in surfaces(model).items()
                if counts.get(surface)
                and surface not in learned
                and width * depth <= largest + 1e-9
                and _fits_on(catalog, name, surface)
            ),
            key=lambda surface: (catalog[surface].size[0] * catalog[surface].size[2], surface),
        )
        slot = entry.anchors[0].slots[0]
        for surface in others:
            for index in range(counts[surface]):
                if left and side_taken[surface, index, slot.side] < 1:
                    placed[name, left.pop(0)] = Placement(surface, index, True, slot)
                    side_taken[surface, index, slot.side] += 1
        holders = [
            (support, index)
            for support in [a.anchor for a in entry.anchors if a.anchor in counts] + others
            if _fits_on(catalog, name, support)
            for index in range(counts[support])
        ]
        for k, piece in enumerate(left if holders else ()):
            support, index = holders[k % len(holders)]
            placed[name, piece] = Placement(support, index, True, slot, overflow=True)
    # Each piece's place among those at its slot of its anchor, for the starting poses.
    groups: dict[tuple, list] = defaultdict(list)
    for key, placement in sorted(placed.items()):
        groups[placement.anchor, placement.anchor_index, placement.slot.side].append(key)
    for members in groups.values():
        for k, key in enumerate(members):
            placed[key] = replace(placed[key], index=k, count=len(members))
    return placed


def _fits_on(catalog, item: str, support: str) -> bool:
    """Whether ``item``'s footprint fits on ``support``'s top (a television wider than a
    dresser would hang off it)."""
    width, _, depth = catalog[item].size
    top_width, _, top_depth = catalog[support].size
    return width <= top_width + 1e-9 and depth <= top_depth + 1e-9


def slot_relations(
    placement: Placement, category: str, model: PlanModel, against_wall: bool
) -> list[tuple[str, str | None]]:
    """The relations (label, target) of an accessory at its ``placement`` (module
    docstring); the target None is its anchor, ``ROOM_NODE`` the room. ``against_wall``:
    whether the anchor stands against a wall."""
    from scenewright.completion.activity import STAY
    from scenewright.core.room import ROOM_NODE

    slot = placement.slot
    if placement.on:
        if placement.overflow:
            return [("OnTopOf", None)]
        if slot.side == "middle":
            label = "OnTopOfMiddle"
        elif slot.flush >= 0.5:
            label = "OnTopOfFrontEdge" if slot.side == "front" else "OnTopOfEdge"
        else:
            label = "OnTopOf"
        return [(label, None), *_turned(slot.yaw)]
    faces = abs(wrap_angle(slot.yaw - FACING_YAW[slot.side])) <= FACING
    stays = model.categories[category].purpose == STAY if category in model.categories else False
    if faces and stays and slot.gap <= SEAT_REACH:
        return [(SEATED[slot.side], None)]
    close = slot.side in CLOSE and slot.gap <= BESIDE_REACH
    relations: list[tuple[str, str | None]] = [
        (CLOSE[slot.side] if close else NEXT_TO[slot.side], None)
    ]
    if faces:
        relations.append(("FacingTowards", None))
    elif slot.flush >= 0.5:
        relations.append(("ImplicitAlignedWith", None))
        if against_wall:
            relations.append(("ImplicitAgainstWall", ROOM_NODE))
    else:
        relations += _turned(slot.yaw)
    return relations


def _turned(yaw: float) -> list[tuple[str, str | None]]:
    """The facing relation (implicit: the pose says it, the text need not) of a piece
    turned ``yaw`` from its anchor, when that is within ``SQUARE`` of a quarter turn:
    the same way, the opposite or across."""
    for label, turn in TURNS:
        if abs(wrap_angle(yaw - turn)) <= SQUARE or abs(wrap_angle(yaw + turn)) <= SQUARE:
            return [(label, None)]
    return []


def slot_pose(
    placement: Placement, anchor: Pose, anchor_size, size, gap_floor: float = 0.02
) -> Pose:
    """The starting pose of an accessory at its ``placement`` beside (or on) its anchor
    standing at ``anchor``: ``anchor_size`` and ``size`` are the (width, depth) of the
    anchor's footprint and the accessory's. On top: the slot's offset, kept on the top.
    Beside: the slot's side at its gap (at least ``gap_floor``); along the side, spread
    evenly when several share the slot, else back in line with the anchor's when the
    plans had it flush, else at the slot's offset, kept within the side."""
    slot = placement.slot
    half_w, half_d = anchor_size[0] / 2.0, anchor_size[1] / 2.0
    c, s = abs(math.cos(slot.yaw)), abs(math.sin(slot.yaw))
    # The accessory's half extents along the anchor's axes once turned by the slot's yaw.
    ex = c * size[0] / 2.0 + s * size[1] / 2.0
    ez = s * size[0] / 2.0 + c * size[1] / 2.0
    if placement.on:
        lx = float(np.clip(slot.offset[0], -max(half_w - ex, 0.0), max(half_w - ex, 0.0)))
        lz = float(np.clip(slot.offset[1], -max(half_d - ez, 0.0), max(half_d - ez, 0.0)))
    else:
        ux, uz = SIDE_VECTORS[slot.side]
        gap = max(slot.gap, gap_floor)
        if ux:  # a left or right side: out along x, along z
            out, along, room, own = half_w + gap + ex, slot.offset[1], half_d, ez
        else:
            out, along, room, own = half_d + gap + ez, slot.offset[0], half_w, ex
        if placement.count > 1:
            along = ((placement.index + 0.5) / placement.count - 0.5) * 2.0 * room
        elif slot.flush >= 0.5 and ux:
            along = -half_d + ez
        else:
            along = float(np.clip(along, -max(room - own, 0.0), max(room - own, 0.0)))
        lx, lz = (ux * out, along) if ux else (along, uz * out)
    x, z = to_world(anchor.x, anchor.z, anchor.yaw, lx, lz)
    return Pose(float(x), 0.0, float(z), float(wrap_angle(anchor.yaw + slot.yaw)))
