"""Hostile inputs: what a rule set may read, special files, and inputs that would take
quadratic time (docs/security.md).

A hang or a memory blow-up is caught by running the command in a subprocess with a
timeout (and an address-space limit), so a regression fails the test instead of
stalling the suite.
"""

from __future__ import annotations

import json
import os
import resource
import subprocess
import sys
from pathlib import Path

import pytest
import trimesh

from scenewright.api import describe
from scenewright.cli import main
from scenewright.core.scene import Scene, SceneObject
from scenewright.describer import TemplateError
from scenewright.describer.english import plural_of
from scenewright.generator import check_rules, load_rules
from scenewright.generator.rules_check_catalog import MAX_NOUN_CHARS
from scenewright.generator.rules_errors import RulesError
from scenewright.generator.rules_scope import ALLOW_VARIABLE

SECRET = "hunter2-secret-line"
HEADER = 'scene s { start S }\nobject t { noun "t" }\nS -> { t }\n'
#: Far more than any of these commands needs, however slow the machine; a hang or a
#: quadratic parse takes minutes.
TIMEOUT = 60

needs_fifo = pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="named pipes need a POSIX system")


def run_cli(*args: str, cwd: Path, memory: int | None = None, env: dict | None = None):
    """The CLI in a child process, stopped after ``TIMEOUT`` s, with at most ``memory``
    bytes of address space when given."""

    def limit_memory() -> None:
        resource.setrlimit(resource.RLIMIT_AS, (memory, memory))

    return subprocess.run(
        [sys.executable, "-m", "scenewright.cli", *args],
        cwd=cwd,
        capture_output=True,
        text=True,
        timeout=TIMEOUT,
        preexec_fn=limit_memory if memory else None,
        env={**os.environ, **(env or {})},
    )


@pytest.fixture
def layout(tmp_path, monkeypatch):
    """A rule set's folder ``set/`` beside a folder ``outside/`` holding a secret."""
    monkeypatch.chdir(tmp_path)
    monkeypatch.delenv(ALLOW_VARIABLE, raising=False)
    (tmp_path / "set").mkdir()
    (tmp_path / "outside").mkdir()
    (tmp_path / "outside" / "secret.txt").write_text(SECRET + "\n")
    (tmp_path / "outside" / "lib.rules").write_text('object u { noun "u" }\n')
    return tmp_path


def errors(diagnostics) -> list[str]:
    return [str(d) for d in diagnostics if d.is_error]


# -- 3. a rule set reads only inside its own folder ------------------------------------


@pytest.mark.parametrize(
    "include", ["../outside/lib.rules", "{tmp}/outside/lib.rules", "link.rules"]
)
def test_includes_outside_the_rule_set_folder_are_refused(layout, include):
    (layout / "set" / "link.rules").symlink_to(layout / "outside" / "lib.rules")
    written = include.format(tmp=layout)
    (layout / "set" / "top.rules").write_text(f'include "{written}"\n' + HEADER)
    (diagnostic,) = check_rules("set/top.rules")
    assert diagnostic.location.line == 1 and diagnostic.location.column == 9
    assert diagnostic.message.startswith(
        f"included file '{written}' is outside the rule set's folder {layout / 'set'}"
    )
    assert "--allow-outside" in diagnostic.message and ALLOW_VARIABLE in diagnostic.message


def test_the_user_allows_more_by_argument_environment_or_option(layout, monkeypatch, capsys):
    (layout / "set" / "top.rules").write_text(
        'include "../outside/lib.rules"\n' + HEADER.replace("{ t }", "{ t; u }")
    )
    with pytest.raises(RulesError, match="outside the rule set's folder"):
        load_rules("set/top.rules")
    assert sorted(load_rules("set/top.rules", allow=[layout / "outside"]).catalog.entries) == [
        "t",
        "u",
    ]
    # a file may be allowed alone
    assert check_rules("set/top.rules", allow=["outside/lib.rules"]) == []
    assert main(["validate", "set/top.rules"]) == 2
    assert main(["validate", "set/top.rules", "--allow-outside", "outside"]) == 0
    assert main(["expand", "set/top.rules", "--allow-outside", "outside"]) == 0
    assert (
        main(
            [
                "generate",
                "set/top.rules",
                "--no-render",
                "-q",
                "-o",
                "out",
                "--allow-outside",
                "outside",
            ]
        )
        == 0
    )
    assert "outside the rule set's folder" in capsys.readouterr().out
    monkeypatch.setenv(ALLOW_VARIABLE, os.pathsep.join(["/nowhere", str(layout / "outside")]))
    assert check_rules("set/top.rules") == []


def test_a_file_that_is_not_rules_is_never_quoted(layout):
    (layout / "set" / "notes.txt").write_text(SECRET + "\n")
    (layout / "set" / "disguised.rules").symlink_to(layout / "set" / "notes.txt")
    for include, shown in (
        ("notes.txt", "set/notes.txt"),
        ("disguised.rules", "set/disguised.rules"),
    ):
        (layout / "set" / "top.rules").write_text(f'include "{include}"\n' + HEADER)
        (diagnostic,) = check_rules("set/top.rules")
        assert str(diagnostic) == (
            f"{shown}:1:1: error: '{shown}' is not a rules file: it does not parse as "
            "rules here (the text of a file not named *.rules is never shown)"
        )
    # the same when the user allows a file outside, or names it
    (layout / "set" / "top.rules").write_text('include "../outside/secret.txt"\n' + HEADER)
    (diagnostic,) = check_rules("set/top.rules", allow=[layout / "outside"])
    assert "is not a rules file" in str(diagnostic) and SECRET not in str(diagnostic)
    (diagnostic,) = check_rules("outside/secret.txt")
    assert "is not a rules file" in str(diagnostic) and SECRET not in str(diagnostic)


def test_rules_files_are_still_quoted(layout):
    (layout / "set" / "top.rules").write_text(HEADER + 'object v { nonu "v" }\n')
    (diagnostic,) = check_rules("set/top.rules")
    assert str(diagnostic).splitlines()[1].strip() == 'object v { nonu "v" }'


def make_box(path: Path) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    trimesh.creation.box().export(path)


def test_mesh_files_outside_the_rule_set_folder_are_refused(layout):
    make_box(layout / "outside" / "box.glb")
    (layout / "set" / "link.glb").symlink_to(layout / "outside" / "box.glb")
    for mesh in ("../outside/box.glb", "link.glb"):
        (layout / "set" / "top.rules").write_text(
            HEADER.replace('noun "t"', f'noun "t" mesh "{mesh}"')
        )
        (diagnostic,) = check_rules("set/top.rules")
        assert diagnostic.message.startswith(
            f"mesh file '{mesh}' is outside the rule set's folder {layout / 'set'}"
        )
        assert check_rules("set/top.rules", allow=[layout / "outside" / "box.glb"]) == []
    make_box(layout / "set" / "models" / "box.glb")
    (layout / "set" / "top.rules").write_text(
        HEADER.replace('noun "t"', 'noun "t" mesh "models/box.glb"')
    )
    assert check_rules("set/top.rules") == []


def scene_with_templates(folder: str) -> str:
    return HEADER.replace("start S", f'start S templates "{folder}"')


def test_templates_folder_must_lie_in_the_rule_set_folder(layout):
    (layout / "outside" / "words").mkdir()
    (layout / "set" / "linked_words").symlink_to(layout / "outside" / "words")
    for folder in ("../outside/words", "linked_words"):
        (layout / "set" / "top.rules").write_text(scene_with_templates(folder))
        (diagnostic,) = check_rules("set/top.rules")
        assert diagnostic.message.startswith(
            f"templates folder '{folder}' is outside the rule set's folder"
        )
        assert check_rules("set/top.rules", allow=[layout / "outside"]) == []


def test_a_template_that_links_outside_its_folder_is_refused(layout, capsys):
    words = layout / "set" / "words"
    words.mkdir()
    (words / "inventory.j2").symlink_to(layout / "outside" / "secret.txt")
    (layout / "set" / "top.rules").write_text(scene_with_templates("words"))
    (diagnostic,) = check_rules("set/top.rules")
    assert diagnostic.message == (
        f"template 'inventory.j2' of templates folder 'words' leads outside that "
        f"folder (to {layout / 'outside' / 'secret.txt'})"
    )
    # generate refuses it at the rules; describing a scene that names the folder, at the template
    assert main(["generate", "set/top.rules", "--no-render", "-o", "out"]) == 2
    assert not (layout / "out" / "description.txt").exists()
    scene = one_table_scene(templates=str(words))
    with pytest.raises(TemplateError, match="inventory.j2: it leads outside its folder") as refused:
        describe(scene)
    assert SECRET not in str(refused.value) and SECRET not in capsys.readouterr().err
    # a link that stays inside the folder is fine
    (words / "inventory.j2").unlink()
    (words / "own.j2").write_text("{{ owner }} holds {{ items | join_list }}.")
    (words / "inventory.j2").symlink_to(words / "own.j2")
    assert describe(scene).text == "The scene holds a table."


def test_templates_include_only_templates_of_their_folders(layout):
    (layout / "words").mkdir()
    (layout / "words" / "inventory.j2").write_text('{% include "../outside/secret.txt" %}')
    with pytest.raises(
        TemplateError, match=r"there is no template '../outside/secret.txt'"
    ) as refused:
        describe(one_table_scene(), templates=layout / "words")
    assert SECRET not in str(refused.value)


def test_templates_are_bounded_in_size(layout):
    words = layout / "words"
    words.mkdir()
    with open(words / "inventory.j2", "wb") as stream:
        stream.truncate(2 * 2**20)  # sparse: nothing is written
    scene = one_table_scene()
    with pytest.raises(
        TemplateError, match=r"inventory.j2: it is 2 MiB, more than the 1 MiB a template may hold"
    ):
        describe(scene, templates=words)


def scene_of(*nouns: str, templates: str | None = None) -> Scene:
    """A scene of one object for each noun, with no relations."""
    objects = [
        SceneObject(
            id=f"thing_{order + 1}",
            type="thing",
            kind="object",
            noun=noun,
            plural=None,
            parent=None,
            style=None,
            position=[0.0, 0.0, 0.0],
            yaw=0.0,
            size=[1.0, 1.0, 1.0],
            order=order,
        )
        for order, noun in enumerate(nouns)
    ]
    return Scene(
        rules="x",
        seed=1,
        extent=[10.0, 10.0],
        objects=objects,
        paths=[],
        relations=[],
        templates=templates,
    )


def one_table_scene(templates: str | None = None) -> Scene:
    return scene_of("table", templates=templates)


# -- 4. only regular files of bounded size ---------------------------------------------


@needs_fifo
@pytest.mark.parametrize(
    "command", [["validate"], ["expand"], ["generate", "--no-render", "-o", "out"]]
)
def test_a_fifo_include_does_not_hang(layout, command):
    os.mkfifo(layout / "set" / "pipe.rules")
    (layout / "set" / "top.rules").write_text('include "pipe.rules"\n' + HEADER)
    done = run_cli(command[0], "set/top.rules", *command[1:], cwd=layout)
    assert done.returncode == 2
    assert (
        "cannot read included file 'set/pipe.rules': it is not a regular file"
        in done.stdout + done.stderr
    )


@needs_fifo
def test_a_fifo_named_as_the_rules_file_or_a_template_does_not_hang(layout):
    os.mkfifo(layout / "set" / "pipe.rules")
    done = run_cli("expand", "set/pipe.rules", cwd=layout)
    assert (
        done.returncode == 2
        and "cannot read 'set/pipe.rules': it is not a regular file" in done.stderr
    )
    (layout / "words").mkdir()
    os.mkfifo(layout / "words" / "caption.j2")
    scene = one_table_scene()
    (layout / "scene.json").write_text(scene.to_json())
    done = run_cli("describe", "scene.json", "--style", "short", "--templates", "words", cwd=layout)
    assert done.returncode == 2 and "caption.j2: it is not a regular file" in done.stderr


@pytest.mark.slow
@pytest.mark.skipif(not Path("/dev/zero").exists(), reason="needs /dev/zero")
def test_dev_zero_is_never_read(layout):
    (layout / "set" / "zero.rules").symlink_to("/dev/zero")
    for include, allow in (("/dev/zero", "/dev"), ("zero.rules", "/dev")):
        (layout / "set" / "top.rules").write_text(f'include "{include}"\n' + HEADER)
        refused = run_cli("validate", "set/top.rules", cwd=layout, memory=2**30)
        assert refused.returncode == 2 and "outside the rule set's folder" in refused.stdout
        allowed = run_cli(
            "validate", "set/top.rules", "--allow-outside", allow, cwd=layout, memory=2**30
        )
        assert allowed.returncode == 2 and "it is not a regular file" in allowed.stdout


def test_rules_files_are_bounded_in_size(layout):
    with open(layout / "set" / "big.rules", "wb") as stream:
        stream.truncate(5 * 2**20)  # sparse: nothing is written
    (layout / "set" / "top.rules").write_text('include "big.rules"\n' + HEADER)
    (diagnostic,) = check_rules("set/top.rules")
    assert diagnostic.message == (
        "cannot read included file 'set/big.rules': it is 5 MiB, more than the 4 MiB "
        "a rules file may hold"
    )
    (diagnostic,) = check_rules("set/big.rules")
    assert (
        diagnostic.message
        == "cannot read 'set/big.rules': it is 5 MiB, more than the 4 MiB a rules file may hold"
    )


# -- 5. no quadratic inputs ---------------------------------------------------------------


def test_runs_of_comment_lines_parse_in_linear_time(tmp_path):
    path = tmp_path / "comments.rules"
    path.write_text(HEADER + "# comment\n" * 16_384)  # lines of ten characters
    timer = (
        "import sys, time\nfrom scenewright.generator import check_rules\nstart = time.perf_counter()\n"
        "found = check_rules(sys.argv[1])\nprint(time.perf_counter() - start, len(found))"
    )
    done = subprocess.run(
        [sys.executable, "-c", timer, str(path)], capture_output=True, text=True, timeout=TIMEOUT
    )
    seconds, found = done.stdout.split()
    assert found == "0"
    assert float(seconds) < 5  # about 0.1 s; quadratic, it was 98 s


@pytest.mark.parametrize(
    "gap", ["\n", "\n# one\n", "\n# one\n\n   # two\n  \n", "  # after\n# one\n"]
)
def test_comment_and_blank_lines_before_a_bar_still_continue_a_production(tmp_path, gap):
    path = tmp_path / "bars.rules"
    path.write_text(
        'scene s { start S }\nobject t { noun "t" }\nobject u { noun "u" }\n'
        f"S -> 2: {{ t }}{gap}   | 1: {{ u }}\n# trailing\n\n"
    )
    rules = load_rules(path)
    assert [alternative.weight for alternative in rules.productions["S"].alternatives] == [2.0, 1.0]


def test_nouns_are_bounded_in_length(tmp_path):
    path = tmp_path / "t.rules"
    path.write_text(
        HEADER.replace(
            'noun "t"', f'noun "{"n" * MAX_NOUN_CHARS}" plural "{"p" * (MAX_NOUN_CHARS + 1)}"'
        )
    )
    (diagnostic,) = check_rules(path)
    line = path.read_text().splitlines()[1]
    assert (diagnostic.location.line, diagnostic.location.column) == (
        2,
        line.index('plural "') + len("plural ") + 1,
    )
    assert diagnostic.message == (
        f"'plural' is {MAX_NOUN_CHARS + 1} characters long; it may have at most {MAX_NOUN_CHARS}"
    )


def test_a_long_noun_from_a_scene_json_is_described_in_well_under_a_second(tmp_path):
    noun = "x" * 100_000
    (tmp_path / "long.json").write_text(scene_of(noun, noun).to_json())
    (tmp_path / "short.json").write_text(scene_of("x", "x").to_json())
    # The short scene first: the timing leaves out imports and compiling the templates.
    timer = (
        "import json, sys, time\nfrom scenewright.core.scene import Scene\n"
        "from scenewright.api import describe\n"
        "short, long = (Scene.from_json(open(name).read()) for name in sys.argv[1:])\ndescribe(short)\n"
        "start = time.perf_counter()\ntext = describe(long).text\n"
        "print(json.dumps([time.perf_counter() - start, text]))"
    )
    done = subprocess.run(
        [sys.executable, "-c", timer, tmp_path / "short.json", tmp_path / "long.json"],
        capture_output=True,
        text=True,
        timeout=TIMEOUT,
    )
    seconds, text = json.loads(done.stdout)
    assert text == f"The scene consists of two {noun}s."
    assert seconds < 1  # about 0.02 s; inflected whole, it took minutes


def test_the_plural_of_a_long_phrase_inflects_its_last_word_only():
    head = "very " * 50
    assert plural_of(head + "big mouse") == head + "big mice"
    assert plural_of("y" * 300) == "y" * 300 + "s"
    assert (
        plural_of("sack of flour") == "sacks of flour"
    )  # short phrases: inflect's whole-phrase rules
