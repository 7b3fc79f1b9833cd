"""Writes examples/sets/bedrooms/: ten bedrooms in the hand-written example format.

How they were authored. Each example is one row of ``BEDROOMS`` below, numbers chosen
by hand (no random draws), so that the set shows the variation of real bedrooms: rooms
from 3.2 x 3.0 m to 4.4 x 3.8 m; a double or a single bed with its head against some
wall, somewhere along it; night tables on both sides, on one side or none, a table
lamp on some of them; a wardrobe against another wall (in two rooms none); in some
rooms a desk with its chair against a wall, a dresser, a plant in a corner. Furniture
stands flush against its wall and square to it, except where a row says it is turned;
the chair's distance and turn are the hand-written variation.

Positions are written in the frame of the wall an object stands against (metres along
the wall to the object's left, its back on the wall) and turned into room coordinates
with ``core.frames``; a lamp on a night table gives only (x, z) and its ``parent``, as
the format allows. The script checks each example with the layout's own measurement
(``measure_layout``): no two objects overlap and everything is inside the room, or it
stops.

    .venv/bin/python scripts/author_bedroom_examples.py
"""

from __future__ import annotations

import json
import math
from pathlib import Path

from author_desk_examples import WALL_YAW, check, rounded

from scenewright.core.frames import to_world

ROOT = Path(__file__).resolve().parents[1]
OUTPUT = ROOT / "examples" / "sets" / "bedrooms"
HEIGHT = 2.6

#: Sizes (W x H x D, metres) by type and style.
SIZES = {
    ("bed", "double"): (1.6, 0.55, 2.1),
    ("bed", "single"): (1.0, 0.5, 2.0),
    ("nightstand", None): (0.45, 0.55, 0.4),
    ("table_lamp", None): (0.25, 0.45, 0.25),
    ("wardrobe", None): (1.2, 2.0, 0.6),
    ("desk", None): (1.1, 0.75, 0.55),
    ("chair", None): (0.45, 0.9, 0.5),
    ("dresser", None): (1.0, 0.85, 0.5),
    ("plant", None): (0.4, 1.0, 0.4),
}
#: Gap (metres) between a bed's side and a night table.
BESIDE = 0.05

# One row per example:
#   room: (width, depth) in metres;
#   bed: (wall, along, style): the wall its head is against and its centre's offset
#     along that wall to the bed's left (as you lie in it looking at the foot);
#   night tables: which sides ("left", "right") have one, and which of those a lamp;
#   wardrobe: (wall, along) or None;
#   desk: (wall, along, chair gap, chair turn in degrees) or None;
#   dresser: (wall, along) or None;
#   plant: the corner ("ne", "nw", "se", "sw") or None.
BEDROOMS = (
    # room         bed                            tables             lamps              wardrobe          desk                          dresser           plant
    (
        (3.6, 3.4),
        ("north", 0.0, "double"),
        ("left", "right"),
        ("left", "right"),
        ("south", 0.9),
        None,
        None,
        None,
    ),
    (
        (3.4, 3.2),
        ("north", -0.4, "single"),
        ("right",),
        ("right",),
        ("east", -0.8),
        ("south", -0.6, 0.2, 0),
        None,
        None,
    ),
    (
        (4.0, 3.6),
        ("west", 0.2, "double"),
        ("left", "right"),
        ("left",),
        ("north", -1.0),
        None,
        ("east", 0.3),
        "se",
    ),
    ((3.2, 3.0), ("east", 0.3, "single"), ("left",), ("left",), ("west", -0.7), None, None, None),
    (
        (4.4, 3.8),
        ("north", 0.5, "double"),
        ("left", "right"),
        ("left", "right"),
        ("west", 0.9),
        ("south", 0.9, 0.25, -8),
        ("east", -0.6),
        "nw",
    ),
    (
        (3.8, 3.8),
        ("south", -0.2, "double"),
        ("left", "right"),
        ("right",),
        None,
        ("north", 0.8, 0.15, 5),
        None,
        None,
    ),
    (
        (3.8, 3.4),
        ("north", -0.6, "single"),
        ("right",),
        (),
        ("south", -0.8),
        ("east", -0.4, 0.3, 0),
        None,
        "ne",
    ),
    (
        (4.0, 3.8),
        ("east", -0.1, "double"),
        ("left", "right"),
        ("left", "right"),
        ("south", -1.0),
        None,
        ("west", -0.8),
        None,
    ),
    (
        (3.4, 3.4),
        ("west", -0.3, "single"),
        (),
        (),
        ("east", 0.9),
        ("north", 0.4, 0.2, 10),
        None,
        "sw",
    ),
    (
        (4.2, 3.6),
        ("south", 0.4, "double"),
        ("left", "right"),
        ("left",),
        None,
        None,
        ("north", -0.9),
        "ne",
    ),
)


def against(
    room: tuple[float, float], wall: str, along: float, depth: float
) -> tuple[float, float, float]:
    """(x, z, yaw in radians) of an object of ``depth`` with its back flush on ``wall``,
    its centre ``along`` metres to its own left of the wall's middle."""
    yaw = math.radians(WALL_YAW[wall])
    reach = {"north": room[1], "south": room[1], "east": room[0], "west": room[0]}[wall] / 2.0
    cx, cz = to_world(0.0, 0.0, yaw, along, -(reach - depth / 2.0))
    return cx, cz, yaw


def example(index: int, row: tuple) -> dict:
    room, (bed_wall, bed_along, bed_style), tables, lamps, wardrobe, desk, dresser, plant = row
    objects: list[dict] = []

    def put(
        object_id: str, kind: str, x: float, z: float, yaw: float, style: str | None = None, **more
    ) -> None:
        size = SIZES[(kind, style)]
        record = {
            "id": object_id,
            "type": kind,
            **({"style": style} if style else {}),
            "size": list(size),
            "position": [rounded(x), 0, rounded(z)],
            "yaw": rounded(math.degrees(yaw)),
            **more,
        }
        if "parent" in more:  # resting on its parent: (x, z) only
            record["position"] = [rounded(x), rounded(z)]
        objects.append(record)

    def on_wall(
        object_id: str, kind: str, wall: str, along: float, style: str | None = None
    ) -> tuple[float, float, float]:
        frame = against(room, wall, along, SIZES[(kind, style)][2])
        put(object_id, kind, *frame, style=style)
        return frame

    bed_w, _, bed_d = SIZES[("bed", bed_style)]
    bx, bz, byaw = on_wall("bed", "bed", bed_wall, bed_along, bed_style)
    table_w, _, table_d = SIZES[("nightstand", None)]
    for side in tables:
        sign = 1.0 if side == "left" else -1.0
        x, z = to_world(
            bx, bz, byaw, sign * (bed_w / 2.0 + BESIDE + table_w / 2.0), -(bed_d - table_d) / 2.0
        )
        put(f"nightstand_{side}", "nightstand", x, z, byaw)
        if side in lamps:
            put(f"lamp_{side}", "table_lamp", x, z, byaw, parent=f"nightstand_{side}")
    if wardrobe is not None:
        on_wall("wardrobe", "wardrobe", *wardrobe)
    if desk is not None:
        wall, along, gap, turn = desk
        dx, dz, dyaw = on_wall("desk", "desk", wall, along)
        chair_d = SIZES[("chair", None)][2]
        x, z = to_world(dx, dz, dyaw, 0.0, SIZES[("desk", None)][2] / 2.0 + gap + chair_d / 2.0)
        put("chair", "chair", x, z, dyaw + math.pi + math.radians(turn))
    if dresser is not None:
        on_wall("dresser", "dresser", *dresser)
    if plant is not None:
        w, _, d = SIZES[("plant", None)]
        x = (room[0] / 2.0 - w / 2.0) * (1 if "e" in plant else -1)
        z = (room[1] / 2.0 - d / 2.0) * (1 if plant[0] == "s" else -1)
        put("plant", "plant", x, z, math.pi if plant[0] == "s" else 0.0)
    return {
        "name": f"bedroom_{index:02d}",
        "room": {"width": room[0], "depth": room[1], "height": HEIGHT},
        "objects": objects,
    }


def main() -> None:
    OUTPUT.mkdir(parents=True, exist_ok=True)
    for index, row in enumerate(BEDROOMS, start=1):
        path = OUTPUT / f"bedroom_{index:02d}.json"
        path.write_text(json.dumps(example(index, row), indent=1) + "\n")
        check(path)
    print(f"wrote {len(BEDROOMS)} examples to {OUTPUT.relative_to(ROOT)}")


if __name__ == "__main__":
    main()
