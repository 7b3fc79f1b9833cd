"""Drawing plans by hand in a designer's terms, and writing the shipped plan set.

Each shipped plan is written once, by hand, in ``completion/designs/<type>.py`` as a
function that draws on a ``Design``: a rectangular room measured from its north-west
corner (x east, y south, metres), doors and windows placed along a wall, and furniture
placed the way a designer says it: "the bed against the north wall, centred at 1.8 m",
"night tables either side of it", "the chair before the desk", "six chairs round the
table". ``Design.plan()`` turns the drawing into the plan format (room centred on the
origin, scene.json's frame) and checks it like any plan file.

    python -m scenewright.completion.authoring         # rewrite completion/plans/*/*.json

rewrites every shipped plan file from its design and reports any plan whose drawing
breaks a rule of ``plan_checks``; the files are data the package ships, so this is run
only when a design changes.
"""

from __future__ import annotations

import importlib
import json
import math
import re
import sys
from pathlib import Path

from scenewright.completion.floor_plan import rounded
from scenewright.core.frames import to_world
from scenewright.core.geometry import wrap_angle
from scenewright.core.room import Room

#: A wall by its compass letter: its index in a rectangle's walls (north, east, south, west).
WALLS = {"N": 0, "E": 1, "S": 2, "W": 3}
#: The yaw that makes a piece face away from each wall (its back to that wall).
AWAY_FROM = {"N": 0.0, "E": -math.pi / 2.0, "S": math.pi, "W": math.pi / 2.0}
#: Facing words for free-standing pieces.
FACING = {"south": 0.0, "east": math.pi / 2.0, "north": math.pi, "west": -math.pi / 2.0}
#: The room types of the shipped set: one design module each.
TYPES = ("bedroom", "living_room", "study", "dining_room", "gym")


def _wrapped(yaw: float) -> float:
    """The yaw in (-pi, pi], rounded so written plans read cleanly."""
    yaw = wrap_angle(yaw)
    return round(math.pi if yaw <= -math.pi + 1e-9 else yaw, 6)


class Design:
    """One plan being drawn. Positions along a wall (``at``) are measured from the
    west end of a north or south wall and from the north end of an east or west wall."""

    def __init__(
        self,
        plan_id: str,
        room_type: str,
        title: str,
        width: float,
        depth: float,
        height: float = 2.6,
    ):
        self.id, self.type, self.title = plan_id, room_type, title
        self.width, self.depth = width, depth
        self.room = Room.rectangle(width, depth, height)
        self.pieces: list[dict] = []
        self.free_areas: list[dict] = []
        self._counts: dict[str, int] = {}

    # -- the room -----------------------------------------------------------------------

    def _wall_offset(self, wall: str, at: float) -> float:
        """``at`` (from the west or north end) as the room's offset along the wall."""
        length = self.width if wall in "NS" else self.depth
        return length - at if wall in "SW" else at

    def door(self, wall: str, at: float, width: float = 0.9) -> None:
        self.room = self.room.with_opening(
            "door", f"wall_{WALLS[wall] + 1}", self._wall_offset(wall, at), width
        )

    def window(
        self, wall: str, at: float, width: float, sill: float = 0.9, height: float = 1.3
    ) -> None:
        self.room = self.room.with_opening(
            "window", f"wall_{WALLS[wall] + 1}", self._wall_offset(wall, at), width, height, sill
        )

    # -- furniture ------------------------------------------------------------------------

    def _add(
        self, category: str, x: float, z: float, size, yaw: float, on: str | None = None
    ) -> str:
        """Add a piece at plan position (x, z) (from the north-west corner); return its id."""
        self._counts[category] = self._counts.get(category, 0) + 1
        piece_id = f"{category}_{self._counts[category]}"
        piece = {
            "id": piece_id,
            "category": category,
            "center": self._centred(x, z),
            "size": [float(size[0]), float(size[1])],
            "yaw": _wrapped(yaw),
        }
        if on is not None:
            piece["on"] = on
        self.pieces.append(piece)
        return piece_id

    def _centred(self, x: float, z: float) -> list[float]:
        """Plan (x, z) from the north-west corner as room coordinates (origin at the centre)."""
        return [
            round(x - self.width / 2.0, 4) + 0.0,
            round(z - self.depth / 2.0, 4) + 0.0,
        ]  # + 0.0: no -0.0

    def _get(self, piece_id: str) -> tuple[float, float, float, float, float]:
        """A piece's plan x, z, yaw, width and depth."""
        piece = next(p for p in self.pieces if p["id"] == piece_id)
        x, z = piece["center"][0] + self.width / 2.0, piece["center"][1] + self.depth / 2.0
        return x, z, piece["yaw"], piece["size"][0], piece["size"][1]

    def against(self, wall: str, category: str, at: float, size, gap: float = 0.0) -> str:
        """``category`` with its back to ``wall`` (``gap`` metres off it), centred ``at`` along it."""
        w, d = size
        off = gap + d / 2.0
        x, z = {
            "N": (at, off),
            "S": (at, self.depth - off),
            "W": (off, at),
            "E": (self.width - off, at),
        }[wall]
        return self._add(category, x, z, size, AWAY_FROM[wall])

    def place(self, category: str, x: float, z: float, size, facing: str | float) -> str:
        """A free-standing piece centred at plan (x, z), facing a compass word or a yaw."""
        return self._add(
            category, x, z, size, FACING[facing] if isinstance(facing, str) else facing
        )

    def beside(self, anchor: str, category: str, size, side: str, gap: float = 0.05) -> str:
        """Beside ``anchor`` on its own ``left`` or ``right``, backs flush, facing the same way."""
        ax, az, yaw, aw, ad = self._get(anchor)
        sign = 1.0 if side == "left" else -1.0
        lx, lz = sign * (aw / 2.0 + gap + size[0] / 2.0), -ad / 2.0 + size[1] / 2.0
        x, z = to_world(ax, az, yaw, lx, lz)
        return self._add(category, x, z, size, yaw)

    def either_side(self, anchor: str, category: str, size, gap: float = 0.05) -> list[str]:
        return [self.beside(anchor, category, size, side, gap) for side in ("left", "right")]

    def before(
        self,
        anchor: str,
        category: str,
        size,
        distance: float,
        facing: str = "towards",
        across: float = 0.0,
    ) -> str:
        """In front of ``anchor``, ``distance`` metres between their faces, ``across``
        metres to its left; facing it (``towards``) or the way it faces (``same``)."""
        ax, az, yaw, aw, ad = self._get(anchor)
        x, z = to_world(ax, az, yaw, across, ad / 2.0 + distance + size[1] / 2.0)
        return self._add(category, x, z, size, yaw + (math.pi if facing == "towards" else 0.0))

    def on(
        self, support: str, category: str, size, across: float = 0.0, forward: float = 0.0
    ) -> str:
        """A small thing standing on ``support``, ``across`` to its left and ``forward`` of its centre."""
        sx, sz, yaw, _, _ = self._get(support)
        x, z = to_world(sx, sz, yaw, across, forward)
        return self._add(category, x, z, size, yaw, on=support)

    def chairs_around(
        self,
        table: str,
        per_side: int,
        ends: int = 0,
        size=(0.45, 0.5),
        gap: float = 0.05,
        sides: str = "both",
    ) -> list[str]:
        """Chairs facing ``table``: ``per_side`` along each long side (``sides``: both,
        front or back), evenly spaced, and ``ends`` (0, 1 or 2) at its ends."""
        tx, tz, yaw, tw, td = self._get(table)
        chairs = []
        sign_of = {"both": (1.0, -1.0), "front": (1.0,), "back": (-1.0,)}[sides]
        for sign in sign_of:
            for k in range(per_side):
                lx = -tw / 2.0 + tw * (k + 0.5) / per_side
                x, z = to_world(tx, tz, yaw, lx, sign * (td / 2.0 + gap + size[1] / 2.0))
                chairs.append(self._add("chair", x, z, size, yaw + (math.pi if sign > 0 else 0.0)))
        for sign in (1.0, -1.0)[:ends]:
            x, z = to_world(tx, tz, yaw, sign * (tw / 2.0 + gap + size[1] / 2.0), 0.0)
            chairs.append(self._add("chair", x, z, size, yaw - sign * math.pi / 2.0))
        return chairs

    def free(self, x: float, z: float, w: float, d: float, *suits: str) -> None:
        """Free floor centred at plan (x, z), ``w`` east-west by ``d`` north-south."""
        area: dict[str, list] = {"center": self._centred(x, z), "size": [float(w), float(d)]}
        if suits:
            area["suits"] = list(suits)
        self.free_areas.append(area)

    # -- output ---------------------------------------------------------------------------

    def to_dict(self) -> dict:
        data = {
            "id": self.id,
            "type": self.type,
            "title": self.title,
            "room": rounded(self.room.to_dict(), 4),
            "furniture": self.pieces,
        }
        if self.free_areas:
            data["free_areas"] = self.free_areas
        return data

    def plan(self):
        """The checked ``Plan`` this design draws (``PlanError`` names what is wrong)."""
        from scenewright.completion.floor_plan import plan_from_dict

        return plan_from_dict(self.to_dict(), f"design {self.id}")


def designs() -> list[Design]:
    """Every shipped design, type by type in ``TYPES`` order, each module's in its order."""
    drawn = []
    for room_type in TYPES:
        module = importlib.import_module(f"scenewright.completion.designs.{room_type}")
        drawn += [draw() for draw in module.DESIGNS]
    return drawn


def plan_json(data: dict) -> str:
    """A plan's JSON text as people read it: indented, with each list of numbers on one line."""
    text = json.dumps(data, indent=1)
    return (
        re.sub(
            r"\[\s+(-?[0-9.e+-]+(?:,\s+-?[0-9.e+-]+)*)\s+\]",
            lambda match: "[" + ", ".join(match[1].replace(",", " ").split()) + "]",
            text,
        )
        + "\n"
    )


def write_plan_set(folder: Path) -> list[str]:
    """Write every design's plan to ``folder/<type>/<id>.json``; return the problems of
    the designs that do not pass the checks (those are not written)."""
    from scenewright.completion.floor_plan import PlanError
    from scenewright.core.atomic import write_atomic

    problems = []
    for design in designs():
        try:
            plan = design.plan()
        except PlanError as error:
            problems.append(str(error))
            continue
        target = folder / plan.type / f"{plan.id}.json"
        target.parent.mkdir(parents=True, exist_ok=True)
        write_atomic(target, plan_json(plan.to_dict()))
    return problems


def main() -> int:
    from scenewright.completion import shipped_plans_dir

    problems = write_plan_set(shipped_plans_dir())
    for problem in problems:
        print(problem, file=sys.stderr)
    return 1 if problems else 0


if __name__ == "__main__":
    raise SystemExit(main())
