"""Everyday room-request wordings that the describer never writes, mapped onto what
the relation registry can say, or reported as not understood where it cannot.

People asking for a room write "a dresser opposite the bed", "a rug at the foot of
the bed", "a desk in front of the window", "a wardrobe next to the door", "a coffee
table in the middle of the room", "a wooden table", "as well as". Each table here
either names the registry wording a phrase means (its labels are then looked up in
the registry's phrases, so a phrase never means a label the registry lacks), or says
why a phrase cannot be composed, so that it is reported rather than dropped or faked.
The parser (``parse``) calls these at fixed points, passing its reader (``reader``:
its vocabulary, request and phrase matching) where a phrase depends on what was read.
"""

from __future__ import annotations

from collections.abc import Collection, Sequence
from dataclasses import replace
from typing import Any, Protocol

from scenewright.core.relations import RELATIONS

from .vocabulary import FUNCTION_WORDS, ORDINALS, WALL_NUMBER, NounSense


class _Word(Protocol):
    low: str


#: Phrases that join two noun phrases as "and" does.
JOINERS: tuple[str, ...] = ("as well as", "along with", "together with", "and also")

#: Relation phrases of everyday English -> the registry wording they mean. "opposite
#: the bed" is "faces the bed" (across the room from it, turned towards it); "at the
#: foot of the bed" is "is in front of" it (a bed's front is its foot).
EVERYDAY_WORDINGS: dict[str, str] = {
    "opposite": "faces",
    "opposite to": "faces",
    "opposite of": "faces",
    "across from": "faces",
    "across the room from": "faces",
    "at the foot of": "is in front of",
    "at the bottom of": "is in front of",
    "in the centre of": "is in the middle of",
    "in the center of": "is in the middle of",
    "at the centre of": "is in the middle of",
    "at the center of": "is in the middle of",
    "at the middle of": "is in the middle of",
}

#: Things next to each other in a line, as "side by side" (each next to and lined up
#: with the one before).
SIDE_BY_SIDE = ("side by side", "in a row", "in a line")

#: "on either side" said without "on": the sides of the thing named before.
BARE_SIDES = ("either side", "each side", "both sides")

#: "at the end of X": the registry wording by X's type (a bed's end is its foot); for
#: any other type, next to it (at the end of a row of counters).
END_OF: tuple[str, ...] = ("at the end of", "at the far end of")
END_OF_WORDINGS: dict[str, str] = {"bed": "is in front of"}
END_OF_DEFAULT = "is next to"

#: Things asked to stand "in the middle of the room": no registry relation places a
#: thing at the room's centre, so these are reported, not composed.
ROOM_MIDDLE: tuple[str, ...] = tuple(
    f"{at} the {middle}{tail}"
    for at in ("in", "at")
    for middle in ("middle", "centre", "center")
    for tail in (" of the room", " of the floor", "")
) + ("centrally", "in the room's centre", "in the room's center", "in the room's middle")
ROOM_MIDDLE_NOTE = "no relation places a thing in the middle of the room"

#: A relation to a window in words of a relation to a thing: "in front of the window"
#: and "at the window" are under it (against its wall, across it), "next to the window"
#: beside it.
WINDOW_LABELS: dict[str, str] = {
    "NextToFront": "UnderWindow",
    "SeatedAround": "UnderWindow",  # "a desk at the window"
    "NextTo": "BesideWindow",
}

#: A relation phrase's first word when it has its verb ("is against"), not bare.
VERBS = ("is", "are", "stands", "stand", "sits", "sit", "faces", "face")

#: Words that deny what follows. Before a relation ("the desk is not under the
#: window") the relation is reported, never composed; before "want", "need" and the
#: like and a thing ("I don't want a TV") the thing is asked to be absent, as "no TV".
NEGATIONS = (
    "not",
    "never",
    "isn't",
    "aren't",
    "doesn't",
    "don't",
    "didn't",
    "shouldn't",
    "mustn't",
    "won't",
    "can't",
    "cannot",
)
NEGATED_NOTE = "a relation said not to hold is not composed"
DENY_VERBS = ("want", "need", "have", "include", "like", "put", "add", "use", "place")
#: Words before a room size that say it is rough: "about 4 by 3 metres".
APPROX = ("about", "around", "roughly", "approximately", "approx", "circa", "some")

#: Labels whose words ("next to", "beside", "near", "by") put a thing in the corner by
#: the door when their object is the door: the room's door is then drawn beside that
#: corner, so the thing stands next to the door.
BY_DOOR_LABELS = frozenset({"NextTo", "BesideWindow"})
BY_DOOR_NOTE = "only one thing can stand in the corner by the door"
DOOR_NOTE = "no relation places a thing relative to a door other than next to it"

OPPOSITE_PART_NOTE = "which wall or corner is opposite is not understood"

#: A support relation ("in the middle of") with a wall as its object: against it.
ALONG_WALL_NOTE = "where along the wall is not held; it stands against the wall"


def phrase_at(toks: Sequence[_Word], i: int, phrases: Sequence[str]) -> int:
    """How many tokens the longest of ``phrases`` at token i takes (0: none)."""
    best = 0
    for phrase in phrases:
        words = phrase.split()
        if len(words) > best and [t.low for t in toks[i : i + len(words)]] == words:
            best = len(words)
    return best


def room_middle_at(toks: Sequence[_Word], i: int) -> int:
    """How many tokens "in the middle of the room" (or "in the middle" alone, not
    followed by "of": "in the middle of the table" is a registry wording) takes at i."""
    n = phrase_at(toks, i, ROOM_MIDDLE)
    if n and i + n < len(toks) and toks[i + n].low == "of":
        return 0
    return n


def everyday_wording(toks: Sequence[_Word], i: int) -> tuple[str, int] | None:
    """The registry wording an everyday relation phrase at token i means, with the
    tokens it takes, or None."""
    n = phrase_at(toks, i, tuple(EVERYDAY_WORDINGS))
    if n:
        return EVERYDAY_WORDINGS[" ".join(t.low for t in toks[i : i + n])], n
    return None


def end_of_wording(type_name: str | None) -> str:
    """The wording "at the end of" a thing of this type means."""
    return END_OF_WORDINGS.get(type_name or "", END_OF_DEFAULT)


def window_label(labels: Sequence[str], registered: Collection[str]) -> str | None:
    """The window label meant by a relation to a thing said of a window, or None."""
    for label in labels:
        meant = WINDOW_LABELS.get(label)
        if meant is not None and meant in registered:
            return meant
    return None


def style_note(word: str, noun: str, styles: Sequence[str]) -> str:
    """Why an adjective before a catalog noun went unused."""
    if styles:
        return f"the catalog has no {word} {noun} (its styles: {', '.join(styles)})"
    return f"the catalog has no {word} {noun} (it has one look)"


# -- called by the parser ---------------------------------------------------------------
# ``reader`` is parse's ``_Reader`` (not imported: it imports this module): ``vocab``,
# ``req``, ``match`` and ``_unused``; ``toks`` its tokens (``low``, ``text``, ``used``,
# ``note``); places are parse's ``Place``, copied with ``dataclasses.replace``.


def everyday_relation(reader: Any, toks: Sequence[Any], k: int):
    """An everyday relation phrase at token k ("opposite", "at the foot of", "at the
    end of"): (the labels of the registry wording it means, tokens taken), or None."""
    found = everyday_wording(toks, k)
    if found is None:
        n = phrase_at(toks, k, END_OF)
        if not n:
            return None
        j = k + n  # the thing's type decides: a bed's end is its foot
        while j < len(toks) and toks[j].low in ("the", "a", "an", "this", "that", "its"):
            j += 1
        hit = reader.match(toks, j, reader.vocab.nouns) if j < len(toks) else None
        found = (end_of_wording(reader.vocab.nouns[hit[0]].type if hit else None), n)
    wording, n = found
    sense = reader.vocab.relations.get(wording)
    return None if sense is None else (sense.labels, n)


def denied_at(reader: Any, toks: Sequence[Any], i: int) -> tuple[str, int] | None:
    """ "don't want a TV", "do not need a rug" at token i: (the type asked to be absent,
    tokens taken), or None."""
    j = i + 1 if toks[i].low in ("do", "does", "did") else i
    if j >= len(toks) or toks[j].low not in NEGATIONS:
        return None
    j += 1
    if j >= len(toks) or toks[j].low not in DENY_VERBS:
        return None
    j += 1
    if j < len(toks) and toks[j].low in ("a", "an", "any", "the"):
        j += 1
    hit = reader.match(toks, j, reader.vocab.nouns) if j < len(toks) else None
    if hit is None:
        return None
    return reader.vocab.nouns[hit[0]].type, j + hit[1] - i


def negation_at(toks: Sequence[Any], i: int) -> int:
    """How many tokens a negation takes at i ("not", "isn't", "do not"; 0: none)."""
    if toks[i].low in NEGATIONS:
        return 1
    if toks[i].low in ("do", "does", "did") and i + 1 < len(toks) and toks[i + 1].low == "not":
        return 2
    return 0


def everyday_place(
    reader: Any,
    how: str,
    labels: tuple[str, ...],
    place: Any,
    subjects: list[str],
    toks,
    span: tuple[int, int],
):
    """A relation to a thing said of a room part, as everyday English says it: "in
    front of the window" (under it), "next to the window" (beside it), "a bookshelf on
    either side of the window" (one beside it on each side), "next to the door" (in the
    corner by it), "opposite the window" (against the wall across the room from it),
    "in the middle of the north wall" (against it). (labels, place, subjects) to go on
    with, or None once reported."""
    start, end = span
    across = [t for t in toks[start:end] if t.low in ("opposite", "across")]
    if place.kind in ("window", "door") and across:
        wall = replace(place, kind="wall", number=None, opposite=place.kind)
        return ("AgainstWall",), wall, subjects
    for t in across if place.kind in ("wall", "corner") else ():
        # "in the opposite corner": some corner (or wall), which one is not held
        t.used, t.note = False, OPPOSITE_PART_NOTE
    if place.kind == "window" and how in ("sides", "flanked") and len(subjects) <= 2:
        # two things beside one window cannot both be on one side of it (each is
        # within reach of the window): one stands on each side
        if len(subjects) == 1:
            first = reader.entity(subjects[0])
            sense = NounSense(first.type, first.style, False)
            subjects = subjects + [reader.create(sense, first.colour, [toks[start]])]
        return ("BesideWindow",), place, subjects
    if place.kind == "window" and not any(x.endswith("Window") for x in labels):
        meant = window_label(labels, RELATIONS.names())
        return ((meant,) if meant else labels), place, subjects
    if place.kind == "door":
        if how != "rel" or not BY_DOOR_LABELS & set(labels):
            reader._unused(toks, start, end, DOOR_NOTE)
            return None
        if any(getattr(s.target, "by_door", False) for s in reader.req.statements):
            reader._unused(toks, start, end, BY_DOOR_NOTE)
            return None
        return ("InCorner",), replace(place, kind="corner", number=None, by_door=True), subjects
    if place.kind == "wall" and any(x.startswith("OnTopOf") and x != "OnTopOf" for x in labels):
        # "in the middle of the north wall": against it; which part of it is not held
        for t in toks[start:end]:
            if t.low in ("middle", "centre", "center", "edge", "front"):
                t.used, t.note = False, ALONG_WALL_NOTE
        return ("AgainstWall",), place, subjects
    return labels, place, subjects


def adjective_noun(reader: Any, toks: Sequence[Any], j: int) -> tuple[str, int] | None:
    """ "a wooden table", "a round table": a word the catalog has no style of, before a
    catalog noun, after a determiner or count. The noun's hit (the word is reported
    with the styles the catalog does have), or None when no noun follows."""
    word = toks[j]
    vocab = reader.vocab
    if (
        j + 1 >= len(toks)
        or not word.low.isalpha()
        or word.low in FUNCTION_WORDS
        or word.low in ORDINALS
        or word.low in vocab.nouns
        or reader.match(toks, j, vocab.relations) is not None
    ):
        return None
    hit = reader.match(toks, j + 1, vocab.nouns)
    if hit is None:
        return None
    entry = vocab.entries[vocab.nouns[hit[0]].type]
    word.used = False
    word.note = style_note(word.text, entry.noun, [s.name for s in entry.styles])
    return hit


def settle_opposite(request: Any) -> None:
    """The wall across the room from a window or door a thing is asked to stand opposite:
    the first one the text puts on a wall, or the wall the plan would give it, which is
    then named so that the plan cannot move it (a door in the south wall, a window in
    the north one, or the east one when the door is in the north wall)."""
    wanted = {getattr(s.target, "opposite", None) for s in request.statements} - {None}
    if not wanted:
        return
    if "door" in wanted:
        request.doors = [d or "south" for d in request.doors] or ["south"]
    if "window" in wanted:
        default = "east" if "north" in request.doors else "north"
        request.windows = [w or default for w in request.windows] or [default]
    sides = {
        "window": request.windows[0] if request.windows else "",
        "door": request.doors[0] if request.doors else "",
    }
    across = {"north": "south", "south": "north", "east": "west", "west": "east"}
    request.statements = [
        replace(
            s,
            target=replace(
                s.target, number=WALL_NUMBER[across[sides[s.target.opposite]]], opposite=None
            ),
        )
        if getattr(s.target, "opposite", None)
        else s
        for s in request.statements
    ]


def everyday_step(reader: Any, toks: Sequence[Any], i: int, free: bool) -> tuple[str, int]:
    """An everyday phrase at token i that the parser reads before its own phrases, with
    the tokens it takes: "and" ("as well as"), "size" ("about" before a room size),
    "negation" ("not", "don't want a TV": the thing then absent), "which" (right after
    a relation's object: the clause is about that object), "clause" ("that", "which" or
    "who" before a verb anywhere else: about the subject), "middle" ("in the middle of
    the room", reported; only where no relation waits for its object: ``free``), or
    ("", 0). Marks the words it takes used, or reports them."""
    t = toks[i]
    n = phrase_at(toks, i, JOINERS)
    if n:
        what = "and"
    elif t.low in APPROX and reader._size_at(toks, i + 1):
        what, n = "size", 1
    elif negation_at(toks, i):
        what, n = "negation", negation_at(toks, i)
        denied = denied_at(reader, toks, i)
        if denied is None:  # reported with the relation it denies, or on its own
            for w in toks[i : i + n]:
                w.note = NEGATED_NOTE
            return what, n
        n = denied[1]
        reader.req.absent[denied[0]] = (t.start, toks[i + n - 1].end)
    elif (
        t.low in ("which", "that", "who")
        and i == reader.object_end
        and i + 1 < len(toks)
        and (toks[i + 1].low in VERBS or negation_at(toks, i + 1))
    ):
        what, n = "which", 1
    elif t.low in ("which", "that", "who") and i + 1 < len(toks) and toks[i + 1].low in VERBS:
        # "a rug that stands against the wall": about the subject, not "that stand"
        what, n = "clause", 1
    elif free and room_middle_at(toks, i):
        n = room_middle_at(toks, i)
        reader._unused(toks, i, i + n, ROOM_MIDDLE_NOTE)
        return "middle", n
    else:
        return "", 0
    for w in toks[i : i + n]:
        w.used = True
    return what, n


def between_pair(reader: Any, subjects: list[str], named: list[str]) -> list[str]:
    """The two things "between" means when its object names fewer: "a coffee table in
    between" (the last two things named before it), "two armchairs across from the sofa
    and a table between them" (the armchair, and the sofa named before it)."""
    earlier = dict.fromkeys(e for e in reversed(reader.mentions) if e not in subjects + named)
    return list(earlier)[: 2 - len(named)][::-1] + named
