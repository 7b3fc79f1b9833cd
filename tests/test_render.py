"""Offscreen rendering of hand-built scenes: images, depth, segmentation, boxes."""

import json
import math

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from PIL import Image
from render_fixtures import (
    market_scene,
    or_skip_without_opengl,
    renderer_or_skip,
    road,
    run_without_opengl,
    scene_of,
    thing,
)

from scenewright.api import build_scene
from scenewright.core.errors import InputError
from scenewright.render.camera import Camera, frame_scene
from scenewright.render.offscreen import encode_render, render_metadata, save_render


@pytest.fixture(scope="module")
def renderer():
    renderer = renderer_or_skip(160, 120)
    yield renderer
    renderer.close()


@pytest.fixture(scope="module")
def market(renderer):
    return renderer.render(market_scene())


def pixel_of(result, point) -> tuple[int, int]:
    ((u, v),) = Camera.from_dict(result.camera).project([point])[0]
    return int(math.floor(u)), int(math.floor(v))


def test_colour_image_shows_something(market):
    assert market.colour.shape == (120, 160, 3) and market.colour.dtype == np.uint8
    assert market.colour.reshape(-1, 3).std(axis=0).max() > 10


def test_segmentation_holds_exactly_the_drawn_entities(market):
    # Groups have no body; objects, junctions and paths are drawn, in scene order.
    assert market.ids == ["table_1", "sign_1", "house_1", "crossing_1", "road_1"]
    values = set(np.unique(market.segmentation).tolist())
    assert values == {0, 1, 2, 3, 4, 5}
    assert set(market.boxes) == set(market.ids)
    for index, entity_id in enumerate(market.ids, start=1):
        assert market.visible[entity_id] > 0.5
        x0, y0, x1, y1 = market.boxes[entity_id]
        rows, cols = np.nonzero(market.segmentation == index)
        assert (x0, y0, x1, y1) == (cols.min(), rows.min(), cols.max() + 1, rows.max() + 1)


def test_closing_one_renderer_leaves_the_others_working(renderer):
    """Every renderer of a process shares one EGL display; closing one used to end it
    for all (a dataset worker's kept renderer failed after a test had closed its own)."""
    other = renderer_or_skip(32, 24)
    other.render(market_scene())
    other.close()
    assert renderer.render(market_scene()).colour.any()


def test_a_box_appears_at_its_projected_centre(renderer):
    scene = scene_of(
        [thing("crate_1", (2.0, 0.0, -1.0), (1.0, 1.0, 1.0)), thing("barrel_1", (-6.0, 0.0, 5.0))]
    )
    for view in ("perspective", "top"):
        result = renderer.render(scene, view)
        u, v = pixel_of(result, [2.0, 0.5, -1.0])
        assert result.segmentation[v, u] == result.ids.index("crate_1") + 1, view


def test_depth_matches_the_camera_and_grows_away_from_it(renderer):
    scene = scene_of([thing("tower_1", (0, 0, 0), (2, 4, 2))])
    top = renderer.render(scene, "top")
    camera = Camera.from_dict(top.camera)
    u, v = pixel_of(top, [0.0, 4.0, 0.0])
    assert top.depth[v, u] == pytest.approx(
        camera.pose[1, 3] - 4.0, abs=0.01
    )  # roof seen from above

    side = renderer.render(scene, "perspective")
    assert np.all(side.depth >= 0) and side.depth.dtype == np.float32
    # The ground recedes from the bottom of the image (near) to the top (far).
    column = side.depth[:, 5]
    ground = column[column > 0]
    assert np.all(np.diff(ground[::-1]) > 0)
    near, far = [0.0, 0.0, 4.0], [0.0, 0.0, -4.0]
    (depth_near, depth_far) = Camera.from_dict(side.camera).project([near, far])[1]
    assert depth_near < depth_far


def test_top_view_has_north_up_and_east_right(renderer):
    scene = scene_of(
        [thing("north_1", (0, 0, -6)), thing("south_1", (0, 0, 6)), thing("east_1", (8, 0, 0))]
    )
    result = renderer.render(scene, "top")

    def centre(entity_id):
        x0, y0, x1, y1 = result.boxes[entity_id]
        return (x0 + x1) / 2, (y0 + y1) / 2

    assert centre("north_1")[1] < centre("south_1")[1]
    assert centre("east_1")[0] > centre("north_1")[0]


def test_visible_fraction_drops_behind_an_occluder(renderer):
    camera = frame_scene(scene_of([thing("target_1")]), "perspective")
    towards_camera = camera.pose[:3, 3] / np.linalg.norm(camera.pose[:3, 3])
    wall_at = towards_camera * 3.0
    scene = scene_of(
        [
            thing("target_1", (0, 0, 0), (1, 1, 1)),
            thing("wall_1", (wall_at[0], 0, wall_at[2]), (0.8, 1.5, 0.8)),
        ]
    )
    result = renderer.render(scene)
    assert result.visible["wall_1"] == pytest.approx(1.0)
    assert 0.0 <= result.visible["target_1"] < 0.9


def test_a_room_shows_its_far_walls_as_backdrop_not_entities(renderer):
    things = [thing("rug_1", (0, 0, 0), (4.6, 0.02, 3.6))]  # covers the floor, hides no wall
    room = scene_of(things, extent=(5.0, 4.0), walls=True)  # a plain room: no door, no window
    side = renderer.render(room)
    assert side.ids == ["rug_1"] and side.visible["rug_1"] == pytest.approx(
        1.0
    )  # walls hide nothing
    camera = Camera.from_dict(side.camera)
    inner_faces = {"north": [-1.0, 1.0, -2.0], "west": [-2.5, 1.0, -1.0]}
    for wall, point in inner_faces.items():
        (u, v), depth = pixel_of(side, point), camera.project([point])[1][0]
        assert side.segmentation[v, u] == 0 and side.depth[v, u] == pytest.approx(
            depth, abs=0.05
        ), wall
    # The near walls (south, east) would stand between the camera and the room: the
    # camera sees past where they would be.
    for point in ([0.0, 1.0, 2.05], [2.55, 1.0, 0.0]):
        u, v = pixel_of(side, point)
        assert side.depth[v, u] > camera.project([point])[1][0] + 0.5, point
    assert side.depth[0, 0] == 0 and side.depth[-1, -1] == 0  # a room has no surroundings

    top = renderer.render(room, "top")
    camera = Camera.from_dict(top.camera)
    for point in (
        [0.0, 2.6, -2.06],
        [2.56, 2.6, 0.0],
        [0.0, 2.6, 2.06],
        [-2.56, 2.6, 0.0],
    ):  # every wall's top
        u, v = pixel_of(top, point)
        assert top.depth[v, u] == pytest.approx(camera.pose[1, 3] - 2.6, abs=0.01), point
        assert top.segmentation[v, u] == 0


def test_rendering_is_deterministic(renderer):
    first, second = renderer.render(market_scene()), renderer.render(market_scene())
    assert np.array_equal(first.colour, second.colour)
    assert np.array_equal(first.segmentation, second.segmentation)
    assert np.array_equal(first.depth, second.depth)


def test_renders_a_scene_with_only_paths(renderer):
    result = renderer.render(scene_of([], [road("road_1", [[-5, 0], [5, 0]])]))
    assert result.ids == ["road_1"] and result.visible["road_1"] == pytest.approx(1.0)


def test_saved_images_round_trip(market, tmp_path):
    files = save_render(market, tmp_path, stem="view")
    assert {p.name for p in files.values()} == {
        "view.png",
        "view_depth.png",
        "view_depth.npy",
        "view_depth.json",
        "view_seg.png",
        "view_ids.json",
        "view_3d.json",
    }
    assert np.array_equal(np.load(files["depth_metres"]), market.depth)
    assert json.loads(files["depth_scale"].read_text()) == {"metres_per_unit": 0.001, "sky": 0}
    assert np.array_equal(np.asarray(Image.open(files["colour"]).convert("RGB")), market.colour)
    depth = np.asarray(Image.open(files["depth"]))
    assert depth.dtype == np.uint16
    assert np.array_equal(depth, np.round(market.depth * 1000).astype(np.uint16))
    assert np.array_equal(np.asarray(Image.open(files["segmentation"])), market.segmentation)
    assert json.loads(files["ids"].read_text()) == {str(k + 1): i for k, i in enumerate(market.ids)}
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted(
        p.name for p in files.values()
    )  # no temp files
    encoded = encode_render(market, stem="view")
    assert all(files[kind].read_bytes() == data for kind, (_, data) in encoded.items())


def test_metadata_for_scene_json(market):
    metadata = render_metadata(market)
    assert metadata["camera"]["view"] == "perspective" and len(metadata["camera"]["pose"]) == 4
    assert list(metadata["objects"]) == market.ids
    assert metadata["objects"]["house_1"]["bbox"] == market.boxes["house_1"]
    json.dumps(metadata)  # plain JSON types only


def test_missing_backend_is_a_clear_one_line_error():
    code = (
        "from scenewright.render.offscreen import Renderer\n"
        "from scenewright.core.errors import GenerationError\n"
        "try:\n    Renderer(8, 8)\nexcept GenerationError as error:\n    print(error)\n"
    )
    done = run_without_opengl(code)
    lines = done.stdout.strip().splitlines()
    assert done.returncode == 0, done.stderr
    assert len(lines) == 1 and "Traceback" not in done.stderr
    assert (
        "PYOPENGL_PLATFORM='no-such-platform'" in lines[0] and "apt-get install libegl1" in lines[0]
    )


def test_unknown_view_is_an_input_error(renderer):
    with pytest.raises(InputError, match="unknown view 'side'; choose one of: perspective, top"):
        renderer.render(market_scene(), "side")


def test_an_empty_scene_shows_its_ground(renderer):
    result = renderer.render(scene_of([], extent=(10.0, 10.0)))
    assert result.ids == [] and result.boxes == {} and not result.segmentation.any()
    assert (result.depth > 0).any()  # the camera frames the extent, so ground is seen


def test_a_degenerate_path_is_not_drawn(renderer):
    scene = scene_of([thing("crate_1")], [road("road_1", [[3, 3], [3, 3]], start="crossing_1")])
    result = renderer.render(scene)
    assert result.ids == ["crate_1"]


def test_visible_fractions_equal_a_brute_force_count(renderer):
    # Boxes in a row towards the camera hide one another in part; one road runs under them.
    row = [
        thing(f"crate_{k}", (1.2 * k, 0, 1.2 * k), (1.0, 1.0 + 0.3 * k, 1.0)) for k in range(1, 6)
    ]
    scene = scene_of(
        row + [thing("crossing_1", (-4, 0, 4), (3, 0, 3), kind="junction", shape=None)],
        [
            road("road_1", [[-4, 4], [4, -4]], start="crossing_1"),
            road("road_2", [[-4, 4], [-8, 8]]),
        ],
    )
    result = renderer.render(scene)

    from scenewright.render.offscreen import _decode_index, _entities, _index_colour, _show_merged

    camera = Camera.from_dict(result.camera)
    entities = _entities(scene, camera)
    world, merged, _ = renderer._build(scene, camera, entities)
    _show_merged(merged, entities, False)  # each entity's own mesh, as the segmentation passes draw
    gl = renderer._gl
    ground_layer = {"crossing_1", "road_1", "road_2"}
    for k, entity in enumerate(entities):
        # Drawn by itself (with the rest of the ground layer, for roads and junctions).
        company = ground_layer if entity.id in ground_layer else {entity.id}
        seg_map = {e.node: _index_colour(j + 1) for j, e in enumerate(entities) if e.id in company}
        seg, _ = renderer._renderer.render(world, flags=gl.RenderFlags.SEG, seg_node_map=seg_map)
        alone = np.count_nonzero(_decode_index(seg) == k + 1)
        seen = np.count_nonzero(result.segmentation == k + 1)
        assert result.visible[entity.id] == pytest.approx(seen / alone), entity.id
    assert min(result.visible[f"crate_{k}"] for k in range(1, 5)) < 0.9  # the row does hide itself


def test_the_merged_colour_pass_draws_what_one_node_per_entity_draws(renderer, market):
    """The colour pass draws every entity as one mesh in world coordinates; drawing each
    as its own node with its pose gives the same picture (but for rounding at edges)."""
    from scenewright.render.offscreen import _entities, _show_merged

    merged_colour, scene = market.colour, market_scene()
    camera = Camera.from_dict(market.camera)
    entities = _entities(scene, camera)
    world, merged, _ = renderer._build(scene, camera, entities)
    _show_merged(merged, entities, False)
    per_node, _ = renderer._renderer.render(
        world, flags=renderer._gl.RenderFlags.SHADOWS_DIRECTIONAL
    )
    differs = np.abs(per_node[..., :3].astype(int) - merged_colour.astype(int)).max(axis=2) > 8
    assert differs.mean() < 0.005
    assert len(np.unique(merged_colour.reshape(-1, 3), axis=0)) > 50  # a picture, not a blank


placements = st.lists(
    st.tuples(
        st.floats(-12, 12),
        st.floats(-8, 8),  # x, z
        st.floats(0.3, 4),
        st.floats(0.3, 6),
        st.floats(0.3, 4),  # w, h, d
        st.floats(0, 2 * math.pi),  # yaw
    ),
    min_size=1,
    max_size=6,
)


@settings(
    max_examples=12, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture]
)
@given(placements, st.sampled_from(["perspective", "top"]))
def test_ground_truth_is_consistent_for_any_small_scene(renderer, placed, view):
    objects = [
        thing(f"crate_{k}", (x, 0, z), (w, h, d), yaw=yaw)
        for k, (x, z, w, h, d, yaw) in enumerate(placed, 1)
    ]
    result = renderer.render(scene_of(objects, [road("road_1", [[-10, 9], [10, 9]])]), view)
    assert result.ids == [o.id for o in objects] + ["road_1"]
    assert set(np.unique(result.segmentation).tolist()) <= set(range(len(result.ids) + 1))
    assert np.all(result.depth[result.segmentation > 0] > 0)  # whatever is labelled has a depth
    for index, entity_id in enumerate(result.ids, start=1):
        assert 0.0 <= result.visible[entity_id] <= 1.0
        if (result.segmentation == index).any():
            x0, y0, x1, y1 = result.boxes[entity_id]
            assert 0 <= x0 < x1 <= 160 and 0 <= y0 < y1 <= 120
        else:
            assert entity_id not in result.boxes and result.visible[entity_id] == 0.0
    # The automatic camera frames everything: every object's centre lands in the image.
    pixels, _ = Camera.from_dict(result.camera).project(
        [[o.position[0], o.size[1] / 2, o.position[2]] for o in objects]
    )
    assert np.all((pixels >= 0) & (pixels < [160, 120]))


@pytest.mark.parametrize(
    "size, side", [((64, 48), 256), ((256, 256), 1024), ((512, 512), 2048), ((4096, 2048), 2048)]
)
def test_the_shadow_map_has_about_one_texel_per_pixel_up_to_pyrenders_size(size, side):
    from scenewright.render.offscreen import GROUND_MARGIN, shadow_map_size

    assert shadow_map_size(*size) == side
    assert side >= min(GROUND_MARGIN * max(size), 2048) > side / 2 or side == 2048


@pytest.mark.parametrize("size", [(256, 256), (96, 72)])
def test_shadows_fall_with_a_smaller_shadow_map_too(size):
    # pyrender draws the shadow map with its default size's viewport whatever the map's
    # size: a smaller map held only a corner of the sun's view and no shadow showed.
    from scenewright.render.offscreen import Renderer, shadow_map_size

    assert shadow_map_size(*size) < 2048
    scene = build_scene("village", 3)
    colours = {}
    for shadows in (True, False):
        with or_skip_without_opengl(
            lambda shadows=shadows: Renderer(*size, shadows=shadows)
        ) as renderer:
            colours[shadows] = renderer.render(scene).colour.astype(int).sum(axis=-1)
    darker = colours[True] < colours[False] - 30
    assert darker.mean() > 0.005  # shadows beside the buildings and trees
    assert not (colours[True] > colours[False] + 30).any()  # a shadow only darkens
