"""A top-down plan image of a laid-out scene (matplotlib, Agg backend, no display).

North (-Z) is up and east (+X) right, as on a map. Drawn: the scene extent; paths as
lines of their true width with their control points; junctions; every object's rotated
footprint with a tick from its centre towards its forward side; ids as labels; and a red
dashed line between the two ends of each relation the layout did not satisfy.
"""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402  (the backend must be chosen first)
from matplotlib.patches import Polygon, Rectangle  # noqa: E402

from scenewright.core.frames import forward  # noqa: E402
from scenewright.core.scene import Scene, object_corners  # noqa: E402

#: Pixels per inch of the saved image.
DPI = 110


def draw_plan(scene: Scene, path) -> Path:
    """Write the scene's top-down plan to ``path`` (PNG) and return the path."""
    width, depth = scene.extent
    size = 9.0
    figure, axes = plt.subplots(figsize=(size, size * depth / width + 0.6))
    axes.set_aspect("equal")
    # Data y is z; inverting the axis puts north (-Z) at the top of the picture.
    axes.add_patch(Rectangle((-width / 2, -depth / 2), width, depth, fill=False, lw=1.5, ec="black"))
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
    for relation in scene.relations:
        if relation.satisfied or relation.source not in centres or relation.target not in centres:
            continue
        (sx, sz), (tx, tz) = centres[relation.source], centres[relation.target]
        axes.plot([sx, tx], [sz, tz], color="red", lw=1.2, ls="--", zorder=7)
        axes.annotate(relation.label, ((sx + tx) / 2, (sz + tz) / 2), fontsize=6, color="red", zorder=7)
    margin = 0.05 * max(width, depth)
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


def _points_per_metre(figure, axes, width: float, depth: float) -> float:
    """Line widths are in points: how many points one metre spans on this axes."""
    box = axes.get_position()
    span = max(width, depth) * 1.1
    inches = min(box.width * figure.get_figwidth(), box.height * figure.get_figheight())
    return inches * 72.0 / span
