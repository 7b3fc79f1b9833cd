"""A top-down plan image of a laid-out scene (matplotlib, Agg backend, no display).

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

# A Figure of its own, not pyplot: pyplot's figure manager and backend machinery cost a
# noticeable part of a command's start-up and are not needed to save a PNG.
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure
from matplotlib.patches import Polygon, Rectangle
from matplotlib.patheffects import withStroke

from scenewright.core.frames import forward
from scenewright.core.house import ID_SEPARATOR, House, in_room
from scenewright.core.room import ROOM_NODE, WALL_THICKNESS, Room
from scenewright.core.scene import Scene, object_corners
from scenewright.render.house_view import inward_normal, wall_openings, wall_reach
from scenewright.render.meshes import wall_footprint

#: Pixels per inch of the saved image.
DPI = 110
#: The picture's larger side in inches: ``BASE_INCHES`` up to ``BASE_LABELS`` labels,
#: growing with the square root of their number (so their density on the page stays
#: the same) up to ``MAX_INCHES``.
BASE_INCHES = 9.0
BASE_LABELS = 60
MAX_INCHES = 24.0
#: Where a label may go, tried in turn: on its anchor, then above, below, right and
#: left of it (in points; the anchor is the text's centre).
LABEL_OFFSETS = ((0, 0), (0, 7), (0, -7), (14, 0), (-14, 0), (10, 7), (-10, 7), (10, -7), (-10, -7))
#: A thin light outline around every label's letters.
HALO = withStroke(linewidth=1.5, foreground="white", alpha=0.8)
#: Label ranks: lower goes first (see the module docstring).
ROOM_NAME, RELATION, PATH, INVOLVED, OBJECT = range(5)


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
    labels: list[Label] = []
    size = figure_inches(len(scene.objects) + len(scene.paths) + len(unsatisfied))
    # At the saved resolution from the start: the label boxes are measured as saved.
    figure = Figure(figsize=(size, size * depth / width + 0.6), dpi=DPI)
    FigureCanvasAgg(figure)  # label sizes are measured with the Agg renderer
    axes = figure.subplots()
    axes.set_aspect("equal")
    # Data y is z; inverting the axis puts north (-Z) at the top of the picture.
    if scene.house is not None:
        labels += _draw_house(axes, scene.house)
    elif scene.room is None:
        axes.add_patch(
            Rectangle((-width / 2, -depth / 2), width, depth, fill=False, lw=1.5, ec="black")
        )
    else:
        labels += _draw_room(axes, scene.room)
    points_per_metre = _points_per_metre(figure, axes, width, depth)
    for road in scene.paths:
        xs = [p[0] for p in road.points]
        zs = [p[1] for p in road.points]
        axes.plot(
            xs,
            zs,
            color=road.colour,
            lw=road.width * points_per_metre,
            solid_capstyle="round",
            alpha=0.8,
            zorder=1,
        )
        axes.plot(xs, zs, "k.", ms=3, zorder=2)
        labels.append(Label(road.id, (xs[-1], zs[-1]), PATH, size=7, colour="saddlebrown"))
    centres = {}
    for obj in scene.objects:
        centres[obj.id] = (obj.position[0], obj.position[2])
        if obj.kind == "group":
            continue
        corners = object_corners([obj])[0]
        if obj.kind == "junction":
            axes.add_patch(
                Polygon(corners, closed=True, fc="tan", ec="saddlebrown", lw=1, zorder=2)
            )
            continue
        stacked = obj.position[1] > 1e-6
        axes.add_patch(
            Polygon(
                corners,
                closed=True,
                fc=obj.colour,
                ec="black",
                lw=0.6,
                alpha=0.9,
                zorder=4 if stacked else 3,
            )
        )
        reach = obj.size[2] / 2.0
        x, z = obj.position[0], obj.position[2]
        fx, fz = forward(obj.yaw)
        axes.plot([x, x + fx * reach], [z, z + fz * reach], color="black", lw=0.8, zorder=5)
        rank = INVOLVED if obj.id in involved else OBJECT
        # In a house the room's name is written in it: an object goes by its own id there.
        text = obj.id.partition(ID_SEPARATOR)[2] if scene.house is not None else obj.id
        labels.append(Label(text or obj.id, (x, z), rank, weight=obj.size[0] * obj.size[2]))
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
        axes.plot([sx, tx], [sz, tz], color="red", lw=1.2, ls="--", zorder=7)
        labels.append(
            Label(relation.label, ((sx + tx) / 2, (sz + tz) / 2), RELATION, size=6, colour="red")
        )
    margin = 0.05 * max(width, depth)
    if scene.room is not None or scene.house is not None:  # walls and openings' labels
        margin = max(margin, WALL_THICKNESS + 0.5)
    # A house lies where its footprint is (a given plan need not be centred).
    x0, z0 = -width / 2, -depth / 2
    if scene.house is not None:
        x0 = min(x for x, _z in scene.house.footprint)
        z0 = min(z for _x, z in scene.house.footprint)
    axes.set_xlim(x0 - margin, x0 + width + margin)
    axes.set_ylim(z0 + depth + margin, z0 - margin)
    axes.set_xlabel("x (east) [m]")
    axes.set_ylabel("z (south) [m]")
    left_out = len(labels) - place_labels(axes, labels)
    status = "ok" if scene.layout.ok else f"{len(scene.layout.problems)} problems"
    crowded = f"  ({left_out} of {len(labels)} labels left out: no room)" if left_out else ""
    axes.set_title(
        f"{scene.rules}  seed {scene.seed}  energy {scene.layout.energy:.2f}  {status}{crowded}",
        fontsize=9,
    )
    target = Path(path)
    figure.savefig(target, dpi=DPI, bbox_inches="tight")
    return target


def figure_inches(labels: int) -> float:
    """The picture's larger side for a plan with this many labels (see ``BASE_INCHES``)."""
    return min(MAX_INCHES, BASE_INCHES * max(1.0, math.sqrt(labels / BASE_LABELS)))


def place_labels(axes, labels: list[Label]) -> int:
    """Draw the labels that find room, each at the first of ``LABEL_OFFSETS`` from its
    anchor where its box overlaps no label drawn before and stays inside the axes, in
    order of rank and then weight; return how many were drawn. The axes' limits and
    aspect must be final (the boxes are measured on the page)."""
    renderer = axes.figure.canvas.get_renderer()
    axes.apply_aspect()
    inside = axes.get_window_extent(renderer)
    points = axes.figure.dpi / 72.0  # pixels per point
    taken = _BoxGrid()
    placed = 0
    for label in sorted(labels, key=lambda label: (label.rank, -label.weight)):
        text = axes.annotate(
            label.text,
            label.anchor,
            xytext=(0, 0),
            textcoords="offset points",
            fontsize=label.size,
            color=label.colour,
            ha="center",
            va="center",
            zorder=8 if label.rank == RELATION else 6,
            path_effects=[HALO],  # readable over footprints, roads and dashed lines
        )
        centred = text.get_window_extent(renderer)  # measured once, then moved
        for dx, dy in LABEL_OFFSETS:
            box = centred.translated(dx * points, dy * points)
            fits = (
                inside.x0 <= box.x0
                and box.x1 <= inside.x1
                and inside.y0 <= box.y0
                and box.y1 <= inside.y1
            )
            if fits and not taken.overlaps(box):
                text.xyann = (dx, dy)
                taken.add(box)
                placed += 1
                break
        else:
            text.remove()
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


def _draw_room(axes, room: Room) -> list[Label]:
    """The room's walls, doors and windows (see the module docstring); returns the
    openings' labels."""
    labels = []
    for wall in room.walls:
        axes.add_patch(
            Polygon(wall_footprint(room, wall), closed=True, fc="0.45", ec="0.25", lw=0.6, zorder=2)
        )
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
            axes.add_patch(
                Polygon(hole, closed=True, fc="lightblue", ec="steelblue", lw=0.6, zorder=2.5)
            )
            mid = [wall.to_world(u0, -thickness / 2.0), wall.to_world(u1, -thickness / 2.0)]
            axes.plot(
                [p[0] for p in mid], [p[1] for p in mid], color="steelblue", lw=0.6, zorder=2.6
            )
        else:
            axes.add_patch(Polygon(hole, closed=True, fc="white", ec="none", zorder=2.5))
            # The leaf hinged at the opening's start, swung open into the room, and its arc.
            arc = [
                wall.to_world(u0 + opening.width * math.cos(a), opening.width * math.sin(a))
                for a in np.linspace(0.0, math.pi / 2.0, 16)
            ]
            axes.plot(
                [p[0] for p in arc], [p[1] for p in arc], color="0.3", lw=0.6, ls=":", zorder=2.6
            )
            leaf = [wall.to_world(u0, 0.0), wall.to_world(u0, opening.width)]
            axes.plot([p[0] for p in leaf], [p[1] for p in leaf], color="0.2", lw=1.2, zorder=2.6)
        x, z = wall.to_world(opening.offset, -thickness - 0.15)
        labels.append(Label(opening.id, (x, z), PATH, colour="0.2"))
    return labels


def _draw_house(axes, house: House) -> list[Label]:
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
        axes.add_patch(Polygon(corners, closed=True, fc="0.45", ec="0.25", lw=0.6, zorder=2))
        for opening, _u in holes[index]:
            _draw_house_opening(axes, house, opening, wall.thickness)
            labels.append(Label(opening.id, opening.center, PATH, colour="0.2"))
    return labels


def _draw_house_opening(axes, house: House, opening, thickness: float) -> None:
    (cx, cz), (dx, dz), w = opening.center, opening.direction, opening.width
    end = (cx + dx, cz + dz)
    nx, nz = inward_normal(house, opening.center, end, opening.rooms[0])

    def at(u: float, v: float) -> tuple[float, float]:  # along the wall, into the first room
        return cx + u * dx + v * nx, cz + u * dz + v * nz

    half = thickness / 2.0
    hole = [at(-w / 2, half), at(w / 2, half), at(w / 2, -half), at(-w / 2, -half)]
    if opening.kind == "window":
        axes.add_patch(
            Polygon(hole, closed=True, fc="lightblue", ec="steelblue", lw=0.6, zorder=2.5)
        )
        mid = [at(-w / 2, 0.0), at(w / 2, 0.0)]
        axes.plot([p[0] for p in mid], [p[1] for p in mid], color="steelblue", lw=0.6, zorder=2.6)
        return
    axes.add_patch(Polygon(hole, closed=True, fc="white", ec="none", zorder=2.5))
    if opening.open:
        return
    arc = [
        at(-w / 2 + w * math.cos(angle), half + w * math.sin(angle))
        for angle in np.linspace(0.0, math.pi / 2.0, 16)
    ]
    axes.plot([p[0] for p in arc], [p[1] for p in arc], color="0.3", lw=0.6, ls=":", zorder=2.6)
    leaf = [at(-w / 2, half), at(-w / 2, half + w)]
    axes.plot([p[0] for p in leaf], [p[1] for p in leaf], color="0.2", lw=1.2, zorder=2.6)


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


def _points_per_metre(figure, axes, width: float, depth: float) -> float:
    """Line widths are in points: how many points one metre spans on this axes."""
    box = axes.get_position()
    span = max(width, depth) * 1.1
    inches = min(box.width * figure.get_figwidth(), box.height * figure.get_figheight())
    return inches * 72.0 / span
