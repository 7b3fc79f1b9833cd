"""Composing a scene from English: the reader, the rule set it writes, the command."""

from __future__ import annotations

import subprocess
import sys

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from scenewright.composer.compose import plan, report_of
from scenewright.composer.request import Place
from scenewright.composer.vocabulary import relation_phrases, vocabulary
from scenewright.core.relations import RELATIONS, RelationLabel
from scenewright.generator.rules import indoor_catalog

DONE_WHEN = (
    "a bedroom with a double bed against the north wall, a nightstand on each side of "
    "the bed, a wardrobe and a desk under the window"
)


def _plan(text):
    return plan(text, indoor_catalog())


def _types(request):
    return sorted(e.type for e in request.entities)


def test_the_bedroom_request_reads_into_things_and_relations():
    request, rules = _plan(DONE_WHEN)
    assert request.room == "bedroom"
    assert _types(request) == ["bed", "desk", "nightstand", "nightstand", "wardrobe"]
    bed = next(e for e in request.entities if e.type == "bed")
    assert bed.style == "double"
    said = {(s.source, s.label, s.target) for s in request.statements}
    assert (bed.id, "AgainstWall", Place("wall", 1)) in said
    nightstands = [e.id for e in request.entities if e.type == "nightstand"]
    # "on each side of": close beside it (which makes "to the left of" true as well)
    assert {(n, lab) for n, lab, t in said if t == bed.id and lab.startswith("Beside")} == {
        (nightstands[0], "BesideLeft"),
        (nightstands[1], "BesideRight"),
    }
    desk = next(e for e in request.entities if e.type == "desk")
    assert (desk.id, "UnderWindow", Place("window")) in said
    assert not request.issues
    assert "bed as e1 AgainstWall wall #1" in rules and "window north" in rules


def test_an_unknown_word_is_reported_with_its_span_and_the_nearest_word():
    text = "a kitchn with a fridge"
    request, _ = _plan(text)
    report = report_of(text, request, "")
    assert report.messages() == ["1:3-8: unknown word 'kitchn'; did you mean 'kitchen'?"]
    assert _types(request) == ["refrigerator"]


def test_the_describer_s_own_sentences_read_back():
    text = (
        "The scene consists of a single bed, two nightstands, a wide wardrobe and a chair. "
        "The room has a door in the south wall and two windows in the north wall. "
        "A lamp is on top of the first nightstand. Another lamp is on top of the other "
        "nightstand. The single bed and the wide wardrobe stand against the east wall. "
        "The chair is in front of the single bed and faces it. "
        "The first nightstand is to the left of the single bed."
    )
    request, _ = _plan(text)
    assert not request.issues
    assert request.doors == ["south"] and request.windows == ["north", "north"]
    ids = {e.id: (e.type, e.style) for e in request.entities}
    said = [(ids[s.source][0], s.label, s.target) for s in request.statements]
    lamps = [s for s in request.statements if ids[s.source][0] == "lamp"]
    assert len({s.target for s in lamps}) == 2  # "the first" and "the other" nightstand
    assert said.count(("bed", "AgainstWall", Place("wall", 2))) == 1
    assert ("wardrobe", "AgainstWall", Place("wall", 2)) in said
    chair = [s for s in request.statements if ids[s.source][0] == "chair"]
    assert [s.label for s in chair] == ["NextToFront", "FacingTowards"]
    assert all(ids[s.target][0] == "bed" for s in chair)  # "it" is the bed


def test_people_s_phrases_counts_sizes_and_absence():
    request, _ = _plan(
        "a 4 by 3 metre kitchen with a few chairs around the table, several books and no rug"
    )
    assert request.size == (4.0, 3.0) and request.room == "kitchen"
    assert _types(request).count("chair") == 3 and _types(request).count("book") == 3
    table = next(e.id for e in request.entities if e.type == "dining_table")
    around = [s for s in request.statements if s.target == table]
    assert {s.label for s in around} == {"SeatedAround"}  # chairs are seated round a table
    assert "rug" in request.absent and not request.issues


def test_a_contradicted_absence_is_reported():
    request, _ = _plan("a room with a rug and no rug")
    assert any("contradicts" in i.message for i in request.issues)


def test_flanked_by_puts_what_follows_on_each_side_of_the_subject():
    request, _ = _plan("a bed flanked by two nightstands")
    assert _types(request) == ["bed", "nightstand", "nightstand"]
    ids = {e.id: e.type for e in request.entities}
    said = {(ids[s.source], s.label, ids[s.target]) for s in request.statements}
    assert ("nightstand", "BesideLeft", "bed") in said
    assert ("nightstand", "BesideRight", "bed") in said
    assert not request.issues


def _said(request):
    """The statements between things, as (source, label, target) ids, and the types."""
    ids = {e.id: e.type for e in request.entities}
    return ids, [(s.source, s.label, s.target) for s in request.statements]


def test_each_after_a_relation_makes_one_subject_per_thing():
    request, _ = _plan("a bed between two nightstands and a lamp on each nightstand")
    assert _types(request) == ["bed", "lamp", "lamp", "nightstand", "nightstand"]
    ids, said = _said(request)
    lamps_on = sorted(t for s, lab, t in said if ids[s] == "lamp" and lab == "OnTopOf")
    assert lamps_on == sorted(e for e, kind in ids.items() if kind == "nightstand")
    assert not request.issues


def test_between_puts_one_thing_on_each_side():
    for text in (
        "a bed between two nightstands",
        "a desk between the bookshelf and the wardrobe",
        "two sofas facing each other and a coffee table between them",
    ):
        request, _ = _plan(text)
        ids, said = _said(request)
        middle = next(e for e, kind in ids.items() if kind in ("bed", "desk", "coffee_table"))
        sides = sorted(lab for s, lab, t in said if t == middle)
        assert sides == ["NextToLeft", "NextToRight"], text
        assert len(ids) == 3 and not request.issues, text


def test_between_one_thing_is_reported():
    request, _ = _plan("a desk between the bookshelf")
    assert [i.message.split(":")[-1].strip() for i in request.issues][:1] == [
        "'between' takes two things"
    ]


def test_on_either_side_without_of_means_the_thing_named_before():
    request, _ = _plan("a bedroom with a bed with a nightstand on either side")
    ids, said = _said(request)
    assert sorted(lab for s, lab, t in said if ids.get(t) == "bed") == [
        "BesideLeft",
        "BesideRight",
        "ImplicitAlignedWith",
        "ImplicitAlignedWith",
    ]
    assert _types(request) == ["bed", "nightstand", "nightstand"] and not request.issues


@pytest.mark.parametrize(
    ("text", "types"),
    [
        ("a bathroom with a shower, a toilet and a sink", ["shower", "toilet", "washbasin"]),
        ("a kitchen with a sink", ["sink_counter"]),
        ("a classroom with four desks", ["student_desk"] * 4),
        ("an office with a swivel chair and a writing desk", ["desk", "office_chair"]),
        ("a lounge with an end table and a cupboard", ["cabinet", "side_table"]),
        ("a music room with a piano and a bench", ["piano", "piano_bench"]),
        ("a laundry room with a washer", ["washing_machine"]),
    ],
)
def test_everyday_words_for_things_and_rooms(text, types):
    request, _ = _plan(text)
    assert _types(request) == types
    assert not request.issues


def test_ordinals_count_as_the_describer_names_things():
    # the first low bookshelf, named on its own second, is the second bookshelf named:
    # the third is the tall one not named yet; a style's noun counts its own
    text = (
        "a room with two bookshelves and two low bookshelves. A book is on top of the first "
        "bookshelf. Another book is on top of the first low bookshelf. The third bookshelf "
        "is to the left of the first bookshelf."
    )
    request, _ = _plan(text)
    ids = {e.id: (e.type, e.style) for e in request.entities}
    tall, low = (
        [e for e, (kind, style) in ids.items() if kind == "bookshelf" and style == s]
        for s in ("tall", "low")
    )
    said = [(s.source, s.label, s.target) for s in request.statements]
    on = [t for src, lab, t in said if lab == "OnTopOf"]
    assert on == [tall[0], low[0]]
    assert (tall[1], "NextToLeft", tall[0]) in said


def test_some_of_the_things_then_the_other():
    text = (
        "a room with three bookshelves. A book is on top of the first bookshelf. Two of the "
        "bookshelves stand against the north wall. The other bookshelf is to the left of the "
        "second bookshelf."
    )
    request, _ = _plan(text)
    shelves = [e.id for e in request.entities if e.type == "bookshelf"]
    said = [(s.source, s.label, s.target) for s in request.statements]
    against = [src for src, lab, t in said if lab == "AgainstWall"]
    assert against == shelves[:2]
    assert (shelves[2], "NextToLeft", shelves[1]) in said
    assert not request.issues


ROWS = (
    "The scene consists of a whiteboard and two rows of desks. The whiteboard stands "
    "against the north wall. The first row of desks is south of the second row of desks. "
    "The first row of desks consists of two desks and two chairs. The two desks face the "
    "opposite way to the whiteboard. The first chair of the first row of desks is at the "
    "back of the first desk. The second desk is to the left of the first desk. The second "
    "row of desks consists of two desks. The second desk is to the left of the first desk."
)


def test_a_group_consists_of_its_members_and_ordinals_count_within_it(tmp_path):
    from scenewright.generator import load_rules

    entries = {**indoor_catalog(), **load_rules("classroom").catalog.entries}
    request, rules = plan(ROWS, entries, {"row", "student_desk"})
    assert not request.issues
    rows = [e.id for e in request.entities if e.group]
    assert [e.type for e in request.entities if e.group] == ["row", "row"]
    desks = {
        g: [e.id for e in request.entities if e.parent == g and e.type == "student_desk"]
        for g in rows
    }
    assert all(len(v) == 2 for v in desks.values())
    said = {(s.source, s.label, s.target) for s in request.statements}
    assert (rows[0], "NextToSouth", rows[1]) in said
    for g in rows:  # "the second desk ... the first desk" of the paragraph's own row
        assert (desks[g][1], "NextToLeft", desks[g][0]) in said
    chair = next(e.id for e in request.entities if e.type == "chair" and e.parent == rows[0])
    assert (chair, "SeatedAtBack", desks[rows[0]][0]) in said
    # the members are written in their group's block, and the rule set loads
    assert "row as e2 {" in rules and "        student_desk as" in rules
    path = tmp_path / "rows.rules"
    path.write_text(rules)
    assert load_rules(path).catalog["row"].kind == "group"


def test_the_empty_room_sentence_reads_whole():
    request, _ = _plan("The room has a door in the south wall. The room is empty.")
    assert not request.issues and not request.entities


def test_on_a_wall_is_against_it():
    request, _ = _plan("a bookcase on the west wall")
    assert [(s.label, s.target) for s in request.statements] == [("AgainstWall", Place("wall", 4))]


@pytest.mark.parametrize(
    ("sentence", "label"),
    [
        ("The nightstand is just to the left of the bed.", "BesideLeft"),
        ("The nightstand is immediately to the right of the bed.", "BesideRight"),
        ("The nightstand is to the left of the bed.", "NextToLeft"),
        ("The chair is pulled up to the desk.", "SeatedAt"),
        ("The chair is drawn up to the desk.", "SeatedAt"),
        ("The chair is at the back of the desk.", "SeatedAtBack"),
        ("The chairs are at the dining table.", "SeatedAround"),
        ("The chair is next to the desk.", "NextTo"),
    ],
)
def test_each_wording_reads_as_the_one_label_the_describer_words_so(sentence, label):
    request, _ = _plan(sentence)
    assert {s.label for s in request.statements} == {label}
    assert not request.issues


def test_every_phrase_names_one_label_for_each_kind_of_object():
    """No two labels share words for the same kind of object (a thing, a wall, a
    window), so a description reads back as the labels it was made from."""
    for phrase, sense in relation_phrases().items():
        for_things = [x for x in sense.labels if not RELATIONS[x].by_room]
        for_windows = [x for x in sense.labels if x.endswith("Window")]
        assert len(for_things) <= 1 and len(for_windows) <= 1, (phrase, sense.labels)


def test_a_label_registered_with_new_words_is_understood_without_the_parser():
    label = RelationLabel(
        name="NextToFlush",
        family="next_to",
        phrase="flush with",
        wordings=("is snug against",),
    )
    relation_phrases.cache_clear()
    try:
        with RELATIONS.extended(label):
            relation_phrases.cache_clear()
            request, _ = plan("a desk is snug against the bed", indoor_catalog())
            assert [s.label for s in request.statements] == ["NextToFlush"]
    finally:
        relation_phrases.cache_clear()


@settings(max_examples=40, deadline=None)
@given(st.text(alphabet="abcdefghijklmnopqrstuvwxyz ,.'-0123456789", max_size=80))
def test_every_word_is_used_or_reported(text):
    if not text.strip():
        return
    request, _ = _plan(text)
    vocab_words = set(vocabulary(indoor_catalog()).known_words)
    spans = request.used + [(i.start, i.end) for i in request.issues]
    from scenewright.composer.request import tokenize
    from scenewright.composer.vocabulary import FUNCTION_WORDS

    for token in tokenize(text):
        if token.low in FUNCTION_WORDS or token.low in ".,;:!?":
            continue
        assert any(s <= token.start and token.end <= e for s, e in spans), (token.text, vocab_words)


def test_the_same_text_and_seed_give_the_same_rules():
    assert _plan(DONE_WHEN)[1] == _plan(DONE_WHEN)[1]


@pytest.mark.slow
def test_compose_command_writes_the_scene_and_restates_the_facts(tmp_path):
    out = tmp_path / "out"
    rules = tmp_path / "bedroom.rules"
    run = subprocess.run(
        [
            sys.executable,
            "-m",
            "scenewright.cli",
            "compose",
            DONE_WHEN,
            "-o",
            str(out),
            "--no-render",
            "--seed",
            "1",
            "--rules-out",
            str(rules),
        ],
        capture_output=True,
        text=True,
    )
    assert run.returncode == 0, run.stderr
    text = (out / "description.txt").read_text()
    for fact in (
        "The double bed stands against the north wall.",
        "to the left of the double bed",
        "to the right of the double bed",
        "The desk is under the window.",
        "a wardrobe",
    ):
        assert fact in text
    again = subprocess.run(
        [sys.executable, "-m", "scenewright.cli", "validate", str(rules)],
        capture_output=True,
        text=True,
    )
    assert again.returncode == 0, again.stdout + again.stderr


def test_strict_refuses_an_unknown_word_and_writes_nothing(tmp_path):
    out = tmp_path / "out"
    run = subprocess.run(
        [
            sys.executable,
            "-m",
            "scenewright.cli",
            "compose",
            "a kitchn with a fridge",
            "--strict",
            "-o",
            str(out),
        ],
        capture_output=True,
        text=True,
    )
    assert run.returncode == 2
    assert "1:3-8: unknown word 'kitchn'; did you mean 'kitchen'?" in run.stderr
    assert "Traceback" not in run.stderr and not out.exists()


def test_one_against_each_wall():
    request, _ = _plan("a room with a bookshelf against each wall")
    walls = sorted(s.target.number for s in request.statements if isinstance(s.target, Place))
    assert _types(request) == ["bookshelf"] * 4 and walls == [1, 2, 3, 4]


def test_a_named_corner_is_where_the_layout_puts_it():
    from scenewright.api import compose

    scene, report = compose("a bathroom with a bathtub in the south-east corner and a toilet", 4)
    tub = next(o for o in scene.objects if o.type == "bathtub")
    assert tub.position[0] > 0 and tub.position[2] > 0 and not report.unsatisfied
    assert "The bathtub stands in the south-east corner." in scene.description.text


def test_everyday_phrases_each_other_side_by_side_every_corner_and_a_room_after_in():
    request, _ = _plan(
        "A living room with two armchairs facing each other, two treadmills side by side, "
        "a plant in every corner and a piano in the living room near the window."
    )
    ids = {e.id: e.type for e in request.entities}
    said = [
        (ids[s.source], s.label, s.target if isinstance(s.target, Place) else ids[s.target])
        for s in request.statements
    ]
    assert said.count(("armchair", "FacingTowards", "armchair")) == 2
    assert ("treadmill", "NextTo", "treadmill") in said
    corners = {s.target.corner for s in request.statements if s.label == "InCorner"}
    assert len(corners) == 4 and _types(request).count("plant") == 4
    assert ("piano", "BesideWindow", Place("window")) in said
    assert not request.issues and request.room == "living_room"


def test_a_relation_left_without_its_object_is_reported():
    request, _ = _plan("a desk facing the window and a chair next to")
    words = {i.text for i in request.issues}
    assert {"facing", "window", "next"} <= words


def test_the_plain_noun_names_the_plain_style_before_another():
    request, _ = _plan(
        "The scene consists of a low bookshelf and a bookshelf. "
        "The bookshelf is to the right of the low bookshelf."
    )
    styles = {e.id: e.style for e in request.entities}
    [said] = request.statements
    assert (styles[said.source], said.label, styles[said.target]) == ("tall", "NextToRight", "low")


@pytest.mark.parametrize("rules_name", ["bedroom", "kitchen", "study"])
def test_close_furniture_described_reads_back_close(rules_name):
    """A nightstand just to the left of the bed, chairs at the table, a chair pulled up
    to the desk: composed from the describer's text, each stands so again, measured
    anew from the composed poses."""
    from collections import Counter

    from scenewright.api import build_scene, compose, describe
    from scenewright.generator import load_rules
    from scenewright.generator.layout.measure import measure_layout
    from scenewright.generator.layout.pinning import scene_layout

    close = {"BesideLeft", "BesideRight", "SeatedAt", "SeatedAtBack", "SeatedAround"}
    rules = load_rules(rules_name)
    source = build_scene(rules, 1000)
    description = describe(source, style="full")
    kind = {o.id: o.type for o in source.objects}
    stated = Counter(
        (kind[a], label, kind[b]) for a, label, b in description.facts if label in close
    )
    assert stated, description.text
    composed, report = compose(description.text, 1000, catalog=rules)
    assert not report.unused
    measured = measure_layout(composed.graph(), *scene_layout(composed))
    kind = {o.id: o.type for o in composed.objects}
    held = Counter(
        (kind[r.source], r.label, kind[r.target])
        for r in measured.relations
        if r.satisfied and r.label in close
    )
    assert not stated - held, (description.text, stated - held)


def test_corners_named_on_the_door_s_wall_stay_clear_of_the_door():
    # two plants in the corners of the door's wall: the wall is long enough that neither
    # is "the corner by the door", as the describer would then say
    request, _ = _plan(
        "The room has a door in the south wall. The first plant stands in the south-east "
        "corner. The other plant stands in the south-west corner."
    )
    assert request.planned_size[0] >= 0.9 + 2 * 1.0
    assert not request.issues


def _facts(request):
    kinds = {e.id: e.type for e in request.entities}
    return {
        (
            kinds[s.source],
            s.label,
            kinds.get(s.target, s.target) if isinstance(s.target, str) else s.target,
        )
        for s in request.statements
        if not s.label.startswith("Implicit")
    }


@pytest.mark.parametrize(
    ("text", "fact"),
    [
        (
            "a bedroom with a bed and a dresser opposite the bed",
            ("dresser", "FacingTowards", "bed"),
        ),
        ("a sofa and two armchairs across from the sofa", ("armchair", "FacingTowards", "sofa")),
        ("a bed and a rug at the foot of the bed", ("rug", "NextToFront", "bed")),
        ("a bed and a bench at the end of the bed", ("piano_bench", "NextToFront", "bed")),
        (
            "counters and a fridge at the end of the counters",
            ("refrigerator", "NextTo", "kitchen_counter"),
        ),
        ("a desk in front of the window", ("desk", "UnderWindow", Place("window"))),
        ("a desk next to the window", ("desk", "BesideWindow", Place("window"))),
        ("a desk by the window", ("desk", "BesideWindow", Place("window"))),
        ("a wardrobe next to the door", ("wardrobe", "InCorner", Place("corner", by_door=True))),
        ("a bed opposite the window", ("bed", "AgainstWall", Place("wall", 3))),
        ("a wardrobe opposite the door", ("wardrobe", "AgainstWall", Place("wall", 1))),
        (
            "a door in the east wall and a sofa opposite the door",
            ("sofa", "AgainstWall", Place("wall", 4)),
        ),
        ("a sofa against the wall", ("sofa", "AgainstWall", Place("wall"))),
        ("a plant in the corner", ("plant", "InCorner", Place("corner"))),
        ("a plant stands away from the walls", ("plant", "AwayFromWall", Place("wall"))),
        ("a plant is away from the west wall", ("plant", "AwayFromWall", Place("wall", 4))),
        ("a rug that stands against the north wall", ("rug", "AgainstWall", Place("wall", 1))),
    ],
)
def test_everyday_relation_phrases_mean_registry_relations(text, fact):
    request, _ = _plan(text)
    assert fact in _facts(request)
    assert not request.issues, [i.message for i in request.issues]


def test_opposite_the_window_names_the_window_s_wall():
    request, rules = _plan("a bedroom with a double bed opposite the window")
    assert request.windows == ["north"] and "window north" in rules
    assert "AgainstWall wall #3" in rules


@pytest.mark.parametrize(
    ("text", "fact", "types"),
    [
        # "stand" is the noun after "a"; the place phrase after it is the stand's
        (
            "a living room with a TV on a stand against the north wall",
            ("tv_stand", "AgainstWall", Place("wall", 1)),
            ["tv", "tv_stand"],
        ),
        # a relation to a thing after the support: both the TV and its stand
        (
            "a TV on a stand opposite the sofa",
            ("tv_stand", "FacingTowards", "sofa"),
            ["sofa", "tv", "tv_stand"],
        ),
        # "with ... on it": the thing the with-phrase hangs on, not the last one named
        (
            "a bed, a nightstand next to the bed with a lamp on it",
            ("lamp", "OnTopOf", "nightstand"),
            ["bed", "lamp", "nightstand"],
        ),
        (
            "a living room with two armchairs across from the sofa and a coffee table between them",
            ("armchair", "NextToLeft", "coffee_table"),
            ["armchair", "armchair", "coffee_table", "sofa"],
        ),
    ],
)
def test_supports_with_phrases_and_them(text, fact, types):
    request, _ = _plan(text)
    assert fact in _facts(request) and _types(request) == types
    assert not request.issues, [i.message for i in request.issues]


def test_a_tv_on_a_stand_against_the_wall_puts_the_stand_there_not_the_tv():
    request, _ = _plan("a TV on a stand against the north wall")
    assert ("tv", "AgainstWall", Place("wall", 1)) not in _facts(request)
    assert ("tv", "OnTopOf", "tv_stand") in _facts(request)


def test_stand_is_still_the_verb_after_things():
    request, _ = _plan("The bed and the dresser stand against the north wall.")
    assert _types(request) == ["bed", "dresser"] and len(request.statements) == 2


@pytest.mark.parametrize(
    ("text", "types"),
    [
        ("a dining room with a table and a dozen chairs", ["chair"] * 12 + ["dining_table"]),
        ("half a dozen chairs", ["chair"] * 6),
        ("a desk as well as a chair", ["chair", "desk"]),
        ("Add a piano and a bench.", ["piano", "piano_bench"]),
        ("There are two sofas and a rug.", ["rug", "sofa", "sofa"]),
        ("I need a desk, plus a bookshelf, also a plant", ["bookshelf", "desk", "plant"]),
        ("a black leather sofa", ["sofa"]),
    ],
)
def test_counts_joiners_and_request_openings(text, types):
    request, _ = _plan(text)
    assert _types(request) == types and not request.issues, [i.message for i in request.issues]


@pytest.mark.parametrize(
    ("text", "words", "why"),
    [
        (
            "a kitchen with a table in the middle of the room and four chairs around it",
            ["middle", "room"],
            "no relation places a thing in the middle of the room",
        ),
        ("a rug in the centre, a sofa", ["centre"], "middle of the room"),
        ("a couch facing the window", ["facing", "window"], "no such relation to a window"),
        ("a chair behind the door", ["behind", "door"], "relative to a door"),
        ("a wooden table", ["wooden"], "no wooden dining table (its styles: long, small)"),
        ("a round table and a small desk", ["round", "small"], "the catalog has no"),
        ("a bed in the middle of the north wall", ["middle"], "where along the wall"),
        ("a whiteboard on the front wall", ["front"], "which one this is"),
        ("a bed at the end of the room, a desk", ["end", "room"], "the room itself"),
        (
            "a bed in a corner and a desk in the opposite corner",
            ["opposite"],
            "which wall or corner",
        ),
        (
            "a wardrobe next to the door and a plant by the door",
            ["door"],
            "only one thing can stand in the corner by the door",
        ),
    ],
)
def test_what_no_relation_can_say_is_reported_not_faked(text, words, why):
    request, _ = _plan(text)
    reported = {text[i.start : i.end]: i.message for i in request.issues}
    assert sorted(reported) == sorted(words) and all(why in m for m in reported.values())


def test_the_middle_of_the_room_is_not_a_relation_to_the_things_after_it():
    request, _ = _plan(
        "Place a dining table in the middle of the room and six chairs around the table."
    )
    assert {lab for _, lab, _ in _facts(request)} == {"SeatedAround"}
    assert request.room == "room" and _types(request) == ["chair"] * 6 + ["dining_table"]


def test_a_thing_by_the_window_and_the_window_leave_each_other_room():
    from scenewright.api import compose

    scene, report = compose(
        "There is a desk by the window and an office chair in front of the desk.", 1002
    )
    assert not report.unsatisfied and "The desk is beside the window." in scene.description.text
    scene, report = compose("a sofa opposite the window and a wardrobe next to the door", 3)
    text = scene.description.text
    assert not report.unsatisfied and "window in the north wall" in text
    assert "The sofa stands against the south wall." in text
    assert "The wardrobe stands in the corner by the door." in text


@pytest.mark.parametrize(
    "text",
    [
        "the desk is not under the window",
        "a bed that is not against the wall",
        "the sofa isn't facing the TV",
        "a desk, and the desk should never be under the window",
    ],
)
def test_a_denied_relation_is_reported_never_composed(text):
    request, _ = _plan(text)
    assert not [s for s in request.statements if not s.label.startswith("Implicit")]
    assert any("said not to hold" in i.message for i in request.issues)


def test_i_don_t_want_a_thing_asks_for_none():
    request, _ = _plan("a living room with a sofa. I don't want a TV, and we do not need a rug")
    assert set(request.absent) == {"tv", "rug"} and _types(request) == ["sofa"]
    assert not request.issues


def test_which_after_an_object_is_about_that_object():
    text = "the sofa is against the north wall, facing the TV which is on the south wall"
    request, _ = _plan(text)
    assert _facts(request) == {
        ("sofa", "AgainstWall", Place("wall", 1)),
        ("sofa", "FacingTowards", "tv"),
        ("tv", "AgainstWall", Place("wall", 3)),
    }


def test_in_between_alone_is_between_the_two_things_named_before():
    request, _ = _plan("a sofa facing the tv with a coffee table in between")
    assert {
        ("sofa", "NextToLeft", "coffee_table"),
        ("tv", "NextToRight", "coffee_table"),
    } <= _facts(request)


def test_two_things_on_two_supports_are_one_on_each():
    request, _ = _plan("There are two lamps on the side tables.")
    on = [(s.source, s.target) for s in request.statements if s.label == "OnTopOf"]
    assert len(on) == 2 and len({t for _, t in on}) == 2


def test_a_thing_on_either_side_of_the_window_lays_out_one_on_each_side():
    from scenewright.api import compose

    scene, report = compose("a study with a bookshelf on either side of the window and a desk", 0)
    assert [o.type for o in scene.objects].count("bookshelf") == 2 and not report.unsatisfied
    assert "Both bookshelves are beside the window." in scene.description.text


def test_a_rough_room_size_reads_whole():
    request, _ = _plan("a small bedroom, about 3 by 3 meters, with a bed")
    assert request.size == (3.0, 3.0) and not request.issues


@pytest.mark.parametrize(
    ("text", "word"),
    [
        ("a bed with a nightstand on the left and a lamp on the right", "left"),
        ("a rug on the floor and a sofa", "floor"),
        ("a plant on the windowsill, a sofa", "windowsill"),
    ],
)
def test_a_relation_whose_object_is_not_understood_takes_nothing_named_later(text, word):
    request, _ = _plan(text)
    assert not any(s.label.startswith("OnTopOf") for s in request.statements)
    assert word in {text[i.start : i.end] for i in request.issues}


def test_a_desk_at_the_window_is_under_it():
    request, _ = _plan("a desk at the window")
    assert _facts(request) == {("desk", "UnderWindow", Place("window"))}


def test_a_relation_s_object_without_its_article_is_the_one_named_before():
    request, _ = _plan("a study: desk under window; chair at desk; bookshelf on east wall")
    assert _types(request) == ["bookshelf", "chair", "desk"] and not request.issues
    assert ("desk", "UnderWindow", Place("window")) in _facts(request)
    assert ("chair", "SeatedAround", "desk") in _facts(request)


def test_in_a_row_either_side_and_the_centre_of():
    request, _ = _plan("an office with four desks in a row against the south wall")
    facts = [(s.label, s.target) for s in request.statements]
    assert facts.count(("AgainstWall", Place("wall", 3))) == 4
    assert sum(label == "NextTo" for label, _ in facts) == 3
    request, _ = _plan("a bedroom with a bed against the north wall, nightstands either side")
    assert {("nightstand", "BesideLeft", "bed"), ("nightstand", "BesideRight", "bed")} <= _facts(
        request
    )
    assert not request.issues
    request, _ = _plan("a lamp in the centre of the desk")
    assert _facts(request) == {("lamp", "OnTopOfMiddle", "desk")}


def test_a_second_kind_of_room_is_reported_not_silently_merged():
    """A house's overview names rooms of several kinds: one text makes one room (the
    first), and every other room word is reported with where a house is written."""
    text = "The flat has a hall, a kitchen and a bedroom. The hall consists of a dresser."
    request, rules = plan(text, indoor_catalog())
    assert request.room == "hall" and _types(request) == ["dresser"]
    reported = [
        m for m in report_of(text, request, rules).messages() if "a text makes one room" in m
    ]
    assert [m.split("'")[1] for m in reported] == ["kitchen", "bedroom"]
    # the same kind again ("guest room" is a bedroom) is the same room, not a second one
    text = "a guest room with a bed. The bedroom has a rug."
    request, rules = plan(text, indoor_catalog())
    assert not [m for m in report_of(text, request, rules).messages() if "one room" in m]
