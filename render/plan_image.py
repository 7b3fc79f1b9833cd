"""A top-down plan image of a laid-out scene, drawn with Pillow on a ``plan_page.PlanPage``.

North (-Z) is up and east (+X) right, as on a map. Drawn: the scene extent, or in a
room its walls (grey, their true thickness behind the inner faces, mitred at the corners
as the renderer builds them), its doors (a gap with the leaf swung open into the room
and its swing arc) and windows (pale blue across the wall); paths as lines of their true
width with their control points; junctions; every object's rotated footprint with a
tick from its centre towards its forward side; ids as labels; and a red dashed line
between the two ends of each relation the layout did not satisfy (a wall, door or
window at its inner face's middle; "the room" at the wall the layout chose).

A house (``scene.house``) is drawn as its walls, each once at its true thickness on its
centre line (``render.house_view``), its doors (an open doorway a gap alone) and windows
under the house's ids (``door_3``), each room's name written in the room ("second
bedroom", ``room_labels``, placed before any other label), and its objects' footprints
labelled with their ids within their room (``bed_1``).

Labels never cover one another (``place_labels``): each goes at its anchor or just
beside it, wherever it first finds room, in order of importance (the unsatisfied
relations, then paths, then the objects those relations name, then the other objects,
largest first); one that finds no room is left out, and the title says how many were.
The picture grows with the number of labels (``figure_inches``), so a 300-object town
still names most of its objects at a readable size.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from scenewright.core.frames import forward
from scenewright.core.house import ID_SEPARATOR, House, in_room
from scenewright.core.room import ROOM_NODE, WALL_THICKNESS, Room
from scenewright.core.scene import Scene, object_corners
from scenewright.render.house_view import inward_normal, wall_openings, wall_reach
from scenewright.render.meshes import wall_footprint
from scenewright.render.plan_page import DPI, POINT, PlanPage, text_box

#: The picture's larger side in inches (of ``plan_page.DPI`` pixels): ``BASE_INCHES``
#: up to ``BASE_LABELS`` labels, growing with the square root of their number (so their
#: density on the page stays the same) up to ``MAX_INCHES``.
BASE_INCHES = 9.0
BASE_LABELS = 60
MAX_INCHES = 24.0
#: Where a label may go, tried in turn: on its anchor, then above, below, right and
#: left of it (in points, y up; the anchor is the text's centre).
LABEL_OFFSETS = ((0, 0), (0, 7), (0, -7), (14, 0), (-14, 0), (10, 7), (-10, 7), (10, -7), (-10, -7))
#: Label ranks: lower goes first (see the module docstring).
ROOM_NAME, RELATION, PATH, INVOLVED, OBJECT = range(5)
#: Greys of the walls and the doors' leaves.
WALL_FILL, WALL_EDGE, LEAF, ARC = "#737373", "#404040", "#333333", "#4d4d4d"


@dataclass
class Label:
    """A text to place near ``anchor`` (data x, z); lower ``rank`` first, and within a
    rank larger ``weight`` first."""

    text: str
    anchor: tuple[float, float]
    rank: int
    weight: float = 0.0
    size: float = 5.0
    colour: str = "black"


def draw_plan(scene: Scene, path) -> Path:
    """Write the scene's top-down plan to ``path`` (PNG) and return the path."""
    width, depth = scene.extent
    unsatisfied = [relation for relation in scene.relations if not relation.satisfied]
    involved = {relation.source for relation in unsatisfied} | {
        relation.target for relation in unsatisfied
    }
    margin = 0.05 * max(width, depth)
    if scene.room is not None or scene.house is not None:  # walls and openings' labels
        margin = max(margin, WALL_THICKNESS + 0.5)
    # A house lies where its footprint is (a given plan need not be centred).
    x0, z0 = -width / 2, -depth / 2
    if scene.house is not None:
        x0 = min(x for x, _z in scene.house.footprint)
        z0 = min(z for _x, z in scene.house.footprint)
    inches = figure_inches(len(scene.objects) + len(scene.paths) + len(unsatisfied))
    page = PlanPage(
        (x0 - margin, x0 + width + margin), (z0 - margin, z0 + depth + margin), inches * DPI
    )
    labels: list[Label] = []
    for road in scene.paths:  # under everything else
        page.line(road.points, road.colour, metres_wide=road.width, alpha=0.8)
        page.dots(road.points, 1.2, "black")
        end = road.points[-1]
        labels.append(Label(road.id, (end[0], end[1]), PATH, size=7, colour="saddlebrown"))
    if scene.house is not None:
        labels += _draw_house(page, scene.house)
    elif scene.room is None:
        page.polygon(
            [
                (-width / 2, -depth / 2),
                (width / 2, -depth / 2),
                (width / 2, depth / 2),
                (-width / 2, depth / 2),
            ],
            None,
            "black",
            width=1.5,
        )
    else:
        labels += _draw_room(page, scene.room)
    centres = {}
    ticks = []
    footprints = [obj for obj in scene.objects if obj.kind != "group"]
    corners = dict(zip([o.id for o in footprints], object_corners(footprints), strict=True))
    # Things standing on others go over them.
    for obj in sorted(footprints, key=lambda o: o.position[1] > 1e-6):
        if obj.kind == "junction":
            page.polygon(corners[obj.id], "tan", "saddlebrown", width=1.0)
            continue
        page.polygon(corners[obj.id], obj.colour, "black", width=0.6, alpha=0.9)
        reach = obj.size[2] / 2.0
        x, z = obj.position[0], obj.position[2]
        fx, fz = forward(obj.yaw)
        ticks.append([(x, z), (x + fx * reach, z + fz * reach)])
    for tick in ticks:
        page.line(tick, "black", 0.8)
    for obj in scene.objects:
        centres[obj.id] = (obj.position[0], obj.position[2])
        if obj.kind in ("group", "junction"):
            continue
        rank = INVOLVED if obj.id in involved else OBJECT
        # In a house the room's name is written in it: an object goes by its own id there.
        text = obj.id.partition(ID_SEPARATOR)[2] if scene.house is not None else obj.id
        weight = obj.size[0] * obj.size[2]
        labels.append(Label(text or obj.id, centres[obj.id], rank, weight=weight))
    for road in scene.paths:
        mid = road.points[len(road.points) // 2]
        centres[road.id] = (mid[0], mid[1])
    if scene.room is not None:
        for wall in scene.room.walls:
            centres[wall.id] = wall.to_world(wall.length / 2.0, 0.0)
        for opening in scene.room.openings:
            centres[opening.id] = opening.center
    if scene.house is not None:  # a room's walls and openings, as its relations name them
        for house_room in scene.house.rooms:
            for wall in house_room.room.walls:
                point = wall.to_world(wall.length / 2.0, 0.0)
                centres[in_room(house_room.id, wall.id)] = house_room.to_house(*point)
            for opening in house_room.room.openings:
                centres[in_room(house_room.id, opening.id)] = house_room.to_house(*opening.center)
    for relation in unsatisfied:
        target = (
            relation.chosen if relation.target == ROOM_NODE and relation.chosen else relation.target
        )
        if relation.source not in centres or target not in centres:
            continue
        (sx, sz), (tx, tz) = centres[relation.source], centres[target]
        page.line([(sx, sz), (tx, tz)], "red", 1.2, style="dashed")
        labels.append(
            Label(relation.label, ((sx + tx) / 2, (sz + tz) / 2), RELATION, size=6, colour="red")
        )
    left_out = len(labels) - place_labels(page, labels)
    status = "ok" if scene.layout.ok else f"{len(scene.layout.problems)} problems"
    crowded = f"  ({left_out} of {len(labels)} labels left out: no room)" if left_out else ""
    title = f"{scene.rules}  seed {scene.seed}  energy {scene.layout.energy:.2f}  {status}{crowded}"
    return page.save(Path(path), title, "x (east) [m]", "z (south) [m]")


def figure_inches(labels: int) -> float:
    """The picture's larger side for a plan with this many labels (see ``BASE_INCHES``)."""
    return min(MAX_INCHES, BASE_INCHES * max(1.0, math.sqrt(labels / BASE_LABELS)))


def place_labels(page: PlanPage, labels: list[Label]) -> int:
    """Place the labels that find room on ``page``, each at the first of
    ``LABEL_OFFSETS`` from its anchor where its box overlaps no label placed before and
    stays inside the plot, in order of rank and then weight; return how many were."""
    taken = _BoxGrid()
    placed = 0
    for label in sorted(labels, key=lambda label: (label.rank, -label.weight)):
        ax, ay = page.anchor(*label.anchor)
        centred = text_box(label.text, label.size).translated(ax, ay)  # measured once, then moved
        for dx, dy in LABEL_OFFSETS:
            box = centred.translated(dx * POINT, -dy * POINT)
            if box.within(page.plot) and not taken.overlaps(box):
                page.place(label.text, box, label.colour, label.size)
                taken.add(box)
                placed += 1
                break
    return placed


class _BoxGrid:
    """Boxes on the page (pixels), kept in square cells so that a new box is compared
    with its neighbours only (a plan may have hundreds of labels)."""

    CELL = 40.0

    def __init__(self) -> None:
        self.cells: dict[tuple[int, int], list] = {}

    def _cells(self, box):
        for i in range(int(box.x0 // self.CELL), int(box.x1 // self.CELL) + 1):
            for j in range(int(box.y0 // self.CELL), int(box.y1 // self.CELL) + 1):
                yield i, j

    def overlaps(self, box) -> bool:
        return any(
            box.overlaps(other) for cell in self._cells(box) for other in self.cells.get(cell, ())
        )

    def add(self, box) -> None:
        for cell in self._cells(box):
            self.cells.setdefault(cell, []).append(box)


def _draw_room(page: PlanPage, room: Room) -> list[Label]:
    """The room's walls, doors and windows (see the module docstring); returns the
    openings' labels."""
    labels = []
    for wall in room.walls:
        page.polygon(wall_footprint(room, wall), WALL_FILL, WALL_EDGE, width=0.6)
    for opening in room.openings:
        wall = room.part(opening.wall)
        u0, u1 = opening.span
        thickness = WALL_THICKNESS
        hole = [
            wall.to_world(u0, 0.0),
            wall.to_world(u1, 0.0),
            wall.to_world(u1, -thickness),
            wall.to_world(u0, -thickness),
        ]
        if opening.kind == "window":
            page.polygon(hole, "lightblue", "steelblue", width=0.6)
            mid = [wall.to_world(u0, -thickness / 2.0), wall.to_world(u1, -thickness / 2.0)]
            page.line(mid, "steelblue", 0.6)
        else:
            page.polygon(hole, "white")
            # The leaf hinged at the opening's start, swung open into the room, and its arc.
            arc = [
                wall.to_world(u0 + opening.width * math.cos(a), opening.width * math.sin(a))
                for a in np.linspace(0.0, math.pi / 2.0, 16)
            ]
            page.line(arc, ARC, 0.6, style="dotted")
            page.line([wall.to_world(u0, 0.0), wall.to_world(u0, opening.width)], LEAF, 1.2)
        x, z = wall.to_world(opening.offset, -thickness - 0.15)
        labels.append(Label(opening.id, (x, z), PATH, colour=LEAF))
    return labels


def _draw_house(page: PlanPage, house: House) -> list[Label]:
    """A house's walls (each once, its true thickness on its centre line), doors (a gap,
    the leaf swung open into the door's first room and its arc; an open doorway a gap
    alone) and windows; returns the room names' and the openings' labels."""
    labels = room_labels(house)
    holes = wall_openings(house)
    for index, wall in enumerate(house.walls):
        (sx, sz), (ex, ez) = wall.start, wall.end
        length = max(wall.length, 1e-12)
        dx, dz = (ex - sx) / length, (ez - sz) / length
        nx, nz = -dz * wall.thickness / 2.0, dx * wall.thickness / 2.0
        before, after = wall_reach(house, index)
        a = (sx - dx * before, sz - dz * before)
        b = (ex + dx * after, ez + dz * after)
        corners = [
            (a[0] + nx, a[1] + nz),
            (b[0] + nx, b[1] + nz),
            (b[0] - nx, b[1] - nz),
            (a[0] - nx, a[1] - nz),
        ]
        page.polygon(corners, WALL_FILL, WALL_EDGE, width=0.6)
    for index, wall in enumerate(house.walls):  # over every wall, as a gap in its own
        for opening, _u in holes[index]:
            _draw_house_opening(page, house, opening, wall.thickness)
            labels.append(Label(opening.id, opening.center, PATH, colour=LEAF))
    return labels


def _draw_house_opening(page: PlanPage, house: House, opening, thickness: float) -> None:
    (cx, cz), (dx, dz), w = opening.center, opening.direction, opening.width
    end = (cx + dx, cz + dz)
    nx, nz = inward_normal(house, opening.center, end, opening.rooms[0])

    def at(u: float, v: float) -> tuple[float, float]:  # along the wall, into the first room
        return cx + u * dx + v * nx, cz + u * dz + v * nz

    half = thickness / 2.0
    hole = [at(-w / 2, half), at(w / 2, half), at(w / 2, -half), at(-w / 2, -half)]
    if opening.kind == "window":
        page.polygon(hole, "lightblue", "steelblue", width=0.6)
        page.line([at(-w / 2, 0.0), at(w / 2, 0.0)], "steelblue", 0.6)
        return
    page.polygon(hole, "white")
    if opening.open:
        return
    arc = [
        at(-w / 2 + w * math.cos(angle), half + w * math.sin(angle))
        for angle in np.linspace(0.0, math.pi / 2.0, 16)
    ]
    page.line(arc, ARC, 0.6, style="dotted")
    page.line([at(-w / 2, half), at(-w / 2, half + w)], LEAF, 1.2)


def room_labels(house: House) -> list[Label]:
    """Each room's name ("second bedroom"), written at the point of its floor farthest
    from its walls (the middle of a rectangle; inside an L-shaped room's wider arm)."""
    return [
        Label(room.name, _inner_point(room.outline), ROOM_NAME, size=9, colour="navy")
        for room in house.rooms
    ]


def _inner_point(outline) -> tuple[float, float]:
    """The point of a grid over ``outline`` (x, z) inside it and farthest from its edges."""
    points = np.asarray(outline, dtype=float)
    lo, hi = points.min(axis=0), points.max(axis=0)
    steps = np.linspace(0.0, 1.0, 23)[1:-1]
    grid = np.array(
        [(lo[0] + a * (hi[0] - lo[0]), lo[1] + b * (hi[1] - lo[1])) for a in steps for b in steps]
    )
    starts, ends = points, np.roll(points, -1, axis=0)
    edge = ends - starts
    along = np.clip(
        np.einsum("gek,ek->ge", grid[:, None, :] - starts[None], edge)
        / np.maximum(np.einsum("ek,ek->e", edge, edge), 1e-12),
        0.0,
        1.0,
    )
    nearest = starts[None] + along[..., None] * edge[None]
    distance = np.linalg.norm(grid[:, None, :] - nearest, axis=2).min(axis=1)
    z0, z1 = starts[:, 1], ends[:, 1]
    crossing = (z0[None] > grid[:, 1:2]) != (z1[None] > grid[:, 1:2])
    with np.errstate(divide="ignore", invalid="ignore"):
        x_cross = (
            starts[None, :, 0] + (grid[:, 1:2] - z0[None]) * edge[None, :, 0] / edge[None, :, 1]
        )
    inside = (crossing & (grid[:, :1] < x_cross)).sum(axis=1) % 2 == 1
    if not inside.any():
        return float(points[:, 0].mean()), float(points[:, 1].mean())
    best = int(np.argmax(np.where(inside, distance, -1.0)))
    return float(grid[best, 0]), float(grid[best, 1])
