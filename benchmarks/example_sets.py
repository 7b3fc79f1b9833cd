"""Example sets in the hand-written format (docs/examples.md), written for the learning
benchmarks: rooms nobody tuned the learner on, with known left/right and wall shares.

Four kinds, each drawn from a seeded stream so a set is a fixed function of
(kind, n, seed):

- ``reading``: a reading corner. An armchair against a wall facing into the room, a
  floor lamp to its left in ``LEFT_SHARE`` of the examples (rounded) and to its right in
  the others, a side table on the lamp's other side, 0 to 2 books stacked on it, a
  bookshelf against another wall, a footstool in front of the armchair and a plant in a
  free corner in about half.
- ``music``: a piano against a wall with its bench in front (a vase on it in about
  half), an armchair against the opposite wall with a floor lamp on either side, a
  music stand, a footstool and a plant in about half.
- ``dining``: a table in the middle with four chairs round it (a bowl on it in about
  half), a sideboard against a wall with a table lamp at its left end in ``LEFT_SHARE``
  of the examples and its right end in the others, a plant in a corner.
- ``study``: a desk against a wall with an office chair at it, a filing cabinet on its
  left in ``LEFT_SHARE`` of the examples and on its right in the others, a waste bin
  always on the cabinet's other side (coupled sides), a plant standing further out on
  one side drawn apart from the cabinet's (independent sides, left in ``LEFT_SHARE``),
  a bookshelf against another wall.

Each main piece comes in two or three styles of its own size (a tall, a low or a
narrow bookshelf; a club, wing or lounge armchair), drawn per example.

Positions are jittered by a few centimetres and degrees, as a hand would place them.
``truth(kind, examples)`` gives the shares a learner should reproduce, measured the
same way as on generated scenes (``shares``).

    .venv/bin/python benchmarks/example_sets.py reading 9 --seed 1 -o my_reading/
"""

from __future__ import annotations

import argparse
import json
import math
from pathlib import Path

import numpy as np

from scenewright.core.frames import to_local, to_world

#: The share of examples with the lamp on its owner's left (6 of 9 in the issue).
LEFT_SHARE = 2.0 / 3.0
#: yaw (degrees) of an object whose back is on each wall of a room centred on the origin.
WALL_YAW = {"north": 0.0, "east": -90.0, "south": 180.0, "west": 90.0}
KINDS = ("reading", "music", "dining")
#: Every kind; ``study`` came later and is left out of ``KINDS`` so that the benchmarks
#: measured on those three keep their sets.
ALL_KINDS = (*KINDS, "study")
#: (parent type, child type) pairs whose left/right share each kind is measured on.
SIDE_PAIRS = {
    "reading": (("armchair", "floor_lamp"),),
    "music": (("armchair", "floor_lamp"),),
    "dining": (("sideboard", "table_lamp"),),
    "study": (("desk", "filing_cabinet"), ("desk", "waste_bin"), ("desk", "plant")),
}


def _against(
    room: tuple[float, float], wall: str, along: float, size, gap: float = 0.0
) -> tuple[float, float, float]:
    """(x, z, yaw degrees) of an object of ``size`` (w, h, d) ``gap`` metres from
    ``wall`` (flush by default), ``along`` metres from the wall's middle to its left."""
    yaw = math.radians(WALL_YAW[wall])
    reach = {"north": room[1], "south": room[1], "east": room[0], "west": room[0]}[wall] / 2.0
    x, z = to_world(0.0, 0.0, yaw, along, -(reach - size[2] / 2.0 - gap))
    return x, z, WALL_YAW[wall]


def _obj(ident: str, kind: str, size, x: float, z: float, yaw: float, **extra) -> dict:
    found = {
        "id": ident,
        "type": kind,
        "size": [round(v, 3) for v in size],
        "position": [round(x, 3) + 0.0, round(z, 3) + 0.0],
        "yaw": round(yaw, 1) + 0.0,
    }
    found.update(extra)
    return found


def _beside(host: dict, size, side: float, gap: float, forward: float = 0.0) -> tuple[float, float]:
    """World (x, z) of an object of ``size`` to ``host``'s left (side +1) or right (-1)."""
    lx = side * (host["size"][0] / 2.0 + gap + size[0] / 2.0)
    return to_world(
        host["position"][0], host["position"][1], math.radians(host["yaw"]), lx, forward
    )


#: Styles a type comes in, with their sizes (W x H x D), as real furniture does.
ARMCHAIRS = {"club": (0.85, 0.95, 0.85), "wing": (0.75, 1.0, 0.8), "lounge": (0.95, 0.9, 0.9)}
SIDE_TABLES = {"small": (0.45, 0.55, 0.45), "large": (0.5, 0.6, 0.5)}
SHELVES = {"tall": (0.9, 1.8, 0.35), "low": (0.9, 1.0, 0.35), "narrow": (0.6, 1.8, 0.3)}
PIANOS = {"upright": (1.5, 1.25, 0.6), "console": (1.4, 1.1, 0.55)}
DINING_TABLES = {"six": (1.6, 0.75, 0.9), "four": (1.4, 0.75, 0.8)}
SIDEBOARDS = {"long": (1.6, 0.85, 0.45), "short": (1.2, 0.8, 0.45)}


def _styled(
    sizes: dict[str, tuple[float, float, float]], rng: np.random.Generator
) -> tuple[str, tuple[float, float, float]]:
    style = sorted(sizes)[int(rng.integers(len(sizes)))]
    return style, sizes[style]


def _maybe_footstool(objects: list[dict], rng: np.random.Generator) -> None:
    """A footstool in front of the armchair, in about half the rooms."""
    if rng.random() >= 0.5:
        return
    chair = next(o for o in objects if o["type"] == "armchair")
    forward = chair["size"][2] / 2 + float(rng.uniform(0.25, 0.4)) + 0.2
    x, z = to_world(
        chair["position"][0], chair["position"][1], math.radians(chair["yaw"]), 0.0, forward
    )
    objects.append(_obj("footstool", "footstool", (0.5, 0.4, 0.4), x, z, chair["yaw"]))


def _maybe_plant(objects: list[dict], room: tuple[float, float], rng: np.random.Generator) -> None:
    """A plant in the first corner clear of the room's standing objects, in about half
    the rooms."""
    if rng.random() >= 0.5:
        return
    for sx, sz in ((1, 1), (-1, 1), (1, -1), (-1, -1)):
        x, z = sx * (room[0] / 2 - 0.25), sz * (room[1] / 2 - 0.25)
        if all(
            math.hypot(x - o["position"][0], z - o["position"][-1])
            > math.hypot(o["size"][0], o["size"][2]) / 2 + 0.35
            for o in objects
            if "parent" not in o
        ):
            objects.append(_obj("plant", "plant", (0.4, 1.0, 0.4), x, z, 0.0))
            return


def _sides(n: int, rng: np.random.Generator) -> list[float]:
    left = round(LEFT_SHARE * n)
    sides = [1.0] * left + [-1.0] * (n - left)
    rng.shuffle(sides)
    return sides


def reading(n: int, rng: np.random.Generator) -> list[dict]:
    rooms = []
    walls = ("north", "east", "south", "west")
    for index, side in enumerate(_sides(n, rng)):
        room = (round(float(rng.uniform(3.2, 4.2)), 2), round(float(rng.uniform(3.0, 3.8)), 2))
        wall = walls[int(rng.integers(4))]
        chair_style, chair_size = _styled(ARMCHAIRS, rng)
        x, z, yaw = _against(room, wall, float(rng.uniform(-0.4, 0.4)), chair_size, 0.04)
        chair = _obj(
            "armchair",
            "armchair",
            chair_size,
            x,
            z,
            yaw + float(rng.uniform(-2, 2)),
            style=chair_style,
        )
        lamp_size = (0.35, 1.6, 0.35)
        lx, lz = _beside(chair, lamp_size, side, float(rng.uniform(0.08, 0.2)), -0.15)
        lamp = _obj("lamp", "floor_lamp", lamp_size, lx, lz, chair["yaw"])
        table_style, table_size = _styled(SIDE_TABLES, rng)
        tx, tz = _beside(chair, table_size, -side, float(rng.uniform(0.05, 0.15)))
        table = _obj("table", "side_table", table_size, tx, tz, chair["yaw"], style=table_style)
        objects = [chair, lamp, table]
        for b in range(int(rng.integers(0, 3))):
            objects.append(
                {
                    "id": f"book{b + 1}",
                    "type": "book",
                    "size": [0.15, 0.04, 0.22],
                    "position": table["position"],
                    "parent": table["id"] if b == 0 else f"book{b}",
                }
            )
        other = walls[(walls.index(wall) + int(rng.integers(1, 4))) % 4]
        shelf_style, shelf_size = _styled(SHELVES, rng)
        sx, sz, syaw = _against(room, other, float(rng.uniform(-0.3, 0.3)), shelf_size)
        objects.append(_obj("shelf", "bookshelf", shelf_size, sx, sz, syaw, style=shelf_style))
        _maybe_footstool(objects, rng)
        _maybe_plant(objects, room, rng)
        rooms.append(
            {
                "name": f"reading_{index + 1:02d}",
                "room": {"width": room[0], "depth": room[1], "height": 2.6},
                "objects": objects,
            }
        )
    return rooms


def music(n: int, rng: np.random.Generator) -> list[dict]:
    rooms = []
    walls = ("north", "east", "south", "west")
    for index, side in enumerate(_sides(n, rng)):
        room = (round(float(rng.uniform(3.8, 4.8)), 2), round(float(rng.uniform(3.4, 4.2)), 2))
        wall = walls[int(rng.integers(4))]
        piano_style, piano_size = _styled(PIANOS, rng)
        x, z, yaw = _against(room, wall, float(rng.uniform(-0.5, 0.5)), piano_size)
        piano = _obj("piano", "piano", piano_size, x, z, yaw, style=piano_style)
        bench_size = (0.8, 0.5, 0.35)
        bx, bz = to_world(
            x,
            z,
            math.radians(yaw),
            float(rng.normal(0, 0.05)),
            0.3 + 0.175 + float(rng.uniform(0.15, 0.3)),
        )
        bench = _obj("bench", "piano_bench", bench_size, bx, bz, yaw + 180.0)
        other = walls[(walls.index(wall) + 2) % 4]
        chair_style, chair_size = _styled(ARMCHAIRS, rng)
        cx, cz, cyaw = _against(room, other, float(rng.uniform(-0.6, 0.6)), chair_size, 0.04)
        chair = _obj(
            "armchair",
            "armchair",
            chair_size,
            cx,
            cz,
            cyaw + float(rng.uniform(-2, 2)),
            style=chair_style,
        )
        lamp_size = (0.35, 1.6, 0.35)
        lx, lz = _beside(chair, lamp_size, side, float(rng.uniform(0.08, 0.2)), -0.15)
        lamp = _obj("lamp", "floor_lamp", lamp_size, lx, lz, chair["yaw"])
        stand_size = (0.5, 1.2, 0.4)
        sx, sz = to_world(x, z, math.radians(yaw), -piano_size[0] / 2, 1.25)
        stand = _obj(
            "stand", "music_stand", stand_size, sx, sz, yaw + 180.0 + float(rng.normal(0, 10))
        )
        objects = [piano, bench, chair, lamp, stand]
        if rng.random() < 0.5:  # a vase on the piano in some rooms
            vx, vz = to_world(x, z, math.radians(yaw), float(rng.uniform(-0.5, 0.5)), 0.0)
            objects.append(
                {
                    "id": "vase",
                    "type": "vase",
                    "size": [0.15, 0.3, 0.15],
                    "position": [round(vx, 3) + 0.0, round(vz, 3) + 0.0],
                    "parent": "piano",
                }
            )
        _maybe_footstool(objects, rng)
        _maybe_plant(objects, room, rng)
        rooms.append(
            {
                "name": f"music_{index + 1:02d}",
                "room": {"width": room[0], "depth": room[1], "height": 2.6},
                "objects": objects,
            }
        )
    return rooms


def dining(n: int, rng: np.random.Generator) -> list[dict]:
    rooms = []
    walls = ("north", "east", "south", "west")
    corners = ((1, 1), (1, -1), (-1, 1), (-1, -1))
    for index, side in enumerate(_sides(n, rng)):
        room = (round(float(rng.uniform(4.0, 5.0)), 2), round(float(rng.uniform(3.6, 4.4)), 2))
        table_style, table_size = _styled(DINING_TABLES, rng)
        tx, tz = float(rng.normal(0, 0.1)), float(rng.normal(0, 0.1))
        tyaw = float(rng.choice([0.0, 90.0]))
        table = _obj("table", "dining_table", table_size, tx, tz, tyaw, style=table_style)
        objects = [table]
        chair_size = (0.45, 0.9, 0.5)
        for c, (lx, lz) in enumerate(((-0.4, 0.8), (0.4, 0.8), (-0.4, -0.8), (0.4, -0.8))):
            cx, cz = to_world(
                tx,
                tz,
                math.radians(tyaw),
                lx + float(rng.normal(0, 0.03)),
                lz + float(rng.normal(0, 0.04)),
            )
            facing = tyaw + (180.0 if lz > 0 else 0.0) + float(rng.normal(0, 4))
            objects.append(_obj(f"chair{c + 1}", "dining_chair", chair_size, cx, cz, facing))
        wall = walls[int(rng.integers(4))]
        board_style, board_size = _styled(SIDEBOARDS, rng)
        bx, bz, byaw = _against(room, wall, float(rng.uniform(-0.3, 0.3)), board_size)
        board = _obj("board", "sideboard", board_size, bx, bz, byaw, style=board_style)
        objects.append(board)
        lx, lz = to_world(
            bx,
            bz,
            math.radians(byaw),
            side * (board_size[0] / 2 - 0.2),
            float(rng.uniform(-0.06, 0.0)),
        )
        objects.append(
            {
                "id": "lamp",
                "type": "table_lamp",
                "size": [0.3, 0.5, 0.3],
                "position": [round(lx, 3) + 0.0, round(lz, 3) + 0.0],
                "parent": "board",
            }
        )
        sx, sz = corners[int(rng.integers(4))]
        objects.append(
            _obj(
                "plant",
                "plant",
                (0.45, 1.1, 0.45),
                sx * (room[0] / 2 - 0.3),
                sz * (room[1] / 2 - 0.3),
                0.0,
            )
        )
        if rng.random() < 0.5:  # a bowl on the table in some rooms
            objects.append(
                {
                    "id": "bowl",
                    "type": "bowl",
                    "size": [0.3, 0.12, 0.3],
                    "position": [round(tx, 3) + 0.0, round(tz, 3) + 0.0],
                    "parent": "table",
                }
            )
        rooms.append(
            {
                "name": f"dining_{index + 1:02d}",
                "room": {"width": room[0], "depth": room[1], "height": 2.6},
                "objects": objects,
            }
        )
    return rooms


def study(n: int, rng: np.random.Generator) -> list[dict]:
    rooms = []
    walls = ("north", "east", "south", "west")
    cabinet_sides = _sides(n, rng)
    plant_sides = _sides(n, rng)  # shuffled apart from the cabinet's: independent sides
    for index in range(n):
        side, plant_side = cabinet_sides[index], plant_sides[index]
        room = (round(float(rng.uniform(4.0, 4.6)), 2), round(float(rng.uniform(4.0, 4.6)), 2))
        wall = walls[int(rng.integers(4))]
        desk_size = (1.4, 0.75, 0.6)
        x, z, yaw = _against(room, wall, float(rng.uniform(-0.2, 0.2)), desk_size)
        desk = _obj("desk", "desk", desk_size, x, z, yaw)
        chair_size = (0.6, 1.0, 0.6)
        cx, cz = to_world(
            x,
            z,
            math.radians(yaw),
            float(rng.normal(0, 0.05)),
            0.3 + 0.3 + float(rng.uniform(0.1, 0.2)),
        )
        chair = _obj(
            "chair", "office_chair", chair_size, cx, cz, yaw + 180.0 + float(rng.normal(0, 5))
        )
        cabinet_size = (0.4, 0.7, 0.5)
        fx, fz = _beside(desk, cabinet_size, side, float(rng.uniform(0.04, 0.1)), -0.05)
        cabinet = _obj("cabinet", "filing_cabinet", cabinet_size, fx, fz, yaw)
        bin_size = (0.3, 0.35, 0.3)
        wx, wz = _beside(desk, bin_size, -side, float(rng.uniform(0.04, 0.1)), 0.05)
        waste_bin = _obj("bin", "waste_bin", bin_size, wx, wz, yaw + float(rng.uniform(-20, 20)))
        plant_size = (0.35, 1.1, 0.35)
        px, pz = _beside(desk, plant_size, plant_side, float(rng.uniform(0.6, 0.7)))
        plant = _obj("plant", "plant", plant_size, px, pz, 0.0)
        objects = [desk, chair, cabinet, waste_bin, plant]
        other = walls[(walls.index(wall) + int(rng.integers(1, 4))) % 4]
        shelf_style, shelf_size = _styled(SHELVES, rng)
        sx, sz, syaw = _against(room, other, float(rng.uniform(-0.3, 0.3)), shelf_size)
        objects.append(_obj("shelf", "bookshelf", shelf_size, sx, sz, syaw, style=shelf_style))
        rooms.append(
            {
                "name": f"study_{index + 1:02d}",
                "room": {"width": room[0], "depth": room[1], "height": 2.6},
                "objects": objects,
            }
        )
    return rooms


def write_set(kind: str, n: int, seed: int, out: Path) -> list[Path]:
    """Write ``n`` examples of ``kind`` drawn with ``seed`` to folder ``out``."""
    rng = np.random.default_rng([seed, ALL_KINDS.index(kind)])
    rooms = {"reading": reading, "music": music, "dining": dining, "study": study}[kind](n, rng)
    out.mkdir(parents=True, exist_ok=True)
    paths = []
    for room in rooms:
        path = out / f"{room['name']}.json"
        path.write_text(json.dumps(room, indent=1) + "\n")
        paths.append(path)
    return paths


def side_shares(scenes, pairs) -> dict[str, float | None]:
    """Per (parent, child) pair: the share of child objects standing on the left of
    their nearest parent object (its local +x), over scenes holding both."""
    found: dict[str, float | None] = {}
    for parent, child in pairs:
        left = total = 0
        for scene in scenes:
            objects = scene.placed_objects()
            hosts = [o for o in objects if o.type == parent]
            for obj in objects:
                if obj.type != child or not hosts:
                    continue
                host = min(
                    hosts,
                    key=lambda h: math.hypot(
                        h.position[0] - obj.position[0], h.position[2] - obj.position[2]
                    ),
                )
                x, _ = to_local(
                    host.position[0], host.position[2], host.yaw, obj.position[0], obj.position[2]
                )
                left += x > 0
                total += 1
        found[f"{child} left of {parent}"] = left / total if total else None
    return found


#: (parent type, child type, other child type) whose share on one side is measured: the
#: examples' reading corners and studies always oppose the first two, a study's plant
#: takes its side apart from the others.
SAME_SIDE = {
    "reading": (("armchair", "floor_lamp", "side_table"),),
    "study": (
        ("desk", "filing_cabinet", "waste_bin"),
        ("desk", "filing_cabinet", "plant"),
        ("desk", "waste_bin", "plant"),
    ),
}


def same_side_share(scenes, parent: str, first: str, second: str) -> float | None:
    """The share of scenes holding one of each in which ``first`` and ``second`` stand on
    the same side of the ``parent`` object (the first of its type)."""
    same = total = 0
    for scene in scenes:
        objects = scene.placed_objects()
        host = next((o for o in objects if o.type == parent), None)
        sides = {}
        for obj in objects:
            if host is not None and obj.type in (first, second):
                x, _ = to_local(
                    host.position[0], host.position[2], host.yaw, obj.position[0], obj.position[2]
                )
                sides[obj.type] = x > 0
        if len(sides) == 2:
            total += 1
            same += sides[first] == sides[second]
    return same / total if total else None


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("kind", choices=ALL_KINDS)
    parser.add_argument("n", type=int)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("-o", "--output", type=Path, required=True)
    args = parser.parse_args()
    paths = write_set(args.kind, args.n, args.seed, args.output)
    print(f"wrote {len(paths)} {args.kind} examples to {args.output}")


if __name__ == "__main__":
    main()
