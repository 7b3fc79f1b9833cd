"""``describe``: a scene in, its English description and the facts it states out.

Plan (``plan``), then realise (``realise``) with the referring expressions of
``refer``, the words of ``lexicon`` and the sentence templates of ``templates``.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from numbers import Integral
from pathlib import Path

from scenewright.core.errors import InputError
from scenewright.core.scene import Scene, SceneDescription

from .content_plan import (
    Introduction,
    Inventory,
    Item,
    Network,
    Section,
    Statement,
    introduced_by,
    plan_document,
)
from .english import singular_of
from .grounding import Mention
from .paraphrase import Choices
from .realise import Realiser, Sentence
from .templates import template_environment
from .world import World, world_of

STYLES = ("full", "summary", "short")
#: The styles a word budget chooses from, the most detailed first.
BUDGET_LEVELS = ("full", "summary", "short")

#: How many times the full text is planned again to put paragraphs in the order of
#: their groups' ordinals (one is enough unless a paragraph names a later group first).
MAX_REORDERINGS = 3


@dataclass
class Description(SceneDescription):
    """A scene's description: the text and every (subject id, label, object id) it states.

    ``sentences`` has the same text sentence by sentence, each with the facts it states
    (what a truth check reads); scene.json stores only text and facts (``record``).
    ``mentions``: every phrase that names something, as a character span into ``text``
    with the entities it names and their objects (``grounding``), in the order the
    phrases start.
    """

    sentences: list[Sentence] = field(default_factory=list)
    mentions: list[Mention] = field(default_factory=list)

    def record(self) -> SceneDescription:
        """What a scene keeps of it (scene.json's ``description``)."""
        return SceneDescription(self.text, list(self.facts), self.style, self.variant)


def describe(
    scene: Scene,
    *,
    style: str = "full",
    variant: int = 0,
    templates: str | Path | None = None,
    words: int | None = None,
) -> Description:
    """Describe ``scene`` in English.

    ``style``: "full" (the scene, then each group, every object mentioned), "summary"
    (the full text with every big cohort told by counts: ``summary``) or "short" (a
    caption of one or two sentences). ``words``: a word budget, instead of ``style``:
    the first of full, summary and short whose text has at most that many words (short
    when none has). ``variant`` 0 is the canonical text; variant k
    is a seeded paraphrase (synonyms, order of list items and statements) drawn from the
    describer's child stream k of ``scene.seed`` (``core.seeds``). ``templates``: a folder whose ``*.j2``
    files replace the package's sentence templates of the same name.
    """
    if words is None:
        return describe_frame(scene, style=style, variant=variant, templates=templates)
    if isinstance(words, bool) or not isinstance(words, Integral) or words < 1:
        raise InputError(f"a word budget must be a whole number >= 1, got {words!r}")
    for level in BUDGET_LEVELS:
        description = describe_frame(scene, style=level, variant=variant, templates=templates)
        if len(description.text.split()) <= words:
            break
    return description


def describe_frame(
    scene: Scene,
    *,
    style: str = "full",
    variant: int = 0,
    templates: str | Path | None = None,
    picture: bool = False,
    picture_sides: bool = False,
    unseen: bool = False,
    concrete: bool = False,
) -> Description:
    """``describe``, with the settings of ``view.describe_view``: ``picture``, the scene
    is what a rendered picture shows of one (its caption may say "A picture of ...");
    ``picture_sides``, its ``NextToChooseSide`` relations are sides as the picture shows
    them ("to the left of the tent in the picture"); ``unseen``, the picture shows
    nothing of a scene that has things (not "an empty village"); ``concrete``, the
    caption names each group by the thing it is arranged around ("three houses", not
    "three homes"), and states only relations among what it names."""
    if style not in STYLES:
        raise InputError(
            f"unknown description style {style!r}; expected one of: {', '.join(STYLES)}"
        )
    if isinstance(variant, bool) or not isinstance(variant, Integral) or variant < 0:
        raise InputError(f"description variant must be a whole number >= 0, got {variant!r}")
    variant = int(variant)  # a numpy integer from a dataset loop is welcome too
    world = world_of(scene)
    environment = template_environment(templates)
    summary = style == "summary"
    sections = plan_document(scene, world, summary=summary)
    realiser = Realiser(
        world, environment, Choices.for_variant(scene.seed, variant), picture_sides=picture_sides
    )
    if style != "short":
        sentences = realiser.sections(sections)
        for _ in range(MAX_REORDERINGS):
            # Ordinals count in the order the text first names things, so a group named
            # before its paragraph ("next to the first park") has its paragraph first:
            # plan again with the paragraphs in that order, until they agree.
            first = realiser.discourse.rank_order()
            again = plan_document(scene, world, first, summary=summary)
            if [s.owner for s in again] == [s.owner for s in sections]:
                break
            sections = again
            realiser = Realiser(
                world,
                environment,
                Choices.for_variant(scene.seed, variant),
                picture_sides=picture_sides,
            )
            sentences = realiser.sections(sections)
    else:
        sentences = _caption(
            scene, world, sections, realiser, picture=picture, unseen=unseen, concrete=concrete
        )
    return Description(
        text=" ".join(s.text for s in sentences),
        facts=[fact for s in sentences for fact in s.facts],
        style=style,
        variant=variant,
        sentences=sentences,
        mentions=_mentions_in_text(sentences, world),
    )


def _mentions_in_text(sentences: list[Sentence], world: World) -> list[Mention]:
    """Each sentence's mentions with offsets into the joined text and their objects filled in."""
    found: list[Mention] = []
    offset = 0
    for sentence in sentences:
        for m in sentence.mentions:
            found.append(
                Mention(
                    m.start + offset, m.end + offset, m.entities, world.grounded_ids(m.entities)
                )
            )
        offset += len(sentence.text) + 1  # the space joining sentences
    return found


def _caption(
    scene: Scene,
    world: World,
    sections: list[Section],
    realiser: Realiser,
    *,
    picture: bool,
    unseen: bool,
    concrete: bool = False,
) -> list[Sentence]:
    """What the scene holds at its top level, and one top-level statement if there is one.

    A scene whose top level is one group (a desk and what is on it) is captioned by
    that group's contents instead. In a room, the statement is where the most prominent
    furniture stands against the room, when some statement says so ("The bed stands in
    the north-east corner.").
    """
    by_owner = {section.owner: section for section in sections}
    owner: str | None = None
    items = _caption_items(by_owner[None], world)
    while (
        len(items) == 1
        and not isinstance(items[0], Network)
        and len(items[0]) == 1
        and items[0][0] in by_owner
    ):
        owner = items[0][0]
        items = _caption_items(by_owner[owner], world)
    if concrete:
        items = _concrete_items(scene, world, items)
    realiser.discourse.start_paragraph(owner)
    setting_ids = (owner,) if owner is not None else ()
    sentences = [
        realiser.caption(
            _setting(scene, world, owner), items, setting_ids, picture=picture, unseen=unseen
        )
    ]
    statements = [m for m in by_owner[owner].messages if isinstance(m, Statement) and not m.also]
    if concrete:  # only what the caption named: no abstract group turns up unannounced
        named = set(introduced_by(Inventory(None, items)))
        statements = [
            m
            for m in statements
            if set(m.subjects) <= named
            and all(t in named or t not in world for c in m.clauses for t in c.targets)
        ]
    by_room = [
        m for m in statements if any(world.place_kind(t) for c in m.clauses for t in c.targets)
    ]
    if by_room:
        # The biggest thing placed against the room says most about how the room looks.
        statements = sorted(by_room, key=lambda m: -max(_volume(scene, s) for s in m.subjects))
    if statements:
        # The canonical caption tells the first relation; a variant any one of them.
        sentences.append(realiser.message(realiser.choices.pick(statements)))
    return sentences


def _volume(scene: Scene, entity_id: str) -> float:
    """The volume of an object's or group's box (0 for a path): how prominent it is."""
    try:
        width, height, depth = scene.object(entity_id).size
    except KeyError:  # a path has no box
        return 0.0
    return width * height * depth


def _concrete_items(scene: Scene, world: World, items: tuple[Item, ...]) -> tuple[Item, ...]:
    """The items with each group replaced by the object it is arranged around (at any
    depth), counted by noun with the other items: what a picture shows of it ("two
    tents", not "two camp pitches"). That object is the one most of the group's
    relations lead to (a home's house: its garden stands around it), the biggest on a
    tie. A group that holds no object stays as it is."""
    leading_to: dict[str, int] = {}
    for relation in scene.relations:
        leading_to[relation.target] = leading_to.get(relation.target, 0) + 1
    concrete: list[Item] = []
    by_noun: dict[str, int] = {}
    for item in items:
        if isinstance(item, Network):
            concrete.append(item)
            continue
        for entity_id in item:
            objects = [
                i
                for i in world.grounded_ids((entity_id,))
                if i in world and world[i].kind == "object"
            ]
            chosen = (
                max(objects, key=lambda i: (leading_to.get(i, 0), _volume(scene, i)))
                if objects
                else entity_id
            )
            noun = world[chosen].noun
            if noun in by_noun:
                counted = concrete[by_noun[noun]]
                assert not isinstance(counted, Network)  # by_noun indexes counted entities only
                concrete[by_noun[noun]] = counted + (chosen,)
            else:
                by_noun[noun] = len(concrete)
                concrete.append((chosen,))
    return tuple(concrete)


def _caption_items(section: Section, world: World) -> tuple[Item, ...]:
    """Everything a section introduces, as list items: its inventory, then what stands on it.

    Entities of one noun are counted together wherever the full text introduces them.
    """
    items: list[Item] = []
    by_noun: dict[str, int] = {}
    for message in section.messages:
        if isinstance(message, Inventory):
            found = list(message.items)
        elif isinstance(message, Introduction):
            found = list(message.subjects)
        else:
            continue
        for item in found:
            if isinstance(item, Network):
                items.append(item)
                continue
            noun = world[item[0]].noun
            if noun in by_noun:
                counted = items[by_noun[noun]]
                assert not isinstance(counted, Network)  # by_noun indexes counted entities only
                items[by_noun[noun]] = counted + item
            else:
                by_noun[noun] = len(items)
                items.append(item)
    return tuple(items)


def _setting(scene: Scene, world: World, owner: str | None) -> str:
    """What the caption calls the whole: the captioned group's noun, the name of the
    rule set's ``scene`` block (``scene music_room``: "music room"; a scene without one
    goes by the rules file's name), made singular ("bedrooms.rules": "A bedroom with"),
    or "scene"."""
    if owner is not None:
        return world[owner].noun
    named = scene.name if scene.name != "scene" else Path(scene.rules).stem
    name = named.replace("_", " ")
    return singular_of(name) if re.fullmatch(r"[A-Za-z]+( [A-Za-z]+)*", name) else "scene"
