"""How a category stands in a room, learned from the plans: per category the share of
its floor pieces that stand in a corner, with their back against a wall, or free in the
middle, and with what they stand in a row and what they stand or lie before
(``plan_model.CategoryStance``). ``furnishing`` places a category the way most of its
plan pieces stand (``stance``), with no rule written per category.

Over one plan's pieces on the floor (not standing on another):

- a footprint side *touches* a wall when it faces the wall (parallel within
  ``PARALLEL``), overlaps it along its length and comes within ``WALL_GAP`` of its
  face (its back or front: a treadmill keeps a safety gap behind it) or ``SIDE_GAP``
  (its left or right);
- a piece stands in a *corner* when its sides touch two walls that are not parallel (a
  plant in the corner, a wardrobe with its back and one side to walls), *against a
  wall* when otherwise its back touches one, and *free* when no side touches a wall
  (the three shares are of all its pieces, and exclusive);
- a piece stands in a *row* with a piece of another category (or of its own) when
  their yaws agree (within ``PARALLEL``), their backs are in line (within ``FLUSH``)
  and their footprints come within ``ROW_GAP`` side by side: two bookshelves, two
  treadmills; the share is over the pieces whose plan has a piece of that category
  besides them;
- a piece whose back touches no wall stands or lies *before* a piece when its centre
  lies in front of that one's front side, within its width and within
  ``BEFORE_REACH`` (the nearest such piece): a rug before the sofa, a bench before the
  dumbbell rack (a dresser across the room from a piano is at its own wall, not before
  the piano); the share is over the pieces away from the walls whose plan has a piece
  of that category besides them.

The same pass learns how a piece stands to the windows and to the pieces round it
(under a window, close before, facing, beside: the tests are in ``neighbours``), and
``under_window``, ``facing_target`` and ``beside_target`` read those shares.
Flat pieces and accessories (``accessories``) are nothing to stand in a row with or
before. ``stance`` turns the shares into one way to place a category, each with the
threshold ``MOST`` (more than half the pieces). A category the plans never show on the
floor takes the pooled shares of all the categories neither flat nor accessories
(``learned_stance``).
"""

from __future__ import annotations

import math
from collections import Counter, defaultdict
from collections.abc import Sequence
from typing import TYPE_CHECKING

from scenewright.core.frames import forward, left, to_local
from scenewright.core.geometry import rect_distance, wrap_angle

from . import neighbours

if TYPE_CHECKING:
    from scenewright.completion.floor_plan import Furniture, Plan
    from scenewright.completion.plan_model import CategoryStance, PlanModel
    from scenewright.core.room import Room, Wall

#: Metres between a footprint's back or front and a wall's face within which it touches it.
WALL_GAP = 0.5
#: Metres between a footprint's left or right side and a wall within which it touches
#: it (a plant in a corner keeps a hand's breadth from the second wall).
SIDE_GAP = 0.3
#: Radians within which a side counts as parallel to a wall, or two pieces as turned alike.
PARALLEL = math.radians(5.0)
#: Metres by which two backs may be out of line and still stand flush in a row.
FLUSH = 0.1
#: Metres between two footprints side by side within which they stand in a row.
ROW_GAP = 0.3
#: Metres in front of a piece's front side within which what stands before it has its centre.
BEFORE_REACH = 2.0
#: A category is placed one way when more than this share of its plan pieces stand so.
MOST = 0.5
#: A category whose pieces stood at a wall (in a corner or not) in more than this share
#: takes its heading from its wall, not from what it faces (a television stand, a
#: wardrobe): facing is for pieces the plans also show away from the walls.
AT_WALL = 0.95
#: The ways to place a category, as ``stance`` returns them.
CORNER, WALL, FREE, ROW, BEFORE, PARTNER = "corner", "wall", "free", "row", "before", "partner"


# -- learning -----------------------------------------------------------------------------


def _sides(piece: Furniture) -> dict[str, tuple[tuple[float, float], tuple[float, float]]]:
    """Per side of the footprint (back, front, left, right): its midpoint and outward normal."""
    fx, fz = forward(piece.yaw)
    lx, lz = left(piece.yaw)
    half_w, half_d = piece.size[0] / 2.0, piece.size[1] / 2.0
    cx, cz = piece.center
    return {
        "back": ((cx - fx * half_d, cz - fz * half_d), (-fx, -fz)),
        "front": ((cx + fx * half_d, cz + fz * half_d), (fx, fz)),
        "left": ((cx + lx * half_w, cz + lz * half_w), (lx, lz)),
        "right": ((cx - lx * half_w, cz - lz * half_w), (-lx, -lz)),
    }


def touched_walls(piece: Furniture, room: Room) -> dict[str, Wall]:
    """The wall each side of ``piece`` touches (module docstring), by side."""
    out = {}
    for side, ((mx, mz), (nx, nz)) in _sides(piece).items():
        along = side in ("back", "front")
        reach = (piece.size[0] if along else piece.size[1]) / 2.0
        gap = WALL_GAP if along else SIDE_GAP
        for wall in room.walls:
            # The side faces the wall: its outward normal against the wall's inner one.
            if nx * wall.normal[0] + nz * wall.normal[1] > -math.cos(PARALLEL):
                continue
            u, v = wall.to_wall(mx, mz)
            if abs(v) <= gap and u + reach > 0.0 and u - reach < wall.length:
                out[side] = wall
                break
    return out


def in_row(piece: Furniture, other: Furniture) -> bool:
    """Whether ``other`` stands in a row with ``piece`` (module docstring)."""
    if abs(wrap_angle(piece.yaw - other.yaw)) > PARALLEL:
        return False
    lx, lz = to_local(*piece.center, piece.yaw, *other.center)
    # Beside it, not before or behind it, and the other's back in line with this one's.
    if abs(lx) < piece.size[0] / 2.0 or abs(lz - other.size[1] / 2.0 + piece.size[1] / 2.0) > FLUSH:
        return False
    return rect_distance(piece.rect, other.rect) <= ROW_GAP


def before_of(piece: Furniture, others: Sequence[Furniture]) -> Furniture | None:
    """The piece of ``others`` that ``piece`` stands or lies before (module docstring), or None."""
    best = None
    for other in others:
        lx, lz = to_local(*other.center, other.yaw, *piece.center)
        front = lz - other.size[1] / 2.0
        if abs(lx) <= other.size[0] / 2.0 and 0.0 < front <= BEFORE_REACH:
            if best is None or (front, other.id) < best[0]:
                best = ((front, other.id), other)
    return best[1] if best is not None else None


def learn_stances(plans: Sequence[Plan], catalog, accessories: set[str]) -> dict:
    """Per category of the plans' floor pieces its stance (``plan_model.CategoryStance``
    as a dict), categories sorted (module docstring); ``accessories``: the accessory
    categories."""
    from scenewright.completion.plan_checks import is_flat

    tallies: dict[str, Counter] = defaultdict(Counter)
    rows: dict[str, Counter] = defaultdict(Counter)
    befores: dict[str, Counter] = defaultdict(Counter)
    closes: dict[str, Counter] = defaultdict(Counter)
    facings: dict[str, Counter] = defaultdict(Counter)
    besides: dict[str, Counter] = defaultdict(Counter)
    chances: dict[str, Counter] = defaultdict(Counter)
    free_chances: dict[str, Counter] = defaultdict(Counter)
    for plan in sorted(plans, key=lambda plan: plan.id):
        floor = [piece for piece in plan.furniture if piece.on is None]
        flat = {piece.id for piece in floor if is_flat(piece, catalog)}
        partners = [p for p in floor if p.id not in flat and p.category not in accessories]
        touched = {piece.id: touched_walls(piece, plan.room) for piece in floor}
        stands_before = _stands_before(floor, partners, touched)
        for piece in floor:
            sides = touched[piece.id]
            walls = list(sides.values())
            tally = tallies[piece.category]
            tally["pieces"] += 1
            tally["flat"] += piece.id in flat
            tally["window chances"] += bool(plan.room.windows)
            tally["window"] += neighbours.is_under_window(piece, plan.room, sides.get("back"))
            if any(
                abs(a.normal[0] * b.normal[0] + a.normal[1] * b.normal[1]) < math.cos(PARALLEL)
                for a in walls
                for b in walls
            ):
                tally["corner"] += 1
            elif "back" in sides:
                tally["wall"] += 1
            elif not walls:
                tally["free"] += 1
            others = [other for other in partners if other.id != piece.id]
            present = {other.category for other in others}
            if piece.id not in flat:
                chances[piece.category].update(present)
                rows[piece.category].update(
                    {other.category for other in others if in_row(piece, other)}
                )
                besides[piece.category].update(
                    {other.category for other in others if neighbours.is_beside(piece, other)}
                )
                ahead = neighbours.faced(piece, others, stands_before)
                if ahead is not None:
                    facings[piece.category][ahead.category] += 1
            if "back" not in sides:  # one at a wall stands by the wall, not before a piece
                free_chances[piece.category].update(present)
                before_id = stands_before.get(piece.id)
                if before_id is not None:
                    before = plan.piece(before_id)
                    befores[piece.category][before.category] += 1
                    if neighbours.gap_before(piece, before) <= neighbours.CLOSE_GAP:
                        closes[piece.category][before.category] += 1
    out: dict[str, dict] = {}
    for name in sorted(tallies):
        tally = tallies[name]
        out[name] = {
            "pieces": tally["pieces"],
            "flat": tally["flat"] * 2 > tally["pieces"],
            "corner": tally["corner"] / tally["pieces"],
            "wall": tally["wall"] / tally["pieces"],
            "free": tally["free"] / tally["pieces"],
            "window": tally["window"] / tally["window chances"] if tally["window chances"] else 0.0,
            "row": _shares(rows[name], chances[name]),
            "before": _shares(befores[name], free_chances[name]),
            "close": _shares(closes[name], free_chances[name], neighbours.LEAST),
            "facing": _shares(facings[name], chances[name], neighbours.LEAST),
            "beside": _shares(besides[name], chances[name], neighbours.LEAST),
        }
    return out


def _stands_before(
    floor: Sequence[Furniture], partners: Sequence[Furniture], touched: dict[str, dict]
) -> dict[str, str]:
    """Per id of a piece of ``floor`` whose back touches no wall (``touched``: each
    piece's ``touched_walls``) the id of the piece of ``partners`` it stands or lies
    before (``before_of``), where it does."""
    out = {}
    for piece in floor:
        if "back" in touched[piece.id]:
            continue
        before = before_of(piece, [other for other in partners if other.id != piece.id])
        if before is not None:
            out[piece.id] = before.id
    return out


def _shares(counter: Counter, chances: Counter, least: int = 1) -> dict[str, float]:
    """Per category of ``counter`` its count over its ``chances`` (those with at least
    ``least``), most first (ties by name)."""
    ranked = sorted(
        (
            (name, count / chances[name])
            for name, count in counter.items()
            if count and chances[name] >= least
        ),
        key=lambda item: (-item[1], item[0]),
    )
    return dict(ranked)


# -- placing ------------------------------------------------------------------------------


def learned_stance(model: PlanModel, name: str) -> CategoryStance:
    """``name``'s stance in ``model``; for a category the plans never show on the floor,
    the pooled shares of all the categories that are neither flat nor accessories
    (weighted by their pieces), with no rows and nothing before."""
    from scenewright.completion.plan_model import CategoryStance

    learned = model.stances.get(name)
    if learned is not None:
        return learned
    pool = [
        entry
        for category, entry in sorted(model.stances.items())
        if not entry.flat and category not in model.accessories
    ]
    pieces = sum(entry.pieces for entry in pool)

    def pooled(share) -> float:
        return sum(share(entry) * entry.pieces for entry in pool) / pieces if pieces else 0.0

    return CategoryStance(
        pieces=0,
        flat=False,
        corner=pooled(lambda entry: entry.corner),
        wall=pooled(lambda entry: entry.wall),
        free=pooled(lambda entry: entry.free),
        window=pooled(lambda entry: entry.window),
        row={},
        before={},
        close={},
        facing={},
        beside={},
    )


def base_stance(model: PlanModel, name: str) -> str:
    """Where ``name`` stands by the room alone (``learned_stance``): ``CORNER`` when more
    than ``MOST`` of its plan pieces stood in a corner, else ``WALL`` when more stood
    with their back to a wall (a corner's piece has too), else ``FREE`` when more stood
    free, else ``PARTNER`` (by what it relates to)."""
    learned = learned_stance(model, name)
    if learned.corner > MOST:
        return CORNER
    if learned.corner + learned.wall > MOST:
        return WALL
    if learned.free > MOST:
        return FREE
    return PARTNER


def room_share(model: PlanModel, name: str) -> float:
    """The share of ``name``'s plan pieces that stood where ``base_stance`` puts it by
    the room: in a corner, at a wall (a corner's too) or free; for ``PARTNER`` the
    larger of at a wall and free."""
    learned = learned_stance(model, name)
    base = base_stance(model, name)
    if base == CORNER:
        return learned.corner
    if base == FREE:
        return learned.free
    if base == WALL:
        return learned.corner + learned.wall
    return max(learned.corner + learned.wall, learned.free)


def stance(model: PlanModel, name: str, present) -> tuple[str, tuple[str, ...]]:
    """How to place ``name`` in a room holding the categories ``present`` (itself
    included), and the categories that decides it by, best first. An accessory that
    found no anchor in the room stands by its partner (``PARTNER``). A flat piece lies
    ``BEFORE`` the present categories it lay before in the plans, most often first
    (none: by its partner). A piece that stands against a wall (``base_stance``) stands
    in a ``ROW`` with the present categories more than ``MOST`` of its pieces stood in
    a row with (bookshelves, treadmills), else in its corner or against its wall. One
    that stands free stands ``BEFORE`` the present categories more than ``MOST`` of its
    pieces stood close before (``neighbours``: a coffee table before the sofa), else
    free (a dining table). Any other stands ``BEFORE`` the
    present categories more than ``MOST`` of its pieces away from the walls stood before
    (a weight bench before the dumbbell rack), else against a wall when at least as
    many of its pieces stood at one as free (an armchair half at a wall, half free),
    else by its partner."""
    if name in model.accessories:
        return PARTNER, ()  # at no anchor of its own (``accessories``): by its partner
    learned = learned_stance(model, name)
    if learned.flat:
        return BEFORE, tuple(n for n in _ranked(learned.before) if n in present)
    base = base_stance(model, name)
    if base in (WALL, CORNER):
        kind, shares = ROW, learned.row
    else:  # one free in the middle stands before only what it stood close before
        kind, shares = BEFORE, learned.close if base == FREE else learned.before
    chosen = tuple(n for n in _ranked(shares) if shares[n] > MOST and n in present)
    if chosen:
        return kind, chosen
    if base == PARTNER and learned.corner + learned.wall >= max(learned.free, 1e-9):
        return WALL, ()  # split between a wall and the middle: at least as many at a wall
    return base, ()


def stands_by_room(model: PlanModel, name: str) -> bool:
    """Whether ``name`` is a large piece placed by the room, against a wall or free in
    its middle, not by another piece: not flat and no accessory. The layout mask
    prefers where such pieces go, and a split room places them by their own category."""
    return (
        not learned_stance(model, name).flat
        and name not in model.accessories
        and base_stance(model, name) in (WALL, FREE)
    )


def _ranked(shares: dict[str, float]) -> list[str]:
    """The categories of ``shares``, the largest share first (ties by name): a model
    file keeps them sorted by name."""
    return sorted(shares, key=lambda name: (-shares[name], name))


def under_window(model: PlanModel, name: str) -> bool:
    """Whether ``name`` goes under a window: more than ``MOST`` of its plan pieces stood
    under one."""
    return learned_stance(model, name).window > MOST


def facing_target(model: PlanModel, name: str, present) -> str | None:
    """The category of ``present`` that ``name`` turns to face: of those more than
    ``MOST`` of its pieces faced, the one faced most often; None for a category that
    takes its heading from its wall (``AT_WALL``) or faced none of them."""
    learned = learned_stance(model, name)
    if learned.corner + learned.wall > AT_WALL:
        return None
    return _most(learned.facing, name, present)


def beside_target(model: PlanModel, name: str, present) -> str | None:
    """The category of ``present`` that ``name`` stands beside: of those more than
    ``MOST`` of its pieces stood beside, the one stood beside most often, when that
    share is larger than the share of its pieces that stood where the room alone would
    put it (``stances.room_share``: an armchair stood beside the coffee table more often
    than at a wall; a floor lamp in a corner more often than beside the armchair); else
    None."""
    shares = learned_stance(model, name).beside
    chosen = _most(shares, name, present)
    return chosen if chosen is not None and shares[chosen] > room_share(model, name) else None


def _most(shares: dict[str, float], name: str, present) -> str | None:
    """The category of ``present`` other than ``name`` with the largest share over
    ``MOST`` (ties by name), or None."""
    chosen = [
        (-share, other)
        for other, share in shares.items()
        if share > MOST and other != name and other in present
    ]
    return min(chosen)[1] if chosen else None
