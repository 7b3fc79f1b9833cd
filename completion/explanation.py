"""A completed room explained to people from its ``completion`` record: ``summary_of``,
one line naming the room's types and what was added to the request, and
``draw_explanation``, a picture of the layout mask mapped back onto the room with the
laid-out floor pieces over it.
"""

from __future__ import annotations

import math

import numpy as np

from scenewright.core.room import Room


def summary_of(record: dict) -> str:
    """One line for people: the room's types and what was added to the request."""
    added = []
    for entry in record["selection"].values():
        for item in entry["categories"]:
            if not item["requested"] and item["category"] not in record["left_out"]:
                count = record["counts"][item["category"]]
                added.append(item["category"] + (f" x{count}" if count > 1 else ""))
    left = "".join(f"; left out {name} ({why})" for name, why in record["left_out"].items())
    left += "".join(
        f"; {n} {name} fewer (no room for more with the rest)"
        for name, n in record.get("given_up", {}).items()
        if name not in record["left_out"]
    )
    return f"room type {' + '.join(record['types'])}; added {', '.join(dict.fromkeys(added)) or 'nothing'}{left}"


def draw_explanation(scene, target) -> None:
    """Write a PNG to ``target`` (a path or binary file): the layout mask of
    ``scene.completion`` mapped back onto the room (darker: more of the reference plans'
    furniture stood there), with the room's outline, its doors (red) and windows (blue)
    and the laid-out floor pieces' outlines, north up. A room split by virtual walls
    shows each region's mask in its region, the virtual walls dashed (green) and each
    region's type."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.patches import Polygon

    from scenewright.core.frames import corners_of

    record, room = scene.completion, scene.room
    xs, zs = (np.array([c[i] for c in room.corners]) for i in (0, 1))
    grid_x, grid_z = np.meshgrid(
        np.linspace(xs.min(), xs.max(), 200), np.linspace(zs.min(), zs.max(), 160)
    )
    points = np.column_stack([grid_x.ravel(), grid_z.ravel()])
    values = recorded_mask_values(record, room, points).reshape(grid_x.shape)
    inside = np.array([room.contains(x, z) for x, z in points]).reshape(grid_x.shape)
    figure, axis = plt.subplots(figsize=(6.0, 6.0 * float(np.ptp(zs) / np.ptp(xs)) + 0.6))
    axis.imshow(
        np.where(inside, values, np.nan),
        cmap="Greys",
        vmin=0.0,
        vmax=1.0,
        origin="upper",
        extent=(xs.min(), xs.max(), zs.max(), zs.min()),
    )
    outline = list(room.corners) + [room.corners[0]]
    axis.plot([c[0] for c in outline], [c[1] for c in outline], color="0.2", lw=2.5)
    for opening in room.openings:
        start, end = room.opening_ends(opening)
        axis.plot(
            [start[0], end[0]],
            [start[1], end[1]],
            color="#c04040" if opening.kind == "door" else "#4a90c8",
            lw=4,
        )
    for (ax, az), (bx, bz) in record.get("virtual_walls", []):
        axis.plot([ax, bx], [az, bz], color="#2a9a4a", lw=2.5, ls="--")
    for region in record.get("regions", []):
        x0, z0, x1, z1 = region["bounds"]
        axis.annotate(
            region["type"].replace("_", " "),
            ((x0 + x1) / 2.0, z0 + 0.25),
            fontsize=8,
            ha="center",
            va="center",
            color="#2a7a3a",
            weight="bold",
        )
    for obj in scene.placed_objects():
        if obj.position[1] > 0.01:
            continue  # stands on another piece
        corners = corners_of(
            obj.position[0],
            obj.position[2],
            obj.size[0] / 2,
            obj.size[2] / 2,
            math.cos(obj.yaw),
            math.sin(obj.yaw),
        )
        axis.add_patch(Polygon(corners, closed=True, fill=False, ec="#e07020", lw=1.2))
        axis.annotate(
            obj.id,
            (obj.position[0], obj.position[2]),
            fontsize=6,
            ha="center",
            va="center",
            color="#a04000",
        )
    if "regions" in record:
        title = " | ".join(f"{r['type']} ({len(r['references'])} plans)" for r in record["regions"])
        axis.set_title(f"layout masks split by virtual walls: {title}", fontsize=8)
    else:
        mask = record["mask"]
        axis.set_title(
            f"layout mask of {mask['type']} ({len(mask['references'])} reference plans) and the layout",
            fontsize=8,
        )
    axis.set_xlabel("x (east) [m]")
    axis.set_ylabel("z (south) [m]")
    axis.set_aspect("equal")
    figure.tight_layout()
    figure.savefig(target, dpi=90, format="png")
    plt.close(figure)


def recorded_mask_values(record: dict, room: Room, points) -> np.ndarray:
    """(n,) the layout mask a ``completion`` record holds, read at room points (n, 2):
    the room's mask, or for a room split by virtual walls each region's in its region."""
    from scenewright.completion.features import CanonicalFrame
    from scenewright.completion.layout_mask import LayoutMask, mask_at
    from scenewright.completion.regions import region_of_points

    points = np.asarray(points, dtype=float).reshape(-1, 2)
    if "regions" not in record:
        mask = record["mask"]
        layout = LayoutMask(
            np.asarray(mask["cells"]),
            CanonicalFrame(**mask["frame"]),
            np.zeros(4),
            mask["references"],
        )
        return mask_at(layout, room, points)
    values = np.zeros(len(points))
    regions = [recorded_region(entry, room) for entry in record["regions"]]
    where = region_of_points(regions, points)
    for k, entry in enumerate(record["regions"]):
        chosen = where == k
        if chosen.any():
            layout = LayoutMask(
                np.asarray(entry["cells"]), CanonicalFrame(**entry["frame"]), np.zeros(4), {}
            )
            values[chosen] = mask_at(layout, regions[k].room, points[chosen])
    return values


def recorded_region(entry: dict, room: Room):
    """A ``regions.Region`` from its entry in a ``completion`` record (its sub-room's
    walls; the openings, which only the mask's frame needed, are not rebuilt)."""
    from scenewright.completion.regions import Region

    x0, z0, x1, z1 = entry["bounds"]
    sub = Room.polygon([(x0, z0), (x1, z0), (x1, z1), (x0, z1)], room.height, centre=False)
    return Region(entry["type"], (x0, z0, x1, z1), sub, entry["virtual_door"])
