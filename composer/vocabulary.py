"""The words composing understands: object nouns from a catalog, relation phrases from
the relation registry, room words, counts, and the nearest known word for one it does not.

Nothing here is a fixed list of furniture: the object nouns are the catalog's nouns,
plurals (given, or made by inflection), style nouns ("double bed") and style names
before the noun ("oak wardrobe"); the relation phrases are the registry's wordings
(``describer.lexicon.relation_wordings``), so a label registered with new wordings is
understood at once. ``SYNONYMS`` maps the words people use for a catalog noun
("fridge") to it; a synonym whose noun the catalog lacks is simply not offered.
"""

from __future__ import annotations

import difflib
import functools
import re
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from types import MappingProxyType

from scenewright.core.relations import RELATIONS, SIDES
from scenewright.describer.colours import COLOUR_TERMS
from scenewright.describer.english import number_word, ordinal_word
from scenewright.describer.lexicon import relation_wordings
from scenewright.generator.catalog import CatalogEntry

#: Everyday words for catalog nouns (lower case, singular): word -> catalog noun.
SYNONYMS: dict[str, str] = {
    "fridge": "refrigerator",
    "couch": "sofa",
    "settee": "sofa",
    "bookcase": "bookshelf",
    "night stand": "nightstand",
    "bedside table": "nightstand",
    "bedside cabinet": "nightstand",
    "closet": "wardrobe",
    "carpet": "rug",
    "mat": "rug",
    "tv": "television",
    "telly": "television",
    "television stand": "TV stand",
    "tv unit": "TV stand",
    "basin": "washbasin",
    "bath": "bathtub",
    "tub": "bathtub",
    "cooker": "stove",
    "oven": "stove",
    "worktop": "counter",
    "kitchen counter": "counter",
    "kitchen sink": "sink",
    "houseplant": "plant",
    "potted plant": "plant",
    "computer": "laptop",
    "table lamp": "lamp",
    "bedside lamp": "lamp",
    "chest of drawers": "dresser",
    "drawers": "dresser",
    "board": "whiteboard",
    "chalkboard": "blackboard",
    "table": "dining table",
    "queen bed": "double bed",
    "queen-size bed": "double bed",
    "king bed": "king-size bed",
    "twin bed": "single bed",
    "three-seater sofa": "sofa",
    "three-seater": "sofa",
    "loveseat": "two-seater sofa",
    "kitchen table": "dining table",
    "sofa table": "coffee table",
    "stool": "chair",
    "dining chair": "chair",
    "desk chair": "office chair",
    "bike": "exercise bike",
    "rower": "rowing machine",
    "loo": "toilet",
    "washer": "washing machine",
    "night table": "nightstand",
    "bedside tables": "nightstand",
    "armoire": "wardrobe",
    "shelf": "bookshelf",
    "shelving unit": "bookshelf",
    "book shelf": "bookshelf",
    "swivel chair": "office chair",
    "computer chair": "office chair",
    "work chair": "office chair",
    "writing desk": "desk",
    "computer desk": "desk",
    "work desk": "desk",
    "end table": "side table",
    "lamp table": "side table",
    "occasional table": "side table",
    "accent table": "side table",
    "cupboard": "cabinet",
    "sideboard": "cabinet",
    "buffet": "cabinet",
    "credenza": "cabinet",
    "bench": "piano bench",
    "piano stool": "piano bench",
    "reading lamp": "floor lamp",
    "standing lamp": "floor lamp",
    "standard lamp": "floor lamp",
    "king size bed": "king-size bed",
    "queen size bed": "double bed",
    "media console": "TV stand",
    "tv cabinet": "TV stand",
    "entertainment center": "TV stand",
    "entertainment unit": "TV stand",
    "dumbbells": "dumbbell rack",
    "rack of dumbbells": "dumbbell rack",
    "weights rack": "dumbbell rack",
    "stationary bike": "exercise bike",
    "running machine": "treadmill",
    "yoga mat": "exercise mat",
    "fridge freezer": "refrigerator",
    "conference table": "dining table",
    "meeting table": "dining table",
    "vanity": "washbasin",
    # "a TV on a stand": the noun; "stand" after a thing is still the verb of the
    # registry's wordings ("the bed and the dresser stand against"), which are read first
    "stand": "TV stand",
}

#: Everyday words whose catalog type depends on the room: in a bathroom a "sink" is
#: the washbasin, not the kitchen's sink counter. Room scene name -> {type: type}.
ROOM_TYPES: dict[str, dict[str, str]] = {
    "bathroom": {"sink_counter": "washbasin"},
    "laundry_room": {"sink_counter": "washbasin"},
    "classroom": {"desk": "student_desk"},
}

#: Room kinds: word -> (scene name, default size W x D in metres).
ROOMS: dict[str, tuple[str, tuple[float, float]]] = {
    "bedroom": ("bedroom", (4.6, 4.0)),
    "kitchen": ("kitchen", (5.5, 4.8)),
    "living room": ("living_room", (5.6, 4.8)),
    "lounge": ("living_room", (5.6, 4.8)),
    "sitting room": ("living_room", (5.6, 4.8)),
    "bathroom": ("bathroom", (3.2, 2.8)),
    "study": ("study", (4.0, 3.6)),
    "office": ("office", (4.0, 3.6)),
    "classroom": ("classroom", (8.0, 7.0)),
    "dining room": ("dining_room", (5.0, 4.2)),
    "gym": ("gym", (6.0, 5.0)),
    "home gym": ("gym", (6.0, 5.0)),
    "master bedroom": ("bedroom", (4.6, 4.0)),
    "guest bedroom": ("bedroom", (4.6, 4.0)),
    "guest room": ("bedroom", (4.6, 4.0)),
    "spare room": ("bedroom", (4.6, 4.0)),
    "kids room": ("bedroom", (4.6, 4.0)),
    "kids' room": ("bedroom", (4.6, 4.0)),
    "children's room": ("bedroom", (4.6, 4.0)),
    "nursery": ("bedroom", (4.6, 4.0)),
    "dorm room": ("bedroom", (4.6, 4.0)),
    "family room": ("living_room", (5.6, 4.8)),
    "den": ("living_room", (5.6, 4.8)),
    "music room": ("living_room", (5.6, 4.8)),
    "reading nook": ("living_room", (5.6, 4.8)),
    "reading corner": ("living_room", (5.6, 4.8)),
    "home office": ("office", (4.0, 3.6)),
    "workspace": ("office", (4.0, 3.6)),
    "library": ("study", (4.0, 3.6)),
    "meeting room": ("meeting_room", (5.0, 4.0)),
    "conference room": ("meeting_room", (5.0, 4.0)),
    "boardroom": ("meeting_room", (5.0, 4.0)),
    "hall": ("hall", (3.0, 2.4)),
    "hallway": ("hall", (3.0, 2.4)),
    "entrance hall": ("hall", (3.0, 2.4)),
    "entryway": ("hall", (3.0, 2.4)),
    "corridor": ("corridor", (6.0, 1.8)),
    "laundry room": ("laundry_room", (3.0, 2.6)),
    "utility room": ("laundry_room", (3.0, 2.6)),
    "studio": ("studio", (6.0, 5.0)),
    "studio apartment": ("studio", (6.0, 5.0)),
    "room": ("room", (0.0, 0.0)),
    "scene": ("room", (0.0, 0.0)),
}

#: Outdoor scenes, read as a room word is ("a small village"): word -> (scene name, no
#: size of its own: the ground is made as large as what it holds needs,
#: ``composer.outdoor.extent``).
OUTDOOR_SCENES: dict[str, tuple[str, tuple[float, float]]] = {
    "village": ("village", (0.0, 0.0)),
    "hamlet": ("village", (0.0, 0.0)),
    "town": ("town", (0.0, 0.0)),
    "market town": ("town", (0.0, 0.0)),
    "city": ("city", (0.0, 0.0)),
}
ROOMS.update(OUTDOOR_SCENES)

#: Size words before a room word: factor on its default sides.
ROOM_SIZES: dict[str, float] = {
    "tiny": 0.7,
    "small": 0.82,
    "little": 0.82,
    "cosy": 0.85,
    "cozy": 0.85,
    "compact": 0.85,
    "medium": 1.0,
    "large": 1.2,
    "big": 1.2,
    "spacious": 1.25,
    "huge": 1.4,
}

NUMBERS: dict[str, int] = {
    "a": 1,
    "an": 1,
    "one": 1,
    "single": 1,
    "two": 2,
    "three": 3,
    "four": 4,
    "five": 5,
    "six": 6,
    "seven": 7,
    "eight": 8,
    "nine": 9,
    "ten": 10,
    "eleven": 11,
    "twelve": 12,
    "a couple of": 2,
    "a pair of": 2,
    "a few": 3,
    "several": 3,
    "some": 2,
    "a couple": 2,
    "couple of": 2,
    "pair of": 2,
    "a dozen": 12,
    "dozen": 12,
    "half a dozen": 6,
}

ORDINALS: dict[str, int] = {
    "first": 1,
    "second": 2,
    "third": 3,
    "fourth": 4,
    "fifth": 5,
    "sixth": 6,
    "seventh": 7,
    "eighth": 8,
    "ninth": 9,
    "tenth": 10,
    "1st": 1,
    "2nd": 2,
    "3rd": 3,
    "4th": 4,
}

#: Counts and positions past twelve and tenth, in the describer's words ("fifty-five
#: homes", "the three hundred and fifteenth home"): a city's description counts that far.
NUMBERS.update({number_word(n): n for n in range(13, 1000)})
ORDINALS.update({ordinal_word(n): n for n in range(5, 1000)})

COMPASS_WORDS = ("north", "east", "south", "west")
#: A rectangle's walls by number (docs/rules-language.md, Rooms).
WALL_NUMBER = {"north": 1, "east": 2, "south": 3, "west": 4}

#: Words that start a request or a sentence of one ("Add a piano ...", "Could you
#: furnish ..."); used wherever they stand, never reported.
REQUEST_WORDS = (
    "add can could you my our just show furnish furnished design so too go goes will"
).split()

#: Words that join or frame phrases; used wherever they stand, never reported.
FUNCTION_WORDS = frozenset(
    "and with , ; : is are be there here has have had contains containing contain consists "
    "consist of includes including include featuring features also plus then it its "
    "that which where this these those please i we want would like need needs make "
    "create give me put place set up an a the in on at to by for as should must "
    "let there's i'd want's both all each every another more other same empty bare".split()
    + REQUEST_WORDS
)


@dataclass(frozen=True)
class NounSense:
    """What an object noun phrase names: a catalog type, a style of it (or any), plural or not."""

    type: str
    style: str | None
    plural: bool
    exact: bool = True  # False: a plain noun, whose style is only the default for a new thing


@dataclass(frozen=True)
class RelationSense:
    """A relation phrase: the labels it may mean (by what its object names), and its number."""

    labels: tuple[str, ...]
    plural: bool
    bare: bool  # a place phrase without its verb ("against the wall" after a noun)


def _plural(word: str) -> str:
    import inflect

    return str(inflect.engine().plural_noun(word))


def _entry_nouns(entry: CatalogEntry) -> dict[str, NounSense]:
    out: dict[str, NounSense] = {}

    def add(noun: str, plural: str | None, style: str | None, exact: bool = True) -> None:
        key = noun.lower()
        out.setdefault(key, NounSense(entry.name, style, False, exact))
        many = (plural or _plural(noun)).lower()
        out.setdefault(many, NounSense(entry.name, style, True, exact))

    # A style without a noun of its own is what the plain noun names (the describer
    # says "a wardrobe" for the oak one); the plain noun means any style when every
    # style renames the thing ("bed": double, single or king-size).
    plain = [s.name for s in entry.styles if s.noun is None or s.noun == entry.noun]
    add(entry.noun, entry.plural, plain[0] if len(plain) == 1 else None, exact=False)
    for style in entry.styles:
        if style.noun is not None:
            add(style.noun, style.plural, style.name)
        add(f"{style.name} {entry.noun}", None, style.name)
    return out


@dataclass(frozen=True)
class Vocabulary:
    """Phrase tables for one catalog (see the module docstring)."""

    nouns: Mapping[str, NounSense]
    relations: Mapping[str, RelationSense]
    entries: Mapping[str, CatalogEntry]
    #: Group types ("row of desks"): things that consist of other things.
    groups: frozenset[str] = frozenset()
    #: Nouns a group shares with an object type (the city's "shop", a group of a shop
    #: building, a sign and goods): the group's sense, the object's being in ``nouns``.
    shared: Mapping[str, NounSense] = field(default_factory=lambda: MappingProxyType({}))

    @functools.cached_property
    def known_words(self) -> tuple[str, ...]:
        words: set[str] = set(FUNCTION_WORDS) | set(NUMBERS) | set(ORDINALS)
        for table in (self.nouns, self.relations, ROOMS, ROOM_SIZES, COLOUR_TERMS):
            for phrase in table:
                words.update(re.findall(r"[a-z'-]+", phrase.lower()))
        words.update(COMPASS_WORDS)
        words.update(
            "wall walls window windows door doors corner corners side sides middle centre "
            "center either around along no without facing metre metres meter meters m by x "
            "against under near next beside between opposite".split()
        )
        return tuple(sorted(w for w in words if len(w) > 1))

    def suggest(self, word: str) -> str | None:
        """The nearest known word to an unknown one, or None when none is near."""
        near = difflib.get_close_matches(word.lower(), self.known_words, n=1, cutoff=0.75)
        return near[0] if near else None


def _relation_phrases() -> dict[str, RelationSense]:
    """Each described label's wordings as phrases: "is to the left of" (singular),
    "are to the left of" (plural), "to the left of" (after a noun, no verb)."""
    found: dict[tuple[str, bool, bool], list[str]] = {}
    for name in sorted(RELATIONS.names()):
        spec = RELATIONS[name]
        if not spec.described:
            continue
        # A label that chooses its direction is stated in the words of the direction
        # chosen, which belong to a label of their own ("is just to the left of":
        # BesideLeft), or as plain "next to" (NextTo's): it has no phrase of its own.
        if spec.chooses and not spec.seat:
            continue
        wordings = list(relation_wordings(name))
        for wording in wordings:
            verb, _, rest = wording.partition(" ")
            forms = [(wording, False, False)]
            if verb == "is":
                forms.append(("are " + rest, True, False))
                forms.append((rest, False, True))
            elif verb.endswith("s"):
                stem = (
                    verb[:-2]
                    if verb.endswith("es") and verb[:-2].endswith(("ss", "sh"))
                    else verb[:-1]
                )
                forms.append((f"{stem} {rest}", True, False))
                if verb == "stands":
                    forms.append((rest, False, True))
            for phrase, plural, bare in forms:
                found.setdefault((phrase, plural, bare), []).append(name)
    out: dict[str, RelationSense] = {}
    for (phrase, plural, bare), labels in sorted(found.items()):
        if phrase in out:  # "beside" after a noun: NextTo's "is beside" or BesideWindow's
            labels = labels + list(out[phrase].labels)
        # "against" comes from both "stands against" and "is against": one label once
        out[phrase] = RelationSense(tuple(sorted(set(labels))), plural, bare)
    return out


@functools.cache
def relation_phrases() -> Mapping[str, RelationSense]:
    return _relation_phrases()


def vocabulary(
    entries: Mapping[str, CatalogEntry],
    prefer: Iterable[str] = (),
    synonyms: Mapping[str, str] = SYNONYMS,
) -> Vocabulary:
    """The vocabulary of a catalog (objects, groups, paths and junctions). Where two
    types share a noun, one of ``prefer`` (the types a rule set given as the catalog
    makes: a classroom's "desk" is its pupils' desk) names it. ``synonyms``: everyday
    words for its nouns (outdoors, ``composer.outdoor.SYNONYMS``)."""
    nouns: dict[str, NounSense] = {}
    objects = {name: e for name, e in sorted(entries.items()) if e.kind == "object"}
    groups = {name: e for name, e in sorted(entries.items()) if e.kind == "group"}
    ways = {name: e for name, e in sorted(entries.items()) if e.kind in ("path", "junction")}
    first = set(prefer)
    ordered = sorted(
        [*objects.values(), *groups.values(), *ways.values()], key=lambda e: e.name not in first
    )
    for entry in ordered:
        for phrase, sense in _entry_nouns(entry).items():
            nouns.setdefault(phrase, sense)
    for word, noun in synonyms.items():
        sense = nouns.get(noun.lower())
        if sense is not None and word not in nouns:
            nouns[word] = sense
            for style in entries[sense.type].styles if not sense.exact else ():
                # "a small table": the style's name before the everyday word
                nouns.setdefault(f"{style.name} {word}", NounSense(sense.type, style.name, False))
            nouns.setdefault(_plural(word), NounSense(sense.type, sense.style, True, sense.exact))
    shared = {
        phrase: sense
        for entry in groups.values()
        for phrase, sense in _entry_nouns(entry).items()
        if nouns[phrase].type != entry.name and nouns[phrase].type in objects
    }
    return Vocabulary(nouns, relation_phrases(), objects | groups | ways, frozenset(groups), shared)


def side_label(side: str) -> str:
    """The next-to label for one of B's own sides ("left" -> ``NextToLeft``)."""
    assert side in SIDES
    return "NextTo" + side.capitalize()
