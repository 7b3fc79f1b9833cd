"""The example importers: hand-written JSON, scene.json and GLB into one Scene form."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest
import trimesh
from hypothesis import given, settings
from hypothesis import strategies as st

from scenewright.examples import ExampleError, infer_supports, load_example, load_examples
from scenewright.examples.example import ObjectRecord, example_scene
from scenewright.examples.glb import parse_node_name
from scenewright.render.export import export_glb

DESK_ROOM = {
    "name": "study",
    "room": {"corners": [[0, 0], [4, 0], [4, 3], [0, 3]], "height": 2.5},
    "objects": [
        {
            "id": "desk",
            "type": "writing_desk",
            "style": "oak",
            "size": [1.2, 0.75, 0.6],
            "position": [2, 0, 0.4],
            "yaw": 0,
        },
        {
            "id": "chair",
            "type": "stool",
            "size": [0.45, 0.9, 0.45],
            "position": [2, 0, 1.1],
            "yaw": 180,
        },
        {
            "id": "lamp",
            "type": "lamp",
            "size": [0.2, 0.4, 0.2],
            "position": [2.3, 0.5],
            "yaw": 90,
            "parent": "desk",
        },
        {"id": "book", "type": "book", "size": [0.2, 0.05, 0.3], "position": [1.7, 0.75, 0.4]},
    ],
}


def write(tmp_path, name, content):
    path = tmp_path / name
    path.write_text(content if isinstance(content, str) else json.dumps(content, indent=1))
    return path


def test_handwritten_example_reads_into_a_scene(tmp_path):
    example = load_example(write(tmp_path, "study.json", DESK_ROOM))
    assert example.format == "example.json" and example.name == "study"
    objects = {o.id: o for o in example.objects()}
    # The room's corners are centred on the origin and the objects moved with them.
    assert example.scene.extent == [4.0, 3.0]
    assert objects["desk"].position == pytest.approx([0.0, 0.0, -1.1])
    assert objects["chair"].yaw == pytest.approx(
        math.pi
    )  # degrees in the file, radians in the Scene
    # A two-number position stands on its parent's top.
    assert objects["lamp"].position == pytest.approx([0.3, 0.75, -1.0])
    assert objects["desk"].style == "oak" and objects["desk"].noun == "writing desk"
    # The lamp's support is given, the book's measured from the boxes.
    assert example.supports() == {"lamp": "desk", "book": "desk"}


def test_a_type_of_the_shipped_catalog_looks_as_the_catalog_has_it(tmp_path):
    from scenewright.examples.example import type_colour
    from scenewright.generator import indoor_catalog

    catalog = indoor_catalog()
    objects = [
        {"id": "p", "type": "plant", "size": [0.4, 1.0, 0.4], "position": [1, 1]},
        {"id": "tv", "type": "tv_stand", "size": [1.6, 0.5, 0.4], "position": [2, 1]},
        {
            "id": "w",
            "type": "wardrobe",
            "style": "white",
            "size": [1.2, 2.0, 0.6],
            "position": [0.8, 2.5],
        },
        {
            "id": "x",
            "type": "wardrobe",
            "style": "polka",
            "size": [1.2, 2.0, 0.6],
            "position": [2.5, 2.5],
        },
    ]
    room = dict(DESK_ROOM, objects=objects)
    placed = {o.id: o for o in load_example(write(tmp_path, "r.json", room)).objects()}
    assert (
        (placed["p"].noun, placed["p"].shape)
        == ("plant", catalog["plant"].shape)
        != ("plant", None)
    )
    assert placed["p"].colour == pytest.approx(list(catalog["plant"].colour))
    assert placed["tv"].noun == "TV stand"
    white = next(s for s in catalog["wardrobe"].styles if s.name == "white")
    assert placed["w"].noun == white.noun and placed["w"].colour == pytest.approx(
        list(white.colour)
    )
    assert (
        placed["x"].noun == "wardrobe" and placed["x"].style == "polka"
    )  # a style the catalog lacks: the entry's looks
    # A type the catalog does not have keeps the reader's own looks (as the study above).
    assert load_example(write(tmp_path, "s.json", DESK_ROOM)).scene.objects[
        0
    ].colour == type_colour("writing_desk")


def test_extent_example_and_names_made_unique(tmp_path):
    data = {
        "extent": [6, 5],
        "objects": [{"id": "t", "type": "table", "size": [1, 0.7, 1], "position": [0, 0]}],
    }
    first = write(tmp_path, "a.json", data)
    (tmp_path / "b").mkdir()
    second = write(tmp_path / "b", "a.json", data)
    examples = load_examples([first, second])
    assert [e.name for e in examples] == ["a", "a-2"]
    assert examples[0].scene.room is None and examples[0].scene.extent == [6.0, 5.0]


def test_a_folder_of_examples_stands_for_its_files_in_name_order(tmp_path):
    data = {
        "extent": [6, 5],
        "objects": [{"id": "t", "type": "table", "size": [1, 0.7, 1], "position": [0, 0]}],
    }
    folder = tmp_path / "set"
    folder.mkdir()
    for name in ("b.json", "a.json"):
        write(folder, name, data)
    (folder / "notes.txt").write_text("not an example")
    (folder / "generated").mkdir()  # a generate output folder: its scene.json
    write(folder / "generated", "scene.json", data)
    (folder / "empty").mkdir()
    examples = load_examples([folder])
    assert [e.name for e in examples] == ["a", "b", "generated"]
    # A folder `scenewright dataset` wrote stands for its scenes, not its settings.
    dataset = tmp_path / "data"
    (dataset / "scenes").mkdir(parents=True)
    write(dataset, "dataset.json", {"rules": "desk", "count": 2})
    write(dataset, "stats.json", {"scenes": 2})
    for name in ("000001.json", "000000.json"):
        write(dataset / "scenes", name, data)
    assert [e.name for e in load_examples([dataset])] == ["000000", "000001"]
    with pytest.raises(ExampleError, match="empty: holds no examples"):
        load_examples([folder / "empty"])
    # The shipped hand-written sets load by their folder.
    assert len(load_examples([Path(__file__).parents[1] / "examples" / "sets" / "bedrooms"])) == 10


@pytest.mark.parametrize(
    ("change", "fragments"),
    [
        (lambda d: d["objects"][1].pop("size"), ["$.objects[1]", "'size' is a required property"]),
        (
            lambda d: d["objects"][2].update(size=[1, -1, 1]),
            ["$.objects[2].size[1] (object 'lamp')"],
        ),
        (
            lambda d: d["objects"][3].update(id="desk"),
            ["$.objects[3].id", "'desk' is used by an earlier object"],
        ),
        (lambda d: d["objects"][2].update(parent="shelf"), ["$.objects[2].parent", "'shelf'"]),
        (lambda d: d["objects"][0].update(parent="lamp"), ["stands on itself"]),
        (lambda d: d["room"].update(corners=[[0, 0], [1, 1], [0, 1], [1, 0]]), ["$.room", "cross"]),
        (lambda d: d.pop("room"), ["$: needs exactly one of", "extent", "room"]),
        (lambda d: d["objects"][0].update(colour="red"), ["$.objects[0]", "colour"]),
        # Places every later stage trusts: inside the room, and touching the parent given.
        (
            lambda d: d["objects"][1].update(position=[30, 0, 1]),
            ["$.objects[1].position (object 'chair')", "outside the room"],
        ),
        (
            lambda d: d["objects"][2].update(position=[2.3, 0, 0.5]),
            ["$.objects[2].position (object 'lamp')", "top is at height 0.75", "base is at 0"],
        ),
        (
            lambda d: d["objects"][2].update(position=[3.5, 0.75, 2.5]),
            ["stands on 'desk'", "not over the footprint"],
        ),
    ],
)
def test_bad_handwritten_files_name_the_place(tmp_path, change, fragments):
    data = json.loads(json.dumps(DESK_ROOM))
    change(data)
    path = write(tmp_path, "bad.json", data)
    with pytest.raises(ExampleError) as raised:
        load_example(path)
    message = str(raised.value)
    assert "\n" not in message and message.startswith(str(path))
    for fragment in fragments:
        assert fragment in message, message


@pytest.mark.parametrize(
    ("text", "fragment"),
    [
        ('{"extent": [4, 4],\n "objects": [1, 2,]}', "bad.json:2:19: not JSON"),
        ('{"extent": [NaN, 4], "objects": []}', "NaN is not a finite number"),
        ("", "bad.json: is empty"),
    ],
)
def test_broken_json_is_located(tmp_path, text, fragment):
    path = write(tmp_path, "bad.json", text)
    with pytest.raises(ExampleError, match=fragment.replace("[", r"\[")):
        load_example(path)


def test_a_file_named_twice_is_refused_and_a_bom_is_read(tmp_path):
    folder = tmp_path / "set"
    folder.mkdir()
    path = write(folder, "a.json", DESK_ROOM)
    with pytest.raises(ExampleError, match=r"a.json: is named twice: an example counts once"):
        load_examples([folder, path])  # the folder holds it already: it would weigh double
    (tmp_path / "bom.json").write_bytes(b"\xef\xbb\xbf" + json.dumps(DESK_ROOM).encode())
    assert len(load_example(tmp_path / "bom.json").objects()) == 4


def test_unreadable_inputs(tmp_path):
    with pytest.raises(ExampleError, match="cannot read"):
        load_example(tmp_path / "missing.json")
    with pytest.raises(ExampleError, match="is a directory"):
        load_example(tmp_path)
    (tmp_path / "x.glb").write_bytes(b"glTF\x02\x00\x00\x00junk")
    with pytest.raises(ExampleError, match="x.glb: not a GLB file"):
        load_example(tmp_path / "x.glb")
    with pytest.raises(ExampleError, match="no example files"):
        load_examples([])


def test_scene_json_keeps_the_grammar_relations(tmp_path):
    example = load_example(write(tmp_path, "a.json", DESK_ROOM))
    folder = tmp_path / "scene"
    folder.mkdir()
    (folder / "scene.json").write_text(example.scene.to_json())
    again = load_example(folder)
    assert again.format == "scene.json" and again.name == "scene"
    assert [o.id for o in again.objects()] == [o.id for o in example.objects()]
    assert again.supports() == example.supports()
    broken = json.loads(example.scene.to_json())
    broken["objects"][0]["size"] = [1, 2]
    (folder / "scene.json").write_text(json.dumps(broken))
    with pytest.raises(ExampleError, match=r"scene.json: \$.objects\[0\].size"):
        load_example(folder)


@pytest.mark.parametrize(
    ("name", "expected"),
    [
        ("desk.oak.001", ("desk", "oak")),
        ("desk.001", ("desk", None)),
        ("desk", ("desk", None)),
        ("desk_3", ("desk", None)),
        ("office chair.black", ("office_chair", "black")),
        ("Dining Chair.002", ("dining_chair", None)),
        ("Wall.001", ("wall", None)),
        ("Desk.Oak", ("desk", "oak")),
    ],
)
def test_node_names(name, expected):
    assert parse_node_name(name) == expected


def blender_style_glb(tmp_path, nodes):
    """A GLB whose nodes carry (name, mesh in its own frame, 4x4 transform)."""
    scene = trimesh.Scene()
    for name, mesh, transform in nodes:
        scene.add_geometry(mesh, node_name=name, geom_name=name, transform=transform)
    path = tmp_path / "room.glb"
    path.write_bytes(scene.export(file_type="glb"))
    return path


def pose(x, y, z, yaw_degrees, scale=1.0):
    matrix = trimesh.transformations.rotation_matrix(math.radians(yaw_degrees), [0, 1, 0])
    matrix[:3, :3] *= scale
    matrix[:3, 3] = (x, y, z)
    return matrix


def test_blender_style_glb(tmp_path):
    # Blender meshes have their origin where the modeller left it: here at the box centre.
    desk = trimesh.creation.box([1.4, 0.76, 0.7])
    lamp = trimesh.creation.box([0.1, 0.2, 0.1])  # scaled x2 by its node
    wall = trimesh.creation.box([6.2, 2.5, 0.1])
    end_wall = trimesh.creation.box([4.2, 2.5, 0.1])
    path = blender_style_glb(
        tmp_path,
        [
            ("desk.oak.001", desk, pose(1.0, 0.38, 0.5, 90)),
            ("lamp.002", lamp, pose(1.1, 0.76 + 0.2, 0.4, 30, scale=2.0)),
            ("wall.north", wall, pose(0.0, 1.25, -2.05, 0)),
            ("wall.south", wall, pose(0.0, 1.25, 2.05, 0)),
            ("wall.east", end_wall, pose(3.05, 1.25, 0.0, 90)),
            ("wall.west", end_wall, pose(-3.05, 1.25, 0.0, 90)),
        ],
    )
    example = load_example(path)
    objects = {o.id: o for o in example.objects()}
    assert set(objects) == {"desk.oak.001", "lamp.002"}
    desk_object, lamp_object = objects["desk.oak.001"], objects["lamp.002"]
    assert (desk_object.type, desk_object.style) == ("desk", "oak")
    assert desk_object.size == pytest.approx([1.4, 0.76, 0.7])
    assert desk_object.position == pytest.approx([1.0, 0.0, 0.5], abs=1e-6)
    assert desk_object.yaw == pytest.approx(math.pi / 2)
    assert lamp_object.size == pytest.approx([0.2, 0.4, 0.2]) and lamp_object.yaw == pytest.approx(
        math.radians(30)
    )
    assert example.supports() == {"lamp.002": "desk.oak.001"}
    assert example.scene.room is not None and example.scene.extent == pytest.approx([6.0, 4.0])


def test_blender_default_names_and_unnamed_nodes(tmp_path):
    box = trimesh.creation.box([1.0, 0.8, 1.0])
    wall = trimesh.creation.box([4.2, 2.5, 0.1])
    side = trimesh.creation.box([0.1, 2.5, 4.2])
    path = blender_style_glb(
        tmp_path,
        [
            ("Dining Table", box, pose(0, 0.4, 0, 0)),
            ("Wall", wall, pose(0, 1.25, -2.05, 0)),
            ("Wall.001", wall, pose(0, 1.25, 2.05, 0)),
            ("Wall.002", side, pose(2.05, 1.25, 0, 0)),
            ("Wall.003", side, pose(-2.05, 1.25, 0, 0)),
        ],
    )
    example = load_example(path)
    assert [(o.id, o.type) for o in example.objects()] == [("Dining_Table", "dining_table")]
    assert example.scene.room is not None and example.scene.extent == pytest.approx([4.0, 4.0])
    # A mesh node without a name says nothing of what it is.
    scene = trimesh.Scene()
    scene.add_geometry(box, geom_name="mesh")
    document = scene.export(file_type="glb")
    length = int.from_bytes(document[12:16], "little")
    chunk = json.loads(document[20 : 20 + length])
    for node in chunk["nodes"]:
        node.pop("name", None)
    text = (
        json.dumps(chunk, separators=(",", ":")).encode().ljust(length)
    )  # shorter: the name is gone
    (tmp_path / "unnamed.glb").write_bytes(document[:20] + text + document[20 + length :])
    with pytest.raises(ExampleError, match="unnamed.glb: node 0: has no name"):
        load_example(tmp_path / "unnamed.glb")


def test_tilted_node_is_refused(tmp_path):
    tilted = trimesh.transformations.rotation_matrix(math.radians(20), [1, 0, 0])
    path = blender_style_glb(tmp_path, [("chair", trimesh.creation.box([0.5, 0.9, 0.5]), tilted)])
    with pytest.raises(ExampleError, match="node 'chair': is tilted 20 degrees"):
        load_example(path)


@settings(max_examples=15, deadline=None)
@given(
    st.lists(
        st.tuples(
            st.floats(-2.0, 2.0),
            st.floats(-2.0, 2.0),
            st.floats(-math.pi + 0.01, math.pi),
            st.floats(0.1, 2.0),
            st.floats(0.1, 2.0),
            st.floats(0.1, 2.0),
        ),
        min_size=1,
        max_size=5,
    )
)
def test_glb_round_trip_of_our_own_export(tmp_path_factory, boxes):
    records = [
        ObjectRecord(f"box_{k}", "crate", (w, h, d), (x, 0.0, z), yaw, "pine" if k % 2 else None)
        for k, (x, z, yaw, w, h, d) in enumerate(boxes)
    ]
    scene = example_scene(records, name="s", source="s", extent=(8.0, 8.0), room=None)
    path = tmp_path_factory.mktemp("glb") / "s.glb"
    export_glb(scene, path)
    again = load_example(path).objects()
    assert [o.id for o in again] == [o.id for o in scene.objects]
    offset = np.mean([o.position for o in again], axis=0) - np.mean(
        [o.position for o in scene.objects], axis=0
    )
    for before, after in zip(scene.objects, again, strict=False):
        assert (after.type, after.style) == (before.type, before.style)
        assert after.size == pytest.approx(before.size, abs=1e-5)
        # The file's frame is re-centred on the objects' bounds: every object moves alike.
        assert np.subtract(after.position, before.position) == pytest.approx(offset, abs=1e-5)
        turn = (after.yaw - before.yaw + math.pi) % (2 * math.pi) - math.pi
        assert abs(turn) < 1e-5


def test_stacking_rules():
    records = [
        ObjectRecord("rug", "rug", (2.0, 0.01, 2.0), (0.0, 0.0, 0.0), 0.0),
        ObjectRecord(
            "table", "table", (1.0, 0.7, 1.0), (0.0, 0.0, 0.0), 0.0
        ),  # on the floor, over the rug
        ObjectRecord("box", "box", (0.3, 0.3, 0.3), (0.4, 0.7, 0.0), 0.0),
        ObjectRecord(
            "cup", "cup", (0.1, 0.1, 0.1), (0.4, 1.0, 0.0), 0.0
        ),  # on the box, not the table
        ObjectRecord(
            "ball", "ball", (0.1, 0.1, 0.1), (0.9, 0.7, 0.0), 0.0
        ),  # past the table's edge: floats
    ]
    scene = example_scene(records, name="s", source="s", extent=(4.0, 4.0), room=None)
    assert infer_supports(scene.objects) == {"box": "table", "cup": "box"}
