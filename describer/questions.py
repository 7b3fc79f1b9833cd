"""Questions about one rendered picture, in the style of CLEVR, each with its program and answer.

``picture_questions(facts, vocabulary, seed)`` asks, of the objects a picture shows
well enough (``programs.PictureFacts``, the same ``PictureView.seen`` thresholds as
the captions), questions of each registered family (``FAMILIES``):

- ``exist``: "Is there a tent?" / "Are there any chairs?";
- ``count``: "How many chairs are there?";
- ``compare_count``: "Are there more chairs than tables?" (fewer, as many as);
- ``relate_exist``: "Is there a chair to the left of the table in the picture?";
- ``relate_count``: "How many trees are behind the house in the picture?";
- ``query_noun``: "What is to the left of the table in the picture?", "What is the
  nearest thing?";
- ``query_colour``: "What colour is the tent?", "What colour is the nearest chair?".

Questions are about objects (what ``PictureFacts`` holds): roads, intersections and
groups are not things here. Objects carry a noun and a colour (``colours.colour_word`` of the catalog colour); a
style either renames the noun ("white wardrobe") or changes nothing a person can name,
so it is asked about through the noun, not on its own.

Sides are the picture's, told as the camera-frame captions tell them ("in the
picture"), so they never clash with a scene-frame caption's "to the left of B" (B's own
left): left and right across the picture, in front of and behind by depth from the
camera (``programs.RELATE_SIDES``).

Every question's answer is what its program gives when ``programs.execute`` runs it on
the picture's facts; the generator only proposes. It proposes only questions a person
could answer from the picture:

- a noun is asked about only when the picture leaves no doubt about its count: no
  object of that noun is shown too little to name (``PictureFacts.glimpsed``), and no
  object in the picture has a noun that is a kind of it (``is_kind_of``: "office chair"
  and "armchair" are chairs, "bucket of coal" a bucket), since the programs compare
  nouns exactly and a person would not;
- a question about a side of an anchor ("the table": the only one of its noun) asks
  only when every object it concerns stands clearly on one side or the other: at
  least the executor's margin away (``programs.MARGINS``), never in between;
- "What is ..." asks only when no glimpsed object could be the answer too.

Answers are balanced within each family as CLEVR balances them, by rejection: the
candidates are grouped by answer; a yes/no family takes as many "yes" as "no"
(``QUESTIONS_PER_FAMILY`` // 2 of each, or none when the picture offers only one), and
a family of other answers takes ``QUESTIONS_PER_FAMILY`` different answers drawn
uniformly, each with one of its questions drawn uniformly; a family of counts asks "0"
only beside a count of something the picture shows. So no answer can dominate a
family within a picture, and over a dataset "yes" and "no" are exactly even. Every draw
comes from the picture's own stream (``core.seeds``, stage ``questions``): the same
seed gives the same questions.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Iterator, Sequence
from dataclasses import dataclass
from functools import partial
from typing import TYPE_CHECKING, overload

from scenewright.core.seeds import SeedLike, stage_stream

from .colours import COLOUR_TERMS
from .english import plural_of, sentence_case, with_article
from .errors import ProgramError
from .programs import (
    MARGINS,
    RELATE_SIDES,
    PictureFacts,
    Program,
    answer_text,
    execute,
    step,
)
from .world import is_kind_of

if TYPE_CHECKING:
    import numpy as np

    from scenewright.core.scene import Scene
    from scenewright.generator.rules import Rules

#: How many questions each family asks of one picture, at most.
QUESTIONS_PER_FAMILY = 2
#: The words of each side ``relate`` knows, as the camera-frame captions say them.
SIDE_WORDS = {
    "left": "to the left of",
    "right": "to the right of",
    "front": "in front of",
    "behind": "behind",
}
#: What a side phrase ends with, so it is read as the picture's side, not the anchor's own.
IN_PICTURE = " in the picture"

#: A candidate question: its template's form, the words that fill the template, and what
#: makes its program (made only for the candidates executed: there may be thousands).
Candidate = tuple[str, dict[str, str], Callable[[], Program]]


@dataclass(frozen=True)
class QuestionFamily:
    """One kind of question: ``templates`` by form ("{a_noun}" and the like are filled
    from a candidate's words), ``candidates`` the questions it could ask of a picture,
    and ``yes_no``: whether its answers are yes and no (balanced one for one);
    ``counts``: whether its answers are counts, so that "0" (what is absent) is asked
    only beside the count of something present."""

    name: str
    templates: dict[str, str]
    candidates: Callable[[Asking], Iterable[Candidate]]
    yes_no: bool
    counts: bool = False


#: The families, in the order a row lists their questions.
FAMILIES: dict[str, QuestionFamily] = {}


def register_family(family: QuestionFamily) -> QuestionFamily:
    if family.name in FAMILIES:
        raise ValueError(f"question family {family.name!r} is registered twice")
    FAMILIES[family.name] = family
    return family


@dataclass(frozen=True)
class Asking:
    """What the families ask about: the picture's facts; ``vocabulary``, the nouns a
    question may name with their plurals; ``clear``, those whose count the picture
    leaves no doubt about (sorted); ``anchors``, the seen objects "the NOUN" picks out
    (the only seen one of a clear noun), in id order."""

    facts: PictureFacts
    vocabulary: dict[str, str]
    clear: tuple[str, ...]
    anchors: tuple[str, ...]

    @classmethod
    def of(cls, facts: PictureFacts, vocabulary: dict[str, str]) -> Asking:
        shown = [o.noun for o in (*facts.objects.values(), *facts.glimpsed.values())]
        glimpsed = {o.noun for o in facts.glimpsed.values()}
        vocabulary = dict(vocabulary) | {n: plural_of(n) for n in shown if n not in vocabulary}
        clear = tuple(
            sorted(
                noun
                for noun in vocabulary
                if noun not in glimpsed and not any(is_kind_of(other, noun) for other in shown)
            )
        )
        seen = [o.noun for o in facts.objects.values()]
        anchors = tuple(
            sorted(
                i for i, o in facts.objects.items() if o.noun in clear and seen.count(o.noun) == 1
            )
        )
        return cls(facts, vocabulary, clear, anchors)

    def seen_nouns(self) -> list[str]:
        """The clear nouns of the seen objects, sorted."""
        return sorted({o.noun for o in self.facts.objects.values()} & set(self.clear))

    def clearly_sided(self, anchor: str, side: str, ids: Iterable[str]) -> bool:
        """Whether each of ``ids`` is at least the margin away from ``anchor`` along the
        side's measure (across the picture, or depth), so "on that side" is clear for it."""
        measure, _ = RELATE_SIDES[side]
        at = getattr(self.facts.objects[anchor], measure)
        known = {**self.facts.glimpsed, **self.facts.objects}
        return all(
            abs(getattr(known[i], measure) - at) >= MARGINS[measure] for i in ids if i != anchor
        )


def picture_questions(
    facts: PictureFacts, vocabulary: dict[str, str], seed: SeedLike, *, view: int = 0
) -> list[dict]:
    """The questions of every family about the picture ``facts`` describe, family by
    family: ``{"family", "question", "answer", "program"}``, each answer the string its
    program gives when executed on ``facts`` (``programs.answer_text``).

    ``vocabulary``: the nouns a question may name, with their plurals (``vocabulary_of``;
    the seen objects' nouns are added); ``seed``: the scene's seed (its ``questions``
    stream, child ``view``) or a Generator."""
    asking = Asking.of(facts, vocabulary)
    rng = stage_stream(seed, "questions", view)
    asked = []
    for family in FAMILIES.values():
        found = family.candidates(asking)
        candidates: Sequence[Candidate] = found if isinstance(found, Sequence) else list(found)
        if family.yes_no:
            chosen = _yes_and_no(candidates, facts, rng)
        else:
            chosen = _different_answers(candidates, facts, rng, absence_alone=not family.counts)
        for answer, (form, words, program) in chosen:
            question = sentence_case(family.templates[form].format(**words))
            asked.append(
                {
                    "family": family.name,
                    "question": question,
                    "answer": answer,
                    "program": program(),
                }
            )
    return asked


def _answer(candidate: Candidate, facts: PictureFacts) -> str | None:
    """The candidate's answer: its program executed on ``facts``; None when it cannot run."""
    try:
        return answer_text(execute(candidate[2](), facts))
    except ProgramError:
        return None


def _yes_and_no(
    candidates: Sequence[Candidate], facts: PictureFacts, rng: np.random.Generator
) -> list:
    """As many (answer, candidate) with "yes" as with "no", up to ``QUESTIONS_PER_FAMILY``
    // 2 of each, in random order: CLEVR's rejection sampling, over the candidates in a
    random order (so each is a uniform draw among the candidates of its answer), stopping
    once both are full."""
    wanted = QUESTIONS_PER_FAMILY // 2
    found: dict[str, list] = {"yes": [], "no": []}
    for k in rng.permutation(len(candidates)):
        answer = _answer(candidates[k], facts)
        if answer is not None and len(found[answer]) < wanted:
            found[answer].append((answer, candidates[k]))
            if all(len(kept) == wanted for kept in found.values()):
                break
    each = min(len(found["yes"]), len(found["no"]))
    chosen = found["yes"][:each] + found["no"][:each]
    return [chosen[k] for k in rng.permutation(len(chosen))]


def _different_answers(
    candidates: Sequence[Candidate],
    facts: PictureFacts,
    rng: np.random.Generator,
    *,
    absence_alone: bool = True,
) -> list:
    """Up to ``QUESTIONS_PER_FAMILY`` (answer, candidate) with different answers: the
    answers drawn uniformly among those the candidates give, then one candidate of each.

    ``absence_alone=False``: none when "0" is the only answer the candidates give. A
    picture of many objects leaves few counts clear, and every noun it does not show
    answers "0": asked alone, absence would be nearly every count question of such
    scenes (it was 99 % of a town's), and a model could answer them without looking."""
    by_answer: dict[str, list[Candidate]] = {}
    for candidate in candidates:
        answer = _answer(candidate, facts)
        if answer is not None:
            by_answer.setdefault(answer, []).append(candidate)
    answers = sorted(by_answer)
    if not absence_alone and answers == ["0"]:
        return []
    chosen = rng.choice(len(answers), size=min(QUESTIONS_PER_FAMILY, len(answers)), replace=False)
    return [
        (answers[k], by_answer[answers[k]][rng.integers(len(by_answer[answers[k]]))])
        for k in chosen
    ]


def vocabulary_of(rules: Rules | None, scene: Scene | None = None) -> dict[str, str]:
    """The nouns questions may name, with their plurals: every object noun the rule set's
    catalog can give (an entry's own noun, unless every style renames it, and each
    style's), and the nouns of ``scene``'s objects; sorted by noun."""
    nouns: dict[str, str] = {}
    for entry in rules.catalog if rules is not None else ():
        if entry.kind != "object":
            continue
        if not entry.styles or any(style.noun is None for style in entry.styles):
            nouns[entry.noun] = plural_of(entry.noun, entry.plural)
        for style in entry.styles:
            if style.noun is not None:
                nouns[style.noun] = plural_of(style.noun, style.plural)
    for thing in scene.objects if scene is not None else ():
        if thing.kind == "object":
            nouns.setdefault(thing.noun, plural_of(thing.noun, thing.plural))
    return dict(sorted(nouns.items()))


# -- the families --------------------------------------------------------------------


def _counted(noun: str) -> Program:
    """How many ``noun`` things: steps 0..2."""
    return [step("scene"), step("filter_noun", noun, 0), step("count", None, 1)]


def _exists(noun: str) -> Program:
    return [step("scene"), step("filter_noun", noun, 0), step("exist", None, 1)]


def _exist(asking: Asking) -> Iterator[Candidate]:
    for noun in asking.clear:
        yield "exist", {"a_noun": with_article(noun)}, partial(_exists, noun)
        yield "exist_any", {"plural": asking.vocabulary[noun]}, partial(_exists, noun)


def _count(asking: Asking) -> Iterator[Candidate]:
    for noun in asking.clear:
        yield "count", {"plural": asking.vocabulary[noun]}, partial(_counted, noun)


def _compared(first: str, second: str, comparison: str) -> Program:
    """The program comparing how many ``first`` and ``second`` things there are."""
    return [
        *_counted(first),
        step("scene"),
        step("filter_noun", second, 3),
        step("count", None, 4),
        step(comparison, None, 2, 5),
    ]


class _CountComparisons(Sequence[Candidate]):
    """The compare-count candidates: each comparison of each ordered pair of clear nouns,
    one of them seen, in that order; each made when read, since a picture of n such
    nouns has 3 n (n - 1) of them (some 2700 in a village) and the family reads a few."""

    COMPARISONS = ("greater_than", "less_than", "equal_integer")

    def __init__(self, asking: Asking):
        seen = set(asking.seen_nouns())
        self.vocabulary = asking.vocabulary
        self.pairs = [
            (first, second)
            for first in asking.clear
            for second in asking.clear
            if first != second and (first in seen or second in seen)
        ]

    def __len__(self) -> int:
        return len(self.COMPARISONS) * len(self.pairs)

    @overload
    def __getitem__(self, index: int) -> Candidate: ...
    @overload
    def __getitem__(self, index: slice) -> Sequence[Candidate]: ...
    def __getitem__(self, index: int | slice) -> Candidate | Sequence[Candidate]:
        if isinstance(index, slice):
            return [self[i] for i in range(*index.indices(len(self)))]
        if not 0 <= index < len(self):
            raise IndexError(index)
        first, second = self.pairs[index // len(self.COMPARISONS)]
        comparison = self.COMPARISONS[index % len(self.COMPARISONS)]
        words = {"first": self.vocabulary[first], "second": self.vocabulary[second]}
        return comparison, words, partial(_compared, first, second, comparison)


def _related_program(anchor_noun: str, side: str, noun: str, last: str) -> Program:
    """``last`` ("exist" or "count") of the ``noun`` things on ``side`` of the only ``anchor_noun``."""
    return [
        step("scene"),
        step("filter_noun", anchor_noun, 0),
        step("unique", None, 1),
        step("relate", side, 2),
        step("filter_noun", noun, 3),
        step(last, None, 4),
    ]


def _related(asking: Asking, last: str) -> Iterator[Candidate]:
    """Questions ending in ``last`` about each anchor, side and seen noun whose objects all
    stand clearly on one side of the anchor or the other."""
    for anchor in asking.anchors:
        anchor_noun = asking.facts.objects[anchor].noun
        for side, side_words in SIDE_WORDS.items():
            for noun in asking.seen_nouns():
                ids = [i for i, o in asking.facts.objects.items() if o.noun == noun]
                if noun == anchor_noun or not asking.clearly_sided(anchor, side, ids):
                    continue
                words = {
                    "a_noun": with_article(noun),
                    "plural": asking.vocabulary[noun],
                    "side": side_words,
                    "anchor": anchor_noun,
                    "where": IN_PICTURE,
                }
                yield (
                    f"relate_{last}",
                    words,
                    partial(_related_program, anchor_noun, side, noun, last),
                )


def _query_side(anchor_noun: str, side: str) -> Program:
    return [
        step("scene"),
        step("filter_noun", anchor_noun, 0),
        step("unique", None, 1),
        step("relate", side, 2),
        step("unique", None, 3),
        step("query_noun", None, 4),
    ]


def _query_extreme(which: str) -> Program:
    return [step("scene"), step("extreme", which, 0), step("query_noun", None, 1)]


def _query_noun(asking: Asking) -> Iterator[Candidate]:
    facts = asking.facts
    for anchor in asking.anchors:
        anchor_noun = facts.objects[anchor].noun
        for side, side_words in SIDE_WORDS.items():
            # Every object, glimpsed ones too, clearly on one side, and none glimpsed on
            # this side: nothing barely shown could be the answer as well.
            measure, sign = RELATE_SIDES[side]
            at = getattr(facts.objects[anchor], measure)
            if not asking.clearly_sided(anchor, side, [*facts.objects, *facts.glimpsed]) or any(
                sign * (getattr(o, measure) - at) > 0 for o in facts.glimpsed.values()
            ):
                continue
            words = {"side": side_words, "anchor": anchor_noun, "where": IN_PICTURE}
            yield "query_side", words, partial(_query_side, anchor_noun, side)
    depths = [o.depth for o in facts.objects.values()]
    for which, sign in (("nearest", 1.0), ("farthest", -1.0)):
        if not depths:
            break
        best = min(depths) if which == "nearest" else max(depths)
        if any(sign * (o.depth - best) < MARGINS["depth"] for o in facts.glimpsed.values()):
            continue  # something barely shown is about as near (far), or nearer (farther)
        yield "query_extreme", {"which": which}, partial(_query_extreme, which)


def _colour_of(noun: str, which: str | None) -> Program:
    """The colour of the only ``noun`` thing (``which`` None) or of the nearest or farthest."""
    one = step("unique", None, 1) if which is None else step("extreme", which, 1)
    return [step("scene"), step("filter_noun", noun, 0), one, step("query_colour", None, 2)]


def _query_colour(asking: Asking) -> Iterator[Candidate]:
    facts = asking.facts
    for noun in asking.seen_nouns():
        if any(word in COLOUR_TERMS for word in noun.split()):
            continue  # "What colour is the white desk?" gives its answer away
        if sum(o.noun == noun for o in facts.objects.values()) == 1:
            yield "query_colour", {"noun": noun}, partial(_colour_of, noun, None)
            continue
        for which in ("nearest", "farthest"):
            yield (
                "query_colour_extreme",
                {"noun": noun, "which": which},
                partial(_colour_of, noun, which),
            )


for _family in (
    QuestionFamily(
        "exist",
        {"exist": "is there {a_noun}?", "exist_any": "are there any {plural}?"},
        _exist,
        True,
    ),
    QuestionFamily("count", {"count": "how many {plural} are there?"}, _count, False, counts=True),
    QuestionFamily(
        "compare_count",
        {
            "greater_than": "are there more {first} than {second}?",
            "less_than": "are there fewer {first} than {second}?",
            "equal_integer": "are there as many {first} as {second}?",
        },
        _CountComparisons,
        True,
    ),
    QuestionFamily(
        "relate_exist",
        {"relate_exist": "is there {a_noun} {side} the {anchor}{where}?"},
        partial(_related, last="exist"),
        True,
    ),
    QuestionFamily(
        "relate_count",
        {"relate_count": "how many {plural} are {side} the {anchor}{where}?"},
        partial(_related, last="count"),
        False,
        counts=True,
    ),
    QuestionFamily(
        "query_noun",
        {
            "query_side": "what is {side} the {anchor}{where}?",
            "query_extreme": "what is the {which} thing?",
        },
        _query_noun,
        False,
    ),
    QuestionFamily(
        "query_colour",
        {
            "query_colour": "what colour is the {noun}?",
            "query_colour_extreme": "what colour is the {which} {noun}?",
        },
        _query_colour,
        False,
    ),
):
    register_family(_family)
