"""Grounding in the describer: every phrase that names something is a span with its ids."""

import re

import pytest
from hypothesis import given, settings
from test_describe_room import two_windows
from test_describer import SceneBuilder, market_scene, random_scenes

from scenewright.core.errors import InputError
from scenewright.describer import TemplateError, describe
from scenewright.describer.world import world_of


def spans(description) -> list[tuple[str, tuple[str, ...]]]:
    return [(description.text[m.start : m.end], m.entities) for m in description.mentions]


def names_its_entities(phrase: str, entities: tuple[str, ...], world) -> bool:
    """The phrase holds the noun (or plural) of what it names, or is the pronoun "it"."""
    if phrase.lower() == "it":
        return len(entities) == 1
    lowered = phrase.lower()
    for entity_id in entities:
        if entity_id in world:
            entity = world[entity_id]
            if entity.noun.lower() not in lowered and entity.plural.lower() not in lowered:
                return False
        elif not re.search(r"\b(door|window)s?\b", lowered):
            return False
    return True


def test_repeated_nouns_in_one_sentence_are_told_apart():
    b = SceneBuilder()
    roads = [b.road() for _ in range(3)]
    well = b.add("well")
    b.relate(well, "NextTo", roads[0])
    b.relate(well, "NextToNorth", roads[2])
    description = describe(b.scene())
    told = spans(description)
    assert ("three roads", tuple(roads)) in told
    sentence = next(s for s in description.sentences if s.text.startswith("The well"))
    by_text = {sentence.text[m.start : m.end]: m.entities for m in sentence.mentions}
    assert by_text["the first road"] == (roads[0],)
    assert by_text["the second road"] == (roads[2],)  # the second road the text names


def test_an_identical_phrase_twice_is_two_mentions_of_two_things():
    description = describe(market_scene())
    tables = [
        (m, description.text[m.start : m.end])
        for m in description.mentions
        if m.entities[0].startswith("table")
    ]
    assert [phrase for _, phrase in tables].count("a table") == 3
    assert len({m.entities for m, phrase in tables if phrase == "a table"}) == 3
    for _m, phrase in tables:
        # "this table" right after "a table" is the same table.
        assert phrase in ("a table", "this table")
    firsts = [m.entities for m, phrase in tables if phrase == "a table"]
    thises = [m.entities for m, phrase in tables if phrase == "this table"]
    assert firsts == thises


def test_groups_are_grounded_to_their_members_at_any_depth():
    b = SceneBuilder()
    farm = b.group("farmstead")
    yard = b.group("yard", parent=farm)
    hens = [b.add("hen", parent=yard) for _ in range(2)]
    barn = b.add("barn", parent=farm)
    description = describe(b.scene())
    world = world_of(b.scene())
    farm_mention = next(m for m in description.mentions if m.entities == (farm,))
    assert description.text[farm_mention.start : farm_mention.end] == "a farmstead"
    assert set(farm_mention.ids) == {*hens, barn}
    assert world.grounded_ids((yard,)) == tuple(hens)
    caption = describe(b.scene(), style="short")
    assert any(m.entities == (farm,) and set(m.ids) == {*hens, barn} for m in caption.mentions)


def test_a_placed_name_holds_the_mention_of_its_group():
    b = SceneBuilder()
    stands = [b.group("market_stand") for _ in range(3)]
    signs = [b.add("sign", parent=stands[1]) for _ in range(2)]
    b.add("table", parent=stands[1])
    lamp, _ = b.add("street_lamp"), b.add("sign")  # a sign of its own: the stands' are "of" theirs
    b.relate(lamp, "NextTo", signs[1])
    description = describe(b.scene())
    told = spans(description)
    assert (
        "the first sign of this market stand",
        (signs[1],),
    ) in told  # the first one the text names
    outer = next(
        m for m in description.mentions if m.entities == (signs[1],) and m.end - m.start > 20
    )
    inner = next(
        m
        for m in description.mentions
        if m.entities == (stands[1],) and outer.start < m.start < outer.end
    )
    assert description.text[inner.start : inner.end] == "this market stand"
    assert inner.end == outer.end
    assert description.mentions.index(outer) < description.mentions.index(inner)  # outer first


def test_doors_and_windows_are_grounded_walls_are_not():
    description = describe(two_windows())
    told = spans(description)
    assert ("two windows", ("window_1", "window_2")) in told
    assert ("the western window in the north wall", ("window_1",)) in told
    named = {e for _, entities in told for e in entities}
    assert not any(e.startswith(("wall_", "corner")) for e in named)
    assert {"door_1", "door_2"} <= named


def test_the_article_a_template_adds_is_part_of_the_mention():
    b = SceneBuilder(rules="desk")
    desk = b.group("desk")
    b.add("laptop", parent=desk)
    caption = describe(b.scene(), style="short")
    assert caption.text.startswith("A desk with a laptop")
    assert spans(caption)[0] == ("A desk", (desk,))


def test_a_template_may_move_and_repeat_phrases(tmp_path):
    (tmp_path / "statement.j2").write_text(
        "{{ predicates | join_list }}, so says {{ subject }} ({{ subject }})."
    )
    b = SceneBuilder()
    well, road, _ = b.add("well"), b.road(), b.add("barrel")  # three items: no folded-in relation
    b.relate(well, "NextTo", road)
    description = describe(b.scene(), templates=tmp_path)
    sentence = description.sentences[-1]
    assert sentence.text == "Is next to the road, so says the well (the well)."
    assert [(sentence.text[m.start : m.end], m.entities) for m in sentence.mentions] == [
        ("the road", (road,)),
        ("the well", (well,)),
        ("the well", (well,)),
    ]


def test_a_template_that_cuts_a_phrase_apart_is_an_error(tmp_path):
    (tmp_path / "statement.j2").write_text("{{ subject[:3] }} {{ predicates | join_list }}.")
    b = SceneBuilder()
    well, road, _ = b.add("well"), b.road(), b.add("barrel")
    b.relate(well, "NextTo", road)
    with pytest.raises(TemplateError, match="cut a named phrase apart"):
        describe(b.scene(), templates=tmp_path)


def test_a_noun_holding_the_private_marks_is_refused():
    b = SceneBuilder()
    b.add("well", "well\ue001")
    with pytest.raises(InputError, match="well_1: its noun holds a private-use character"):
        describe(b.scene())


@settings(max_examples=40, deadline=None)
@given(random_scenes())
def test_every_mention_names_what_it_links_to(drawn):
    scene, variant = drawn
    world = world_of(scene)
    for style in ("full", "short"):
        description = describe(scene, style=style, variant=variant)
        for m in description.mentions:
            phrase = description.text[m.start : m.end]
            assert phrase == phrase.strip() and phrase, (description.text, m)
            assert names_its_entities(phrase, m.entities, world), (phrase, m.entities)
            assert m.ids == world.grounded_ids(m.entities)
        if style == "full":
            named = {e for m in description.mentions for e in m.entities}
            assert named == set(world.entities)  # every entity is mentioned somewhere
        # The text is the same with or without the grounding: mentions only point into it.
        assert description.text == " ".join(s.text for s in description.sentences)
