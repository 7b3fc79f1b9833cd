"""Hostile input through the command line: every answer is a result or a clean refusal.

scene.json documents and rules files with hostile values (NaN, huge and negative
numbers, deep nesting, long strings, control characters, broken references) go through
``validate``, ``describe``, ``export``, ``render --size 32x32`` and ``generate
--no-render`` in-process (``scenewright.cli.main``). Each run must end with exit 0 and
a valid result, or exit 2 with the error on stderr (one line; a rules file's errors
are its located diagnostics), or - for ``generate`` only - exit 1 because the layout
could not satisfy every relation. Never the "bug" path (exit 1, "rerun with --debug"),
never a traceback.
"""

from __future__ import annotations

import contextlib
import copy
import io
import json
import math
import tempfile
from pathlib import Path

import pytest
from hypothesis import HealthCheck, event, given, settings
from hypothesis import strategies as st

from scenewright.cli import main

#: A rules file with a slot for every hostile value.
RULES = """\
scene s {{ extent {extent}  start S{scene} }}
object table {{ noun "{noun}" size {size} shape {shape} }}
object pot {{ noun "pot" size 0.4 x 0.3 x 0.4 shape pot
    style big {weight} {{ noun "big pot" }} }}
group stall {{ noun "stall" }}
path road {{ noun "road" width {width} max_length {max_length} segments {segments} }}
S -> {{ road; {count} Stall NextTo road #{ordinal} }}
Stall -> {alternative}{{ {nested} }} | 1: {{ stall {{ table }} }}
"""

HOSTILE_NUMBERS = st.sampled_from(
    ["0", "-1", "1001", "10001", "20001", "1" + "0" * 30, "9" * 400, "0.0000001"]
)
HOSTILE_TEXT = st.sampled_from(
    ["", " ", "x" * 300, "a\x00b", "ta\u202eble", "t\u2028x", "t\tab", "\x1b[31mred"]
)


SLOTS = (
    "extent",
    "scene",
    "noun",
    "size",
    "weight",
    "width",
    "max_length",
    "segments",
    "count",
    "ordinal",
    "alternative",
    "nested",
)


@st.composite
def rules_texts(draw) -> str:
    """A rules file whose slots hold valid values but for none, one or two hostile ones,
    so that many files get past the checks to expansion, layout, meshes and the text."""
    count = draw(st.sampled_from([0, 0, 0, 1, 2]))
    hostile = set(draw(st.lists(st.sampled_from(SLOTS), min_size=count, max_size=count)))
    slots = iter(SLOTS)

    def slot(valid, bad=HOSTILE_NUMBERS):
        name = next(slots)
        return draw(bad if name in hostile else st.sampled_from(valid))

    values = dict(
        extent=slot(
            ["30 x 20", "60 x 40", "10000 x 10000"], HOSTILE_NUMBERS.map("{0} x {0}".format)
        ),
        scene=slot(
            ["", " max_nodes 60", " max_depth 8", " max_nodes 10000"],
            HOSTILE_NUMBERS.map(" max_nodes {}".format),
        ),
        noun=slot(["table", "big table", "\u00e9tal", "x" * 200], HOSTILE_TEXT),
        size=slot(
            ["1.6 x 0.8 x 0.9", "8 x 0.2 x 6", "1000 x 0.5 x 1000"],
            HOSTILE_NUMBERS.map("1 x {} x 1".format),
        ),
        weight=slot(["1", "2", "1000000"]),
        width=slot(["3", "0.5", "1000"]),
        max_length=slot(["28", "5", "20000"]),
        segments=slot(["3", "1", "100"]),
        count=slot(
            ["", "2 ", "0..2 ", "1..3 "],
            st.sampled_from(["3..1 ", "20001 ", "9" * 400 + " ", "-1 "]),
        ),
        ordinal=slot(["1"], st.sampled_from(["0", "2", "9" * 5000])),
        alternative=slot(["", "2: "], st.sampled_from(["0: ", "1000001: ", "9" * 400 + ": "])),
        nested=slot(range(1, 7), st.integers(7, 40)),
    )
    depth = values.pop("nested")
    nested = "stall { " * depth + "table; 0.5? pot OnTopOf some table" + " }" * depth
    return RULES.format(
        **values,
        nested=nested,
        shape=draw(st.sampled_from(["table", "field", "tower", "nonsense"])),
    )


#: Values to put anywhere in a scene.json document.
HOSTILE = st.one_of(
    st.sampled_from(
        [
            math.nan,
            math.inf,
            -math.inf,
            1e308,
            -1e308,
            1e6,
            -1.0,
            0.0,
            10**30,
            -(10**30),
            True,
            None,
        ]
    ),
    st.sampled_from(
        ["", "x" * 10_000, "a\x00b", "ta\u202eble", "\x1b[31mred", "table_1", "NextTo", "Implicit"]
    ),
    st.sampled_from([[], {}, [0.0], [0.0, 0.0], [1.0, 2.0, 3.0], [[0.0, 0.0]], {"a": 1}]),
    st.integers(1, 200).map(lambda depth: json.loads("[" * depth + "]" * depth)),
)


def leaves(value, path=()):
    """Every place in a JSON document, as a path of keys and indices."""
    yield path
    if isinstance(value, dict):
        for key, item in value.items():
            yield from leaves(item, path + (key,))
    elif isinstance(value, list):
        for index, item in enumerate(value):
            yield from leaves(item, path + (index,))


def _at(document, path):
    for part in path:
        document = document[part]
    return document


def replaced(document, path, value):
    """``document`` with the value at ``path`` replaced (or the key deleted, for value ``...``)."""
    if not path:
        return {} if value is ... else value
    changed = copy.deepcopy(document)
    holder = changed
    for part in path[:-1]:
        holder = holder[part]
    if value is ... and isinstance(holder, dict):
        del holder[path[-1]]
    else:
        holder[path[-1]] = None if value is ... else value
    return changed


@pytest.fixture(scope="module")
def scene_document(tmp_path_factory) -> dict:
    """A generated scene: groups, a path and a junction, relations, a description."""
    out = tmp_path_factory.mktemp("fuzz") / "out"
    with contextlib.redirect_stdout(io.StringIO()):
        market = Path(__file__).parent / "rules" / "market.rules"
        assert main(["generate", str(market), "--seed", "3", "--no-render", "-o", str(out)]) in (
            0,
            1,
        )
    return json.loads((out / "scene.json").read_text())


def run(*argv: str) -> tuple[int, str, str]:
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        code = main(list(argv))
    return code, out.getvalue(), err.getvalue()


def assert_clean(
    code: int, out: str, err: str, *, rules: bool = False, generate: bool = False
) -> None:
    assert "Traceback" not in out + err and "rerun with --debug" not in err, err
    if code == 0:
        return
    if code == 1 and generate:
        assert "the layout did not satisfy every constraint" in err, err
        return
    assert code == 2, (code, err)
    if rules:  # located diagnostics: each error line, then its line of rules and a caret
        assert err.splitlines()[0].split(": ")[1:2] == ["error"] or err.startswith(
            "scenewright: error: "
        ), err
    elif err:
        assert len(err.strip().splitlines()) == 1 and err.startswith("scenewright: error: "), err
    else:  # validate reports on stdout
        assert out and all(
            ": error: " in line or line.endswith(": ok") for line in out.splitlines()
        ), out


def plausible(document, value) -> st.SearchStrategy:
    """A value of the kind already there: a number nearby, another id or label, a shorter list."""
    if isinstance(value, bool):
        return st.booleans()
    if isinstance(value, (int, float)):
        return st.one_of(
            st.floats(0.0, 1.0), st.integers(1, 6)
        )  # within most of scene.json's ranges
    if isinstance(value, str):
        ids = [entry["id"] for section in ("objects", "paths") for entry in document[section]]
        return st.sampled_from(
            ids + ["NextTo", "OnTopOfMiddle", "ImplicitFacingTowards", "PathConnectedTo", "x"]
        )
    if isinstance(value, list) and value:
        return st.integers(0, len(value) - 1).map(lambda cut: value[:cut])
    return st.just(value)


@settings(
    max_examples=25, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture]
)
@pytest.mark.slow
@given(data=st.data())
def test_hostile_scene_json(scene_document, data):
    document = scene_document
    for _ in range(data.draw(st.integers(1, 3))):
        path = data.draw(st.sampled_from(list(leaves(document))))
        current = _at(document, path)
        hostile = data.draw(st.integers(0, 2)) == 0
        value = data.draw(
            st.one_of(HOSTILE, st.just(...)) if hostile else plausible(scene_document, current)
        )
        document = replaced(document, path, value)
    text = json.dumps(document, allow_nan=True)
    with tempfile.TemporaryDirectory() as folder:
        scene = Path(folder) / "scene.json"
        scene.write_text(text)
        code, out, err = run("validate", str(scene))
        assert_clean(code, out, err)
        valid = code == 0
        event(f"scene.json valid: {valid}")
        for argv in (
            ["describe", str(scene)],
            ["export", str(scene), "-o", folder],
            ["render", str(scene), "-o", str(Path(folder) / "x.png"), "--size", "32x32"],
        ):
            code, out, err = run(*argv)
            assert_clean(code, out, err)
            if valid and code != 0:  # validate passed it, so only rendering may be unavailable
                assert argv[0] == "render" and "OpenGL" in err, (argv, err)
        if valid and (Path(folder) / "scene.glb").exists():
            assert (Path(folder) / "scene.glb").read_bytes()[:4] == b"glTF"


@pytest.mark.slow
@settings(max_examples=25, deadline=None)
@given(text=rules_texts())
def test_hostile_rules_files(text):
    with tempfile.TemporaryDirectory() as folder:
        rules = Path(folder) / "hostile.rules"
        rules.write_text(text)
        code, out, err = run("validate", str(rules))
        assert "Traceback" not in out + err and code in (0, 2), (code, out, err)
        code, out, err = run(
            "generate", str(rules), "--no-render", "-o", str(Path(folder) / "out"), "-q"
        )
        assert_clean(code, out, err, rules=True, generate=True)
        event(f"generate exit {code}")
        if code in (0, 1):
            scene = Path(folder) / "out" / "scene.json"
            assert run("validate", str(scene))[0] == 0  # what generate writes, validate accepts
