"""The command line: every command's happy path, and bad input exiting 2 with one line.

Commands run in-process through ``main(argv)`` (fast); one test runs the installed
console script to check exit codes and that no traceback reaches the user.
"""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

from scenewright import __version__
from scenewright.cli import main
from scenewright.scene import LayoutStats, Relation, Scene, SceneObject, ScenePath

SCENEWRIGHT = Path(sys.executable).with_name("scenewright")


def run(capsys, *argv: str) -> tuple[int, str, str]:
    code = main(list(argv))
    captured = capsys.readouterr()
    return code, captured.out, captured.err


def assert_one_line_error(err: str, *fragments: str) -> None:
    lines = err.strip().splitlines()
    assert len(lines) == 1, err
    assert lines[0].startswith("scenewright: error: ")
    assert "Traceback" not in err
    for fragment in fragments:
        assert fragment in lines[0]


@pytest.fixture
def scene_file(tmp_path) -> Path:
    """A small hand-built scene.json: a table with a pot on it beside a road."""
    scene = Scene(
        rules="test",
        seed=1,
        extent=[20.0, 20.0],
        objects=[
            SceneObject("table_1", "table", "object", "table", None, None, None, [0.0, 0.0, 2.0], 0.0, [1.6, 0.8, 0.9], shape="box", order=1),
            SceneObject("pot_1", "pot", "object", "pot", None, None, None, [0.0, 0.8, 2.0], 0.0, [0.4, 0.3, 0.4], shape="box", order=2),
        ],
        paths=[ScenePath("road_1", "road", "road", None, None, [[-10.0, 0.0], [10.0, 0.0]], 3.0, order=0)],
        relations=[Relation("pot_1", "table_1", "OnTopOf"), Relation("table_1", "road_1", "NextTo")],
        layout=LayoutStats(energy=0.0, steps=10, acceptance=0.5, ok=True),
        version=__version__,
    )  # fmt: skip
    path = tmp_path / "scene.json"
    path.write_text(scene.to_json(reproducible=True))
    return path


# -- general conventions ----------------------------------------------------------------


def test_version_and_help_with_examples(capsys):
    with pytest.raises(SystemExit) as exit_info:
        main(["--version"])
    assert exit_info.value.code == 0 and capsys.readouterr().out.strip() == f"scenewright {__version__}"
    for command in ("generate", "dataset", "validate", "expand", "describe", "render", "export", "schema", "list"):
        with pytest.raises(SystemExit) as exit_info:
            main([command, "--help"])
        out = capsys.readouterr().out
        assert exit_info.value.code == 0
        assert "examples:\n  scenewright " + command in out


@pytest.mark.parametrize(
    "argv, fragment",
    [
        (["nonsense"], "invalid choice: 'nonsense'"),
        ([], "required: COMMAND"),
        (["generate", "village", "--size", "640"], "expected WIDTHxHEIGHT"),
        (["generate", "village", "--seed", "-1"], "must be between 0"),
        (["generate", "village", "--style", "long"], "invalid choice: 'long'"),
        (["dataset", "village", "-o", "x"], "required: -n/--count"),
        (["dataset", "village", "-n", "0", "-o", "x"], "must be at least 1"),
        (["dataset", "village", "-n", "4", "-o", "x", "--workers", "zero"], "expected a whole number"),
    ],
)
def test_bad_options_exit_2_on_one_line(capsys, argv, fragment):
    code, _, err = run(capsys, *argv)
    assert code == 2
    assert_one_line_error(err, fragment)


def test_console_script_exit_codes_and_no_traceback(tmp_path):
    missing = subprocess.run(
        [str(SCENEWRIGHT), "describe", str(tmp_path / "nowhere.json")], capture_output=True, text=True
    )
    assert missing.returncode == 2
    assert_one_line_error(missing.stderr, "nowhere.json: cannot read: No such file")
    debug = subprocess.run(
        [str(SCENEWRIGHT), "describe", str(tmp_path / "nowhere.json"), "--debug"], capture_output=True, text=True
    )
    assert debug.returncode == 2 and "Traceback" in debug.stderr


# -- validate, expand, list, schema -----------------------------------------------------

BAD_RULES = "scene village {\n  extent 10 x 10\n  start Village\n}\nVillage -> tabel\n"


def test_validate_shipped_rules_ok(capsys):
    code, out, _ = run(capsys, "validate", *(str(p) for p in Path("grammar_rules").glob("*.rules")))
    assert code == 0
    assert sorted(out.splitlines()) == [f"grammar_rules/{n}.rules: ok" for n in ("bedroom", "desk", "village")]


def test_validate_reports_located_errors_and_missing_files(capsys, tmp_path):
    bad = tmp_path / "bad.rules"
    bad.write_text(BAD_RULES)
    code, out, _ = run(capsys, "validate", str(bad), str(tmp_path / "missing.rules"))
    assert code == 2
    assert f"{bad}:" in out and "error:" in out and "^" in out
    assert f"{tmp_path / 'missing.rules'}: error: no such file" in out


def test_validate_scene_json(capsys, scene_file, tmp_path):
    broken = tmp_path / "broken.json"
    broken.write_text(json.dumps({**json.loads(scene_file.read_text()), "seed": "seven"}))
    code, out, _ = run(capsys, "validate", str(scene_file), str(broken))
    assert code == 2
    lines = out.splitlines()
    assert lines[0] == f"{scene_file}: ok"
    assert lines[1].startswith(f"{broken}: error: ") and "$.seed" in lines[1]


def test_bad_rules_print_the_located_excerpt_and_exit_2(capsys, tmp_path):
    bad = tmp_path / "bad.rules"
    bad.write_text(BAD_RULES)
    code, out, err = run(capsys, "generate", str(bad), "-o", str(tmp_path / "out"))
    assert code == 2 and out == ""
    assert err.startswith(f"{bad}:5:") and "^" in err and "Traceback" not in err
    assert not (tmp_path / "out" / "scene.json").exists()


def test_expand_json_and_dot(capsys, tmp_path):
    code, out, _ = run(capsys, "expand", "village", "--seed", "3")
    graph = json.loads(out)
    assert code == 0 and graph["params"]["name"] == "village" and graph["nodes"] and graph["edges"]
    _, again, _ = run(capsys, "expand", "village", "--seed", "3")
    assert again == out
    code, _, _ = run(capsys, "expand", "village", "--seed", "3", "--format", "dot", "-o", str(tmp_path / "g.dot"))
    assert code == 0 and (tmp_path / "g.dot").read_text().startswith("digraph")


def test_list_and_schema(capsys):
    code, out, _ = run(capsys, "list")
    assert code == 0
    assert "village  (60 x 60 m;" in out and "windmill" in out and "desk  (" in out
    code, out, _ = run(capsys, "schema")
    assert code == 0 and "layout" in json.loads(out)["properties"]


# -- commands on a scene.json -----------------------------------------------------------


def test_bad_scene_json_exit_2(capsys, tmp_path, scene_file):
    not_json = tmp_path / "not.json"
    not_json.write_text("{ nope")
    code, _, err = run(capsys, "export", str(not_json), "-o", str(tmp_path / "x.glb"))
    assert code == 2
    assert_one_line_error(err, "not.json: not JSON")
    wrong = tmp_path / "wrong.json"
    wrong.write_text(json.dumps({"objects": []}))
    code, _, err = run(capsys, "render", str(wrong), "-o", str(tmp_path / "p.png"))
    assert code == 2
    assert_one_line_error(err, "wrong.json: ")


def test_export_and_unwritable_output(capsys, scene_file, tmp_path):
    code, out, _ = run(capsys, "export", str(scene_file), "-o", str(tmp_path / "scene.glb"))
    assert code == 0 and (tmp_path / "scene.glb").read_bytes()[:4] == b"glTF"
    code, _, err = run(capsys, "export", str(scene_file), "-o", str(scene_file / "scene.glb"))
    assert code == 2
    assert_one_line_error(err, "cannot write to", "not a directory")


def test_render_writes_preview_and_ground_truth(capsys, scene_file, tmp_path):
    code, out, _ = run(capsys, "render", str(scene_file), "-o", str(tmp_path / "top.png"), "--size", "64x48", "--view", "top")
    assert code == 0
    assert {p.name for p in tmp_path.glob("top*")} == {"top.png", "top_depth.png", "top_seg.png", "top_ids.json"}
    from PIL import Image

    assert Image.open(tmp_path / "top.png").size == (64, 48)
