"""Shape builders for living rooms, dining rooms and classrooms: sofas, armchairs, tables,
a television and its stand, a dresser, a piano, a whiteboard and a floor lamp.
"""

from __future__ import annotations

import numpy as np
import trimesh

from .mesh_parts import (
    BLOSSOM,
    COAL,
    DARK_WOOD,
    GLASS,
    IRON,
    LIGHT,
    LINEN,
    ROOF,
    SCREEN,
    Builder,
    ball,
    block,
    combine,
    cylinder,
    frustum,
    legs,
    register_in,
    shade,
    slab,
)

#: The living-room, dining-room and classroom builders by shape name.
HOME: dict[str, Builder] = {}
builder = register_in(HOME)


def _upholstered(size, colour, seats: int) -> trimesh.Trimesh:
    """A sofa or an armchair: a base on short legs, ``seats`` seat and back cushions
    between two arms, a back rest at -Z; one sits facing +Z."""
    w, h, d = size
    leg_h, seat_y, arm_h = 0.1 * h, 0.5 * h, 0.7 * h
    arm_w, back_d, cushion_t = min(0.18 * w, 0.2), 0.22 * d, 0.12 * h
    inner = np.linspace(-w / 2 + arm_w, w / 2 - arm_w, seats + 1)
    cushions = []
    for x0, x1 in zip(inner[:-1], inner[1:], strict=False):
        cushions.append(
            slab(
                (x0 + 0.005, seat_y - cushion_t, -d / 2 + back_d),
                (x1 - 0.005, seat_y, d / 2 - 0.02),
                shade(colour, 1.12),
            )
        )
        cushions.append(
            slab(
                (x0 + 0.01, seat_y, -d / 2 + back_d),
                (x1 - 0.01, 0.9 * h, -d / 2 + back_d + 0.15 * d),
                shade(colour, 1.05),
            )
        )
    return combine(
        legs(0.96 * w, 0.9 * d, leg_h, 0.05, DARK_WOOD),
        slab((-w / 2, leg_h, -d / 2), (w / 2, seat_y - cushion_t, d / 2), colour),
        [
            slab((x0, leg_h, -d / 2), (x1, arm_h, d / 2), shade(colour, 0.92))
            for x0, x1 in ((-w / 2, -w / 2 + arm_w), (w / 2 - arm_w, w / 2))
        ],
        slab((-w / 2, leg_h, -d / 2), (w / 2, h, -d / 2 + back_d), shade(colour, 0.85)),
        cushions,
    )


@builder("sofa")
def sofa(size, colour) -> trimesh.Trimesh:
    """Two or three seats (by width) between two arms, a back rest at -Z."""
    w = size[0]
    return _upholstered(size, colour, int(np.clip(round((w - 2 * min(0.18 * w, 0.2)) / 0.6), 1, 3)))


@builder("armchair")
def armchair(size, colour) -> trimesh.Trimesh:
    """One seat between two arms, a back rest at -Z."""
    return _upholstered(size, colour, 1)


@builder("coffee_table")
def coffee_table(size, colour) -> trimesh.Trimesh:
    """A low table: top on four legs, a shelf below with two magazines on it."""
    w, h, d = size
    top, shelf_y = min(0.05, 0.12 * h), 0.15 * h
    return combine(
        slab((-w / 2, h - top, -d / 2), (w / 2, h, d / 2), colour),
        legs(w, d, h - top, 0.05, shade(colour, 0.75)),
        slab(
            (-w / 2 + 0.03, shelf_y, -d / 2 + 0.03),
            (w / 2 - 0.03, shelf_y + 0.025, d / 2 - 0.03),
            shade(colour, 0.9),
        ),
        slab(
            (-0.3 * w, shelf_y + 0.025, -0.25 * d), (-0.05 * w, shelf_y + 0.035, 0.15 * d), BLOSSOM
        ),
        slab((0.05 * w, shelf_y + 0.025, -0.1 * d), (0.28 * w, shelf_y + 0.04, 0.3 * d), GLASS),
    )


@builder("tv_stand")
def tv_stand(size, colour) -> trimesh.Trimesh:
    """A low media cabinet on short legs: a door either side, an open middle shelf with
    a dark media box in it, all on the front (+Z)."""
    w, h, d = size
    leg_h, top = 0.12 * h, 0.04
    body_front = d / 2 - 0.02
    door = (-w / 2 + 0.02, -w / 6 - 0.005), (w / 6 + 0.005, w / 2 - 0.02)
    return combine(
        legs(0.96 * w, 0.9 * d, leg_h, 0.04, IRON),
        slab((-w / 2, leg_h, -d / 2), (w / 2, h - top, body_front), colour),
        slab((-w / 2, h - top, -d / 2), (w / 2, h, d / 2), shade(colour, 0.8)),
        [
            slab((x0, leg_h + 0.02, body_front), (x1, h - top - 0.02, d / 2), shade(colour, 1.15))
            for x0, x1 in door
        ],
        [
            block((0.02, 0.12 * h, 0.02), (x, (leg_h + h - top) / 2, d / 2 - 0.01), IRON)
            for x in (-w / 6 - 0.04, w / 6 + 0.04)
        ],
        # The open shelf: its shadowed inside, and a media box standing in it.
        slab(
            (-w / 6 + 0.01, leg_h + 0.02, body_front - 0.004),
            (w / 6 - 0.01, h - top - 0.02, body_front + 0.002),
            shade(colour, 0.4),
        ),
        slab(
            (-w / 8, leg_h + 0.025, body_front - 0.004),
            (w / 8, leg_h + 0.025 + 0.25 * (h - top - leg_h), d / 2 - 0.004),
            COAL,
        ),
        block((0.015, 0.01, 0.004), (w / 8 - 0.03, leg_h + 0.06, d / 2 - 0.003), LIGHT),
    )


@builder("tv")
def tv(size, colour) -> trimesh.Trimesh:
    """A flat screen facing +Z on a neck and a flat foot (the foot's depth is the depth)."""
    w, h, d = size
    panel_t, bezel, panel_y = min(0.05, 0.3 * d), min(0.03, 0.05 * w), 0.14 * h
    return combine(
        slab((-0.22 * w, 0.0, -d / 2), (0.22 * w, 0.02 * h, d / 2), colour),
        slab(
            (-0.05 * w, 0.02 * h, -panel_t / 2 - 0.01),
            (0.05 * w, panel_y + 0.1 * h, -panel_t / 2 + 0.005),
            shade(colour, 1.2),
        ),
        slab((-w / 2, panel_y, -panel_t / 2), (w / 2, h, panel_t / 2), colour),
        slab(
            (-w / 2 + bezel, panel_y + bezel, panel_t / 2),
            (w / 2 - bezel, h - bezel, panel_t / 2 + 0.004),
            SCREEN,
        ),
        # A faint sheen across the glass, so the screen reads as one.
        slab(
            (-w / 2 + bezel, h - 0.35 * (h - panel_y), panel_t / 2 + 0.004),
            (-0.1 * w, h - bezel, panel_t / 2 + 0.005),
            shade(SCREEN, 1.6),
        ),
    )


@builder("dining_table")
def dining_table(size, colour) -> trimesh.Trimesh:
    """A table top over an apron on four legs, a runner down its middle and a plate at
    each end of either long side."""
    w, h, d = size
    top, apron = 0.04, 0.09
    plate_r = min(0.12, 0.14 * d, 0.12 * w)
    plates = [
        cylinder(plate_r, (x, h - 0.004, z), (x, h, z), LINEN, sections=12)
        for x in (-0.25 * w, 0.25 * w)
        for z in (-d / 2 + 1.3 * plate_r, d / 2 - 1.3 * plate_r)
    ]
    return combine(
        slab((-w / 2, h - top, -d / 2), (w / 2, h - 0.004, d / 2), colour),
        slab(
            (-w / 2 + 0.06, h - top - apron, -d / 2 + 0.06),
            (w / 2 - 0.06, h - top, d / 2 - 0.06),
            shade(colour, 0.8),
        ),
        legs(w - 0.08, d - 0.08, h - top, 0.07, shade(colour, 0.8)),
        slab((-0.42 * w, h - 0.004, -0.12 * d), (0.42 * w, h, 0.12 * d), shade(ROOF, 1.2)),
        plates,
    )


@builder("dresser")
def dresser(size, colour) -> trimesh.Trimesh:
    """A chest of drawers on a plinth: two small drawers over two wide ones, knobs on
    the front (+Z), a top slightly proud of the body."""
    w, h, d = size
    plinth, top = 0.06 * h, 0.03
    front = d / 2 - 0.035
    rows = np.linspace(plinth + 0.01, h - top - 0.01, 4)
    fronts, knobs = [], []
    for row, (y0, y1) in enumerate(zip(rows[:-1], rows[1:], strict=False)):
        columns = (
            ((-w / 2 + 0.02, -0.005), (0.005, w / 2 - 0.02))
            if row == 2
            else ((-w / 2 + 0.02, w / 2 - 0.02),)
        )
        for x0, x1 in columns:
            fronts.append(
                slab((x0, y0 + 0.008, front), (x1, y1 - 0.008, d / 2 - 0.02), shade(colour, 1.15))
            )
            for x in (
                ((x0 + x1) / 2,)
                if len(columns) == 2
                else (x0 + 0.25 * (x1 - x0), x1 - 0.25 * (x1 - x0))
            ):
                knobs.append(block((0.03, 0.025, 0.02), (x, (y0 + y1) / 2, d / 2 - 0.01), IRON))
    return combine(
        slab(
            (-w / 2 + 0.02, 0.0, -d / 2 + 0.02),
            (w / 2 - 0.02, plinth, front - 0.02),
            shade(colour, 0.7),
        ),
        slab((-w / 2, plinth, -d / 2), (w / 2, h - top, front), colour),
        slab((-w / 2, h - top, -d / 2), (w / 2, h, d / 2), shade(colour, 0.85)),
        fronts,
        knobs,
    )


@builder("piano")
def piano(size, colour) -> trimesh.Trimesh:
    """An upright piano: the tall case at the back (-Z), the keyboard standing out on
    its front (+Z) between two cheeks on legs, a music desk above it, pedals below."""
    w, h, d = size
    case_front = -d / 2 + 0.55 * d
    key_y = 0.58 * h  # the top of the white keys
    side = 0.05
    keys_x0, keys_x1 = -w / 2 + side, w / 2 - side
    octaves = int(
        np.clip(round((keys_x1 - keys_x0) / 0.3), 1, 4)
    )  # black keys drawn coarser than life
    white = (keys_x1 - keys_x0) / (7 * octaves)
    black_keys = [
        slab(
            (x - 0.3 * white, key_y, case_front),
            (x + 0.3 * white, key_y + 0.02, case_front + 0.6 * (d / 2 - case_front)),
            COAL,
        )
        for octave in range(octaves)
        for x in (keys_x0 + (7 * octave + i + 1) * white for i in (0, 1, 3, 4, 5))
    ]
    ends = []
    for x0 in (-w / 2, w / 2 - side):
        ends.append(
            slab(
                (x0, key_y - 0.12, case_front), (x0 + side, key_y + 0.06, d / 2), shade(colour, 0.9)
            )
        )
        ends.append(
            slab(
                (x0 + 0.01, 0.0, d / 2 - 0.07),
                (x0 + side - 0.01, key_y - 0.12, d / 2 - 0.02),
                colour,
            )
        )
    return combine(
        slab((-w / 2, 0.0, -d / 2), (w / 2, h - 0.03, case_front), colour),
        slab((-w / 2, h - 0.03, -d / 2), (w / 2, h, case_front + 0.01), shade(colour, 1.25)),
        ends,
        slab(
            (keys_x0, key_y - 0.1, case_front),
            (keys_x1, key_y - 0.025, d / 2 - 0.01),
            shade(colour, 0.8),
        ),
        slab(
            (keys_x0, key_y - 0.025, case_front),
            (keys_x1, key_y, d / 2 - 0.015),
            (0.95, 0.94, 0.88),
        ),
        black_keys,
        slab(
            (keys_x0, key_y, case_front),
            (keys_x1, key_y + 0.1, case_front + 0.025),
            shade(colour, 0.8),
        ),
        slab(
            (-0.3 * w, key_y + 0.16, case_front),
            (0.3 * w, key_y + 0.34, case_front + 0.02),
            shade(colour, 1.3),
        ),
        [
            slab(
                (x - 0.02, 0.03, case_front), (x + 0.02, 0.05, case_front + 0.12), (0.8, 0.65, 0.3)
            )
            for x in (-0.07, 0.0, 0.07)
        ],
    )


@builder("whiteboard")
def whiteboard(size, colour) -> trimesh.Trimesh:
    """A board (the catalog colour) in a metal frame between two legs on feet, writing in
    marker on its front (+Z) and a pen tray along its foot. Made shallow (a few
    centimetres deep) it is a board on two posts standing against a wall."""
    w, h, d = size
    metal = (0.66, 0.68, 0.71)
    half = min(0.02, 0.3 * d)  # the board's half thickness
    face = half + min(0.004, 0.1 * d)
    y0, y1 = 0.4 * h, h - 0.03
    x0, x1 = -w / 2 + 0.05, w / 2 - 0.05
    lines = [
        slab((x0 + 0.1 * w, y, face), (x0 + (0.1 + length) * w, y + 0.012, face + 0.001), ink)
        for y, length, ink in (
            (y1 - 0.12 * (y1 - y0), 0.45, (0.15, 0.3, 0.75)),
            (y1 - 0.3 * (y1 - y0), 0.6, (0.1, 0.1, 0.12)),
            (y1 - 0.45 * (y1 - y0), 0.35, (0.1, 0.1, 0.12)),
            (y0 + 0.3 * (y1 - y0), 0.25, (0.8, 0.2, 0.2)),
        )
    ]
    box_x, box_y = x0 + 0.55 * w, y0 + 0.15 * (y1 - y0)
    sketch = [  # a red box drawn on the right: two sides and top and bottom
        slab(
            (box_x, box_y, face),
            (box_x + 0.012, box_y + 0.25 * (y1 - y0), face + 0.001),
            (0.8, 0.2, 0.2),
        ),
        slab(
            (box_x + 0.2 * w, box_y, face),
            (box_x + 0.2 * w + 0.012, box_y + 0.25 * (y1 - y0), face + 0.001),
            (0.8, 0.2, 0.2),
        ),
        slab((box_x, box_y, face), (box_x + 0.2 * w, box_y + 0.012, face + 0.001), (0.8, 0.2, 0.2)),
        slab(
            (box_x, box_y + 0.25 * (y1 - y0) - 0.012, face),
            (box_x + 0.2 * w, box_y + 0.25 * (y1 - y0), face + 0.001),
            (0.8, 0.2, 0.2),
        ),
    ]
    tray = min(0.06, d / 2 - face)
    parts = [
        [
            slab((x - 0.02, 0.0, -d / 2), (x + 0.02, 0.04, d / 2), metal)
            for x in (-w / 2 + 0.02, w / 2 - 0.02)
        ],
        [
            slab((x - 0.02, 0.04, -half), (x + 0.02, h, half), metal)
            for x in (-w / 2 + 0.02, w / 2 - 0.02)
        ],
        slab((x0, y0, -half), (x1, y1, half), metal),
        slab((x0 + 0.025, y0 + 0.025, -face), (x1 - 0.025, y1 - 0.025, face), colour),
        lines,
        sketch,
    ]
    if tray > 0.005:
        parts.append(slab((-0.3 * w, y0 - 0.01, half), (0.3 * w, y0 + 0.02, half + tray), metal))
    return combine(*parts)


@builder("floor_lamp")
def floor_lamp(size, colour) -> trimesh.Trimesh:
    """A standing lamp: a round foot, a tall thin pole, a lit bulb under a cloth shade
    (the catalog colour) at the top."""
    w, h, d = size
    return combine(
        frustum(0.4 * w, 0.32 * w, 0.0, min(0.04, 0.05 * h), IRON, sections=12),
        cylinder(0.04 * w, (0.0, 0.0, 0.0), (0.0, 0.8 * h, 0.0), IRON, sections=6),
        ball(0.12 * w, (0.0, 0.76 * h, 0.0), LIGHT, subdivisions=0),
        frustum(0.5 * w, 0.3 * w, 0.72 * h, h, colour, sections=12),
    )
