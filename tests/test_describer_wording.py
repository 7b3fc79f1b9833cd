"""Wordings readers found wrong, each reproduced on a real laid-out scene and fixed.

``tests/rules/hall.rules`` (seed 3) nests rows of desks in rows of desks and gives desks
two styles whose nouns share a head ("white desk", "desk"). Before the fixes its text
read "The second row of desks at the first row of desks on its own is south of the
first row of desks at the first row of desks on its own.", "Two of the desks face the
same way as the first desk." (meaning the other two) and "The desk is to the left of
this white desk." after "the first white desk" ... "the second desk" counted by style
apart. Every sentence here must still be true (``check_true_and_complete``: facts,
ordinals in reading order) and parse with link-grammar.
"""

from pathlib import Path

import pytest

from scenewright.core.scene import assemble_scene
from scenewright.describer import describe
from scenewright.generator import expand, load_rules
from scenewright.generator.layout import layout_scene

from test_describer import SceneBuilder
from test_describer_e2e import check_ordinals, check_true_and_complete, ungrammatical

HALL = Path(__file__).parent / "rules" / "hall.rules"


def laid_out_file(path: Path, seed: int):
    graph = expand(load_rules(path), seed)
    return assemble_scene(graph, layout_scene(graph, seed), rules=str(path), seed=seed)


@pytest.fixture(scope="module")
def hall():
    return laid_out_file(HALL, 3)


def test_nested_groups_of_one_type_are_counted_across_the_scene(hall):
    text = describe(hall).text
    assert " at the row of desks" not in text and "row of desks on its own" not in text
    assert "The first row of desks consists of two rows of desks. The third row of desks is south of the fourth row of desks." in text
    assert "The second row of desks consists of two rows of desks. The fifth row of desks is south of the sixth row of desks." in text


def test_the_rest_of_a_cohort_named_in_the_sentence_is_the_other_ones(hall):
    text = describe(hall).text
    assert "Two of the desks face the same way as the first desk." not in text
    assert "The two other desks face the same way as the first desk." in text
    assert "The two other white desks face the same way as the first white desk." in text


def test_ordinals_of_a_noun_count_its_kinds_too(hall):
    # "desk" covers white desks: the plain desk named after the first white desk is the second desk.
    text = describe(hall).text
    # Before: "... the first white desk. The first desk is to the left of this white desk.", two counts of desks.
    assert "This chair is behind the first white desk. The second desk is to the left of this white desk." in text
    assert "The second white desk is to the left of the second desk." in text


def test_the_hall_is_told_truly_and_parses(hall):
    sentences = check_true_and_complete(hall)
    assert ungrammatical(sentences) == []


def test_ordinals_follow_the_order_the_text_singles_things_out():
    # The derivation's third pine tree is the first one the text names.
    b = SceneBuilder()
    trees = b.group("group_of_trees", "group of trees")
    pines = [b.add("pine_tree", parent=trees) for _ in range(3)]
    bushes = [b.add("bush", plural="bushes", parent=trees) for _ in range(2)]
    b.relate(bushes[0], "NextToSouth", pines[2])
    b.relate(bushes[1], "NextToNorth", pines[0])
    scene = b.scene()
    description = describe(scene)
    assert "the third pine tree" not in description.text
    assert "The first bush is south of the first pine tree." in description.text
    assert "The other bush is north of the second pine tree." in description.text
    check_ordinals(scene, description)
    assert ungrammatical([s.text for s in description.sentences]) == []


def test_the_ordinal_check_catches_an_ordinal_out_of_order():
    b = SceneBuilder()
    pines = [b.add("pine_tree") for _ in range(3)]
    b.add("well")
    b.relate("well_1", "NextTo", pines[2])
    scene = b.scene()
    description = describe(scene)
    check_ordinals(scene, description)
    wrong = description.text.replace("the first pine tree", "the third pine tree")
    description.text = wrong
    with pytest.raises(AssertionError):
        check_ordinals(scene, description)
