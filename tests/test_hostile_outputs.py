"""Commands that write several files, and the outputs later commands read back, under
unlucky or hostile conditions: a set of files appears whole or not at all, a killed
run's scratch is cleared by the next, a context fitted to other rules is refused, a
resumed dataset redoes a damaged scene, every count option is bounded, and a plan
folder is read under the rule sets' folder rules."""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

import pytest

from scenewright.cli import main
from scenewright.core.atomic import OutputError, scratch_directory, staged_files
from scenewright.generator.layout.learned_term import LearnedContext, read_context

ROOT = Path(__file__).resolve().parents[1]
DESKS = ROOT / "examples" / "sets" / "desks"


def dead_pid() -> int:
    process = subprocess.Popen([sys.executable, "-c", "pass"])
    process.wait()
    return process.pid


def refused(capsys, *argv: str) -> str:
    assert main(list(argv)) == 2
    captured = capsys.readouterr()
    lines = (captured.out + captured.err).strip().splitlines()
    assert len(lines) == 1 and "Traceback" not in lines[0] and "--debug" not in lines[0], lines
    return lines[0]


# -- staged sets of files -------------------------------------------------------------


def test_a_staged_set_appears_whole(tmp_path):
    (tmp_path / "a.txt").write_text("old a")
    with staged_files() as staged:
        staged.write(tmp_path / "a.txt", "new a")
        staged.write(tmp_path / "sub" / "b.txt", b"new b")
        assert (tmp_path / "a.txt").read_text() == "old a"
        assert not (tmp_path / "sub" / "b.txt").exists()
    assert (tmp_path / "a.txt").read_text() == "new a"
    assert (tmp_path / "sub" / "b.txt").read_text() == "new b"
    assert sorted(p.name for p in tmp_path.rglob("*")) == ["a.txt", "b.txt", "sub"]


def test_a_failed_set_leaves_everything_as_it_was(tmp_path):
    (tmp_path / "a.txt").write_text("old a")
    (tmp_path / "c.txt").mkdir()  # a folder where the last file goes
    with pytest.raises(OutputError, match="c.txt: it is a directory"):
        with staged_files() as staged:
            staged.write(tmp_path / "a.txt", "new a")
            staged.write(tmp_path / "new" / "b.txt", "new b")
            staged.write(tmp_path / "c.txt", "c")
    assert (tmp_path / "a.txt").read_text() == "old a"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a.txt", "c.txt"]


def test_a_check_after_the_commit_that_fails_puts_the_old_files_back(tmp_path):
    (tmp_path / "a.txt").write_text("old a")
    with pytest.raises(ValueError):
        with staged_files() as staged:
            staged.write(tmp_path / "a.txt", "new a")
            staged.write(tmp_path / "b.txt", "new b")
            staged.commit()
            assert (tmp_path / "a.txt").read_text() == "new a"
            raise ValueError("the check failed")
    assert (tmp_path / "a.txt").read_text() == "old a"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a.txt"]


def test_partials_of_a_killed_writer_are_removed_by_the_next(tmp_path):
    left = tmp_path / f".a.txt.{dead_pid()}-x1y2.partial"
    left.write_text("half")
    with staged_files() as staged:
        staged.write(tmp_path / "a.txt", "a")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a.txt"]


def test_the_scratch_folder_of_a_killed_run_is_removed_by_the_next(tmp_path, monkeypatch):
    monkeypatch.setattr(tempfile, "tempdir", str(tmp_path))
    killed = tmp_path / f".scenewright-learn.{dead_pid()}-abcd.partial"
    (killed / "x").mkdir(parents=True)
    alive = tmp_path / f".scenewright-learn.{os.getppid()}-abcd.partial"
    alive.mkdir()
    with scratch_directory("learn") as folder:
        assert folder.is_dir() and not killed.exists() and alive.exists()
    assert not folder.exists()


@pytest.mark.slow
def test_learn_writes_nothing_when_its_context_cannot_be_written(tmp_path, capsys):
    out = tmp_path / "out"
    (out / "d.context.json").mkdir(parents=True)
    line = refused(
        capsys,
        "learn",
        "-q",
        str(DESKS),
        "-o",
        str(out / "d.rules"),
        "--report",
        str(out / "learn.json"),
        "--check",
        "0",
        "--rounds",
        "0",
        "--layouts",
        "2",
    )
    assert "d.context.json: it is a directory" in line
    assert sorted(p.name for p in out.iterdir()) == ["d.context.json"]


# -- a context knows its rules --------------------------------------------------------


def rules_with_context(tmp_path: Path) -> Path:
    rules = tmp_path / "b.rules"
    shutil.copy(ROOT / "grammar_rules" / "desk.rules", rules)
    context = LearnedContext(()).for_rules(rules.read_text(encoding="utf-8"))
    (tmp_path / "b.context.json").write_text(context.to_json())
    return rules


def test_a_context_records_its_rules_and_is_used_with_them(tmp_path, capsys):
    rules = rules_with_context(tmp_path)
    assert read_context(str(tmp_path / "b.context.json")).rules_digest is not None
    assert main(["generate", str(rules), "--no-render", "-o", str(tmp_path / "o")]) in (0, 1)
    assert "context: " in capsys.readouterr().out


def test_a_context_of_other_rules_is_refused(tmp_path, capsys):
    rules = rules_with_context(tmp_path)
    rules.write_text(rules.read_text() + "\n# changed\n")
    line = refused(capsys, "generate", str(rules), "--no-render", "-o", str(tmp_path / "o"))
    assert "fitted to another version of" in line and "--no-context" in line
    assert not (tmp_path / "o").exists()
    line = refused(
        capsys, "dataset", str(rules), "-n", "1", "--no-images", "-o", str(tmp_path / "d")
    )
    assert "fitted to another version of" in line
    assert main(
        ["generate", str(rules), "--no-context", "--no-render", "-o", str(tmp_path / "o")]
    ) in (0, 1)


def test_a_context_with_an_unknown_relation_label_is_refused(tmp_path, capsys):
    rules = rules_with_context(tmp_path)
    document = {
        "format": "scenewright-context",
        "version": 1,
        "bins": 32,
        "yaw_bins": 32,
        "pairs": [],
    }
    document.update(json.loads((tmp_path / "b.context.json").read_text()))
    document["pairs"] = [
        {
            "source": "chair",
            "target": "desk",
            "labels": ["NoSuchLabel"],
            "bounds": [-1, -1, 1, 1],
            "position": [0.0] * (32 * 32 + 1),
            "yaw": [0.0] * 32,
        }
    ]
    (tmp_path / "b.context.json").write_text(json.dumps(document))
    line = refused(capsys, "generate", str(rules), "--no-render", "-o", str(tmp_path / "o"))
    assert "'NoSuchLabel' is not a relation label" in line


# -- a resumed dataset verifies ---------------------------------------------------------


def test_a_resumed_dataset_redoes_a_missing_or_cut_file(tmp_path, capsys):
    out = tmp_path / "d"
    argv = ["dataset", "desk", "-n", "3", "--no-images", "--workers", "1", "-q", "-o", str(out)]
    assert main(argv) == 0
    whole = {p: p.read_bytes() for p in (out / "scenes").iterdir()}
    whole.update({p: p.read_bytes() for p in (out / "texts").iterdir()})
    metadata = (out / "metadata.jsonl").read_bytes()
    (out / "texts" / "000001.txt").unlink()
    cut = out / "scenes" / "000002.json"
    cut.write_bytes(whole[cut][:50])
    capsys.readouterr()
    assert main(argv[:-2] + ["-o", str(out)]) == 0
    assert all(p.read_bytes() == data for p, data in whole.items())
    assert (out / "metadata.jsonl").read_bytes() == metadata


# -- bounds ---------------------------------------------------------------------------


@pytest.mark.parametrize(
    "argv, bound",
    [
        (["vary", "a.json", "b.json", "-n", "1000000000", "-o", "v"], "at most 10000"),
        (["vary", "a.json", "b.json", "--operations", "5000", "-o", "v"], "at most 100"),
        (["dataset", "desk", "-n", "10000000000000", "-o", "d"], "at most 1000000000000"),
        (["dataset", "desk", "-n", "2", "--captions", "100000", "-o", "d"], "at most 100,"),
        (["dataset", "desk", "-n", "2", "--views", "1000", "-o", "d"], "at most 100,"),
        (["learn", "x", "--check", "10000000", "-o", "l.rules"], "at most 10000"),
        (["complete", "--room", "1000x1000", "--with", "bed", "-o", "c"], "between 0.5 and 100 m"),
    ],
)
def test_count_and_size_options_are_bounded(tmp_path, capsys, monkeypatch, argv, bound):
    monkeypatch.chdir(tmp_path)
    line = refused(capsys, *argv)
    assert bound in line.replace("(the bounds", ",(the bounds") or bound in line
    assert list(tmp_path.iterdir()) == []


def test_a_room_of_a_thousand_corners_is_refused_at_once(tmp_path, capsys):
    import math

    corners = " ".join(
        f"{10 * math.cos(k * math.tau / 1000):.4f},{10 * math.sin(k * math.tau / 1000):.4f}"
        for k in range(1000)
    )
    line = refused(
        capsys, "complete", "--room", corners, "--with", "bed", "-o", str(tmp_path / "c")
    )
    assert "at most 64" in line and len(line) < 300


# -- plan folders ------------------------------------------------------------------------


def test_a_plan_linking_outside_its_folder_is_not_read(tmp_path, capsys):
    secret = tmp_path / "secret.json"
    secret.write_text(json.dumps({"id": "SECRET-VALUE-" + "s" * 300}))
    plans = tmp_path / "plans" / "bedroom"
    plans.mkdir(parents=True)
    (plans / "a.json").symlink_to(secret)
    line = refused(
        capsys, "plans", "build", str(tmp_path / "plans"), "-o", str(tmp_path / "m.json")
    )
    assert "outside the plan set's folder" in line and "SECRET-VALUE" not in line
    assert not (tmp_path / "m.json").exists()


def test_a_link_loop_in_the_allowed_paths_is_one_line(tmp_path, capsys, monkeypatch):
    (tmp_path / "loop").symlink_to(tmp_path / "loop")
    shutil.copy(ROOT / "grammar_rules" / "desk.rules", tmp_path / "d.rules")
    line = refused(
        capsys, "validate", str(tmp_path / "d.rules"), "--allow-outside", str(tmp_path / "loop")
    )
    assert "loop of symbolic links" in line
    monkeypatch.setenv("SCENEWRIGHT_ALLOW_OUTSIDE", str(tmp_path / "loop"))
    line = refused(
        capsys, "generate", str(tmp_path / "d.rules"), "--no-render", "-o", str(tmp_path / "o")
    )
    assert "loop of symbolic links" in line


CAMP = """\
scene camp { extent 20 x 20  start S }
object tent { noun "tent" size 2 x 1.5 x 2 mesh "models/tent.obj" }
object fire { noun "fire pit" size 1 x 0.3 x 1 }
S -> { 1..3 tent; fire }
"""


def test_fit_into_another_folder_of_a_rule_set_with_meshes(tmp_path, capsys):
    camp = tmp_path / "camp"
    (camp / "models").mkdir(parents=True)
    (camp / "models" / "tent.obj").write_text(
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 2 4\nf 1 3 4\nf 2 3 4\n"
    )
    (camp / "camp.rules").write_text(CAMP)
    examples = []
    for seed in (1, 2):
        out = tmp_path / f"ex{seed}"
        assert (
            main(
                [
                    "generate",
                    str(camp / "camp.rules"),
                    "--seed",
                    str(seed),
                    "--no-render",
                    "-q",
                    "-o",
                    str(out),
                ]
            )
            == 0
        )
        examples.append(str(out))
    line = refused(
        capsys,
        "fit",
        str(camp / "camp.rules"),
        *examples,
        "-o",
        str(tmp_path / "other" / "f.rules"),
    )
    assert "names models/tent.obj" in line and "copy models/tent.obj" in line
    assert list((tmp_path / "other").iterdir()) == []  # the folder checked writable, no file
    # beside the rule set, or with the mesh copied, it works; the report goes with the set
    shutil.copytree(camp / "models", tmp_path / "other" / "models")
    argv = [
        "fit",
        str(camp / "camp.rules"),
        *examples,
        "-q",
        "-o",
        str(tmp_path / "other" / "f.rules"),
    ]
    assert main([*argv, "--report", str(tmp_path / "other" / "fit.json")]) == 0
    assert sorted(p.name for p in (tmp_path / "other").iterdir()) == [
        "f.rules",
        "fit.json",
        "models",
    ]


def test_a_failed_set_puts_back_a_link_it_replaced(tmp_path):
    (tmp_path / "real.txt").write_text("real")
    (tmp_path / "a.txt").symlink_to("real.txt")
    with pytest.raises(ValueError):
        with staged_files() as staged:
            staged.write(tmp_path / "a.txt", "new a")
            staged.commit()
            raise ValueError("the check failed")
    assert (tmp_path / "a.txt").is_symlink() and (tmp_path / "a.txt").read_text() == "real"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a.txt", "real.txt"]


def test_a_huge_argument_is_shortened_in_the_error_but_a_long_path_is_kept(tmp_path, capsys):
    """An error line does not repeat a pasted 100,000-character argument, and still names
    a file by its whole path, however deep it lies."""
    from scenewright.cli import main

    huge = "x" * 100_000
    assert main(["describe", huge]) == 2
    line = capsys.readouterr().err.strip()
    assert len(line) < 500 and "(100000 characters)" in line
    deep = tmp_path.joinpath(*["folder"] * 20)
    deep.mkdir(parents=True)
    missing = deep / "scene.json"
    assert main(["describe", str(missing)]) == 2
    assert str(missing) in capsys.readouterr().err


KILLED_DURING_RENAMES = """
import os, sys
from scenewright.core import atomic

replace, done = os.replace, []


def replace_then_die(source, target):
    replace(source, target)
    if not str(target).endswith("-journal.partial"):  # a file of the set, not the journal
        done.append(target)
    if len(done) == 1:
        os._exit(9)  # as a kill -9 after the set's first rename


atomic.os.replace = replace_then_die
with atomic.staged_files() as staged:
    for name in ("a.rules", "a.context.json", "a.report.json"):
        staged.write(os.path.join(sys.argv[1], name), "new " + name)
"""


def test_a_set_killed_during_its_renames_is_finished_by_the_next_staged_write(tmp_path):
    """Between the first and the last rename of a staged set the old and the new files
    stand side by side; the journal the renames leave lets the next run finish them."""
    names = ("a.rules", "a.context.json", "a.report.json")
    for name in names:
        (tmp_path / name).write_text("old " + name)
    done = subprocess.run([sys.executable, "-c", KILLED_DURING_RENAMES, str(tmp_path)])
    assert done.returncode == 9
    texts = {name: (tmp_path / name).read_text() for name in names}
    assert texts == {"a.rules": "new a.rules", **{n: "old " + n for n in names[1:]}}
    assert any(p.name.endswith("-journal.partial") for p in tmp_path.iterdir())
    with staged_files() as staged:  # the next run writes its own file into the folder
        staged.write(tmp_path / "other.txt", "next run")
    assert {name: (tmp_path / name).read_text() for name in names} == {
        name: "new " + name for name in names
    }
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted([*names, "other.txt"])
