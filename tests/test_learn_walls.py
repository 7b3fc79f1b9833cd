"""Wall labels learned per placement (``Placement.wall``: held by most of its objects): a
floor lamp flush with the wall beside its armchair in most reading corners and out in
the room in the rest is put at the wall only in its flush placement, so the scenes made
keep the examples' share instead of putting every lamp there (or none)."""

from __future__ import annotations

import json
import math
import re
from pathlib import Path

import numpy as np
import pytest

from scenewright.api import build_scene, load_rules
from scenewright.core.frames import to_world
from scenewright.examples import load_examples, scene_supports
from scenewright.learning.induce import _walls, induce
from scenewright.learning.rules_text import rules_text

CHAIR = (0.85, 0.95, 0.85)
LAMP = (0.35, 1.6, 0.35)


def corners(folder: Path, at_wall: list[bool]) -> list[Path]:
    """Reading corners: an armchair with its back to some wall of a 4 x 3.6 m room and a
    floor lamp on its left, its back flush with the wall or, where ``at_wall`` says
    not, 0.4 m out into the room (positions in the room turned so the wall is north)."""
    folder.mkdir(parents=True, exist_ok=True)
    draw = np.random.default_rng(3)
    room = (4.0, 3.6)
    paths = []
    for index, flush in enumerate(at_wall):
        yaw = float(draw.choice([0.0, 90.0, 180.0, -90.0]))
        reach = (room[1] if yaw in (0.0, 180.0) else room[0]) / 2
        turn = math.radians(yaw)
        along = float(draw.uniform(-0.4, 0.4))
        out = CHAIR[0] / 2 + float(draw.uniform(0.08, 0.15)) + LAMP[0] / 2
        chair = to_world(0, 0, turn, along, CHAIR[2] / 2 + 0.02 - reach)
        lamp = to_world(0, 0, turn, along + out, LAMP[2] / 2 + 0.02 - reach + (0 if flush else 0.4))
        objects = [
            {"id": ident, "type": kind, "size": list(size), "position": list(at), "yaw": yaw}
            for ident, kind, size, at in (
                ("chair", "armchair", CHAIR, chair),
                ("lamp", "floor_lamp", LAMP, lamp),
            )
        ]
        path = folder / f"corner_{index:02d}.json"
        path.write_text(
            json.dumps({"room": {"width": room[0], "depth": room[1]}, "objects": objects})
        )
        paths.append(path)
    return paths


@pytest.mark.parametrize("flush", [8, 7])
def test_a_lamp_flush_with_the_wall_in_most_examples_keeps_their_share(tmp_path, flush):
    paths = corners(tmp_path / "corners", [True] * flush + [False] * (10 - flush))
    induction = induce(load_examples(paths), name="corners", seed=0)
    text = rules_text(induction)
    lines = [line for line in text.splitlines() if re.search(r"\{ floor_lamp NextToLeft", line)]
    # Two ways: flush (aligned with the armchair's back, at the wall) and out in the room.
    assert len(lines) == 2, text
    assert f"{flush}: {{" in lines[0] and "AgainstWall some wall" in lines[0]
    assert f"{10 - flush}: {{" in lines[1] and "AgainstWall" not in lines[1]
    output = tmp_path / "corners.rules"
    output.write_text(text)
    rules = load_rules(output)
    scenes = [build_scene(rules, seed) for seed in range(40)]
    assert all(scene.layout.ok for scene in scenes)
    share = _walls(scenes, [scene_supports(scene) for scene in scenes])["floor_lamp"]
    assert abs(share.held["AgainstWall"] / share.objects - flush / 10) <= 0.15


def test_every_lamp_flush_keeps_one_way_with_its_wall(tmp_path):
    text = rules_text(induce(load_examples(corners(tmp_path / "c", [True] * 10)), name="c", seed=0))
    assert re.search(r"^\s*floor_lamp NextToLeft [^#\n]*AgainstWall some wall", text, re.M), text
