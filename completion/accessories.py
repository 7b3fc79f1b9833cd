"""What stands on or at a piece, learned from the plans: for each accessory category
the pieces it stood on or at (its anchors) and where (the relative pose distribution,
``plan_model.AccessoryCategory``), learned with no rule written per category.

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

``model_builder`` keeps them in the plan model.
"""

from __future__ import annotations

import math
from collections import Counter, defaultdict

import numpy as np

from scenewright.core.frames import to_local
from scenewright.core.geometry import make_rect, rect_distance, wrap_angle

#: Metres between two footprints within which a piece stands at another.
ACCESSORY_GAP = 0.3
#: A category is an accessory when more than this share of its pieces stand on or at
#: an anchor.
ANCHORED_SHARE = 0.5
#: Metres from the centre of its anchor's top within which a piece stands in its middle,
#: and within which a piece counts as flush with an edge or a back.
MIDDLE = 0.1
FLUSH = 0.05
#: Radians within which a piece counts as parallel to its anchor.
PARALLEL = math.radians(5.0)

# -- learning -----------------------------------------------------------------------------


def anchor_of(piece, pieces, catalog) -> tuple[object, bool] | None:
    """``piece``'s anchor among ``pieces`` (one plan's) and whether it stands on it, or
    None (module docstring)."""
    from scenewright.completion.plan_checks import is_flat

    if piece.on is not None:
        support = next((other for other in pieces if other.id == piece.on), None)
        return (support, True) if support is not None else None
    if is_flat(piece, catalog):
        return None
    own = make_rect(*piece.center, *piece.size, piece.yaw)
    best = None
    for other in pieces:
        if other.id == piece.id or other.on is not None or other.area <= piece.area:
            continue
        if is_flat(other, catalog):
            continue
        gap = rect_distance(own, make_rect(*other.center, *other.size, other.yaw))
        if gap <= ACCESSORY_GAP and (best is None or (gap, other.id) < best[0]):
            best = ((gap, other.id), other)
    return (best[1], False) if best is not None else None


def relative_pose(piece, anchor, on: bool) -> dict:
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
        make_rect(*piece.center, *piece.size, piece.yaw),
        make_rect(*anchor.center, *anchor.size, anchor.yaw),
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
        anchors = [
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
