"""Controlled English -> a request: the things a text asks for, their relations, the room.

The text is read left to right, a sentence at a time, in chunks: a noun phrase
(determiner or count, ordinal, colour, then a catalog noun: "two nightstands", "the
first nightstand", "a black sofa", "it"), a relation phrase (a registry wording, with
its verb "is to the left of", plural "stand against", or bare after a noun "against"),
a room part ("the north wall", "the window", "the north-west corner"), a room ("a
large kitchen", "a 4 by 3 metre room"), an opening ("a door in the south wall"), or a
negation ("no rug"). A relation applies to the subject before it (the last noun
phrase, or every coordinated one when its verb is plural: "the bed and the dresser
stand against ...") and takes the next noun phrase or room part as its object.

What each phrase names is read by ``phrases.PhraseReader``; this module reads the
sentences and applies their relations. Every word is either used or reported
(``Issue``), with its character span.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from scenewright.core.relations import RELATIONS, RelationLabel

from .everyday import (
    BARE_SIDES,
    NEGATED_NOTE,
    SIDE_BY_SIDE,
    VERBS,
    between_pair,
    everyday_place,
    everyday_relation,
    everyday_step,
    phrase_at,
    settle_opposite,
)
from .phrases import PhraseReader
from .request import Entity, Issue, Place, Request, Statement, Token, tokenize
from .vocabulary import (
    COMPASS_WORDS,
    FUNCTION_WORDS,
    NUMBERS,
    ROOM_TYPES,
    ROOMS,
    WALL_NUMBER,
    NounSense,
    Vocabulary,
)
from .ways import (
    WAY_KINDS,
    connect,
    junction_type,
    network_phrase,
    trailing_paths,
)

_SIDES_OF = (
    "on each side of",
    "each side of",
    "on either side of",
    "either side of",
    "on both sides of",
    "both sides of",
    "at each side of",
    "flanking",
)
#: The same without "of": the sides of the thing named before ("a bed with a nightstand
#: on either side").
_SIDES = ("on each side", "on either side", "on both sides", "at each side", "at either side")
_AROUND = ("around", "round", "surrounding", "about")
_CORNERS = (("north", "west"), ("east", "north"), ("south", "east"), ("west", "south"))


#: Why a room of a second kind in one text is not made.
SECOND_ROOM_NOTE = "a text makes one room; rooms of several kinds are a house plan (docs/houses.md)"


def _sentences(tokens: list[Token]) -> list[list[Token]]:
    out: list[list[Token]] = [[]]
    for t in tokens:
        if t.low in ".;!?":
            t.used = True
            out.append([])
        else:
            out[-1].append(t)
    return [s for s in out if s]


@dataclass
class _Subject:
    groups: list[list[str]] = field(default_factory=list)  # coordinated noun phrases

    def last(self) -> list[str]:
        return self.groups[-1] if self.groups else []

    def all(self) -> list[str]:
        return [e for g in self.groups for e in g]


class _Reader(PhraseReader):
    """Reads a text's sentences into a ``Request``: each phrase (``PhraseReader``), then
    the relations between what they name."""

    def __init__(self, vocab: Vocabulary, request: Request) -> None:
        self.vocab = vocab
        self.req = request
        self.mentions: list[str] = []
        self.ordinal_used: dict[str, set[str]] = {}
        #: Per type, the things in the order the text first names each on its own (as
        #: the describer counts its ordinals: after "the first bookshelf" and "the low
        #: bookshelf", "the third bookshelf" is the one not named yet), and the things
        #: named in a set ("two of the bookshelves"), which "the other" is not.
        self.ranks: dict[tuple[str, str | None], list[str]] = {}
        self.in_sets: set[str] = set()
        #: The group whose members a "consists of" sentence is naming, and the group the
        #: text is about since (its paragraph): "the first desk" there is one of its own.
        self.members_of: str | None = None
        self.focus: str | None = None
        #: Whether the last noun phrase read was "each N" / "every N": a relation to it
        #: then makes one subject per N ("a lamp on each nightstand").
        self.each = False
        #: The thing a "with" phrase hangs on ("a nightstand ... with a lamp on it"):
        #: what "it" names there, before the last thing named.
        self.with_head: list[str] = []
        #: The things the last relation put something on ("a TV on a stand"), while a
        #: place phrase may follow them without "and": "a TV on a stand against the
        #: north wall" puts the stand against it. And what rests on what, so far.
        self.support: list[str] = []
        self.resting: dict[str, str] = {}
        #: Where the last relation's object ended, and the thing it named.
        self.object_end, self.last_object = -1, ""
        #: The things named, by type.
        self.of_type: dict[str, list[Entity]] = {}

    # -- sentences -----------------------------------------------------------------

    def relation_at(self, toks: list[Token], i: int):
        """(kind, value, tokens taken): a registry relation phrase, a phrase of our own
        ("on each side of", "around", "along"), or None."""
        n = phrase_at(toks, i, SIDE_BY_SIDE)  # "side by side", "in a row"
        if n:
            return "side by side", None, n
        way = network_phrase([t.low for t in toks[i : i + 8]], NUMBERS)
        if way is not None:  # "meeting at an intersection": composer/ways.py
            return way[0], (str(way[1]),), way[2]
        n = phrase_at(toks, i, _SIDES_OF)
        if n:
            return "sides", None, n
        n = phrase_at(toks, i, _SIDES + BARE_SIDES)
        if n:
            return "sides of it", None, n
        if [t.low for t in toks[i : i + 2]] == ["flanked", "by"]:  # the passive
            return "flanked", None, 2
        k = i
        if toks[k].low in ("is", "are", "stands", "stand", "sits", "sit") and k + 1 < len(toks):
            k += 1
        everyday = everyday_relation(self, toks, k)
        if everyday is not None:
            return "rel", everyday[0], k + everyday[1] - i
        if toks[k].low in _AROUND:
            return "around", None, k + 1 - i
        if toks[k].low in ("between", "in-between"):
            return "between", None, k + 1 - i
        if toks[k].low == "along":  # a wall, or a road
            return "rel", ("AgainstWall", "NextTo"), k + 1 - i
        if toks[k].low in ("near", "by") or (
            toks[k].low == "close" and k + 1 < len(toks) and toks[k + 1].low == "to"
        ):
            n = 2 if toks[k].low == "close" else 1
            return "rel", ("NextTo", "BesideWindow", "AgainstWall"), k + n - i
        if toks[k].low in ("facing", "faces", "face"):
            hit = self.match(toks, i, self.vocab.relations)
            if hit is None or hit[1] <= k - i + 1:
                return "rel", ("FacingTowards",), k + 1 - i
        hit = self.match(toks, i, self.vocab.relations)
        if hit is not None:
            return "rel", self.vocab.relations[hit[0]].labels, hit[1]
        if toks[k].low in ("in", "on", "at", "into") and k + 1 < len(toks):
            # "in the north-west corner", "on the north wall", "in a corner"
            return "in", None, k + 1 - i
        return None

    def sentence(self, toks: list[Token]) -> None:
        subject = _Subject()
        pending: tuple[str, tuple[str, ...], int, list[str]] | None = None
        joined = False  # the last word was "and" or a comma
        self.members_of = None
        self.with_head, self.support = [], []
        negated: int | None = None  # where a negation stands before the next relation
        self.object_end = -1
        i = 0
        while i < len(toks):
            t = toks[i]
            owner = subject.last()
            if (
                t.low in ("consists", "consist")
                and i + 1 < len(toks)
                and toks[i + 1].low == "of"
                and len(owner) == 1
                and self.entity(owner[0]).group
            ):  # "the first row of desks consists of four desks and four chairs"
                self.members_of = self.focus = owner[0]
                t.used = toks[i + 1].used = True
                subject, pending, joined = _Subject(), None, False
                i += 2
                continue
            what, n = everyday_step(self, toks, i, pending is None)
            if what:  # "as well as", "about 4 by 3 m", "not", "which is", "in the middle"
                joined = joined or what == "and"
                self.support = [] if what == "and" else self.support
                negated = i if what == "negation" else negated
                subject = _Subject([[self.last_object]]) if what == "which" else subject
                i += n
                continue
            if t.low in ("and", ",", "with", "plus", "also", "while"):
                t.used = True
                joined = t.low in ("and", ",")
                if t.low == "with" and pending is None:
                    # "a nightstand next to the bed with a lamp on it": it is the nightstand
                    self.with_head = owner
                    # "a farm with a barn and a field", the group named just before
                    if len(owner) == 1 and self.entity(owner[0]).group and i > 0:
                        if self.entity(owner[0]).end == toks[i - 1].end:
                            self.members_of = owner[0]
                    subject = _Subject()
                if t.low == ",":
                    self.with_head = []
                self.support = []
                i += 1
                continue
            rel = self.relation_at(toks, i) if pending is None or pending[0] == "in" else None
            if rel is not None and (subject.all() or self.mentions):
                kind, labels, n = rel
                plural = any(w.low in ("are", "stand", "face", "sit") for w in toks[i : i + n])
                if i >= 2 and toks[i - 1].low == "also":  # "... are also next to the road"
                    plural = plural or toks[i - 2].low in ("are", "stand", "face", "sit")
                if kind == "in" and pending is not None:
                    rel = None
                else:
                    if not subject.all() and self.mentions:
                        subject.groups = [[self.mentions[-1]]]
                    who = subject.all() if plural else subject.last()
                    if self.support and toks[i].low not in VERBS:
                        # "a TV on a stand against the wall": the stand (see _apply)
                        who = who + [s for s in self.support if s not in who]
                    self.support = []
                    if kind in ("network", "networks", "meet"):  # "two roads and a lane meeting at"
                        who = trailing_paths(subject.all(), self.kind_of)
                    elif kind == "branch":  # "a road and a lane off it": the lane
                        who = trailing_paths(subject.last(), self.kind_of)
                    pending = (kind, labels or (), i, who)
                    if negated is not None:  # reported from the negation on
                        kind, pending, negated = "negated", ("negated", (), negated, who), None
                    for w in toks[i : i + n]:
                        w.used = True
                    if kind == "between" and [w.low for w in toks[i + n : i + n + 1]] in (
                        [],
                        [","],
                        ["and"],
                    ):
                        # "in between" alone: between the two things named before it
                        self._apply(pending, between_pair(self, who, []), "things", toks, i + n)
                        pending = None
                    if kind == "sides of it":  # "a nightstand on either side": of the bed
                        pending = ("sides", (), i, who)
                        target = self._pronoun(who)
                        if target:
                            self._apply(pending, target, "things", toks, i + n)
                        else:
                            self._unused(toks, i, i + n, "a relation without its object")
                        pending = None
                    if kind == "meet":  # "two roads crossing each other"
                        pending = None
                        self._meet(who, toks, i, n)
                    if kind == "side by side":  # next to each other, lined up
                        pending = None
                        if len(who) < 2:
                            self._unused(toks, i, i + n, "side by side needs two things")
                        for a, b in zip(who[1:], who, strict=False):
                            self.req.statements.append(
                                Statement(a, "NextTo", b, toks[i].start, toks[i + n - 1].end)
                            )
                            self.req.statements.append(
                                Statement(
                                    a, "ImplicitAlignedWith", b, toks[i].start, toks[i + n - 1].end
                                )
                            )
                    i += n
                    joined = False
                    continue
            np = self.noun_phrase(toks, i, subject.all(), obj=pending is not None)
            if np is None:
                if pending is not None and t.low not in FUNCTION_WORDS:
                    # "a rug on the floor ...": its object is a word not understood, not
                    # whatever is named next ("... and a lamp" would be under the rug);
                    # "the front wall" is still some wall, "front" reported
                    if i + 1 < len(toks) and self._place(toks, i + 1):
                        t.note = "which one this is is not understood"
                    else:
                        self._unused(toks, pending[2], i + 1, "a relation without its object")
                        pending = None
                i += 1
                continue
            kind, value, n = np
            span = toks[i : i + n]
            if kind == "it":
                value = self._pronoun(pending[3] if pending else [], plural=value == "them")
                if value and pending is not None and pending[0] == "between" and len(value) < 2:
                    value = between_pair(self, pending[3], value)  # "a table between them"
                kind = "things" if value else "none"
            if (
                kind == "things"
                and pending is not None
                and pending[0] == "between"
                and len(value) == 1
                and i + n + 1 < len(toks)
                and toks[i + n].low == "and"
            ):  # "between the bed and the wardrobe": the second thing too
                second = self.noun_phrase(toks, i + n + 1, pending[3], obj=True)
                if second is not None and second[0] == "things":
                    value = value + second[1]
                    n += 1 + second[2]
                    span = toks[i : i + n]
            if kind == "each other" and (pending is None or len(pending[3]) < 2):
                kind = "none"
            if kind == "none":
                i += 1
                continue
            for w in span:
                w.used = w.used or not w.note  # a word reported in the phrase stays so
            self.support = []
            if kind == "room":
                if pending is not None and pending[0] != "in":  # "at the end of the room"
                    self._unused(toks, pending[2], i + n, "no relation takes the room itself")
                pending = None  # "a piano in the living room": the room it is in
                word, dims, factor = value
                name = ROOMS[word][0]
                if name not in ("room", self.req.room) and self.req.room != "room":
                    # "The flat has a hall, a kitchen and ...": one text makes one room
                    self._unused(toks, i, i + n, SECOND_ROOM_NOTE)
                    i += n
                    continue
                if name != "room" or self.req.room == "room":
                    self.req.room = name
                if dims is not None:
                    self.req.size = dims
                self.req.size_factor = factor
                subject = _Subject()
            elif kind == "size":
                self.req.size = value
            elif kind == "absent":
                self.req.absent[value] = (span[0].start, span[-1].end)
            elif kind == "opening":
                side, count = value
                wall = self._opening_wall(toks, i + n)
                where = wall[0] if wall else ""
                for _ in range(count):
                    (self.req.doors if side == "door" else self.req.windows).append(where)
                if wall:
                    for w in toks[i + n : i + n + wall[1]]:
                        w.used = True
                    n += wall[1]
            elif pending is not None:
                self._apply(pending, value, kind, toks, i + n, each=self.each)
                subject_ids = pending[3]
                if kind == "things":  # "which" right after it is about it
                    self.object_end, self.last_object = i + n, value[-1]
                if kind == "things" and any(x.startswith("OnTopOf") for x in pending[1]):
                    self.support = list(value)
                    self.resting.update((s, value[0]) for s in subject_ids)
                pending = None
                if kind == "things":
                    self.mentions.extend(value)
                # "and faces it" continues with the same subject
                subject = _Subject([subject_ids]) if subject_ids else subject
            elif kind == "things":
                negated = None  # a new thing: the negation before it is not about it
                if joined and subject.groups:
                    subject.groups.append(value)
                else:
                    subject = _Subject([value])
                self.mentions.extend(value)
            else:  # a room part standing alone ("the window")
                for w in span:
                    w.used = False
            joined = False
            i += n
        if pending is not None:
            self._unused(toks, pending[2], len(toks), "a relation without its object")

    def _meet(self, who: list[str], toks: list[Token], i: int, n: int) -> None:
        """Paths that meet at no junction named: at a new one (``ways.junction_type``)."""
        type_ = junction_type(self.vocab.entries)
        if type_ is None or len(who) < 2:
            return self._unused(toks, i, i + n, "two roads or more meet at a junction")
        junction = self.create(NounSense(type_, None, False), None, toks[i : i + n])
        span = toks[i].start, toks[i + n - 1].end
        self.req.statements += [Statement(p, "PathConnectedTo", junction, *span) for p in who]

    def _pronoun(self, subject: list[str], plural: bool = False) -> list[str]:
        """What "it" refers to: the last thing named, other than the subject; "them":
        that thing and the things of its type named just before it."""
        head = [e for e in self.with_head if e not in subject]
        if head and not plural:
            return head[-1:]
        found: list[str] = []
        for eid in reversed(self.mentions):
            if eid in subject or eid in found:
                continue
            if found and (not plural or self.entity(eid).type != self.entity(found[0]).type):
                break
            found.append(eid)
        return found[::-1]

    def _opening_wall(self, toks: list[Token], k: int):
        """ "in the south wall", "on the north side": (side, tokens taken) or None."""
        j = k
        if j < len(toks) and toks[j].low in ("in", "on", "at", "along"):
            j += 1
            if j < len(toks) and toks[j].low == "the":
                j += 1
            if j < len(toks) and toks[j].low in COMPASS_WORDS:
                side = toks[j].low
                j += 1
                if j < len(toks) and toks[j].low in ("wall", "side"):
                    j += 1
                return side, j - k
        return None

    def _apply(
        self, pending, value, kind: str, toks: list[Token], end: int, each: bool = False
    ) -> None:
        how, labels, start, subjects = pending
        if how == "negated":  # "the desk is not under the window"
            return self._unused(toks, start, end, NEGATED_NOTE)
        span_end = toks[end - 1].end
        span_start = toks[start].start
        if subjects:
            first = self.entity(subjects[0])
            span_start = min(span_start, first.start)

        def add(src: str, label: str, target: str | Place) -> None:
            self.req.statements.append(Statement(src, label, target, span_start, span_end))

        if kind == "place":
            place: Place = value
            if len(subjects) > 1:  # "a TV on a stand against the wall": the stand only
                subjects = [s for s in subjects if self.resting.get(s) not in subjects]
            everyday = everyday_place(self, how, labels, place, subjects, toks, (start, end))
            if everyday is None:
                return None
            labels, place, subjects = everyday
            if (how == "in" or "OnTopOf" in labels) and place.kind == "wall":
                label = "AgainstWall"  # "on the west wall": against it
            elif (
                how == "in"
                and place.kind == "corner"
                or "InCorner" in labels
                and place.kind == "corner"
            ):
                label = "InCorner"
            elif place.kind == "window":
                wall_labels = [x for x in labels if x in ("UnderWindow", "BesideWindow")]
                if not wall_labels:
                    return self._unused(toks, start, end, "no such relation to a window")
                label = wall_labels[0]
            elif place.kind == "wall" and "AgainstWall" in labels:
                label = "AgainstWall"
            elif place.kind == "wall" and "AwayFromWall" in labels:
                label = "AwayFromWall"  # "stands away from the west wall"
            elif place.kind == "corner":
                label = "InCorner"
            else:
                return self._unused(toks, start, end, "no such relation to a room part")
            if place.number == 0:  # "against each wall", "in every corner": one each
                first = self.entity(subjects[0])
                sense = NounSense(first.type, first.style, False)
                subjects = subjects + [
                    self.create(sense, first.colour, [toks[start]])
                    for _ in range(len(WALL_NUMBER) - len(subjects))
                ]
                for s, number in zip(subjects, sorted(WALL_NUMBER.values()), strict=False):
                    corner = _CORNERS[number - 1] if place.kind == "corner" else None
                    add(s, label, Place(place.kind, number, corner))
                return
            for s in subjects:
                add(s, label, place)
            return
        if kind == "each other":  # "two armchairs facing each other": each the next
            object_labels = [x for x in labels if not x.endswith("Window")]
            label = object_labels[0] if object_labels else ""
            if not label or how != "rel":
                return self._unused(toks, start, end, "no such relation among them")
            for a, b in zip(subjects, subjects[1:] + subjects[:1], strict=True):
                if a != b and not (
                    label != "FacingTowards" and len(subjects) == 2 and a == subjects[1]
                ):
                    add(a, label, b)
            return
        if kind != "things":
            return self._unused(toks, start, end, "a relation without its object")
        targets: list[str] = value
        if how in ("network", "networks", "branch"):
            why = connect(how, int(labels[0]), subjects, targets, self.kind_of, add)
            return None if why is None else self._unused(toks, start, end, why)
        if all(self.kind_of(t) in WAY_KINDS for t in targets) and (
            how == "in" or any(x.startswith("OnTopOf") for x in labels)
        ):
            how, labels = "rel", ("NextTo",)  # "at the intersection", "on the first road"
        if how == "in":
            return self._unused(toks, start, end, "no relation says 'in' of furniture")
        if how in ("sides", "flanked"):
            # paired furniture close on each side (a nightstand by the bed's head): the
            # close labels, which make the 2 m "to the left of" true as well
            subs, middle = (targets, subjects[0]) if how == "flanked" else (subjects, targets[0])
            subs = list(subs)
            if len(subs) == 1:
                e = self.entity(subs[0])
                sense = NounSense(e.type, e.style, False)
                subs.append(self.create(sense, e.colour, [toks[start]]))
            for k, s in enumerate(subs):
                add(s, ("BesideLeft", "BesideRight")[k % 2], middle)
                add(s, "ImplicitAlignedWith", middle)
            return
        if how == "between":
            # "a bed between two nightstands", "a coffee table between the sofas": one
            # to its left and one to its right (within 2 m, NextTo's reach)
            if len(targets) != 2 or len(subjects) != 1:
                return self._unused(toks, start, end, "'between' takes two things")
            add(targets[0], "NextToLeft", subjects[0])
            add(targets[1], "NextToRight", subjects[0])
            return
        if how == "around":
            if all(_is_seat(self.entity(sub).type) for sub in subjects):
                # chairs round a table: seated at whichever side each fits, facing it
                for sub in subjects:
                    add(sub, "SeatedAround", targets[0])
                return
            sides = ("NextToFront", "NextToBehind", "NextToLeft", "NextToRight")
            for k, s in enumerate(subjects):
                add(s, sides[k % 4], targets[0])
                if not self.entity(s).group:  # a group faces no way of its own
                    add(s, "FacingTowards", targets[0])
            return
        object_labels = [
            x for x in labels if not x.endswith("Window") and x not in ("AgainstWall", "InCorner")
        ]
        if not object_labels:
            return self._unused(toks, start, end, "this relation takes a wall, window or corner")
        # The shipped labels' words name one label each (a label that chooses its
        # direction is worded by a label of its own, "is just to the left of":
        # BesideLeft). Should a registered label share words with another, the
        # narrowest is taken (one direction, then the shortest reach): it makes the
        # broader one true as well, so the scene holds whichever the words meant.
        label = min(object_labels, key=lambda x: (_breadth(RELATIONS[x]), x))
        if label.startswith("OnTopOf") and len(subjects) == len(targets) > 1:
            each = True  # "two lamps on the side tables": one on each
        if each and len(targets) > 1 and 0 < len(subjects) <= len(targets):
            # "a lamp on each nightstand": one lamp per nightstand
            first = self.entity(subjects[0])
            sense = NounSense(first.type, first.style, False)
            subjects = subjects + [
                self.create(sense, first.colour, [toks[start]])
                for _ in range(len(targets) - len(subjects))
            ]
            for s, t in zip(subjects, targets, strict=True):
                add(s, label, t)
            return
        for s in subjects:
            for t in targets:
                if s != t:
                    add(s, label, t)

    def _unused(self, toks: list[Token], start: int, end: int, why: str) -> None:
        for w in toks[start:end]:
            if w.low not in FUNCTION_WORDS:
                w.used = False
                w.note = why


#: Words in a type's name that make it a seat: "chairs around the table" are seated at it.
SEAT_WORDS = ("chair", "stool", "bench", "seat")


def _is_seat(type_name: str) -> bool:
    return any(word in type_name for word in SEAT_WORDS) and type_name != "armchair"


def _breadth(spec: RelationLabel) -> tuple[int, float]:
    """How much a relation label allows: its directions, then its reach (metres)."""
    return len(spec.directions), math.inf if spec.reach is None else spec.reach


def parse(text: str, vocab: Vocabulary) -> Request:
    """Read ``text`` into a Request; every word it could not use is in ``issues``."""
    request = Request()
    tokens = tokenize(text)
    reader = _Reader(vocab, request)
    for sentence in _sentences(tokens):
        reader.sentence(sentence)
    settle_opposite(request)
    for entity in request.entities:  # a "sink" in a bathroom is its washbasin
        swap = ROOM_TYPES.get(request.room, {}).get(entity.type)
        if swap is not None and swap in vocab.entries:
            entity.type, entity.style = swap, None
    for t in tokens:
        if t.used:
            request.used.append((t.start, t.end))
            continue
        if t.low in FUNCTION_WORDS or t.low in ".,;:!?":
            continue
        if t.note:
            request.issues.append(
                Issue(t.start, t.end, t.text, f"unused word '{t.text}': {t.note}")
            )
        elif t.low in vocab.known_words:
            request.issues.append(
                Issue(t.start, t.end, t.text, f"unused word '{t.text}': not understood here")
            )
        else:
            near = vocab.suggest(t.low)
            hint = f"; did you mean '{near}'?" if near else ""
            request.issues.append(Issue(t.start, t.end, t.text, f"unknown word '{t.text}'{hint}"))
    for type_, (start, end) in request.absent.items():
        if any(e.type == type_ for e in request.entities):
            request.issues.append(
                Issue(
                    start,
                    end,
                    text[start:end],
                    f"'{text[start:end]}' contradicts a {type_.replace('_', ' ')} asked for",
                )
            )
    return request
