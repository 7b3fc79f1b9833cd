"""Surface realisation: planned messages -> English sentences, through the templates.

Walks the plan in reading order, names every entity with the referring-expression
rules of ``refer.Discourse``, picks words from the lexicon, makes verbs agree and fills
the sentence templates. Each sentence comes out with the facts it states and the
mentions it makes (``grounding``: which characters name which entities).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from jinja2.sandbox import SandboxedEnvironment

from scenewright.core.scene import Fact

from .content_plan import (
    Clause,
    Introduction,
    Inventory,
    Item,
    Message,
    Network,
    RoomOutline,
    Section,
    Statement,
    facts_of,
)
from .english import (
    counted,
    join_list,
    number_word,
    plural_of,
    sentence_case,
    verb_agreeing,
    with_also,
    with_article,
    without_repeated_copula,
)
from .grounding import Mention
from .lexicon import Lexicon, place_phrases
from .paraphrase import Choices
from .refer import SCENE, Discourse
from .summary import Claim, Composition, Pattern, Quantified
from .templates import render
from .world import World

#: The label whose sides are the picture's when the realiser tells picture sides.
PICTURE_SIDE_LABEL = "NextToChooseSide"

#: Road networks alike (paths of the same nouns at junctions of one noun) are told as
#: one list item from this many on ("thirty-six streets meeting four at each of nine
#: intersections"); fewer are each their own ("four roads meeting at an intersection, three
#: more roads meeting at another intersection").
NETWORKS_COUNTED = 3


@dataclass(frozen=True)
class _Networks:
    """Road networks alike, told as one list item (``Realiser._networks_counted``)."""

    networks: tuple[Network, ...]


@dataclass(frozen=True)
class Sentence:
    """One sentence of the text, the facts it states, its mentions (spans into ``text``)
    and the counts it claims (``summary.Claim``: "Most of the thirty-eight homes ...")."""

    text: str
    facts: tuple[Fact, ...]
    mentions: tuple[Mention, ...] = ()
    claims: tuple[Claim, ...] = ()


class Realiser:
    """Realises the messages of one description, in order (the discourse state is its memory)."""

    def __init__(
        self,
        world: World,
        environment: SandboxedEnvironment,
        choices: Choices,
        *,
        picture_sides: bool = False,
    ) -> None:
        self.world = world
        #: Sides are the picture's: a side clause's targets are followed by "in the picture".
        self.picture_sides = picture_sides
        self.environment = environment
        self.choices = choices
        self.lexicon = Lexicon(choices)
        self.discourse = Discourse(world)

    # -- documents ------------------------------------------------------------------

    def sections(self, sections: list[Section]) -> list[Sentence]:
        sentences: list[Sentence] = []
        for section in sections:
            self.discourse.start_paragraph(section.owner)
            sentences += [self.message(m) for m in self._reading_order(section.messages)]
        return sentences

    def _reading_order(self, messages: tuple[Message, ...]) -> list[Message]:
        """Statements may come in any order (they introduce nothing); the rest keep theirs.

        A statement continued by "also" keeps its continuation right after it.
        """
        blocks: list[list[Message]] = []
        for message in messages:
            if isinstance(message, Statement) and message.also:
                blocks[-1].append(message)
            elif isinstance(message, Statement):
                blocks.append([message])
        # The summary level's counts: those of relations with the statements, then what
        # the groups of a big cohort hold and how their members stand.
        counts = [m for m in messages if isinstance(m, Quantified)]
        groups = [m for m in messages if isinstance(m, (Composition, Pattern))]
        others = [
            m for m in messages if not isinstance(m, (Statement, Quantified, Composition, Pattern))
        ]
        return (
            others + counts + [m for block in self.choices.shuffled(blocks) for m in block] + groups
        )

    def message(self, message: Message) -> Sentence:
        self.discourse.start_sentence()
        text = _REALISERS[type(message)](self, message)
        claims = (message.claim,) if isinstance(message, (Composition, Pattern, Quantified)) else ()
        return self._sentence(text, facts_of(message), claims)

    def caption(
        self,
        setting: str,
        items: tuple[Item, ...],
        setting_ids: tuple[str, ...] = (),
        *,
        picture: bool = False,
        unseen: bool = False,
    ) -> Sentence:
        """The short style's sentence: "A village with three roads meeting at an intersection, ...".

        ``setting_ids``: the group the setting word names ("A desk with ..."), if one;
        ``picture``: the caption is of a rendered picture; ``unseen``: that picture
        shows nothing of the scene well enough to name (the scene is not empty).
        """
        self.discourse.start_sentence()
        if setting_ids:
            setting = self.discourse.marks.mark(setting, setting_ids)
        phrases = [
            self._item(item) for item in self.choices.shuffled(self._networks_counted(items))
        ]
        text = render(
            self.environment,
            "caption.j2",
            setting=setting,
            link=self.lexicon.caption_link(),
            items=phrases,
            picture=picture,
            unseen=unseen,
        )
        return self._sentence(text, facts_of(Inventory(None, items)))

    def _sentence(self, marked: str, facts: list[Fact], claims: tuple[Claim, ...] = ()) -> Sentence:
        """The rendered sentence without its marks, capitalised, with its facts, mentions and claims."""
        text, mentions = self.discourse.marks.read(marked)
        return Sentence(sentence_case(text), tuple(facts), mentions, claims)

    # -- messages -------------------------------------------------------------------

    def _inventory(self, inventory: Inventory) -> str:
        if inventory.owner is None:
            owner = self.discourse.scene()
        else:
            owner = self.discourse.name(inventory.owner, pronoun=False)
        self.discourse.mark_subject((inventory.owner,) if inventory.owner else (SCENE,))
        verb = self.lexicon.composition()
        if inventory.link is not None:
            subject, target = inventory.items
            items = [
                render(
                    self.environment,
                    "linked_item.j2",
                    subject=self._item(subject),
                    place=self.lexicon.place(inventory.link.label, inventory.link.chosen),
                    target=self._item(target) + self._frame_words(inventory.link),
                )
            ]
        else:
            merged = self._networks_counted(inventory.items)
            items = [self._item(item) for item in self.choices.shuffled(merged)]
        return render(self.environment, "inventory.j2", owner=owner, verb=verb, items=items)

    def _networks_counted(self, items: tuple[Item, ...]) -> list[Item | _Networks]:
        """``items`` with the road networks alike (as many paths of the same nouns at
        junctions of one noun) told as one when there are at least ``NETWORKS_COUNTED``
        of them, at the first one's place: a city's nine intersections are "thirty-six
        streets meeting four at each of nine intersections", not nine list items."""
        alike: dict[tuple, list[Network]] = {}
        for item in items:
            if isinstance(item, Network):
                alike.setdefault(self._network_kind(item), []).append(item)
        merged: list[Item | _Networks] = []
        for item in items:
            if not isinstance(item, Network):
                merged.append(item)
                continue
            networks = alike[self._network_kind(item)]
            if len(networks) < NETWORKS_COUNTED:
                merged.append(item)
            elif networks[0] is item:
                merged.append(_Networks(tuple(networks)))
        return merged

    def _network_kind(self, network: Network) -> tuple:
        return (
            self.world[network.junction].noun,
            tuple(sorted(self.world[path].noun for path in network.paths)),
        )

    def _item(self, item: Item | _Networks) -> str:
        if isinstance(item, _Networks):
            streets = tuple(path for network in item.networks for path in network.paths)
            junctions = tuple(network.junction for network in item.networks)
            each = len(item.networks[0].paths)
            return (
                f"{self.discourse.introduce(streets)} meeting {number_word(each)} at each of "
                f"{self.discourse.introduce(junctions)}"
            )
        if isinstance(item, Network):
            by_noun: dict[str, tuple[str, ...]] = {}
            for path in item.paths:
                noun = self.world[path].noun
                by_noun[noun] = by_noun.get(noun, ()) + (path,)
            paths = [self.discourse.introduce(ids) for ids in by_noun.values()]
            junction = self.discourse.introduce((item.junction,))
            return render(
                self.environment,
                "network.j2",
                paths=paths,
                count=len(item.paths),
                junction=junction,
            )
        return self.discourse.introduce(item)

    def _room(self, outline: RoomOutline) -> str:
        """ "The room has a door in the south wall and two windows in the north wall."."""
        room = self.discourse.room()
        room_view = self.world.room
        assert room_view is not None  # an outline is planned for a room only
        self.discourse.mark_subject(())
        openings = []
        for kind, wall, ids in self.choices.shuffled(outline.openings):
            self.discourse.note_place(ids)
            what = self.discourse.marks.mark(counted(len(ids), kind, plural_of(kind)), ids)
            self.discourse.note_place((wall,))
            phrase = render(
                self.environment,
                "opening.j2",
                openings=what,
                wall=room_view.wall_phrase(wall),
            )
            openings.append(phrase)
        return render(
            self.environment, "room.j2", room=room, shape=outline.shape or "", openings=openings
        )

    def _introduction(self, introduction: Introduction) -> str:
        clause = introduction.clause
        subjects = introduction.subjects
        plural = len(subjects) > 1 or len(subjects[0]) > 1
        forms = ["plain"]
        if place_phrases(clause.label, clause.chosen):
            # "There is" agrees with its nearest noun, so it takes one noun only.
            forms += ["inverted", "existential"] if len(subjects) == 1 else ["inverted"]
        form = self.choices.pick(forms)
        if form == "inverted":  # "On top of this table are two books.": the target comes first
            place = self.lexicon.place(clause.label, clause.chosen)
            target = self._targets(clause)
            subject = join_list([self.discourse.introduce(unit) for unit in subjects])
            verb = verb_agreeing("is", plural)
        else:
            subject = join_list([self.discourse.introduce(unit) for unit in subjects])
            self.discourse.mark_subject(tuple(s for unit in subjects for s in unit))
            if form == "existential":
                place, verb = (
                    self.lexicon.place(clause.label, clause.chosen),
                    verb_agreeing("is", plural),
                )
            else:
                place, verb = (
                    "",
                    verb_agreeing(self.lexicon.relation(clause.label, clause.chosen), plural),
                )
            target = self._targets(clause)
        return render(
            self.environment,
            "introduction.j2",
            form=form,
            place=place,
            subject=subject,
            verb=verb,
            target=target,
        )

    def _statement(self, statement: Statement) -> str:
        targets = tuple(t for clause in statement.clauses for t in clause.targets)
        names = self.discourse.name_set(statement.subjects, alongside=targets)
        self.discourse.mark_subject(statement.subjects)
        plural = len(statement.subjects) > 1
        predicates = [
            f"{verb_agreeing(self._words(c), plural)} {self._targets(c)}{self._frame_words(c)}"
            for c in statement.clauses
        ]
        predicates = without_repeated_copula(predicates)
        if statement.also:
            predicates[0] = with_also(predicates[0])
        return render(
            self.environment, "statement.j2", subject=join_list(names), predicates=predicates
        )

    # -- the summary level's counts ("summary") --------------------------------------------

    def _counted_members(self, claim: Claim) -> str:
        """ "all thirty-eight homes", "most of the thirty-eight homes", "one of the four
        market stands": the members a claim counts, marked as the ones it holds for,
        around the whole cohort."""
        members = self.world[claim.members[0]]
        count = f"{number_word(len(claim.members))} {members.plural}"
        self.discourse.mark_subject(claim.holders)
        if claim.quantifier == "all":
            return self.discourse.marks.mark(f"all {count}", claim.members)
        cohort = self.discourse.marks.mark(f"the {count}", claim.members)
        return self.discourse.marks.mark(f"{claim.quantifier} of {cohort}", claim.holders)

    def _composition(self, composition: Composition) -> str:
        """ "All four market stands have a table and a sign."."""
        claim = composition.claim
        owner = self._counted_members(claim)
        items = [
            self.discourse.marks.mark(
                counted(number, noun, self._plural(claim, noun)), self._held(claim, noun)
            )
            for noun, number in claim.items
        ]
        verb = "has" if claim.quantifier == "one" else "have"
        return render(self.environment, "inventory.j2", owner=owner, verb=verb, items=items)

    def _plural(self, claim: Claim, noun: str) -> str:
        return next(
            m.plural for g in claim.members for m in self.world.members(g) if m.noun == noun
        )

    def _held(self, claim: Claim, noun: str) -> tuple[str, ...]:
        return tuple(m.id for g in claim.holders for m in self.world.members(g) if m.noun == noun)

    def _pattern(self, pattern: Pattern) -> str:
        """ "In most of the thirty-eight homes, the flowerpot is in front of the house."."""
        claim = pattern.claim
        groups = self._counted_members(claim)
        subjects = tuple(dict.fromkeys(s for s, _, _ in pattern.facts))
        subject = self._generic(claim.subject_noun, pattern.subject_definite, subjects)
        target = self._generic(claim.target_noun, pattern.target_definite, pattern.targets)
        verb = self.lexicon.relation(claim.label, claim.chosen)
        return render(
            self.environment,
            "pattern.j2",
            groups=groups,
            subject=subject,
            predicate=f"{verb} {target}",
        )

    def _generic(self, noun: str, definite: bool, ids: tuple[str, ...]) -> str:
        """ "the house" (one in each group) or "a bush", naming the ones the count reaches."""
        return self.discourse.marks.mark(f"the {noun}" if definite else with_article(noun), ids)

    def _quantified(self, quantified: Quantified) -> str:
        """ "Most of the twelve street lamps are next to a road."."""
        claim = quantified.claim
        subject = self._counted_members(claim)
        noun = claim.target_noun
        same = noun == self.world[claim.members[0]].noun
        target = self.discourse.marks.mark(
            f"another {noun}" if same else with_article(noun), quantified.targets
        )
        predicate = (
            f"{verb_agreeing(self.lexicon.relation(claim.label, claim.chosen), True)} {target}"
        )
        return render(self.environment, "statement.j2", subject=subject, predicates=[predicate])

    def _words(self, clause: Clause) -> str:
        # A clause's targets share their words (``plan.aggregate``), so the first one's
        # kind of room part, if it is one, stands for all.
        return self.lexicon.relation(
            clause.label, clause.chosen, self.world.place_kind(clause.targets[0])
        )

    def _frame_words(self, clause: Clause) -> str:
        """ " in the picture" after a side told as a picture shows it, else nothing."""
        return (
            " in the picture" if self.picture_sides and clause.label == PICTURE_SIDE_LABEL else ""
        )

    def _targets(self, clause: Clause) -> str:
        # Objects are named one by one: "next to two of the roads" would hide which.
        return join_list([self.discourse.name(t) for t in clause.targets])


#: How each kind of planned message becomes a sentence.
_REALISERS: dict[type, Callable[[Realiser, Any], str]] = {
    Inventory: Realiser._inventory,
    RoomOutline: Realiser._room,
    Introduction: Realiser._introduction,
    Statement: Realiser._statement,
    Composition: Realiser._composition,
    Pattern: Realiser._pattern,
    Quantified: Realiser._quantified,
}
