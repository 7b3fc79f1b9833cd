"""Shape builders for gyms. The cardio machines face their console or flywheel at the back
(-Z); the end one gets on at is the front (+Z). Also a rack of dumbbells, a bench and a mat.
"""

from __future__ import annotations

import trimesh

from .mesh_parts import (
    CHROME,
    COAL,
    IRON,
    SCREEN,
    Builder,
    block,
    combine,
    cylinder,
    register_in,
    repeats,
    shade,
    slab,
)

#: The gym builders by shape name.
GYM: dict[str, Builder] = {}
builder = register_in(GYM)


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
