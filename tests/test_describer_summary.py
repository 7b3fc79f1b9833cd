"""The summary level on a laid-out scene: counts that hold, a checker that catches
counts that do not, and the word budget that chooses a level.

``tests/rules/hamlet.rules`` (seed 1): five homes with gardens beside three roads and
street lamps; its full text is 236 words, its summary 133.
"""

import dataclasses
from pathlib import Path

import pytest
from test_describer_e2e import check_claims, check_true_and_complete, ungrammatical
from test_describer_wording import laid_out_file

from scenewright.cli import main
from scenewright.core.errors import InputError
from scenewright.describer import describe

HAMLET = Path(__file__).parent / "rules" / "hamlet.rules"


@pytest.fixture(scope="module")
def hamlet():
    return laid_out_file(HAMLET, 1)


def words(text: str) -> int:
    return len(text.split())


def test_the_summary_counts_repeated_groups(hamlet):
    full, summary = describe(hamlet), describe(hamlet, style="summary")
    assert summary.style == "summary" and words(summary.text) < words(full.text) * 0.6
    assert "The second home consists of" in full.text and " home consists of" not in summary.text
    assert "All five homes have a flowerpot." in summary.text
    assert "In most of the five homes, the flowerpot is in front of the cottage." in summary.text
    assert "All four street lamps are next to a road." in summary.text
    kinds = {claim.kind for s in summary.sentences for claim in s.claims}
    assert kinds == {"has", "in", "is"}


def test_every_count_is_measured_true_and_every_sentence_parses(hamlet):
    sentences = check_true_and_complete(hamlet)  # summaries' claims included (check_claims)
    assert ungrammatical(sentences) == []


def lie(description, sentence_index: int, quantifier: str, text: str):
    """The description with one sentence's claim and words changed."""
    sentences = list(description.sentences)
    sentence = sentences[sentence_index]
    claim = dataclasses.replace(sentence.claims[0], quantifier=quantifier)
    sentences[sentence_index] = dataclasses.replace(sentence, text=text, claims=(claim,))
    return dataclasses.replace(description, sentences=sentences)


@pytest.mark.parametrize(
    ("said", "quantifier", "lied"),
    [
        ("Most of the five homes have a bush.", "all", "All five homes have a bush."),
        ("One of the five homes has a house.", "some", "Some of the five homes have a house."),
        (
            "In most of the five homes, the flowerpot is in front of the cottage.",
            "all",
            "In all five homes, the flowerpot is in front of the cottage.",
        ),
    ],
)
def test_the_checker_catches_a_count_that_does_not_hold(hamlet, said, quantifier, lied):
    summary = describe(hamlet, style="summary")
    check_claims(hamlet, summary)
    index = next(k for k, s in enumerate(summary.sentences) if s.text == said)
    with pytest.raises(AssertionError):
        check_claims(hamlet, lie(summary, index, quantifier, lied))


def test_a_word_budget_chooses_the_most_detailed_level_that_fits(hamlet):
    full, summary = describe(hamlet), describe(hamlet, style="summary")
    assert describe(hamlet, words=words(full.text)).text == full.text
    assert describe(hamlet, words=words(full.text) - 1).text == summary.text
    assert describe(hamlet, words=words(summary.text)).style == "summary"
    short = describe(hamlet, words=5)  # nothing fits: the caption
    assert short.style == "short" and short.text == describe(hamlet, style="short").text
    for bad in (0, -3, 2.5, True):
        with pytest.raises(InputError):
            describe(hamlet, words=bad)


def test_the_describe_command_takes_a_word_budget(hamlet, tmp_path, capsys):
    path = tmp_path / "scene.json"
    path.write_text(hamlet.to_json())
    budget = words(describe(hamlet, style="summary").text)
    assert main(["describe", str(path), "--words", str(budget)]) == 0
    assert capsys.readouterr().out.strip() == describe(hamlet, style="summary").text
    assert main(["describe", str(path), "--words", "0"]) == 2
    assert "must be at least 1" in capsys.readouterr().err


def test_a_large_scenes_picture_is_captioned_by_concrete_things(hamlet, monkeypatch):
    from render_fixtures import renderer_or_skip

    from scenewright.describer import view
    from scenewright.render.visibility import PictureView, Thresholds

    renderer = renderer_or_skip(160, 120)
    try:
        picture = PictureView.from_render(
            renderer.render(hamlet), hamlet, Thresholds(min_visible=0.0, min_size=1)
        )
    finally:
        renderer.close()
    assert "five homes" in view.describe_view(hamlet, picture).text  # a small scene: its groups
    monkeypatch.setattr(
        view, "LARGE_SCENE", 10
    )  # the hamlet (over 10 objects) is a large scene now
    caption = view.describe_view(hamlet, picture)
    first = caption.sentences[0].text
    assert "home" not in caption.text and "four cottages, a house and four street lamps" in first, (
        first
    )
    # Each home is named by the thing its garden stands around, and only what is named is related.
    named = {i for m in caption.mentions for i in m.ids}
    assert {o.parent for o in hamlet.objects if o.id in named and o.type == "house"} == {
        o.id for o in hamlet.objects if o.type == "home"
    }
    assert all(s in named and t in named for s, _, t in caption.facts)
    assert ungrammatical([s.text for s in caption.sentences]) == []
