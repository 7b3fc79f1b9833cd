"""Shape builders for a castle keep or a dungeon: a chest, a weapon rack, a bunk, a bench,
a stool, a banner and a torch stand. Fronts face +Z: a chest's lock and the side its lid
opens to, the rack's weapons, a bunk's foot end, a banner's face.
"""

from __future__ import annotations

import trimesh

from .mesh_parts import (
    DARK_WOOD,
    GLOW,
    IRON,
    LINEN,
    STRAW,
    Builder,
    block,
    combine,
    cone,
    cylinder,
    legs,
    register_in,
    repeats,
    shade,
    slab,
)

#: The keep and dungeon builders by shape name.
KEEP: dict[str, Builder] = {}
builder = register_in(KEEP)


@builder("chest")
def chest(size, colour) -> trimesh.Trimesh:
    """A wooden box with a darker lid, two iron bands over it and an iron lock plate on
    the front (+Z)."""
    w, h, d = size
    lid_y = 0.72 * h
    band = min(0.05, 0.08 * w)
    return combine(
        slab((-w / 2, 0.0, -d / 2), (w / 2, lid_y, d / 2), colour),
        slab((-w / 2, lid_y, -d / 2), (w / 2, h, d / 2), shade(colour, 0.8)),
        [
            slab(
                (x - band / 2, 0.0, -d / 2 - 0.005), (x + band / 2, h + 0.005, d / 2 + 0.005), IRON
            )
            for x in (-0.3 * w, 0.3 * w)
        ],
        block((0.12 * w, 0.22 * h, 0.02), (0.0, lid_y - 0.06 * h, d / 2 + 0.005), IRON),
    )


@builder("weapon_rack")
def weapon_rack(size, colour) -> trimesh.Trimesh:
    """Two posts on feet with two rails between them, and blades standing in it, their
    iron towards the front (+Z); the back (-Z) goes to a wall."""
    w, h, d = size
    post = 0.06
    back_z = -d / 2 + post / 2
    count = repeats(w - 2 * post, 0.2, least=2)
    step = (w - 2 * post) / count
    blades = [
        slab(
            (-w / 2 + post + (k + 0.35) * step, 0.05, -0.02),
            (-w / 2 + post + (k + 0.65) * step, 0.92 * h, 0.01),
            shade(IRON, 2.4),
        )
        for k in range(count)
    ]
    return combine(
        [
            slab((x - post / 2, 0.0, -d / 2), (x + post / 2, post, d / 2), DARK_WOOD)
            for x in (-(w / 2 - post / 2), w / 2 - post / 2)
        ],
        [
            block((post, h, post), (sx * (w / 2 - post / 2), h / 2, back_z), colour)
            for sx in (-1, 1)
        ],
        [
            block((w, post, post), (0.0, y, back_z), shade(colour, 0.85))
            for y in (0.35 * h, 0.8 * h)
        ],
        block((w - 2 * post, post / 2, d / 2), (0.0, 0.06, d / 4), shade(colour, 0.7)),
        blades,
    )


@builder("bunk")
def bunk(size, colour) -> trimesh.Trimesh:
    """A low wooden frame on four legs with a straw mattress and a rolled blanket at the
    foot (+Z); the head (-Z) goes to a wall."""
    w, h, d = size
    frame_y = 0.55 * h
    return combine(
        legs(w, d, frame_y, 0.08, shade(colour, 0.8)),
        slab((-w / 2, frame_y - 0.08, -d / 2), (w / 2, frame_y, d / 2), colour),
        slab(
            (-w / 2 + 0.04, frame_y, -d / 2 + 0.04), (w / 2 - 0.04, 0.85 * h, d / 2 - 0.04), STRAW
        ),
        slab((-w / 2 + 0.06, 0.85 * h, d / 2 - 0.35), (w / 2 - 0.06, h, d / 2 - 0.08), LINEN),
        slab((-w / 2, frame_y, -d / 2), (w / 2, h, -d / 2 + 0.06), shade(colour, 0.9)),
    )


@builder("bench")
def bench(size, colour) -> trimesh.Trimesh:
    """A plank seat on two trestle legs with a stretcher between them; the same from the
    front and the back."""
    w, h, d = size
    seat = 0.08 * h + 0.02
    return combine(
        slab((-w / 2, h - seat, -d / 2), (w / 2, h, d / 2), colour),
        [
            slab(
                (x - 0.03, 0.0, -d / 2 + 0.02),
                (x + 0.03, h - seat, d / 2 - 0.02),
                shade(colour, 0.75),
            )
            for x in (-0.4 * w, 0.4 * w)
        ],
        slab((-0.4 * w, 0.3 * h, -0.02), (0.4 * w, 0.3 * h + 0.05, 0.02), shade(colour, 0.65)),
    )


@builder("stool")
def stool(size, colour) -> trimesh.Trimesh:
    """A round seat on three splayed legs."""
    w, h, d = size
    seat = 0.1 * h
    radius = min(w, d) / 2
    return combine(
        cylinder(radius, (0.0, h - seat, 0.0), (0.0, h, 0.0), colour, sections=12),
        [
            cylinder(
                0.025,
                (x * 0.85 * radius, 0.0, z * 0.85 * radius),
                (x * 0.5 * radius, h - seat, z * 0.5 * radius),
                shade(colour, 0.75),
                sections=6,
            )
            for x, z in ((0.0, 1.0), (0.87, -0.5), (-0.87, -0.5))
        ],
    )


@builder("banner")
def banner(size, colour) -> trimesh.Trimesh:
    """A cloth hanging from a crossbar on a pole on a foot, its face to the front (+Z) with
    a pale stripe down it and a narrower tail."""
    w, h, d = size
    pole = 0.05
    cloth_top, cloth_bottom = 0.95 * h, 0.3 * h
    return combine(
        slab((-0.4 * w, 0.0, -d / 2), (0.4 * w, 0.05, d / 2), DARK_WOOD),
        block((pole, h, pole), (0.0, h / 2, -d / 2 + pole / 2 + 0.02), DARK_WOOD),
        block((w, pole, pole), (0.0, cloth_top, -d / 2 + pole + 0.05), DARK_WOOD),
        slab(
            (-w / 2 + 0.03, cloth_bottom, 0.0), (w / 2 - 0.03, cloth_top - pole / 2, 0.03), colour
        ),
        slab(
            (-0.08 * w, cloth_bottom, 0.03),
            (0.08 * w, cloth_top - pole / 2, 0.04),
            shade(LINEN, 0.95),
        ),
        slab((-w / 4, cloth_bottom - 0.08 * h, 0.0), (w / 4, cloth_bottom, 0.03), colour),
    )


@builder("torch_stand")
def torch_stand(size, colour) -> trimesh.Trimesh:
    """An iron pole on four splayed feet with a cup at the top holding a burning torch."""
    w, h, d = size
    cup_y = 0.82 * h
    feet = [
        cylinder(0.02, (0.0, 0.25 * h, 0.0), (x * w / 2, 0.0, z * d / 2), colour, sections=6)
        for x, z in ((0.0, 1.0), (1.0, 0.0), (0.0, -1.0), (-1.0, 0.0))
    ]
    return combine(
        feet,
        cylinder(0.025, (0.0, 0.0, 0.0), (0.0, cup_y, 0.0), colour, sections=6),
        cone(
            0.3 * w, (0.0, cup_y + 0.1 * h, 0.0), (0.0, cup_y, 0.0), shade(colour, 1.3), sections=8
        ),
        cylinder(0.035, (0.0, cup_y, 0.0), (0.0, 0.94 * h, 0.0), DARK_WOOD, sections=6),
        cone(0.06, (0.0, 0.92 * h, 0.0), (0.0, h, 0.0), GLOW, sections=6),
    )
