"""Drawn cameras: ranges and their errors, seeded draws, the aimed framing, the
recorded intrinsics and extrinsics, several views per scene in a dataset, and
``generate --camera``."""

from __future__ import annotations

import json
import math
from importlib import resources

import jsonschema
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from render_fixtures import market_scene, renderer_or_skip, scene_of, thing
from test_dataset import dataset_bytes

from scenewright.cli import main
from scenewright.core.errors import InputError
from scenewright.core.seeds import stream
from scenewright.dataset.run import run_dataset
from scenewright.dataset.spec import METADATA_FILE, dataset_spec
from scenewright.render.camera import FILL, aimed_camera, entity_points, frame_scene, scene_points
from scenewright.render.views import (
    CameraRanges,
    aimed_view,
    camera_column,
    parse_camera,
    parse_range,
)

# -- ranges and draws ---------------------------------------------------------------


def test_ranges_parse_single_values_and_low_high():
    assert parse_range("30", "azimuth") == (30.0, 30.0)
    assert parse_range("-90:270", "azimuth") == (-90.0, 270.0)
    assert parse_range(" 20 : 60 ", "elevation") == (20.0, 60.0)
    assert parse_range(".8:1.25", "distance") == (0.8, 1.25)
    assert parse_camera("azimuth=30,elevation=10:50,target=table") == CameraRanges(
        azimuth=(30.0, 30.0), elevation=(10.0, 50.0), target="table"
    )


@pytest.mark.parametrize(
    ("text", "name", "message"),
    [
        ("60:20", "elevation", "runs backwards"),
        ("90", "elevation", "must lie within 0:89"),
        ("-5:10", "elevation", "must lie within 0:89"),
        ("0.05", "distance", "must lie within 0.1:10"),
        ("0:361", "azimuth", "more than a full turn"),
        ("inf", "azimuth", "a number or a range"),
        ("1e400", "azimuth", "a number or a range"),
        ("1:2:3", "azimuth", "a number or a range"),
        ("", "distance", "a number or a range"),
    ],
)
def test_bad_ranges_are_input_errors_of_one_line(text, name, message):
    with pytest.raises(InputError, match=message) as caught:
        parse_range(text, name)
    assert "\n" not in str(caught.value)


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("azimuth", "KEY=VALUE"),
        ("zoom=2", "unknown --camera key"),
        ("azimuth=1,azimuth=2", "twice"),
        ("elevation=95", "within 0:89"),
        ("target=", "KEY=VALUE"),
    ],
)
def test_bad_camera_settings_are_input_errors(text, message):
    with pytest.raises(InputError, match=message):
        parse_camera(text)


@settings(max_examples=40, deadline=None)
@given(
    st.tuples(st.floats(-360, 360), st.floats(0, 360)).map(lambda a: (a[0], a[0] + a[1])),
    st.tuples(st.floats(0, 89), st.floats(0, 89)).map(sorted),
    st.tuples(st.floats(0.1, 10), st.floats(0.1, 10)).map(sorted),
    st.integers(0, 2**63 - 1),
    st.integers(0, 50),
)
def test_draws_stay_in_their_ranges_and_depend_on_seed_and_view_only(
    azimuth, elevation, distance, seed, view
):
    ranges = CameraRanges(azimuth=azimuth, elevation=tuple(elevation), distance=tuple(distance))
    drawn = [ranges.draw(stream(seed, "camera", view), default_azimuth=35.0) for _ in range(2)]
    assert drawn[0] == drawn[1]
    for value, (low, high) in zip(
        drawn[0], (ranges.azimuth, ranges.elevation, ranges.distance), strict=True
    ):
        assert low <= value <= high


def test_unset_ranges_take_the_automatic_values_and_views_differ():
    fixed = CameraRanges().draw(stream(7, "camera", 0), default_azimuth=35.0)
    assert fixed == (35.0, pytest.approx(35.0), 1.0)
    ranges = CameraRanges(azimuth=(0.0, 360.0))
    assert ranges.draw(stream(7, "camera", 0), 35.0) != ranges.draw(stream(7, "camera", 1), 35.0)


# -- the aimed framing and what a row records ------------------------------------------


@settings(max_examples=40, deadline=None)
@given(
    st.floats(-180, 180),
    st.floats(0, 89),
    st.sampled_from([None, "house_1", "market_stand_1", "road_1"]),
)
def test_an_aimed_camera_centres_its_target_and_frames_it_at_distance_one(
    azimuth, elevation, target
):
    scene = market_scene()
    camera = aimed_camera(
        scene,
        320,
        240,
        azimuth=math.radians(azimuth),
        elevation=math.radians(elevation),
        target=target,
    )
    points = (
        scene_points(scene, camera.pose[:3, 2]) if target is None else entity_points(scene, target)
    )
    centre = (points.min(axis=0) + points.max(axis=0)) / 2
    assert np.allclose(camera.project(centre)[0][0], [160, 120], atol=1e-6)
    pixels, depth = camera.project(points)
    reach = (np.abs(pixels - [160, 120]) / [160, 120]).max()
    assert np.all(depth > 0) and reach <= FILL + 1e-6
    if target in (
        None,
        "market_stand_1",
    ):  # big enough that MIN_DISTANCE does not hold the camera back
        assert reach >= FILL - 1e-6
    farther = aimed_camera(
        scene,
        320,
        240,
        azimuth=math.radians(azimuth),
        elevation=math.radians(elevation),
        target=target,
        distance=2.0,
    )
    near, far = (np.linalg.norm(c.pose[:3, 3] - centre) for c in (camera, farther))
    assert far == pytest.approx(2 * near)


def test_the_recorded_intrinsics_and_extrinsics_project_as_the_camera_does():
    for camera in (
        frame_scene(market_scene(), "perspective", 320, 240),
        frame_scene(market_scene(), "top", 200, 100),
        aimed_camera(market_scene(), 64, 48, azimuth=2.0, elevation=0.3, target="sign_1"),
    ):
        column = camera_column(camera.to_dict())
        points = scene_points(market_scene())
        expected, _ = camera.project(points)
        assert np.allclose(project_with_column(column, points), expected, atol=1e-4)


def project_with_column(column: dict, points) -> np.ndarray:
    """Pixels (N, 2) of world points through a row's ``camera`` column, as the docs say."""
    world = np.column_stack([points, np.ones(len(points))])
    x, y, z = (np.asarray(column["world_to_camera"]) @ world.T)[:3]
    if column["projection"] == "perspective":
        x, y = x / z, y / z
    return np.column_stack([column["fx"] * x + column["cx"], column["fy"] * y + column["cy"]])


def test_a_rendered_aimed_view_shows_objects_where_its_camera_projects_them():
    renderer = renderer_or_skip(96, 72)
    ranges = CameraRanges(azimuth=(0.0, 360.0), elevation=(20.0, 60.0), distance=(0.9, 1.1))
    for view in range(3):
        result = aimed_view(renderer, market_scene(), ranges, stream(3, "camera", view))
        column = camera_column(result.camera)
        assert result.camera["aim"]["tries"] >= 1 and 0.9 <= column["distance"] <= 1.1
        for obj in market_scene().placed_objects():
            if result.visible[obj.id] < 1.0:
                continue
            centre = np.array([obj.position[0], obj.position[1] + obj.size[1] / 2, obj.position[2]])
            ((u, v),) = project_with_column(column, centre[None])
            x0, y0, x1, y1 = result.boxes[obj.id]
            assert x0 <= u <= x1 and y0 <= v <= y1, (view, obj.id)


def test_in_a_room_no_wall_stands_between_an_aimed_camera_and_the_room():
    """From any side, the walls drawn are the far ones: a box in the room shows as many
    pixels as it does with no room round it."""
    renderer = renderer_or_skip(64, 64)
    box = thing("box_1", (0.4, 0, 0.3), (0.8, 0.8, 0.8))
    roomed, bare = (
        scene_of([box], extent=(5.0, 4.0), walls=True),
        scene_of([box], extent=(5.0, 4.0)),
    )
    for azimuth in range(0, 360, 45):
        camera = aimed_camera(
            roomed,
            64,
            64,
            azimuth=math.radians(azimuth),
            elevation=math.radians(15),
            target="box_1",
        )
        pixels = [
            int((renderer.render(s, camera=camera).segmentation == 1).sum()) for s in (roomed, bare)
        ]
        assert pixels[0] == pixels[1] > 100, azimuth


def test_a_view_is_drawn_again_until_its_target_shows_enough():
    """A table north of a tall house, seen from afar and low: draws from the south see the
    house instead."""
    renderer = renderer_or_skip(64, 48)
    scene = scene_of(
        [thing("house_1", (0, 0, 0), (4, 4, 4)), thing("table_1", (0, 0, -5), (1, 0.8, 1))]
    )
    ranges = CameraRanges(
        azimuth=(0.0, 360.0),
        elevation=(5.0, 10.0),
        distance=(5.0, 5.0),
        target="table",
        min_visible=0.9,
        tries=12,
    )
    tries = []
    for view in range(6):
        aim = aimed_view(renderer, scene, ranges, stream(1, "camera", view)).camera["aim"]
        assert aim["target"] == "table_1" and (aim["target_visible"] >= 0.9 or aim["tries"] == 12)
        tries.append(aim["tries"])
    assert max(tries) > 1


# -- datasets and the command line ----------------------------------------------------


def views_spec():
    ranges = CameraRanges(azimuth=(0.0, 360.0), elevation=(20.0, 60.0), distance=(0.8, 1.2))
    return dataset_spec("desk", 2, size=(48, 48), views=2, camera=ranges)


@pytest.mark.slow
def test_several_views_per_scene_are_rows_of_their_own_whatever_the_workers(tmp_path):
    run_dataset(views_spec(), tmp_path / "one", workers=1, progress=False)
    rows = [
        json.loads(line) for line in (tmp_path / "one" / METADATA_FILE).read_text().splitlines()
    ]
    assert [(r["scene_id"], r["view"], r["file_name"]) for r in rows] == [
        ("000000", 0, "images/000000_0.png"),
        ("000000", 1, "images/000000_1.png"),
        ("000001", 0, "images/000001_0.png"),
        ("000001", 1, "images/000001_1.png"),
    ]
    assert rows[0]["camera"]["world_to_camera"] != rows[1]["camera"]["world_to_camera"]
    assert rows[0]["text"] == rows[1]["text"]
    coco = json.loads((tmp_path / "one" / "annotations" / "instances.json").read_text())
    assert [image["id"] for image in coco["images"]] == [1, 2, 3, 4]
    schema = json.loads(
        resources.files("scenewright.dataset")
        .joinpath("schema/metadata_row.schema.json")
        .read_text()
    )
    for row in rows:
        jsonschema.validate(row, schema)
        camera = row["camera"]
        assert 20 <= camera["elevation"] <= 60 and 0.8 <= camera["distance"] <= 1.2
        assert (camera["width"], camera["height"], camera["cx"]) == (48, 48, 24.0)
        scene = json.loads((tmp_path / "one" / "scenes" / f"{row['scene_id']}.json").read_text())
        table = next(o for o in scene["objects"] if o["type"] == "table")
        centre = np.array(
            [
                table["position"][0],
                table["position"][1] + table["size"][1] / 2,
                table["position"][2],
            ]
        )
        ((u, v),) = project_with_column(camera, centre[None])
        image_id = int(row["scene_id"]) * 2 + row["view"] + 1
        x, y, w, h = next(
            a["bbox"]
            for a in coco["annotations"]
            if a["image_id"] == image_id and a["entity_id"] == table["id"]
        )
        assert x <= u <= x + w and y <= v <= y + h
    run_dataset(views_spec(), tmp_path / "two", workers=2, progress=False)
    assert dataset_bytes(tmp_path / "two") == dataset_bytes(tmp_path / "one")


@pytest.mark.parametrize(
    "options",
    [
        ["--azimuth", "90:10"],
        ["--elevation", "0:120"],
        ["--distance", "x"],
        ["--views", "3"],
        ["--views", "2", "--azimuth", "0:90", "--view", "top"],
        ["--target-visible", "1.5"],
    ],
)
def test_bad_camera_options_exit_2_with_one_line_and_write_nothing(options, tmp_path, capsys):
    assert main(["dataset", "desk", "-n", "1", "-o", str(tmp_path / "out"), *options]) == 2
    error = capsys.readouterr().err
    assert error.startswith("scenewright: error: ") and error.count("\n") == 1
    assert not (tmp_path / "out").exists()


def test_generate_camera_writes_the_preview_from_that_camera(tmp_path):
    from render_fixtures import or_skip_without_opengl

    argv = ["generate", "desk", "--seed", "4", "--size", "64x48", "-q", "-o", str(tmp_path)]
    code = or_skip_without_opengl(
        lambda: main([*argv, "--camera", "azimuth=200,elevation=50,distance=1.3"])
    )
    assert code == 0 and (tmp_path / "preview.png").is_file()
    document = json.loads((tmp_path / "scene.json").read_text())
    camera = document["render"]["camera"]
    assert camera["aim"] == {
        "azimuth": 200.0,
        "elevation": 50.0,
        "distance": 1.3,
        "target": None,
        "target_visible": camera["aim"]["target_visible"],
        "tries": 1,
    }
    from scenewright.core.scene import Scene

    scene = Scene.from_dict(document)
    expected = aimed_camera(
        scene, 64, 48, azimuth=math.radians(200), elevation=math.radians(50), distance=1.3
    )
    assert np.allclose(camera["pose"], expected.pose)
    assert not np.allclose(camera["pose"], frame_scene(scene, "perspective", 64, 48).pose)
    assert main([*argv, "--camera", "target=zebra"]) == 2
