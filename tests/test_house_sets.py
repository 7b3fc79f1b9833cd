"""The shipped house plans: each reads cleanly, makes the rooms its comment promises, and
makes a good house at a fixed seed (every room laid out ok, reachable, described)."""

from __future__ import annotations

import json
import re

import pytest

from scenewright.cli import main
from scenewright.house import read_plan, shipped_plans

SETS = ("apartment", "house", "office_floor", "dungeon")
#: A seed each plan makes a good house with, and whether that takes more than a few seconds.
SEEDS = {"apartment": 1002, "dungeon": 1000, "house": 1013, "office_floor": 1000}
SLOW = {"apartment", "house", "office_floor"}


def test_the_house_sets_are_shipped_and_are_no_scene_rule_sets():
    from scenewright.generator import shipped_rule_sets

    assert set(SETS) <= set(shipped_plans())
    assert not set(shipped_plans()) & set(shipped_rule_sets())


@pytest.mark.parametrize("name", SETS)
def test_the_room_count_the_comment_promises(name):
    spec = read_plan(name)
    header = spec.path.read_text().split("\nplan ", 1)[0]
    low, high = (int(v) for v in re.search(r"(\d+)\.\.(\d+)\s+rooms", header).groups())
    always = sum(room.count[0] for room in spec.rooms if room.probability >= 1.0)
    most = sum(room.count[1] for room in spec.rooms)
    assert (always, most) == (low, high)


@pytest.mark.parametrize(
    "name", [pytest.param(n, marks=pytest.mark.slow) if n in SLOW else n for n in SETS]
)
def test_makes_a_good_house_at_a_fixed_seed(name, tmp_path, capsys):
    out = tmp_path / name
    assert main(["generate", name, "--seed", str(SEEDS[name]), "--no-render", "-o", str(out)]) == 0
    scene = json.loads((out / "scene.json").read_text())
    house = scene["house"]
    ids = {room["id"] for room in house["rooms"]}
    assert scene["layout"]["ok"] and scene["layout"]["problems"] == []
    assert all(room["layout"]["ok"] for room in house["rooms"])
    # every object is in a room of the house, every room holds something but halls and corridors
    assert {o["id"].split("/")[0] for o in scene["objects"]} <= ids
    furnished = {o["id"].split("/")[0] for o in scene["objects"]}
    assert {r["id"] for r in house["rooms"] if r["type"] not in ("hall", "corridor")} <= furnished
    noun = read_plan(name).noun
    text = (out / "description.txt").read_text()
    assert text.startswith(f"The {noun} has ")
    assert "The front door opens into the " in text
    for room in house["rooms"]:  # the overview, then a part per room that names it
        assert f"The {room['name']} " in text


def test_list_shows_the_house_plans_with_their_rooms(capsys):
    assert main(["list"]) == 0
    out = capsys.readouterr().out
    assert "apartment  (house plan, flat: 5..7 rooms)" in out
    assert "office_floor  (house plan, office floor: 10..20 rooms)" in out
    dungeon = out[out.index("dungeon  (house plan") :].splitlines()[1]
    assert dungeon.split(", ") == ["    guard_room", "corridor", "barracks", "treasury", "library"]
