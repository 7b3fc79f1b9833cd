"""The bounds of ``scenewright.core.limits``: a number beyond one is refused at once, with
its location and the limit; work within them runs in bounded memory and time.

The runs that once exhausted memory or hung run the CLI in a subprocess with a time
limit and an address-space limit, so a regression fails the test instead of the machine.
"""

from __future__ import annotations

import json
import random
import resource
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from scenewright.cli import main
from scenewright.core import limits
from scenewright.core.errors import InputError
from scenewright.generator import check_rules
from scenewright.generator.layout.state import Grid
from scenewright.render.builders import BUILDERS
from scenewright.render.meshes import shaped_mesh

#: The address space a subprocess may use: enough for Python, numpy, trimesh and a
#: scene at the limits; far less than the gigabytes the unbounded runs took.
ADDRESS_SPACE = 2 * 1024**3
COLOUR = (0.6, 0.5, 0.4)


def run_bounded(tmp_path: Path, *argv: str, seconds: float = 60) -> subprocess.CompletedProcess:
    """``scenewright ARGV`` in a subprocess limited to ``seconds`` and ``ADDRESS_SPACE``."""

    def limit_memory() -> None:
        resource.setrlimit(resource.RLIMIT_AS, (ADDRESS_SPACE, ADDRESS_SPACE))

    return subprocess.run(
        [sys.executable, "-m", "scenewright.cli", *argv],
        cwd=tmp_path,
        capture_output=True,
        text=True,
        timeout=seconds,
        preexec_fn=limit_memory,
    )


def rules_file(tmp_path: Path, text: str, name: str = "test.rules") -> Path:
    path = tmp_path / name
    path.write_text(textwrap.dedent(text).lstrip())
    return path


def assert_no_bug(done: subprocess.CompletedProcess) -> None:
    assert "Traceback" not in done.stderr and "rerun with --debug" not in done.stderr, done.stderr


# -- item 2: one number no longer exhausts memory or time --------------------------------


def test_a_field_a_million_metres_wide_is_refused_at_once(tmp_path):
    """Before: MemoryError at 6 GB even with --no-render (export built the field's rows)."""
    rules = rules_file(
        tmp_path,
        """
        scene s { extent 40 x 40  start S }
        object f { noun "field" size 1000000 x 0.5 x 10 shape field }
        S -> { f }
    """,
    )
    done = run_bounded(tmp_path, "generate", str(rules), "--no-render", "-o", "out")
    assert done.returncode == 2
    assert_no_bug(done)
    assert done.stderr.splitlines() == [
        f"{rules}:2:30: error: each side of a size may be at most 1000 m, not 1000000 (the limits: docs/limits.md)",
        '    object f { noun "field" size 1000000 x 0.5 x 10 shape field }',
        "                                 ^",
    ]


def test_every_object_a_billion_metres_is_refused_at_once(tmp_path):
    """Before: 12 GB held for 90 s."""
    rules = rules_file(
        tmp_path,
        """
        scene s { extent 40 x 40  start S }
        object a { noun "tower" size 1000000000 x 1000000000 x 1000000000 shape tower }
        object b { noun "field" size 1000000000 x 1 x 1000000000 shape field }
        S -> { 20 a; 20 b }
    """,
    )
    done = run_bounded(tmp_path, "generate", str(rules), "--no-render", "-o", "out")
    assert done.returncode == 2
    assert_no_bug(done)
    assert (
        done.stderr.count("error: each side of a size may be at most 1000 m, not 1000000000") == 2
    )


@pytest.mark.slow
def test_a_huge_field_in_a_scene_json_is_refused_at_once(tmp_path):
    rules = rules_file(
        tmp_path,
        """
        scene s { extent 40 x 40  start S }
        object f { noun "field" size 8 x 0.5 x 6 shape field }
        S -> { f }
    """,
    )
    assert run_bounded(tmp_path, "generate", str(rules), "--no-render", "-o", "out").returncode == 0
    scene = json.loads((tmp_path / "out" / "scene.json").read_text())
    scene["objects"][0]["size"][0] = 1_000_000.0
    (tmp_path / "huge.json").write_text(json.dumps(scene))
    for command in (
        ["export", "huge.json", "-o", "x.glb"],
        ["render", "huge.json", "-o", "x.png", "--size", "32x32"],
    ):
        done = run_bounded(tmp_path, *command)
        assert done.returncode == 2
        assert_no_bug(done)
        assert done.stderr.strip() == (
            "scenewright: error: huge.json: scene.json $.objects[0].size[0]: 1000000.0 is greater than the maximum of 1000.0"
        )


@pytest.mark.slow
def test_work_at_the_limits_runs_in_bounded_memory_and_time(tmp_path):
    """Twenty 1 km fields and a road of up to 20 km in a 10 km extent, among 20 cm boxes.

    Before: the fields' 1250 crop rows each took 28 s of mesh building, and the road
    across the extent made the layout's grid list 10**9 cells (10 GB, over 600 s).
    """
    rules = rules_file(
        tmp_path,
        f"""
        scene s {{ extent {limits.MAX_EXTENT:g} x {limits.MAX_EXTENT:g}  start S }}
        object f {{ noun "field" size {limits.MAX_SIZE:g} x 0.5 x {limits.MAX_SIZE:g} shape field }}
        object b {{ noun "box" size 0.2 x 0.2 x 0.2 }}
        path road {{ noun "road" width 3 max_length {limits.MAX_PATH_LENGTH:g} segments {limits.MAX_SEGMENTS} }}
        S -> {{ road; 20 f; 30 b NextTo road #1 }}
    """,
    )
    done = run_bounded(tmp_path, "generate", str(rules), "--no-render", "-o", "out", seconds=120)
    assert_no_bug(done)
    assert done.returncode in (0, 1), done.stderr  # 1: a layout that did not satisfy every relation
    scene = json.loads((tmp_path / "out" / "scene.json").read_text())
    assert len(scene["paths"][0]["points"]) == limits.MAX_SEGMENTS + 1


@pytest.mark.slow
def test_the_deepest_nesting_the_limits_allow_is_generated(tmp_path):
    """max_depth 64 calls, each nesting groups 6 blocks deep: 384 nested groups."""
    depth, nesting = limits.MAX_DEPTH, limits.MAX_BLOCK_NESTING
    opening, closing = "g { " * nesting, " }" * nesting
    lines = [
        f"scene s {{ extent 60 x 60  start G0  max_depth {depth} }}",
        'group g { noun "g" }',
        'object b { noun "box" size 0.2 x 0.2 x 0.2 }',
    ]
    lines += [f"G{i} -> {{ {opening}b; G{i + 1}{closing} }}" for i in range(depth - 1)]
    lines.append(f"G{depth - 1} -> {{ {opening}b{closing} }}")
    rules = rules_file(tmp_path, "\n".join(lines) + "\n")
    done = run_bounded(tmp_path, "generate", str(rules), "--no-render", "-o", "out", seconds=120)
    assert_no_bug(done)
    assert done.returncode in (0, 1), done.stderr
    scene = json.loads((tmp_path / "out" / "scene.json").read_text())
    assert sum(o["kind"] == "group" for o in scene["objects"]) == limits.MAX_GROUP_DEPTH
    done = run_bounded(tmp_path, "describe", "out/scene.json")
    assert done.returncode == 0, done.stderr


# -- the rules checker's bounds -----------------------------------------------------------

BASE = """\
scene s {{ extent {extent}  start S{scene} }}
object b {{ noun "box" size {size} }}
path road {{ noun "road" width {width} max_length {max_length} segments {segments} }}
S -> {weight}{{ {count}b; road }}
"""
DEFAULTS = dict(
    extent="40 x 40",
    scene="",
    size="1 x 1 x 1",
    width="3",
    max_length="30",
    segments="3",
    weight="",
    count="",
)


def check(tmp_path: Path, **changes: str) -> list[str]:
    path = rules_file(tmp_path, BASE.format(**{**DEFAULTS, **changes}))
    return [d.message for d in check_rules(str(path)) if d.is_error]


def test_the_base_rules_are_within_every_limit(tmp_path):
    assert check(tmp_path) == []
    at_the_limits = dict(
        extent="10000 x 10000",
        scene=" max_depth 64 max_nodes 10000",
        size="1000 x 1000 x 1000",
        width="1000",
        max_length="20000",
        segments="100",
        weight="1000000: ",
        count="10000 ",
    )
    assert check(tmp_path, **at_the_limits) == []


NINES = "9" * 400  # read as infinity


@pytest.mark.parametrize(
    "changes, at, message",
    [
        (
            dict(size="1000.5 x 1 x 1"),
            "1000.5",
            "each side of a size may be at most 1000 m, not 1000.5",
        ),
        (
            dict(size=f"1 x {NINES} x 1"),
            "1 x 9",
            "each side of a size may be at most 1000 m, not inf",
        ),
        (
            dict(extent="10001 x 40"),
            "10001",
            "each side of the extent may be at most 10000 m, not 10001",
        ),
        (dict(width="1001"), "1001", "'width' may be at most 1000 m, not 1001"),
        (dict(max_length="20001"), "20001", "'max_length' may be at most 20000 m, not 20001"),
        (dict(segments="101"), "101", "'segments' may be at most 100, not 101"),
        (dict(scene=" max_depth 65"), "65", "'max_depth' may be at most 64, not 65"),
        (dict(scene=" max_nodes 10001"), "10001", "'max_nodes' may be at most 10000, not 10001"),
        (
            dict(scene=f" max_nodes {NINES}"),
            NINES,
            "'max_nodes' must be a whole number of at least 1, not inf",
        ),
        (
            dict(weight="1000001: "),
            "1000001:",
            "an alternative weight may be at most 1e+06, not 1000001",
        ),
        (
            dict(size="1 x 0.0001 x 1"),
            "1 x",
            "each side of a size must be at least 0.001 m, not 0.0001",
        ),
        (
            dict(extent="0.0005 x 40"),
            "0.0005",
            "each side of the extent must be at least 0.001 m, not 0.0005",
        ),
        (
            dict(max_length="0.0000001"),
            "0.0000001",
            "'max_length' must be at least 0.001 m, not 1e-07",
        ),
        (
            dict(count="2001 "),
            "2001 b",
            "count 2001 exceeds max_nodes 2000 (raise it in the scene block, e.g. max_nodes 2001)",
        ),
        (
            dict(count="20000 "),
            "20000 b",
            "count 20000 exceeds max_nodes 2000 (max_nodes may be at most 10000, see docs/limits.md)",
        ),
        (dict(count=f"{NINES} "), NINES, "a count must be a whole number, not inf"),
    ],
)
def test_numbers_beyond_the_limits_are_located_errors(tmp_path, changes, at, message):
    messages = check(tmp_path, **changes)
    assert len(messages) == 1 and messages[0].startswith(message), messages
    path = tmp_path / "test.rules"
    error = next(d for d in check_rules(str(path)) if d.is_error)
    line = path.read_text().splitlines()[error.location.line - 1]
    assert line[error.location.column - 1 :].startswith(at), (line, error.location)


def test_an_ordinal_of_thousands_of_digits_is_a_located_error(tmp_path):
    """Before: int() of a 5000-digit ordinal raised inside the parser (exit 1)."""
    rules = rules_file(
        tmp_path,
        f"""
        scene s {{ extent 40 x 40  start S }}
        object b {{ noun "box" size 1 x 1 x 1 }}
        S -> {{ b; b NextTo b #{"9" * 5000} }}
    """,
    )
    errors = [d for d in check_rules(str(rules)) if d.is_error]
    assert [(e.location.line, e.location.column, e.message) for e in errors] == [
        (3, 20, "this ordinal is larger than max_nodes 2000, so it can never name a node")
    ]


@pytest.mark.parametrize("character", ["\x00", "\u202e", "\x1b", "\u2029", "\u200f"])
def test_control_and_bidi_characters_in_nouns_are_located_errors(tmp_path, capsys, character):
    """Before: a NUL or a right-to-left override in a noun was printed as it is."""
    rules = rules_file(
        tmp_path,
        f"""
        scene s {{ extent 40 x 40  start S }}
        object b {{ noun "box{character}x" size 1 x 1 x 1 }}
        S -> {{ b }}
    """,
    )
    assert main(["validate", str(rules)]) == 2
    out = capsys.readouterr().out
    lines = out.splitlines()
    assert lines[0] == (
        f"{rules}:2:17: error: 'noun' contains the character U+{ord(character):04X} "
        f"({_name(character)}); text may not hold control or bidirectional-control characters"
    )
    assert (
        lines[1] == '    object b { noun "box\ufffdx" size 1 x 1 x 1 }'
    )  # shown, never printed raw
    assert character not in out


def _name(character: str) -> str:
    import unicodedata

    return unicodedata.name(character, "control character").lower()


@pytest.mark.parametrize("depth", [limits.MAX_BLOCK_NESTING + 1, 3000])
def test_blocks_nested_too_deep_are_a_located_error(tmp_path, capsys, depth):
    """Before: lark's VisitError of a RecursionError (exit 1, "rerun with --debug") from 300 deep."""
    body = "g { " * depth + "}" * depth
    rules = rules_file(
        tmp_path,
        'scene s { extent 40 x 40  start S }\ngroup g { noun "g" }\nS -> { ' + body + " }\n",
    )
    assert main(["generate", str(rules), "--no-render", "-o", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err
    column = len("S -> { ") + 4 * limits.MAX_BLOCK_NESTING + 3  # the '{' of the 7th "g { "
    assert err.splitlines()[0] == (
        f"{rules}:3:{column}: error: blocks nested more than 6 deep; move the inner "
        "ones into a production of their own and call it (the limits: docs/limits.md)"
    )
    assert "Traceback" not in err and "rerun with --debug" not in err


def test_blocks_nested_as_deep_as_allowed_are_fine(tmp_path):
    depth = limits.MAX_BLOCK_NESTING
    rules = rules_file(
        tmp_path,
        'scene s { extent 40 x 40  start S }\ngroup g { noun "g" }\n'
        'object b { noun "box" size 1 x 1 x 1 }\nS -> { '
        + "g { " * depth
        + "b"
        + " }" * depth
        + " }\n",
    )
    assert [d for d in check_rules(str(rules)) if d.is_error] == []


# -- mesh detail --------------------------------------------------------------------------


@settings(max_examples=80, deadline=None)
@given(
    shape=st.sampled_from(sorted(BUILDERS)),
    size=st.tuples(*[st.floats(0.001, limits.MAX_SIZE, allow_nan=False)] * 3),
)
def test_mesh_detail_is_bounded_whatever_the_size(shape, size):
    mesh = shaped_mesh(shape, None, size, COLOUR)
    assert 0 < len(mesh.faces) < 500 and np.isfinite(mesh.vertices).all()


def test_a_field_a_kilometre_wide_has_the_detail_of_a_30_metre_one():
    wide = BUILDERS["field"]((limits.MAX_SIZE, 0.5, 10.0), COLOUR)
    narrow = BUILDERS["field"]((limits.MAX_REPEATS * 0.8, 0.5, 10.0), COLOUR)
    assert len(wide.faces) == len(narrow.faces) < 500


@pytest.mark.parametrize(
    "size", [(1e9, 1.0, 1.0), (1.0, float("nan"), 1.0), (1.0, 1.0, float("inf")), (-1.0, 1.0, 1.0)]
)
def test_a_mesh_beyond_the_size_limit_is_refused_before_it_is_built(size):
    with pytest.raises(InputError, match="is not within 0..1000 m on each side"):
        shaped_mesh("field", None, size, COLOUR)


# -- the layout's grid: a huge box or a query across the extent costs no more ---------------


def test_the_grid_finds_the_same_neighbours_when_boxes_and_areas_are_huge():
    rng = random.Random(4)
    grid = Grid(0.5)
    boxes = {}
    for box in range(60):
        radius = rng.choice([0.1, 0.3, 2.0, 40.0, 700.0])  # some span far more than MAX_SPAN cells
        x, z = rng.uniform(-2000, 2000), rng.uniform(-2000, 2000)
        grid.insert(box, x, z, radius)
        boxes[box] = (x - radius, z - radius, x + radius, z + radius)
    for box in list(boxes)[::3]:  # move some: remove and insert again
        grid.remove(box)
        x, z, radius = rng.uniform(-500, 500), rng.uniform(-500, 500), rng.choice([0.2, 900.0])
        grid.insert(box, x, z, radius)
        boxes[box] = (x - radius, z - radius, x + radius, z + radius)

    def cells(area):
        x0, z0, x1, z1 = area
        return int(x0 // 0.5), int(x1 // 0.5), int(z0 // 0.5), int(z1 // 0.5)

    def meet(a, b):
        return a[0] <= b[1] and b[0] <= a[1] and a[2] <= b[3] and b[2] <= a[3]

    assert len(grid.large) > 0
    assert sum(len(keys) for keys in grid.keys.values()) < 60 * Grid.MAX_SPAN
    for box, area in boxes.items():
        assert grid.near_box(box) == {
            other for other, their in boxes.items() if meet(cells(area), cells(their))
        }
    for area in [
        (-3000.0, -3000.0, 3000.0, 3000.0),
        (0.0, 0.0, 1.0, 1.0),
        (-100.0, 10.0, 400.0, 12.0),
    ]:
        assert grid.in_area(*area) == {
            other for other, their in boxes.items() if meet(cells(area), cells(their))
        }


# -- description templates: bounded, and their failures located --------------------------


@pytest.mark.parametrize(
    "template, fault",
    [
        ("line 1\n{% set x = 1 %}\n{{ 1 / 0 }}", ":3: ZeroDivisionError: division by zero"),
        (
            "{% macro f(n) %}{{ f(n + 1) }}{% endmacro %}{{ f(0) }}",
            ":1: it calls itself too deeply",
        ),
        (
            "{% for i in range(10**9) %}{% endfor %}",
            ":1: range(1000000000) would take the template's loops past 100000",
        ),
        (
            "{% for i in range(1000) %}{% for j in range(1000) %}{% endfor %}{% endfor %}",
            ":1: range(1000) would take",
        ),
        ("{{ 'x' * 10**9 }}", ":1: '*' would make a result larger than 100000"),
        ("{{ 10 ** 1000000 }}", ":1: '**' would make a result larger than 100000"),
        ("{{ [1] + [2] * 100000 }}", ":1: '+' would make a result larger than 100000"),
    ],
)
def test_a_template_that_fails_at_run_time_is_a_located_input_error(
    tmp_path, capsys, template, fault
):
    """Before: each of these was an exception on the "bug" path (exit 1, "rerun with --debug")."""
    assert main(["generate", "desk", "--no-render", "-o", str(tmp_path / "out"), "-q"]) == 0
    scene = tmp_path / "out" / "scene.json"
    words = tmp_path / "words"
    words.mkdir()
    (words / "caption.j2").write_text(template)
    assert main(["describe", str(scene), "--style", "short", "--templates", str(words)]) == 2
    err = capsys.readouterr().err
    assert err.startswith(
        f"scenewright: error: description template {words.resolve() / 'caption.j2'}{fault}"
    ), err
    assert len(err.splitlines()) == 1 and "rerun with --debug" not in err


def test_a_template_that_writes_a_control_character_is_refused(tmp_path, capsys):
    assert main(["generate", "desk", "--no-render", "-o", str(tmp_path / "out"), "-q"]) == 0
    words = tmp_path / "words"
    words.mkdir()
    (words / "caption.j2").write_text("A desk\u202e.")
    assert (
        main(
            [
                "describe",
                str(tmp_path / "out" / "scene.json"),
                "--style",
                "short",
                "--templates",
                str(words),
            ]
        )
        == 2
    )
    err = capsys.readouterr().err
    assert "it writes the character U+202E (right-to-left override)" in err and "\u202e" not in err


# -- running out of memory ------------------------------------------------------------------


def test_running_out_of_memory_says_where(capsys, tmp_path, monkeypatch):
    """Before: "scenewright: error: MemoryError:  (rerun with --debug for the traceback)"."""

    def no_memory(*args, **kwargs):
        raise MemoryError()

    monkeypatch.setattr(Grid, "insert", no_memory)
    assert main(["generate", "desk", "--no-render", "-o", str(tmp_path / "out")]) == 1
    assert capsys.readouterr().err == (
        "scenewright: error: out of memory while laying the scene out (docs/limits.md lists the bounds on input; "
        "this machine has less memory than the input needs)\n"
    )


def test_the_forbidden_characters_are_categories_cc_zl_zp_and_the_bidi_controls():
    """The character class ``forbidden_character`` and ``printable`` search stands for
    exactly what its comment says, over every code point."""
    import unicodedata

    from scenewright.core.limits import _BIDI_CONTROLS, forbidden_character, printable

    expected = {
        chr(code)
        for code in range(0x110000)
        if chr(code) in _BIDI_CONTROLS or unicodedata.category(chr(code)) in ("Cc", "Zl", "Zp")
    }
    text = "".join(chr(code) for code in range(0x110000) if not 0xD800 <= code <= 0xDFFF)
    replaced = printable(text)
    found = {a for a, b in zip(text, replaced, strict=True) if a != b}
    assert found == expected - {"\t"}
    assert forbidden_character("tab\there") == "U+0009 (control character)"
    assert forbidden_character("plain text, café") is None
