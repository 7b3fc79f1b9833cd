"""Descriptions of real scenes: shipped rules -> expansion -> layout -> text.

Every stated fact must hold in the layout (and, for direction words, in the geometry),
every entity must be mentioned or counted, and every sentence must parse with
link-grammar (``link-parser``; Debian package ``link-grammar``, installed by
scripts/setup.sh). Without ``link-parser`` the grammar checks skip, unless ``CI`` is set.

In a room, every name of a wall, door, window or corner in the text is read back from
the geometry alone (``RoomReader``: "the longer north wall" is the longer of the two
walls whose inner face looks south) and must pick out exactly one part; each relation a
sentence states to the room is measured again, by the layout's own code and thresholds
(``measure_layout``), against the part the sentence names; and the room sentence's
doors and windows are counted on the walls it names.

The default run covers a few seeds per rule set; the long sweep over seeds 0..199 runs
with ``SCENEWRIGHT_SLOW=1 .venv/bin/python -m pytest tests/test_describer_e2e.py -m slow``.
"""

import math
import os
import re
import shutil
import subprocess
from dataclasses import dataclass
from pathlib import Path

import pytest

from scenewright.core.geometry import make_rect, polyline_rects_distance
from scenewright.core.relations import RELATIONS
from scenewright.core.room import ROOM_NODE, Room, compass_word
from scenewright.core.scene import Scene, assemble_scene
from scenewright.core.scene_graph import SceneGraph
from scenewright.describer import Description, describe
from scenewright.describer.content_plan import introduced_by, plan_document
from scenewright.describer.english import plural_of
from scenewright.describer.rooms import DOOR_NEAR_CORNER
from scenewright.describer.world import world_of
from scenewright.generator import expand, load_rules
from scenewright.generator.layout import layout_scene
from scenewright.generator.layout.measure import measure_layout
from scenewright.generator.layout.pinning import scene_layout
from scenewright.generator.layout.relation_terms import WALL_TOLERANCE
from scenewright.generator.rules import shipped_rule_sets

GOLDEN = Path(__file__).parent / "golden" / "descriptions"

#: Unit vectors (x, z) of the directions a next-to label may name; north is -Z, east +X.
COMPASS = {"north": (0.0, -1.0), "east": (1.0, 0.0), "south": (0.0, 1.0), "west": (-1.0, 0.0)}
FIXED_DIRECTION = {
    "NextToNorth": "north",
    "NextToEast": "east",
    "NextToSouth": "south",
    "NextToWest": "west",
    "NextToLeft": "left",
    "NextToRight": "right",
    "NextToFront": "front",
    "NextToBehind": "behind",
}
#: The layout promises 45 degrees; the test allows some slack for its own centre-to-centre reading.
MAX_DIRECTION_ERROR = math.radians(60)


def split_sentences(text: str) -> list[str]:
    return re.split(r"(?<=\.) (?=[A-Z])", text)


def ungrammatical(sentences: list[str]) -> list[str]:
    """The sentences link-grammar finds no complete linkage for (skips without the parser)."""
    if shutil.which("link-parser") is None:
        if os.environ.get("CI"):
            pytest.fail("link-parser (Debian package link-grammar) is required under CI")
        pytest.skip("link-parser not installed (apt-get install link-grammar)")
    unique = list(dict.fromkeys(sentences))
    run = subprocess.run(
        ["link-parser", "en", "-batch"],
        # !limit: how many linkages the parser extracts and post-processes per sentence
        # (1000 by default). With 100 it takes 2.5 times less CPU time and flagged exactly
        # the same sentences among those of the shipped rule sets' tested seeds, the
        # golden descriptions and 300 mangled ones.
        input="!echo=1\n!limit=100\n" + "\n".join(unique) + "\n",
        capture_output=True,
        text=True,
        timeout=60 + 0.25 * len(unique),  # about 30 ms a sentence here; generous for a busy machine
    )
    failed, last = [], None
    for line in run.stdout.splitlines():
        if line.startswith("+++++ error"):
            failed.append(last)
        elif line in unique:
            last = line
    return failed


def direction_of(
    scene: Scene, label: str, chosen: str | None, target_id: str
) -> tuple[float, float] | None:
    """The world (x, z) unit vector a next-to label's words name, None when they name none."""
    word = FIXED_DIRECTION.get(label) or (chosen if label.startswith("NextToChoose") else None)
    if word is None:
        return None
    if word in COMPASS:
        return COMPASS[word]
    # B's own sides: yaw turns forward (local +Z) towards +X; left is local +X.
    yaw = scene.object(target_id).yaw
    forward, left = (math.sin(yaw), math.cos(yaw)), (math.cos(yaw), -math.sin(yaw))
    sides = {
        "front": forward,
        "left": left,
        "behind": (-forward[0], -forward[1]),
        "right": (-left[0], -left[1]),
    }
    return sides[word]


def check_true_and_complete(scene: Scene) -> list[str]:
    """Assert what every description of ``scene`` must satisfy; return its sentences."""
    description = describe(scene)
    holds = {(r.source, r.label, r.target): r for r in scene.relations if r.satisfied}
    starts = {(p.id, "PathConnectedTo", p.start) for p in scene.paths if p.start}
    for fact in description.facts:
        assert fact in holds or fact in starts, f"seed {scene.seed}: stated but not true: {fact}"
        relation = holds.get(fact)
        direction = relation and direction_of(
            scene, relation.label, relation.chosen, relation.target
        )
        if direction:
            source, target = scene.object(fact[0]).position, scene.object(fact[2]).position
            dx, dz = source[0] - target[0], source[2] - target[2]
            cosine = (dx * direction[0] + dz * direction[1]) / max(math.hypot(dx, dz), 1e-9)
            assert math.acos(max(-1.0, min(1.0, cosine))) < MAX_DIRECTION_ERROR, (
                f"seed {scene.seed}: {fact}"
            )
    world = world_of(scene)
    introduced = [
        i for s in plan_document(scene, world) for m in s.messages for i in introduced_by(m)
    ]
    assert sorted(introduced) == sorted(world.entities), (
        f"seed {scene.seed}: not every entity is mentioned"
    )
    descriptions = [description] + [describe(scene, variant=k) for k in (1, 2)]
    descriptions.append(describe(scene, style="short"))
    summaries = [describe(scene, style="summary"), describe(scene, style="summary", variant=1)]
    for summary in summaries:
        check_claims(scene, summary)
        for fact in summary.facts:
            assert fact in holds or fact in starts, (
                f"seed {scene.seed}: summary states but not true: {fact}"
            )
    descriptions += summaries
    for told in descriptions:
        check_ordinals(scene, told)
    if scene.room is not None:
        for told in descriptions:
            check_room_text(scene, told)
    texts = [told.text for told in descriptions]
    found = [sentence for text in texts for sentence in split_sentences(text)]
    for sentence in found:
        words = sentence.lower().rstrip(".").split()
        assert sentence[0].isupper() and sentence.endswith(".") and "  " not in sentence, sentence
        assert all(a != b for a, b in zip(words, words[1:], strict=False)), (
            f"seed {scene.seed}: word repeated: {sentence}"
        )
    return found


# -- counts: the summary level's claims, counted again from the scene -------------------------

#: The fixed label a chosen side or direction is measured by.
CHOSEN_LABEL = {
    "left": "NextToLeft",
    "right": "NextToRight",
    "front": "NextToFront",
    "behind": "NextToBehind",
    "north": "NextToNorth",
    "east": "NextToEast",
    "south": "NextToSouth",
    "west": "NextToWest",
}


def number_words(count: int) -> str:
    # inflect itself, not the describer's wrapper; imported here, after the describer
    # has loaded it without typeguard's instrumentation (1.5 s at import otherwise).
    import inflect

    return inflect.engine().number_to_words(count)


def quantifier_holds(word: str, count: int, total: int, *, exact: bool) -> bool:
    """Whether ``word`` is true of ``count`` of ``total``: "all" every one, "most" more than
    half, "some" at least two, "one" exactly one. An exact count (what groups hold) must
    also not fit a stronger word; a measured one is a lower bound of what the text knows."""
    if word == "all":
        return count == total
    if word == "most":
        return 2 * count > total and (count < total or not exact)
    if word == "some":
        return count >= 2 and (2 * count <= total or not exact)
    if word == "one":
        return count == 1
    return False


#: The last scene measured, with its graph as plain data and its poses: a long text's
#: claims are measured one by one against the same scene.
_LAST_MEASURED: list = []


def laid_out_data(scene: Scene) -> tuple[dict, dict, dict]:
    """The scene's graph as plain data (``SceneGraph.to_dict``), its poses and its paths,
    made once per scene (the scene is not changed while it is checked)."""
    if not _LAST_MEASURED or _LAST_MEASURED[0] is not scene:
        poses, paths = scene_layout(scene)
        _LAST_MEASURED[:] = [scene, scene.graph().to_dict(), poses, paths]
    _, data, poses, paths = _LAST_MEASURED
    return data, poses, paths


def measured_many(
    scene: Scene, triples: list[tuple[str, str, str]]
) -> dict[tuple[str, str, str], bool]:
    """Each (source, label, target) measured at the scene's poses by the layout's own code, in one pass."""
    if not triples:
        return {}
    data, poses, paths = laid_out_data(scene)
    data = {
        **data,
        "edges": [{"source": a, "target": b, "label": label} for a, label, b in triples],
    }
    relations = measure_layout(SceneGraph.from_dict(data), poses, paths).relations
    # Read back by name: the graph lists its edges source by source, in node order.
    verdicts = {(r.source, r.label, r.target): bool(r.satisfied) for r in relations}
    return {triple: verdicts[triple] for triple in triples}


def check_claims(scene: Scene, description: Description) -> None:
    """Every count a sentence claims ("Most of the thirty-eight homes have a flowerpot.")
    is counted again from the scene alone: the cohort is every thing of that noun and
    parent and the sentence gives its size; what groups hold is counted member by member;
    a relation is measured between every pair that could make it true."""
    things = {t.id: t for t in [*scene.objects, *scene.paths]}
    members_of: dict[str, list] = {}
    for thing in things.values():
        members_of.setdefault(thing.parent, []).append(thing)
    for sentence in description.sentences:
        for claim in sentence.claims:
            first = things[claim.members[0]]
            cohort = [
                t.id for t in things.values() if t.noun == first.noun and t.parent == first.parent
            ]
            assert sorted(cohort) == sorted(claim.members), sentence.text
            size = f"{number_words(len(cohort))} {plural_of(first.noun, first.plural)}"
            said = (
                f"all {size}" if claim.quantifier == "all" else f"{claim.quantifier} of the {size}"
            )
            assert said in sentence.text.lower(), f"{said!r} not in {sentence.text!r}"
            if claim.kind == "has":

                def holds(group, items=claim.items):
                    nouns = [m.noun for m in members_of.get(group, [])]
                    return all(nouns.count(noun) == number for noun, number in items)

                count = sum(holds(g) for g in cohort)
                assert quantifier_holds(claim.quantifier, count, len(cohort), exact=True), (
                    f"seed {scene.seed}: {count} of {len(cohort)}: {sentence.text!r}"
                )
                continue
            label = (
                CHOSEN_LABEL.get(claim.chosen, claim.label)
                if claim.label.startswith("NextToChoose")
                else claim.label
            )
            pairs: dict[str, list[tuple[str, str, str]]] = {}
            for member in cohort:
                if claim.kind == "is":
                    sources = [member]
                    targets = [
                        t.id
                        for t in things.values()
                        if t.noun == claim.target_noun and t.id != member
                    ]
                else:
                    inside = members_of.get(member, [])
                    sources = [t.id for t in inside if t.noun == claim.subject_noun]
                    targets = [t.id for t in inside if t.noun == claim.target_noun]
                pairs[member] = [(a, label, b) for a in sources for b in targets if a != b]
            verdicts = measured_many(scene, [p for found in pairs.values() for p in found])
            count = sum(any(verdicts[p] for p in found) for found in pairs.values())
            assert quantifier_holds(claim.quantifier, count, len(cohort), exact=False), (
                f"seed {scene.seed}: measured {count} of {len(cohort)}: {sentence.text!r}"
            )
            for noun in (claim.subject_noun, claim.target_noun):
                assert noun in sentence.text, sentence.text


# -- ordinals: a reader meets "the first" before "the second" ---------------------------------

ORDINAL_WORDS = [
    "first",
    "second",
    "third",
    "fourth",
    "fifth",
    "sixth",
    "seventh",
    "eighth",
    "ninth",
    "tenth",
    "eleventh",
    "twelfth",
    "thirteenth",
    "fourteenth",
    "fifteenth",
    "sixteenth",
    "seventeenth",
    "eighteenth",
    "nineteenth",
    "twentieth",
]
INDEFINITE = ("a ", "an ", "another ")


def is_kind_of(noun: str, general: str) -> bool:
    """The reader's own test: a "white desk" is a desk, an "armchair" a chair, a "sack of flour" no flour."""
    return noun == general or (" of " not in general and noun.split(" of ")[0].endswith(general))


def check_ordinals(scene: Scene, description: Description) -> None:
    """Every "the k-th N" counts what an N covers (its noun, or a kind of it: a "white desk"
    is a desk) among its siblings (for a noun nested in itself, in the whole scene) that
    the text named before it, on its own or in a set ("two of the pine trees"), and
    always gives the same k. A set's members count together where the set was named,
    taking its places in the order the text singles them out later: after "two of the
    pine trees" and "the third pine tree", the first of the two singled out is "the
    first pine tree"; a set said to be "other" than what the rest of its sentence names
    comes after that ("The two other desks face the same way as the first desk.").
    Every "the other N" comes after every other thing it could mean was named, on its
    own or in a set."""
    things = {o.id: o for o in [*scene.objects, *scene.paths]}
    parent = {i: (t.parent if t.parent in things else None) for i, t in things.items()}
    nested = {
        t.noun
        for t in things.values()
        if any(things[a].noun == t.noun for a in ancestors(t.id, parent))
    }
    named: list[
        tuple[str, ...]
    ] = []  # a thing named on its own, or a set's new members, in reading order
    singled: list[str] = []  # things named on their own, in reading order
    told: dict[str, int] = {}
    for mention in reading_order(
        description, lambda i: (things[i].noun, parent[i]) if i in things else i
    ):
        words = description.text[mention.start : mention.end]
        if words.lower().startswith(INDEFINITE) or not set(mention.entities) <= set(things):
            continue  # a door or a window: named by its place in the room, never by an ordinal
        if len(mention.entities) > 1:
            if names_a_set(words, len(mention.entities)) and not inside_another(
                mention, description
            ):
                new = tuple(i for i in mention.entities if not any(i in before for before in named))
                named += [new] if new else []
            continue
        (entity,) = mention.entities
        noun = things[entity].noun

        def covered(i: str, noun=noun, entity=entity) -> bool:
            return (
                i != entity
                and is_kind_of(things[i].noun, noun)
                and (noun in nested or parent[i] == parent[entity])
            )

        at = next((k for k, before in enumerate(named) if entity in before), len(named))
        match = re.match(r"[Tt]he (\w+) ", words)
        if match and match.group(1) in ORDINAL_WORDS:
            k = ORDINAL_WORDS.index(match.group(1)) + 1
            assert words[match.end() :].startswith(noun), words
            before = sum(covered(i) for earlier in named[:at] for i in earlier)
            within = sum(
                covered(i) for i in dict.fromkeys(singled) if at < len(named) and i in named[at]
            )
            expected = told.setdefault(entity, before + within + 1)
            assert k == expected, (
                f"seed {scene.seed}: {words!r} is the {expected}th named: {description.text}"
            )
        elif words.lower().startswith(f"the other {noun}"):
            unnamed = [
                i for i in things if covered(i) and not any(i in earlier for earlier in named)
            ]
            assert not unnamed, (
                f"seed {scene.seed}: {words!r} before {unnamed} were named: {description.text}"
            )
        singled.append(entity)
        named += [] if at < len(named) else [(entity,)]


def reading_order(description: Description, cohort_of) -> list:
    """The mentions in the order a reader counts them: the order they start in, but a set
    said to be "other" ("the two other desks") after what of its cohort (``cohort_of``:
    an id -> its noun and parent) the rest of its sentence names: it is other than those."""
    found, offset = [], 0
    for sentence in description.sentences:
        end = offset + len(sentence.text)
        here = [m for m in description.mentions if offset <= m.start < end]
        place = {id(m): float(k) for k, m in enumerate(here)}
        for k, mention in enumerate(here):
            words = description.text[mention.start : mention.end].lower()
            if (
                len(mention.entities) > 1
                and " other " in f" {words}"
                and names_a_set(words, len(mention.entities))
            ):
                cohort = {cohort_of(i) for i in mention.entities}
                for later in here[k + 1 :]:
                    if len(later.entities) == 1 and cohort_of(later.entities[0]) in cohort:
                        place[id(later)] = k - 0.5
        found += sorted(here, key=lambda m: place[id(m)])
        offset = end + 1  # the space joining sentences
    return found


def names_a_set(words: str, size: int) -> bool:
    """Whether a phrase names known things together: "both pallets", "the three market
    stands", "two of the pine trees", "(the) two other desks"; not "two more desks" or
    "three desks" (new ones) or "most of the homes"."""
    count = number_words(size)
    sets = ["both"] if size == 2 else []
    sets += [f"the {count}", f"the {count} other", f"{count} of the", f"{count} other"]
    return any(words.lower().startswith(f"{words_before} ") for words_before in sets)


def inside_another(mention, description: Description) -> bool:
    """Whether a mention is part of a larger one ("the five homes" in "most of the five homes")."""
    return any(
        other.start <= mention.start
        and mention.end <= other.end
        and (other.start, other.end) != (mention.start, mention.end)
        for other in description.mentions
    )


def ancestors(entity_id: str, parent: dict) -> list[str]:
    found, up = [], parent.get(entity_id)
    while up is not None:
        found.append(up)
        up = parent.get(up)
    return found


# -- rooms: names read back from the geometry, relations measured against what they name ---

#: Unit vectors (x, z) of the eight compass words (north is -Z, east +X).
COMPASS8 = {
    **COMPASS,
    "north-east": (math.sqrt(0.5), -math.sqrt(0.5)),
    "south-east": (math.sqrt(0.5), math.sqrt(0.5)),
    "south-west": (-math.sqrt(0.5), math.sqrt(0.5)),
    "north-west": (-math.sqrt(0.5), -math.sqrt(0.5)),
}
ORDINALS = {"first": 0, "second": 1, "third": 2, "fourth": 3, "fifth": 4, "sixth": 5}
COUNTS = {"a": 1, "an": 1, "one": 1, "two": 2, "three": 3, "four": 4, "five": 5, "six": 6}
ROOM_WORDS = {"wall", "walls", "window", "windows", "door", "doors", "corner", "corners"}
#: What a wall label's words name, by its placement (the reader's own table).
NAMED_BY_PLACEMENT = {
    "against": "wall",
    "corner": "corner",
    "under_window": "window",
    "beside_window": "window",
}


@dataclass
class Phrase:
    """A name of room parts in a sentence: its kind, the parts that fit it, words[start:end]."""

    kind: str  # wall, door, window or corner
    parts: list  # wall and opening ids; a corner is (wall ending there, wall starting there)
    start: int
    end: int


class RoomReader:
    """Reads the names of a room's parts as a reader of the text would, from the geometry.

    A name is read by its words alone ("the outer east wall": of the walls whose inner
    face looks west, the one furthest east), never by asking the describer; every part
    that fits is returned, so an ambiguous name shows as more than one.
    """

    def __init__(self, room: Room) -> None:
        self.room = room
        self.corners = {}  # (wall ending there, wall starting there) -> (point, compass word)
        for index, after in enumerate(room.walls):
            before = room.walls[index - 1]
            if room.convex_corner(before, after):
                out = (-(before.normal[0] + after.normal[0]), -(before.normal[1] + after.normal[1]))
                self.corners[(before.id, after.id)] = (after.start, compass_word(*out))

    @property
    def l_shaped(self) -> bool:
        return len(self.room.walls) == 6 and len(self.corners) == 5

    def phrases(self, words: list[str]) -> list[Phrase]:
        """The names of room parts in a sentence, left to right (the longest at each place)."""
        found, index = [], 0
        while index < len(words):
            phrase = self.phrase(words, index)
            found += [phrase] if phrase else []
            index = phrase.end if phrase else index + 1
        return found

    def phrase(self, words: list[str], i: int) -> Phrase | None:
        for read in (self.corner, self.opening, self.wall):
            phrase = read(words, i)
            if phrase is not None:
                return phrase
        return None

    # -- "the north wall", "the longer north wall", "one of the north walls"

    def wall(self, words: list[str], i: int) -> Phrase | None:
        ahead = words[i : i + 5]
        if ahead[:3] == ["one", "of", "the"] and len(ahead) == 5 and ahead[4] == "walls":
            return Phrase("wall", [w.id for w in self.room.walls if w.side == ahead[3]], i, i + 5)
        if ahead[:1] != ["the"]:
            return None
        if len(ahead) >= 3 and ahead[1] in COMPASS8 and ahead[2] == "wall":
            return Phrase("wall", [w.id for w in self.room.walls if w.side == ahead[1]], i, i + 3)
        if len(ahead) >= 4 and ahead[2] in COMPASS8 and ahead[3] == "wall":
            walls = [w for w in self.room.walls if w.side == ahead[2]]
            return Phrase("wall", self._wall_by(ahead[1], walls, ahead[2]), i, i + 4)
        return None

    def _wall_by(self, modifier: str, walls: list, side: str) -> list[str]:
        if modifier in ("longer", "shorter", "longest", "shortest"):
            if (modifier in ("longer", "shorter")) != (len(walls) == 2):
                return [w.id for w in walls]  # "longer" of three, "longest" of two: not understood
            sign = 1.0 if modifier.startswith("long") else -1.0
            return extreme(walls, lambda w: sign * w.length)
        if modifier in ("outer", "outermost", "inner", "innermost"):
            sign = 1.0 if modifier.startswith("outer") else -1.0
            return extreme(walls, lambda w: sign * dot(midpoint(w), COMPASS8[side]))
        direction = direction_of_adjective(modifier)
        return extreme(walls, lambda w: dot(midpoint(w), COMPASS8[direction])) if direction else []

    # -- "the window", "the north window", "the window in W", "the western window in W",
    #    "the second window from the west in W"

    def opening(self, words: list[str], i: int) -> Phrase | None:
        if words[i] != "the":
            return None
        for j in (i + 1, i + 2):  # "the window" or one word before the noun
            if j < len(words) and words[j] in ("door", "window"):
                break
        else:
            return None
        kind, modifier, after = words[j], words[i + 1 : j], words[j + 1 :]
        alike = [o for o in self.room.openings if o.kind == kind]
        if modifier and modifier[0] in ORDINALS:  # "the second window from the west in W"
            if (
                after[:2] != ["from", "the"]
                or after[2:3] == []
                or after[2] not in COMPASS8
                or after[3:4] != ["in"]
            ):
                return None
            wall = self.wall(words, j + 5)
            if wall is None or len(wall.parts) != 1:
                return None
            from_end = [o for o in alike if o.wall == wall.parts[0]]
            from_end.sort(key=lambda o: -dot(o.center, COMPASS8[after[2]]))
            index = ORDINALS[modifier[0]]
            return Phrase(kind, [from_end[index].id] if index < len(from_end) else [], i, wall.end)
        if after[:1] == ["in"]:  # "the window in W", "the western window in W"
            wall = self.wall(words, j + 2)
            if wall is None:
                return None
            on_wall = [o for o in alike if len(wall.parts) == 1 and o.wall == wall.parts[0]]
            if not modifier:
                return Phrase(kind, [o.id for o in on_wall], i, wall.end)
            direction = direction_of_adjective(modifier[0])
            parts = (
                extreme(on_wall, lambda o: dot(o.center, COMPASS8[direction]))
                if direction and on_wall
                else []
            )
            return Phrase(kind, parts, i, wall.end)
        if not modifier:  # "the window"
            return Phrase(kind, [o.id for o in alike], i, j + 1)
        if modifier[0] in COMPASS8:  # "the north window"
            return Phrase(
                kind, [o.id for o in alike if self.room.part(o.wall).side == modifier[0]], i, j + 1
            )
        return None

    # -- "the corner by the door", "the north-east corner", "the north-east corner of W"

    def corner(self, words: list[str], i: int) -> Phrase | None:
        if words[i : i + 3] == ["the", "corner", "by"]:
            door = self.opening(words, i + 3)
            if door is None or door.kind != "door" or len(door.parts) != 1:
                return Phrase("corner", [], i, door.end if door else i + 3)
            opening = self.room.part(door.parts[0])
            near = [
                key
                for key, (point, _) in self.corners.items()
                if opening_distance(self.room, opening, point) <= DOOR_NEAR_CORNER
            ]
            return Phrase("corner", near, i, door.end)
        if (
            words[i] == "the"
            and words[i + 1 : i + 2]
            and words[i + 1] in COMPASS8
            and words[i + 2 : i + 3] == ["corner"]
        ):
            named = [key for key, (_, side) in self.corners.items() if side == words[i + 1]]
            wall = self.wall(words, i + 4) if words[i + 3 : i + 4] == ["of"] else None
            if wall is None:
                return Phrase("corner", named, i, i + 3)
            named = [key for key in named if len(wall.parts) == 1 and wall.parts[0] in key]
            return Phrase("corner", named, i, wall.end)
        return None


def midpoint(wall) -> tuple[float, float]:
    return (wall.start[0] + wall.end[0]) / 2.0, (wall.start[1] + wall.end[1]) / 2.0


def direction_of_adjective(word: str) -> str | None:
    """ "western" or "westernmost" -> "west"."""
    for direction in COMPASS8:
        if word in (direction + "ern", direction + "ernmost"):
            return direction
    return None


def extreme(items: list, score) -> list[str]:
    """The item that scores highest (on a tie all the tied ones, so the name is ambiguous)."""
    best = max(score(item) for item in items)
    return [item.id for item in items if score(item) > best - 1e-6]


def dot(point, direction) -> float:
    return point[0] * direction[0] + point[1] * direction[1]


def opening_distance(room: Room, opening, point) -> float:
    """Distance from a point to the stretch of wall an opening fills."""
    wall = room.part(opening.wall)
    a = wall.to_world(opening.offset - opening.width / 2.0, 0.0)
    b = wall.to_world(opening.offset + opening.width / 2.0, 0.0)
    dx, dz = b[0] - a[0], b[1] - a[1]
    t = max(0.0, min(1.0, ((point[0] - a[0]) * dx + (point[1] - a[1]) * dz) / (dx * dx + dz * dz)))
    return math.hypot(point[0] - a[0] - t * dx, point[1] - a[1] - t * dz)


def against_what(scene: Scene, source: str, label: str, kind: str, part) -> list[tuple]:
    """The (source, label, target) relations ``holds_against`` reads for a part a
    sentence names: the part itself, or for a corner both of its walls."""
    if kind != "corner":
        return [(source, label, part)]
    return [(source, label, wall_id) for wall_id in part]


def holds_against(
    scene: Scene, source: str, label: str, kind: str, part, verdicts: dict[tuple, bool]
) -> bool:
    """The relation measured against the part a sentence names (``verdicts``: each
    relation of ``against_what`` measured at the scene's poses by the layout's own
    measures and thresholds). A corner: the object stands in a corner of one of its
    walls (the label measured on that wall) with a side against the other (within the
    layout's ``WALL_TOLERANCE``)."""
    if kind != "corner":
        return verdicts[(source, label, part)]
    thing = scene.object(source)
    rect = make_rect(thing.position[0], thing.position[2], thing.size[0], thing.size[2], thing.yaw)
    for wall_id, other_id in (part, part[::-1]):
        other = scene.room.part(other_id)
        side_gap = polyline_rects_distance([list(other.start), list(other.end)], [rect])
        if side_gap <= WALL_TOLERANCE and verdicts[(source, label, wall_id)]:
            return True
    return False


def check_room_text(scene: Scene, description: Description) -> None:
    """Every name of a room part picks out one part; every relation to the room holds
    against the part its sentence names; the room sentence counts the openings right.
    The relations are measured in one pass, once every sentence is read."""
    reader = RoomReader(scene.room)
    parts = {w.id: "wall" for w in scene.room.walls} | {o.id: o.kind for o in scene.room.openings}
    object_words = {word for o in scene.objects for word in o.noun.lower().split()}
    claims = []  # (source, label, target, kind, the parts named, the sentence)
    for sentence in description.sentences:
        words = sentence.text.lower().rstrip(".").replace(",", " ,").split()
        if re.match(r"The (L-shaped )?room ", sentence.text):
            check_room_sentence(reader, sentence.text)
            continue
        phrases = reader.phrases(words)
        covered = {k for phrase in phrases for k in range(phrase.start, phrase.end)}
        loose = [
            w
            for k, w in enumerate(words)
            if w in ROOM_WORDS and k not in covered and w not in object_words
        ]
        assert not loose, (
            f"seed {scene.seed}: {loose} read as no part of the room: {sentence.text!r}"
        )
        for phrase in phrases:
            assert len(phrase.parts) == 1, (
                f"seed {scene.seed}: names {phrase.parts}: {sentence.text!r}"
            )
        for source, label, target in sentence.facts:
            if target != ROOM_NODE and target not in parts:
                continue
            spec = RELATIONS[label]
            kind = NAMED_BY_PLACEMENT[spec.wall] if spec.family == "wall" else parts[target]
            named = [
                p.parts[0]
                for p in phrases
                if p.kind == kind or {p.kind, kind} == {"window", "door"}
            ]
            claims.append((source, label, target, kind, named, sentence.text))
    wanted = {
        triple
        for source, label, _, kind, named, _ in claims
        for part in named
        for triple in against_what(scene, source, label, kind, part)
    }
    verdicts = measured_many(scene, sorted(wanted))
    for source, label, target, kind, named, text in claims:
        assert any(holds_against(scene, source, label, kind, part, verdicts) for part in named), (
            f"seed {scene.seed}: {(source, label, target)} does not hold of what {text!r} names"
        )


def check_room_sentence(reader: RoomReader, text: str) -> None:
    """ "The L-shaped room has a door in the south wall and two windows in the north wall.":
    the shape is the room's, and each wall holds as many doors and windows as it says,
    all of them told."""
    match = re.fullmatch(r"The (L-shaped )?room (?:has (.+)|is (L-shaped))\.", text)
    assert match, f"not a room sentence: {text!r}"
    if match.group(1) or match.group(3):
        assert reader.l_shaped, f"not L-shaped: {text!r}"
    if match.group(2) is None:
        return
    counted = {"door": 0, "window": 0}
    for item in re.split(r", | and ", match.group(2)):
        number, noun, preposition, *rest = item.split(" ")
        kind = noun.removesuffix("s")
        wall = reader.wall(rest, 0)
        assert preposition == "in" and wall is not None and wall.end == len(rest) and wall.parts, (
            item
        )
        found = [len([o for o in reader.room.openings_on(w) if o.kind == kind]) for w in wall.parts]
        # "one of the north walls" need only be true of one of them
        assert found == [COUNTS[number]] or (len(found) > 1 and COUNTS[number] in found), item
        counted[kind] += COUNTS[number]
    assert counted == {k: len([o for o in reader.room.openings if o.kind == k]) for k in counted}, (
        text
    )


def laid_out(rules_name: str, seed: int) -> Scene:
    graph = expand(load_rules(rules_name), seed)
    return assemble_scene(graph, layout_scene(graph, seed), rules=rules_name, seed=seed)


def check_rule_set(rules_name: str, seeds: range) -> None:
    sentences = [s for seed in seeds for s in check_true_and_complete(laid_out(rules_name, seed))]
    assert ungrammatical(sentences) == []


@pytest.mark.parametrize(
    ("rules_name", "seeds"),
    # The bedroom's twenty seeds in two halves, so that two workers can share them.
    [
        ("village", range(2)),
        ("desk", range(20)),
        ("bedroom", range(10)),
        ("bedroom", range(10, 20)),
    ],
)
@pytest.mark.slow
def test_shipped_rule_sets_are_described_truly(rules_name, seeds):
    check_rule_set(rules_name, seeds)


#: Every other shipped rule set (the rooms: study, kitchen, ...) gets a few seeds, so each
#: room the package ships is read back true and parsed.
OTHER_RULE_SETS = [
    name for name in shipped_rule_sets() if name not in ("village", "desk", "bedroom", "city")
]
# The city is left out: its full text of some 14,000 words names "the one hundred and
# first home", which the link grammar cannot parse, and checking 1,300 sentences takes
# minutes; its summary's counted networks are checked in test_describer_networks.


@pytest.mark.slow
@pytest.mark.parametrize("rules_name", OTHER_RULE_SETS)
def test_other_shipped_rule_sets_are_described_truly(rules_name):
    check_rule_set(rules_name, range(2))


@pytest.mark.slow
@pytest.mark.skipif(
    not os.environ.get("SCENEWRIGHT_SLOW"), reason="long sweep: set SCENEWRIGHT_SLOW=1"
)
@pytest.mark.parametrize("rules_name", ["village", "desk", "bedroom"])
def test_shipped_rule_sets_over_many_seeds(rules_name):
    check_rule_set(rules_name, range(200))


def test_golden_descriptions_are_grammatical():
    sentences = [s for path in sorted(GOLDEN.glob("*.txt")) for s in path.read_text().splitlines()]
    assert sentences
    assert ungrammatical(sentences) == []


def test_the_grammar_check_can_fail():
    assert ungrammatical(
        ["The sign is besides of the table.", "The sign is next to the table."]
    ) == ["The sign is besides of the table."]
