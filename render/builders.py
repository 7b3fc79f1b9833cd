"""Procedural low-poly mesh builders, one per ``shape`` name a catalog entry may use.

A builder takes the catalog size (w, h, d) and colour and returns a ``trimesh.Trimesh``
in the object's local frame: base centre at the origin, +Y up, front towards +Z (the
convention of ``scenewright.core.frames``). The shape names, and what each one's front
is, are the registry ``scenewright.core.shapes.SHAPES``, which the static checks read
too; importing this module fails unless its builders and that registry name exactly
the same shapes. ``scenewright.render.meshes`` then fits the result exactly to
the size, so a builder only has to get proportions right; each one builds at the real
size so the fit barely scales. Colours go on as per-face colours so one object can have
several: the catalog colour is the main one (a house's walls), the builder picks the
others (its roof, door and windows) from the palette below. A builder's detail never
grows with the size: parts it repeats along a length (a field's crop rows) number at
most ``MAX_REPEATS`` (``repeats``), so a 1 km field costs what a 30 m one does.

The file is in three parts: colour and solid helpers, then the builders grouped by
where they appear (furniture and small wares, the village, then homes, kitchens,
bathrooms and classrooms). Every builder stays well under 500 triangles.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping

import numpy as np
import trimesh

from scenewright.core.limits import MAX_REPEATS
from scenewright.core.shapes import SHAPES, Shape

Builder = Callable[[tuple[float, float, float], tuple[float, float, float]], trimesh.Trimesh]

#: Every builder by shape name. Register new ones with ``@builder("name")``.
BUILDERS: dict[str, Builder] = {}


def builder(name: str) -> Callable[[Builder], Builder]:
    def register(function: Builder) -> Builder:
        BUILDERS[name] = function
        return function

    return register


# ---------------------------------------------------------------------------------
# Secondary colours (linear RGB). The catalog colour stays the main one.

WOOD = (0.52, 0.35, 0.2)
DARK_WOOD = (0.3, 0.2, 0.12)
IRON = (0.22, 0.22, 0.25)
ROOF = (0.55, 0.22, 0.15)
STRAW = (0.8, 0.68, 0.38)
SOIL = (0.38, 0.27, 0.17)
LEAVES = (0.22, 0.48, 0.2)
BARK = (0.36, 0.25, 0.15)
GLASS = (0.35, 0.5, 0.65)
GLOW = (1.0, 0.55, 0.15)
LIGHT = (1.0, 0.9, 0.55)
LINEN = (0.92, 0.9, 0.84)
COAL = (0.08, 0.08, 0.09)
SCREEN = (0.1, 0.14, 0.2)
PAGES = (0.93, 0.9, 0.8)
BLOSSOM = (0.9, 0.3, 0.45)
CHROME = (0.78, 0.79, 0.82)
WORKTOP = (0.28, 0.28, 0.3)
WATER = (0.55, 0.75, 0.88)
SHOWER_GLASS = (0.78, 0.9, 0.94)


def repeats(length: float, spacing: float, least: int = 1) -> int:
    """How many parts ``spacing`` apart fit along ``length``: at least ``least``, at most
    ``MAX_REPEATS``, so a mesh's triangle count is bounded whatever its size."""
    return min(max(least, int(length / spacing)), MAX_REPEATS)


def shade(colour, factor: float) -> tuple[float, float, float]:
    """``colour`` made darker (factor < 1) or lighter (factor > 1), clipped to [0, 1]."""
    return tuple(float(c) for c in np.clip(np.asarray(colour, dtype=float) * factor, 0.0, 1.0))


# ---------------------------------------------------------------------------------
# Solids. Each returns one coloured mesh; builders concatenate them with ``combine``.


def coloured(mesh: trimesh.Trimesh, colour) -> trimesh.Trimesh:
    """Give every face of ``mesh`` one RGB colour in [0, 1]."""
    rgba = np.append(np.clip(np.asarray(colour, dtype=float), 0, 1), 1.0)
    mesh.visual.face_colors = np.tile((rgba * 255).round().astype(np.uint8), (len(mesh.faces), 1))
    return mesh


def block(extents, centre, colour) -> trimesh.Trimesh:
    """An axis-aligned box with the given extents (x, y, z) and centre, in one colour."""
    mesh = trimesh.creation.box(extents=extents)
    mesh.apply_translation(centre)
    return coloured(mesh, colour)


def slab(low, high, colour) -> trimesh.Trimesh:
    """An axis-aligned box between the corners ``low`` and ``high`` (x, y, z)."""
    low, high = np.asarray(low, dtype=float), np.asarray(high, dtype=float)
    return block(high - low, (low + high) / 2.0, colour)


def cylinder(radius: float, bottom, top, colour, sections: int = 10) -> trimesh.Trimesh:
    """A cylinder from point ``bottom`` to point ``top`` (any direction)."""
    mesh = trimesh.creation.cylinder(radius=radius, segment=[bottom, top], sections=sections)
    return coloured(mesh, colour)


def frustum(
    bottom_radius: float,
    top_radius: float,
    y0: float,
    y1: float,
    colour,
    sections: int = 10,
    centre=(0.0, 0.0),
) -> trimesh.Trimesh:
    """An upright truncated cone from height ``y0`` to ``y1`` around (x, z) ``centre``."""
    x, z = centre
    mesh = trimesh.creation.cylinder(
        radius=bottom_radius, segment=[(x, y0, z), (x, y1, z)], sections=sections
    )
    vertices = mesh.vertices.copy()
    top = np.isclose(vertices[:, 1], y1)
    vertices[top, 0] = x + (vertices[top, 0] - x) * (top_radius / bottom_radius)
    vertices[top, 2] = z + (vertices[top, 2] - z) * (top_radius / bottom_radius)
    mesh.vertices = vertices
    return coloured(mesh, colour)


def cone(radius: float, base, apex, colour, sections: int = 10) -> trimesh.Trimesh:
    """A cone with its base disc centred on ``base`` and its tip at ``apex``."""
    base, apex = np.asarray(base, dtype=float), np.asarray(apex, dtype=float)
    axis = apex - base
    # trimesh builds cones along +Z from the origin: turn that axis onto ours, then move.
    transform = trimesh.geometry.align_vectors([0.0, 0.0, 1.0], axis / np.linalg.norm(axis))
    transform[:3, 3] = base
    mesh = trimesh.creation.cone(
        radius=radius, height=float(np.linalg.norm(axis)), sections=sections, transform=transform
    )
    return coloured(mesh, colour)


def ball(radius, centre, colour, subdivisions: int = 1) -> trimesh.Trimesh:
    """A sphere, or an ellipsoid when ``radius`` is (rx, ry, rz)."""
    mesh = trimesh.creation.icosphere(subdivisions=subdivisions, radius=1.0)
    mesh.apply_scale(np.broadcast_to(np.asarray(radius, dtype=float), (3,)))
    mesh.apply_translation(centre)
    return coloured(mesh, colour)


def gable_roof(width: float, depth: float, eave_y: float, rise: float, colour) -> trimesh.Trimesh:
    """A triangular prism roof: ridge along x at ``eave_y + rise``, slopes to front and back."""
    half_w, half_d = width / 2.0, depth / 2.0
    vertices = np.array(
        [
            [-half_w, eave_y, -half_d],
            [-half_w, eave_y, half_d],
            [-half_w, eave_y + rise, 0.0],
            [half_w, eave_y, -half_d],
            [half_w, eave_y, half_d],
            [half_w, eave_y + rise, 0.0],
        ]
    )
    faces = np.array(
        [[0, 1, 2], [3, 5, 4], [1, 4, 5], [1, 5, 2], [0, 2, 5], [0, 5, 3], [0, 3, 4], [0, 4, 1]]
    )
    mesh = trimesh.Trimesh(vertices, faces, process=False)
    mesh.fix_normals()
    return coloured(mesh, colour)


def legs(
    width: float, depth: float, height: float, thickness: float, colour
) -> list[trimesh.Trimesh]:
    """Four square legs standing at the corners of a ``width`` x ``depth`` footprint."""
    x = width / 2.0 - thickness / 2.0
    z = depth / 2.0 - thickness / 2.0
    return [
        block((thickness, height, thickness), (sx * x, height / 2.0, sz * z), colour)
        for sx in (-1, 1)
        for sz in (-1, 1)
    ]


def combine(*parts) -> trimesh.Trimesh:
    """One mesh of all ``parts`` (meshes or lists of meshes), face colours kept."""
    flat: list[trimesh.Trimesh] = []
    for part in parts:
        flat.extend(part if isinstance(part, (list, tuple)) else [part])
    return trimesh.util.concatenate(flat)


# ---------------------------------------------------------------------------------
# Furniture and small wares (village stalls, desks, bedrooms).


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


# ---------------------------------------------------------------------------------
# The village: buildings, plants, carts, street furniture, smithy and mill wares.


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


# ---------------------------------------------------------------------------------
# Homes, kitchens, bathrooms and classrooms: living room, dining and kitchen
# furniture, bathroom fittings, a piano and a whiteboard.


def ring(inner: float, outer: float, start, end, colour, sections: int = 12) -> trimesh.Trimesh:
    """A flat ring (a washer) from point ``start`` to point ``end`` along its axis."""
    mesh = trimesh.creation.annulus(
        r_min=inner, r_max=outer, segment=[start, end], sections=sections
    )
    return coloured(mesh, colour)


def oval(mesh: trimesh.Trimesh, ratio: float, centre_z: float = 0.0) -> trimesh.Trimesh:
    """``mesh`` (built round the Y axis) stretched along Z by ``ratio`` and moved to ``centre_z``:
    a round part made oval, as a toilet bowl or a basin is."""
    mesh.apply_scale((1.0, 1.0, ratio))
    mesh.apply_translation((0.0, 0.0, centre_z))
    return mesh


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


# ---------------------------------------------------------------------------------
# Gyms: the cardio machines face their console or flywheel at the back (-Z), the end
# one gets on at is the front (+Z); a rack of dumbbells, a bench and a mat.


@builder("treadmill")
def treadmill(size, colour) -> trimesh.Trimesh:
    """A treadmill: a low deck with a dark belt along Z between two side rails, the
    motor hood at the back (-Z), two uprights rising from it to a console whose screen
    faces +Z, and handrails reaching forward; one walks on it facing -Z."""
    w, h, d = size
    back = -d / 2
    deck_y, hood_y, hood_d = min(0.2, 0.15 * h), min(0.3, 0.22 * h), 0.2 * d
    rail, post_x = 0.1 * w, w / 2 - 0.04
    console_y, console_z = 0.8 * h, back + min(0.3, 0.16 * d)
    return combine(
        slab(
            (-w / 2 + rail / 2, 0.0, back + hood_d),
            (w / 2 - rail / 2, 0.7 * deck_y, d / 2),
            shade(colour, 0.8),
        ),
        slab(
            (-w / 2 + rail, 0.7 * deck_y, back + hood_d), (w / 2 - rail, deck_y, d / 2 - 0.02), COAL
        ),
        [
            slab((x0, 0.0, back + hood_d), (x0 + rail, deck_y + 0.01, d / 2), shade(colour, 1.4))
            for x0 in (-w / 2, w / 2 - rail)
        ],
        slab((-w / 2, 0.0, back), (w / 2, hood_y, back + hood_d), colour),
        [
            cylinder(
                0.03,
                (sx * post_x, hood_y, back + 0.6 * hood_d),
                (sx * post_x, console_y, back + 0.1),
                CHROME,
                sections=8,
            )
            for sx in (-1, 1)
        ],
        [
            cylinder(
                0.02,
                (sx * post_x, 0.72 * h, back + 0.12),
                (sx * post_x, 0.72 * h, back + 0.12 + 0.25 * d),
                CHROME,
                sections=6,
            )
            for sx in (-1, 1)
        ],
        slab((-w / 2, console_y, back), (w / 2, h, console_z), colour),
        slab(
            (-0.25 * w, console_y + 0.03, console_z), (0.25 * w, h - 0.03, console_z + 0.01), SCREEN
        ),
    )


@builder("exercise_bike")
def exercise_bike(size, colour) -> trimesh.Trimesh:
    """An upright exercise bike on two feet across its width: the flywheel at the back
    (-Z) under a post rising to the handlebars and a console, the crank and pedals in
    the middle, the saddle on its post towards the front (+Z); one rides it facing -Z."""
    w, h, d = size
    back, front, foot = -d / 2, d / 2, 0.06
    wheel_r = min(0.22, 0.3 * d, 0.18 * h)
    wheel_y, wheel_z = foot + wheel_r, back + wheel_r + 0.08
    bar_y, bar_z = 0.85 * h, back + 0.14
    saddle_y, saddle_z = 0.66 * h, front - 0.3 * d
    crank_y = 0.25 * h
    return combine(
        [
            slab((-w / 2, 0.0, z - 0.04), (w / 2, foot, z + 0.04), IRON)
            for z in (back + 0.05, front - 0.05)
        ],
        slab((-0.04, foot, back + 0.05), (0.04, foot + 0.05, front - 0.05), colour),
        cylinder(
            wheel_r,
            (-0.035, wheel_y, wheel_z),
            (0.035, wheel_y, wheel_z),
            shade(colour, 1.4),
            sections=14,
        ),
        cylinder(0.035, (0.0, foot, wheel_z), (0.0, bar_y, bar_z), colour, sections=8),
        cylinder(
            0.035, (0.0, foot, front - 0.2 * d), (0.0, saddle_y, saddle_z), colour, sections=8
        ),
        cylinder(0.025, (0.0, crank_y, 0.0), (0.0, wheel_y, wheel_z), colour, sections=6),
        cylinder(0.08, (-0.03, crank_y, 0.0), (0.03, crank_y, 0.0), CHROME, sections=10),
        [
            slab(
                (sx * 0.12 - 0.05, crank_y - 0.02, -0.04),
                (sx * 0.12 + 0.05, crank_y + 0.02, 0.04),
                COAL,
            )
            for sx in (-1, 1)
        ],
        slab((-0.11, saddle_y, saddle_z - 0.14), (0.11, saddle_y + 0.06, saddle_z + 0.12), COAL),
        cylinder(0.02, (-0.4 * w, bar_y, bar_z), (0.4 * w, bar_y, bar_z), CHROME, sections=6),
        [
            cylinder(
                0.02,
                (sx * 0.4 * w, bar_y, bar_z),
                (sx * 0.4 * w, bar_y, bar_z + 0.25 * d),
                COAL,
                sections=6,
            )
            for sx in (-1, 1)
        ],
        slab((-0.13, bar_y + 0.04, back), (0.13, h, back + 0.1), SCREEN),
    )


@builder("rowing_machine")
def rowing_machine(size, colour) -> trimesh.Trimesh:
    """A rowing machine: the round flywheel housing at the back (-Z), two footrests
    before it and the handle across, a rail running to the front (+Z) on a leg, a seat
    on the rail and a foot at each end; one sits on the seat facing -Z."""
    w, h, d = size
    back, front = -d / 2, d / 2
    r = min(0.27, h / 2)
    rail_y = 0.45 * h
    feet_z = back + 2 * r
    return combine(
        [
            slab((-w / 2, 0.0, z0), (w / 2, 0.05, z0 + 0.08), IRON)
            for z0 in (back + r - 0.04, front - 0.08)
        ],
        cylinder(r, (-0.12, r, back + r), (0.12, r, back + r), colour, sections=14),
        cylinder(
            0.6 * r, (-0.125, r, back + r), (0.125, r, back + r), shade(colour, 1.5), sections=14
        ),
        slab((-0.06, 0.05, back + r), (0.06, rail_y - 0.05, feet_z + 0.3), colour),
        slab((-0.05, rail_y - 0.05, feet_z), (0.05, rail_y, front - 0.02), CHROME),
        slab((-0.04, 0.05, front - 0.08), (0.04, rail_y - 0.05, front - 0.02), colour),
        [
            slab((sx * 0.02, rail_y - 0.08, feet_z), (sx * 0.17, rail_y - 0.04, feet_z + 0.3), COAL)
            for sx in (-1, 1)
        ],
        cylinder(
            0.02,
            (-0.25 * w, 1.3 * r, feet_z + 0.05),
            (0.25 * w, 1.3 * r, feet_z + 0.05),
            COAL,
            sections=6,
        ),
        slab((-0.15, rail_y, 0.05 * d - 0.15), (0.15, rail_y + 0.07, 0.05 * d + 0.15), COAL),
    )


@builder("weight_bench")
def weight_bench(size, colour) -> trimesh.Trimesh:
    """A weight bench: a short seat pad at the front (+Z) and a long back pad behind
    it (the catalog colour) on a steel spine, two uprights and a foot across each end."""
    w, h, d = size
    back, front = -d / 2, d / 2
    pad_y, pad_w = h - 0.08, min(0.3, 0.5 * w)
    split = front - 0.35 * d
    return combine(
        [
            slab((-w / 2, 0.0, z - 0.04), (w / 2, 0.05, z + 0.04), IRON)
            for z in (back + 0.12, front - 0.12)
        ],
        [
            slab((-0.03, 0.05, z - 0.03), (0.03, pad_y - 0.05, z + 0.03), CHROME)
            for z in (back + 0.12, front - 0.12)
        ],
        slab((-0.04, pad_y - 0.05, back + 0.08), (0.04, pad_y, front - 0.08), IRON),
        slab((-pad_w / 2, pad_y, back), (pad_w / 2, h, split - 0.015), colour),
        slab((-pad_w / 2, pad_y, split + 0.015), (pad_w / 2, h - 0.005, front), shade(colour, 1.2)),
    )


@builder("dumbbell_rack")
def dumbbell_rack(size, colour) -> trimesh.Trimesh:
    """A two-tier rack: a low tier at the front and a higher one behind it, each a pair
    of rails along X holding a row of hex dumbbells (handles front to back, heads
    growing from left to right), on four legs."""
    w, h, d = size
    low_y, high_y = 0.42 * h, h - 0.14
    count = min(5, repeats(w - 0.1, 0.22))
    parts = []
    for x, top in ((sx * (w / 2 - 0.02), y) for sx in (-1, 1) for y in (low_y, high_y)):
        z = d / 2 - 0.03 if top == low_y else -d / 2 + 0.03
        parts.append(slab((x - 0.02, 0.0, z - 0.02), (x + 0.02, top, z + 0.02), colour))
    for y, z0, z1, middle in (
        (low_y, 0.0, d / 2 - 0.01, 0.22 * d),
        (high_y, -d / 2 + 0.01, 0.1 * d, -0.2 * d),
    ):
        parts += [
            slab((-w / 2, y - 0.03, z - 0.02), (w / 2, y, z + 0.02), colour)
            for z in (z0 + 0.03, z1 - 0.03)
        ]
        for k in range(count):
            x = -w / 2 + 0.05 + (k + 0.5) * (w - 0.1) / count
            r = 0.04 + 0.005 * k
            parts += [
                block((1.7 * r, 2 * r, 0.07), (x, y + r, middle + s * 0.11), COAL) for s in (-1, 1)
            ]
            parts.append(block((0.03, 0.03, 0.16), (x, y + r, middle), CHROME))
    return combine(parts)


@builder("exercise_mat")
def exercise_mat(size, colour) -> trimesh.Trimesh:
    """A flat exercise mat, a lighter stripe across it near each end (+X and -X)."""
    w, h, d = size
    stripe = min(0.1, 0.06 * w)
    return combine(
        slab((-w / 2, 0.0, -d / 2), (w / 2, 0.8 * h, d / 2), colour),
        [
            slab(
                (sx * (w / 2 - 2 * stripe) - stripe / 3, 0.0, -d / 2 + 0.03),
                (sx * (w / 2 - 2 * stripe) + stripe / 3, h, d / 2 - 0.03),
                shade(colour, 1.5),
            )
            for sx in (-1, 1)
        ],
    )


# A teacher's desk is a writing desk; its own name lets a classroom say which desk it is.
builder("teacher_desk")(desk)


# ---------------------------------------------------------------------------------
# The builders and the shape registry name the same shapes, or this module fails to import.


class ShapeRegistryMismatch(RuntimeError):
    """``BUILDERS`` and ``scenewright.core.shapes.SHAPES`` name different shapes."""


def check_registry(builders: Mapping[str, Builder], shapes: Mapping[str, Shape]) -> None:
    """Raise ``ShapeRegistryMismatch`` unless ``builders`` and ``shapes`` have the same names."""
    unregistered = sorted(set(builders) - set(shapes))
    unbuilt = sorted(set(shapes) - set(builders))
    problems = []
    if unregistered:
        problems.append(
            f"builders with no entry in scenewright.core.shapes.SHAPES: {', '.join(unregistered)}"
        )
    if unbuilt:
        problems.append(
            f"shapes in scenewright.core.shapes.SHAPES with no builder: {', '.join(unbuilt)}"
        )
    if problems:
        raise ShapeRegistryMismatch("; ".join(problems))


check_registry(BUILDERS, SHAPES)
