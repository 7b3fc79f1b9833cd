"""The match / augment / vary commands: output, and bad input as one line with exit 2."""

from __future__ import annotations

import json

import pytest

from scenewright.cli import main

ROOM = {
    "extent": [6, 6],
    "objects": [
        {"id": "desk", "type": "desk", "size": [1.4, 0.75, 0.7], "position": [0, 0, 0], "yaw": 0},
        {
            "id": "chair",
            "type": "chair",
            "size": [0.5, 0.9, 0.5],
            "position": [0, 0, 0.8],
            "yaw": 180,
        },
        {
            "id": "lamp",
            "type": "lamp",
            "size": [0.2, 0.4, 0.2],
            "position": [0.4, 0],
            "parent": "desk",
        },
        {
            "id": "shelf",
            "type": "shelf",
            "size": [0.9, 1.8, 0.35],
            "position": [-1.5, 0, -0.2],
            "yaw": 0,
        },
    ],
}


def run(capsys, *argv: str) -> tuple[int, str, str]:
    code = main(list(argv))
    captured = capsys.readouterr()
    return code, captured.out, captured.err


@pytest.fixture
def rooms(tmp_path):
    first = tmp_path / "first.json"
    first.write_text(json.dumps(ROOM))
    renamed = json.loads(json.dumps(ROOM))
    for obj in renamed["objects"]:
        obj["type"] = "thing_" + obj["type"]
    renamed["objects"][3]["position"] = [1.8, 0, -0.1]
    second = tmp_path / "second.json"
    second.write_text(json.dumps(renamed))
    return first, second


def test_match_prints_pairs_and_json(capsys, rooms):
    code, out, _ = run(capsys, "match", str(rooms[0]), str(rooms[1]))
    assert code == 0
    assert out.splitlines()[0].startswith("first -> second: 3 matched")
    assert any(line.split()[:3] == ["desk", "->", "desk"] for line in out.splitlines())
    code, out, _ = run(capsys, "match", str(rooms[0]), str(rooms[1]), "--json")
    data = json.loads(out)
    assert {(p["a"], p["b"]) for p in data["pairs"]} == {
        ("desk", "desk"),
        ("chair", "chair"),
        ("shelf", "shelf"),
    }


@pytest.mark.parametrize(
    ("argv", "fragment"),
    [
        (["match", "{a}", "{missing}"], "cannot read"),
        (["match", "{a}", "{bad}"], "bad.json:1:2: not JSON"),
        (
            ["match", "{a}", "{a}", "--threshold", "1.5"],
            "argument --threshold: must be from 0 to 1",
        ),
        (["match", "{a}"], "the following arguments are required"),
    ],
)
def test_bad_input_is_one_line_and_exit_2(capsys, tmp_path, rooms, argv, fragment):
    (tmp_path / "bad.json").write_text("{oops")
    names = {
        "a": str(rooms[0]),
        "missing": str(tmp_path / "missing.json"),
        "bad": str(tmp_path / "bad.json"),
    }
    code, out, err = run(capsys, *[part.format(**names) for part in argv])
    assert code == 2 and out == ""
    lines = err.strip().splitlines()
    assert (
        len(lines) == 1 and lines[0].startswith("scenewright: error: ") and fragment in lines[0]
    ), err


def test_augment_writes_json_or_dot(capsys, tmp_path, rooms):
    target = tmp_path / "ag.json"
    code, out, _ = run(capsys, "augment", str(rooms[0]), str(rooms[1]), "-o", str(target))
    assert code == 0 and out.startswith(f"wrote {target}: ")
    data = json.loads(target.read_text())
    assert (
        len([n for n in data["nodes"] if len(n["members"]) == 2]) == 3
    )  # desk, chair, shelf merged
    code, out, _ = run(capsys, "augment", str(rooms[0]), str(rooms[1]), "--format", "dot")
    assert code == 0 and out.startswith("digraph augmented {")


def test_augment_bad_example_writes_nothing(capsys, tmp_path, rooms):
    (tmp_path / "bad.json").write_text('{"extent": [4, 4], "objects": [{"id": "x"}]}')
    target = tmp_path / "ag.json"
    code, _, err = run(
        capsys, "augment", str(rooms[0]), str(tmp_path / "bad.json"), "-o", str(target)
    )
    assert code == 2 and not target.exists()
    assert len(err.strip().splitlines()) == 1 and "bad.json: $.objects[0] (object 'x')" in err


def test_vary_writes_ranked_variant_folders(capsys, tmp_path, rooms):
    out = tmp_path / "variants"
    code, stdout, err = run(
        capsys,
        "vary",
        str(rooms[0]),
        str(rooms[1]),
        "-n",
        "2",
        "--seed",
        "3",
        "--no-render",
        "-o",
        str(out),
    )
    index = json.loads((out / "index.json").read_text())
    assert len(index["variants"]) == 2 and code == 0, err
    assert stdout.startswith(f"wrote {out}/: 2 variants")
    for entry in index["variants"]:
        folder = out / entry["folder"]
        assert sorted(p.name for p in folder.iterdir()) == [
            "description.txt",
            "plan.png",
            "scene.glb",
            "scene.json",
            "timings.json",
        ]
        scene = json.loads((folder / "scene.json").read_text())
        assert scene["synthesis"]["operations"] and set(scene["synthesis"]["sources"]) == {
            o["id"] for o in scene["objects"] if o["kind"] == "object"
        }
    again = tmp_path / "again"
    run(
        capsys,
        "vary",
        str(rooms[0]),
        str(rooms[1]),
        "-n",
        "2",
        "--seed",
        "3",
        "--no-render",
        "-o",
        str(again),
    )
    assert (again / "variant_001" / "scene.json").read_bytes() == (
        out / "variant_001" / "scene.json"
    ).read_bytes()


def test_vary_bad_input_writes_nothing(capsys, tmp_path, rooms):
    out = tmp_path / "variants"
    code, _, err = run(
        capsys, "vary", str(rooms[0]), str(tmp_path / "none.glb"), "-n", "2", "-o", str(out)
    )
    assert code == 2 and len(err.strip().splitlines()) == 1 and "none.glb: cannot read" in err
    assert not out.exists() or not any(out.iterdir())
    code, _, err = run(capsys, "vary", str(rooms[0]), "-n", "0", "-o", str(out))
    assert code == 2 and "must be at least 1" in err
    code, _, err = run(capsys, "vary", str(rooms[0]), "-n", "2", "-o", str(out))
    assert (
        code == 2
        and len(err.strip().splitlines()) == 1
        and "at least 2 example scenes, got 1" in err
    )
    assert not out.exists() or not any(out.iterdir())


def test_help_has_examples(capsys):
    for command in ("match", "augment", "vary"):
        with pytest.raises(SystemExit) as exit_info:
            main([command, "--help"])
        out = capsys.readouterr().out
        assert exit_info.value.code == 0 and f"examples:\n  scenewright {command} " in out
