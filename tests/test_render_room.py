"""Rooms drawn and exported: walls with their doors and windows cut out, closed corners
in rectangular and L-shaped rooms, the floor, doors and windows as segmentation
entities, the camera that looks in from the door's side, the GLB's named nodes, the plan."""

from __future__ import annotations

import io
import json
import math
import os
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest
import trimesh
from PIL import Image
from render_fixtures import renderer_or_skip, scene_of, thing

from scenewright.core.room import WALL_THICKNESS, Room
from scenewright.render.camera import AZIMUTH, Camera, frame_scene, room_azimuth, walls_in_view
from scenewright.render.export import glb_bytes, preview_camera
from scenewright.render.meshes import floor_mesh, opening_mesh, opening_transform, wall_mesh
from scenewright.render.plan_image import draw_plan

ROOT = Path(__file__).resolve().parent.parent
T = WALL_THICKNESS

#: A 5 x 4 m room with a door in the south wall and a window in the north wall.
RECTANGLE = (
    Room.rectangle(5, 4)
    .with_opening("door", "south", 1.0, 0.9)
    .with_opening("window", "north", 2.5, 1.4, 1.2, 0.9)
)
#: An L-shaped room (6 x 5 m less a 3 x 2 m notch at the south-east): a door in the
#: notch's south-facing wall, a window in the north wall, a second door at the west
#: wall's end (reaching its corner) and a window in the notch's east-facing wall.
L_SHAPED = (
    Room.polygon([(0, 0), (6, 0), (6, 3), (3, 3), (3, 5), (0, 5)])
    .with_opening("door", "wall_3", 1.5, 0.9)
    .with_opening("window", "north", 3.0, 1.6, 1.2, 0.9)
    .with_opening("door", "west", 4.55, 0.9)
    .with_opening("window", "wall_4", 1.0, 1.0, 1.0, 1.0)
)
ROOMS = {"rectangle": RECTANGLE, "L-shaped": L_SHAPED}


def ray_hits(mesh: trimesh.Trimesh, origins, directions) -> np.ndarray:
    """(R,) whether each ray (origins and directions (R, 3)) meets ``mesh``, by the
    Moller-Trumbore test against every triangle at once (the meshes here are small)."""
    origins, directions = (
        np.atleast_2d(origins).astype(float),
        np.atleast_2d(directions).astype(float),
    )
    a, b, c = (mesh.triangles[:, k][None] for k in range(3))  # (1, T, 3)
    e1, e2 = b - a, c - a
    p = np.cross(directions[:, None], e2)
    det = np.einsum("rtk,rtk->rt", e1.repeat(len(origins), 0), p)
    with np.errstate(divide="ignore", invalid="ignore"):  # rays parallel to a triangle: det 0
        inv = 1.0 / det
        s = origins[:, None] - a
        u = np.einsum("rtk,rtk->rt", s, p) * inv
        q = np.cross(s, e1)
        v = np.einsum("rk,rtk->rt", directions, q) * inv
        t = np.einsum("rtk,rtk->rt", e2.repeat(len(origins), 0), q) * inv
        hit = (np.abs(det) > 1e-12) & (u >= 0) & (v >= 0) & (u + v <= 1) & (t > 0)
    return hit.any(axis=1)


def through(wall, points) -> tuple[np.ndarray, np.ndarray]:
    """Rays from inside the room through the wall at (u, y) points, outwards."""
    origins = []
    for u, y in points:
        x, z = wall.to_world(u, 0.5)
        origins.append([x, y, z])
    direction = np.array([-wall.normal[0], 0.0, -wall.normal[1]])
    return np.array(origins), np.tile(direction, (len(points), 1))


# -- walls, floor, doors and windows as meshes ---------------------------------------------


@pytest.mark.parametrize("name", ROOMS)
def test_walls_have_holes_where_their_openings_are(name):
    room = ROOMS[name]
    for wall in room.walls:
        mesh = wall_mesh(room, wall)
        u, v = np.array([wall.to_wall(x, z) for x, z in mesh.vertices[:, [0, 2]]]).T
        assert v.min() == pytest.approx(-T) and v.max() == pytest.approx(
            0.0
        )  # behind the inner face
        assert mesh.bounds[0][1] == 0.0 and mesh.bounds[1][1] == pytest.approx(wall.height)
        openings = room.openings_on(wall.id)
        solid = [(wall.length * f, y) for f in (0.02, 0.5, 0.98) for y in (0.1, 1.3, 2.5)]
        solid = [
            (s, y)
            for s, y in solid
            if not any(abs(s - o.offset) < o.width / 2 + 0.05 for o in openings)
        ]
        hole, around = [], []
        for o in openings:
            u0, u1 = o.offset - o.width / 2, o.offset + o.width / 2
            hole += [
                (o.offset, (o.sill + o.top) / 2),
                (u0 + 0.02, o.sill + 0.02),
                (u1 - 0.02, o.top - 0.02),
            ]
            around += [(u0 - 0.05, 1.0), (u1 + 0.05, 1.0), (o.offset, o.top + 0.05)]
            if o.sill > 0.05:
                around.append((o.offset, o.sill - 0.05))
        around = [(s, y) for s, y in around if 0.0 < s < wall.length and y < wall.height]
        if solid + around:
            assert ray_hits(mesh, *through(wall, solid + around)).all(), wall.id
        if hole:
            assert not ray_hits(mesh, *through(wall, hole)).any(), wall.id


@pytest.mark.parametrize("name", ROOMS)
def test_walls_close_every_corner_without_overlapping(name):
    room = ROOMS[name]
    plain = Room(room.walls)  # the same walls without their openings
    walls = trimesh.util.concatenate([wall_mesh(plain, wall) for wall in plain.walls])
    # An orthogonal room's walls fill its outline grown by the thickness: the perimeter
    # times the thickness, plus a square of it at each convex corner, less one at each reflex one.
    turns = [
        plain.convex_corner(plain.walls[k - 1], plain.walls[k]) for k in range(len(plain.walls))
    ]
    convex = sum(turns)
    perimeter = sum(w.length for w in plain.walls)
    ring = perimeter * T + (convex - (len(turns) - convex)) * T * T
    assert walls.volume == pytest.approx(ring * plain.height, rel=1e-9)
    # With the openings cut (one reaches a corner): exactly their holes less, no piece overlapping another.
    cut = trimesh.util.concatenate([wall_mesh(room, wall) for wall in room.walls])
    assert cut.volume == pytest.approx(
        walls.volume - sum(o.width * o.height * T for o in room.openings), rel=1e-9
    )
    # Looking straight down at each corner's outer square, on either side of the mitre: wall.
    down = np.array([0.0, -1.0, 0.0])
    for k, second in enumerate(plain.walls):
        first = plain.walls[k - 1]
        corner = np.array(second.start)
        n1, n2 = np.array(first.normal), np.array(second.normal)
        for a, b in ((0.3, 0.7), (0.7, 0.3)):
            x, z = corner - (a * n1 + b * n2) * T
            assert ray_hits(walls, [[x, 5.0, z]], [down]).all(), (second.id, a, b)
        x, z = corner + (n1 + n2) * 0.05  # just inside the room: clear
        assert not ray_hits(walls, [[x, 5.0, z]], [down]).any(), second.id


def test_the_floor_is_the_room_polygon():
    floor = floor_mesh(L_SHAPED)
    assert floor.is_watertight and floor.volume > 0
    assert np.allclose(floor.bounds, [[-3.0, -0.05, -2.5], [3.0, 0.0, 2.5]])
    top = floor.area_faces[floor.face_normals[:, 1] > 0.99].sum()
    assert top == pytest.approx(L_SHAPED.area)  # 6 x 5 less the 3 x 2 notch
    down = np.array([[0.0, -1.0, 0.0]] * 2)
    assert not ray_hits(
        floor, [[2.0, 1.0, 1.5], [1.0, 1.0, 2.0]], down
    ).any()  # the notch: no floor
    assert ray_hits(floor, [[-2.0, 1.0, 1.5], [2.0, 1.0, -1.5]], down).all()


@pytest.mark.parametrize("name", ROOMS)
def test_doors_and_windows_fill_their_holes_and_stay_out_of_the_room(name):
    room = ROOMS[name]
    for opening in room.openings:
        wall = room.part(opening.wall)
        mesh = opening_mesh(opening)
        mesh.apply_transform(opening_transform(room, opening))
        u, v = np.array([wall.to_wall(x, z) for x, z in mesh.vertices[:, [0, 2]]]).T
        assert u.min() == pytest.approx(opening.offset - opening.width / 2)
        assert u.max() == pytest.approx(opening.offset + opening.width / 2)
        assert (
            v.min() == pytest.approx(-T) and v.max() <= 1e-9
        )  # within the wall: never in the swing zone
        assert mesh.bounds[0][1] == pytest.approx(opening.sill) and mesh.bounds[1][
            1
        ] == pytest.approx(opening.top)
        # A ray through the middle meets the door leaf or the window pane.
        assert ray_hits(
            mesh, *through(wall, [(opening.offset, (opening.sill + opening.top) / 2)])
        ).all()


# -- cameras ------------------------------------------------------------------------------


def looks_from(camera: Camera) -> np.ndarray:
    """The horizontal unit direction (x, z) from the scene back towards the camera."""
    back = camera.pose[:3, 2][[0, 2]]
    return back / np.linalg.norm(back)


@pytest.mark.parametrize(
    "side, outward", [("south", (0, 1)), ("north", (0, -1)), ("east", (1, 0)), ("west", (-1, 0))]
)
def test_the_perspective_camera_looks_in_through_the_door_wall(side, outward):
    room = Room.rectangle(5, 4).with_opening("door", side, 1.0, 0.9)
    camera = frame_scene(scene_of([], room=room), "perspective", 96, 96)
    towards = looks_from(camera)
    assert towards @ np.array(outward) == pytest.approx(
        math.cos(AZIMUTH)
    )  # from the door's side...
    turn = outward[0] * towards[1] - outward[1] * towards[0]
    assert turn < 0  # ... turned to the right, as the south-east view is turned from the south
    drawn = {wall.id for wall in walls_in_view(room, camera.pose[:3, 2])}
    assert room.doors[0].wall not in drawn  # the door's wall is the one cut away


def test_a_room_with_a_south_door_is_seen_from_the_south_and_its_windows_face_the_camera():
    camera = frame_scene(scene_of([], room=RECTANGLE), "perspective", 96, 96)
    x, _, z = camera.pose[:3, 3]
    assert z > 2.0 and z > x > 0  # south of the room, turned east
    drawn = {wall.side for wall in walls_in_view(RECTANGLE, camera.pose[:3, 2])}
    assert drawn == {"north", "west"}  # the window's wall among them
    # The framing holds the floor and the far walls' tops.
    pixels, depth = camera.project([[-2.5 - T, 2.6, -2.0 - T], [2.5, 0.0, 2.0], [-2.5, 0.0, 2.0]])
    assert np.all((pixels >= 0) & (pixels <= 96)) and np.all(depth > 0)


def test_without_a_door_the_camera_faces_the_window_and_without_either_it_looks_from_the_south_east():
    windowed = Room.rectangle(5, 4).with_opening("window", "north", 2.5, 1.0, 1.0, 1.0)
    assert room_azimuth(windowed) == pytest.approx(AZIMUTH)  # from the south, across the room
    assert room_azimuth(
        Room.rectangle(5, 4).with_opening("window", "east", 2.0, 1.0, 1.0, 1.0)
    ) == pytest.approx(AZIMUTH - math.pi / 2)
    assert room_azimuth(Room.rectangle(5, 4)) == room_azimuth(None) == AZIMUTH


@pytest.mark.parametrize("name", ROOMS)
def test_the_top_view_of_a_room_is_north_up_and_shows_every_wall(name):
    room = ROOMS[name]
    camera = frame_scene(scene_of([], room=room), "top", 96, 96)
    north, south, east, west = camera.project(
        [[0, 0, -2.0], [0, 0, 2.0], [2.0, 0, 0], [-2.0, 0, 0]]
    )[0]
    assert north[1] < south[1] and east[0] > west[0] and north[0] == pytest.approx(south[0])
    assert len(walls_in_view(room, camera.pose[:3, 2])) == len(room.walls)
    outer = [[x + dx, 2.6, z + dz] for x, z in room.corners for dx in (-T, T) for dz in (-T, T)]
    pixels, _ = camera.project(outer)
    assert np.all((pixels >= 0) & (pixels <= 96))  # the walls' tops are framed


# -- rendering ------------------------------------------------------------------------------


@pytest.fixture(scope="module")
def renderer():
    renderer = renderer_or_skip(96, 96)
    yield renderer
    renderer.close()


def two_door_room():
    """RECTANGLE with a second door in the west wall, which the camera (looking in
    through the south door's wall) sees, and an armchair-sized box in the room."""
    room = RECTANGLE.with_opening("door", "west", 1.5, 0.9)
    return scene_of([thing("crate_1", (0.5, 0.0, 0.5), (0.8, 0.8, 0.8))], room=room)


def test_doors_and_windows_are_entities_with_ids_boxes_and_visible_fractions(renderer):
    result = renderer.render(two_door_room())
    assert result.ids == ["crate_1", "door_1", "window_1", "door_2"]  # openings after the objects
    labels = set(np.unique(result.segmentation).tolist())
    assert labels == {0, 1, 3, 4}  # door_1 is in the cut-away south wall: not drawn
    assert "door_1" not in result.boxes and result.visible["door_1"] == 0.0
    for index, entity_id in ((3, "window_1"), (4, "door_2")):
        rows, cols = np.nonzero(result.segmentation == index)
        assert result.boxes[entity_id] == [cols.min(), rows.min(), cols.max() + 1, rows.max() + 1]
        assert result.visible[entity_id] == pytest.approx(1.0)
    camera = Camera.from_dict(result.camera)
    for index, opening in ((3, RECTANGLE.windows[0]), (4, two_door_room().room.doors[1])):
        x, z = opening.center
        ((u, v),) = camera.project([[x, (opening.sill + opening.top) / 2, z]])[0]
        assert result.segmentation[int(v), int(u)] == index, opening.id
    # The wall around the window is backdrop.
    x, z = RECTANGLE.part("wall_1").to_world(0.4, 0.0)
    ((u, v),) = camera.project([[x, 1.0, z]])[0]
    assert result.segmentation[int(v), int(u)] == 0


def test_furniture_in_front_of_a_door_hides_part_of_it(renderer):
    scene = two_door_room()
    door = scene.room.doors[1]
    camera = frame_scene(scene, "perspective", 96, 96)
    towards = camera.pose[:3, 3] - np.array([door.center[0], 1.0, door.center[1]])
    x, _, z = (
        np.array([door.center[0], 0.0, door.center[1]]) + towards / np.linalg.norm(towards) * 1.2
    )
    scene.objects.append(thing("wardrobe_1", (x, 0.0, z), (0.5, 1.4, 0.5)))
    result = renderer.render(scene)
    assert 0.0 < result.visible["door_2"] < 0.9
    assert result.visible["wardrobe_1"] == pytest.approx(1.0)


def test_from_above_the_lintels_hide_the_doors_and_windows(renderer):
    result = renderer.render(two_door_room(), "top")
    assert result.ids == ["crate_1", "door_1", "window_1", "door_2"]
    assert set(np.unique(result.segmentation).tolist()) == {0, 1}
    for opening_id in ("door_1", "window_1", "door_2"):
        assert opening_id not in result.boxes and result.visible[opening_id] == 0.0


def test_an_l_shaped_room_renders_with_its_openings(renderer):
    result = renderer.render(scene_of([], room=L_SHAPED))
    assert result.ids == ["door_1", "window_1", "door_2", "window_2"]
    # Looking in through the notch's south-facing wall (door_1), turned to the side that
    # shows both windows; the walls turned away from the camera are cut away.
    assert set(result.boxes) == {"window_1", "window_2"}


# -- GLB export and the plan ------------------------------------------------------------------


def test_the_glb_has_named_wall_door_and_window_nodes(tmp_path):
    scene = scene_of([thing("crate_1", (-1.0, 0.0, -1.0))], room=L_SHAPED)
    data = glb_bytes(scene)
    loaded = trimesh.load(io.BytesIO(data), file_type="glb")
    document = json.loads(_json_chunk(data))
    names = {node["name"] for node in document["nodes"] if "mesh" in node}
    assert names == {
        "crate_1",
        "floor",
        *(w.id for w in L_SHAPED.walls),
        "door_1",
        "door_2",
        "window_1",
        "window_2",
    }
    length = int.from_bytes(data[12:16], "little")
    nodes = {node["name"]: node for node in json.loads(data[20 : 20 + length])["nodes"]}
    # The preview looks in through door_1's wall, which it cuts away.
    cut = {w.id for w in L_SHAPED.walls} - {
        w.id for w in walls_in_view(L_SHAPED, preview_camera(scene).pose[:3, 2])
    }
    assert "wall_3" in cut and "wall_1" not in cut
    assert nodes["door_1"]["extras"] == {
        "id": "door_1",
        "kind": "door",
        "wall": "wall_3",
        "cutaway": True,
    }
    assert nodes["window_2"]["extras"] == {
        "id": "window_2",
        "kind": "window",
        "wall": "wall_4",
        "cutaway": "wall_4" in cut,
    }
    assert nodes["wall_1"]["extras"] == {
        "id": "wall_1",
        "kind": "wall",
        "side": "north",
        "cutaway": False,
    }
    assert nodes["floor"]["extras"] == {"kind": "floor"}
    kept = json.loads(_json_chunk(glb_bytes(scene, cutaway=True)))["nodes"]
    assert {node["name"] for node in kept} == set(nodes) - cut - {
        o.id for o in L_SHAPED.openings if o.wall in cut
    }
    # In the world, each wall is where it was built, its openings cut.
    for wall in L_SHAPED.walls:
        mesh = _world_mesh(loaded, wall.id)
        assert np.allclose(mesh.bounds, wall_mesh(L_SHAPED, wall).bounds, atol=1e-6)
        for opening in L_SHAPED.openings_on(wall.id):
            assert not ray_hits(
                mesh, *through(wall, [(opening.offset, (opening.sill + opening.top) / 2)])
            ).any()
        world_door, _ = loaded.graph["door_1"]
        assert np.allclose(world_door, opening_transform(L_SHAPED, L_SHAPED.part("door_1")))
    path = tmp_path / "room.glb"
    path.write_bytes(data)
    _validate_if_possible(path)


def _world_mesh(loaded: trimesh.Scene, name: str) -> trimesh.Trimesh:
    """Node ``name``'s mesh in world coordinates, its primitives (trimesh loads each
    material's as a child node) joined."""
    parts = []
    for node in loaded.graph.nodes_geometry:
        if node == name or loaded.graph.transforms.parents.get(node) == name:
            world, geometry = loaded.graph[node]
            parts.append(loaded.geometry[geometry].copy().apply_transform(world))
    return trimesh.util.concatenate(parts)


def _json_chunk(data: bytes) -> bytes:
    return data[20 : 20 + int.from_bytes(data[12:16], "little")]


def _validate_if_possible(path: Path) -> None:
    """Khronos' glTF validator on ``path``: zero errors and warnings (skipped when it is
    not installed, as in tests/test_export.py)."""
    node, modules = shutil.which("node"), ROOT / ".tools" / "node_modules"
    if node is None or not (modules / "gltf-validator").is_dir():
        return
    done = subprocess.run(
        [node, str(ROOT / "tests" / "validate_gltf.js"), str(path)],
        env=dict(os.environ, NODE_PATH=str(modules)),
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert done.returncode == 0, done.stderr
    issues = json.loads(done.stdout)["issues"]
    assert issues["numErrors"] == 0 and issues["numWarnings"] == 0, issues["messages"]


def test_the_plan_draws_walls_doors_and_windows(tmp_path):
    image = draw_plan(scene_of([], room=L_SHAPED), tmp_path / "plan.png")
    pixels = np.asarray(Image.open(image).convert("RGB")).astype(int)
    wall_grey = np.all(np.abs(pixels - 115) < 4, axis=-1)  # the walls' grey (WALL_FILL)
    window_blue = np.all(np.abs(pixels - [173, 216, 230]) < 4, axis=-1)  # "lightblue"
    assert wall_grey.sum() > 2000 and window_blue.sum() > 50


def test_the_camera_turns_to_the_side_of_the_door_that_shows_the_windows():
    door_south = Room.rectangle(5, 4).with_opening("door", "south", 1.0, 0.9)
    assert room_azimuth(door_south) == pytest.approx(AZIMUTH)  # no window: turned east, as before
    east_window = door_south.with_opening("window", "east", 2.0, 1.0, 1.0, 1.0)
    west_window = door_south.with_opening("window", "west", 2.0, 1.0, 1.0, 1.0)
    for room, seen in ((east_window, "east"), (west_window, "west")):
        towards = np.array([math.sin(room_azimuth(room)), 0.0, math.cos(room_azimuth(room))])
        assert seen in {wall.side for wall in walls_in_view(room, towards)}
