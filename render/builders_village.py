"""Shape builders for the village: buildings, plants, carts, street furniture, smithy and
mill wares.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
import trimesh

from .mesh_parts import (
    BARK,
    BLOSSOM,
    COAL,
    DARK_WOOD,
    GLASS,
    GLOW,
    IRON,
    LIGHT,
    LINEN,
    ROOF,
    SOIL,
    STRAW,
    WOOD,
    Builder,
    ball,
    block,
    coloured,
    combine,
    cone,
    cylinder,
    frustum,
    gable_roof,
    register_in,
    repeats,
    shade,
    slab,
)

#: The village builders by shape name.
VILLAGE: dict[str, Builder] = {}
builder = register_in(VILLAGE)


def _dwelling(size, colour, storeys: int, roof_colour) -> trimesh.Trimesh:
    """Walls, a gable roof with its ridge along x, a door on the front (+Z), windows."""
    w, h, d = size
    wall_h = 0.6 * h
    storey_h = wall_h / storeys
    parts = [
        slab((-w / 2 + 0.1, 0.0, -d / 2 + 0.1), (w / 2 - 0.1, wall_h, d / 2 - 0.1), colour),
        gable_roof(w, d, wall_h, h - wall_h, roof_colour),
        slab(
            (-0.45, 0.0, d / 2 - 0.12), (0.45, min(2.0, 0.85 * storey_h), d / 2 - 0.05), DARK_WOOD
        ),
    ]
    for storey in range(storeys):
        y = storey * storey_h + 0.45 * storey_h
        for x in (-w / 4 - 0.2, w / 4 + 0.2):
            parts.append(slab((x - 0.4, y, d / 2 - 0.12), (x + 0.4, y + 0.8, d / 2 - 0.06), GLASS))
    return combine(parts)


@builder("house")
def house(size, colour) -> trimesh.Trimesh:
    return _dwelling(size, colour, 1, ROOF)


@builder("townhouse")
def townhouse(size, colour) -> trimesh.Trimesh:
    return _dwelling(size, colour, 2, shade(ROOF, 0.8))


@builder("shed")
def shed(size, colour) -> trimesh.Trimesh:
    """Plank walls under a straw roof, with a wide double door on the front."""
    w, h, d = size
    wall_h = 0.65 * h
    return combine(
        slab((-w / 2 + 0.05, 0.0, -d / 2 + 0.05), (w / 2 - 0.05, wall_h, d / 2 - 0.05), colour),
        gable_roof(w, d, wall_h, h - wall_h, STRAW),
        slab(
            (-0.35 * w, 0.0, d / 2 - 0.06),
            (0.35 * w, 0.85 * wall_h, d / 2 - 0.02),
            shade(colour, 0.7),
        ),
        slab((-0.01, 0.0, d / 2 - 0.05), (0.01, 0.85 * wall_h, d / 2), DARK_WOOD),
    )


@builder("tower")
def tower(size, colour) -> trimesh.Trimesh:
    """An octagonal stone tower with a pointed roof, a door and windows facing +Z."""
    w, h, d = size
    body_h = 0.75 * h
    r = 0.45 * w
    front = r * math.cos(math.pi / 8)  # an octagon's flat side is at this distance
    octagons = combine(
        cylinder(r, (0.0, 0.0, 0.0), (0.0, body_h, 0.0), colour, sections=8),
        cylinder(
            w / 2, (0.0, body_h - 0.4, 0.0), (0.0, body_h, 0.0), shade(colour, 0.85), sections=8
        ),
        cone(w / 2, (0.0, body_h, 0.0), (0.0, h, 0.0), ROOF, sections=8),
    )
    # trimesh puts an octagon's corner on +Z; turn it so a flat side faces forward.
    octagons.apply_transform(trimesh.transformations.rotation_matrix(math.pi / 8, [0, 1, 0]))
    windows = [
        slab((-0.25, y, front - 0.1), (0.25, y + 0.8, front + 0.02), DARK_WOOD)
        for y in (0.45 * body_h, 0.7 * body_h)
    ]
    return combine(
        octagons, slab((-0.5, 0.0, front - 0.1), (0.5, 2.0, front + 0.02), DARK_WOOD), windows
    )


@builder("windmill")
def windmill(size, colour) -> trimesh.Trimesh:
    """A tapering mill house under a cap, four sails in an X on its front (+Z)."""
    w, h, d = size
    body_h = 0.62 * h
    r = min(0.3 * w, 0.4 * d)
    # The sails form an X whose tips reach the sides and the top of the bounding box.
    reach = min(w / 2, 0.45 * h)
    hub = np.array([0.0, h - reach, r + 0.25])
    arm = reach * math.sqrt(2.0)
    sails = []
    for angle in (math.pi / 4, 3 * math.pi / 4, 5 * math.pi / 4, 7 * math.pi / 4):
        direction = np.array([math.cos(angle), math.sin(angle), 0.0])
        sails.append(cylinder(0.06, hub, hub + direction * arm, DARK_WOOD, sections=4))
        # The sail cloth: a lattice panel along the outer part of the arm.
        centre = hub + direction * arm * 0.6
        panel = trimesh.creation.box(extents=(0.8 * arm, 0.22 * arm, 0.04))
        panel.apply_transform(trimesh.transformations.rotation_matrix(angle, [0, 0, 1]))
        panel.apply_translation(centre + np.array([0.0, 0.0, 0.03]))
        sails.append(coloured(panel, LINEN))
    # A strongly tapering body under a wooden cap, so it never passes for a tower.
    return combine(
        frustum(r, 0.6 * r, 0.0, body_h, colour, sections=8),
        cone(
            0.72 * r,
            (0.0, body_h, 0.0),
            (0.0, body_h + 0.18 * h, 0.0),
            shade(DARK_WOOD, 1.3),
            sections=8,
        ),
        slab((-0.5, 0.0, r * 0.85), (0.5, 2.0, r * 0.95 + 0.05), DARK_WOOD),
        cylinder(0.2, (0.0, hub[1], 0.0), hub + np.array([0.0, 0.0, 0.1]), IRON, sections=8),
        sails,
    )


@builder("forge")
def forge(size, colour) -> trimesh.Trimesh:
    """A stone hearth with glowing coals in its mouth (+Z) and a chimney at the back."""
    w, h, d = size
    hearth_h = 0.35 * h
    return combine(
        slab((-w / 2, 0.0, -d / 2), (w / 2, hearth_h, d / 2), colour),
        slab(
            (-0.3 * w, hearth_h * 0.35, d / 2 - 0.35 * d),
            (0.3 * w, hearth_h * 0.8, d / 2 + 0.005),
            COAL,
        ),
        slab(
            (-0.25 * w, hearth_h * 0.35, d / 2 - 0.3 * d),
            (0.25 * w, hearth_h * 0.5, d / 2 + 0.01),
            GLOW,
        ),
        slab((-0.35 * w, hearth_h, -0.1 * d), (0.35 * w, 0.55 * h, d / 2), shade(colour, 0.85)),
        slab((-0.2 * w, hearth_h, -d / 2), (0.2 * w, h, -0.1 * d), shade(colour, 0.9)),
    )


@builder("brazier")
def brazier(size, colour) -> trimesh.Trimesh:
    """An iron fire bowl on three legs, full of glowing coals."""
    w, h, d = size
    bowl_y = 0.6 * h
    leg_feet = [(0.4 * w * math.cos(a), 0.0, 0.4 * d * math.sin(a)) for a in (0.5, 2.6, 4.7)]
    return combine(
        [
            cylinder(0.03 * w, foot, (foot[0] * 0.5, bowl_y, foot[2] * 0.5), colour, sections=4)
            for foot in leg_feet
        ],
        frustum(0.25 * w, 0.5 * w, bowl_y, 0.9 * h, colour, sections=10),
        cylinder(0.45 * w, (0.0, 0.88 * h, 0.0), (0.0, h, 0.0), GLOW, sections=10),
    )


@builder("anvil")
def anvil(size, colour) -> trimesh.Trimesh:
    """Foot, waist, face block, and a horn pointing to one side (+X)."""
    w, h, d = size
    face_w = 0.7 * w
    x0 = -w / 2
    return combine(
        slab((x0 + 0.1 * w, 0.0, -d / 2), (x0 + 0.6 * w, 0.3 * h, d / 2), colour),
        slab((x0 + 0.22 * w, 0.3 * h, -d / 4), (x0 + 0.48 * w, 0.7 * h, d / 4), colour),
        slab((x0, 0.7 * h, -d / 3), (x0 + face_w, h, d / 3), shade(colour, 1.3)),
        cone(
            0.15 * h,
            (x0 + face_w, 0.85 * h, 0.0),
            (w / 2, 0.9 * h, 0.0),
            shade(colour, 1.3),
            sections=8,
        ),
    )


@builder("hammer")
def hammer(size, colour) -> trimesh.Trimesh:
    """A hammer lying flat: wooden handle along x, iron head across its end (+X)."""
    w, h, d = size
    head_w = 0.25 * w
    return combine(
        slab((-w / 2, 0.25 * h, -0.12 * d), (w / 2 - head_w, 0.75 * h, 0.12 * d), WOOD),
        slab((w / 2 - head_w, 0.0, -d / 2), (w / 2, h, d / 2), colour),
    )


@builder("sign")
def sign(size, colour) -> trimesh.Trimesh:
    """Two posts holding a board whose painted face looks forward (+Z)."""
    w, h, d = size
    post = 0.08
    board_y0, board_y1 = 0.55 * h, h - 0.05
    return combine(
        [
            slab((x - post / 2, 0.0, -d / 2), (x + post / 2, h, -d / 2 + post), shade(colour, 0.7))
            for x in (-w / 2 + post / 2, w / 2 - post / 2)
        ],
        slab((-w / 2, board_y0, -d / 2 + post), (w / 2, board_y1, d / 2 - 0.02), colour),
        slab((-0.35 * w, board_y0 + 0.1, d / 2 - 0.02), (0.35 * w, board_y1 - 0.1, d / 2), LINEN),
    )


@builder("lamp_post")
def lamp_post(size, colour) -> trimesh.Trimesh:
    """A wooden pole on a foot, a lantern with a lit pane and a little roof at the top."""
    w, h, d = size
    lantern_y = 0.8 * h
    return combine(
        slab((-w / 2, 0.0, -d / 2), (w / 2, 0.08 * h, d / 2), shade(colour, 0.8)),
        cylinder(0.15 * w, (0.0, 0.0, 0.0), (0.0, lantern_y, 0.0), colour, sections=6),
        slab((-0.35 * w, lantern_y, -0.35 * d), (0.35 * w, 0.93 * h, 0.35 * d), LIGHT),
        cone(0.5 * w, (0.0, 0.93 * h, 0.0), (0.0, h, 0.0), IRON, sections=4),
    )


@builder("clothes_line")
def clothes_line(size, colour) -> trimesh.Trimesh:
    """Two posts at the ends (along x), a line between them, laundry hanging on it."""
    w, h, d = size
    post = min(0.1, d)
    line_y = 0.95 * h
    laundry_colours = (LINEN, GLASS, BLOSSOM, STRAW)
    laundry = [
        slab((x - 0.25, line_y - 0.7, -0.02), (x + 0.25, line_y, 0.02), laundry_colours[index % 4])
        for index, x in enumerate(np.linspace(-w / 2 + 0.8, w / 2 - 0.8, 4))
    ]
    return combine(
        [
            slab((x - post / 2, 0.0, -d / 2), (x + post / 2, h, d / 2), colour)
            for x in (-w / 2 + post / 2, w / 2 - post / 2)
        ],
        slab((-w / 2, line_y - 0.01, -0.01), (w / 2, line_y + 0.01, 0.01), LINEN),
        laundry,
    )


@builder("well")
def well(size, colour) -> trimesh.Trimesh:
    """A round stone well with dark water inside its rim."""
    w, h, d = size
    r = w / 2
    rim = trimesh.creation.annulus(
        r_min=0.72 * r, r_max=r, segment=[(0.0, 0.75 * h, 0.0), (0.0, h, 0.0)], sections=12
    )
    return combine(
        cylinder(r, (0.0, 0.0, 0.0), (0.0, 0.75 * h, 0.0), colour, sections=12),
        cylinder(0.72 * r, (0.0, 0.75 * h, 0.0), (0.0, 0.8 * h, 0.0), (0.1, 0.2, 0.3), sections=12),
        coloured(rim, shade(colour, 0.85)),
    )


@builder("field")
def field(size, colour) -> trimesh.Trimesh:
    """A plot of tilled soil with rows of crop (the catalog colour) running along z."""
    w, h, d = size
    rows = repeats(w, 0.8, least=3)
    row_w = 0.5 * w / rows
    crops = [
        slab((x - row_w / 2, 0.3 * h, -d / 2 + 0.2), (x + row_w / 2, h, d / 2 - 0.2), colour)
        for x in np.linspace(-w / 2 + w / rows / 2, w / 2 - w / rows / 2, rows)
    ]
    return combine(slab((-w / 2, 0.0, -d / 2), (w / 2, 0.3 * h, d / 2), SOIL), crops)


@builder("pine_tree")
def pine_tree(size, colour) -> trimesh.Trimesh:
    """A trunk and three stacked cones, narrowing towards the top."""
    w, h, d = size
    trunk_h = 0.2 * h
    # (radius as a fraction of the half width, base and tip heights as fractions of h)
    shapes = ((1.0, 0.15, 0.6), (0.78, 0.38, 0.8), (0.55, 0.58, 1.0))
    tiers = [
        cone(
            radius * w / 2,
            (0.0, base * h, 0.0),
            (0.0, tip * h, 0.0),
            shade(colour, 1.0 + 0.1 * index),
            sections=8,
        )
        for index, (radius, base, tip) in enumerate(shapes)
    ]
    return combine(
        cylinder(0.08 * w, (0.0, 0.0, 0.0), (0.0, trunk_h + 0.05 * h, 0.0), BARK, sections=6), tiers
    )


@builder("oak_tree")
def oak_tree(size, colour) -> trimesh.Trimesh:
    """A thick trunk under a broad crown of four overlapping leaf clusters and a top."""
    w, h, d = size
    crown_y = 0.62 * h
    clusters = [
        ball(
            (0.3 * w, 0.22 * h, 0.3 * d),
            (0.2 * w * math.cos(a), crown_y, 0.2 * d * math.sin(a)),
            shade(colour, 0.9 + 0.05 * index),
        )
        for index, a in enumerate(np.arange(4) * math.pi / 2)
    ]
    top = ball((0.3 * w, 0.2 * h, 0.3 * d), (0.0, 0.8 * h, 0.0), shade(colour, 1.15))
    return combine(frustum(0.09 * w, 0.06 * w, 0.0, 0.5 * h, BARK, sections=8), clusters, top)


@builder("bush")
def bush(size, colour) -> trimesh.Trimesh:
    """Three overlapping leafy lumps."""
    w, h, d = size
    return combine(
        ball((0.32 * w, 0.45 * h, 0.32 * d), (-0.17 * w, 0.45 * h, 0.0), colour),
        ball((0.3 * w, 0.4 * h, 0.3 * d), (0.2 * w, 0.4 * h, 0.1 * d), shade(colour, 1.1)),
        ball((0.3 * w, 0.5 * h, 0.3 * d), (0.0, 0.5 * h, -0.18 * d), shade(colour, 0.9)),
    )


@builder("sheaf")
def sheaf(size, colour) -> trimesh.Trimesh:
    """A bundle of straw tied at the waist, flaring at the foot and the ears."""
    w, h, d = size
    r = w / 2
    return combine(
        frustum(0.8 * r, 0.45 * r, 0.0, 0.5 * h, colour, sections=10),
        cylinder(
            0.48 * r, (0.0, 0.45 * h, 0.0), (0.0, 0.55 * h, 0.0), shade(colour, 0.6), sections=10
        ),
        frustum(0.45 * r, r, 0.5 * h, 0.85 * h, colour, sections=10),
        frustum(r, 0.55 * r, 0.85 * h, h, shade(colour, 1.1), sections=10),
    )


@builder("grain_pallet")
def grain_pallet(size, colour) -> trimesh.Trimesh:
    """A wooden pallet with six upright sheaves of grain on it."""
    w, h, d = size
    deck = 0.15 * h
    bundle_r = min(w / 6, d / 4)
    sheaves = [
        frustum(
            bundle_r,
            0.8 * bundle_r,
            deck,
            h,
            shade(colour, 0.95 + 0.05 * (i % 2)),
            sections=8,
            centre=(x, z),
        )
        for i, (x, z) in enumerate((x, z) for x in (-w / 3, 0.0, w / 3) for z in (-d / 4, d / 4))
    ]
    return combine(
        [
            slab((-w / 2, 0.0, z - 0.05), (w / 2, deck * 0.6, z + 0.05), DARK_WOOD)
            for z in (-0.4 * d, 0.0, 0.4 * d)
        ],
        slab((-w / 2, deck * 0.6, -d / 2), (w / 2, deck, d / 2), WOOD),
        sheaves,
    )


def _wagon(
    size, colour, load: Callable[[float, float, float, float], list[trimesh.Trimesh]]
) -> trimesh.Trimesh:
    """A two-axle cart: plank bed with side boards, four wheels, a shaft at the front (+Z).

    ``load(width, depth, floor_y, top_y)`` returns what lies on the bed.
    """
    w, h, d = size
    wheel_r = 0.13 * d
    body_d = 0.72 * d
    z_back = -d / 2
    z_front = z_back + body_d
    floor_y = wheel_r + 0.05
    side_y = min(h, floor_y + 0.45)
    wheels = [
        cylinder(
            wheel_r,
            (side * w / 2, wheel_r, z),
            (side * (w / 2 - 0.1), wheel_r, z),
            DARK_WOOD,
            sections=10,
        )
        for side in (-1, 1)
        for z in (z_back + 0.2 * body_d, z_front - 0.2 * body_d)
    ]
    inner_w = w - 0.25
    boards = [
        slab((-inner_w / 2, floor_y - 0.08, z_back), (inner_w / 2, floor_y, z_front), colour),
        slab(
            (-inner_w / 2, floor_y, z_back),
            (-inner_w / 2 + 0.05, side_y, z_front),
            shade(colour, 0.85),
        ),
        slab(
            (inner_w / 2 - 0.05, floor_y, z_back),
            (inner_w / 2, side_y, z_front),
            shade(colour, 0.85),
        ),
        slab(
            (-inner_w / 2, floor_y, z_back),
            (inner_w / 2, side_y, z_back + 0.05),
            shade(colour, 0.85),
        ),
        slab(
            (-inner_w / 2, floor_y, z_front - 0.05),
            (inner_w / 2, side_y, z_front),
            shade(colour, 0.85),
        ),
    ]
    shafts = [
        slab((x - 0.03, floor_y - 0.1, z_front), (x + 0.03, floor_y - 0.04, d / 2), DARK_WOOD)
        for x in (-0.3, 0.3)
    ]
    return combine(wheels, boards, shafts, load(inner_w - 0.1, body_d - 0.1, floor_y, h))


@builder("wagon")
def wagon(size, colour) -> trimesh.Trimesh:
    return _wagon(size, colour, lambda *_: [])


@builder("grain_wagon")
def grain_wagon(size, colour) -> trimesh.Trimesh:
    """A wagon heaped with grain: a golden mound filling its bed."""

    def heap(width, depth, floor_y, top_y):
        z_centre = -size[2] / 2 + 0.05 + depth / 2
        return [
            ball(
                (width / 2, (top_y - floor_y) / 2, depth / 2),
                (0.0, (floor_y + top_y) / 2, z_centre),
                STRAW,
            )
        ]

    return _wagon(size, colour, heap)


@builder("crate_wagon")
def crate_wagon(size, colour) -> trimesh.Trimesh:
    """A wagon loaded with wooden crates, a second layer on top at the back."""

    def crates(width, depth, floor_y, top_y):
        z_back = -size[2] / 2 + 0.05
        cell = (top_y - floor_y) / 2
        stack = [
            block(
                (0.9 * width / 2, cell, 0.9 * depth / 3),
                (x, floor_y + cell / 2, z_back + depth / 6 + i * depth / 3),
                shade(WOOD, 1.1 + 0.1 * ((i + int(x > 0)) % 2)),
            )
            for i in range(3)
            for x in (-width / 4, width / 4)
        ]
        stack.append(
            block(
                (0.9 * width / 2, cell, 0.9 * depth / 3),
                (-width / 4, floor_y + 1.5 * cell, z_back + depth / 6),
                shade(WOOD, 1.25),
            )
        )
        stack.append(
            block(
                (0.9 * width / 2, cell, 0.9 * depth / 3),
                (width / 4, floor_y + 1.5 * cell, z_back + depth / 2),
                shade(WOOD, 1.15),
            )
        )
        return stack

    return _wagon(size, colour, crates)
