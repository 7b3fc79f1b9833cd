"""Captions of a rendered picture: what it shows, relations that hold in it, picture sides."""

import re
from dataclasses import replace

import numpy as np
import pytest
from render_fixtures import scene_of, thing
from test_visibility import hidden_tiny_and_row

from scenewright.core.errors import InputError
from scenewright.core.room import Room
from scenewright.core.scene import Relation
from scenewright.describer import describe
from scenewright.describer.view import describe_view, view_scene
from scenewright.render.visibility import PictureView, Thresholds


def related(scene, *relations):
    return replace(
        scene,
        relations=[Relation(s, t, label, 0.0, True, chosen) for s, label, t, chosen in relations],
    )


def picture_of(renderer, scene, thresholds=None):
    return PictureView.from_render(renderer.render(scene), scene, thresholds)


def named(description) -> set[str]:
    return {i for m in description.mentions for i in m.ids}


def test_a_caption_names_only_what_the_picture_shows(renderer):
    scene = hidden_tiny_and_row()
    picture = picture_of(renderer, scene)
    caption = describe_view(scene, picture)
    assert (
        "cube" in describe(scene, style="short").text
        and "pebble" in describe(scene, style="short").text
    )
    assert "cube" not in caption.text and "pebble" not in caption.text
    assert named(caption) == {"crate_1", "post_1", "post_2", "wall_slab_1"}
    assert all(picture.seen(i) for i in named(caption))
    everything = describe_view(
        scene, picture_of(renderer, scene, Thresholds(min_visible=0.0, min_size=1))
    )
    assert "pebble" in everything.text  # the thresholds decide


def test_groups_are_counted_and_grounded_by_their_members_in_the_picture(renderer):
    objects = [
        thing("market_stand_1", (0, 0, 0), (4, 4, 4), kind="group", shape=None),
        thing("table_1", (0, 0, 0), (4, 4, 4), parent="market_stand_1"),
        thing("market_stand_2", (-2.4, 0, -3.2), (0.6, 0.6, 0.6), kind="group", shape=None),
        thing(
            "table_2", (-2.4, 0, -3.2), (0.6, 0.6, 0.6), parent="market_stand_2"
        ),  # behind the first
        thing("market_stand_3", (-6, 0, 10), (2, 2, 2), kind="group", shape=None),
        thing("table_3", (-6, 0, 10), (2, 1, 2), parent="market_stand_3"),
        thing("sign_1", (-6, 0, 10.5), (0.3, 2, 0.1), parent="market_stand_3"),
    ]
    scene = scene_of(objects)
    caption = describe_view(scene, picture_of(renderer, scene))
    assert (
        caption.text == "A picture of a test with two market stands."
    )  # one item: link-grammar needs the frame
    stands = next(
        m for m in caption.mentions if caption.text[m.start : m.end] == "two market stands"
    )
    assert "table_2" not in stands.ids and {"table_1", "table_3"} <= set(stands.ids)
    assert "three market stands" in describe(scene, style="short").text


def test_no_relation_through_something_standing_between_in_the_picture(renderer):
    scene = related(hidden_tiny_and_row(), ("post_1", "NextTo", "post_2", None))
    assert "The post is next to the other post." in describe(scene, style="short").text.replace(
        "first ", ""
    )
    caption = describe_view(scene, picture_of(renderer, scene))
    assert "next to" not in caption.text
    without_slab = replace(scene, objects=[o for o in scene.objects if o.id != "wall_slab_1"])
    caption = describe_view(without_slab, picture_of(renderer, without_slab))
    assert re.search(r"post is next to the (other|second) post", caption.text)


@pytest.mark.parametrize("label", ["NextToLeft", "NextToNorth", "NextToChooseSide"])
def test_camera_frame_words_are_the_picture_s(renderer, label):
    base = hidden_tiny_and_row()
    scene = related(
        replace(base, objects=[o for o in base.objects if o.id != "wall_slab_1"]),
        ("post_1", label, "post_2", "right"),
    )
    picture = picture_of(renderer, scene)
    (u1, _), (u2, _) = picture.camera.project(
        np.stack([picture.centres["post_1"], picture.centres["post_2"]])
    )[0]
    side = "left" if u1 < u2 else "right"
    caption = describe_view(scene, picture, frame="camera")
    assert f"is to the {side} of the other post in the picture." in caption.text
    assert ("post_1", "NextToChooseSide", "post_2") in caption.facts
    assert (
        "in the picture" not in describe_view(scene, picture).text
    )  # the scene's frame keeps its words


def test_a_relation_to_a_wall_the_view_cuts_away_is_not_said(renderer):
    room = Room.rectangle(8, 6)
    scene = scene_of(
        [
            thing("wardrobe_1", (0, 0, -2.7), (1.2, 2.0, 0.6)),
            thing("bed_1", (0, 0, 2.0), (1.6, 0.5, 2)),
        ],
        room=room,
    )
    north = next(w.id for w in room.walls if w.side == "north")
    south = next(w.id for w in room.walls if w.side == "south")
    scene = related(
        scene, ("wardrobe_1", "AgainstWall", north, None), ("bed_1", "AgainstWall", south, None)
    )
    picture = picture_of(renderer, scene)
    assert north in picture.walls and south not in picture.walls
    kept = {(r.source, r.target) for r in view_scene(scene, picture).relations}
    assert kept == {("wardrobe_1", north)}


def test_a_picture_that_shows_nothing_says_so_and_not_that_the_scene_is_empty(renderer):
    scene = hidden_tiny_and_row()
    picture = picture_of(renderer, scene, Thresholds(min_size=1000))
    assert describe_view(scene, picture).text == "A picture of a test too small to make out."
    assert describe_view(scene, picture).mentions == []


def test_an_unknown_frame_is_refused(renderer):
    scene = hidden_tiny_and_row()
    with pytest.raises(InputError, match="unknown caption frame"):
        describe_view(scene, picture_of(renderer, scene), frame="viewer")
