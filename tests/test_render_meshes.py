"""Meshes for rendering: size fitting, the box fallback for shapes without a builder,
the walls a viewer sees, and the fronts of the home, kitchen, bathroom and classroom
shapes."""

import numpy as np
import pytest
from render_fixtures import scene_of, thing

from scenewright.core.room import DEFAULT_WALL_HEIGHT, WALL_THICKNESS
from scenewright.core.scene import ScenePath
from scenewright.core.shapes import SHAPES
from scenewright.render.builders import BUILDERS
from scenewright.render.mesh_parts import CHROME, SCREEN, SHOWER_GLASS, shade
from scenewright.render.meshes import fit_to_size, junction_mesh, object_mesh, path_mesh, room_walls


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


@pytest.mark.parametrize("start", [None, "crossing_1"])
def test_a_path_is_a_ribbon_of_its_width_facing_up_with_round_joints(start):
    points = [[0.0, 0.0], [4.0, 0.0], [4.0, 0.0], [4.0, 3.0]]  # a repeated point: no quad there
    road = ScenePath("road_1", "road", "road", None, None, points, 2.0, start=start)
    mesh = path_mesh(road)
    discs = 2 + (start is None)  # one at each inner point, one at a start no junction covers
    assert len(mesh.faces) == 2 * 2 + 16 * discs
    assert np.ptp(mesh.vertices[:, 1]) == 0 and mesh.vertices[0, 1] > 0
    winding = np.cross(
        *(mesh.vertices[mesh.faces[:, k]] - mesh.vertices[mesh.faces[:, 0]] for k in (1, 2))
    )
    assert np.all(winding[:, 1] > 0) and np.array_equal(
        mesh.face_normals, np.tile([0.0, 1.0, 0.0], (len(mesh.faces), 1))
    )
    # Quads of the width along each segment, discs of the width at the joints.
    assert np.allclose(mesh.bounds[:, [0, 2]], [[-1.0 if start is None else 0.0, -1.0], [5.0, 3.0]])
    assert mesh.area == pytest.approx(
        2.0 * 4.0 + 2.0 * 3.0 + discs * 16 / 2 * np.sin(2 * np.pi / 16)
    )


def test_a_room_has_walls_on_the_sides_a_viewer_sees_from_inside():
    room = scene_of([], extent=(5.0, 4.0), walls=True)
    t, h = WALL_THICKNESS, DEFAULT_WALL_HEIGHT
    from_south_east = room_walls(room, towards_viewer=[0.5, 0.6, 0.6])
    # North (z = -2) and west (x = -2.5) walls, behind their inner faces, as tall as the room.
    assert np.allclose(from_south_east.bounds, [[-2.5 - t, 0.0, -2.0 - t], [2.5 + t, h, 2.0 + t]])
    inside = from_south_east.vertices[:, [0, 2]]
    assert not np.any(
        (np.abs(inside[:, 0]) < 2.5 - 1e-9) & (np.abs(inside[:, 1]) < 2.0 - 1e-9)
    )  # floor clear
    assert inside[:, 0].max() == pytest.approx(2.5 + t) and inside[:, 1].max() == pytest.approx(
        2.0 + t
    )
    near = (inside[:, 0] > 2.5 - 1e-9) & (
        inside[:, 1] > -2.0 + 1e-9
    )  # the east wall's line, south of the corner
    assert not near.any(), "the east wall is a near wall from the south-east"
    from_north_west = room_walls(room, towards_viewer=[-0.5, 0.6, -0.6])
    assert np.allclose(from_north_west.bounds, [[-2.5 - t, 0.0, -2.0 - t], [2.5 + t, h, 2.0 + t]])
    seen = from_north_west.vertices[:, [0, 2]]
    assert not np.any((seen[:, 0] < -2.5 + 1e-9) & (seen[:, 1] < 2.0 - 1e-9)), (
        "the west wall is a near wall"
    )
    assert not np.any((seen[:, 1] < -2.0 + 1e-9) & (seen[:, 0] < 2.5 - 1e-9)), (
        "so is the north wall"
    )
    # Straight above sees every wall (their tops); outdoors there are none.
    assert np.isclose(
        room_walls(room, towards_viewer=[0.0, 1.0, 0.0]).volume,
        ((5 + 2 * t) * (4 + 2 * t) - 20) * h,
    )
    assert room_walls(scene_of([], extent=(5.0, 4.0)), towards_viewer=[0.5, 0.6, 0.6]) is None


# -- the shapes of homes, kitchens, bathrooms and classrooms ----------------------------

#: A test colour no builder uses as a secondary colour, so its faces can be told apart.
MAIN = (0.5, 0.1, 0.9)
#: Sizes (w, h, d) a catalog would give them.
ROOM_SHAPES = {
    "armchair": (0.85, 0.9, 0.85),
    "bathtub": (1.7, 0.55, 0.75),
    "coffee_table": (1.1, 0.45, 0.6),
    "dining_table": (1.6, 0.75, 0.9),
    "dresser": (1.0, 0.85, 0.45),
    "floor_lamp": (0.4, 1.7, 0.4),
    "kitchen_counter": (1.2, 0.9, 0.6),
    "piano": (1.5, 1.25, 0.6),
    "refrigerator": (0.7, 1.8, 0.7),
    "shower": (0.9, 2.1, 0.9),
    "sink_counter": (1.2, 1.05, 0.6),
    "sofa": (2.0, 0.85, 0.9),
    "stove": (0.6, 0.9, 0.6),
    "teacher_desk": (1.4, 0.76, 0.7),
    "toilet": (0.4, 0.8, 0.7),
    "towel_rail": (0.6, 0.95, 0.3),
    "tv": (1.2, 0.75, 0.25),
    "tv_stand": (1.6, 0.5, 0.42),
    "washbasin": (0.55, 0.9, 0.45),
    "washing_machine": (0.6, 0.85, 0.6),
    "whiteboard": (1.8, 1.9, 0.5),
}


def built(shape: str):
    return BUILDERS[shape](ROOM_SHAPES[shape], MAIN)


def centres_of_colour(mesh, colour) -> np.ndarray:
    """Centres of the faces painted ``colour`` (how a builder tells its parts apart)."""
    rgb = np.round(np.asarray(colour) * 255)
    return mesh.triangles_center[np.all(mesh.visual.face_colors[:, :3] == rgb, axis=1)]


@pytest.mark.parametrize("shape", sorted(ROOM_SHAPES))
def test_room_shapes_are_registered_small_and_fill_their_size(shape):
    assert shape in SHAPES
    size = np.array(ROOM_SHAPES[shape])
    mesh = built(shape)
    assert 0 < len(mesh.faces) < 500 and len(np.unique(mesh.visual.face_colors, axis=0)) >= 2
    extents = mesh.bounds[1] - mesh.bounds[0]
    assert np.all(np.abs(extents / size - 1.0) < 0.1), (
        extents
    )  # built at its size: the fit barely scales
    assert abs(mesh.bounds[0][1]) < 1e-9  # stands on the floor
    assert np.all(np.abs((mesh.bounds[0] + mesh.bounds[1])[[0, 2]] / 2) <= 0.05 * size[[0, 2]])
    fitted = fit_to_size(mesh, size)
    w, h, d = size
    np.testing.assert_allclose(fitted.bounds, [[-w / 2, 0.0, -d / 2], [w / 2, h, d / 2]], atol=1e-9)


@pytest.mark.parametrize(
    "shape, part, where",
    [
        ("sofa", shade(MAIN, 0.85), "back"),  # the back rest
        ("armchair", shade(MAIN, 0.85), "back"),
        ("tv", SCREEN, "front"),
        ("refrigerator", CHROME, "front"),  # the handles
        ("washing_machine", (0.16, 0.2, 0.26), "front"),  # the door's glass
        ("stove", (0.12, 0.12, 0.14), "front"),  # the oven window
        ("piano", (0.95, 0.94, 0.88), "front"),  # the white keys
        ("whiteboard", (0.15, 0.3, 0.75), "front"),  # blue marker
        ("kitchen_counter", CHROME, "front"),  # handles
        ("washbasin", CHROME, "back"),  # the tap
        (
            "shower",
            CHROME,
            "back",
        ),  # the riser, head and mixer ... and the screen's frame, on the front
    ],
)
def test_what_a_shape_shows_on_its_front_is_there(shape, part, where):
    w, h, d = ROOM_SHAPES[shape]
    centres = centres_of_colour(built(shape), part)
    assert len(centres)
    if (
        shape == "shower"
    ):  # the riser and head (cylinders, not the frame's flat slabs) stand at the back
        centres = centres[np.abs(centres[:, 0] + 0.1 * w) < 0.02]
    assert np.all(centres[:, 2] > 0.0) if where == "front" else np.all(centres[:, 2] < 0.0), centres


def test_a_toilet_has_its_cistern_at_the_back_and_its_bowl_in_front():
    w, h, d = ROOM_SHAPES["toilet"]
    centres = built("toilet").triangles_center
    assert np.all(centres[centres[:, 1] > 0.95 * h][:, 2] < -0.2 * d)  # the cistern's top
    seat = centres[(centres[:, 1] > 0.45 * h) & (centres[:, 1] < 0.55 * h)]
    assert seat[:, 2].max() > 0.45 * d  # the bowl reaches the front


def test_a_sink_counter_has_its_tap_at_the_back_above_the_worktop():
    w, h, d = ROOM_SHAPES["sink_counter"]
    tap = centres_of_colour(built("sink_counter"), CHROME)
    tap = tap[tap[:, 1] > 0.85 * h]
    assert len(tap) and np.all(tap[:, 2] < 0.0)


def test_a_shower_has_glass_on_its_front_and_plus_x_sides_only():
    w, h, d = ROOM_SHAPES["shower"]
    glass = centres_of_colour(built("shower"), SHOWER_GLASS)
    assert len(glass) and np.all((glass[:, 0] > 0.0) | (glass[:, 2] > 0.0))
    front = glass[glass[:, 2] > d / 2 - 0.02]
    assert front[:, 0].min() > 0.0  # the -X half of the front is the way in


def test_an_upright_piano_keeps_its_tall_case_at_the_back():
    w, h, d = ROOM_SHAPES["piano"]
    centres = built("piano").triangles_center
    high = centres[centres[:, 1] > 0.9 * h]
    assert np.all(high[:, 2] < 0.1 * d)


def test_a_teacher_desk_is_drawn_as_a_desk():
    assert BUILDERS["teacher_desk"] is BUILDERS["desk"]
    assert SHAPES["teacher_desk"].front == SHAPES["desk"].front
