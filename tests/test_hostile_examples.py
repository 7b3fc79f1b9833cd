"""Example files (GLB, hand-written JSON) and the JSON files a user hands in, under
hostile or unlucky input: every one is read, or refused with one line and exit 2, in
bounded time and memory; the readers are fuzzed with hypothesis."""

from __future__ import annotations

import copy
import json
import math
import struct
import time
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from scenewright.cli import main
from scenewright.core.files import JSONTooDeep, load_json
from scenewright.examples import load_example
from scenewright.examples.example import ExampleError
from scenewright.examples.glb_check import MAX_GLB_NODES

BOX_POSITIONS = np.array(
    [[x, y, z] for x in (-0.5, 0.5) for y in (0.0, 0.8) for z in (-0.4, 0.4)], dtype="<f4"
)
BOX_INDICES = np.array(
    [0, 1, 3, 0, 3, 2, 4, 6, 7, 4, 7, 5, 0, 4, 5, 0, 5, 1, 2, 3, 7, 2, 7, 6, 0, 2, 6, 0, 6, 4]
    + [1, 5, 7, 1, 7, 3],
    dtype="<u2",
)


def box_document(names=("desk.001", "chair.001")) -> tuple[dict, bytes]:
    """A glTF document of one box mesh used by a node per name, and its binary chunk."""
    binary = BOX_POSITIONS.tobytes() + BOX_INDICES.tobytes()
    document = {
        "asset": {"version": "2.0"},
        "scene": 0,
        "scenes": [{"nodes": list(range(len(names)))}],
        "nodes": [
            {"name": name, "mesh": 0, "translation": [1.5 * k, 0.0, 0.0]}
            for k, name in enumerate(names)
        ],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
        "accessors": [
            {
                "bufferView": 0,
                "componentType": 5126,
                "count": 8,
                "type": "VEC3",
                "min": [-0.5, 0.0, -0.4],
                "max": [0.5, 0.8, 0.4],
            },
            {"bufferView": 1, "componentType": 5123, "count": 36, "type": "SCALAR"},
        ],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": 96},
            {"buffer": 0, "byteOffset": 96, "byteLength": 72},
        ],
        "buffers": [{"byteLength": len(binary)}],
    }
    return document, binary


def glb_bytes(document: dict, binary: bytes) -> bytes:
    text = json.dumps(document).encode()
    text += b" " * (-len(text) % 4)
    binary += b"\0" * (-len(binary) % 4)
    chunks = struct.pack("<I4s", len(text), b"JSON") + text
    chunks += struct.pack("<I4s", len(binary), b"BIN\0") + binary
    return b"glTF" + struct.pack("<II", 2, 12 + len(chunks)) + chunks


def write_glb(tmp_path: Path, document: dict, binary: bytes, name: str = "room.glb") -> Path:
    path = tmp_path / name
    path.write_bytes(glb_bytes(document, binary))
    return path


def refused(capsys, *argv: str) -> str:
    """The one line of a command that must refuse its input with exit 2 (``validate``
    reports on stdout, the other commands on stderr)."""
    assert main(list(argv)) == 2
    captured = capsys.readouterr()
    err = captured.out + captured.err
    lines = err.strip().splitlines()
    assert len(lines) == 1 and "Traceback" not in err and "--debug" not in err, err
    return lines[0]


def test_the_box_glb_reads(tmp_path):
    example = load_example(write_glb(tmp_path, *box_document()))
    assert [o.type for o in example.objects()] == ["desk", "chair"]


def broken(change):
    document, binary = box_document()
    change(document)
    return document, binary


#: (what is changed, a fragment of the error): each a reproduction of the issue.
HOSTILE_GLB = [
    # an accessor of 5e7 elements with no data behind it: refused before any allocation
    (
        lambda d: d["accessors"].append(
            {"componentType": 5126, "count": 50_000_000, "type": "VEC3"}
        ),
        "accessors[2]: has no bufferView",
    ),
    (lambda d: d["accessors"][0].update(count=50_000_000), "accessors[0]: 50000000 elements need"),
    (lambda d: d["buffers"][0].update(uri="http://example.com/x.bin"), "refers to data outside"),
    (lambda d: d["buffers"][0].update(byteLength=10**9), "more than the file's binary chunk"),
    (lambda d: d["nodes"][0].update(children=[1]) or d["nodes"][1].update(children=[0]), "cycle"),
    (lambda d: d["nodes"][0].update(children=[0]), "its own child"),
    (lambda d: d["nodes"][0].update(children=[7]), "is not a node of the file"),
    (lambda d: d["nodes"][0].update(mesh=3), "is not a mesh of the file"),
    (lambda d: d["nodes"][0].update(translation=[1e308, 0, 0]), "translation: must be 3 finite"),
    (lambda d: d["nodes"][0].update(name="desk\u202e.001"), "U+202E"),
    (lambda d: d["nodes"][0].update(name="desk\x1b[31m"), "U+001B"),
    (lambda d: d["accessors"][1].update(componentType=5122), "unsigned whole numbers"),
    (lambda d: d["bufferViews"][0].update(byteLength=10**12), "beyond its buffer"),
    (lambda d: d.update(nodes={}), '"nodes": must be a list'),
    (lambda d: d["nodes"][1].update(name="desk.001"), "also names node 0"),
    (lambda d: d["meshes"][0]["primitives"][0].update(attributes={}), "has no POSITION"),
    (lambda d: d["nodes"][0].update(rotation=[0, 0, 0, 0]), "not a unit quaternion"),
    (lambda d: d.update(scenes=[]), '"scenes": is empty'),
    (lambda d: d["nodes"][0].update(translation=[99999, 0, 0]), "each side must lie between"),
    (lambda d: d["nodes"][0].update(scale=[1e5, 1, 1]), "each side may be at most 1000 m"),
    (lambda d: d["nodes"][1].update(name="wall.001"), "enclose no floor"),
]


@pytest.mark.parametrize("change, fragment", HOSTILE_GLB)
def test_hostile_glb_is_refused_at_its_place(tmp_path, capsys, change, fragment):
    path = write_glb(tmp_path, *broken(change))
    line = refused(capsys, "validate", str(path))
    assert fragment in line and len(line) < 400


def test_bad_triangle_index_and_unusable_positions(tmp_path, capsys):
    document, binary = box_document()
    indices = BOX_INDICES.copy()
    indices[5] = 9
    path = write_glb(tmp_path, document, BOX_POSITIONS.tobytes() + indices.tobytes())
    assert "index 9 names a vertex past the last of 8" in refused(capsys, "validate", str(path))
    for bad in (math.nan, 1e30, math.inf):
        positions = BOX_POSITIONS.copy()
        positions[3, 1] = bad
        path = write_glb(tmp_path, document, positions.tobytes() + BOX_INDICES.tobytes())
        line = refused(capsys, "validate", str(path))
        assert "not a finite number within 100000 m" in line


def test_deep_json_in_a_glb(tmp_path, capsys):
    document, binary = box_document()
    document["extras"] = "DEEP"
    text = json.dumps(document).replace('"DEEP"', "[" * 5000 + "]" * 5000).encode()
    path = tmp_path / "deep.glb"
    path.write_bytes(glb_bytes_raw(text, binary))
    assert "nested deeper than 64 levels" in refused(capsys, "validate", str(path))


def glb_bytes_raw(text: bytes, binary: bytes) -> bytes:
    text += b" " * (-len(text) % 4)
    chunks = struct.pack("<I4s", len(text), b"JSON") + text
    chunks += struct.pack("<I4s", len(binary), b"BIN\0") + binary
    return b"glTF" + struct.pack("<II", 2, 12 + len(chunks)) + chunks


def test_short_and_truncated_glb(tmp_path, capsys):
    (tmp_path / "four.glb").write_bytes(b"glTF")
    assert "only 4 bytes" in refused(capsys, "validate", str(tmp_path / "four.glb"))
    whole = glb_bytes(*box_document())
    (tmp_path / "cut.glb").write_bytes(whole[: len(whole) // 2])
    assert "cut short" in refused(capsys, "validate", str(tmp_path / "cut.glb"))


def test_too_many_nodes_is_refused_quickly(tmp_path, capsys):
    names = [f"chair.{k:05d}" for k in range(MAX_GLB_NODES * 2)]
    path = write_glb(tmp_path, *box_document(names))
    start = time.perf_counter()
    line = refused(capsys, "validate", str(path))
    assert f"at most {MAX_GLB_NODES}" in line and time.perf_counter() - start < 20


# -- hand-written examples and other JSON files ----------------------------------------


def handwritten(objects, **more) -> str:
    return json.dumps({"extent": [20, 20], "objects": objects, **more})


def test_a_stack_of_1500_objects_reads(tmp_path):
    objects = [{"id": "o0", "type": "crate", "size": [1, 0.1, 1], "position": [0, 0]}]
    objects += [
        {
            "id": f"o{k}",
            "type": "crate",
            "size": [1, 0.1, 1],
            "position": [0, 0],
            "parent": f"o{k - 1}",
        }
        for k in range(1, 1500)
    ]
    (tmp_path / "stack.json").write_text(handwritten(objects))
    start = time.perf_counter()
    example = load_example(tmp_path / "stack.json")
    assert len(example.supports()) == 1499 and time.perf_counter() - start < 30
    assert example.objects()[-1].position[1] == pytest.approx(149.9)


@pytest.mark.parametrize(
    "text, fragment",
    [
        ("", "is empty"),
        ("[" * 100_000 + "]" * 100_000, "nested deeper than 64 levels"),
        (
            handwritten(
                [{"id": "a", "type": "bed", "size": [2, 0.5, 1.6], "position": [0, 0]}],
                name="bed\u202eroom",
            ),
            "U+202E",
        ),
        (
            handwritten(
                [{"id": "a\x07", "type": "bed", "size": [2, 0.5, 1.6], "position": [0, 0]}]
            ),
            "does not match",
        ),
        ('{"objects": [], "note": "rules format"}', "$"),
    ],
)
def test_bad_handwritten_files(tmp_path, capsys, text, fragment):
    (tmp_path / "x.json").write_text(text)
    line = refused(capsys, "validate", str(tmp_path / "x.json"))
    assert fragment in line


def test_format_is_told_by_structure_not_words(tmp_path):
    # the words "rules" and "format" inside a hand-written example's strings do not make
    # it a scene.json
    text = handwritten(
        [{"id": "rules", "type": "format", "size": [1, 1, 1], "position": [0, 0]}],
        name='"rules" "format"',
    )
    (tmp_path / "x.json").write_text(text)
    assert load_example(tmp_path / "x.json").format == "example.json"


def test_load_json_bounds_depth_without_recursion():
    assert load_json("[" * 64 + "]" * 64) is not None
    for depth in (65, 5000, 200_000):
        with pytest.raises(JSONTooDeep):
            load_json("[" * depth + "]" * depth)
    with pytest.raises(ValueError, match="NaN is not a finite number"):
        load_json('{"a": NaN}')


@pytest.mark.parametrize("name", ["context", "dataset", "plan"])
def test_deep_json_files_are_refused(tmp_path, capsys, name):
    deep = "[" * 5000 + "]" * 5000
    if name == "context":
        (tmp_path / "c.json").write_text(deep)
        argv = [
            "generate",
            "bedroom",
            "--context",
            str(tmp_path / "c.json"),
            "-o",
            str(tmp_path / "o"),
        ]
    elif name == "dataset":
        out = tmp_path / "d"
        (out / "scenes").mkdir(parents=True)
        (out / "dataset.json").write_text(deep)
        argv = ["dataset", "bedroom", "-n", "1", "--no-images", "-o", str(out)]
    else:
        plans = tmp_path / "plans" / "bedroom"
        plans.mkdir(parents=True)
        (plans / "p.json").write_text(deep)
        argv = ["plans", "build", str(tmp_path / "plans"), "-o", str(tmp_path / "m.json")]
    line = refused(capsys, *argv)
    assert "nested deeper than 64 levels" in line or "not JSON" in line
    assert not (tmp_path / "o").exists() and not (tmp_path / "m.json").exists()


def test_a_dataset_json_that_is_a_list(tmp_path, capsys):
    out = tmp_path / "d"
    (out / "scenes").mkdir(parents=True)
    (out / "dataset.json").write_text("[]")
    line = refused(capsys, "dataset", "bedroom", "-n", "1", "--no-images", "-o", str(out))
    assert "not a dataset's settings" in line


# -- fuzz ---------------------------------------------------------------------------

FUZZ = settings(
    max_examples=60, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture]
)

SCALARS = st.one_of(
    st.none(),
    st.booleans(),
    st.integers(-(2**40), 2**40),
    st.floats(allow_nan=False, allow_infinity=False),
    st.text(max_size=8),
)


def _leaf_paths(value, path=()):
    yield path
    if isinstance(value, dict):
        for key, item in value.items():
            yield from _leaf_paths(item, (*path, key))
    elif isinstance(value, list):
        for index, item in enumerate(value):
            yield from _leaf_paths(item, (*path, index))


def _replaced(document, path, value):
    document = copy.deepcopy(document)
    if not path:
        return value
    target = document
    for part in path[:-1]:
        target = target[part]
    target[path[-1]] = value
    return document


GLB_PATHS = list(_leaf_paths(box_document()[0]))


@FUZZ
@given(
    st.lists(st.tuples(st.sampled_from(GLB_PATHS), SCALARS), min_size=1, max_size=4),
    st.binary(max_size=64),
)
def test_fuzz_the_glb_reader(tmp_path, edits, tail):
    """Any value at any place of a GLB's JSON, and any bytes after it: read, or refused
    with an ExampleError (never another exception)."""
    document, binary = box_document()
    for path, value in edits:
        try:
            document = _replaced(document, path, value)
        except (KeyError, IndexError, TypeError):
            continue
    data = glb_bytes(document, binary) + tail
    (tmp_path / "f.glb").write_bytes(data)
    try:
        load_example(tmp_path / "f.glb")
    except ExampleError:
        pass


HANDWRITTEN = {
    "room": {"width": 4, "depth": 3},
    "objects": [
        {"id": "bed", "type": "bed", "size": [2, 0.5, 1.6], "position": [0, 0], "yaw": 90},
        {
            "id": "lamp",
            "type": "lamp",
            "size": [0.2, 0.4, 0.2],
            "position": [0, 0],
            "parent": "bed",
        },
    ],
}
HANDWRITTEN_PATHS = list(_leaf_paths(HANDWRITTEN))


@FUZZ
@given(st.lists(st.tuples(st.sampled_from(HANDWRITTEN_PATHS), SCALARS), min_size=1, max_size=4))
def test_fuzz_the_example_reader(tmp_path, edits):
    """Any value at any place of a hand-written example: read, or refused with an
    ExampleError."""
    document = HANDWRITTEN
    for path, value in edits:
        try:
            document = _replaced(document, path, value)
        except (KeyError, IndexError, TypeError):
            continue
    (tmp_path / "f.json").write_text(json.dumps(document))
    try:
        load_example(tmp_path / "f.json")
    except ExampleError:
        pass


def _supports_all_pairs(objects):
    """The supports by testing every pair: what the grid must find."""
    from scenewright.examples.stacking import rests_on

    supports = {}
    for upper in objects:
        below = [lower for lower in objects if rests_on(upper, lower)]
        if below:
            nearest = min(
                below,
                key=lambda lower: (
                    abs(upper.position[1] - lower.position[1] - lower.size[1]),
                    lower.id,
                ),
            )
            supports[upper.id] = nearest.id
    return supports


@FUZZ
@given(
    st.lists(
        st.tuples(
            st.floats(-5, 5),
            st.sampled_from([0.0, 0.5, 0.75, 0.76, 1.0, 1.5]),
            st.floats(-5, 5),
            st.floats(0.05, 40),
            st.sampled_from([0.25, 0.5, 0.75]),
            st.floats(0.05, 4),
            st.floats(-math.pi, math.pi),
        ),
        max_size=40,
    )
)
def test_supports_through_the_grid_are_those_of_all_pairs(boxes):
    from types import SimpleNamespace

    objects = [
        SimpleNamespace(id=f"o{k}", position=[x, y, z], size=[w, h, d], yaw=yaw)
        for k, (x, y, z, w, h, d, yaw) in enumerate(boxes)
    ]
    from scenewright.examples.stacking import infer_supports

    assert infer_supports(objects) == _supports_all_pairs(objects)


def test_supports_of_ten_thousand_objects_are_found_quickly():
    from types import SimpleNamespace

    from scenewright.examples.stacking import infer_supports

    objects = []
    for k in range(5000):
        x, z = 1.5 * (k % 70), 1.5 * (k // 70)
        objects.append(
            SimpleNamespace(id=f"t{k}", position=[x, 0.0, z], size=[1, 0.75, 1], yaw=0.0)
        )
        objects.append(
            SimpleNamespace(id=f"b{k}", position=[x, 0.75, z], size=[0.3, 0.2, 0.3], yaw=0.0)
        )
    start = time.perf_counter()
    supports = infer_supports(objects)
    assert len(supports) == 5000 and supports["b7"] == "t7"
    assert time.perf_counter() - start < 10


def test_the_structure_graph_of_a_tall_stack_is_quick(tmp_path):
    """Only a support relates objects off the floor, so a stack of 1500 is measured pair
    by supporting pair, not all pairs of its one spot."""
    from scenewright.variation.structure import structure_graph

    objects = [{"id": "o0", "type": "crate", "size": [1, 0.1, 1], "position": [0, 0]}]
    objects += [
        {
            "id": f"o{k}",
            "type": "crate",
            "size": [1, 0.1, 1],
            "position": [0, 0],
            "parent": f"o{k - 1}",
        }
        for k in range(1, 1500)
    ]
    (tmp_path / "stack.json").write_text(handwritten(objects))
    scene = load_example(tmp_path / "stack.json").scene
    start = time.perf_counter()
    graph = structure_graph(scene)
    assert len(graph.edges) == 2 * 1499 and time.perf_counter() - start < 30
