"""Shape builders for kitchens and bathrooms: a refrigerator, counters, a stove, a bathtub,
a toilet, a washbasin, a washing machine, a shower and a towel rail.
"""

from __future__ import annotations

import numpy as np
import trimesh

from .mesh_parts import (
    CHROME,
    COAL,
    IRON,
    SCREEN,
    SHOWER_GLASS,
    WATER,
    WORKTOP,
    Builder,
    block,
    combine,
    cylinder,
    frustum,
    oval,
    register_in,
    ring,
    shade,
    slab,
)

#: The kitchen and bathroom builders by shape name.
KITCHEN_BATH: dict[str, Builder] = {}
builder = register_in(KITCHEN_BATH)


@builder("refrigerator")
def refrigerator(size, colour) -> trimesh.Trimesh:
    """A tall fridge-freezer: a freezer door below a fridge door on the front (+Z), a dark
    seam between them, a long handle on each."""
    w, h, d = size
    body_front, seam = d / 2 - 0.04, 0.36 * h
    door_front = d / 2 - 0.02
    handle_x = w / 2 - 0.07
    return combine(
        slab((-w / 2, 0.0, -d / 2), (w / 2, h, body_front), colour),
        slab(
            (-w / 2 + 0.02, 0.0, body_front - 0.02), (w / 2 - 0.02, 0.03, body_front + 0.005), COAL
        ),
        slab((-w / 2, 0.03, body_front), (w / 2, seam - 0.006, door_front), shade(colour, 1.05)),
        slab(
            (-w / 2, seam + 0.006, body_front), (w / 2, h - 0.005, door_front), shade(colour, 1.05)
        ),
        slab(
            (-w / 2, seam - 0.006, body_front - 0.01),
            (w / 2, seam + 0.006, door_front - 0.005),
            shade(colour, 0.35),
        ),
        slab(
            (handle_x - 0.015, seam - 0.3 * h * 0.75, door_front),
            (handle_x + 0.015, seam - 0.05, d / 2),
            CHROME,
        ),
        slab(
            (handle_x - 0.015, seam + 0.05, door_front),
            (handle_x + 0.015, seam + 0.3 * h, d / 2),
            CHROME,
        ),
    )


def _base_cabinet(
    width: float, top_y: float, depth: float, colour, drawers: bool
) -> list[trimesh.Trimesh]:
    """A kitchen base cabinet ``top_y`` tall (under a worktop), ``depth`` deep, centred:
    a recessed dark plinth, then a column of door (under a drawer, if ``drawers``) about
    every 60 cm, fronts and handles on +Z, the front at ``depth / 2``."""
    w, d = width, depth
    plinth = 0.1
    body_front = d / 2 - 0.04
    columns = int(np.clip(round(w / 0.6), 1, 6))
    edges = np.linspace(-w / 2, w / 2, columns + 1)
    drawer_y = top_y - 0.16 if drawers else top_y
    parts = [
        slab((-w / 2, 0.0, -d / 2), (w / 2, plinth, body_front - 0.06), shade(colour, 0.35)),
        slab((-w / 2, plinth, -d / 2), (w / 2, top_y, body_front), colour),
    ]
    for x0, x1 in zip(edges[:-1], edges[1:], strict=False):
        x0, x1 = x0 + 0.004, x1 - 0.004
        parts.append(
            slab(
                (x0, plinth + 0.004, body_front),
                (x1, drawer_y - 0.004, d / 2 - 0.02),
                shade(colour, 1.1),
            )
        )
        handle_x = x1 - 0.06 if columns > 1 and x0 < 0 else x0 + 0.06
        parts.append(block((0.02, 0.14, 0.02), (handle_x, drawer_y - 0.12, d / 2 - 0.01), CHROME))
        if drawers:
            parts.append(
                slab(
                    (x0, drawer_y + 0.004, body_front),
                    (x1, top_y - 0.004, d / 2 - 0.02),
                    shade(colour, 1.1),
                )
            )
            parts.append(
                block(
                    (0.4 * (x1 - x0), 0.02, 0.02),
                    ((x0 + x1) / 2, drawer_y + 0.08, d / 2 - 0.01),
                    CHROME,
                )
            )
    return parts


@builder("kitchen_counter")
def kitchen_counter(size, colour) -> trimesh.Trimesh:
    """A base cabinet (doors under drawers, handles) under a dark worktop overhanging its front."""
    w, h, d = size
    worktop = min(0.04, 0.1 * h)
    return combine(
        _base_cabinet(w, h - worktop, d, colour, drawers=True),
        slab((-w / 2, h - worktop, -d / 2), (w / 2, h, d / 2), WORKTOP),
    )


@builder("sink_counter")
def sink_counter(size, colour) -> trimesh.Trimesh:
    """A base cabinet with doors under a worktop at 85 % of the height, a steel basin
    sunk in it and a tap at its back (-Z) rising to the full height."""
    w, h, d = size
    top_y, worktop = 0.85 * h, min(0.04, 0.1 * h)
    bw, bd, bz = min(0.6 * w, 0.55), 0.55 * d, 0.05 * d  # basin width, depth, centre z
    x0, x1, z0, z1 = -bw / 2, bw / 2, bz - bd / 2, bz + bd / 2
    floor_y = top_y - min(0.18, 0.5 * top_y)
    wall = 0.01
    tap_z = z0 - 0.05
    steel = shade(CHROME, 0.9)
    return combine(
        _base_cabinet(w, floor_y - 0.01, d, colour, drawers=False),
        slab((-w / 2, floor_y - 0.01, -d / 2), (w / 2, top_y - worktop, d / 2 - 0.04), colour),
        # The worktop round the basin's hole.
        slab((-w / 2, top_y - worktop, -d / 2), (x0, top_y, d / 2), WORKTOP),
        slab((x1, top_y - worktop, -d / 2), (w / 2, top_y, d / 2), WORKTOP),
        slab((x0, top_y - worktop, -d / 2), (x1, top_y, z0), WORKTOP),
        slab((x0, top_y - worktop, z1), (x1, top_y, d / 2), WORKTOP),
        # The basin: a steel floor and four walls under the hole, a drain.
        slab((x0, floor_y, z0), (x1, floor_y + wall, z1), shade(steel, 0.85)),
        [
            slab((x0, floor_y, za), (x1, top_y, zb), steel)
            for za, zb in ((z0, z0 + wall), (z1 - wall, z1))
        ],
        [
            slab((xa, floor_y, z0), (xb, top_y, z1), steel)
            for xa, xb in ((x0, x0 + wall), (x1 - wall, x1))
        ],
        cylinder(
            0.03, (0.0, floor_y + wall, bz), (0.0, floor_y + wall + 0.002, bz), COAL, sections=8
        ),
        # The tap: a pillar at the back, a spout reaching over the basin.
        cylinder(0.02, (0.0, top_y, tap_z), (0.0, h - 0.015, tap_z), CHROME, sections=8),
        cylinder(
            0.015, (0.0, h - 0.015, tap_z - 0.01), (0.0, h - 0.015, z0 + 0.12), CHROME, sections=8
        ),
        cylinder(0.015, (0.0, h - 0.05, z0 + 0.11), (0.0, h, z0 + 0.11), CHROME, sections=8),
    )


@builder("stove")
def stove(size, colour) -> trimesh.Trimesh:
    """A cooker: an oven door with a dark window and a handle, a strip of knobs above it
    on the front (+Z), a black hob with four rings on top."""
    w, h, d = size
    hob = 0.03
    front = d / 2 - 0.02
    strip_y = h - hob - 0.1
    r = 0.2 * min(w, d)
    knobs = [
        cylinder(0.022, (x, strip_y + 0.05, front), (x, strip_y + 0.05, d / 2), IRON, sections=6)
        for x in np.linspace(-0.3 * w, 0.3 * w, 4)
    ]
    rings = [
        ring(0.55 * r, r, (x, h - 0.004, z), (x, h, z), (0.55, 0.55, 0.58), sections=8)
        for x in (-w / 4, w / 4)
        for z in (-d / 4, d / 4)
    ]
    return combine(
        slab((-w / 2, 0.0, -d / 2), (w / 2, h - hob, front), colour),
        slab((-w / 2, strip_y, front), (w / 2, h - hob, front + 0.005), shade(colour, 0.85)),
        knobs,
        slab(
            (-w / 2 + 0.03, 0.08, front),
            (w / 2 - 0.03, strip_y - 0.02, front + 0.008),
            shade(colour, 1.05),
        ),
        slab(
            (-w / 2 + 0.09, 0.2, front + 0.008),
            (w / 2 - 0.09, strip_y - 0.12, front + 0.01),
            (0.12, 0.12, 0.14),
        ),
        slab(
            (-w / 2 + 0.07, strip_y - 0.09, front + 0.008),
            (w / 2 - 0.07, strip_y - 0.065, d / 2),
            CHROME,
        ),
        slab((-w / 2, h - hob, -d / 2), (w / 2, h - 0.004, d / 2), COAL),
        rings,
    )


@builder("bathtub")
def bathtub(size, colour) -> trimesh.Trimesh:
    """A bathtub along X: sides round water filling it to two thirds, a tap on the inside
    of its -X end; one steps in over the long front side (+Z)."""
    w, h, d = size
    rim, base = min(0.08, 0.12 * d), 0.25 * h
    x0, x1, z0, z1 = -w / 2 + rim, w / 2 - rim, -d / 2 + rim, d / 2 - rim
    return combine(
        slab((-w / 2, 0.0, -d / 2), (w / 2, base, d / 2), shade(colour, 0.9)),
        slab((-w / 2, base, -d / 2), (w / 2, h, z0), colour),
        slab((-w / 2, base, z1), (w / 2, h, d / 2), colour),
        slab((-w / 2, base, z0), (x0, h, z1), colour),
        slab((x1, base, z0), (w / 2, h, z1), colour),
        slab((x0, base, z0), (x1, 0.65 * h, z1), WATER),
        cylinder(0.02, (x0, h - 0.08, 0.0), (x0 + 0.1, h - 0.08, 0.0), CHROME, sections=8),
        [
            cylinder(0.02, (x0 - 0.005, h - 0.05, z), (x0 + 0.01, h - 0.05, z), CHROME, sections=8)
            for z in (-0.08, 0.08)
        ],
    )


@builder("toilet")
def toilet(size, colour) -> trimesh.Trimesh:
    """A toilet: the cistern at the back (-Z) with a flush button, an oval bowl on a
    pedestal reaching forward (+Z), an open seat and the lid up against the cistern."""
    w, h, d = size
    cistern_d = 0.24 * d
    seat_y = 0.5 * h
    rx = w / 2
    rz = (d - cistern_d) / 2 + 0.02
    bowl_z = d / 2 - rz
    ratio = rz / rx
    lid_z = -d / 2 + cistern_d + 0.02
    lid = cylinder(0.9 * rx, (0.0, 0.0, -0.01), (0.0, 0.0, 0.01), shade(colour, 0.97), sections=12)
    lid_r_y = min(0.9 * rx, (h - seat_y - 0.06) / 2)
    lid.apply_scale((1.0, lid_r_y / (0.9 * rx), 1.0))
    lid.apply_translation((0.0, seat_y + 0.04 + lid_r_y, lid_z))
    return combine(
        slab((-w / 2, 0.42 * h, -d / 2), (w / 2, h, -d / 2 + cistern_d), colour),
        cylinder(
            0.035,
            (0.0, h - 0.001, -d / 2 + cistern_d / 2),
            (0.0, h, -d / 2 + cistern_d / 2),
            CHROME,
            sections=8,
        ),
        oval(
            frustum(0.55 * rx, 0.65 * rx, 0.0, 0.3 * h, colour, sections=12),
            ratio * 0.8,
            bowl_z - 0.03,
        ),
        oval(frustum(0.65 * rx, rx, 0.3 * h, seat_y, colour, sections=12), ratio, bowl_z),
        oval(
            cylinder(
                0.62 * rx, (0.0, seat_y - 0.01, 0.0), (0.0, seat_y + 0.003, 0.0), WATER, sections=12
            ),
            ratio,
            bowl_z,
        ),
        oval(
            ring(
                0.62 * rx,
                0.98 * rx,
                (0.0, seat_y, 0.0),
                (0.0, seat_y + 0.03, 0.0),
                shade(colour, 0.97),
            ),
            ratio,
            bowl_z,
        ),
        lid,
    )


@builder("washbasin")
def washbasin(size, colour) -> trimesh.Trimesh:
    """A bathroom sink: an oval basin on a pedestal, its bowl showing from above, and a
    tap at its back (-Z) reaching over the bowl."""
    w, h, d = size
    rim_y = 0.85 * h
    basin_y = rim_y - 0.18
    rx = w / 2
    ratio = d / w
    tap_z = -d / 2 + 0.06
    return combine(
        frustum(
            0.18 * w, 0.12 * w, 0.0, basin_y + 0.02, colour, sections=10, centre=(0.0, -0.1 * d)
        ),
        oval(frustum(0.7 * rx, rx, basin_y, rim_y, colour, sections=14), ratio),
        oval(
            cylinder(
                0.72 * rx,
                (0.0, rim_y, 0.0),
                (0.0, rim_y + 0.003, 0.0),
                shade(colour, 0.82),
                sections=14,
            ),
            ratio,
            0.05 * d,
        ),
        cylinder(
            0.02, (0.0, rim_y + 0.003, 0.05 * d), (0.0, rim_y + 0.005, 0.05 * d), COAL, sections=8
        ),
        cylinder(0.018, (0.0, rim_y, tap_z), (0.0, h - 0.015, tap_z), CHROME, sections=8),
        cylinder(
            0.013,
            (0.0, h - 0.015, tap_z - 0.01),
            (0.0, h - 0.015, tap_z + 0.12),
            CHROME,
            sections=8,
        ),
        [
            cylinder(0.02, (x, rim_y, tap_z), (x, rim_y + 0.04, tap_z), CHROME, sections=8)
            for x in (-0.1, 0.1)
        ],
    )


@builder("washing_machine")
def washing_machine(size, colour) -> trimesh.Trimesh:
    """A front-loading washing machine: a round door with a dark glass window, a control
    panel with a drawer, a display and a knob across the top of the front (+Z)."""
    w, h, d = size
    front = d / 2 - 0.02
    panel = 0.14 * h
    door_y = (h - panel) / 2 + 0.02
    r = 0.36 * min(w, h - panel)
    return combine(
        slab((-w / 2, 0.0, -d / 2), (w / 2, h, front), colour),
        slab(
            (-w / 2 + 0.01, h - panel, front),
            (w / 2 - 0.01, h - 0.01, front + 0.008),
            shade(colour, 0.9),
        ),
        slab(
            (-w / 2 + 0.03, h - panel + 0.02, front + 0.008),
            (-w / 2 + 0.2 * w + 0.03, h - 0.03, front + 0.012),
            shade(colour, 1.1),
        ),
        slab(
            (-0.05 * w, h - panel + 0.04, front + 0.008), (0.12 * w, h - 0.04, front + 0.01), SCREEN
        ),
        cylinder(
            0.035,
            (0.3 * w, h - panel / 2, front + 0.008),
            (0.3 * w, h - panel / 2, d / 2),
            CHROME,
            sections=10,
        ),
        ring(
            0.75 * r, r, (0.0, door_y, front), (0.0, door_y, d / 2), shade(CHROME, 0.9), sections=16
        ),
        cylinder(
            0.75 * r,
            (0.0, door_y, front),
            (0.0, door_y, d / 2 - 0.008),
            (0.16, 0.2, 0.26),
            sections=16,
        ),
        slab(
            (-w / 2 + 0.02, 0.0, front - 0.02),
            (w / 2 - 0.02, 0.05, front + 0.004),
            shade(colour, 0.8),
        ),
    )


@builder("shower")
def shower(size, colour) -> trimesh.Trimesh:
    """A shower tray (the catalog colour) with a drain; a glass screen in a chrome frame
    on its +X side and the +X half of its front (+Z), the other half open to step in;
    a riser with a mixer on its back (-Z), its head reaching out above the glass."""
    w, h, d = size
    tray = min(0.06, 0.05 * h)
    glass_t, glass_top = 0.012, 0.88 * h
    door_x = 0.1 * w  # the front screen runs from here to the +X side
    riser_z, riser_x = -d / 2 + 0.04, -0.1 * w
    arm_y = h - 0.02
    head_z = riser_z + min(0.3, 0.4 * d)
    return combine(
        slab((-w / 2, 0.0, -d / 2), (w / 2, tray - 0.008, d / 2), colour),
        slab(
            (-w / 2 + 0.04, tray - 0.008, -d / 2 + 0.04),
            (w / 2 - 0.04, tray, d / 2 - 0.04),
            shade(colour, 0.92),
        ),
        cylinder(0.04, (0.0, tray, 0.0), (0.0, tray + 0.002, 0.0), IRON, sections=8),
        slab((door_x, tray, d / 2 - glass_t), (w / 2, glass_top, d / 2), SHOWER_GLASS),
        slab((w / 2 - glass_t, tray, -d / 2), (w / 2, glass_top, d / 2 - glass_t), SHOWER_GLASS),
        slab((door_x - 0.02, tray, d / 2 - glass_t), (door_x, glass_top, d / 2), CHROME),
        slab((door_x, glass_top - 0.02, d / 2 - glass_t), (w / 2, glass_top, d / 2), CHROME),
        slab(
            (w / 2 - glass_t, glass_top - 0.02, -d / 2), (w / 2, glass_top, d / 2 - glass_t), CHROME
        ),
        cylinder(
            0.012, (riser_x, 0.45 * h, riser_z), (riser_x, arm_y, riser_z), CHROME, sections=6
        ),
        cylinder(0.012, (riser_x, arm_y, riser_z), (riser_x, arm_y, head_z), CHROME, sections=6),
        frustum(
            0.03, 0.09, arm_y - 0.06, arm_y - 0.01, CHROME, sections=10, centre=(riser_x, head_z)
        ),
        slab(
            (riser_x - 0.08, 0.5 * h - 0.04, -d / 2),
            (riser_x + 0.08, 0.5 * h + 0.04, -d / 2 + 0.05),
            CHROME,
        ),
    )


@builder("towel_rail")
def towel_rail(size, colour) -> trimesh.Trimesh:
    """A standing towel rail: two posts on feet at its ends (-X, +X), three bars between
    them, a towel over the top bar and a smaller one over the middle bar."""
    w, h, d = size
    posts = [w / 2 - 0.02, -w / 2 + 0.02]
    bars_y = (0.45 * h, 0.7 * h, h - 0.015)
    towels = []
    for y, x_half, towel_colour, drop in (
        (h, 0.36 * w, (0.55, 0.72, 0.85), 0.45 * h),
        (0.7 * h, 0.28 * w, (0.9, 0.6, 0.5), 0.3 * h),
    ):
        towels.append(slab((-x_half, y - drop, -0.035), (x_half, y - 0.005, -0.015), towel_colour))
        towels.append(slab((-x_half, y - drop, 0.015), (x_half, y - 0.005, 0.035), towel_colour))
        towels.append(
            slab((-x_half, y - 0.03, -0.035), (x_half, y, 0.035), shade(towel_colour, 1.1))
        )
    return combine(
        [slab((x - 0.02, 0.0, -d / 2), (x + 0.02, 0.03, d / 2), colour) for x in posts],
        [cylinder(0.015, (x, 0.0, 0.0), (x, h, 0.0), colour, sections=8) for x in posts],
        [
            cylinder(0.012, (-w / 2 + 0.02, y, 0.0), (w / 2 - 0.02, y, 0.0), colour, sections=8)
            for y in bars_y
        ],
        towels,
    )
