"""Writes examples/sets/desks/: twenty desk corners in the hand-written example format.

How they were authored. Each example is one row of ``DESKS`` below, numbers chosen by
hand (no random draws), so that the set shows the variation a person's photos of desks
would: which wall the desk stands against and where along it, its style, where the
office chair was left (pushed in at various distances, turned a little, pulled out to
the desk's left side, in one room parked in a far corner, in two rooms absent), whether
a monitor, a desk lamp (at the back left or back right corner), books (a stack of up to
three at the front right), a mug and a waste bin (on the floor at the desk's right)
are there, and a plant in some corner of the room. Every desk stands flush against its
wall and square to it; the chair's turn and the monitor's shift are the hand-written
variation. The room is 3.4 x 3.0 m, 2.6 m high, in every example.

Positions are written in the desk's own frame (metres along its left and its front,
its front being the side you sit at) and turned into room coordinates with
``core.frames``; objects standing on the desk (and books on books) give only (x, z)
and their ``parent``, as the format allows. The script checks each example with the
layout's own measurement (``measure_layout``): no two objects overlap and everything
is inside the room, or it stops.

    .venv/bin/python scripts/author_desk_examples.py
"""

from __future__ import annotations

import json
import math
import sys
from pathlib import Path

from scenewright.core.frames import to_world
from scenewright.core.poses import Pose
from scenewright.examples import load_example
from scenewright.generator.layout import measure_layout

ROOT = Path(__file__).resolve().parents[1]
OUTPUT = ROOT / "examples" / "sets" / "desks"
ROOM = {"width": 3.4, "depth": 3.0, "height": 2.6}

#: Sizes (W x H x D, metres) by type and style.
SIZES = {
    ("desk", "oak"): (1.2, 0.75, 0.6),
    ("desk", "white"): (1.4, 0.74, 0.7),
    ("office_chair", None): (0.6, 1.05, 0.6),
    ("monitor", None): (0.55, 0.45, 0.2),
    ("desk_lamp", None): (0.2, 0.45, 0.2),
    ("book", None): (0.17, 0.03, 0.24),
    ("mug", None): (0.09, 0.1, 0.09),
    ("waste_bin", None): (0.3, 0.35, 0.3),
    ("plant", None): (0.45, 1.1, 0.45),
}
#: The desk's yaw (degrees) against each wall: its back to the wall, its front into the room.
WALL_YAW = {"north": 0.0, "east": -90.0, "south": 180.0, "west": 90.0}

# One row per example:
#   wall, along: the wall the desk stands against, and its centre's offset (metres)
#     along that wall from the wall's middle, to the desk's left as you sit at it;
#   style: oak or white;
#   chair: ("front", sideways, gap, turn): pushed in front, `sideways` metres to the
#     desk's left, `gap` metres between the desk's front and the chair's back, turned
#     `turn` degrees off facing the desk; ("aside", turn): pulled out to the desk's left
#     side, facing it; ("corner", x, z, yaw): parked elsewhere in the room; None;
#   monitor: sideways shift on the desk's back, or None;
#   lamp: "left" / "right" back corner, or None;
#   books: how many, stacked at the front right;
#   mug: its style ("white", "blue") at the front left, or None;
#   bin: a waste bin on the floor at the desk's right;
#   plant: the corner ("ne", "nw", "se", "sw") a plant stands in, or None.
DESKS = (
    # wall     along  style    chair                          monitor lamp    books mug      bin    plant
    ("north", 0.30, "oak", ("front", 0.00, 0.15, 0), 0.00, "left", 2, "white", True, "se"),
    ("north", -0.20, "oak", ("front", 0.05, 0.25, -4), 0.02, "left", 0, None, True, None),
    ("north", 0.50, "white", ("front", -0.05, 0.10, 3), 0.00, "right", 1, "blue", False, "sw"),
    ("north", 0.00, "oak", ("aside", -6), -0.03, None, 3, None, True, None),
    ("north", 0.40, "oak", ("front", 0.10, 0.20, 6), 0.00, "left", 1, "white", True, "se"),
    ("north", -0.10, "white", ("front", 0.00, 0.05, 0), 0.04, None, 0, None, True, None),
    ("north", 0.60, "oak", ("corner", -1.1, 1.0, 135), 0.00, "right", 2, None, False, None),
    ("north", 0.20, "oak", ("front", -0.08, 0.30, -2), 0.00, "left", 0, "white", True, "sw"),
    ("east", 0.10, "oak", ("front", 0.00, 0.15, 2), 0.00, "left", 1, None, True, "nw"),
    ("east", -0.30, "white", ("front", 0.06, 0.20, -5), -0.02, "right", 0, "blue", True, None),
    ("east", 0.00, "oak", None, 0.00, "left", 2, None, False, None),
    ("east", -0.05, "oak", ("aside", 4), 0.03, None, 0, "white", True, "sw"),
    ("east", -0.15, "oak", ("front", -0.04, 0.10, 0), 0.00, "left", 3, None, True, None),
    ("west", 0.20, "white", ("front", 0.02, 0.18, 3), 0.00, "right", 1, "white", True, "ne"),
    ("west", -0.25, "oak", ("front", 0.00, 0.22, -3), 0.01, "left", 0, None, False, None),
    ("west", 0.00, "oak", ("aside", 0), None, "left", 2, "blue", True, None),
    ("west", 0.30, "oak", ("front", 0.07, 0.12, 5), 0.00, None, 0, None, True, "se"),
    ("south", 0.10, "oak", ("front", 0.00, 0.15, -1), 0.00, "right", 1, "white", True, "nw"),
    ("south", -0.35, "white", None, -0.04, "left", 0, None, True, None),
    ("south", 0.25, "oak", ("front", -0.03, 0.28, 2), 0.00, "left", 2, None, False, "ne"),
)


def desk_frame(wall: str, along: float, depth: float) -> tuple[float, float, float]:
    """(x, z, yaw in radians) of a desk of ``depth`` flush against ``wall``."""
    yaw = math.radians(WALL_YAW[wall])
    half_w, half_d = ROOM["width"] / 2.0, ROOM["depth"] / 2.0
    reach = {"north": half_d, "south": half_d, "east": half_w, "west": half_w}[wall]
    # The wall's line is `reach` behind the desk's centre plus half its depth; `along`
    # runs to the desk's left (its local +X).
    cx, cz = to_world(0.0, 0.0, yaw, along, -(reach - depth / 2.0))
    return cx, cz, yaw


def rounded(value: float) -> float:
    return round(value, 3) + 0.0


def example(index: int, row: tuple) -> dict:
    wall, along, style, chair, monitor, lamp, books, mug, waste_bin, plant = row
    width, height, depth = SIZES[("desk", style)]
    cx, cz, yaw = desk_frame(wall, along, depth)
    degrees = math.degrees(yaw)
    objects = [
        {
            "id": "desk",
            "type": "desk",
            "style": style,
            "size": [width, height, depth],
            "position": [rounded(cx), 0, rounded(cz)],
            "yaw": degrees,
        }
    ]

    def at(lx: float, lz: float) -> list[float]:
        x, z = to_world(cx, cz, yaw, lx, lz)
        return [rounded(x), rounded(z)]

    def add(object_id: str, kind: str, position: list[float], turn: float, **more) -> None:
        size = SIZES[(kind, None)]
        objects.append(
            {
                "id": object_id,
                "type": kind,
                "size": list(size),
                "position": position,
                "yaw": rounded(degrees + turn),
                **more,
            }
        )

    chair_depth = SIZES[("office_chair", None)][2]
    if chair is not None and chair[0] == "front":
        _, sideways, gap, turn = chair
        add(
            "chair",
            "office_chair",
            at(sideways, depth / 2.0 + gap + chair_depth / 2.0),
            180.0 + turn,
        )
    elif chair is not None and chair[0] == "aside":
        add("chair", "office_chair", at(width / 2.0 + 0.4, 0.15), -90.0 + chair[1])
    elif chair is not None:
        _, x, z, chair_yaw = chair
        objects.append(
            {
                "id": "chair",
                "type": "office_chair",
                "size": list(SIZES[("office_chair", None)]),
                "position": [x, z],
                "yaw": chair_yaw,
            }
        )
    if monitor is not None:
        add("monitor", "monitor", at(monitor, -depth / 2.0 + 0.12), 0.0, parent="desk")
    if lamp is not None:
        side = 1.0 if lamp == "left" else -1.0
        add(
            "lamp",
            "desk_lamp",
            at(side * (width / 2.0 - 0.14), -depth / 2.0 + 0.14),
            0.0,
            parent="desk",
        )
    below = "desk"
    for k in range(books):
        add(f"book_{k + 1}", "book", at(-(width / 2.0 - 0.22), 0.1), 4.0 * k - 3.0, parent=below)
        below = f"book_{k + 1}"
    if mug is not None:
        add("mug", "mug", at(width / 2.0 - 0.25, depth / 2.0 - 0.12), 0.0, parent="desk", style=mug)
    if waste_bin:
        add("bin", "waste_bin", at(-(width / 2.0 + 0.25), -depth / 2.0 + 0.15), 0.0)
    if plant is not None:
        half_w, half_d = ROOM["width"] / 2.0, ROOM["depth"] / 2.0
        size = SIZES[("plant", None)]
        x = (half_w - size[0] / 2.0) * (1 if "e" in plant else -1)
        z = (half_d - size[2] / 2.0) * (1 if plant[0] == "s" else -1)
        facing = 180.0 if plant[0] == "s" else 0.0  # its back to the north or south wall
        objects.append(
            {"id": "plant", "type": "plant", "size": list(size), "position": [x, z], "yaw": facing}
        )
    return {"name": f"desk_{index:02d}", "room": ROOM, "objects": objects}


def check(path: Path) -> None:
    """Stop if an example has overlapping objects or anything outside the room."""
    scene = load_example(path).scene
    graph = scene.graph()
    poses = {o.id: Pose(*o.position, o.yaw) for o in scene.placed_objects()}
    problems = measure_layout(graph, poses, {}).problems
    if problems:
        sys.exit(f"{path}: {'; '.join(problems)}")


def main() -> None:
    OUTPUT.mkdir(parents=True, exist_ok=True)
    for index, row in enumerate(DESKS, start=1):
        path = OUTPUT / f"desk_{index:02d}.json"
        path.write_text(json.dumps(example(index, row), indent=1) + "\n")
        check(path)
    print(f"wrote {len(DESKS)} examples to {OUTPUT.relative_to(ROOT)}")


if __name__ == "__main__":
    main()
