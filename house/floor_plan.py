"""Making a floor plan from a plan in the rules language: room outlines inside the footprint.

The method is recursive slicing on a grid (the squarified "slicing floor plan" of
architecture and of ProcTHOR-like house generators), drawn at random and checked:

1. Draw the plan's rooms (optional ones with their probability, counts in their range)
   and an area for each in its range; draw the footprint's size in its ranges so the
   rooms fill it (a footprint given by corners is as it is); rasterise the footprint,
   less its courtyards, on a ``CELL`` grid; then stretch or shrink the rooms' areas
   within their ranges until they fill it (``_fill``).
2. Slice: a set of rooms on a region is split in two groups, and the region cut
   across its longer side where the cell count matches the groups' areas, until each
   room has a region of its own. A region that holds the plan's hub (the room type the
   most rooms must connect to: a hall, a corridor) is cut, with a high probability,
   into three strips with the hub in the middle, so the hub runs past every room of
   the region (a corridor with offices either side, a hall across the house).
3. Check the draw: every room one piece without holes, its area within its range (a
   fifth either way, since the rooms must fill the footprint), at least its width
   everywhere (a square of that side fits around every cell of it), not too elongated
   (circulation rooms aside); every connection the plan asks for a shared wall long
   enough for a door; rooms that want a window, and the entrance room, an outside wall
   long enough for one; every room reachable from the entrance through doors (doors
   added, nearest the hub first, where the plan's connections leave a room out).
4. The first slicing that passes, of at most ``ATTEMPTS`` (the rooms and footprint
   drawn anew every ``DRAWS``), is the plan; none passing is a
   ``PlanError`` that names what failed most often.

Everything is drawn from the plan's own stream of the scene's seed.
"""

from __future__ import annotations

import math
from collections import Counter
from dataclasses import dataclass

import numpy as np
from scipy import ndimage

from scenewright.core.errors import InputError
from scenewright.core.geometry import points_in_polygon
from scenewright.core.seeds import stream

from .outline import Outlines, PlannedDoor, PlannedRoom
from .plan_language import CIRCULATION, PlanSpec, RoomSpec

#: Grid cells times tries a plan may cost at most (a 15 x 11 m footprint gets every one
#: of ``ATTEMPTS`` tries, a 200 x 200 m one ``DRAWS``).
WORK = 3_000_000
#: The grid step of generated plans (m): walls lie on its lines.
CELL = 0.5
#: Slicings tried before a plan is given up, and how many of them share one draw of the
#: rooms and the footprint.
ATTEMPTS = 1500
DRAWS = 150
#: The shortest shared wall a door needs, and the shortest outside wall for a window or
#: the front door (cells).
DOOR_RUN = 3
WINDOW_RUN = 3
#: A room's area may leave its range by this share either way (the rooms must fill the footprint).
AREA_SLACK = 0.2
#: Rooms that are not for walking through: bounding box at most this elongated, at least this full.
MAX_ASPECT = 2.5
MIN_FILL = 0.7
#: A cut this many lines or fewer from a step in the region's outline is moved onto the
#: step with this probability.
SNAP_LINES = 3
SNAP_CHANCE = 0.7
#: The probability that a region holding the hub is cut into strips with the hub in the middle.
STRIP_CHANCE = 0.85


class PlanError(InputError):
    """A plan for which no floor plan could be drawn."""


@dataclass
class _Room:
    spec: RoomSpec
    index: int  # its number among the rooms of its type (0-based)
    target: float  # cells


def generate_outlines(spec: PlanSpec, seed: int) -> Outlines:
    """A floor plan for ``spec``: room outlines and doors (walls and windows come later)."""
    rng = stream(seed, "plan")
    failures: Counter[str] = Counter()
    attempts = ATTEMPTS
    for attempt in range(ATTEMPTS):
        if attempt >= attempts:
            break
        if attempt % DRAWS == 0:  # new rooms and footprint now and then: some draws cannot work
            rooms = _draw_rooms(spec, rng)
            mask, origin = _footprint(spec, rooms, rng)
            # a big footprint costs more a try: fewer tries, so no plan takes minutes
            attempts = min(ATTEMPTS, max(DRAWS, WORK // max(int(mask.size), 1)))
            _fill(rooms, int(mask.sum()))
            hub = _hub(spec, rooms)
        labels = _slice(mask, list(range(len(rooms))), rooms, hub, rng)
        if labels is None:
            failures["the rooms did not divide the footprint"] += 1
            continue
        why = _problem(labels, mask, rooms, spec)
        if why is None:
            doors, why = _doors(labels, mask, rooms, spec, hub)
            if why is None:
                return _outlines(spec, rooms, labels, doors, origin, attempt + 1)
        failures[why] += 1
    worst, times = failures.most_common(1)[0]
    raise PlanError(
        f"{spec.path.name}: no floor plan found in {attempts} tries "
        f"({times} failed because {worst}); give the footprint more room or the rooms "
        f"wider area ranges"
    )


# -- drawing the rooms and the footprint ----------------------------------------------


def _draw_rooms(spec: PlanSpec, rng: np.random.Generator) -> list[_Room]:
    rooms = []
    for room_spec in spec.rooms:
        if room_spec.probability < 1.0 and rng.random() >= room_spec.probability:
            continue
        count = int(rng.integers(room_spec.count[0], room_spec.count[1] + 1))
        for index in range(count):
            area = (
                rng.uniform(*room_spec.area)
                if room_spec.area[1] > room_spec.area[0]
                else room_spec.area[0]
            )
            rooms.append(_Room(room_spec, index, area / (CELL * CELL)))
    if not rooms:
        rooms.append(_Room(spec.rooms[0], 0, spec.rooms[0].area[0] / (CELL * CELL)))
    return rooms


def _fill(rooms: list[_Room], cells: int) -> None:
    """Make the rooms' targets add up to the footprint's ``cells``: first within their
    area ranges (each moved towards its range's end in proportion to the room left
    there), then, if the ranges cannot, all scaled alike (the checks then judge)."""
    gap = cells - sum(room.target for room in rooms)
    ends = [(room.spec.area[1] if gap > 0 else room.spec.area[0]) / (CELL * CELL) for room in rooms]
    room_left = [end - room.target for room, end in zip(rooms, ends, strict=False)]
    total_left = sum(room_left)
    if total_left and gap / total_left > 0:
        share = min(1.0, gap / total_left)
        for room, left in zip(rooms, room_left, strict=False):
            room.target += share * left
    scale = cells / sum(room.target for room in rooms)
    for room in rooms:
        room.target *= scale


def _footprint(spec: PlanSpec, rooms: list[_Room], rng) -> tuple[np.ndarray, tuple[float, float]]:
    """The footprint's cells (row = z, column = x) and the world (x, z) of cell (0, 0)'s corner."""
    if spec.size is not None:
        (w_lo, w_hi), (d_lo, d_hi) = spec.size
        wanted = sum(room.target for room in rooms) * CELL * CELL
        width = rng.uniform(w_lo, w_hi) if w_hi > w_lo else w_lo
        depth = min(max(wanted / width, d_lo), d_hi)
        width = min(max(wanted / depth, w_lo), w_hi)
        columns = max(2, round(width / CELL))
        rows = max(2, round(depth / CELL))
        return np.ones((rows, columns), dtype=bool), (-columns * CELL / 2, -rows * CELL / 2)
    xs = [p[0] for p in spec.corners]
    zs = [p[1] for p in spec.corners]
    x0, z0 = math.floor(min(xs) / CELL) * CELL, math.floor(min(zs) / CELL) * CELL
    columns = math.ceil((max(xs) - x0) / CELL)
    rows = math.ceil((max(zs) - z0) / CELL)
    centres_x = x0 + (np.arange(columns) + 0.5) * CELL
    centres_z = z0 + (np.arange(rows) + 0.5) * CELL
    grid_x, grid_z = np.meshgrid(centres_x, centres_z)
    mask = points_in_polygon(spec.corners, grid_x, grid_z)
    for courtyard in spec.courtyards:
        mask &= ~points_in_polygon(courtyard, grid_x, grid_z)
    # centre the house on the origin
    cx, cz = (min(xs) + max(xs)) / 2.0, (min(zs) + max(zs)) / 2.0
    cx, cz = round(cx / CELL) * CELL, round(cz / CELL) * CELL
    return mask, (x0 - cx, z0 - cz)


def _hub(spec: PlanSpec, rooms: list[_Room]) -> int | None:
    """The room most others must connect to (the first of its type), if any must."""
    partners: Counter[str] = Counter()
    for connection in spec.connections:
        for other in connection.others:
            partners[connection.hub] += sum(1 for room in rooms if room.spec.type == other)
    if not partners:
        return None
    hub_type, count = partners.most_common(1)[0]
    if count < 2:
        return None
    return next((k for k, room in enumerate(rooms) if room.spec.type == hub_type), None)


# -- slicing ------------------------------------------------------------------------------


def _slice(mask: np.ndarray, members: list[int], rooms: list[_Room], hub, rng) -> np.ndarray | None:
    labels = np.full(mask.shape, -1, dtype=np.int32)
    return labels if _split(mask, members, rooms, hub, rng, labels) else None


def _split(mask, members, rooms, hub, rng, labels) -> bool:
    if not mask.any():
        return False
    if len(members) == 1:
        labels[mask] = members[0]
        return True
    rows, columns = np.nonzero(mask)
    height = rows.max() - rows.min() + 1
    width = columns.max() - columns.min() + 1
    long_axis = 1 if width >= height else 0  # 1: cut across columns (cut lines run along z)
    if hub in members and len(members) >= 3 and rng.random() < STRIP_CHANCE:
        others = [m for m in members if m != hub]
        order = [others[k] for k in rng.permutation(len(others))]
        cut = int(rng.integers(1, len(order))) if len(order) > 1 else 1
        groups = [order[:cut], [hub], order[cut:]]
        groups = [g for g in groups if g]
        # strips along the long side (cuts across the short one: a corridor the length of
        # the house) or, as often, across it (a hall the depth of the house)
        axis = 1 - long_axis if rng.random() < 0.5 else long_axis
    else:
        order = [members[k] for k in rng.permutation(len(members))]
        if hub in order:  # keep the hub's group first so it tends to stay central
            order.remove(hub)
            order.insert(int(rng.integers(0, len(order) + 1)), hub)
        cut = _balanced_cut(order, rooms, rng)
        groups = [order[:cut], order[cut:]]
        axis = long_axis if rng.random() < 0.85 else 1 - long_axis
    weights = [sum(rooms[m].target for m in g) for g in groups]
    if [hub] in groups and len(groups) > 1:
        pieces = _strips(mask, axis, groups, weights, rooms[hub], rng)
    else:
        pieces = _cut(mask, axis, weights, rng)
    if pieces is None:
        return False
    return all(
        _split(piece, group, rooms, hub, rng, labels)
        for piece, group in zip(pieces, groups, strict=False)
    )


def _balanced_cut(order: list[int], rooms: list[_Room], rng) -> int:
    """Where to split ``order`` in two: near half the area, with a little chance."""
    total = sum(rooms[m].target for m in order)
    running, best, best_gap = 0.0, 1, math.inf
    for k in range(1, len(order)):
        running += rooms[order[k - 1]].target
        gap = abs(running - total / 2.0) + rng.uniform(0.0, 0.25) * total
        if gap < best_gap:
            best, best_gap = k, gap
    return best


def _cut(mask: np.ndarray, axis: int, weights: list[float], rng) -> list[np.ndarray] | None:
    """``mask`` cut into ``len(weights)`` slabs along ``axis`` whose cell counts follow the weights."""
    counts = mask.sum(axis=1 - axis) if axis == 0 else mask.sum(axis=0)
    lines = np.nonzero(counts)[0]
    first, last = int(lines[0]), int(lines[-1])
    cumulative = np.cumsum(counts[first : last + 1])
    total = float(cumulative[-1])
    lines_of = mask if axis == 0 else mask.T
    # the lines after which the region's cross-section changes: where its outline steps
    features = [k for k in range(first, last) if not np.array_equal(lines_of[k], lines_of[k + 1])]
    pieces, start = [], first
    share = 0.0
    for k, weight in enumerate(weights[:-1]):
        share += weight / sum(weights)
        end = first + int(np.argmin(np.abs(cumulative - share * total)))
        near = [f for f in features if abs(f - end) <= SNAP_LINES]
        if near and rng.random() < SNAP_CHANCE:
            # cut along a corner of the footprint (a courtyard's edge, an L's inner
            # corner): the pieces then keep their width where the outline steps
            end = min(near, key=lambda f: (abs(f - end), f))
        elif rng.random() < 0.25:
            end += int(rng.choice((-1, 1)))
        end = min(max(end, start), last - (len(weights) - 2 - k) - 1)
        if end < start:
            return None
        pieces.append(_slab(mask, axis, start, end))
        start = end + 1
    pieces.append(_slab(mask, axis, start, last))
    return pieces


def _strips(mask, axis, groups, weights, hub: _Room, rng) -> list[np.ndarray] | None:
    """``mask`` cut into the slabs of ``groups`` with the hub's slab as thick as the hub's
    width needs (its area follows from the region's length, not from its target)."""
    counts = mask.sum(axis=1) if axis == 0 else mask.sum(axis=0)
    lines = np.nonzero(counts)[0]
    first, last = int(lines[0]), int(lines[-1])
    length = float(np.median(counts[first : last + 1]))
    thick = max(math.ceil(hub.spec.width / CELL - 1e-9), round(hub.target / max(length, 1.0)))
    thick += int(rng.random() < 0.3)
    if thick > last - first - 1:
        return None
    position = next(
        k for k, group in enumerate(groups) if len(group) == 1 and weights[k] == hub.target
    )
    before = sum(weights[:position])
    around = before + sum(weights[position + 1 :])
    cumulative = np.cumsum(counts[first : last + 1])
    free = float(cumulative[-1]) - thick * length
    if around <= 0 or free <= 0:
        return None
    start = (
        first + int(np.argmin(np.abs(cumulative - before / around * free))) + (1 if before else 0)
    )
    start = min(
        max(start, first + (1 if before else 0)),
        last - thick + 1 - (1 if position < len(groups) - 1 else 0),
    )
    end = start + thick - 1
    pieces = []
    if before:
        pieces.append(_slab(mask, axis, first, start - 1))
    pieces.append(_slab(mask, axis, start, end))
    if position < len(groups) - 1:
        pieces.append(_slab(mask, axis, end + 1, last))
    return pieces


def _slab(mask: np.ndarray, axis: int, start: int, end: int) -> np.ndarray:
    piece = np.zeros_like(mask)
    if axis == 0:
        piece[start : end + 1, :] = mask[start : end + 1, :]
    else:
        piece[:, start : end + 1] = mask[:, start : end + 1]
    return piece


# -- checks ---------------------------------------------------------------------------------


def _problem(
    labels: np.ndarray, mask: np.ndarray, rooms: list[_Room], spec: PlanSpec
) -> str | None:
    """Why this slicing is no floor plan, or None when every room is a good room. Each
    room is checked in the window of its bounding box (one cell more all round), the
    cheap checks first."""
    boxes = ndimage.find_objects(labels + 1)  # room k is label k + 1; outside (-1) is 0
    rows_all, columns_all = labels.shape
    for k, room in enumerate(rooms):
        words = room.spec.type.replace("_", " ")
        box = boxes[k] if k < len(boxes) else None
        if box is None:
            return f"a {words} got no floor"
        r0, r1 = max(box[0].start - 1, 0), min(box[0].stop + 1, rows_all)
        c0, c1 = max(box[1].start - 1, 0), min(box[1].stop + 1, columns_all)
        window, window_mask = labels[r0:r1, c0:c1], mask[r0:r1, c0:c1]
        cells = window == k
        count = int(cells.sum())
        area = count * CELL * CELL
        lo, hi = room.spec.area
        if room.spec.type in CIRCULATION:  # as long as the rooms along it need
            hi = max(hi, lo) * 2.0
        if not lo * (1 - AREA_SLACK) <= area <= hi * (1 + AREA_SLACK):
            return f"a {words} came out {area:g} m², outside {lo:g}..{hi:g} m²"
        h = box[0].stop - box[0].start
        w = box[1].stop - box[1].start
        if room.spec.type not in CIRCULATION and (
            max(h, w) > MAX_ASPECT * min(h, w) or count < MIN_FILL * h * w
        ):
            return f"a {words} came out too long and thin"
        if (
            ndimage.label(cells)[1] != 1
            or not np.array_equal(ndimage.binary_fill_holes(cells), cells)
            or _pinched(cells)
        ):
            return f"a {words} came out in pieces or round a hole"
        side = max(1, math.ceil(room.spec.width / CELL - 1e-9))
        square = np.ones((side, side), dtype=bool)
        if not np.array_equal(ndimage.binary_opening(cells, structure=square), cells):
            return f"a {words} came out narrower than {room.spec.width:g} m"
        if room.spec.wants_window and _longest_outside(window, window_mask, k) < WINDOW_RUN:
            return f"a {words} has no outside wall for its window"
    return None


def _pinched(cells: np.ndarray) -> bool:
    """Whether two cells of the piece touch at a corner only (its outline would cross itself)."""
    a, b, c, d = cells[:-1, :-1], cells[:-1, 1:], cells[1:, :-1], cells[1:, 1:]
    return bool(((a & d & ~b & ~c) | (b & c & ~a & ~d)).any())


def _runs(labels: np.ndarray, mask: np.ndarray) -> dict[tuple[int, int], int]:
    """The longest straight shared wall (cells) between each pair of neighbouring rooms;
    the pair ``(k, -1)`` for room k's walls to the outside."""
    padded = np.pad(np.where(mask, labels, -1), 1, constant_values=-1)
    longest: dict[tuple[int, int], int] = {}
    for axis in (0, 1):
        a = padded[:-1, :] if axis == 0 else padded[:, :-1]
        b = padded[1:, :] if axis == 0 else padded[:, 1:]
        differs = a != b
        # walk each grid line, counting consecutive edges between the same pair
        lines = differs if axis == 0 else differs.T
        first = a if axis == 0 else a.T
        second = b if axis == 0 else b.T
        for row in range(lines.shape[0]):
            run_pair, run = None, 0
            for column in range(lines.shape[1]):
                if lines[row, column]:
                    x, y = int(first[row, column]), int(second[row, column])
                    pair = (max(x, y), min(x, y)) if min(x, y) == -1 else (min(x, y), max(x, y))
                    run = run + 1 if pair == run_pair else 1
                    run_pair = pair
                    if run > longest.get(pair, 0):
                        longest[pair] = run
                else:
                    run_pair, run = None, 0
    return longest


def _longest_outside(labels: np.ndarray, mask: np.ndarray, k: int) -> int:
    return _runs(np.where(labels == k, k, -2), mask | (labels == k)).get((k, -1), 0)


def _doors(labels, mask, rooms: list[_Room], spec: PlanSpec, hub):
    """The doors: the plan's connections, the front door, and doors that make every room
    reachable; or why there can be none."""
    runs = _runs(labels, mask)

    def run(a: int, b: int) -> int:
        return runs.get((min(a, b), max(a, b)), 0)

    doors: list[tuple[int, ...]] = []
    opens: set[tuple[int, int]] = set()
    joined: set[tuple[int, int]] = set()
    for connection in spec.connections:
        hubs = [k for k, r in enumerate(rooms) if r.spec.type == connection.hub]
        for other_type in connection.others:
            for k, room in enumerate(rooms):
                if room.spec.type != other_type:
                    continue
                choices = [h for h in hubs if h != k and run(h, k) >= DOOR_RUN]
                if not choices and hubs:
                    words = connection.hub.replace("_", " ")
                    return [], f"a {room.spec.type.replace('_', ' ')} does not touch a {words}"
                if not choices:
                    continue
                best = max(choices, key=lambda h: (run(h, k), -h))
                pair = (min(best, k), max(best, k))
                if pair not in joined:
                    joined.add(pair)
                    doors.append(pair)
                    if connection.open:
                        opens.add(pair)
    entrance = next((k for k, r in enumerate(rooms) if r.spec.entrance), None)
    if entrance is None:
        entrance = next((k for k, r in enumerate(rooms) if r.spec.type in CIRCULATION), 0)
    if runs.get((entrance, -1), 0) < WINDOW_RUN:
        return (
            [],
            f"the {rooms[entrance].spec.type.replace('_', ' ')} has no outside wall for the front door",
        )
    reached = _reached(entrance, joined)
    while len(reached) < len(rooms):
        best_pair, best_key = None, None
        for k in range(len(rooms)):
            if k in reached:
                continue
            for r in reached:
                length = run(k, r)
                if length < DOOR_RUN:
                    continue
                kind = rooms[r].spec.type
                key = (kind in CIRCULATION, r == hub, kind == "living_room", length, -r, -k)
                if best_key is None or key > best_key:
                    best_pair, best_key = (min(k, r), max(k, r)), key
        if best_pair is None:
            return [], "a room cannot be reached through doors"
        joined.add(best_pair)
        doors.append(best_pair)
        reached = _reached(entrance, joined)
    planned = [(entrance,)] + doors
    return [(pair, pair in opens) for pair in planned], None


def _reached(start: int, joined: set[tuple[int, int]]) -> set[int]:
    seen, todo = {start}, [start]
    while todo:
        room = todo.pop()
        for a, b in joined:
            for here, there in ((a, b), (b, a)):
                if here == room and there not in seen:
                    seen.add(there)
                    todo.append(there)
    return seen


# -- outlines -------------------------------------------------------------------------------


def _outlines(spec, rooms, labels, doors, origin, attempts: int) -> Outlines:
    ids = _room_ids(rooms)
    names = _room_names(rooms)
    planned = [
        PlannedRoom(
            id=ids[k],
            type=room.spec.type,
            name=names[k],
            rules=room.spec.rules,
            outline=trace(labels == k, origin),
            wants_window=room.spec.wants_window or room.spec.type not in CIRCULATION,
            width=room.spec.width,
            window=room.spec.window,
        )
        for k, room in enumerate(rooms)
    ]
    footprint_mask = labels >= 0
    holes = []
    filled = ndimage.binary_fill_holes(footprint_mask)
    hole_labels, count = ndimage.label(filled & ~footprint_mask)
    for h in range(1, count + 1):
        holes.append(trace(hole_labels == h, origin))
    return Outlines(
        noun=spec.noun,
        footprint=trace(filled, origin),
        holes=tuple(holes),
        height=spec.height,
        rooms=planned,
        doors=[
            PlannedDoor(rooms=tuple(ids[k] for k in pair), open=is_open) for pair, is_open in doors
        ],
        notes={"attempts": attempts, "cell": CELL},
    )


def _room_ids(rooms: list[_Room]) -> list[str]:
    return [f"{room.spec.type}_{room.index + 1}" for room in rooms]


def _room_names(rooms: list[_Room]) -> list[str]:
    from scenewright.describer.english import ordinal_word

    counts = Counter(room.spec.type for room in rooms)
    return [
        f"{ordinal_word(room.index + 1)} {room.spec.name}"
        if counts[room.spec.type] > 1
        else room.spec.name
        for room in rooms
    ]


def trace(cells: np.ndarray, origin: tuple[float, float]) -> tuple[tuple[float, float], ...]:
    """The outline of one simply connected piece of cells: its corners in order (world x, z)."""
    rows, columns = cells.shape
    padded = np.pad(cells, 1)
    edges: dict[tuple[int, int], tuple[int, int]] = {}
    # Directed edges with the cells on their left, as (column, row) grid points.
    for i, j in zip(*np.nonzero(cells), strict=False):
        i, j = int(i), int(j)
        if not padded[i, j + 1]:  # nothing above (row i - 1)
            edges[(j + 1, i)] = (j, i)
        if not padded[i + 2, j + 1]:  # nothing below
            edges[(j, i + 1)] = (j + 1, i + 1)
        if not padded[i + 1, j]:  # nothing to the left
            edges[(j, i)] = (j, i + 1)
        if not padded[i + 1, j + 2]:  # nothing to the right
            edges[(j + 1, i + 1)] = (j + 1, i)
    start = min(edges)
    loop = [start]
    point = edges[start]
    while point != start:
        loop.append(point)
        point = edges[point]
    corners = [
        p
        for k, p in enumerate(loop)
        if (loop[k - 1][0] == p[0]) != (p[0] == loop[(k + 1) % len(loop)][0])
    ]
    return tuple((origin[0] + c * CELL, origin[1] + r * CELL) for c, r in corners)
