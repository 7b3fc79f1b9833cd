"""Composing outdoors: roads meeting at junctions, things next to them, groups, the
outdoor catalog, and the village's own descriptions read back (docs/compose.md)."""

from __future__ import annotations

import subprocess
import sys

from hypothesis import given, settings
from hypothesis import strategies as st

from scenewright.api import build_scene, compose, describe
from scenewright.composer.compose import plan, report_of
from scenewright.composer.outdoor import catalog_for
from scenewright.composer.vocabulary import NUMBERS
from scenewright.generator import load_rules

REQUEST = (
    "a village with two roads meeting at a crossroads, a well next to the first road, "
    "a tower and three cottages along the second road, and a group of trees"
)


def _plan(text, own=None):
    return plan(text, *catalog_for(text, own))


def _by_type(request, type_):
    return [e.id for e in request.entities if e.type == type_]


def _said(request):
    return {(s.source, s.label, s.target) for s in request.statements}


def test_an_everyday_village_request_makes_roads_at_a_junction_and_things_beside_them():
    request, rules = _plan(REQUEST)
    assert not request.issues
    roads = _by_type(request, "road")
    (junction,) = _by_type(request, "intersection")  # "crossroads": the catalog's junction
    said = _said(request)
    assert {(r, "PathConnectedTo", junction) for r in roads} <= said
    (well,) = _by_type(request, "well")
    assert (well, "NextTo", roads[0]) in said
    cottages = [e for e in request.entities if e.type == "house"]
    assert [e.style for e in cottages] == ["cottage"] * 3
    assert {(c.id, "NextTo", roads[1]) for c in cottages} <= said
    # the junction is made first, each road after it, on open ground
    body = rules[rules.index("Compose ->") :]
    assert body.index(f"intersection as {junction}") < body.index(f"road as {roads[0]}")
    assert f"road as {roads[0]} PathConnectedTo {junction}" in body
    assert "extent 60 x 60" in rules and "ground grass" in rules and "room " not in rules
    assert "path road {" in rules and "junction intersection {" in rules


def test_the_composed_village_restates_its_roads_and_what_stands_beside_them():
    scene, report = compose(REQUEST, seed=4)
    assert report.messages() == [] and report.conflicts() == []
    text = scene.description.text
    assert text.startswith("The scene consists of two roads meeting at an intersection")
    assert "The well is next to the first road." in text
    assert "The group of trees consists of two pine trees and a bush." in text
    assert len(scene.paths) == 2 and scene.layout.ok


def test_a_group_named_alone_holds_what_its_noun_means_and_stays_together():
    request, rules = _plan("a village with a road and a group of trees next to the road")
    (group,) = [e for e in request.entities if e.group]
    members = [e for e in request.entities if e.parent == group.id]
    assert sorted(e.type for e in members) == ["bush", "pine_tree", "pine_tree"]
    # implicit (never described): kept next to the first member
    assert all((m.id, "ImplicitNextTo", members[0].id) in _said(request) for m in members[1:])


def test_many_roads_are_shared_out_among_their_junctions():
    text = "The scene consists of twelve roads meeting four at each of three intersections."
    request, _ = _plan(text)
    assert not request.issues
    junctions = _by_type(request, "intersection")
    assert len(junctions) == 3 and len(_by_type(request, "road")) == 12
    starts = [t for _, label, t in _said(request) if label == "PathConnectedTo"]
    assert sorted(starts.count(j) for j in junctions) == [4, 4, 4]


@settings(max_examples=15, deadline=None)
@given(st.integers(1, 6))
def test_every_road_named_before_meeting_at_starts_there(n):
    word = next(w for w, k in NUMBERS.items() if k == n and " " not in w and w != "single")
    plural = "road" if n == 1 else "roads"
    request, _ = _plan(f"a village with {word} {plural} meeting at an intersection")
    assert not request.issues
    (junction,) = _by_type(request, "intersection")
    roads = _by_type(request, "road")
    assert len(roads) == n
    assert {(r, "PathConnectedTo", junction) for r in roads} <= _said(request)


def test_a_lane_branching_off_a_road_starts_on_it_and_is_made_after_it():
    request, rules = _plan(
        "a town with a road and a lane branching off it, two sheds along the lane"
    )
    assert not request.issues
    (road,), (lane,) = _by_type(request, "road"), _by_type(request, "lane")
    assert (lane, "PathConnectedTo", road) in _said(request)
    assert rules.index(f"road as {road}") < rules.index(f"lane as {lane} PathConnectedTo {road}")
    assert all((s, "NextTo", lane) in _said(request) for s in _by_type(request, "shed"))


def test_other_and_large_ordinals_count_as_the_describer_does():
    text = (
        "The scene consists of a road, a lane and forty homes. Seven of the homes are next "
        "to the road. Thirty-two other homes are next to the lane. The fortieth home is "
        "next to the road. The first home consists of a house."
    )
    request, _ = _plan(text, load_rules("town"))
    assert not request.issues
    homes = _by_type(request, "home")
    assert len(homes) == 40  # "other homes" are homes named before, not new ones
    said = _said(request)
    (road,), (lane,) = _by_type(request, "road"), _by_type(request, "lane")
    assert sum((h, "NextTo", road) in said for h in homes) == 8
    assert sum((h, "NextTo", lane) in said for h in homes) == 32
    assert (homes[-1], "NextTo", road) in said
    big = "The scene consists of a road and two hundred homes. The one hundred and first home is next to the road."
    request, _ = _plan(big, load_rules("town"))
    assert not request.issues
    assert len(_by_type(request, "home")) == 200


def test_groups_within_groups_are_written_as_nested_blocks():
    text = (
        "The scene consists of a road and a market. The market is next to the road. The "
        "market consists of a well and two market stands. The two market stands are next "
        "to this well. The first market stand consists of a sign to the left of a table. "
        "A book is on top of this table."
    )
    request, rules = _plan(text, load_rules("town"))
    assert not request.issues
    market = _by_type(request, "market")[0]
    stand = _by_type(request, "market_stand")[0]
    (book,) = _by_type(request, "book")
    assert rules.index(f"market as {market}") < rules.index(f"market_stand as {stand}")
    assert f"        market_stand as {stand}" in rules  # inside the market's block
    assert f"            book as {book} OnTopOf" in rules  # and the stand's
    assert next(e for e in request.entities if e.id == book).parent == stand


def test_the_village_s_own_description_reads_back_whole():
    rules = load_rules("village")
    source = build_scene(rules, 1000)
    text = describe(source, style="full").text
    scene, report = compose(text, 1000, catalog=rules)
    assert report.messages() == [] and report.conflicts() == []
    again = scene.description.text
    for sentence in (
        "The scene consists of three roads meeting at an intersection",
        "The first street lamp is next to the intersection.",
        "The blacksmith forge faces away from the tower.",
        "The first market stand consists of a sign to the left of a table.",
    ):
        assert sentence in text and sentence in again
    assert {(s.type) for s in scene.paths} == {"road"}


def test_outdoors_the_nouns_are_the_outdoor_catalog_s_and_indoors_stays_indoors():
    entries, _, ground = catalog_for("a kitchen with a table")
    assert ground is None and "refrigerator" in entries and "road" not in entries
    entries, _, ground = catalog_for("a village with a well")
    assert ground is not None and "road" in entries and "refrigerator" not in entries
    text = "a village with a road and a sofa next to the road"
    request, _ = _plan(text)
    report = report_of(text, request, "")
    assert report.messages() == ["1:29-32: unknown word 'sofa'"]


def test_words_outdoors_that_cannot_be_used_are_reported_with_their_spans():
    text = "a vilage with a road and a tower meeting at an intersection"
    request, _ = _plan(text)
    messages = report_of(text, request, "").messages()
    assert messages[0] == "1:3-8: unknown word 'vilage'; did you mean 'village'?"
    assert any("meeting" in m and "only roads" in m for m in messages)


def test_the_command_composes_a_village(tmp_path):
    out = tmp_path / "v"
    done = subprocess.run(
        [
            sys.executable,
            "-m",
            "scenewright.cli",
            "compose",
            "a hamlet with three roads meeting at a junction and a street lamp on each road",
            "-o",
            str(out),
            "--no-render",
            "--rules-out",
            str(tmp_path / "hamlet.rules"),
        ],
        capture_output=True,
        text=True,
    )
    assert done.returncode == 0, done.stderr
    said = (out / "description.txt").read_text()
    assert said.startswith("The scene consists of three roads meeting at an intersection")
    assert said.count("street lamp is next to the") == 3
    assert "scene village {" in (tmp_path / "hamlet.rules").read_text()


def test_what_is_said_of_a_road_becomes_what_a_road_can_be():
    request, rules = _plan("a village with a road and a cottage on either side of the road")
    (road,) = _by_type(request, "road")
    cottages = _by_type(request, "house")
    assert len(cottages) == 2
    assert {(c, "NextTo", road) for c in cottages} == _said(request)
    request, _ = _plan("a village with a road and a well between the road and a tower")
    (well,), (tower,) = _by_type(request, "well"), _by_type(request, "tower")
    assert (well, "NextTo", _by_type(request, "road")[0]) in _said(request)
    assert (tower, "NextToRight", well) in _said(request)
    text = "a village with a well and a road on top of the well"
    request, _ = _plan(text)
    assert report_of(text, request, "").messages() == [
        "1:27-51: a road or junction is only next to things"
    ]
    assert not request.statements


def test_roads_that_meet_at_no_junction_named_meet_at_one_of_their_own():
    for text in ("two roads crossing each other", "a hamlet where three lanes meet, with a well"):
        request, _ = _plan(text)
        assert not request.issues
        (junction,) = _by_type(request, "intersection")
        paths = [e.id for e in request.entities if e.type in ("road", "lane")]
        assert len(paths) >= 2
        assert {(p, "PathConnectedTo", junction) for p in paths} <= _said(request)


def test_a_group_with_things_holds_them_but_never_a_road():
    request, _ = _plan("a farm with a barn, a field and a cart next to the barn, by a lane")
    (farm,) = _by_type(request, "farmstead")
    inside = sorted(e.type for e in request.entities if e.parent == farm)
    assert inside == ["empty_wagon", "field", "shed"]  # what it was said to hold, no more
    (lane,) = _by_type(request, "lane")
    assert next(e for e in request.entities if e.id == lane).parent is None


def test_things_only_the_outdoor_catalog_has_make_a_text_outdoors():
    assert catalog_for("a market stand with a table and two barrels")[2] is not None
    assert catalog_for("The scene consists of a tower and a well.")[2] is not None
    assert catalog_for("a desk with a lamp")[2] is None
    assert catalog_for("a kitchen with a barrel")[2] is None  # a room is named


def test_a_noun_a_group_shares_with_a_thing_reads_as_the_describer_uses_it():
    # the city's "shop" is a group (a shop building, its sign, its goods) and the
    # building; the describer's ordinals count both, so "the third shop" in the first
    # shop's paragraph is that shop's building
    text = (
        "The scene consists of a main street and two shops. The two shops are next to the "
        "main street. The first shop consists of a shop, a sign and a barrel. This sign is "
        "in front of the third shop. The barrel is to the left of this shop."
    )
    request, _ = _plan(text, load_rules("city"))
    assert not request.issues
    shops = _by_type(request, "shop")
    assert len(shops) == 2
    first = {e.type: e.id for e in request.entities if e.parent == shops[0]}
    assert sorted(first) == ["barrel", "shop_house", "sign"]
    building = first["shop_house"]
    assert {
        (first["sign"], "NextToFront", building),
        (first["barrel"], "NextToLeft", building),
    } <= _said(request)
    # the other shop, named alone, holds what a shop means: its building and a sign
    assert sorted(e.type for e in request.entities if e.parent == shops[1]) == [
        "shop_house",
        "sign",
    ]


def test_groups_around_a_thing_stand_at_its_sides_without_facing_it():
    request, _ = _plan("a village square with a well and four market stalls around the well")
    (well,) = _by_type(request, "well")
    stands = _by_type(request, "market_stand")
    sides = {(s, label) for s, label, t in _said(request) if t == well}
    assert sides == {
        (stands[0], "NextToFront"),
        (stands[1], "NextToBehind"),
        (stands[2], "NextToLeft"),
        (stands[3], "NextToRight"),
    }
