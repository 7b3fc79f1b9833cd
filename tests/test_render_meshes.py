"""Meshes for rendering: size fitting, the box fallback for shapes without a builder."""

import numpy as np
from render_fixtures import scene_of, thing

from scenewright.render.builders import BUILDERS
from scenewright.render.meshes import WALL_HEIGHT, junction_mesh, object_mesh, room_walls


def test_shape_without_a_builder_is_drawn_as_its_box():
    assert "no_such_shape" not in BUILDERS
    obj = thing("statue_1", size=(0.6, 2.0, 0.4), shape="no_such_shape", colour=(0.1, 0.5, 0.9))
    mesh = object_mesh(obj)
    box = object_mesh(thing("statue_1", size=(0.6, 2.0, 0.4), shape="box", colour=(0.1, 0.5, 0.9)))
    assert np.allclose(mesh.bounds, [[-0.3, 0.0, -0.2], [0.3, 2.0, 0.2]])
    assert np.allclose(mesh.vertices, box.vertices) and np.array_equal(mesh.faces, box.faces)
    assert np.array_equal(mesh.visual.face_colors, box.visual.face_colors)


def test_junction_is_a_flat_disc_above_the_ground_facing_up():
    disc = junction_mesh(thing("crossing_1", size=(4.0, 0.0, 3.0), kind="junction", shape=None))
    assert np.ptp(disc.vertices[:, 1]) == 0 and disc.vertices[0, 1] > 0
    assert np.allclose(disc.extents[[0, 2]], 3.0, atol=0.05)  # inscribed in the footprint
    assert np.all(disc.face_normals[:, 1] > 0.99)


def test_a_room_has_walls_on_the_sides_a_viewer_sees_from_inside():
    room = scene_of([], extent=(5.0, 4.0), walls=True)
    from_south_east = room_walls(room, towards_viewer=[0.5, 0.6, 0.6])
    lo, hi = from_south_east.bounds
    # North (z = -2) and west (x = -2.5) walls, just outside the floor, as tall as a room.
    assert np.allclose(lo, [-2.6, 0.0, -2.1]) and hi[1] == WALL_HEIGHT
    assert np.allclose(hi[[0, 2]], [2.6, 2.1])  # each runs its whole side, corners closed
    inside = from_south_east.vertices[:, [0, 2]]
    assert not np.any((np.abs(inside[:, 0]) < 2.5) & (np.abs(inside[:, 1]) < 2.0))  # floor clear
    from_north_west = room_walls(room, towards_viewer=[-0.5, 0.6, -0.6])
    assert np.allclose(from_north_west.bounds, [[-2.6, 0.0, -2.1], [2.6, WALL_HEIGHT, 2.1]])
    assert from_north_west.vertices[:, 0].max() == 2.6 and from_north_west.vertices[:, 2].max() == 2.1
    assert room_walls(room, towards_viewer=[0.0, 1.0, 0.0]) is None  # straight above: no walls
    assert room_walls(scene_of([], extent=(5.0, 4.0)), towards_viewer=[0.5, 0.6, 0.6]) is None
