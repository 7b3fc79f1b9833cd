"""Where a completed room's layout starts (step 4 of ``complete``): the pieces that stand
against a wall go, largest first, to the place along the walls whose footprint covers
the most of the layout mask, clear of the door swings and of what is already placed;
tables stand free with room for their chairs round them; accessories (what stands on or
at a piece) where the plans put them by their started anchors
(``accessories.slot_pose``), flat pieces before what they lie before. The mask is in
the room's door-aware canonical frame; ``layout_mask.mask_at`` reads it at room
positions. Nothing here draws a random number.
"""

from __future__ import annotations

import math

import numpy as np

from scenewright.core.geometry import corners, make_rect, rect_overlap, wrap_angle
from scenewright.core.poses import Pose
from scenewright.core.room import ROOM_NODE, Room
from scenewright.core.scene_graph import SceneGraph

from .accessories import Placement, slot_pose

#: Starting poses: the step along a wall between candidate places (metres), the samples
#: per side of a footprint read from the mask, the gap kept to a wall.
WALL_STEP = 0.1
FOOTPRINT_SAMPLES = 5
WALL_GAP = 0.02
#: Pieces at most this tall (metres) lie flat: a rug. The selection counts no floor for
#: them (plans lay rugs under furniture) but the layout keeps every piece apart, so one
#: the starting poses find no free floor for is left out rather than failing the layout.
FLAT = 0.02


def starting_poses(
    graph: SceneGraph, room: Room, mask, placements: dict[str, Placement] | None = None
) -> dict[str, Pose]:
    """Poses for the pieces that stand against a wall (``AgainstWall``, ``UnderWindow``
    to the room), those under a window first, then the largest first: each at the place along the walls whose footprint
    covers most of the layout ``mask`` and whose footprint and clearance are clear of the
    door swings, the room's outline and the pieces already placed. Under a window a
    piece goes to the window's middle. What flanks a piece along its wall (night tables
    ``BesideLeft``/``BesideRight`` of the bed) is placed with it, one unit. Then the
    free-standing tables, the accessories (``placements``: node id -> its
    ``accessories.Placement``, the anchor a node id) by their started anchors, and
    what stands in front of a started piece."""
    placements = placements or {}
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
        if relation.label in ("BesideLeft", "BesideRight") and relation.target in wall_of:
            flanks.setdefault(relation.target, []).append(
                (relation.source, -1.0 if relation.label == "BesideLeft" else 1.0)
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
    _start_tables(graph, room, mask, poses, placed, swings, placements)
    _start_accessories(graph, room, poses, placed, swings, placements)
    _start_in_front(graph, room, poses, placed, swings)
    return poses


def _start_tables(
    graph: SceneGraph,
    room: Room,
    mask,
    poses: dict,
    placed: dict,
    swings: list,
    placements: dict[str, Placement],
) -> None:
    """Start a free-standing piece (no relation of its own, not flat: a table the plans
    show standing free, ``stances.FREE``) where
    it and a ring as deep as what stands at it (its chairs) cover most of the mask,
    inside the room and clear of the rest."""
    from scenewright.completion.layout_mask import mask_values

    sources = {r.source for r in graph.edges()}
    for table in graph.nodes("object"):
        if table.id in sources or table.id in poses or table.size[1] <= FLAT:
            continue
        seats = [box for box, at in placements.items() if at.anchor == table.id and not at.on]
        ring = max((graph.node(seat).size[2] for seat in seats), default=0.3) + 2 * WALL_GAP
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
        for k in order:
            (x, z), yaw = grid[k % len(grid)], (0.0, math.pi / 2.0)[k // len(grid)]
            rect = make_rect(x, z, width + 2 * ring, depth + 2 * ring, yaw)
            if room.footprint_excess(corners(rect)) > 1e-6:
                continue
            if any(rect_overlap(rect, other) > 1e-6 for other in swings + list(placed.values())):
                continue
            placed[table.id] = rect
            poses[table.id] = Pose(float(x), 0.0, float(z), yaw)
            break


def _start_accessories(
    graph: SceneGraph,
    room: Room,
    poses: dict,
    placed: dict,
    swings: list,
    placements: dict[str, Placement],
) -> None:
    """Start each accessory not yet started whose anchor is at its slot
    (``accessories.slot_pose``): on its top, or beside it where the footprint is
    inside the room and clear of the door ``swings`` and the ``placed`` pieces (but its
    anchor's: a chair stands in the space kept free before its desk, or in the ring
    kept round its table). An anchor started here starts what stands on or at it."""
    waiting = [box for box in placements if box not in poses]
    while waiting:
        started = False
        for box in list(waiting):
            at = placements[box]
            anchor = poses.get(at.anchor)
            if anchor is None:
                continue
            waiting.remove(box)
            node, target = graph.node(box), graph.node(at.anchor)
            pose = slot_pose(
                at, anchor, (target.size[0], target.size[2]), (node.size[0], node.size[2])
            )
            if not at.on:
                rect = make_rect(pose.x, pose.z, node.size[0], node.size[2], pose.yaw)
                others = swings + [other for key, other in placed.items() if key != at.anchor]
                if room.footprint_excess(corners(rect)) > 1e-6 or any(
                    rect_overlap(rect, other) > 1e-6 for other in others
                ):
                    continue
                placed[box] = rect
            poses[box] = pose
            started = True
        if not started:
            break


def _start_in_front(graph: SceneGraph, room: Room, poses: dict, placed: dict, swings: list) -> None:
    """Start what stands ``NextToFront`` of a started piece (a chair at its desk, a rug
    before the bed, a coffee table before the sofa) just in front of it, turned to it
    when it also faces it, where that is inside the room and clear of the door
    ``swings`` and the ``placed`` pieces' footprints and clearances (but its own
    piece's: a chair stands in the space kept free before its desk)."""
    from scenewright.completion.activity import SEATS

    seated = graph.edges("SeatedAt")  # a seat at its desk: in front of it, facing it
    facing = {(r.source, r.target) for r in [*graph.edges("FacingTowards"), *seated]}
    for relation in [*graph.edges("NextToFront"), *seated]:
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
