"""A house drawn and exported: its walls (each shared wall once), doors, windows and
floors in the preview, the plan image, the GLB and the USD stage."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
import trimesh
from render_fixtures import renderer_or_skip, scene_of, thing
from test_render_room import _validate_if_possible

from scenewright.core.house import room_of
from scenewright.house import house_of
from scenewright.house.assemble import house_scene
from scenewright.render import plan_image
from scenewright.render.camera import frame_scene
from scenewright.render.export import export_glb
from scenewright.render.house_meshes import house_opening_mesh, house_walls
from scenewright.render.house_view import (
    CUT_HEIGHT,
    opening_pose,
    opening_wall,
    wall_heights,
    wall_name,
    wall_owner,
    wall_reach,
)
from scenewright.render.meshes import object_transform

PLAN = """plan apartment {
    noun "flat"
    footprint 11..15 x 8..11
    room hall area 6..12 entrance width 1.2
    room living_room
    room kitchen
    room bathroom
    room bedroom 2
    connect hall bedroom bathroom living_room
    open kitchen living_room
}
"""
SEED = 2


@pytest.fixture(scope="module")
def scene(tmp_path_factory):
    """The flat of seed 2, each room holding one crate in its middle (no layout: fast)."""
    plan = tmp_path_factory.mktemp("plan") / "flat.rules"
    plan.write_text(PLAN)
    house = house_of(plan, SEED)
    rooms = [
        scene_of([thing("crate_1", size=(0.6, 0.5, 0.6))], room=room.room) for room in house.rooms
    ]
    return house_scene(house, rooms, rules="flat", seed=SEED, name="flat")


def _wall_points(loaded, name: str) -> np.ndarray:
    """World vertices (N, 3) of a node's mesh in a loaded GLB (trimesh gives each of its
    primitives a child node)."""
    parts = []
    for child in loaded.graph.transforms.children[name]:
        world, geometry = loaded.graph[child]
        parts.append(trimesh.transform_points(loaded.geometry[geometry].vertices, world))
    return np.vstack(parts)


def _gltf(path: Path) -> dict:
    data = path.read_bytes()
    return json.loads(data[20 : 20 + int.from_bytes(data[12:16], "little")])


def test_the_plan_has_shared_walls_to_check(scene):
    house = scene.house
    assert len(house.rooms) >= 5
    assert sum(not wall.outside for wall in house.walls) >= 4
    assert any(door.open for door in house.doors) and house.entrance is not None


def test_a_side_view_cuts_inner_and_near_walls_and_keeps_the_far_ones(scene):
    house = scene.house
    assert wall_heights(house, [0.0, 1.0, 0.0]) == [wall.height for wall in house.walls]
    towards = [0.0, 1.0, 1.0]  # from the south: the north walls are the far ones
    heights = wall_heights(house, towards)
    north = min(z for _x, z in house.footprint)
    for wall, height in zip(house.walls, heights, strict=True):
        far = wall.outside and abs(wall.start[1] - north) < 1e-6 and abs(wall.end[1] - north) < 1e-6
        assert height == pytest.approx(wall.height if far else CUT_HEIGHT), wall
    assert sum(h > CUT_HEIGHT for h in heights) >= 2


def test_every_opening_sits_in_its_wall_facing_its_first_room(scene):
    house = scene.house
    for opening in house.openings:
        index = opening_wall(house, opening)
        assert index is not None, opening.id
        wall = house.walls[index]
        mesh = house_opening_mesh(opening)
        mesh.apply_transform(opening_pose(house, opening))
        # within the wall's thickness about its centre line, and the right width along it
        (sx, sz), (dx, dz) = wall.start, opening.direction
        offsets = (mesh.vertices[:, 0] - sx) * -dz + (mesh.vertices[:, 2] - sz) * dx
        assert np.abs(offsets).max() <= wall.thickness / 2 + 1e-6
        along = (mesh.vertices[:, 0] - opening.center[0]) * dx + (
            mesh.vertices[:, 2] - opening.center[1]
        ) * dz
        assert along.max() - along.min() == pytest.approx(opening.width, abs=1e-6)
        # its local +Z (into the room) points into its first room
        pose = opening_pose(house, opening)
        inside = pose[:3, 3] + pose[:3, 2] * 0.3
        room = house.room(opening.rooms[0]).room
        offset = house.room(opening.rooms[0]).offset
        assert room.contains(inside[0] - offset[0], inside[2] - offset[1]), opening.id


def test_the_walls_are_each_drawn_once_centred_on_their_lines(scene):
    house = scene.house
    mesh = house_walls(house, [0.0, 1.0, 0.0])
    thickness = house.walls[0].thickness
    total = sum(
        (wall.length + sum(wall_reach(house, k))) * thickness for k, wall in enumerate(house.walls)
    )
    # plan area of the wall tops: each wall once (a doubled wall would double it)
    up = mesh.face_normals[:, 1] > 0.99
    at_top = np.abs(mesh.triangles_center[:, 1] - house.height) < 1e-6
    assert mesh.area_faces[up & at_top].sum() == pytest.approx(total, rel=1e-6)
    assert mesh.bounds[1][1] == pytest.approx(house.height)
    width, depth = house.extent
    assert mesh.bounds[1][0] - mesh.bounds[0][0] == pytest.approx(width + thickness)
    assert mesh.bounds[1][2] - mesh.bounds[0][2] == pytest.approx(depth + thickness)


def test_the_glb_has_a_node_per_room_with_its_walls_openings_floor_and_furniture(scene, tmp_path):
    path = export_glb(scene, tmp_path / "house.glb")
    document = _gltf(path)
    nodes = document["nodes"]
    top = [nodes[k] for k in document["scenes"][0]["nodes"]]
    rooms = {node["name"]: node for node in top if node.get("extras", {}).get("kind") == "room"}
    house = scene.house
    assert list(rooms) == [room.id for room in house.rooms]
    children = {
        name: {nodes[k]["name"] for k in node.get("children", [])} for name, node in rooms.items()
    }
    names = [node["name"] for node in nodes]
    for index, wall in enumerate(house.walls):
        assert names.count(wall_name(index)) == 1  # a shared wall is there once
        assert wall_name(index) in children[wall_owner(wall)]
    for opening in house.openings:
        assert names.count(opening.id) == 1
        assert opening.id in children[opening.rooms[0]]
    for obj in scene.objects:
        assert obj.id in children[room_of(obj.id)]
    for room in house.rooms:
        assert f"{room.id}/floor" in children[room.id]
    _validate_if_possible(path)
    # the room nodes' offsets leave every object where the scene has it
    loaded = trimesh.load(path)
    for obj in scene.objects:
        world, _ = loaded.graph[obj.id]
        assert np.allclose(world, object_transform(obj), atol=1e-6)
    # and every wall where the house has it: its mesh on its centre line
    for index, wall in enumerate(house.walls):
        points = _wall_points(loaded, wall_name(index))
        (sx, sz), (ex, ez) = wall.start, wall.end
        dx, dz = (ex - sx) / wall.length, (ez - sz) / wall.length
        across = (points[:, 0] - sx) * -dz + (points[:, 2] - sz) * dx
        along = (points[:, 0] - sx) * dx + (points[:, 2] - sz) * dz
        assert across.min() == pytest.approx(-wall.thickness / 2, abs=1e-5)
        assert across.max() == pytest.approx(wall.thickness / 2, abs=1e-5)
        before, after = wall_reach(house, index)
        assert along.min() == pytest.approx(-before, abs=1e-5)
        assert along.max() == pytest.approx(wall.length + after, abs=1e-5)


def test_a_cut_away_glb_holds_the_walls_as_the_preview_cuts_them(scene, tmp_path):
    path = export_glb(scene, tmp_path / "cut.glb", cutaway=True)
    loaded = trimesh.load(path)
    view = frame_scene(scene, "perspective", 640, 480)
    heights = wall_heights(scene.house, view.pose[:3, 2])
    for index, height in enumerate(heights):
        points = _wall_points(loaded, wall_name(index))
        assert points[:, 1].max() == pytest.approx(height, abs=1e-5)
    _validate_if_possible(path)


def test_the_usd_stage_holds_the_rooms_as_the_glb_does(scene, tmp_path):
    pytest.importorskip("pxr")
    from pxr import Usd

    from scenewright.render.usd_export import export_usd

    stage = Usd.Stage.Open(str(export_usd(scene, tmp_path / "house.usda")))
    house = scene.house
    for index, wall in enumerate(house.walls):
        prim = stage.GetPrimAtPath(f"/World/{wall_owner(wall)}/{wall_name(index)}")
        assert prim.IsValid(), wall_name(index)
        assert list(prim.GetCustomDataByKey("rooms")) == [r for r in wall.rooms if r is not None]
    door = house.doors[0]
    assert stage.GetPrimAtPath(f"/World/{door.rooms[0]}/{door.id}").IsValid()


def test_the_plan_names_every_room_inside_it(scene, tmp_path, monkeypatch):
    house = scene.house
    labels = plan_image.room_labels(house)
    assert [label.text for label in labels] == [room.name for room in house.rooms]
    assert "second bedroom" in [label.text for label in labels]
    for label, room in zip(labels, house.rooms, strict=True):
        assert room.room.contains(
            label.anchor[0] - room.offset[0], label.anchor[1] - room.offset[1]
        )
    placed: list = []
    real = plan_image.place_labels

    def recording(page, given):
        count = real(page, given)
        placed.extend(text.text for text in page.texts)
        return count

    monkeypatch.setattr(plan_image, "place_labels", recording)
    path = plan_image.draw_plan(scene, tmp_path / "plan.png")
    assert path.stat().st_size > 10_000
    for room in house.rooms:
        assert room.name in placed  # written first: nothing else takes its place
    for opening in house.openings:
        assert opening.id in placed
    assert "crate_1" in placed  # objects go by their id within their room


def test_the_preview_draws_walls_and_has_the_doors_as_entities(scene):
    renderer = renderer_or_skip(320, 240)
    try:
        result = renderer.render(scene)
        top = renderer.render(scene, "top")
    finally:
        renderer.close()
    house = scene.house
    openings = [opening.id for opening in house.openings]
    assert [i for i in result.ids if room_of(i) is None] == openings
    assert len(result.ids) == len(scene.objects) + len(openings)
    for door in house.doors:  # cut low, doors show as entities with pixels
        assert door.id in result.boxes and result.visible[door.id] > 0.2, door.id
    boxes = {entry["id"] for entry in result.ground_truth["objects"]}
    assert set(openings) <= boxes
    # a far wall stands whole: at its top's middle the depth is the wall's, background
    camera = frame_scene(scene, "perspective", 320, 240)
    heights = wall_heights(house, camera.pose[:3, 2])
    far = [wall for wall, height in zip(house.walls, heights, strict=True) if height > CUT_HEIGHT]
    assert far
    for wall in far:
        point = [
            (wall.start[0] + wall.end[0]) / 2,
            wall.height - 0.01,
            (wall.start[1] + wall.end[1]) / 2,
        ]
        (u, v), depth = (array[0] for array in camera.project([point]))
        assert result.depth[int(v), int(u)] == pytest.approx(depth, abs=0.15)
        assert result.segmentation[int(v), int(u)] == 0  # walls are backdrop
    # straight down, every door is under its wall's lintel
    assert all(top.visible[door.id] == 0.0 for door in house.doors if not door.open)


def test_a_view_can_aim_at_a_room_by_its_id_or_type(scene):
    from scenewright.render.camera import aimed_camera, entity_family
    from scenewright.render.views import resolve_target, target_members

    house = scene.house
    bedroom = next(room for room in house.rooms if room.type == "bedroom")
    assert resolve_target(scene, "bedroom") == bedroom.id
    assert resolve_target(scene, bedroom.id) == bedroom.id
    assert entity_family(scene, bedroom.id) == {f"{bedroom.id}/crate_1"}
    assert target_members(scene, bedroom.id) == [f"{bedroom.id}/crate_1"]
    camera = aimed_camera(scene, 320, 240, azimuth=0.6, elevation=0.6, target=bedroom.id)
    xs = [x for x, _z in bedroom.outline]
    zs = [z for _x, z in bedroom.outline]
    middle = [(min(xs) + max(xs)) / 2, 0.25, (min(zs) + max(zs)) / 2]
    (u, v), _depth = (array[0] for array in camera.project([middle]))
    assert abs(u - 160) < 40 and abs(v - 120) < 40  # the room is in the middle of the picture


def test_the_plan_of_a_given_plan_off_the_origin_frames_its_footprint(tmp_path, monkeypatch):
    plan = tmp_path / "given.json"
    plan.write_text(
        json.dumps(
            {
                "rooms": [
                    {"id": "hall", "type": "hall", "polygon": [[0, 0], [2, 0], [2, 6], [0, 6]]},
                    {"id": "bed", "type": "bedroom", "polygon": [[2, 0], [6, 0], [6, 6], [2, 6]]},
                ]
            }
        )
    )
    house = house_of(plan, 1)
    rooms = [scene_of([], room=room.room) for room in house.rooms]
    given = house_scene(house, rooms, rules="given", seed=1, name="given")
    limits: list = []
    real = plan_image.place_labels

    def recording(page, labels):
        limits.extend([page.x_limits, page.z_limits])
        return real(page, labels)

    monkeypatch.setattr(plan_image, "place_labels", recording)
    plan_image.draw_plan(given, tmp_path / "plan.png")
    (x0, x1), (z0, z1) = limits
    assert x0 < 0.0 < 6.0 < x1 and z0 < 0.0 < 6.0 < z1
    assert x1 - x0 < 8.0  # framed on the footprint, not on the origin
