"""A scene.json from anyone: numbers finite and bounded, text printable, references that
resolve, nesting bounded; bad ones exit 2 with the JSON path, never the "bug" path.

Also the commands that read a scene.json with awkward but valid input: an empty
scene, an output directory given as ``-o``, and a mesh file that is not a mesh.
"""

from __future__ import annotations

import copy
import json
import math
from pathlib import Path

import pytest
from render_fixtures import renderer_or_skip
from test_cli import assert_one_line_error as cli_one_line_error
from test_cli import run

from scenewright import __version__
from scenewright.core import limits
from scenewright.core.scene import LayoutStats, Relation, Scene, SceneObject, ScenePath
from scenewright.core.schema_check import (
    SceneSchemaError,
    load_schema,
    parse_scene_json,
    scene_problems,
    validate_scene_dict,
)


def assert_one_line_error(err: str, *fragments: str) -> None:
    """``test_cli``'s check, and the line must not offer --debug: bad input is no crash."""
    cli_one_line_error(err, *fragments)
    assert "rerun with --debug" not in err


def scene_dict() -> dict:
    """A small valid scene: a stall group (table and sign), a junction and a road."""
    scene = Scene(
        rules="test",
        seed=1,
        extent=[20.0, 20.0],
        objects=[
            SceneObject(
                "stall_1",
                "stall",
                "group",
                "stall",
                None,
                None,
                None,
                [0.0, 0.0, 2.0],
                0.0,
                [2.0, 1.6, 1.0],
                order=0,
            ),
            SceneObject(
                "table_1",
                "table",
                "object",
                "table",
                None,
                "stall_1",
                None,
                [0.0, 0.0, 2.0],
                0.0,
                [1.6, 0.8, 0.9],
                shape="table",
                order=1,
            ),
            SceneObject(
                "sign_1",
                "sign",
                "object",
                "sign",
                None,
                "stall_1",
                None,
                [1.2, 0.0, 2.0],
                0.0,
                [0.6, 1.6, 0.15],
                shape="sign",
                order=2,
            ),
            SceneObject(
                "crossing_1",
                "crossing",
                "junction",
                "crossing",
                None,
                None,
                None,
                [-6.0, 0.0, 0.0],
                0.0,
                [3.0, 0.0, 3.0],
                order=3,
            ),
        ],
        paths=[
            ScenePath(
                "road_1",
                "road",
                "road",
                None,
                None,
                [[-6.0, 0.0], [0.0, 0.0], [4.0, 0.0], [8.0, 0.0]],
                3.0,
                start="crossing_1",
                order=4,
            )
        ],
        relations=[
            Relation("sign_1", "table_1", "NextToChooseSide", -0.01, True, "left"),
            Relation("table_1", "road_1", "NextTo", 0.0, True),
            Relation("road_1", "crossing_1", "PathConnectedTo", 0.0, True),
        ],
        layout=LayoutStats(energy=0.0, steps=10, acceptance=0.5, ok=True),
        version=__version__,
    )
    return json.loads(scene.to_json(reproducible=True))


def write(tmp_path: Path, data, name: str = "scene.json") -> Path:
    path = tmp_path / name
    path.write_text(data if isinstance(data, str) else json.dumps(data))
    return path


def test_the_base_scene_is_valid(tmp_path, capsys):
    validate_scene_dict(scene_dict())
    code, out, err = run(capsys, "validate", str(write(tmp_path, scene_dict())))
    assert (code, err) == (0, "") and out.endswith(": ok\n")


# -- numbers (item 9) -------------------------------------------------------------------


@pytest.mark.parametrize("text", ["NaN", "Infinity", "-Infinity", "1e999", "-1e400"])
def test_non_finite_numbers_are_refused_at_their_json_path(tmp_path, capsys, text):
    raw = json.dumps(scene_dict()).replace(
        '"position": [1.2, 0.0, 2.0]', f'"position": [{text}, 0.0, 2.0]', 1
    )
    assert text in raw
    path = write(tmp_path, raw)
    code, out, err = run(capsys, "validate", str(path))
    assert code == 2 and err == ""
    assert (
        out
        == f"{path}: error: scene.json $.objects[2].position[0]: {text} is not a finite number\n"
    )
    for command in (
        ["describe"],
        ["export", "-o", str(tmp_path / "x.glb")],
        ["render", "-o", str(tmp_path / "x.png")],
    ):
        code, out, err = run(capsys, *command[:1], str(path), *command[1:])
        assert code == 2 and out == ""
        assert_one_line_error(err, "$.objects[2].position[0]", "not a finite number")
    assert not (tmp_path / "x.glb").exists()


def test_non_finite_floats_from_python_are_refused_too():
    data = scene_dict()
    data["objects"][1]["yaw"] = math.nan
    with pytest.raises(SceneSchemaError) as caught:
        validate_scene_dict(data)
    assert caught.value.path == "$.objects[1].yaw"


@pytest.mark.parametrize(
    "break_it, path, words",
    [
        (
            lambda d: d["objects"][1].update(position=[1e300, 0.0, 0.0]),
            "$.objects[1].position[0]",
            "maximum of 100000",
        ),
        (
            lambda d: d["paths"][0]["points"][1].__setitem__(1, -2e5),
            "$.paths[0].points[1][1]",
            "minimum of -100000",
        ),
        (
            lambda d: d["objects"][1].update(size=[1e6, 1.0, 1.0]),
            "$.objects[1].size[0]",
            "maximum of 1000",
        ),
        (lambda d: d.update(extent=[1e9, 10.0]), "$.extent[0]", "maximum of 10000"),
        (lambda d: d.update(extent=[0.0, 10.0]), "$.extent[0]", "less than the minimum of 0.001"),
        (lambda d: d["paths"][0].update(width=5000.0), "$.paths[0].width", "maximum of 1000"),
        (lambda d: d["paths"][0].update(segments=10**6), "$.paths[0].segments", "maximum of 100"),
        (lambda d: d.update(seed=-1), "$.seed", "minimum of 0"),
    ],
)
def test_coordinates_sizes_and_counts_are_bounded(break_it, path, words):
    data = copy.deepcopy(scene_dict())
    break_it(data)
    with pytest.raises(SceneSchemaError) as caught:
        validate_scene_dict(data)
    assert caught.value.path == path
    assert words in str(caught.value)


def test_a_group_box_may_be_larger_than_an_object():
    data = scene_dict()
    data["objects"][0]["size"] = [5000.0, 2.0, 5000.0]  # the union of members far apart
    validate_scene_dict(data)


def test_the_schema_carries_the_limits_of_core_limits():
    schema = load_schema()
    definitions, properties = schema["$defs"], schema["properties"]
    assert definitions["vec3"]["items"]["maximum"] == limits.MAX_COORDINATE
    assert definitions["pair"]["items"]["minimum"] == -limits.MAX_COORDINATE
    assert properties["extent"]["items"]["maximum"] == limits.MAX_EXTENT
    assert (
        definitions["object"]["then"]["properties"]["size"]["items"]["maximum"] == limits.MAX_SIZE
    )
    assert definitions["path"]["properties"]["width"]["maximum"] == limits.MAX_SIZE
    assert definitions["path"]["properties"]["max_length"]["maximum"] == limits.MAX_PATH_LENGTH
    assert definitions["path"]["properties"]["segments"]["maximum"] == limits.MAX_SEGMENTS
    assert properties["objects"]["maxItems"] == properties["paths"]["maxItems"] == limits.MAX_NODES


def test_huge_coordinates_no_longer_crash_the_renderer(tmp_path, capsys):
    """Before: ``render`` of positions of 1e300 failed with ``zfar must be >0`` (exit 1)."""
    data = scene_dict()
    for obj in data["objects"]:
        obj["position"][0] = 1e300
    code, out, err = run(
        capsys,
        "render",
        str(write(tmp_path, data)),
        "-o",
        str(tmp_path / "x.png"),
        "--size",
        "32x32",
    )
    assert code == 2
    assert_one_line_error(err, "position[0]", "greater than the maximum of 100000")


def test_a_scene_at_the_coordinate_limit_renders(tmp_path, capsys):
    renderer_or_skip(32, 32).close()
    data = scene_dict()
    for obj in data["objects"]:
        obj["position"][0] += limits.MAX_COORDINATE - 10.0
    for point in data["paths"][0]["points"]:
        point[0] += limits.MAX_COORDINATE - 10.0
    code, out, err = run(
        capsys,
        "render",
        str(write(tmp_path, data)),
        "-o",
        str(tmp_path / "far.png"),
        "--size",
        "32x32",
    )
    assert (code, err) == (0, "")
    assert (tmp_path / "far.png").stat().st_size > 0


def test_exported_glb_of_a_checked_scene_passes_khronos_validator(tmp_path, capsys):
    """Before: a NaN position was exported (exit 0) to a GLB the validator rejects."""
    from test_export import test_khronos_validator_reports_no_errors

    code, _, _ = run(
        capsys, "export", str(write(tmp_path, scene_dict())), "-o", str(tmp_path / "ok.glb")
    )
    assert code == 0
    test_khronos_validator_reports_no_errors(tmp_path / "ok.glb")


# -- text (item 14) ---------------------------------------------------------------------


@pytest.mark.parametrize("character", ["\x00", "\u202e", "\x1b", "\u2028", "\u2066"])
def test_control_and_bidi_characters_in_strings_are_refused(tmp_path, capsys, character):
    data = scene_dict()
    data["objects"][1]["noun"] = f"ta{character}ble"
    path = write(tmp_path, data)
    code, out, err = run(capsys, "describe", str(path))
    assert code == 2 and out == ""
    assert_one_line_error(err, "$.objects[1].noun", f"U+{ord(character):04X}")
    assert character not in err


def test_a_key_with_a_control_character_is_shown_escaped():
    data = scene_dict()
    data["timings"] = {"a\u202eb": 1.0}
    problems = scene_problems(data)
    assert problems == [
        ("$.timings", "a key contains the character U+202E (right-to-left override)")
    ]


# -- nesting (item 10) ------------------------------------------------------------------


def test_deeply_nested_json_is_bad_input_and_validate_goes_on(tmp_path, capsys):
    """Before: a RecursionError (exit 1, "rerun with --debug"), and validate stopped."""
    deep = write(tmp_path, "[" * 100_000 + "]" * 100_000, "deep.json")
    medium = write(
        tmp_path,
        json.dumps({**scene_dict(), "timings": json.loads("[" * 500 + "]" * 500)}),
        "medium.json",
    )
    good = write(tmp_path, scene_dict(), "good.json")
    code, out, err = run(capsys, "validate", str(deep), str(medium), str(good))
    assert code == 2 and err == ""
    assert out.splitlines() == [
        f"{deep}: error: scene.json $: nested deeper than 64 levels",
        f"{medium}: error: scene.json $.timings{'[0]' * 64}: nested deeper than 64 levels",
        f"{good}: ok",
    ]
    code, out, err = run(capsys, "describe", str(deep))
    assert code == 2
    assert_one_line_error(err, "nested deeper than 64 levels")


def test_parse_keeps_non_finite_numbers_as_markers():
    data = parse_scene_json('{"a": [NaN, 1e999, 2.5]}')
    assert data["a"][2] == 2.5
    assert [marker.text for marker in data["a"][:2]] == ["NaN", "1e999"]


# -- references (item 11) -------------------------------------------------------------


def test_every_broken_reference_is_one_line_with_its_path(tmp_path, capsys):
    data = scene_dict()
    data["objects"].append(dict(data["objects"][1]))  # a second table_1
    data["objects"][1]["parent"] = "ghost_1"
    data["objects"][3]["parent"] = "crossing_1"  # its own parent
    data["paths"][0]["parent"] = "table_1"  # not a group
    data["relations"][0]["target"] = "nowhere_1"
    data["relations"][1]["label"] = "NextTwo"
    data["templates"] = str(tmp_path / "no-such-folder")
    path = write(tmp_path, data)
    code, out, err = run(capsys, "validate", str(path))
    assert code == 2 and err == ""
    assert out.splitlines() == [
        f"{path}: error: scene.json $.objects[4].id: duplicate id 'table_1' (also at $.objects[1].id)",
        f"{path}: error: scene.json $.objects[1].parent: the parent 'ghost_1' is not an id of this scene",
        f"{path}: error: scene.json $.objects[3].parent: 'crossing_1' is its own parent",
        f"{path}: error: scene.json $.paths[0].parent: the parent 'table_1' is an object, not a group",
        f"{path}: error: scene.json $.relations[0].target: 'nowhere_1' is not an id of this scene",
        f"{path}: error: scene.json $.relations[1].label: unknown relation label 'NextTwo'; did you mean 'NextTo'?",
        f"{path}: error: scene.json $.templates: the description templates folder "
        f"'{tmp_path / 'no-such-folder'}' does not exist",
    ]
    code, out, err = run(capsys, "describe", str(path))
    assert code == 2
    assert_one_line_error(
        err,
        "$.objects[4].id: duplicate id",
        "(and 5 more problems: 'scenewright validate' lists them)",
    )


def test_a_path_must_start_at_a_junction_or_on_another_path_of_the_scene():
    data = scene_dict()
    data["paths"][0]["start"] = "table_1"
    assert scene_problems(data) == [
        (
            "$.paths[0].start",
            "the path starts at 'table_1', which is an object, not a junction or a path",
        )
    ]
    data["paths"][0]["start"] = data["paths"][0]["id"]
    assert scene_problems(data) == [
        ("$.paths[0].start", f"the path starts on itself ({data['paths'][0]['id']!r})")
    ]
    branch = {**data["paths"][0], "id": "lane_1", "start": data["paths"][0]["id"]}
    data["paths"][0]["start"] = None
    data["paths"].append(branch)  # a branch starts on its road
    assert scene_problems(data) == []


def test_parent_cycles_and_groups_nested_too_deep_are_refused():
    data = scene_dict()
    group = dict(data["objects"][0])
    data["objects"] += [
        {**group, "id": "a_1", "parent": "b_1"},
        {**group, "id": "b_1", "parent": "a_1"},
    ]
    assert scene_problems(data) == [
        ("$.objects[4].parent", "its parents lead round in a cycle (a_1 -> b_1 -> a_1)")
    ]

    data = scene_dict()
    chain = [
        {**group, "id": f"g_{i}", "parent": f"g_{i - 1}" if i else None}
        for i in range(limits.MAX_GROUP_DEPTH + 2)
    ]
    data["objects"] += chain
    deepest = len(data["objects"]) - 1
    assert scene_problems(data) == [
        (
            f"$.objects[{deepest}].parent",
            f"it lies {limits.MAX_GROUP_DEPTH + 1} groups deep; groups may nest at most "
            f"{limits.MAX_GROUP_DEPTH} deep",
        )
    ]
    data["objects"].pop()
    assert scene_problems(data) == []


# -- awkward but valid input (items 10, 14) ----------------------------------------------


def test_an_empty_scene_describes_exports_and_renders(tmp_path, capsys):
    """Before: ``export`` of an empty scene failed in trimesh ("Can't export empty scenes!", exit 1)."""
    data = {**scene_dict(), "objects": [], "paths": [], "relations": []}
    path = write(tmp_path, data)
    assert run(capsys, "describe", str(path))[:2] == (0, "The scene is empty.\n")
    code, out, err = run(capsys, "export", str(path), "-o", str(tmp_path / "empty.glb"))
    assert (code, err) == (0, "")
    glb = (tmp_path / "empty.glb").read_bytes()
    assert glb[:4] == b"glTF" and int.from_bytes(glb[8:12], "little") == len(glb)
    bare = tmp_path / "bare.glb"
    assert run(capsys, "export", str(path), "-o", str(bare), "--no-ground")[0] == 0
    glb = bare.read_bytes()  # a camera and a light, nothing to draw
    assert glb[:4] == b"glTF" and int.from_bytes(glb[8:12], "little") == len(glb)
    assert b"BIN\x00" not in glb  # no empty binary chunk
    from test_export import test_khronos_validator_reports_no_errors

    test_khronos_validator_reports_no_errors(tmp_path / "empty.glb")


@pytest.mark.parametrize("slash", [True, False])
def test_export_and_render_into_a_directory(tmp_path, capsys, slash):
    """Before: ``export -o DIR`` failed (IsADirectoryError, exit 1) and ``render -o DIR/``
    wrote DIR.png and its siblings into DIR's parent."""
    path = write(tmp_path, scene_dict())
    target = tmp_path / "exports"
    if not slash:
        target.mkdir()
    code, out, err = run(capsys, "export", str(path), "-o", str(target) + ("/" if slash else ""))
    assert (code, err) == (0, "")
    assert out == f"wrote {target / 'scene.glb'}\n"
    assert (target / "scene.glb").read_bytes()[:4] == b"glTF"
    renderer_or_skip(32, 32).close()
    code, out, err = run(
        capsys, "render", str(path), "-o", str(target) + ("/" if slash else ""), "--size", "32x32"
    )
    assert (code, err) == (0, "")
    assert sorted(p.name for p in target.iterdir()) == [
        "preview.png",
        "preview_3d.json",
        "preview_depth.json",
        "preview_depth.npy",
        "preview_depth.png",
        "preview_ids.json",
        "preview_seg.png",
        "scene.glb",
    ]
    assert not (tmp_path / "exports.png").exists()


@pytest.mark.parametrize("argument", ["３２x32", "32x３２", "٣٢x32", "32 x32", "+32x32", "3_2x32"])
def test_size_takes_ascii_digits_only(capsys, argument):
    """Before: full-width digits ("３２x32") were taken as 32."""
    code, out, err = run(capsys, "render", "scene.json", "--size", argument)
    assert code == 2
    assert_one_line_error(err, "argument --size: expected WIDTHxHEIGHT")
    assert argument not in err or argument.isascii()


@pytest.mark.parametrize("argument", ["１", "1_0", " 1", "1e3"])
def test_seed_takes_ascii_digits_only(capsys, argument):
    code, out, err = run(capsys, "expand", "desk", "--seed", argument)
    assert code == 2
    assert_one_line_error(err, "argument --seed: expected a whole number")


def test_a_mesh_file_that_is_not_a_mesh_is_bad_input(tmp_path, capsys):
    (tmp_path / "bad.obj").write_bytes(b"garbage\x00\x01 not a mesh")
    data = scene_dict()
    data["objects"][1]["mesh"] = str(tmp_path / "bad.obj")
    path = write(tmp_path, data)
    code, out, err = run(capsys, "export", str(path), "-o", str(tmp_path / "x.glb"))
    assert code == 2
    assert_one_line_error(err, "mesh file", "bad.obj", "has no triangles")
    data["objects"][1]["mesh"] = str(tmp_path / "gone.obj")
    code, out, err = run(capsys, "validate", str(write(tmp_path, data)))
    assert code == 2
    assert out.strip().endswith(
        f"scene.json $.objects[1].mesh: the mesh file '{tmp_path / 'gone.obj'}' does not exist"
    )
