"""``scenewright layout``: re-lay out a scene.json keeping pinned objects exactly where they are."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from scenewright import __version__
from scenewright.cli import main
from scenewright.core.scene import LayoutStats, Relation, Scene, SceneObject
from scenewright.scene_folder import SCENE_FILES

PINNED = ("tower_1", "house_1", "street_lamp_2")


def run(capsys, *argv: str) -> tuple[int, str, str]:
    code = main([str(a) for a in argv])
    captured = capsys.readouterr()
    return code, captured.out, captured.err


def assert_one_line_error(err: str, *fragments: str) -> None:
    lines = err.strip().splitlines()
    assert len(lines) == 1, err
    assert lines[0].startswith("scenewright: error: ") and "Traceback" not in err
    for fragment in fragments:
        assert fragment in lines[0], lines[0]


def poses(scene: dict) -> dict[str, tuple]:
    """id -> (x, y, z, yaw) exactly as scene.json has them."""
    return {o["id"]: (*o["position"], o["yaw"]) for o in scene["objects"] if o["kind"] != "group"}


@pytest.fixture(scope="module")
def village(tmp_path_factory) -> Path:
    """``scenewright generate village --seed 7 --no-render -o out/``: its scene.json."""
    out = tmp_path_factory.mktemp("village")
    assert main(["generate", "village", "--seed", "7", "--no-render", "-q", "-o", str(out)]) == 0
    return out / "scene.json"


def test_layout_keeps_the_pinned_poses_exactly_and_moves_the_others(capsys, tmp_path, village):
    out = tmp_path / "out2"
    code, stdout, err = run(
        capsys,
        "layout",
        village,
        "--pin",
        ",".join(PINNED),
        "--seed",
        "2",
        "--no-render",
        "-o",
        out,
    )
    before = json.loads(village.read_text())
    after = json.loads((out / "scene.json").read_text())
    # exit code and summary as generate gives them
    assert code == (0 if after["layout"]["ok"] else 1), err
    assert code == 0, err
    lines = stdout.splitlines()
    assert lines[0] == f"pinned: {', '.join(PINNED)}"
    assert lines[1].startswith(f"wrote {out}/: ")
    assert lines[2].startswith("ok: 30 objects, 2 paths, relations satisfied 30/30, energy ")
    assert sorted(p.name for p in out.iterdir()) == sorted(
        set(SCENE_FILES) - {name for name in SCENE_FILES if name.startswith("preview")}
    )
    old, new = poses(before), poses(after)
    for object_id in PINNED:
        assert new[object_id] == old[object_id], object_id
    others = [object_id for object_id in old if object_id not in PINNED]
    assert all(new[object_id] != old[object_id] for object_id in others)
    # the same scene otherwise: rules, objects, relations; a new seed and description
    assert after["rules"] == before["rules"] == "village" and after["seed"] == 2
    assert [o["id"] for o in after["objects"]] == [o["id"] for o in before["objects"]]
    assert [(r["source"], r["label"], r["target"]) for r in after["relations"]] == [
        (r["source"], r["label"], r["target"]) for r in before["relations"]
    ]
    assert after["derivation"] == before["derivation"]
    text = (out / "description.txt").read_text()
    assert text == after["description"]["text"] + "\n"
    assert set(json.loads((out / "timings.json").read_text())) >= {"layout", "describe", "export"}


def test_layout_is_reproducible_for_the_same_file_pins_and_seed(capsys, tmp_path, village):
    outputs = []
    for name in ("a", "b"):
        code, _, err = run(
            capsys,
            "layout",
            village,
            "--pin",
            "tower_1",
            "--seed",
            "2",
            "--no-render",
            "-q",
            "-o",
            tmp_path / name,
        )
        assert code == 0, err
        outputs.append(tmp_path / name)
    for name in ("scene.json", "description.txt"):
        assert (outputs[0] / name).read_bytes() == (outputs[1] / name).read_bytes(), name


def test_pinning_a_group_pins_its_members_and_a_road_its_junction(capsys, tmp_path, village):
    out = tmp_path / "out"
    code, stdout, err = run(
        capsys,
        "layout",
        village,
        "--pin",
        "market_stand_1",
        "--pin",
        "road_1",
        "--seed",
        "3",
        "--no-render",
        "-o",
        out,
    )
    assert code == 0, err
    assert stdout.splitlines()[0] == (
        "pinned: market_stand_1, road_1 (with intersection_1, table_1, sign_1, pot_of_stew_1)"
    )
    before = json.loads(village.read_text())
    after = json.loads((out / "scene.json").read_text())
    old, new = poses(before), poses(after)
    for object_id in ("intersection_1", "table_1", "sign_1", "pot_of_stew_1"):
        assert new[object_id] == old[object_id], object_id
    roads = (
        {p["id"]: p["points"] for p in before["paths"]},
        {p["id"]: p["points"] for p in after["paths"]},
    )
    assert roads[1]["road_1"] == roads[0]["road_1"]
    assert (
        roads[1]["road_2"] != roads[0]["road_2"] and roads[1]["road_2"][0] == roads[0]["road_2"][0]
    )


def test_warm_starts_from_the_old_poses(capsys, tmp_path, village):
    code, _, err = run(
        capsys, "layout", village, "--pin", "tower_1", "--warm", "--no-render", "-q", "-o", tmp_path
    )
    assert code == 0, err
    old, new = (
        poses(json.loads(village.read_text())),
        poses(json.loads((tmp_path / "scene.json").read_text())),
    )
    assert new["tower_1"] == old["tower_1"]
    # started where they were: most things end near their old place
    near = [k for k in old if abs(new[k][0] - old[k][0]) + abs(new[k][2] - old[k][2]) < 3.0]
    assert len(near) >= len(old) // 2


def test_layout_renders_like_generate(capsys, tmp_path, village):
    code, _, err = run(
        capsys, "layout", village, "--pin", "tower_1", "--size", "64x48", "-q", "-o", tmp_path
    )
    assert code == 0, err
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted(SCENE_FILES)
    assert json.loads((tmp_path / "scene.json").read_text())["render"]["camera"]["width"] == 64


def test_help_has_examples(capsys):
    with pytest.raises(SystemExit) as exit_info:
        main(["layout", "--help"])
    out = capsys.readouterr().out
    assert exit_info.value.code == 0
    assert (
        "examples:" in out and "scenewright layout out/scene.json --pin" in out and "--warm" in out
    )


@pytest.mark.parametrize(
    "argv, fragments",
    [
        (["--pin", "tower_9"], ["--pin: unknown id 'tower_9'", "did you mean"]),
        (["--pin", "tower_1,,nothing_here"], ["unknown id 'nothing_here'"]),
        (["--seed", "-1"], ["argument --seed"]),
        (["--size", "12"], ["argument --size"]),
    ],
)
def test_bad_options_exit_2_on_one_line(capsys, tmp_path, village, argv, fragments):
    code, _, err = run(capsys, "layout", village, *argv, "--no-render", "-o", tmp_path / "out")
    assert code == 2
    assert_one_line_error(err, *fragments)
    assert not (tmp_path / "out").exists()


def test_bad_scene_files_exit_2_on_one_line(capsys, tmp_path):
    not_json = tmp_path / "broken.json"
    not_json.write_text("{")
    code, _, err = run(capsys, "layout", not_json, "-o", tmp_path / "out")
    assert code == 2
    assert_one_line_error(err, "broken.json: not JSON")
    code, _, err = run(capsys, "layout", tmp_path / "nowhere.json", "-o", tmp_path / "out")
    assert code == 2
    assert_one_line_error(err, "nowhere.json: cannot read")
    wrong = tmp_path / "wrong.json"
    wrong.write_text(json.dumps({"rules": "x", "seed": 1}))
    code, _, err = run(capsys, "layout", wrong, "-o", tmp_path / "out")
    assert code == 2
    assert_one_line_error(err, "wrong.json")
    code, _, err = run(capsys, "layout", wrong)
    assert code == 2
    assert_one_line_error(err, "-o/--output")


def test_a_layout_that_is_not_ok_exits_1_with_its_problems(capsys, tmp_path):
    """Two boxes pinned on top of each other: the files are written, the exit code is 1."""
    box = dict(
        type="box",
        kind="object",
        noun="box",
        plural=None,
        parent=None,
        style=None,
        yaw=0.0,
        size=[1.0, 1.0, 1.0],
        shape="box",
    )
    scene = Scene(
        rules="test",
        seed=1,
        extent=[10.0, 10.0],
        objects=[
            SceneObject("box_1", position=[0.0, 0.0, 0.0], order=0, **box),
            SceneObject("box_2", position=[0.25, 0.0, 0.0], order=1, **box),
            SceneObject("box_3", position=[3.0, 0.0, 3.0], order=2, **box),
        ],
        paths=[],
        relations=[Relation("box_3", "box_1", "NextTo", 0.0, False)],
        layout=LayoutStats(ok=False),
        version=__version__,
    )
    path = tmp_path / "scene.json"
    path.write_text(scene.to_json(reproducible=True))
    code, stdout, err = run(
        capsys, "layout", path, "--pin", "box_1,box_2", "--no-render", "-o", tmp_path / "out"
    )
    assert code == 1
    assert "LAYOUT FAILED: 3 objects" in stdout
    assert_one_line_error(
        err, "the layout did not satisfy every constraint", "box_1 overlaps box_2"
    )
    after = json.loads((tmp_path / "out" / "scene.json").read_text())
    assert after["layout"]["ok"] is False
    assert poses(after)["box_2"] == (0.25, 0.0, 0.0, 0.0)
