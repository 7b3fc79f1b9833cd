"""Shapes and mesh files: the registry the checks and the renderer share, and its checks.

The registry names exactly the renderer's builders (the renderer will not import
otherwise) and states each shape's front truthfully; ``validate`` warns about a shape
it lacks; a mesh file that does not load is a located input error (exit 2) from
``validate`` and ``generate`` alike, and still an input error if the renderer meets it
later; ``list --shapes`` prints the registry; the rules-language docs list it.
"""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import trimesh

from scenewright.cli import main
from scenewright.core.errors import InputError, MeshFileError
from scenewright.core.shapes import MAX_MESH_BYTES, SHAPES, load_mesh_file
from scenewright.generator import check_rules, load_rules, shipped_rule_sets
from scenewright.render.builders import BUILDERS, ShapeRegistryMismatch, check_registry
from scenewright.render.mesh_parts import shade
from scenewright.render.meshes import shaped_mesh

DOCS = Path(__file__).parents[1] / "docs" / "rules-language.md"
#: A small rule set with one object whose look is the line under test.
RULES = 'scene s {{ start S }}\nobject crate {{ noun "crate" {look} }}\nS -> {{ crate }}\n'
#: The column of the look's field (``shape`` or ``mesh``) on line 2, counted from 1.
LOOK_COLUMN = len('object crate { noun "crate" ') + 1


def run(capsys, *argv: str) -> tuple[int, str, str]:
    code = main(list(argv))
    captured = capsys.readouterr()
    return code, captured.out, captured.err


def rules_with(folder: Path, look: str) -> Path:
    path = folder / "crates.rules"
    path.write_text(RULES.format(look=look))
    return path


# -- the registry and the builders ------------------------------------------------------


def test_registry_names_exactly_the_builders():
    assert set(SHAPES) == set(BUILDERS)
    assert list(SHAPES) == sorted(SHAPES), "kept in alphabetical order, as listed"
    for name, shape in SHAPES.items():
        assert shape.name == name
        for text in (shape.description, shape.front, shape.used_from):
            assert text.strip() and "\n" not in text and len(text) <= 72, (name, text)


def test_every_shape_the_shipped_rule_sets_use_is_registered():
    for name in shipped_rule_sets():
        assert not [d for d in check_rules(name) if "unknown shape" in d.message], name


def test_check_registry_names_what_differs():
    box = BUILDERS["box"]
    check_registry({"box": box}, {"box": SHAPES["box"]})
    with pytest.raises(ShapeRegistryMismatch, match="builders with no entry .*: crate$"):
        check_registry({"box": box, "crate": box}, {"box": SHAPES["box"]})
    with pytest.raises(ShapeRegistryMismatch, match="shapes .* with no builder: box, well$"):
        check_registry({}, {"box": SHAPES["box"], "well": SHAPES["well"]})


@pytest.mark.parametrize(
    "change, message",
    [
        (
            "del shapes.SHAPES['well']",
            "builders with no entry in scenewright.core.shapes.SHAPES: well",
        ),
        ("shapes.SHAPES['crate_stack'] = shapes.SHAPES['box']", "with no builder: crate_stack"),
    ],
)
def test_the_renderer_refuses_to_import_when_the_registry_differs(change, message):
    """A fresh interpreter, so the real module's import-time check runs on the changed registry."""
    program = (
        f"import scenewright.core.shapes as shapes\n{change}\nimport scenewright.render.builders\n"
    )
    result = subprocess.run(
        [sys.executable, "-c", program], capture_output=True, text=True, timeout=120
    )
    assert result.returncode != 0
    assert "ShapeRegistryMismatch" in result.stderr and message in result.stderr


# -- what the registry says about fronts is what the builders build ----------------------


MAIN = (0.5, 0.1, 0.9)


def built(shape: str, size=(1.2, 1.0, 0.8)) -> trimesh.Trimesh:
    return BUILDERS[shape](size, MAIN)


def centres_of_colour(mesh: trimesh.Trimesh, colour) -> np.ndarray:
    """Centres of the faces painted ``colour`` (how a builder tells its parts apart)."""
    rgb = np.round(np.asarray(colour) * 255)
    return mesh.triangles_center[np.all(mesh.visual.face_colors[:, :3] == rgb, axis=1)]


@pytest.mark.parametrize(
    "shape, part_colour, axis, said",
    [
        ("desk", shade(MAIN, 0.85), 0, "pedestal on its right (-X)"),
        ("book", shade(MAIN, 0.8), 0, "spine on its right (-X)"),
        ("forge", shade(MAIN, 0.9), 2, "chimney at the back (-Z)"),
        ("bookshelf", shade(MAIN, 0.8), 2, "back board at -Z"),
        ("sign", shade(MAIN, 0.7), 2, "posts at -Z"),
    ],
)
def test_a_part_said_to_be_on_the_negative_side_is_there(shape, part_colour, axis, said):
    assert said in SHAPES[shape].front
    part = centres_of_colour(built(shape), part_colour)
    assert len(part) and np.all(part[:, axis] < 0)


def test_the_hammer_head_and_the_anvil_horn_point_left():
    assert "+X" in SHAPES["hammer"].front and "+X" in SHAPES["anvil"].front
    head = centres_of_colour(built("hammer"), MAIN)
    assert len(head) and np.all(head[:, 0] > 0)
    vertices = built("anvil").vertices
    x = vertices[:, 0]
    tip, far_end = vertices[np.isclose(x, x.max())], vertices[np.isclose(x, x.min())]
    assert np.ptp(tip[:, 2]) < 1e-9  # the horn comes to a point at +X
    assert np.ptp(far_end[:, 2]) > 0.5 * 0.8  # the face block's full end at -X


# -- validate: unknown shapes ------------------------------------------------------------


def test_unknown_shape_warns_with_did_you_mean(tmp_path, capsys):
    assert "wardrobe" in SHAPES and "wardrob" not in SHAPES
    rules = rules_with(tmp_path, "shape wardrob")
    (diagnostic,) = check_rules(rules)
    assert diagnostic.severity == "warning"
    assert (diagnostic.location.line, diagnostic.location.column) == (
        2,
        LOOK_COLUMN + len("shape "),
    )
    assert (
        diagnostic.message
        == "unknown shape 'wardrob', drawn as a plain box; did you mean 'wardrobe'?"
    )
    code, out, _ = run(capsys, "validate", str(rules))
    assert code == 0
    first, line, caret, verdict = out.splitlines()
    assert first == f"{rules}:2:{LOOK_COLUMN + 6}: warning: {diagnostic.message}"
    assert line.strip() == 'object crate { noun "crate" shape wardrob }'
    assert caret.index("^") == line.index("wardrob")
    assert verdict == f"{rules}: ok (1 warning)"


def test_unknown_shape_with_nothing_close_points_at_the_list(tmp_path):
    (diagnostic,) = check_rules(rules_with(tmp_path, "shape zeppelin"))
    assert diagnostic.message == (
        "unknown shape 'zeppelin', drawn as a plain box; 'scenewright list --shapes' lists the shapes"
    )


def test_known_shapes_and_styles_with_unknown_shapes(tmp_path):
    assert check_rules(rules_with(tmp_path, "shape wardrobe")) == []
    (diagnostic,) = check_rules(rules_with(tmp_path, "shape box style old { shape bookshelve }"))
    assert diagnostic.message.endswith("did you mean 'bookshelf'?")


# -- mesh files --------------------------------------------------------------------------


def good_glb(path: Path) -> Path:
    path.parent.mkdir(parents=True, exist_ok=True)
    trimesh.creation.box(extents=(1.0, 2.0, 3.0)).export(path)
    return path


def make_garbage_glb(path: Path) -> str:
    path.write_bytes(b"\x8f\x12not a binary glTF\x00" * 64)
    return "is not a valid .glb file (it does not start with a binary glTF header)"


def make_cut_short_glb(path: Path) -> str:
    whole = trimesh.creation.box().export(file_type="glb")
    path.write_bytes(whole[: len(whole) // 2])
    return (
        f"is not a valid .glb file (its header gives {len(whole)} bytes "
        f"but the file has only {len(whole) // 2}: cut short)"
    )


def make_empty_obj(path: Path) -> str:
    path.write_bytes(b"")
    return "is empty"


def make_obj_without_faces(path: Path) -> str:
    path.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\n")
    return "has no triangles"


def make_directory(path: Path) -> str:
    path.mkdir()
    return "is a directory, not a file"


def make_pipe(path: Path) -> str:
    os.mkfifo(path)
    return "is not a regular file"


def make_huge(path: Path) -> str:
    with path.open("wb") as stream:  # sparse: its size is all there is to read
        stream.truncate(MAX_MESH_BYTES + 1)
    return "is 256.1 MiB, more than the 256 MiB a mesh may hold"


def make_gltf_with_missing_buffer(path: Path) -> str:
    path.write_text(
        '{"asset": {"version": "2.0"}, "buffers": [{"uri": "crate.bin", "byteLength": 8}]}'
    )
    return "refers to 'crate.bin', which does not exist"


def make_gltf_reaching_outside(path: Path) -> str:
    path.write_text(
        '{"asset": {"version": "2.0"}, "buffers": [{"uri": "../secret.bin", "byteLength": 8}]}'
    )
    return "refers to '../secret.bin', outside its folder"


BAD_MESHES = {
    "crate.glb": make_garbage_glb,
    "half.glb": make_cut_short_glb,
    "crate.obj": make_empty_obj,
    "lines.obj": make_obj_without_faces,
    "folder.glb": make_directory,
    "pipe.stl": make_pipe,
    "huge.glb": make_huge,
    "crate.gltf": make_gltf_with_missing_buffer,
    "escape.gltf": make_gltf_reaching_outside,
}


@pytest.mark.parametrize("name", sorted(BAD_MESHES))
def test_bad_mesh_is_a_located_error(tmp_path, name):
    (tmp_path / "models").mkdir()
    reason = BAD_MESHES[name](tmp_path / "models" / name)
    (diagnostic,) = check_rules(rules_with(tmp_path, f'mesh "models/{name}"'))
    assert diagnostic.severity == "error"
    assert (diagnostic.location.line, diagnostic.location.column) == (2, LOOK_COLUMN + len("mesh "))
    assert diagnostic.message == f"mesh file 'models/{name}' {reason}"


def test_good_meshes_load_and_are_fitted(tmp_path):
    good_glb(tmp_path / "models" / "crate.glb")
    trimesh.creation.box().export(tmp_path / "models" / "crate.obj")
    trimesh.creation.box().export(tmp_path / "models" / "crate.gltf")  # with its .bin buffers
    for name in ("crate.glb", "crate.obj", "crate.gltf"):
        assert check_rules(rules_with(tmp_path, f'mesh "models/{name}"')) == []
        assert len(load_mesh_file(tmp_path / "models" / name).faces) == 12
    mesh = shaped_mesh(
        None, str(tmp_path / "models" / "crate.glb"), (0.5, 0.5, 0.5), (0.2, 0.3, 0.4)
    )
    np.testing.assert_allclose(mesh.bounds, [[-0.25, 0.0, -0.25], [0.25, 0.5, 0.25]])


def test_validate_and_generate_exit_2_on_a_corrupt_glb(tmp_path, capsys):
    (tmp_path / "models").mkdir()
    reason = make_garbage_glb(tmp_path / "models" / "crate.glb")
    rules = rules_with(tmp_path, 'mesh "models/crate.glb"')
    located = f"{rules}:2:{LOOK_COLUMN + 5}: error: mesh file 'models/crate.glb' {reason}"
    excerpt = [
        '    object crate { noun "crate" mesh "models/crate.glb" }',
        "    " + " " * len('object crate { noun "crate" mesh ') + "^",
    ]

    code, out, _ = run(capsys, "validate", str(rules))
    assert code == 2 and out.splitlines() == [located, *excerpt]

    code, out, err = run(capsys, "generate", str(rules), "--no-render", "-o", str(tmp_path / "out"))
    assert code == 2 and out == ""
    assert err.splitlines() == [located, *excerpt]
    assert not (tmp_path / "out").exists()


def test_the_renderer_meets_a_mesh_spoilt_after_validation(tmp_path):
    mesh_file = good_glb(tmp_path / "models" / "late.glb")
    rules = load_rules(rules_with(tmp_path, 'mesh "models/late.glb"'))
    assert rules.catalog["crate"].mesh == str(mesh_file)
    make_garbage_glb(mesh_file)
    with pytest.raises(MeshFileError) as raised:
        shaped_mesh(None, str(mesh_file), (1.0, 1.0, 1.0), (0.5, 0.5, 0.5))
    assert isinstance(raised.value, InputError) and raised.value.exit_code == 2
    assert str(raised.value) == f"mesh file '{mesh_file}' " + make_garbage_glb(
        tmp_path / "again.glb"
    )


def test_a_file_of_another_type_is_refused_before_it_is_read(tmp_path):
    """The suffix is checked first: this file does not even exist."""
    with pytest.raises(MeshFileError) as raised:
        load_mesh_file(tmp_path / "notes.txt")
    assert raised.value.reason == "is not a .glb, .gltf, .obj, .ply or .stl file"


# -- list --shapes and the docs ------------------------------------------------------------


def test_list_shapes_prints_the_registry_aligned(capsys):
    code, out, _ = run(capsys, "list", "--shapes")
    assert code == 0
    header, *rows = out.splitlines()
    assert (
        header.split()[0] == "shape"
        and "front (local +Z" in header
        and header.endswith("used from")
    )
    assert [row.split()[0] for row in rows] == list(SHAPES)
    front_at, used_at = header.index("front"), header.index("used from")
    for row, shape in zip(rows, SHAPES.values(), strict=False):
        assert row[front_at:].startswith(shape.front) and row[used_at:] == shape.used_from


def test_list_help_shows_the_shapes_example(capsys):
    with pytest.raises(SystemExit):
        main(["list", "--help"])
    assert "scenewright list --shapes" in capsys.readouterr().out


def test_the_rules_language_docs_list_the_registry():
    section = DOCS.read_text().split("\n## Shapes\n", 1)[1].split("\n## ", 1)[0]
    rows = re.findall(r"^\| `(\w+)` \| (.+?) \| (.+?) \| (.+?) \|$", section, flags=re.MULTILINE)
    assert rows == [(s.name, s.description, s.front, s.used_from) for s in SHAPES.values()]
