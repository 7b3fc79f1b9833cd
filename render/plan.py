"""A top-down plan image of a laid-out scene (matplotlib, Agg backend, no display).

North (-Z) is up and east (+X) right, as on a map. Drawn: the scene extent, or in a
room its walls (grey, their true thickness behind the inner faces, mitred at the corners
as the renderer builds them), its doors (a gap with the leaf swung open into the room
and its swing arc) and windows (pale blue across the wall); paths as lines of their true
width with their control points; junctions; every object's rotated footprint with a
tick from its centre towards its forward side; ids as labels; and a red dashed line
between the two ends of each relation the layout did not satisfy (a wall, door or
window at its inner face's middle; "the room" at the wall the layout chose).
"""

from __future__ import annotations

import math
from pathlib import Path

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402  (the backend must be chosen first)
import numpy as np  # noqa: E402
from matplotlib.patches import Polygon, Rectangle  # noqa: E402

from scenewright.core.frames import forward  # noqa: E402
from scenewright.core.room import ROOM_NODE, WALL_THICKNESS, Room  # noqa: E402
from scenewright.core.scene import Scene, object_corners  # noqa: E402
from scenewright.render.meshes import wall_footprint  # noqa: E402

#: Pixels per inch of the saved image.
DPI = 110


def draw_plan(scene: Scene, path) -> Path:
    """Write the scene's top-down plan to ``path`` (PNG) and return the path."""
    width, depth = scene.extent
    size = 9.0
    figure, axes = plt.subplots(figsize=(size, size * depth / width + 0.6))
    axes.set_aspect("equal")
    # Data y is z; inverting the axis puts north (-Z) at the top of the picture.
    if scene.room is None:
        axes.add_patch(Rectangle((-width / 2, -depth / 2), width, depth, fill=False, lw=1.5, ec="black"))
    else:
        _draw_room(axes, scene.room)
    points_per_metre = _points_per_metre(figure, axes, width, depth)
    for road in scene.paths:
        xs = [p[0] for p in road.points]
        zs = [p[1] for p in road.points]
        axes.plot(xs, zs, color=road.colour, lw=road.width * points_per_metre, solid_capstyle="round", alpha=0.8, zorder=1)
        axes.plot(xs, zs, "k.", ms=3, zorder=2)
        axes.annotate(road.id, (xs[-1], zs[-1]), fontsize=7, color="saddlebrown", zorder=6)
    centres = {}
    for obj in scene.objects:
        centres[obj.id] = (obj.position[0], obj.position[2])
        if obj.kind == "group":
            continue
        corners = object_corners([obj])[0]
        if obj.kind == "junction":
            axes.add_patch(Polygon(corners, closed=True, fc="tan", ec="saddlebrown", lw=1, zorder=2))
            continue
        stacked = obj.position[1] > 1e-6
        axes.add_patch(Polygon(corners, closed=True, fc=obj.colour, ec="black", lw=0.6, alpha=0.9, zorder=4 if stacked else 3))
        reach = obj.size[2] / 2.0
        x, z = obj.position[0], obj.position[2]
        fx, fz = forward(obj.yaw)
        axes.plot([x, x + fx * reach], [z, z + fz * reach], color="black", lw=0.8, zorder=5)
        axes.annotate(obj.id, (x, z), fontsize=5, ha="center", va="bottom", zorder=6)
    for road in scene.paths:
        mid = road.points[len(road.points) // 2]
        centres[road.id] = (mid[0], mid[1])
    if scene.room is not None:
        for wall in scene.room.walls:
            centres[wall.id] = wall.to_world(wall.length / 2.0, 0.0)
        for opening in scene.room.openings:
            centres[opening.id] = opening.center
    for relation in scene.relations:
        target = relation.chosen if relation.target == ROOM_NODE and relation.chosen else relation.target
        if relation.satisfied or relation.source not in centres or target not in centres:
            continue
        (sx, sz), (tx, tz) = centres[relation.source], centres[target]
        axes.plot([sx, tx], [sz, tz], color="red", lw=1.2, ls="--", zorder=7)
        axes.annotate(relation.label, ((sx + tx) / 2, (sz + tz) / 2), fontsize=6, color="red", zorder=7)
    margin = 0.05 * max(width, depth)
    if scene.room is not None:  # the walls and the openings' labels stand outside the extent
        margin = max(margin, WALL_THICKNESS + 0.5)
    axes.set_xlim(-width / 2 - margin, width / 2 + margin)
    axes.set_ylim(depth / 2 + margin, -depth / 2 - margin)
    axes.set_xlabel("x (east) [m]")
    axes.set_ylabel("z (south) [m]")
    status = "ok" if scene.layout.ok else f"{len(scene.layout.problems)} problems"
    axes.set_title(f"{scene.rules}  seed {scene.seed}  energy {scene.layout.energy:.2f}  {status}", fontsize=9)
    target = Path(path)
    figure.savefig(target, dpi=DPI, bbox_inches="tight")
    plt.close(figure)
    return target


def _draw_room(axes, room: Room) -> None:
    """The room's walls, doors and windows (see the module docstring)."""
    for wall in room.walls:
        axes.add_patch(Polygon(wall_footprint(room, wall), closed=True, fc="0.45", ec="0.25", lw=0.6, zorder=2))
    for opening in room.openings:
        wall = room.part(opening.wall)
        u0, u1 = opening.span
        thickness = WALL_THICKNESS
        hole = [wall.to_world(u0, 0.0), wall.to_world(u1, 0.0), wall.to_world(u1, -thickness), wall.to_world(u0, -thickness)]
        if opening.kind == "window":
            axes.add_patch(Polygon(hole, closed=True, fc="lightblue", ec="steelblue", lw=0.6, zorder=2.5))
            mid = [wall.to_world(u0, -thickness / 2.0), wall.to_world(u1, -thickness / 2.0)]
            axes.plot([p[0] for p in mid], [p[1] for p in mid], color="steelblue", lw=0.6, zorder=2.6)
        else:
            axes.add_patch(Polygon(hole, closed=True, fc="white", ec="none", zorder=2.5))
            # The leaf hinged at the opening's start, swung open into the room, and its arc.
            arc = [wall.to_world(u0 + opening.width * math.cos(a), opening.width * math.sin(a))
                   for a in np.linspace(0.0, math.pi / 2.0, 16)]
            axes.plot([p[0] for p in arc], [p[1] for p in arc], color="0.3", lw=0.6, ls=":", zorder=2.6)
            leaf = [wall.to_world(u0, 0.0), wall.to_world(u0, opening.width)]
            axes.plot([p[0] for p in leaf], [p[1] for p in leaf], color="0.2", lw=1.2, zorder=2.6)
        x, z = wall.to_world(opening.offset, -thickness - 0.15)
        axes.annotate(opening.id, (x, z), fontsize=5, ha="center", va="center", color="0.2", zorder=6)


def _points_per_metre(figure, axes, width: float, depth: float) -> float:
    """Line widths are in points: how many points one metre spans on this axes."""
    box = axes.get_position()
    span = max(width, depth) * 1.1
    inches = min(box.width * figure.get_figwidth(), box.height * figure.get_figheight())
    return inches * 72.0 / span
