"""Houses: plans in the rules language and given as JSON, drawn into rooms joined by doors,
each room furnished, described, and checked the way the issue asks (reachable rooms,
shared walls once, doors clear, objects inside their rooms, the same house whatever the
number of workers)."""

from __future__ import annotations

import json
import math

import pytest

from scenewright.cli import main
from scenewright.core.house import room_of
from scenewright.core.scene import Scene
from scenewright.generator.rules_errors import RulesError
from scenewright.house import house_of, house_scene_from, read_plan
from scenewright.house.assemble import room_scene
from scenewright.house.describe import describe_house, overview_sentences
from scenewright.house.floor_plan import PlanError
from scenewright.house.given_plan import GivenPlanError

# Small rooms with few things, so a house lays out in a moment.
SMALL = """\
# a small flat for the tests
plan flat {
    noun "flat"
    footprint 9..10 x 6..7
    room hall area 6..10 entrance width 1.2
    room bathroom
    room corridor area 5..9 width 1.2
    0.5? room study
    connect hall bathroom corridor
}
"""


@pytest.fixture
def small_plan(tmp_path):
    path = tmp_path / "flat.rules"
    path.write_text(SMALL)
    return path


def _write(tmp_path, text, name="plan.rules"):
    path = tmp_path / name
    path.write_text(text)
    return path


# -- the plan language ----------------------------------------------------------------


def test_a_plan_reads_its_rooms_and_connections(small_plan):
    spec = read_plan(small_plan)
    assert [room.type for room in spec.rooms] == ["hall", "bathroom", "corridor", "study"]
    assert spec.rooms[0].entrance and spec.rooms[3].probability == 0.5
    assert spec.connections[0].hub == "hall"
    assert spec.connections[0].others == ("bathroom", "corridor")
    assert spec.size == ((9.0, 10.0), (6.0, 7.0))


@pytest.mark.parametrize(
    ("text", "where", "words"),
    [
        ("plan p { footprint 8 x 6 room bedrom }", ":1:31:", "did you mean 'bedroom'"),
        (
            "plan p { footprint 8 x 6 room hall connect hall kitchn }",
            ":1:49:",
            "'kitchn' is not a room of this plan",
        ),
        ("plan p { footprint 4 x 4 room bedroom area 20..30 }", ":1:31:", "needs at least 20"),
        (
            "plan p { footprint 6 x 6 room hall area 20..30 room bathroom area 20..25 }",
            ":1:10:",
            "need at least 40",
        ),
        ("plan p { footprint 8 x 6 room hall area 9..5 }", ":1:41:", "runs backwards"),
        ("plan p { footprint 8 x 6 rom hall }", ":1:26:", "unexpected 'rom'"),
        ("plan p { room hall }", ":1:1:", "no 'footprint'"),
    ],
)
def test_a_plan_that_cannot_exist_is_refused_at_its_mistake(tmp_path, text, where, words):
    path = _write(tmp_path, text)
    with pytest.raises(RulesError) as caught:
        read_plan(path)
    message = str(caught.value)
    assert where in message and words in message, message


def test_the_cli_refuses_a_bad_plan_in_one_located_line(tmp_path, capsys):
    path = _write(tmp_path, "plan p {\n    footprint 8 x 6\n    room kitchn\n}\n")
    code = main(["generate", str(path), "-o", str(tmp_path / "out")])
    err = capsys.readouterr().err
    assert code == 2
    assert "plan.rules:3:10: error: no shipped rule set furnishes room type 'kitchn'" in err
    assert "did you mean 'kitchen'" in err
    assert "Traceback" not in err
    assert not (tmp_path / "out").exists()


def test_a_plan_with_no_floor_plan_says_what_failed(tmp_path):
    # four rooms that each want 3 m of width, in a footprint 4 m deep: never two side by side
    path = _write(
        tmp_path,
        "plan p { footprint 7 x 4 room hall width 3 area 6..8 room bathroom width 3 area 6..8 "
        "room study width 3 area 6..8 connect hall bathroom study }",
    )
    with pytest.raises(PlanError, match=r"no floor plan found in \d+ tries \(\d+ failed because"):
        house_of(path, 0)


# -- the floor plan ---------------------------------------------------------------------


@pytest.mark.parametrize("seed", [0, 1, 1000, 1001])
def test_every_room_is_reachable_and_every_wall_is_there_once(small_plan, seed):
    house = house_of(small_plan, seed)
    assert house.reachable() == {room.id for room in house.rooms}
    assert house.entrance is not None and house.entrance.rooms == ("hall_1",)
    # no two walls run along the same stretch
    for k, a in enumerate(house.walls):
        for b in house.walls[k + 1 :]:
            assert _overlap(a, b) < 1e-6, (a, b)
    # each door lies in a wall between the rooms it joins (or an outside wall of its room)
    for door in house.doors:
        wall = min(house.walls, key=lambda w: _distance(w, door.center))
        assert _distance(wall, door.center) < 1e-6
        expected = set(door.rooms) if len(door.rooms) == 2 else {door.rooms[0], None}
        assert set(wall.rooms) == expected
    for window in (o for o in house.openings if o.kind == "window"):
        wall = min(house.walls, key=lambda w: _distance(w, window.center))
        assert None in wall.rooms and window.rooms[0] in wall.rooms


def test_the_same_seed_draws_the_same_plan_and_another_seed_another(small_plan):
    first, again = house_of(small_plan, 5), house_of(small_plan, 5)
    assert first.to_dict() == again.to_dict()
    others = [house_of(small_plan, seed).to_dict() for seed in range(6, 10)]
    assert any(other != first.to_dict() for other in others)


def test_a_courtyard_footprint_keeps_its_hole(tmp_path):
    path = _write(
        tmp_path,
        "plan ring { footprint (0,0) (12,0) (12,10) (0,10) courtyard (4,3) (8,3) (8,7) (4,7)\n"
        "  room hall area 10..30 entrance width 1.2 room bathroom room study 3 area 14..28 }",
    )
    house = house_of(path, 0)
    assert len(house.holes) == 1
    xs = [p[0] for p in house.holes[0]]
    assert max(xs) - min(xs) == pytest.approx(4.0)
    assert house.reachable() == {room.id for room in house.rooms}


# -- furnished, described, stored ----------------------------------------------------------


def test_a_house_is_furnished_room_by_room_inside_its_rooms(small_plan):
    scene = house_scene_from(small_plan, 3)
    assert scene.house is not None and scene.room is None
    for house_room in scene.house.rooms:
        room = room_scene(scene, house_room.id)
        for obj in room.placed_objects():
            assert room.room.contains(obj.position[0], obj.position[2]), obj.id
    assert {room_of(o.id) for o in scene.objects} <= {r.id for r in scene.house.rooms}


def test_a_house_is_the_same_whatever_the_number_of_workers(small_plan):
    one = house_scene_from(small_plan, 7, workers=1)
    two = house_scene_from(small_plan, 7, workers=2)
    assert one.to_json(reproducible=True) == two.to_json(reproducible=True)


def _failing_first_plans(monkeypatch, failing):
    """Make the first ``failing`` floor plans furnished come back with their first room not
    ok (as a room no try of its rule set furnishes does); returns the houses furnished."""
    import scenewright.house.furnish as furnishing

    real = furnishing.furnish
    furnished = []

    def furnish(house, seed, *, workers=1):
        rooms = real(house, seed, workers=workers)
        furnished.append(house)
        if len(furnished) <= failing:
            rooms[0].layout.ok = False
        return rooms

    monkeypatch.setattr(furnishing, "furnish", furnish)
    return furnished


def _outlines(house):
    return [room.outline for room in house.rooms]


def test_a_plan_whose_room_cannot_be_furnished_is_drawn_again(small_plan, monkeypatch):
    furnished = _failing_first_plans(monkeypatch, failing=1)
    scene = house_scene_from(small_plan, 3)
    assert len(furnished) == 2
    assert _outlines(furnished[1]) != _outlines(furnished[0])  # a new floor plan
    assert _outlines(scene.house) == _outlines(furnished[1])
    assert scene.layout.ok and scene.seed == 3
    furnished.clear()
    again = house_scene_from(small_plan, 3)  # the same seed draws the same plans again
    assert again.to_json(reproducible=True) == scene.to_json(reproducible=True)


def test_when_no_plan_furnishes_the_best_is_kept_and_says_why(small_plan, monkeypatch):
    from scenewright.house import PLAN_TRIES

    furnished = _failing_first_plans(monkeypatch, failing=PLAN_TRIES)
    scene = house_scene_from(small_plan, 3)
    assert len(furnished) == PLAN_TRIES
    assert not scene.layout.ok
    assert _outlines(scene.house) == _outlines(furnished[0])  # the first of equals


def test_a_given_plan_is_not_drawn_again(tmp_path, monkeypatch):
    path = tmp_path / "mine.json"
    path.write_text(json.dumps(GIVEN))
    furnished = _failing_first_plans(monkeypatch, failing=1)
    scene = house_scene_from(path, 0)
    assert len(furnished) == 1 and not scene.layout.ok


def test_scene_json_keeps_the_house_and_gives_each_room_back(small_plan):
    scene = house_scene_from(small_plan, 3)
    again = Scene.from_json(scene.to_json())
    assert again.to_json() == scene.to_json()
    first = scene.house.rooms[0].id
    assert room_scene(again, first).to_json() == room_scene(scene, first).to_json()


def test_the_overview_says_what_the_plan_holds(small_plan):
    scene = house_scene_from(small_plan, 3)
    house = scene.house
    overview = overview_sentences(house)
    assert overview[0].startswith("The flat has a hall, a bathroom, a corridor")
    assert overview[1] == "The front door opens into the hall."
    text = describe_house(scene).text
    for other, _door in house.neighbours("hall_1"):
        assert house.room(other).name in overview[2]
    assert "\n" not in text
    assert f"The {house.rooms[1].name} " in text  # each room's paragraph names it
    assert describe_house(scene, style="short").text == overview[0]


def test_generate_writes_a_house_folder(small_plan, tmp_path):
    out = tmp_path / "out"
    assert main(["generate", str(small_plan), "--seed", "3", "--no-render", "-o", str(out)]) == 0
    data = json.loads((out / "scene.json").read_text())
    assert data["house"]["noun"] == "flat"
    assert (out / "description.txt").read_text().startswith("The flat has")


# -- a plan of the user's own, as JSON -------------------------------------------------------

GIVEN = {
    "noun": "flat",
    "rooms": [
        {"id": "hall", "type": "hall", "polygon": [[0, 0], [2, 0], [2, 6], [0, 6]]},
        {"type": "bathroom", "polygon": [[2, 0], [5, 0], [5, 3], [2, 3]]},
        # an L-shaped study round the bathroom's corner
        {"type": "study", "polygon": [[2, 3], [5, 3], [5, 0], [8, 0], [8, 6], [2, 6]]},
    ],
}


def test_a_given_plan_is_furnished_as_drawn(tmp_path):
    path = tmp_path / "mine.json"
    path.write_text(json.dumps(GIVEN))
    scene = house_scene_from(path, 0)
    house = scene.house
    assert [r.id for r in house.rooms] == ["hall", "bathroom_1", "study_1"]
    assert house.reachable() == {"hall", "bathroom_1", "study_1"}
    assert house.entrance.rooms == ("hall",)
    study = house.room("study_1")
    assert len(study.room.walls) == 6
    # 27 m² on the centre lines, less half a wall (6 cm) along its 24 m of outline
    assert study.area == pytest.approx(27 - 0.06 * 24, abs=0.05)


@pytest.mark.parametrize(
    ("change", "words"),
    [
        (
            lambda p: p["rooms"][1].update(type="bathrom"),
            "rooms[1]: no shipped rule set furnishes room type 'bathrom'; did you mean 'bathroom'",
        ),
        (
            lambda p: p["rooms"][0].update(polygon=[[0, 0], [2, 0]]),
            "rooms[0]: 'polygon' must list at least three",
        ),
        (
            lambda p: p.update(doors=[{"between": ["hall", "kitchen"]}]),
            "doors[0]: there is no room 'kitchen'",
        ),
        (lambda p: p.update(doors=[{"between": ["hall", "study_1"]}]), "no front door"),
    ],
)
def test_a_given_plan_with_a_mistake_names_its_place(tmp_path, change, words):
    plan = json.loads(json.dumps(GIVEN))
    change(plan)
    path = tmp_path / "mine.json"
    path.write_text(json.dumps(plan))
    with pytest.raises(GivenPlanError) as caught:
        house_of(path, 0)
    assert words in str(caught.value)


def _distance(wall, point) -> float:
    (ax, az), (bx, bz) = wall.start, wall.end
    dx, dz = bx - ax, bz - az
    t = max(0.0, min(1.0, ((point[0] - ax) * dx + (point[1] - az) * dz) / (dx * dx + dz * dz)))
    return math.hypot(point[0] - ax - t * dx, point[1] - az - t * dz)


def _overlap(a, b) -> float:
    """Length along which two walls run over each other (0 unless collinear)."""
    (ax, az), (bx, bz) = a.start, a.end
    length = math.hypot(bx - ax, bz - az)
    tx, tz = (bx - ax) / length, (bz - az) / length
    for p in (b.start, b.end):
        if abs((p[0] - ax) * tz - (p[1] - az) * tx) > 1e-6:
            return 0.0
    u = sorted(((p[0] - ax) * tx + (p[1] - az) * tz) for p in (b.start, b.end))
    return max(0.0, min(length, u[1]) - max(0.0, u[0]))


# -- the other commands on houses ---------------------------------------------------------------


@pytest.fixture
def house_folder(small_plan, tmp_path):
    out = tmp_path / "house"
    assert main(["generate", str(small_plan), "--seed", "3", "--no-render", "-o", str(out)]) == 0
    return out


def test_evaluate_measures_a_house_room_by_room(house_folder, capsys):
    assert main(["evaluate", str(house_folder / "scene.json"), "--json"]) == 0
    measured = json.loads(capsys.readouterr().out)
    house = json.loads((house_folder / "scene.json").read_text())["house"]
    names = [scene["scene"] for scene in measured["scenes"]]
    assert names == [f"{house_folder / 'scene.json'} {room['id']}" for room in house["rooms"]]
    assert measured["summary"]["collision_rate"] == 0.0


def test_layout_keeps_a_pinned_object_of_a_house_and_moves_the_rest(house_folder, tmp_path, capsys):
    before = json.loads((house_folder / "scene.json").read_text())
    pinned = next(o["id"] for o in before["objects"] if o["kind"] == "object")
    out = tmp_path / "again"
    code = main(
        [
            "layout",
            str(house_folder / "scene.json"),
            "--pin",
            pinned,
            "--seed",
            "9",
            "--no-render",
            "-o",
            str(out),
        ]
    )
    assert code in (0, 1)
    after = json.loads((out / "scene.json").read_text())
    poses = {o["id"]: (o["position"], o["yaw"]) for o in after["objects"]}
    first = {o["id"]: (o["position"], o["yaw"]) for o in before["objects"]}
    assert poses[pinned] == first[pinned]
    assert any(poses[i] != first[i] for i in first if i != pinned)
    assert after["house"]["rooms"] == [
        {**room, "seed": a["seed"], "layout": a["layout"], "derivation": a["derivation"]}
        for room, a in zip(before["house"]["rooms"], after["house"]["rooms"], strict=True)
    ]
    capsys.readouterr()
    assert (
        main(
            [
                "layout",
                str(house_folder / "scene.json"),
                "--pin",
                "bed_1",
                "-o",
                str(tmp_path / "x"),
            ]
        )
        == 2
    )
    assert "named ROOM/OBJECT" in capsys.readouterr().err


def test_a_dataset_of_houses(small_plan, tmp_path):
    out = tmp_path / "data"
    code = main(
        ["dataset", str(small_plan), "-n", "2", "--no-images", "--workers", "1", "-o", str(out)]
    )
    assert code in (0, 1)
    rows = [json.loads(line) for line in (out / "metadata.jsonl").read_text().splitlines()]
    assert rows and all(row["text"].startswith("The flat has") for row in rows)


def test_complete_adds_to_one_room_of_a_house_and_keeps_the_rest(house_folder, tmp_path, capsys):
    before = json.loads((house_folder / "scene.json").read_text())
    room = before["house"]["rooms"][0]["id"]
    out = tmp_path / "completed"
    code = main(
        [
            "complete",
            str(house_folder / "scene.json"),
            "--in",
            room,
            "--add",
            "plant",
            "--no-render",
            "-o",
            str(out),
        ]
    )
    assert code in (0, 1)
    after = json.loads((out / "scene.json").read_text())
    poses = {o["id"]: o["position"] for o in after["objects"]}
    for obj in before["objects"]:
        assert poses[obj["id"]] == obj["position"]
    added = set(poses) - {o["id"] for o in before["objects"]}
    assert added and all(name.startswith(room + "/") for name in added)
    capsys.readouterr()
    assert (
        main(
            [
                "complete",
                str(house_folder / "scene.json"),
                "--add",
                "plant",
                "-o",
                str(tmp_path / "x"),
            ]
        )
        == 2
    )
    assert "is a house: --in names which room to complete" in capsys.readouterr().err
