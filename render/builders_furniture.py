"""Shape builders for furniture and small wares: tables, desks, chairs, beds, shelves,
lamps, screens, books, bottles, crates, pots and sacks (village stalls, desks, bedrooms).
"""

from __future__ import annotations

import math

import numpy as np
import trimesh

from .mesh_parts import (
    BLOSSOM,
    COAL,
    GLASS,
    IRON,
    LEAVES,
    LIGHT,
    LINEN,
    PAGES,
    ROOF,
    SCREEN,
    STRAW,
    WOOD,
    Builder,
    ball,
    block,
    combine,
    cone,
    cylinder,
    frustum,
    legs,
    register_in,
    shade,
    slab,
)

#: The furniture and small-ware builders by shape name.
FURNITURE: dict[str, Builder] = {}
builder = register_in(FURNITURE)


@builder("box")
def box(size, colour) -> trimesh.Trimesh:
    w, h, d = size
    return block((w, h, d), (0.0, h / 2.0, 0.0), colour)


@builder("table")
def table(size, colour) -> trimesh.Trimesh:
    """A plank top on four legs."""
    w, h, d = size
    top = 0.06 * h + 0.02
    return combine(
        slab((-w / 2, h - top, -d / 2), (w / 2, h, d / 2), colour),
        legs(w * 0.94, d * 0.9, h - top, 0.07, shade(colour, 0.75)),
    )


@builder("fancy_table")
def fancy_table(size, colour) -> trimesh.Trimesh:
    """A darker table with an apron, turned legs and a drawer facing the sitter (+Z)."""
    w, h, d = size
    top, apron = 0.04, 0.1
    leg_x, leg_z = w / 2 - 0.07, d / 2 - 0.07
    turned = [
        frustum(
            0.035,
            0.05,
            0.0,
            h - top,
            shade(colour, 0.8),
            sections=8,
            centre=(sx * leg_x, sz * leg_z),
        )
        for sx in (-1, 1)
        for sz in (-1, 1)
    ]
    return combine(
        slab((-w / 2, h - top, -d / 2), (w / 2, h, d / 2), colour),
        slab(
            (-w / 2 + 0.05, h - top - apron, -d / 2 + 0.05),
            (w / 2 - 0.05, h - top, d / 2 - 0.05),
            shade(colour, 0.85),
        ),
        slab(
            (-w * 0.2, h - top - apron * 0.85, d / 2 - 0.05),
            (w * 0.2, h - top - apron * 0.15, d / 2 - 0.04),
            shade(colour, 1.3),
        ),
        turned,
    )


@builder("desk")
def desk(size, colour) -> trimesh.Trimesh:
    """A writing desk: top, a drawer pedestal on its right (-X) and two legs on its left."""
    w, h, d = size
    top = 0.04
    pedestal_w = min(0.4, w * 0.35)
    x0 = -w / 2
    drawers = [
        slab(
            (x0 + 0.03, y, d / 2 - 0.03),
            (x0 + pedestal_w - 0.03, y + (h - top) / 3 - 0.04, d / 2),
            shade(colour, 1.2),
        )
        for y in np.linspace(0.04, (h - top) * 2 / 3, 3)
    ]
    return combine(
        slab((-w / 2, h - top, -d / 2), (w / 2, h, d / 2), colour),
        slab((x0, 0.0, -d / 2), (x0 + pedestal_w, h - top, d / 2 - 0.03), shade(colour, 0.85)),
        drawers,
        [
            block(
                (0.05, h - top, 0.05),
                (w / 2 - 0.04, (h - top) / 2, sz * (d / 2 - 0.04)),
                shade(colour, 0.7),
            )
            for sz in (-1, 1)
        ],
    )


@builder("chair")
def chair(size, colour) -> trimesh.Trimesh:
    """Seat, four legs and a back rest at the back (-Z): one sits facing +Z."""
    w, h, d = size
    seat_y, seat_t, back_t = 0.5 * h, 0.05, 0.05
    return combine(
        slab((-w / 2, seat_y - seat_t, -d / 2), (w / 2, seat_y, d / 2), colour),
        legs(w, d, seat_y - seat_t, 0.045, shade(colour, 0.75)),
        slab((-w / 2, seat_y, -d / 2), (w / 2, h, -d / 2 + back_t), shade(colour, 0.9)),
    )


@builder("nightstand")
def nightstand(size, colour) -> trimesh.Trimesh:
    """A small cabinet with two drawers on its front and knobs."""
    w, h, d = size
    fronts = []
    for y0, y1 in ((0.08, h * 0.5), (h * 0.52, h - 0.06)):
        fronts.append(
            slab(
                (-w / 2 + 0.03, y0, d / 2 - 0.01),
                (w / 2 - 0.03, y1 - 0.02, d / 2),
                shade(colour, 1.2),
            )
        )
        fronts.append(block((0.04, 0.03, 0.02), (0.0, (y0 + y1) / 2, d / 2 + 0.005), IRON))
    return combine(
        slab((-w / 2, 0.0, -d / 2), (w / 2, h - 0.03, d / 2 - 0.01), colour),
        slab((-w / 2, h - 0.03, -d / 2), (w / 2, h, d / 2), shade(colour, 0.85)),
        fronts,
    )


@builder("wardrobe")
def wardrobe(size, colour) -> trimesh.Trimesh:
    """A tall cabinet with two doors and handles on its front (+Z)."""
    w, h, d = size
    doors, handles = [], []
    for side in (-1, 1):
        inner, outer = side * 0.01, side * (w / 2 - 0.03)
        doors.append(
            slab(
                (min(inner, outer), 0.1, d / 2 - 0.02),
                (max(inner, outer), h - 0.08, d / 2),
                shade(colour, 1.15),
            )
        )
        handles.append(block((0.02, 0.25, 0.03), (side * 0.07, h * 0.55, d / 2 + 0.01), IRON))
    return combine(
        slab((-w / 2, 0.0, -d / 2), (w / 2, h, d / 2 - 0.02), colour),
        doors,
        handles,
    )


@builder("bookshelf")
def bookshelf(size, colour) -> trimesh.Trimesh:
    """An open shelf unit, back at -Z, with a row of books on each of its shelves."""
    w, h, d = size
    board = 0.025
    levels = 4
    spacing = (h - board) / levels
    parts = [
        slab((-w / 2, 0.0, -d / 2), (w / 2, h, -d / 2 + board), shade(colour, 0.8)),
        slab((-w / 2, 0.0, -d / 2), (-w / 2 + board, h, d / 2), colour),
        slab((w / 2 - board, 0.0, -d / 2), (w / 2, h, d / 2), colour),
    ]
    book_colours = (BLOSSOM, GLASS, STRAW, shade(LEAVES, 1.2), ROOF)
    for level in range(levels + 1):
        y = level * spacing
        parts.append(slab((-w / 2, y, -d / 2), (w / 2, y + board, d / 2), colour))
        if level == levels:
            break
        # A row of books covering most of the shelf, each a slightly different height.
        edges = np.linspace(-w / 2 + board, w / 2 - board - 0.1 * w, 6)
        for index, (x0, x1) in enumerate(zip(edges[:-1], edges[1:], strict=False)):
            top = y + board + spacing * (0.6 + 0.06 * (index % 3))
            parts.append(
                slab(
                    (x0 + 0.005, y + board, -d / 2 + board),
                    (x1 - 0.005, top, d / 2 - 0.05),
                    book_colours[(index + level) % 5],
                )
            )
    return combine(parts)


@builder("bed")
def bed(size, colour) -> trimesh.Trimesh:
    """Frame, mattress, blanket and pillow, with the headboard at the back (-Z)."""
    w, h, d = size
    frame_top, mattress_top = 0.3 * h, 0.55 * h
    head = 0.06
    return combine(
        slab((-w / 2, 0.0, -d / 2 + head), (w / 2, frame_top, d / 2), colour),
        slab((-w / 2, 0.0, -d / 2), (w / 2, h, -d / 2 + head), shade(colour, 0.85)),
        slab(
            (-w / 2 + 0.03, frame_top, -d / 2 + head),
            (w / 2 - 0.03, mattress_top, d / 2 - 0.03),
            LINEN,
        ),
        slab(
            (-w / 2 + 0.02, mattress_top, -d / 2 + head + 0.5),
            (w / 2 - 0.02, mattress_top + 0.04, d / 2 - 0.02),
            shade(GLASS, 1.1),
        ),
        slab(
            (-w / 2 + 0.12, mattress_top, -d / 2 + head + 0.06),
            (w / 2 - 0.12, mattress_top + 0.12, -d / 2 + head + 0.4),
            PAGES,
        ),
    )


@builder("rug")
def rug(size, colour) -> trimesh.Trimesh:
    """A flat rug with a lighter border."""
    w, h, d = size
    border = 0.12 * min(w, d)
    return combine(
        slab((-w / 2, 0.0, -d / 2), (w / 2, h * 0.6, d / 2), shade(colour, 1.5)),
        slab((-w / 2 + border, 0.0, -d / 2 + border), (w / 2 - border, h, d / 2 - border), colour),
    )


@builder("potted_plant")
def potted_plant(size, colour) -> trimesh.Trimesh:
    """A clay pot with a leafy crown; the catalog colour is the foliage."""
    w, h, d = size
    pot_h = 0.35 * h
    crown = (w / 2, (h - pot_h) / 2, d / 2)
    return combine(
        frustum(0.3 * w, 0.42 * w, 0.0, pot_h, (0.72, 0.38, 0.22), sections=10),
        ball(crown, (0.0, pot_h + crown[1], 0.0), colour),
    )


@builder("table_lamp")
def table_lamp(size, colour) -> trimesh.Trimesh:
    """A bedside lamp: round base, stem, and a cloth shade (the catalog colour)."""
    w, h, d = size
    return combine(
        frustum(0.3 * w, 0.22 * w, 0.0, 0.08 * h, IRON, sections=10),
        cylinder(0.04 * w, (0.0, 0.08 * h, 0.0), (0.0, 0.55 * h, 0.0), IRON, sections=6),
        frustum(0.5 * w, 0.3 * w, 0.5 * h, h, colour, sections=10),
    )


@builder("desk_lamp")
def desk_lamp(size, colour) -> trimesh.Trimesh:
    """An angled desk lamp: base at the back, arm up and forward, shade aiming down at +Z."""
    w, h, d = size
    base_z = -d / 2 + w / 2
    shade_z = d / 2 - 0.3 * w
    return combine(
        frustum(0.5 * w, 0.4 * w, 0.0, 0.06 * h, IRON, sections=10, centre=(0.0, base_z)),
        cylinder(0.05 * w, (0.0, 0.06 * h, base_z), (0.0, 0.8 * h, base_z), colour, sections=6),
        cylinder(0.05 * w, (0.0, 0.8 * h, base_z), (0.0, 0.95 * h, shade_z), colour, sections=6),
        cone(0.3 * w, (0.0, 0.6 * h, shade_z), (0.0, h, shade_z - 0.1 * d), colour, sections=10),
        ball(0.1 * w, (0.0, 0.62 * h, shade_z), LIGHT, subdivisions=0),
    )


@builder("laptop")
def laptop(size, colour) -> trimesh.Trimesh:
    """A thin base with keyboard and an open screen standing at its back edge (-Z)."""
    w, h, d = size
    base_t, lid_t = 0.1 * h, 0.012
    return combine(
        slab((-w / 2, 0.0, -d / 2), (w / 2, base_t, d / 2), colour),
        slab(
            (-w * 0.42, base_t, -d * 0.3), (w * 0.42, base_t + 0.002, d * 0.1), shade(colour, 0.5)
        ),
        slab((-w / 2, base_t, -d / 2), (w / 2, h, -d / 2 + lid_t), colour),
        slab(
            (-w * 0.45, base_t + 0.01, -d / 2 + lid_t),
            (w * 0.45, h - 0.01, -d / 2 + lid_t + 0.002),
            SCREEN,
        ),
    )


def _screen_slab(size, colour, border: float) -> trimesh.Trimesh:
    """A flat device lying face up: a case with a dark glass face inset by ``border``."""
    w, h, d = size
    return combine(
        slab((-w / 2, 0.0, -d / 2), (w / 2, h * 0.85, d / 2), colour),
        slab(
            (-w / 2 + border, h * 0.85, -d / 2 + border),
            (w / 2 - border, h, d / 2 - border),
            SCREEN,
        ),
    )


@builder("tablet")
def tablet(size, colour) -> trimesh.Trimesh:
    return _screen_slab(size, colour, 0.012)


@builder("phone")
def phone(size, colour) -> trimesh.Trimesh:
    return _screen_slab(size, colour, 0.006)


@builder("desk_phone")
def desk_phone(size, colour) -> trimesh.Trimesh:
    """A telephone: sloped body with a keypad at the front and a handset lying across."""
    w, h, d = size
    return combine(
        slab((-w / 2, 0.0, -d / 2), (w / 2, 0.6 * h, d / 2), colour),
        slab((-w * 0.3, 0.6 * h, 0.05 * d), (w * 0.3, 0.65 * h, 0.4 * d), shade(colour, 0.6)),
        slab((-w / 2, 0.6 * h, -d * 0.45), (w / 2, h, -d * 0.1), shade(colour, 0.85)),
    )


@builder("paper")
def paper(size, colour) -> trimesh.Trimesh:
    """A sheet with a few printed lines."""
    w, h, d = size
    lines = [
        slab(
            (-w * 0.38, h * 0.8, z - 0.003),
            (w * (0.38 if index % 3 else 0.1), h, z + 0.003),
            (0.3, 0.3, 0.32),
        )
        for index, z in enumerate(np.linspace(-d * 0.38, d * 0.3, 7))
    ]
    return combine(slab((-w / 2, 0.0, -d / 2), (w / 2, h * 0.8, d / 2), colour), lines)


@builder("book")
def book(size, colour) -> trimesh.Trimesh:
    """A closed book lying flat: covers in the catalog colour, pages showing on three sides."""
    w, h, d = size
    cover = 0.12 * h
    return combine(
        slab((-w / 2, 0.0, -d / 2), (w / 2, cover, d / 2), colour),
        slab((-w / 2, h - cover, -d / 2), (w / 2, h, d / 2), colour),
        slab((-w / 2, 0.0, -d / 2), (-w / 2 + 0.01, h, d / 2), shade(colour, 0.8)),
        slab(
            (-w / 2 + 0.01, cover, -d / 2 + 0.005), (w / 2 - 0.005, h - cover, d / 2 - 0.005), PAGES
        ),
    )


@builder("bottle")
def bottle(size, colour) -> trimesh.Trimesh:
    """Glass body, shoulder, neck and cork."""
    w, h, d = size
    r = w / 2
    return combine(
        cylinder(r, (0.0, 0.0, 0.0), (0.0, 0.6 * h, 0.0), colour, sections=8),
        frustum(r, 0.35 * r, 0.6 * h, 0.72 * h, colour, sections=8),
        cylinder(0.3 * r, (0.0, 0.72 * h, 0.0), (0.0, 0.93 * h, 0.0), colour, sections=6),
        cylinder(0.32 * r, (0.0, 0.93 * h, 0.0), (0.0, h, 0.0), WOOD, sections=6),
    )


@builder("wine_box")
def wine_box(size, colour) -> trimesh.Trimesh:
    """An open wooden crate with six bottle necks showing above its rim."""
    w, h, d = size
    rim = 0.7 * h
    necks = [
        cylinder(0.025, (x, rim - 0.05, z), (x, h, z), (0.15, 0.35, 0.2), sections=6)
        for x in (-w / 3, 0.0, w / 3)
        for z in (-d / 4, d / 4)
    ]
    return combine(
        slab((-w / 2, 0.0, -d / 2), (w / 2, rim, d / 2), colour),
        slab(
            (-w / 2 - 0.005, rim * 0.45, -d / 2 - 0.005),
            (w / 2 + 0.005, rim * 0.55, d / 2 + 0.005),
            shade(colour, 0.7),
        ),
        necks,
    )


@builder("crate")
def crate(size, colour) -> trimesh.Trimesh:
    """A closed wooden crate: a box with darker slats round its sides and across its lid."""
    w, h, d = size
    slat = shade(colour, 0.7)
    t = 0.02 * min(w, d)  # slats stand this far proud of the boards
    bands = [
        slab((-w / 2 - t, y - 0.04 * h, -d / 2 - t), (w / 2 + t, y + 0.04 * h, d / 2 + t), slat)
        for y in (0.15 * h, 0.85 * h)
    ]
    lid = [
        slab((x - 0.04 * w, h, -d / 2), (x + 0.04 * w, h + t, d / 2), slat) for x in (-w / 3, w / 3)
    ]
    return combine(slab((-w / 2, 0.0, -d / 2), (w / 2, h, d / 2), colour), bands, lid)


@builder("flowerpot")
def flowerpot(size, colour) -> trimesh.Trimesh:
    """A terracotta pot (the catalog colour) with green leaves and a few blossoms."""
    w, h, d = size
    pot_h = 0.55 * h
    leaves_r = (0.45 * w, (h - pot_h) / 2, 0.45 * d)
    leaves_y = pot_h + leaves_r[1]
    blossoms = [
        ball(
            0.1 * w,
            (0.25 * w * math.cos(a), leaves_y + 0.5 * leaves_r[1], 0.25 * d * math.sin(a)),
            BLOSSOM,
            subdivisions=0,
        )
        for a in (0.3, 2.4, 4.4)
    ]
    return combine(
        frustum(0.34 * w, 0.5 * w, 0.0, pot_h, colour, sections=10),
        ball(leaves_r, (0.0, leaves_y, 0.0), LEAVES),
        blossoms,
    )


@builder("pot")
def pot(size, colour) -> trimesh.Trimesh:
    """A big iron cooking pot full of stew, with two handles at its sides."""
    w, h, d = size
    r = 0.42 * w
    return combine(
        frustum(0.8 * r, r, 0.0, 0.35 * h, colour, sections=12),
        frustum(r, 0.95 * r, 0.35 * h, 0.9 * h, colour, sections=12),
        cylinder(0.9 * r, (0.0, 0.9 * h, 0.0), (0.0, h, 0.0), (0.55, 0.3, 0.12), sections=12),
        [
            block(
                (w / 2 - r + 0.02, 0.04, 0.08),
                (side * (w / 2 - (w / 2 - r) / 2), 0.75 * h, 0.0),
                IRON,
            )
            for side in (-1, 1)
        ],
    )


@builder("barrel")
def barrel(size, colour) -> trimesh.Trimesh:
    """A bulging wooden barrel with iron hoops."""
    w, h, d = size
    r = w / 2
    hoops = [
        cylinder(0.98 * r, (0.0, y - 0.02, 0.0), (0.0, y + 0.02, 0.0), IRON, sections=10)
        for y in (0.15 * h, 0.85 * h)
    ]
    return combine(
        frustum(0.85 * r, 0.97 * r, 0.0, 0.5 * h, colour, sections=10),
        frustum(0.97 * r, 0.85 * r, 0.5 * h, h, colour, sections=10),
        hoops,
    )


def _pail(size, colour, contents) -> trimesh.Trimesh:
    """A bucket: tapered body, a bail handle over the top, and what fills it."""
    w, h, d = size
    body_h = 0.75 * h
    return combine(
        frustum(0.38 * w, 0.5 * w, 0.0, body_h, colour, sections=10),
        cylinder(0.45 * w, (0.0, body_h - 0.02, 0.0), (0.0, body_h, 0.0), contents, sections=10),
        slab((-0.48 * w, body_h - 0.1 * h, -0.015), (-0.44 * w, h, 0.015), IRON),
        slab((0.44 * w, body_h - 0.1 * h, -0.015), (0.48 * w, h, 0.015), IRON),
        slab((-0.48 * w, h - 0.02, -0.015), (0.48 * w, h, 0.015), IRON),
    )


@builder("bucket")
def bucket(size, colour) -> trimesh.Trimesh:
    return _pail(size, colour, GLASS)


@builder("coal_bucket")
def coal_bucket(size, colour) -> trimesh.Trimesh:
    return _pail(size, colour, COAL)


@builder("sack")
def sack(size, colour) -> trimesh.Trimesh:
    """A filled sack: a plump body gathered at the top into a tied tuft."""
    w, h, d = size
    r = w / 2
    mesh = combine(
        frustum(0.9 * r, r, 0.0, 0.55 * h, colour, sections=8),
        frustum(r, 0.2 * r, 0.55 * h, 0.85 * h, colour, sections=8),
        frustum(0.15 * r, 0.35 * r, 0.85 * h, h, shade(colour, 0.8), sections=6),
    )
    mesh.apply_scale((1.0, 1.0, d / w))  # sacks are flatter front to back
    return mesh
