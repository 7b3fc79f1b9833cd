"""Plans drawn as a designer reads them, a sheet of them in one PNG (matplotlib, Agg).

Each plan is a panel, north up: the walls, the doors with their swing (dotted square)
and leaf arc, the windows (blue), every piece's footprint with a tick towards its front,
coloured by its functional purpose (stay: orange, fetch: green, others: grey; rugs pale,
things standing on others darker), free areas dashed; beside it, with ``masks``, its
10 x 10 layout mask in the door-aware canonical frame (door top-left). This is the view
to check a hand-drawn plan by (``scenewright plans draw``).
"""

from __future__ import annotations

import math

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402  (the backend must be chosen first)
import numpy as np  # noqa: E402
from matplotlib.patches import Polygon, Rectangle  # noqa: E402

from scenewright.completion.activity import FETCH, STAY, purpose  # noqa: E402
from scenewright.completion.features import canonical_frame, occupancy_mask  # noqa: E402
from scenewright.completion.model_builder import floor_pieces  # noqa: E402
from scenewright.completion.plan_checks import is_flat  # noqa: E402
from scenewright.generator import indoor_catalog  # noqa: E402

COLOURS = {STAY: "#e8a25a", FETCH: "#6fae6f", None: "#a8adb4"}
#: The most panels one sheet holds (a sheet is one image; draw more as several sheets).
MAX_PANELS = 64


def draw_plans(plans, target, *, masks: bool = False, columns: int | None = None) -> None:
    """Write a sheet of ``plans`` (at most ``MAX_PANELS``) as PNG to ``target``, a path
    or a binary file; ``columns`` plans a row (4, or 2 with their masks)."""
    plans = list(plans)[:MAX_PANELS]
    per_plan = 2 if masks else 1
    columns = max(1, min(columns or (2 if masks else 4), len(plans)))
    rows = math.ceil(len(plans) / columns)
    figure, axes = plt.subplots(
        rows, columns * per_plan, figsize=(3.6 * columns * per_plan, 3.6 * rows), squeeze=False
    )
    for axis in axes.flat:
        axis.set_axis_off()
    for index, plan in enumerate(plans):
        row, column = divmod(index, columns)
        _draw_plan(axes[row][column * per_plan], plan)
        if masks:
            floor = floor_pieces(plan)
            mask = occupancy_mask(plan.room, floor, canonical_frame(plan.room, floor))
            axis = axes[row][column * per_plan + 1]
            axis.imshow(mask, cmap="Greys", vmin=0.0, vmax=1.0)
            axis.set_title("mask (door top-left)", fontsize=7)
    figure.tight_layout()
    figure.savefig(target, dpi=90, format="png")
    plt.close(figure)


def _draw_plan(axis, plan) -> None:
    room = plan.room
    axis.set_axis_on()
    axis.set_xticks([])
    axis.set_yticks([])
    corners = list(room.corners) + [room.corners[0]]
    axis.plot([c[0] for c in corners], [c[1] for c in corners], color="0.2", lw=2.5)
    for opening in room.openings:
        start, end = room.opening_ends(opening)
        if opening.kind == "window":
            axis.plot([start[0], end[0]], [start[1], end[1]], color="#4a90c8", lw=4)
            continue
        axis.plot([start[0], end[0]], [start[1], end[1]], color="white", lw=4)
        axis.add_patch(Polygon(room.swing_zone(opening), fill=False, ec="#c04040", ls=":", lw=0.8))
        wall, (u0, _) = room.part(opening.wall), opening.span
        arc = [
            wall.to_world(u0 + opening.width * math.cos(a), opening.width * math.sin(a))
            for a in np.linspace(0.0, math.pi / 2.0, 16)
        ]
        axis.plot([p[0] for p in arc], [p[1] for p in arc], color="#c04040", lw=0.8)
    catalog = indoor_catalog()
    for piece in plan.furniture:
        flat = is_flat(piece, catalog)
        colour = COLOURS[purpose(piece.category)]
        axis.add_patch(
            Polygon(
                piece.corners,
                closed=True,
                fc=colour,
                ec="0.25",
                lw=0.6,
                alpha=0.25 if flat else (1.0 if piece.on else 0.75),
            )
        )
        x, z = piece.center
        tip = (x + 0.25 * math.sin(piece.yaw), z + 0.25 * math.cos(piece.yaw))
        axis.plot([x, tip[0]], [z, tip[1]], color="0.15", lw=0.8)
        if not piece.on and not flat:
            axis.annotate(
                piece.category.replace("_", " "), (x, z), fontsize=5, ha="center", va="center"
            )
    for area in plan.free_areas:
        (x, z), (w, d) = area.center, area.size
        axis.add_patch(
            Rectangle((x - w / 2, z - d / 2), w, d, fill=False, ec="#8060c0", ls="--", lw=0.8)
        )
    width, depth = room.extent
    axis.set_title(f"{plan.id}  {width:g} x {depth:g} m", fontsize=8)
    axis.set_aspect("equal")
    axis.invert_yaxis()  # north (-Z) up
