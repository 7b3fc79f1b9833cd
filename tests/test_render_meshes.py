"""Meshes for rendering: size fitting, the box fallback for shapes without a builder."""

import numpy as np
from render_fixtures import thing

from scenewright.render.builders import BUILDERS
from scenewright.render.meshes import junction_mesh, object_mesh


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
