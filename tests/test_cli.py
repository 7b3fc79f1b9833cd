"""The command line: every command's happy path, and bad input exiting 2 with one line.

Commands run in-process through ``main(argv)`` (fast); one test runs the installed
console script to check exit codes and that no traceback reaches the user.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from scenewright import __version__
from scenewright.cli import main, set_process_defaults
from scenewright.core.scene import LayoutStats, Relation, Scene, SceneObject, ScenePath
from scenewright.generator.rules import shipped_rule_sets

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
            SceneObject(
                "table_1",
                "table",
                "object",
                "table",
                None,
                None,
                None,
                [0.0, 0.0, 2.0],
                0.0,
                [1.6, 0.8, 0.9],
                shape="box",
                order=1,
            ),
            SceneObject(
                "pot_1",
                "pot",
                "object",
                "pot",
                None,
                None,
                None,
                [0.0, 0.8, 2.0],
                0.0,
                [0.4, 0.3, 0.4],
                shape="box",
                order=2,
            ),
        ],
        paths=[
            ScenePath(
                "road_1", "road", "road", None, None, [[-10.0, 0.0], [10.0, 0.0]], 3.0, order=0
            )
        ],
        relations=[
            Relation("pot_1", "table_1", "OnTopOf", 0.0, True),
            Relation("table_1", "road_1", "NextTo", -0.01, True),
        ],
        layout=LayoutStats(energy=0.0, steps=10, acceptance=0.5, ok=True),
        version=__version__,
    )
    path = tmp_path / "scene.json"
    path.write_text(scene.to_json(reproducible=True))
    return path


# -- general conventions ----------------------------------------------------------------


def test_version_and_help_with_examples(capsys):
    with pytest.raises(SystemExit) as exit_info:
        main(["--version"])
    assert (
        exit_info.value.code == 0
        and capsys.readouterr().out.strip() == f"scenewright {__version__}"
    )
    for command in (
        "generate",
        "dataset",
        "validate",
        "expand",
        "describe",
        "render",
        "export",
        "schema",
        "list",
    ):
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
        (
            ["dataset", "village", "-n", "4", "-o", "x", "--workers", "zero"],
            "expected a whole number",
        ),
        (["validate"], "required: FILE"),
        (["render", "scene.json", "--view", "side"], "invalid choice: 'side'"),
    ],
)
def test_bad_options_exit_2_on_one_line(capsys, argv, fragment):
    code, _, err = run(capsys, *argv)
    assert code == 2
    assert_one_line_error(err, fragment)


def test_console_script_exit_codes_and_no_traceback(tmp_path):
    missing = subprocess.run(
        [str(SCENEWRIGHT), "describe", str(tmp_path / "nowhere.json")],
        capture_output=True,
        text=True,
    )
    assert missing.returncode == 2
    assert_one_line_error(missing.stderr, "nowhere.json: cannot read: No such file")
    debug = subprocess.run(
        [str(SCENEWRIGHT), "describe", str(tmp_path / "nowhere.json"), "--debug"],
        capture_output=True,
        text=True,
    )
    assert debug.returncode == 2 and "Traceback" in debug.stderr


EXITING = """
import atexit, sys, threading, time
from scenewright.cli import exit_now
atexit.register(lambda: print("at exit ran"))
sys.stdout.write("unflushed ")
if sys.argv[1] == "thread":
    threading.Thread(target=lambda: (time.sleep(0.3), print("thread finished"))).start()
exit_now(int(sys.argv[2]))
"""


@pytest.mark.parametrize("thread", ["none", "thread"])
def test_the_command_exits_with_its_code_after_its_exit_functions_and_threads(thread):
    """The console command ends without the interpreter's teardown, but only once the
    exit functions have run and the output is flushed; a running thread is waited for."""
    done = subprocess.run(
        [sys.executable, "-c", EXITING, thread, "3"], capture_output=True, text=True
    )
    assert done.returncode == 3
    assert done.stdout.startswith("unflushed ") and "at exit ran" in done.stdout
    assert ("thread finished" in done.stdout) == (thread == "thread")
    assert done.stderr == ""


def test_the_command_runs_openblas_on_one_thread_unless_the_user_says(monkeypatch):
    monkeypatch.delenv("OPENBLAS_NUM_THREADS", raising=False)
    set_process_defaults()
    assert os.environ["OPENBLAS_NUM_THREADS"] == "1"
    monkeypatch.setenv("OPENBLAS_NUM_THREADS", "4")
    set_process_defaults()
    assert os.environ["OPENBLAS_NUM_THREADS"] == "4"


# -- validate, expand, list, schema -----------------------------------------------------

BAD_RULES = "scene village {\n  extent 10 x 10\n  start Village\n}\nVillage -> tabel\n"


def test_validate_shipped_rules_ok(capsys):
    code, out, _ = run(capsys, "validate", *(str(p) for p in Path("grammar_rules").glob("*.rules")))
    assert code == 0
    # the house plans beside the rule sets are validated as plans
    from scenewright.house import shipped_plans

    assert sorted(out.splitlines()) == [
        f"grammar_rules/{n}.rules: ok" for n in sorted([*shipped_rule_sets(), *shipped_plans()])
    ]


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


def test_validate_example_scenes_as_learn_reads_them(capsys, scene_file, tmp_path):
    desks = sorted((Path(__file__).parents[1] / "examples" / "sets" / "desks").glob("*.json"))[:2]
    broken = tmp_path / "broken.json"
    document = json.loads(desks[0].read_text())
    document["objects"][0]["position"] = [40, 0, 0]
    broken.write_text(json.dumps(document))
    code, out, _ = run(capsys, "validate", *map(str, desks), str(broken), str(scene_file))
    assert code == 2
    lines = out.splitlines()
    assert (
        lines[0].startswith(f"{desks[0]}: ok (hand-written example: ") and "in a room)" in lines[0]
    )
    assert (
        lines[2].startswith(f"{broken}: error: $.objects[0].position")
        and "outside the room" in lines[2]
    )
    assert lines[3] == f"{scene_file}: ok"  # a scene.json is still checked against its schema


def test_bad_rules_print_the_located_excerpt_and_exit_2(capsys, tmp_path):
    bad = tmp_path / "bad.rules"
    bad.write_text(BAD_RULES)
    code, out, err = run(capsys, "generate", str(bad), "-o", str(tmp_path / "out"))
    assert code == 2 and out == ""
    assert err.startswith(f"{bad}:5:") and "^" in err and "Traceback" not in err
    assert not (tmp_path / "out" / "scene.json").exists()


def test_missing_rules_file_exit_2_on_one_line(capsys):
    code, out, err = run(capsys, "expand", "nowhere.rules")
    assert code == 2 and out == ""
    assert err.strip() == (
        "nowhere.rules:1:1: error: no rules file 'nowhere.rules' "
        f"(and no shipped rule set of that name: {', '.join(shipped_rule_sets())})"
    )


def test_expand_json_and_dot(capsys, tmp_path):
    code, out, _ = run(capsys, "expand", "village", "--seed", "3")
    graph = json.loads(out)
    assert code == 0 and graph["params"]["name"] == "village" and graph["nodes"] and graph["edges"]
    _, again, _ = run(capsys, "expand", "village", "--seed", "3")
    assert again == out
    code, _, _ = run(
        capsys, "expand", "village", "--seed", "3", "--format", "dot", "-o", str(tmp_path / "g.dot")
    )
    assert code == 0 and (tmp_path / "g.dot").read_text().startswith("digraph")


def test_list_and_schema(capsys):
    code, out, _ = run(capsys, "list")
    assert code == 0
    assert "village  (60 x 60 m;" in out and "windmill" in out and "desk  (" in out
    # A room set lists what it makes, not the whole shared indoor catalog.
    bathroom = out[out.index("bathroom  (") : out.index("bedroom  (")]
    assert (
        "makes 7 of its catalog's 46 object types" in bathroom
        and "toilet" in bathroom
        and "piano" not in bathroom
    )
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
    code, out, _ = run(
        capsys,
        "render",
        str(scene_file),
        "-o",
        str(tmp_path / "top.png"),
        "--size",
        "64x48",
        "--view",
        "top",
        "--normals",
    )
    assert code == 0
    assert {p.name for p in tmp_path.glob("top*")} == {
        "top.png",
        "top_depth.png",
        "top_depth.npy",
        "top_depth.json",
        "top_seg.png",
        "top_ids.json",
        "top_normals.png",
        "top_3d.json",
    }
    from PIL import Image

    assert Image.open(tmp_path / "top.png").size == (64, 48)
    truth = json.loads((tmp_path / "top_3d.json").read_text())
    assert truth["camera"]["model"] == "orthographic" and len(truth["camera"]["K"]) == 3
    assert {entry["id"] for entry in truth["objects"]} <= set(
        json.loads((tmp_path / "top_ids.json").read_text()).values()
    )


# -- generate -----------------------------------------------------------------------------

CLASH_RULES = """\
scene clash {
    extent 10 x 10
    start Clash
}
object box { noun "box" size 1 x 1 x 1 shape box colour #888888 }
Clash -> {
    box as a
    box NextToNorth a NextToSouth a
}
"""


def test_generate_writes_every_file_reproducibly(capsys, tmp_path):
    from scenewright.scene_folder import SCENE_FILES

    outputs = []
    for name in ("first", "second"):
        code, out, err = run(
            capsys, "generate", "desk", "--seed", "2", "--size", "64x48", "-o", str(tmp_path / name)
        )
        assert code == 0, err
        outputs.append(tmp_path / name)
    assert sorted(p.name for p in outputs[0].iterdir()) == sorted(SCENE_FILES)
    lines = out.splitlines()
    assert lines[0].startswith(f"wrote {tmp_path / 'second'}/: ") and lines[1].startswith("ok: ")
    assert "relations satisfied" in lines[1] and "energy" in lines[1]
    for name in ("scene.json", "description.txt", "preview.png", "preview_seg.png", "scene.glb"):
        assert (outputs[0] / name).read_bytes() == (outputs[1] / name).read_bytes(), name
    scene = json.loads((outputs[0] / "scene.json").read_text())
    assert (
        scene["seed"] == 2 and scene["rules"] == "desk" and scene["render"]["camera"]["width"] == 64
    )
    assert set(json.loads((outputs[0] / "timings.json").read_text())) >= {
        "expand",
        "layout",
        "describe",
        "render",
    }


def test_no_render_drops_stale_previews_and_quiet_prints_nothing(capsys, tmp_path):
    run(capsys, "generate", "desk", "--size", "32x32", "-o", str(tmp_path))
    code, out, _ = run(
        capsys,
        "generate",
        "desk",
        "--no-render",
        "--quiet",
        "-o",
        str(tmp_path),
        "--style",
        "short",
    )
    assert code == 0 and out == ""
    assert not list(tmp_path.glob("preview*")) and (tmp_path / "scene.glb").exists()
    assert json.loads((tmp_path / "scene.json").read_text())["description"]["style"] == "short"


@pytest.fixture
def quick_layout(monkeypatch):
    """The real sampler with a small step budget, so a hopeless layout gives up fast."""
    from scenewright.generator import layout
    from scenewright.generator.layout import LayoutParams

    real = layout.layout_scene
    monkeypatch.setattr(
        layout,
        "layout_scene",
        lambda graph, seed, **options: real(
            graph, seed, params=LayoutParams(steps=300, restarts=0), **options
        ),
    )


def test_failed_layout_keeps_files_and_exits_1(capsys, tmp_path, quick_layout):
    rules = tmp_path / "clash.rules"
    rules.write_text(CLASH_RULES)
    code, out, err = run(capsys, "generate", str(rules), "--no-render", "-o", str(tmp_path / "out"))
    assert code == 1
    assert "LAYOUT FAILED: 2 objects" in out
    assert_one_line_error(
        err, "the layout did not satisfy every constraint", "box_2 is not north of box_1"
    )
    assert json.loads((tmp_path / "out" / "scene.json").read_text())["layout"]["ok"] is False


def test_a_failing_stage_leaves_no_partial_outputs(capsys, tmp_path, monkeypatch):
    from scenewright import scene_folder
    from scenewright.core.errors import GenerationError

    def broken_export(scene, path):
        Path(path).write_bytes(b"half a file")
        raise GenerationError("the exporter broke")

    monkeypatch.setattr(scene_folder, "export", broken_export)
    code, _, err = run(capsys, "generate", "desk", "--size", "32x32", "-o", str(tmp_path / "out"))
    assert code == 1
    assert_one_line_error(err, "the exporter broke")
    assert list((tmp_path / "out").iterdir()) == []


def test_generate_into_a_file_path_is_bad_input(capsys, tmp_path):
    (tmp_path / "taken").write_text("")
    code, _, err = run(capsys, "generate", "desk", "-o", str(tmp_path / "taken"))
    assert code == 2
    assert_one_line_error(err, "cannot write to", "not a directory")


def test_dataset_into_a_file_path_is_bad_input(capsys, tmp_path):
    (tmp_path / "taken").write_text("")
    code, _, err = run(capsys, "dataset", "desk", "-n", "2", "-o", str(tmp_path / "taken" / "data"))
    assert code == 2
    assert_one_line_error(err, "cannot write the dataset to", "taken")


def test_describe_command(capsys, tmp_path):
    run(capsys, "generate", "desk", "--seed", "4", "--no-render", "-o", str(tmp_path))
    code, out, _ = run(capsys, "describe", str(tmp_path / "scene.json"))
    assert code == 0 and out.strip() == (tmp_path / "description.txt").read_text().strip()
    code, short, _ = run(
        capsys, "describe", str(tmp_path / "scene.json"), "--style", "short", "--variant", "1"
    )
    assert code == 0 and 0 < len(short) < len(out)


def test_validate_accepts_shipped_rule_set_names(capsys):
    code, out, _ = run(capsys, "validate", "desk", "village")
    assert code == 0 and out.splitlines() == ["desk: ok", "village: ok"]
    code, out, _ = run(capsys, "validate", "vilage")
    assert code == 2
    assert (
        out.strip()
        == f"vilage: error: no such file (nor a shipped rule set: {', '.join(shipped_rule_sets())})"
    )


STALL = Path(__file__).parent / "rules" / "stall" / "stall.rules"


def test_describe_uses_the_rule_sets_templates_unless_given_others(capsys, tmp_path):
    code, _, err = run(
        capsys, "generate", str(STALL), "--seed", "1", "--no-render", "-o", str(tmp_path / "out")
    )
    assert code == 0, err
    scene_json = tmp_path / "out" / "scene.json"
    assert json.loads(scene_json.read_text())["templates"] == str(
        STALL.parent.resolve() / "templates"
    )
    code, out, _ = run(capsys, "describe", str(scene_json))
    assert code == 0 and out.startswith("At this stall the scene offers ")
    assert out.strip() == (tmp_path / "out" / "description.txt").read_text().strip()
    words = tmp_path / "words"
    words.mkdir()
    (words / "inventory.j2").write_text("Here {{ owner }} {{ verb }} {{ items | join_list }}.")
    code, out, _ = run(capsys, "describe", str(scene_json), "--templates", str(words))
    assert code == 0 and out.startswith("Here the scene consists of ")
    code, out, err = run(
        capsys, "describe", str(scene_json), "--templates", str(tmp_path / "nowhere")
    )
    assert code == 2 and out == ""
    assert_one_line_error(err, "description templates folder", "nowhere", "does not exist")


def test_generate_and_dataset_templates_option(capsys, tmp_path):
    words = tmp_path / "words"
    words.mkdir()
    (words / "caption.j2").write_text("A small {{ setting }}.")
    out_dir = tmp_path / "out"
    code, _, err = run(
        capsys,
        "generate",
        "desk",
        "--no-render",
        "--style",
        "short",
        "--templates",
        str(words),
        "-o",
        str(out_dir),
    )
    assert code == 0, err
    caption = (out_dir / "description.txt").read_text()
    assert caption.startswith("A small desk.")
    assert json.loads((out_dir / "scene.json").read_text())["templates"] == str(words.resolve())
    code, out, _ = run(capsys, "describe", str(out_dir / "scene.json"), "--style", "short")
    assert code == 0 and out == caption

    (words / "caption.j2").write_text("A {% if %} desk.")  # a syntax error
    for argv in (
        ["generate", "desk", "-o", str(tmp_path / "again")],
        ["dataset", "desk", "-n", "1", "-o", str(tmp_path / "data")],
    ):
        code, out, err = run(capsys, *argv, "--templates", str(words))
        assert code == 2 and out == ""
        assert_one_line_error(err, f"description template {words.resolve() / 'caption.j2'}:1: ")
        assert not (tmp_path / "again").exists() and not (tmp_path / "data").exists()

    (words / "caption.j2").write_text("A {{ settting }}.")  # compiles, fails when rendered
    code, out, err = run(
        capsys,
        "describe",
        str(out_dir / "scene.json"),
        "--style",
        "short",
        "--templates",
        str(words),
    )
    assert code == 2 and out == ""
    assert_one_line_error(
        err, f"description template {words.resolve() / 'caption.j2'}:1: 'settting' is undefined"
    )


def test_the_command_collects_garbage_less_often_and_the_library_leaves_the_collector():
    """The console command's process collects cyclic garbage at ``collector.THRESHOLDS``;
    importing and calling the library changes nothing."""
    probe = (
        "import atexit, gc, sys\n"
        "sys.argv = ['scenewright', 'list']\n"
        "from scenewright.cli import main, run\n"
        "main(['list'])\n"
        "atexit.register(lambda: print('after', gc.get_threshold()))\n"
        "print('before', gc.get_threshold())\n"
        "run()\n"
    )
    done = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    assert "before (700, 10, 10)" in done.stdout
    assert "after (20000, 20, 20)" in done.stdout
