"""What a rendered picture shows: visible enough to name, boxes, between, picture sides."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from render_fixtures import scene_of, thing

from scenewright.core.errors import InputError
from scenewright.render.camera import frame_scene
from scenewright.render.visibility import PictureView, Thresholds, world_centres


def hidden_tiny_and_row():
    """A big crate hiding a cube behind it (as the south-east camera sees it), a pebble
    too small to see, and three posts in a row across the picture, the middle one tall."""
    return scene_of(
        [
            thing("crate_1", (0, 0, 0), (4, 4, 4)),
            thing("cube_1", (-2.4, 0, -3.2), (0.6, 0.6, 0.6)),
            thing("pebble_1", (6, 0, -6), (0.3, 0.3, 0.3)),
            # Across the picture: the camera's right is (0.82, 0, -0.57) on the ground.
            thing("post_1", (-9.3, 0, 12.3), (1.5, 2.5, 1.5)),
            thing("wall_slab_1", (-6, 0, 10), (2.0, 5.0, 2.0)),
            thing("post_2", (-2.7, 0, 7.7), (1.5, 2.5, 1.5)),
        ]
    )


@pytest.fixture(scope="module")
def picture(renderer):
    scene = hidden_tiny_and_row()
    result = renderer.render(scene)
    return scene, result, PictureView.from_render(result, scene)


def test_visible_fraction_and_box_come_from_the_render(picture):
    _, result, view = picture
    for entity_id in result.ids:
        assert view.entities[entity_id].visible == result.visible[entity_id]
        assert view.box(entity_id) == result.boxes.get(entity_id)
        assert view.entities[entity_id].pixels == int(
            (result.segmentation == result.ids.index(entity_id) + 1).sum()
        )


def test_only_what_is_visible_enough_is_seen(picture):
    _, result, view = picture
    assert view.seen("crate_1")
    assert result.visible["cube_1"] < 0.25 and not view.seen("cube_1")
    assert view.entities["pebble_1"].size() < 120 // 16 and not view.seen("pebble_1")
    for entity_id in result.ids:
        entity = view.entities[entity_id]
        assert view.seen(entity_id) == (entity.visible >= 0.25 and entity.size() >= 120 // 16)


def test_the_default_box_size_follows_small_images():
    assert Thresholds().size_in(512, 384) == 16 and Thresholds().size_in(64, 64) == 4
    assert Thresholds(min_size=30).size_in(64, 64) == 30


def test_thresholds_are_settable(picture):
    scene, result, _ = picture
    lenient = PictureView.from_render(result, scene, Thresholds(min_visible=0.0, min_size=1))
    assert all(lenient.seen(i) for i in result.ids if result.boxes.get(i))
    strict = PictureView.from_render(result, scene, Thresholds(min_visible=1.0, min_size=1000))
    assert not any(strict.seen(i) for i in result.ids)


@pytest.mark.parametrize(
    ("settings_", "word"), [({"min_visible": 1.5}, "between 0 and 1"), ({"min_size": -1}, ">= 0")]
)
def test_bad_thresholds_are_refused(settings_, word):
    with pytest.raises(InputError, match=word):
        Thresholds(**settings_)


def test_something_between_two_things_in_the_picture(picture):
    _, _, view = picture
    assert view.seen("post_1") and view.seen("post_2") and view.seen("wall_slab_1")
    assert view.between(["post_1"], ["post_2"])
    assert not view.between(["post_1"], ["post_2"], ignore=["wall_slab_1"])
    assert not view.between(["post_1"], ["wall_slab_1"])


def test_picture_sides_agree_with_the_projection(picture):
    scene, _, view = picture
    (u1, _), (u2, _) = view.camera.project(
        np.stack([view.centres["post_1"], view.centres["post_2"]])
    )[0]
    assert view.picture_side("post_1", "post_2") == ("left" if u1 < u2 else "right")
    assert view.picture_side("post_2", "post_1") == ("right" if u1 < u2 else "left")
    # The cube is straight behind the crate as the camera looks.
    assert view.picture_side("cube_1", "crate_1") == "behind"
    assert view.picture_side("crate_1", "cube_1") == "front"


@settings(max_examples=60, deadline=None)
@given(
    st.lists(
        st.tuples(st.floats(-10, 10), st.floats(-10, 10)), min_size=2, max_size=2, unique=True
    ),
    st.sampled_from(["perspective", "top"]),
)
def test_a_picture_side_is_what_the_projection_shows(places, view_name):
    (ax, az), (bx, bz) = places
    if math.hypot(ax - bx, az - bz) < 0.5:
        return
    scene = scene_of([thing("box_1", (ax, 0, az)), thing("box_2", (bx, 0, bz))])
    camera = frame_scene(scene, view_name, 160, 120)
    view = PictureView(
        camera, np.zeros((120, 160), dtype=np.int32), [], {}, world_centres(scene), frozenset()
    )
    side = view.picture_side("box_1", "box_2")
    (pa, pb), (da, db) = camera.project(np.stack([view.centres["box_1"], view.centres["box_2"]]))
    if side == "left":
        assert pa[0] < pb[0]
    elif side == "right":
        assert pa[0] > pb[0]
    elif side == "front":
        assert da < db and view_name == "perspective"
    elif side == "behind":
        assert da > db and view_name == "perspective"
    opposite = {"left": "right", "right": "left", "front": "behind", "behind": "front", None: None}
    assert view.picture_side("box_2", "box_1") == opposite[side]
