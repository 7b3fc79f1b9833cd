"""Referring expressions: every form, programs that run to exactly their object."""

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from test_describer_e2e import is_kind_of  # the reader's own kind test: an armchair is a chair
from test_visibility import hidden_tiny_and_row

from scenewright.describer.refexp import (
    DEPTH_MARGIN,
    SIDE_MARGIN,
    PictureFacts,
    ProgramError,
    Seen,
    execute,
    referring_expressions,
)
from scenewright.render.visibility import PictureView


def facts(*objects) -> PictureFacts:
    return PictureFacts([Seen(*o) for o in objects])


def expressions(picture: PictureFacts) -> dict[str, str]:
    return {e["id"]: e["text"] for e in referring_expressions(picture)}


def test_each_form_picks_out_its_object():
    picture = facts(
        ("tent_1", "tent", 100, 10.0),
        ("sign_1", "sign", 40, 12.0),
        ("sign_2", "sign", 160, 12.2),
        ("chair_1", "chair", 10, 20.0),
        ("chair_2", "chair", 30, 8.0),
        ("chair_3", "chair", 200, 15.0),
        ("chair_4", "chair", 201, 30.0),
    )
    found = expressions(picture)
    assert found["tent_1"] == "the tent"
    assert found["sign_1"] == "the sign to the left of the tent"
    assert found["sign_2"] == "the sign to the right of the tent"
    assert found["chair_1"] == "the first chair from the left"
    assert found["chair_2"] == "the second chair from the left"
    # chair_3 and chair_4 are 1 pixel apart: no order across the picture, and both are
    # right of the tent; but their depths differ by far more than the margin.
    assert "chair_3" not in found  # neither nearest (chair_2 is) nor farthest (chair_4 is)
    assert found["chair_4"] == "the farthest chair"


def test_an_object_nothing_sets_apart_gets_no_expression():
    picture = facts(
        ("cup_1", "cup", 50, 3.0), ("cup_2", "cup", 50 + SIDE_MARGIN / 2, 3.0 + DEPTH_MARGIN / 2)
    )
    assert referring_expressions(picture) == []


def test_a_noun_with_a_kind_in_the_picture_names_nothing():
    # A music room's picture (dataset row 0 of a user's music_room.rules) gave "the chair"
    # for the chair and "the armchair" for the plain armchair beside a green armchair.
    picture = facts(
        ("chair_1", "chair", 20, 3.0),
        ("armchair_1", "green armchair", 60, 4.0),
        ("armchair_2", "armchair", 100, 5.0),
        ("piano_1", "piano", 140, 6.0),
    )
    found = expressions(picture)
    assert "chair_1" not in found and "armchair_2" not in found
    assert found["armchair_1"] == "the green armchair" and found["piano_1"] == "the piano"
    # Nor is such a noun an anchor: "the lamp to the right of the chair" would ask a
    # reader which chair. Without the armchair it is said.
    lamps = [
        ("chair_1", "chair", 50, 3.0),
        ("lamp_1", "lamp", 100, 5.0),
        ("lamp_2", "lamp", 10, 5.0),
    ]
    assert expressions(facts(*lamps))["lamp_1"] == "the lamp to the right of the chair"
    beside_an_armchair = expressions(facts(*lamps, ("armchair_1", "armchair", 200, 3.0)))
    assert beside_an_armchair == {
        "armchair_1": "the armchair",
        "lamp_1": "the second lamp from the left",
        "lamp_2": "the first lamp from the left",
    }


def test_programs_run_to_their_object_and_fail_loudly_otherwise():
    picture = facts(
        ("tent_1", "tent", 100, 10.0), ("sign_1", "sign", 40, 12.0), ("sign_2", "sign", 160, 12.2)
    )
    for expression in referring_expressions(picture):
        assert execute(expression["program"], picture) == expression["id"]
    the_sign = [
        {"function": "scene", "inputs": [], "value_inputs": []},
        {"function": "filter_noun", "inputs": [0], "value_inputs": ["sign"]},
        {"function": "unique", "inputs": [1], "value_inputs": []},
    ]
    with pytest.raises(ProgramError, match="2 objects, not one"):
        execute(the_sign, picture)
    both = the_sign[:2] + [{"function": "intersect", "inputs": [0, 1], "value_inputs": []}]
    assert execute(both, picture) == ["sign_1", "sign_2"]


#: "armchair" is a kind of chair and "green armchair" of armchair (a style's noun).
NOUNS = ["tent", "sign", "chair", "armchair", "green armchair"]


@settings(max_examples=80, deadline=None)
@given(
    st.lists(
        st.tuples(st.sampled_from(NOUNS), st.integers(0, 60), st.integers(0, 20)),
        min_size=1,
        max_size=9,
    )
)
def test_every_expression_is_true_and_unique_by_an_independent_count(drawn):
    picture = facts(
        *[
            (f"{noun}_{k}", noun, float(across), depth / 2)
            for k, (noun, across, depth) in enumerate(drawn)
        ]
    )
    seen = list(picture.objects.values())
    for expression in referring_expressions(picture):
        me = picture.objects[expression["id"]]
        assert execute(expression["program"], picture) == me.id
        words = expression["text"].split()
        alike = [o for o in seen if is_kind_of(o.noun, me.noun)]  # what a reader takes the noun for
        if expression["text"] == f"the {me.noun}":
            assert alike == [me]
        elif "of the" in expression["text"]:  # "the sign to the left of the tent"
            anchor_noun, side = (
                expression["text"].split(" of the ")[1],
                words[words.index("to") + 2],
            )
            anchors = [o for o in seen if is_kind_of(o.noun, anchor_noun)]
            assert len(anchors) == 1
            sign = -1 if side == "left" else 1
            matching = [o for o in alike if sign * (o.across - anchors[0].across) >= SIDE_MARGIN]
            assert matching == [me]
        elif "from the" in expression["text"]:
            side = words[-1]
            ordered = sorted(alike, key=lambda o: o.across if side == "left" else -o.across)
            place = ordered.index(me) + 1
            assert expression["program"][-1]["value_inputs"] == [side, str(place)]
            assert (
                sum(
                    1
                    for o in alike
                    if (o.across < me.across if side == "left" else o.across > me.across)
                )
                == place - 1
            )
            neighbours = ordered[max(place - 2, 0) : place - 1] + ordered[place : place + 1]
            assert all(abs(o.across - me.across) >= SIDE_MARGIN for o in neighbours)
        else:
            which = words[1]
            others = [o.depth for o in alike if o is not me]
            if which == "nearest":
                assert all(d >= me.depth + DEPTH_MARGIN for d in others)
            else:
                assert all(d <= me.depth - DEPTH_MARGIN for d in others)


def test_a_rendered_picture_s_expressions_name_only_what_it_shows(renderer):
    scene = hidden_tiny_and_row()
    picture = PictureView.from_render(renderer.render(scene), scene)
    seen = PictureFacts.of(scene, picture)
    assert set(seen.objects) == {"crate_1", "post_1", "post_2", "wall_slab_1"}
    found = {e["id"]: e for e in referring_expressions(seen)}
    assert found["crate_1"]["text"] == "the crate"
    # The slab stands between the posts across the picture (post_1 on the left), and
    # both posts are left of the crate.
    assert found["post_1"]["text"] == "the post to the left of the wall slab"
    assert found["post_2"]["text"] == "the post to the right of the wall slab"
    for expression in found.values():
        assert execute(expression["program"], seen) == expression["id"]
