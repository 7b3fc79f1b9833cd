"""A house in English: what rooms it has and how they join, then each room as a room is described.

The overview is read off the plan: the rooms by type and count ("The flat has a hall,
a kitchen, a living room, a bathroom and two bedrooms."), the front door ("The front
door opens into the hall."), then each room a door leads from, in plan order, with the
rooms it leads to that no earlier sentence named ("The hall leads to the living room,
the bathroom and both bedrooms.") and the rooms open to each other ("The kitchen is
open to the living room."). Then one paragraph per room, the room's own description
(``describer.describe`` of the room scene) with the room named where a room scene says
"the scene" or "the room" ("The second bedroom has a double bed, ...").

The short style is the overview's first sentence; summary describes each room in the
summary style.
"""

from __future__ import annotations

import re
from collections import Counter

from scenewright.core.house import House, in_room
from scenewright.core.scene import Scene
from scenewright.describer import describe
from scenewright.describer.description import Description
from scenewright.describer.english import join_list, number_word, plural_of, sentence_case

from .assemble import room_scene

#: A room scene's words for itself at the start of a sentence, which the house replaces
#: by the room's name.
_SELF = re.compile(r"(^|(?<=\. ))The (scene|room) (?=(consists of|is made up of|has|is empty))")


def describe_house(scene: Scene, *, style: str = "full", variant: int = 0) -> Description:
    house = scene.house
    assert house is not None
    overview = overview_sentences(house)
    if style == "short":
        return Description(overview[0], [], style, variant)
    paragraphs = [" ".join(overview)]
    facts: list[tuple[str, str, str]] = []
    for house_room in house.rooms:
        room = room_scene(scene, house_room.id)
        text = describe(room, style=style, variant=variant)
        name = f"The {house_room.name}"
        paragraphs.append(
            _SELF.sub(f"{name} ", text.text).replace(" The room has ", f" {name} has ")
        )
        facts.extend(
            (in_room(house_room.id, a), label, in_room(house_room.id, b))
            for a, label, b in text.facts
        )
    # one line: scene.json's text holds no line breaks (the overview and each room still
    # start sentences of their own)
    return Description(" ".join(paragraphs), facts, style, variant)


def overview_sentences(house: House) -> list[str]:
    """The overview: rooms, front door, which rooms lead to which."""
    counts = Counter(room.type for room in house.rooms)
    names: dict[str, str] = {}
    listed = []
    for room in house.rooms:
        words = _type_words(house, room.type)
        if room.type in names:
            continue
        names[room.type] = words
        count = counts[room.type]
        listed.append(
            f"{_article(words)} {words}"
            if count == 1
            else f"{number_word(count)} {plural_of(words)}"
        )
    sentences = [f"The {house.noun} has {join_list(listed)}."]
    entrance = house.entrance
    if entrance is not None:
        sentences.append(f"The front door opens into the {house.room(entrance.rooms[0]).name}.")
    told: set[frozenset[str]] = set()
    for room in house.rooms:
        shut = [
            other
            for other, door in house.neighbours(room.id)
            if not door.open and frozenset((room.id, other)) not in told
        ]
        if shut:
            sentences.append(f"The {room.name} leads to {join_list(_the_rooms(house, shut))}.")
            told.update(frozenset((room.id, other)) for other in shut)
    for door in house.doors:
        if door.open and len(door.rooms) == 2:
            a, b = (house.room(r) for r in door.rooms)
            sentences.append(f"The {a.name} is open to the {b.name}.")
    return [sentence_case(s) for s in sentences]


def _the_rooms(house: House, room_ids: list[str]) -> list[str]:
    """ "the bathroom", "both bedrooms", "all three bedrooms" where a sentence names every
    room of a type, else each room by name."""
    by_type = Counter(house.room(r).type for r in room_ids)
    total = Counter(room.type for room in house.rooms)
    phrases, done = [], set()
    for room_id in room_ids:
        room = house.room(room_id)
        if room.type in done:
            continue
        if by_type[room.type] == total[room.type] and total[room.type] > 1:
            words = plural_of(_type_words(house, room.type))
            count = total[room.type]
            phrases.append(f"both {words}" if count == 2 else f"all {number_word(count)} {words}")
            done.add(room.type)
        else:
            phrases.append(f"the {room.name}")
    return phrases


def _type_words(house: House, room_type: str) -> str:
    """A room type in words: its rooms' name without an ordinal ("bedroom")."""
    names = [room.name for room in house.rooms if room.type == room_type]
    if len(names) == 1:
        return names[0]
    return names[0].split(" ", 1)[1] if " " in names[0] else names[0]


def _article(words: str) -> str:
    from scenewright.describer.english import with_article

    return with_article(words).split(" ", 1)[0]
