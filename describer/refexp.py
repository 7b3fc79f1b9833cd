"""Referring expressions for a rendered picture, each with a program that picks out its object.

For every object the picture shows well enough (``PictureView.seen``), the first of
these forms that picks out exactly that object among the seen ones. A noun is used
(for the object or an anchor) only when no other seen object has a noun that is a kind
of it (``world.is_kind_of``, as ``questions`` asks): a person takes an armchair for a
chair and a green armchair for an armchair, but the programs compare nouns exactly, so
"the chair" beside an armchair, or "the armchair" beside a green armchair, would not
pick out one thing to a reader. An object of such a noun gets no expression.

1. "the tent": the only seen object of its noun;
2. "the sign to the left of the table" (or "to the right of"): the only one of its noun
   on that side of an anchor that is itself the only one of its noun, across the
   picture (box centres, at least ``SIDE_MARGIN`` pixels apart);
3. "the second chair from the left" (or "from the right"): its place among the seen
   objects of its noun, ordered across the picture, when its neighbours in that order
   are at least ``SIDE_MARGIN`` pixels away and the place is at most ``MAX_PLACE``
   (nobody counts to the twelfth chair);
4. "the nearest chair" / "the farthest chair": the one of its noun nearest to (or
   farthest from) the camera by at least ``DEPTH_MARGIN`` metres.

Each expression comes with a functional program in the style of CLEVR (``programs``:
steps ``{"function", "inputs", "value_inputs"}``, run by ``programs.execute`` on the
picture's facts, ``PictureFacts``); an expression is kept only when its program,
executed, gives exactly its object: uniqueness is checked by running the program, not
assumed. Its programs use ``scene``, ``filter_noun``, ``unique``, ``relate`` ("left"
or "right"), ``nth`` and ``extreme``.
"""

from __future__ import annotations

from collections import Counter

from .english import ordinal_word
from .errors import ProgramError
from .programs import DEPTH_MARGIN, SIDE_MARGIN, PictureFacts, Seen, execute, step
from .world import is_kind_of

__all__ = [
    "DEPTH_MARGIN",
    "MAX_PLACE",
    "SIDE_MARGIN",
    "PictureFacts",
    "ProgramError",
    "Seen",
    "execute",
    "referring_expressions",
]

#: The furthest place in an order across the picture an expression counts to.
MAX_PLACE = 5


def referring_expressions(facts: PictureFacts) -> list[dict]:
    """One ``{"text", "id", "program"}`` for each seen object some form picks out, in id
    order; each program, executed on ``facts``, gives its ``id``."""
    found = []
    counts = Counter(o.noun for o in facts.objects.values())
    # A noun a reader takes to mean just the objects of that noun: no seen object's noun
    # is a kind of it ("armchair" of "chair", "green armchair" of "armchair").
    clear = {noun for noun in counts if not any(is_kind_of(other, noun) for other in counts)}
    for entity_id in sorted(facts.objects):
        for text, program in _candidates(facts, entity_id, counts, clear):
            try:
                picked = execute(program, facts)
            except ProgramError:
                continue
            if picked == entity_id:
                found.append({"text": text, "id": entity_id, "program": program})
                break
    return found


def _candidates(facts: PictureFacts, entity_id: str, counts: Counter, clear: set[str]):
    """The forms of the module docstring for one object, in order, as (text, program);
    ``counts``: the seen objects per noun, ``clear``: the nouns a reader takes for just
    those objects."""
    noun = facts.objects[entity_id].noun
    if noun not in clear:
        return  # "the chair" beside an armchair: a reader counts the armchair too
    yield f"the {noun}", [step("scene"), step("filter_noun", noun, 0), step("unique", None, 1)]
    anchors = sorted(
        i
        for i, o in facts.objects.items()
        if i != entity_id and counts[o.noun] == 1 and o.noun in clear
    )
    for anchor in anchors:
        anchor_noun = facts.objects[anchor].noun
        for side in ("left", "right"):
            program = [
                step("scene"),
                step("filter_noun", anchor_noun, 0),
                step("unique", None, 1),
                step("relate", side, 2),
                step("filter_noun", noun, 3),
                step("unique", None, 4),
            ]
            yield f"the {noun} to the {side} of the {anchor_noun}", program
    same = sorted((o for o in facts.objects.values() if o.noun == noun), key=lambda o: o.across)
    position = [o.id for o in same].index(entity_id) + 1
    for side, place in (("left", position), ("right", len(same) + 1 - position)):
        if place > MAX_PLACE:
            continue
        program = [step("scene"), step("filter_noun", noun, 0), step("nth", [side, str(place)], 1)]
        yield f"the {ordinal_word(place)} {noun} from the {side}", program
    for which in ("nearest", "farthest"):
        yield (
            f"the {which} {noun}",
            [step("scene"), step("filter_noun", noun, 0), step("extreme", which, 1)],
        )
