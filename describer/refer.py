"""Referring expressions: which words name an entity at this point of the text.

A reader must always be able to tell which thing a phrase means. First mentions are
indefinite ("a table", "three pine trees"); later ones definite, choosing the first
form that is unambiguous here:

1. "it": the entity was the last one named in the previous sentence and the only
   singular one named there (or, inside one sentence, the only singular thing named
   besides the subject: "The chair is in front of the desk and faces it.");
2. "the oak tree" when it is the scene's only oak tree;
3. "this table" when the previous sentence named it and no other table, and the
   phrase is not one of a list;
4. inside a group's paragraph, a member of that group by its place in its cohort
   ("the sign", "the second sack of flour") while no same-noun thing from elsewhere
   has been named in the paragraph and none stands at the top level;
5. otherwise its place in its cohort ("the first road"; "the other tower" for the
   second of two right after the first was named, and "the other pine tree" for the
   last of a cohort whose others were named, some only in a set), followed by "of" and
   its group ("the sign of the third market stand", "the wagon of grain at the mill",
   "the house on its own" for a top-level one) when a namesake from elsewhere could be
   meant. Ordinals count after what sets named before ("two of the pine trees", then
   "the third pine tree"), so one never suggests a member of such a set it is not.

Sets of entities (aggregated subjects) are named per cohort: "the three market
stands", "both pallets", "four of the street lamps" ("four other street lamps" when
others of the cohort, and none of these, were named before).

A room's walls, doors, windows and corners always take the name that sets them apart
in the room (``rooms``: "the north wall", "the window in the longer north wall", "the
corner by the door"), never "it" or "this". They are still noted as things named, so an
entity named beside one is not taken for the only thing "it" could mean.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from .english import counted, number_word, ordinal_word
from .grounding import Marks
from .world import World

#: How "the scene" itself is tracked as a mention ("The scene consists of ...").
SCENE = "<scene>"
#: How a room, and each part of it, is tracked as a mention: a key no noun can be, so
#: "this" and "the other" never count a wall as a namesake of an object.
ROOM_PART = "<room>"
#: The parts of a room that are drawn as things of their own, and so grounded.
SEEN_PARTS = ("door", "window")


@dataclass
class _Mention:
    ids: tuple[str, ...]
    noun: str
    plural: bool
    embedded: bool = (
        False  # inside another phrase: "the farmstead" in "the cottage of the farmstead"
    )


@dataclass
class Discourse:
    """The state of the text so far, as referring expressions need it."""

    world: World
    focus: str | None = None  # the group whose paragraph this is; None: the scene
    introduced: set[str] = field(default_factory=set)
    previous: list[_Mention] = field(default_factory=list)
    current: list[_Mention] = field(default_factory=list)
    last_of_noun: dict[str, tuple[str, ...]] = field(default_factory=dict)
    paragraph_nouns: dict[str, set[str]] = field(default_factory=dict)
    named_in_paragraph: set[str] = field(default_factory=set)  # known entities named again
    #: Ordinals as the text has given them: family key -> ids in the order the text first
    #: named each by its place ("the first road" is the first road the text singled out),
    #: a set's members together where the set was named ("two of the pine trees").
    ranks: dict[tuple[str, ...], list[str]] = field(default_factory=dict)
    #: Entities named only in a set so far -> that set's members not named before it: they
    #: hold its places in ``ranks``, in the order they are singled out later.
    unsettled: dict[str, frozenset[str]] = field(default_factory=dict)
    sentence_subject: tuple[str, ...] = ()
    #: The phrases of the sentence being made and what each names (``grounding``).
    marks: Marks = field(default_factory=Marks)

    # -- structure --------------------------------------------------------------

    def start_paragraph(self, owner: str | None) -> None:
        self.focus = owner
        self.paragraph_nouns = {}
        self.named_in_paragraph = set()

    def start_sentence(self) -> None:
        self.previous = self.current
        self.current = []
        self.sentence_subject = ()
        self.marks.clear()

    def mark_subject(self, ids: tuple[str, ...]) -> None:
        """Record the current sentence's subject (a pronoun never refers back to it)."""
        self.sentence_subject = ids

    # -- naming -------------------------------------------------------------------

    def scene(self) -> str:
        self._note((SCENE,), SCENE, plural=False)
        return "the scene"

    def room(self) -> str:
        """The room itself: "the room"."""
        self._note((ROOM_PART,), ROOM_PART, plural=False)
        return "the room"

    def name_place(self, place_id: str) -> str:
        """A part of the room by the name that sets it apart (``rooms``)."""
        self._note((place_id,), ROOM_PART, plural=False)
        room = self.world.room
        assert room is not None  # a place is a part of the room
        name = room.name(place_id)
        assert name is not None  # only a part that has a name is a place (``RoomView.place``)
        # A door or a window is drawn, so its name is grounded; a wall or a corner is not.
        return self.marks.mark(name, (place_id,)) if room.kind(place_id) in SEEN_PARTS else name

    def note_place(self, place_ids: tuple[str, ...]) -> None:
        """Record parts of the room named by other means (the room sentence's "two windows")."""
        self._note(place_ids, ROOM_PART, plural=len(place_ids) > 1)

    def introduce(self, ids: tuple[str, ...]) -> str:
        """An indefinite phrase for new entities of one noun: "a table", "three books".

        When others of the cohort are already known, the new ones are "another flowerpot"
        or "two more flowerpots", so they cannot be taken for the known ones.
        """
        entity = self.world[ids[0]]
        known = any(i in self.introduced for i in self.world.cohort(ids[0]))
        self.introduced.update(ids)
        self._note(ids, entity.noun, plural=len(ids) > 1)
        if not known:
            phrase = counted(len(ids), entity.noun, entity.plural)
        elif len(ids) == 1:
            phrase = f"another {entity.noun}"
        else:
            phrase = f"{number_word(len(ids))} more {entity.plural}"
        return self.marks.mark(phrase, ids)

    def name(self, entity_id: str, *, pronoun: bool = True, demonstrative: bool = True) -> str:
        """A definite phrase for one known entity.

        "it" only when ``pronoun`` is allowed here, "this table" only when
        ``demonstrative`` is: a phrase inside a list of others takes neither ("the
        street lamp, this wagon and the mill" reads as if the wagon were special).
        A part of the room is named as ``name_place`` names it.
        """
        if entity_id not in self.world:
            return self.name_place(entity_id)
        entity = self.world[entity_id]
        self.named_in_paragraph.add(entity_id)
        if pronoun and self._may_be_it(entity_id):
            self._rank(entity_id)
            self._note((entity_id,), entity.noun, plural=False)
            return self.marks.mark("it", (entity_id,))
        phrase, placed = self._definite(entity_id, demonstrative=demonstrative)
        self._rank(entity_id)  # "the white desk" counts among the desks too
        self._note((entity_id,), entity.noun, plural=False)
        return self.marks.mark(phrase if placed else self._placed(phrase, entity_id), (entity_id,))

    def name_set(self, ids: tuple[str, ...], alongside: tuple[str, ...] = ()) -> list[str]:
        """Phrases naming a set of known entities, one per cohort, in order.

        ``alongside``: what the rest of the sentence names ("the first desk" in "The two
        other desks face the same way as the first desk"), so a part of a cohort is
        "other" than those too.
        """
        by_cohort: dict[tuple[str, ...], list[str]] = {}
        for entity_id in ids:
            by_cohort.setdefault(self.world.cohort(entity_id), []).append(entity_id)
        alone = len(by_cohort) == 1
        # Parts of cohorts ("two of the sacks") lead, whole cohorts ("the two market
        # stands") close the list: "the two pallets and two of the sacks" reads as counting
        # on, and heavy phrases read best last. link-grammar parses only this order.
        chunks = sorted(by_cohort.items(), key=lambda chunk: _weight(len(chunk[1]), len(chunk[0])))
        phrases = []
        for cohort, chosen in chunks:
            if len(chosen) == 1:
                phrases.append(self.name(chosen[0], pronoun=alone, demonstrative=alone))
            else:
                phrases.append(self._name_part(cohort, tuple(chosen), alone, alongside))
        return phrases

    def rank_order(self) -> dict[str, int]:
        """Each entity the text has named by an ordinal -> its place in its family's order."""
        return {
            entity_id: k for ranked in self.ranks.values() for k, entity_id in enumerate(ranked)
        }

    # -- the rules ----------------------------------------------------------------

    def _may_be_it(self, entity_id: str) -> bool:
        if entity_id in self.sentence_subject:
            return False  # the subject itself would be "itself"
        subject = set(self.sentence_subject)
        # An owner inside a phrase ("the cottage of the farmstead") is no rival antecedent
        # there: "... of the cottage of the farmstead and at a right angle to it".
        named_here = [
            m.ids
            for m in self.current
            if not m.plural and not m.embedded and not set(m.ids) <= subject
        ]
        if named_here:
            return all(ids == (entity_id,) for ids in named_here)
        singular_before = {m.ids for m in self.previous if not m.plural}
        return (
            bool(self.previous)
            and self.previous[-1].ids == (entity_id,)
            and singular_before == {(entity_id,)}
        )

    def _definite(self, entity_id: str, *, demonstrative: bool) -> tuple[str, bool]:
        """The definite phrase, and whether it is clear without saying where the entity belongs."""
        entity = self.world[entity_id]
        namesakes = self.world.namesakes(entity_id)
        if len(namesakes) == 1:
            return f"the {entity.noun}", True
        named_before = [m.ids for m in self.previous if m.noun == entity.noun]
        if (
            demonstrative
            and self.last_of_noun.get(entity.noun) == (entity_id,)
            and named_before == [(entity_id,)]
        ):
            return f"this {entity.noun}", True
        if entity.noun in self.world.nested_nouns:
            # Counted across the scene: "the row of desks at the row of desks" tells nothing.
            return self._place_in_cohort(entity_id), True
        cohort = self.world.cohort(entity_id)
        clear = len(cohort) == len(namesakes) or self._clear_in_paragraph(entity_id)
        return self._place_in_cohort(entity_id), clear

    def _place_in_cohort(self, entity_id: str) -> str:
        """ "the sign", "the other tower" or "the third road".

        Ordinals count in the order the text first names each thing on its own (``_rank``),
        so a reader meets "the first road" before "the second". A noun counts what it
        covers among its siblings (``World.family``): "the second desk" is the second desk
        named, white ones included; "the second white desk" the second white one.
        """
        entity = self.world[entity_id]
        family = self.world.family(entity_id)
        if len(family) == 1 or (
            len(self.world.cohort(entity_id)) == 1 and entity.noun not in self.world.nested_nouns
        ):
            return f"the {entity.noun}"  # its noun alone sets it apart among its siblings
        new = entity_id not in self.ranks.get(family, ())
        ranked = self._rank(entity_id)
        # "the other" always means the later of two, said right after the first was named,
        # so it never flips between the two.
        others = [i for i in family if i != entity_id]
        if (
            len(family) == 2
            and ranked.index(entity_id) == 1
            and self.world[others[0]].noun == entity.noun
            and self.last_of_noun.get(entity.noun) == tuple(others)
        ):
            return f"the other {entity.noun}"
        if (
            self.world.family_noun(entity_id) != entity.noun
        ):  # "the second white desk": white ones only
            ranked = [i for i in ranked if self.world[i].noun == entity.noun]
            family = tuple(i for i in family if self.world[i].noun == entity.noun)
        if new and len(ranked) == len(family) and any(i in self.unsettled for i in ranked):
            # The last one, every other named before and some only in a set ("two of the
            # pine trees"): an ordinal could be taken for one of the set, "the other" cannot.
            return f"the other {entity.noun}"
        return f"the {ordinal_word(ranked.index(entity_id) + 1)} {entity.noun}"

    def _rank(self, entity_id: str) -> list[str]:
        """Its family in the order the text has named them one by one, with it counted.

        One named before only in a set takes the first of that set's places not yet
        taken: after "two of the pine trees" and "the third pine tree", the first of
        the two singled out is "the first pine tree", the other "the second".
        """
        ranked = self.ranks.setdefault(self.world.family(entity_id), [])
        if entity_id not in ranked:
            ranked.append(entity_id)
        elif entity_id in self.unsettled:
            block = self.unsettled.pop(entity_id)
            first = min(ranked.index(i) for i in block if i in self.unsettled or i == entity_id)
            here = ranked.index(entity_id)
            ranked[first], ranked[here] = ranked[here], ranked[first]
        return ranked

    def _rank_set(self, cohort: tuple[str, ...], chosen: tuple[str, ...]) -> None:
        """Give the members of a set named together the next places of their family, to
        be taken in the order they are singled out (``_rank``)."""
        ranked = self.ranks.setdefault(self.world.family(chosen[0]), [])
        new = [i for i in cohort if i in chosen and i not in ranked]
        ranked.extend(new)
        self.unsettled.update(dict.fromkeys(new, frozenset(new)))

    def _clear_in_paragraph(self, entity_id: str) -> bool:
        """Whether naming by place in the cohort alone is clear here.

        A member of the paragraph's group is clear while no namesake from elsewhere has
        been named in the paragraph and none stands at the top level: a top-level entity
        is named bare in every paragraph ("the cottage"), so once one is known, a
        group's "the cottage" could mean it. A top-level entity is clear while no
        namesake belonging to a group has been introduced at all.
        """
        entity = self.world[entity_id]
        cohort = set(self.world.cohort(entity_id))
        others = [
            i for i in self.world.namesakes(entity_id) if i not in cohort and i in self.introduced
        ]
        if entity.parent is None:
            return not others
        if any(self.world[i].parent is None for i in others):
            return False
        return (
            entity.parent == self.focus and self.paragraph_nouns.get(entity.noun, set()) <= cohort
        )

    def _placed(self, phrase: str, entity_id: str, *, plural: bool = False) -> str:
        """The phrase with where the entity belongs: "the table of the third market stand",
        "the house on its own" for a top-level one.

        A noun with an "of" of its own is placed "at" its group ("the wagon of grain at
        the mill"): "the wagon of grain of the mill" stacks two "of"s.
        """
        entity = self.world[entity_id]
        if entity.parent is None:
            return f"{phrase} on their own" if plural else f"{phrase} on its own"
        preposition = "at" if " of " in entity.noun else "of"
        first = len(self.current)
        owner = self.name(entity.parent, pronoun=False)
        for mention in self.current[first:]:
            mention.embedded = True
        return f"{phrase} {preposition} {owner}"

    def _name_part(
        self,
        cohort: tuple[str, ...],
        chosen: tuple[str, ...],
        alone: bool,
        alongside: tuple[str, ...] = (),
    ) -> str:
        entity = self.world[chosen[0]]
        before: tuple[str, ...] = ()
        if len(chosen) == len(cohort):
            whole = len(chosen) == 2 and alone
            phrase = (
                f"both {entity.plural}"
                if whole
                else f"the {number_word(len(chosen))} {entity.plural}"
            )
        else:
            phrase, before = self._part_of_cohort(cohort, chosen, alongside)
        self.named_in_paragraph.update(chosen)
        for other in before:
            self._rank(other)  # "The two other desks face the same way as the first desk."
        self._rank_set(cohort, chosen)
        clear = len(cohort) == len(self.world.namesakes(chosen[0])) or self._clear_in_paragraph(
            chosen[0]
        )
        self._note(chosen, entity.noun, plural=True)
        return self.marks.mark(
            phrase if clear else self._placed(phrase, chosen[0], plural=True), chosen
        )

    def _part_of_cohort(
        self, cohort: tuple[str, ...], chosen: tuple[str, ...], alongside: tuple[str, ...]
    ) -> tuple[str, tuple[str, ...]]:
        """Some of a cohort: "two of the street lamps"; and what of the rest of the
        sentence the phrase counts before them.

        When others of the cohort were named in this paragraph or are named in the rest
        of the sentence (``alongside``) and these were not, the phrase says so, so a
        reader does not take them for those: "two other street lamps", or "the two other
        street lamps" when they are all the rest ("The two other desks face the same way
        as the first desk.", not "Two of the desks ..."). Those of the rest of the
        sentence then count before these: "the first desk" there, not "the other desk".
        """
        plural, count = self.world[chosen[0]].plural, number_word(len(chosen))
        besides = tuple(i for i in alongside if i in cohort)
        if besides and not set(besides) & set(chosen) and set(besides) | set(chosen) == set(cohort):
            return (
                f"the {count} other {plural}",
                besides,
            )  # the sentence names the rest of the cohort
        named = (self.named_in_paragraph | set(besides)) & set(cohort)
        if named and not named & set(chosen):
            if named == set(cohort) - set(chosen):
                return f"the {count} other {plural}", besides
            return f"{count} other {plural}", besides
        return f"{count} of the {plural}", ()

    def _note(self, ids: tuple[str, ...], noun: str, *, plural: bool) -> None:
        self.current.append(_Mention(ids, noun, plural))
        if noun not in (SCENE, ROOM_PART):
            self.last_of_noun[noun] = ids
            self.paragraph_nouns.setdefault(noun, set()).update(ids)


def _weight(chosen: int, cohort: int) -> int:
    """Where a cohort's phrase goes in a list: part of a cohort, then single ones, then whole ones."""
    if chosen == 1:
        return 1
    return 2 if chosen == cohort else 0
