"""GLB export: node names and extras, hierarchy, poses, validity for Khronos' validator."""

import io
import json
import os
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest
import trimesh
from render_fixtures import market_scene, road, scene_of, thing

from scenewright.core import VERSION
from scenewright.core.relations import Relation
from scenewright.examples.glb import read_glb
from scenewright.render.export import (
    CAMERA_NODE,
    GROUND_NODE,
    SUN_NODE,
    export_glb,
    glb_bytes,
    preview_camera,
)
from scenewright.render.meshes import object_transform
from scenewright.render.offscreen import SUN_DIRECTION

ROOT = Path(__file__).resolve().parent.parent
VALIDATOR_MODULES = ROOT / ".tools" / "node_modules"


@pytest.fixture(scope="module")
def glb_path(tmp_path_factory):
    return export_glb(market_scene(), tmp_path_factory.mktemp("glb") / "market.glb")


@pytest.fixture(scope="module")
def loaded(glb_path):
    return trimesh.load(glb_path)


def test_one_named_node_per_entity(glb_path):
    names = {node["name"] for node in _gltf_json(glb_path)["nodes"]}
    assert names == {
        "market_stand_1",
        "table_1",
        "sign_1",
        "house_1",
        "crossing_1",
        "road_1",
        GROUND_NODE,
        CAMERA_NODE,
        SUN_NODE,
    }


def test_nodes_carry_their_scene_data_in_extras(glb_path):
    nodes = {node["name"]: node for node in _gltf_json(glb_path)["nodes"]}
    assert nodes["house_1"]["extras"] == {
        "id": "house_1",
        "type": "house",
        "kind": "object",
        "noun": "house",
    }
    assert nodes["market_stand_1"]["extras"]["kind"] == "group"
    assert nodes["road_1"]["extras"]["kind"] == "path"
    assert "mesh" not in nodes["market_stand_1"]  # a group is only a parent


def test_groups_are_parents_of_their_members(loaded):
    parents = {child: parent for parent, child, _ in loaded.graph.to_edgelist()}
    assert parents["table_1"] == parents["sign_1"] == "market_stand_1"
    assert parents["house_1"] == loaded.graph.base_frame


def test_world_poses_survive_the_round_trip(loaded):
    scene = market_scene()
    for object_id in ("table_1", "house_1"):
        world, _ = loaded.graph[object_id]
        assert np.allclose(world, object_transform(scene.object(object_id)), atol=1e-6)
    house = loaded.geometry["house_1"]
    assert np.allclose(house.extents, [4, 3, 5], atol=1e-6)  # local frame, fitted to size


def test_export_is_deterministic_and_leaves_no_temporary_files(glb_path):
    assert glb_bytes(market_scene()) == glb_path.read_bytes()
    assert [p.name for p in glb_path.parent.iterdir()] == [glb_path.name]


def test_khronos_validator_reports_no_errors(glb_path):
    node = shutil.which("node")
    if node is None or not (VALIDATOR_MODULES / "gltf-validator").is_dir():
        if os.environ.get("CI") and node is not None:
            pytest.fail("CI has node but no gltf-validator: run scripts/setup.sh")
        pytest.skip("glTF validator not installed (scripts/setup.sh installs it when npm exists)")
    done = subprocess.run(
        [node, str(ROOT / "tests" / "validate_gltf.js"), str(glb_path)],
        env=dict(os.environ, NODE_PATH=str(VALIDATOR_MODULES)),
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert done.returncode == 0, done.stderr
    issues = json.loads(done.stdout)["issues"]
    assert issues["numErrors"] == 0, issues["messages"]
    assert issues["numWarnings"] == 0, issues["messages"]


def _gltf_json(path: Path) -> dict:
    data = path.read_bytes()
    length = int.from_bytes(data[12:16], "little")  # first chunk: the JSON
    return json.loads(data[20 : 20 + length])


def test_a_degenerate_path_still_gets_its_node(tmp_path):
    scene = scene_of([thing("crate_1")], [road("road_1", [[3, 3], [3, 3]], start="crossing_1")])
    loaded = trimesh.load(export_glb(scene, tmp_path / "flat.glb"))
    assert {"crate_1", "road_1"} <= set(loaded.graph.nodes)
    assert "road_1" not in loaded.graph.nodes_geometry


def test_one_shared_pbr_material_per_colour(glb_path):
    document = _gltf_json(glb_path)
    colours = [tuple(m["pbrMetallicRoughness"]["baseColorFactor"]) for m in document["materials"]]
    assert len(colours) == len(set(colours))  # shared, not one per mesh
    nodes = {node["name"]: node for node in document["nodes"]}
    for name, colour in (("table_1", (0.8, 0.3, 0.2)), ("sign_1", (0.2, 0.2, 0.9))):
        used = {p["material"] for p in document["meshes"][nodes[name]["mesh"]]["primitives"]}
        assert len(used) == 1
        pbr = document["materials"][used.pop()]["pbrMetallicRoughness"]
        assert np.allclose(pbr["baseColorFactor"][:3], colour, atol=0.003)
        assert pbr["metallicFactor"] == 0.0
        assert 0.5 <= pbr["roughnessFactor"] <= 1.0


def test_vertices_carry_flat_unit_normals(glb_path):
    document = _gltf_json(glb_path)
    nodes = {node["name"]: node for node in document["nodes"]}
    binary = _bin_chunk(glb_path.read_bytes())
    for name in ("table_1", "house_1", "road_1", GROUND_NODE):
        for primitive in document["meshes"][nodes[name]["mesh"]]["primitives"]:
            points = _accessor(document, binary, primitive["attributes"]["POSITION"])
            normals = _accessor(document, binary, primitive["attributes"]["NORMAL"])
            assert np.allclose(np.linalg.norm(normals, axis=1), 1.0, atol=1e-6)
            corners = points.reshape(-1, 3, 3).astype(float)
            faces = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
            faces /= np.linalg.norm(faces, axis=1)[:, None]
            # Flat: each triangle's three vertex normals are its face's normal.
            assert np.allclose(normals.reshape(-1, 3, 3), faces[:, None, :], atol=1e-4)


def test_generator_camera_and_sun(glb_path):
    document = _gltf_json(glb_path)
    assert document["asset"]["generator"] == f"scenewright {VERSION}"
    nodes = {node["name"]: node for node in document["nodes"]}
    view = preview_camera(market_scene())
    lens = document["cameras"][nodes[CAMERA_NODE]["camera"]]
    assert lens["perspective"]["yfov"] == pytest.approx(view.yfov)
    assert np.allclose(_node_matrix(nodes[CAMERA_NODE]), view.pose, atol=1e-9)
    light_index = nodes[SUN_NODE]["extensions"]["KHR_lights_punctual"]["light"]
    sun = document["extensions"]["KHR_lights_punctual"]["lights"][light_index]
    assert sun["type"] == "directional" and sun["intensity"] > 0
    shines = -_node_matrix(nodes[SUN_NODE])[:3, 2]  # a directional light shines along -Z
    assert np.allclose(shines, SUN_DIRECTION / np.linalg.norm(SUN_DIRECTION))
    assert document["extensionsUsed"] == ["KHR_lights_punctual"]


def test_camera_light_and_ground_can_be_left_out():
    data = glb_bytes(market_scene(), ground=False, camera=False, light=False)
    document = json.loads(_json_chunk(data))
    names = {node["name"] for node in document["nodes"]}
    assert not names & {GROUND_NODE, CAMERA_NODE, SUN_NODE}
    assert "cameras" not in document and "extensions" not in document


def _supported_market():
    """The market, with a pot resting on the table and a lid on the pot."""
    scene = market_scene()
    scene.objects += [
        thing("pot_1", (2, 0.8, 0), (0.3, 0.2, 0.3), parent="market_stand_1", yaw=0.3),
        thing("lid_1", (2, 1.0, 0), (0.3, 0.02, 0.3), parent="market_stand_1"),
    ]
    scene.relations = [
        Relation("pot_1", "table_1", "OnTopOf"),
        Relation("lid_1", "pot_1", "OnTopOf"),
        Relation("sign_1", "house_1", "NextTo"),
    ]
    return scene


def test_what_rests_on_something_is_its_child():
    scene = _supported_market()
    loaded = trimesh.load(io.BytesIO(glb_bytes(scene)), file_type="glb")
    parents = {child: parent for parent, child, _ in loaded.graph.to_edgelist()}
    assert parents["pot_1"] == "table_1"
    assert parents["lid_1"] == "pot_1"
    assert parents["table_1"] == parents["sign_1"] == "market_stand_1"
    for object_id in ("pot_1", "lid_1", "table_1"):
        world, _ = loaded.graph[object_id]
        assert np.allclose(world, object_transform(scene.object(object_id)), atol=1e-6)
    nodes = {n["name"]: n for n in json.loads(_json_chunk(glb_bytes(scene)))["nodes"]}
    assert nodes["pot_1"]["extras"]["on"] == "table_1"
    assert nodes["pot_1"]["extras"]["group"] == "market_stand_1"


def test_a_support_loop_in_a_hand_edited_scene_is_broken():
    scene = _supported_market()
    scene.relations.append(Relation("table_1", "lid_1", "OnTopOf"))  # table on lid on pot on table
    loaded = trimesh.load(io.BytesIO(glb_bytes(scene)), file_type="glb")
    parents = {child: parent for parent, child, _ in loaded.graph.to_edgelist()}
    assert parents["table_1"] == "market_stand_1"


def test_moving_the_table_in_the_file_moves_what_rests_on_it():
    """Round trip: export, move the table node as a 3D tool does, read the file back
    as an example scene: the pot and its lid moved with the table, nothing else did."""
    scene = _supported_market()
    data = glb_bytes(scene)
    document = json.loads(_json_chunk(data))
    table = next(node for node in document["nodes"] if node["name"] == "table_1")
    table["translation"][0] += 1.5
    edited = _with_json(data, document)
    before = read_glb("before.glb", data, "market")
    after = read_glb("after.glb", edited, "market")
    for object_id in ("table_1", "pot_1", "lid_1"):
        moved = np.subtract(after.object(object_id).position, before.object(object_id).position)
        assert np.allclose(moved, [1.5, 0, 0], atol=1e-5)
        assert after.object(object_id).type == scene.object(object_id).type
    assert np.allclose(after.object("house_1").position, before.object("house_1").position)


def _json_chunk(data: bytes) -> bytes:
    return data[20 : 20 + int.from_bytes(data[12:16], "little")]


def _bin_chunk(data: bytes) -> bytes:
    start = 20 + int.from_bytes(data[12:16], "little")
    return data[start + 8 : start + 8 + int.from_bytes(data[start : start + 4], "little")]


def _with_json(data: bytes, document: dict) -> bytes:
    """``data`` (a GLB) with its JSON chunk replaced by ``document``."""
    text = json.dumps(document).encode()
    text += b" " * (-len(text) % 4)
    rest = data[20 + int.from_bytes(data[12:16], "little") :]
    body = len(text).to_bytes(4, "little") + b"JSON" + text + rest
    return b"glTF" + (2).to_bytes(4, "little") + (12 + len(body)).to_bytes(4, "little") + body


def _accessor(document: dict, binary: bytes, index: int) -> np.ndarray:
    accessor = document["accessors"][index]
    view = document["bufferViews"][accessor["bufferView"]]
    raw = binary[view["byteOffset"] : view["byteOffset"] + view["byteLength"]]
    return np.frombuffer(raw, dtype="<f4").reshape(accessor["count"], 3)


def _node_matrix(node: dict) -> np.ndarray:
    matrix = np.eye(4)
    if "rotation" in node:
        x, y, z, w = node["rotation"]
        matrix[:3, :3] = trimesh.transformations.quaternion_matrix([w, x, y, z])[:3, :3]
    matrix[:3, 3] = node.get("translation", [0.0, 0.0, 0.0])
    return matrix
