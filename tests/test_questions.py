"""Questions about a picture: every answer re-counted independently, balance, determinism,
grammar, and the dataset's questions column and questions.json."""

import json
import re
from collections import Counter
from importlib import resources

import jsonschema
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from render_fixtures import or_skip_without_opengl
from test_describer_e2e import ungrammatical

from scenewright.api import build_scene, load_rules
from scenewright.cli import main
from scenewright.dataset.produce import produce_scene, with_picture_captions
from scenewright.dataset.questions import publish_questions
from scenewright.dataset.spec import dataset_spec, scene_seed
from scenewright.describer.colours import colour_word
from scenewright.describer.programs import (
    DEPTH_MARGIN,
    SIDE_MARGIN,
    PictureFacts,
    Seen,
    answer_text,
    execute,
)
from scenewright.describer.questions import (
    FAMILIES,
    QUESTIONS_PER_FAMILY,
    picture_questions,
    vocabulary_of,
)
from scenewright.render.visibility import PictureView

#: The side phrases of the questions: which measure they compare and the sign of "on that side".
SIDES = {
    "to the left of": ("across", -1),
    "to the right of": ("across", 1),
    "in front of": ("depth", -1),
    "behind": ("depth", 1),
}
SIDE = "(to the left of|to the right of|in front of|behind)"
MARGIN = {"across": SIDE_MARGIN, "depth": DEPTH_MARGIN}


def yes(value: bool) -> str:
    return "yes" if value else "no"


def recount(question: dict, objects: list[Seen], vocabulary: dict[str, str]) -> str:
    """The answer to ``question``, read from its words alone and counted over ``objects``
    (the seen ones) in plain Python: no program, no executor."""
    singular = {plural: noun for noun, plural in vocabulary.items()}
    text = question["question"]
    of = lambda noun: [o for o in objects if o.noun == noun]  # noqa: E731

    def anchor_and_sided(side: str, anchor_noun: str):
        (anchor,) = of(anchor_noun)  # "the table": exactly one seen
        measure, sign = SIDES[side]
        at = getattr(anchor, measure)
        others = [o for o in objects if o is not anchor]
        # Every object a side question concerns is clearly on one side: no margin case.
        return anchor, [o for o in others if sign * (getattr(o, measure) - at) > 0], measure, at

    family = question["family"]
    if family == "exist":
        if m := re.fullmatch(r"Is there an? (.+)\?", text):
            return yes(bool(of(m[1])))
        return yes(bool(of(singular[re.fullmatch(r"Are there any (.+)\?", text)[1]])))
    if family == "count":
        return str(len(of(singular[re.fullmatch(r"How many (.+) are there\?", text)[1]])))
    if family == "compare_count":
        m = re.fullmatch(r"Are there (?:(more|fewer) (.+) than (.+)|as many (.+) as (.+))\?", text)
        if m[1]:
            first, second = len(of(singular[m[2]])), len(of(singular[m[3]]))
            return yes(first > second if m[1] == "more" else first < second)
        return yes(len(of(singular[m[4]])) == len(of(singular[m[5]])))
    if family == "relate_exist":
        m = re.fullmatch(rf"Is there an? (.+?) {SIDE} the (.+) in the picture\?", text)
        _, sided, measure, at = anchor_and_sided(m[2], m[3])
        assert all(abs(getattr(o, measure) - at) >= MARGIN[measure] for o in of(m[1]))
        return yes(any(o.noun == m[1] for o in sided))
    if family == "relate_count":
        m = re.fullmatch(rf"How many (.+?) are {SIDE} the (.+) in the picture\?", text)
        noun = singular[m[1]]
        _, sided, measure, at = anchor_and_sided(m[2], m[3])
        assert all(abs(getattr(o, measure) - at) >= MARGIN[measure] for o in of(noun))
        return str(sum(o.noun == noun for o in sided))
    if family == "query_noun":
        if m := re.fullmatch(rf"What is {SIDE} the (.+) in the picture\?", text):
            anchor, sided, measure, at = anchor_and_sided(m[1], m[2])
            assert all(
                abs(getattr(o, measure) - at) >= MARGIN[measure] for o in objects if o is not anchor
            )
            (only,) = sided
            return only.noun
        which = re.fullmatch(r"What is the (nearest|farthest) thing\?", text)[1]
        ordered = sorted(objects, key=lambda o: o.depth, reverse=which == "farthest")
        assert len(ordered) == 1 or abs(ordered[1].depth - ordered[0].depth) >= DEPTH_MARGIN
        return ordered[0].noun
    if family == "query_colour":
        m = re.fullmatch(r"What colour is the (?:(nearest|farthest) )?(.+)\?", text)
        alike = sorted(of(m[2]), key=lambda o: o.depth, reverse=m[1] == "farthest")
        assert (
            len(alike) == 1
            if m[1] is None
            else abs(alike[1].depth - alike[0].depth) >= DEPTH_MARGIN
        )
        return alike[0].colour
    raise AssertionError(f"a family the test does not know: {family}")


# -- hand-made pictures ----------------------------------------------------------------

VOCABULARY = {
    "tent": "tents",
    "chair": "chairs",
    "office chair": "office chairs",
    "table": "tables",
    "bucket": "buckets",
    "bucket of coal": "buckets of coal",
    "oak tree": "oak trees",
    "well": "wells",
}
COLOURS = ["red", "green", "brown", None]

objects_drawn = st.lists(
    st.tuples(
        st.sampled_from(sorted(VOCABULARY)),
        st.integers(0, 40),
        st.integers(0, 24),
        st.sampled_from(COLOURS),
    ),
    min_size=1,
    max_size=10,
)


def picture_of(drawn, glimpsed=()) -> PictureFacts:
    """Seen objects ``(noun, across / 4 px, depth / 4 m, colour)`` spaced on coarse grids,
    so some stand within the margins of each other and some clearly apart."""
    seen = [
        Seen(f"{noun.replace(' ', '_')}_{k}", noun, 4.0 * a, d / 4.0, c)
        for k, (noun, a, d, c) in enumerate(drawn)
    ]
    return PictureFacts(seen, [Seen(f"g_{k}", *g) for k, g in enumerate(glimpsed)])


@settings(max_examples=150, deadline=None)
@given(objects_drawn, st.integers(0, 2**32 - 1))
def test_every_answer_is_the_independent_recount(drawn, seed):
    facts = picture_of(drawn)
    objects = list(facts.objects.values())
    for question in picture_questions(facts, VOCABULARY, seed):
        assert question["answer"] == recount(question, objects, VOCABULARY), question
        assert answer_text(execute(question["program"], facts)) == question["answer"]


@settings(max_examples=150, deadline=None)
@given(objects_drawn, st.integers(0, 2**32 - 1))
def test_each_family_balances_its_answers_within_a_picture(drawn, seed):
    asked = picture_questions(picture_of(drawn), VOCABULARY, seed)
    for name, family in FAMILIES.items():
        answers = [q["answer"] for q in asked if q["family"] == name]
        assert len(answers) <= QUESTIONS_PER_FAMILY
        if family.yes_no:
            assert answers.count("yes") == answers.count("no") == len(answers) // 2
        else:
            assert len(set(answers)) == len(answers)  # no answer twice in one family


def test_every_family_asks_on_a_rich_picture_and_each_program_uses_its_functions():
    facts = picture_of(
        [
            ("tent", 10, 10, "red"),
            ("table", 20, 12, "brown"),
            ("chair", 5, 4, "brown"),
            ("chair", 30, 20, "green"),
            ("oak tree", 35, 2, "green"),
            ("well", 25, 16, None),
        ]
    )
    asked = picture_questions(facts, VOCABULARY, 3)
    assert {q["family"] for q in asked} == set(FAMILIES)
    for question in asked:
        assert question["program"][0] == {"function": "scene", "inputs": [], "value_inputs": []}
        for index, step in enumerate(question["program"]):
            assert all(0 <= i < index for i in step["inputs"]) and all(
                isinstance(v, str) for v in step["value_inputs"]
            )


def test_a_family_with_only_one_possible_answer_asks_nothing():
    # Every noun the vocabulary has is in the picture: "Is there ...?" can only be "yes".
    facts = picture_of([("tent", 10, 10, "red"), ("well", 20, 2, "red")])
    asked = picture_questions(facts, {"tent": "tents", "well": "wells"}, 0)
    assert not [q for q in asked if q["family"] == "exist"]
    assert {q["answer"] for q in asked if q["family"] == "count"} == {"1"}  # one answer, asked once


def test_counts_ask_zero_only_beside_something_present():
    # One tent seen and another shown too little to name: how many tents is not clear,
    # so every count the picture leaves clear is of an absent noun ("0").
    vocabulary = {"tent": "tents", "table": "tables", "well": "wells"}
    absent_only = picture_of([("tent", 10, 10, "red")], glimpsed=[("tent", 20.0, 3.0)])
    for seed in range(10):
        asked = picture_questions(absent_only, vocabulary, seed)
        assert not [q for q in asked if FAMILIES[q["family"]].counts]
    present = picture_of([("well", 10, 10, "red"), ("well", 30, 2, "red")])
    answers = {
        q["answer"] for q in picture_questions(present, vocabulary, 4) if q["family"] == "count"
    }
    assert answers == {"0", "2"}  # "How many tables?" beside "How many wells?"


def test_unclear_nouns_are_never_asked_about():
    # A bucket shown too little to name, and an office chair (a kind of chair) seen: how
    # many buckets or chairs the picture shows is not clear to a person.
    facts = picture_of(
        [("office chair", 10, 10, "red"), ("tent", 30, 2, "green")],
        glimpsed=[("bucket", 20.0, 3.0)],
    )
    for seed in range(20):
        for question in picture_questions(facts, VOCABULARY, seed):
            nouns = {
                v
                for step in question["program"]
                for v in step["value_inputs"]
                if step["function"] == "filter_noun"
            }
            assert not nouns & {"bucket", "chair"}, question


def test_a_side_question_needs_everything_it_concerns_clearly_on_one_side():
    # The chair is within the margin of the table across the picture: "to the left of
    # the table" is not asked of chairs, nor "What is to the left/right of the table?".
    facts = PictureFacts(
        [
            Seen("table_1", "table", 100.0, 10.0),
            Seen("chair_1", "chair", 100.0 - SIDE_MARGIN / 2, 20.0),
            Seen("tent_1", "tent", 40.0, 10.0),
        ]
    )
    for seed in range(30):
        for question in picture_questions(facts, VOCABULARY, seed):
            text = question["question"]
            assert not re.search(r"chairs? (are )?to the (left|right) of the table", text), text
            assert not re.fullmatch(
                r"What is to the (left|right) of the (table|tent) in the picture\?", text
            ), text


def test_the_same_seed_gives_the_same_questions():
    facts = picture_of(
        [("tent", 10, 10, "red"), ("table", 20, 12, "brown"), ("chair", 5, 4, "brown")]
    )
    assert picture_questions(facts, VOCABULARY, 7) == picture_questions(facts, VOCABULARY, 7)
    assert picture_questions(facts, VOCABULARY, np.random.default_rng(1)) == picture_questions(
        facts, VOCABULARY, np.random.default_rng(1)
    )
    draws = {json.dumps(picture_questions(facts, VOCABULARY, seed)) for seed in range(10)}
    assert len(draws) > 1  # the seed does choose


def test_the_vocabulary_holds_every_object_noun_a_rule_set_can_give():
    vocabulary = vocabulary_of(load_rules("bedroom"))
    assert (
        vocabulary["double bed"] == "double beds"
        and vocabulary["low bookshelf"] == "low bookshelves"
    )
    assert "bed" not in vocabulary  # every style of the bed renames it
    assert vocabulary["wardrobe"] == "wardrobes"  # the oak style keeps the entry's noun
    assert "road" not in vocabulary_of(load_rules("village"))  # a path is not an object


# -- rendered pictures -----------------------------------------------------------------


@pytest.fixture(scope="module")
def rendered():
    """(questions, seen objects re-derived from the render, vocabulary) of small desk and
    village pictures."""
    from render_fixtures import renderer_or_skip

    renderer = renderer_or_skip(128, 96)
    found = []
    try:
        for name, count in (("desk", 3), ("village", 1)):
            rules = load_rules(name)
            for index in range(count):
                seed = scene_seed(0, index)
                scene = build_scene(rules, seed)
                picture = PictureView.from_render(renderer.render(scene), scene)
                vocabulary = vocabulary_of(rules, scene)
                questions = picture_questions(PictureFacts.of(scene, picture), vocabulary, seed)
                found.append((questions, seen_objects(scene, picture), vocabulary))
    finally:
        renderer.close()
    return found


def seen_objects(scene, picture) -> list[Seen]:
    """The scene's objects the picture shows well enough, read from the render directly."""
    seen = [o for o in scene.objects if o.kind == "object" and picture.seen(o.id)]
    _, depths = picture.camera.project(np.stack([picture.centres[o.id] for o in seen]))
    return [
        Seen(
            o.id,
            o.noun,
            (picture.box(o.id)[0] + picture.box(o.id)[2]) / 2.0,
            float(depth),
            colour_word(o.colour),
        )
        for o, depth in zip(seen, depths, strict=True)
    ]


def test_rendered_pictures_answers_are_the_independent_recount(rendered):
    families = Counter()
    for questions, objects, vocabulary in rendered:
        for question in questions:
            assert question["answer"] == recount(question, objects, vocabulary), question
            families[question["family"]] += 1
    assert set(families) == set(FAMILIES)


def test_questions_parse_with_link_grammar(rendered):
    facts = picture_of(
        [
            ("tent", 10, 10, "red"),
            ("table", 20, 12, "brown"),
            ("chair", 5, 4, "brown"),
            ("chair", 30, 20, "green"),
            ("bucket of coal", 35, 2, "green"),
            ("well", 25, 16, None),
        ]
    )
    sentences = [
        q["question"] for seed in range(5) for q in picture_questions(facts, VOCABULARY, seed)
    ]
    sentences += [q["question"] for questions, _, _ in rendered for q in questions]
    assert ungrammatical(sentences) == []


# -- the dataset -----------------------------------------------------------------------


def test_rows_carry_questions_that_follow_the_row_schema():
    schema = json.loads(
        resources.files("scenewright.dataset")
        .joinpath("schema/metadata_row.schema.json")
        .read_text()
    )
    spec = dataset_spec("desk", 1, size=(64, 64))
    row = or_skip_without_opengl(lambda: produce_scene(spec, 0)).row
    assert row["questions"]
    jsonschema.validate(row, schema)
    broken = dict(row, questions=[dict(row["questions"][0], answer=3)])
    with pytest.raises(jsonschema.ValidationError):
        jsonschema.validate(broken, schema)
    off = or_skip_without_opengl(
        lambda: produce_scene(with_picture_captions(spec, questions=False), 0)
    ).row
    assert "questions" not in off and off["caption"] == row["caption"]


def test_the_questions_file_covers_the_rows_after_a_resume_and_no_questions_turns_both_off(
    tmp_path, capsys
):
    out = tmp_path / "data"
    common = ["-q", "dataset", "desk", "-o", str(out), "--size", "48x48", "--workers", "1"]
    assert or_skip_without_opengl(lambda: main([*common, "-n", "1"])) == 0
    assert main([*common, "-n", "2"]) == 0  # resumed: scene 0 is kept, scene 1 made
    rows = [json.loads(line) for line in (out / "metadata.jsonl").read_text().splitlines()]
    stored = json.loads((out / "questions.json").read_text())
    assert stored["info"]["count"] == 2
    expected = [
        (row["file_name"], q["question"], q["answer"], q["program"])
        for row in rows
        for q in row["questions"]
    ]
    got = [
        (q["image_filename"], q["question"], q["answer"], q["program"]) for q in stored["questions"]
    ]
    assert got == expected and [q["question_index"] for q in stored["questions"]] == list(
        range(len(got))
    )
    assert {q["image_index"] for q in stored["questions"]} == {0, 1}

    # --no-questions is a setting of the dataset: refused on this one before any work...
    capsys.readouterr()
    assert main([*common, "-n", "2", "--no-questions"]) == 2
    assert "questions True -> False" in capsys.readouterr().err
    # ...and a dataset made with it has no questions file.
    off = with_picture_captions(dataset_spec("desk", 2, size=(48, 48)), questions=False)
    assert off.settings()["questions"] is False
    (out / "questions.json").unlink()
    assert publish_questions(out, off) is None and not (out / "questions.json").exists()
