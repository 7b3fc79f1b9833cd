"""The phrases of a sentence and what each names: a noun phrase (a count or determiner,
an ordinal, a colour and a catalog noun, or a pronoun: the things it makes or refers
to), a room ("a large kitchen", "a 4 by 3 metre room"), a size, a room part as a
relation's object ("the north wall", "the window", "the north-west corner"), an opening
("a door in the south wall") or an absence ("no rug"). ``parse._Reader`` reads sentences
with these and applies the relations between what they name.
"""

from __future__ import annotations

from scenewright.describer.colours import COLOUR_TERMS

from .everyday import adjective_noun
from .request import Entity, Place, Token
from .vocabulary import (
    COMPASS_WORDS,
    NUMBERS,
    ORDINALS,
    ROOM_SIZES,
    ROOMS,
    WALL_NUMBER,
    NounSense,
)
from .ways import WAY_KINDS, shared_sense

#: The most words a phrase of a table may have.
_LONGEST = 8
#: ``PhraseReader.matching``'s "wherever it is": no group named for it.
_ANYWHERE = "*"


class PhraseReader:
    """What a phrase at a token names; the state it reads and writes (the vocabulary, the
    request, the things named so far) is set up by ``parse._Reader``."""

    # -- phrase matching -----------------------------------------------------------

    def match(self, toks: list[Token], i: int, table) -> tuple[str, int] | None:
        """The longest phrase of ``table`` starting at token i: (phrase, tokens taken)."""
        for n in range(min(_LONGEST, len(toks) - i), 0, -1):
            phrase = " ".join(t.low for t in toks[i : i + n])
            if phrase in table:
                return phrase, n
        return None

    # -- entities ------------------------------------------------------------------

    def create(self, sense: NounSense, colour: str | None, toks: list[Token]) -> str:
        n = len(self.req.entities) + 1
        entity = Entity(
            f"e{n}",
            sense.type,
            sense.style,
            colour,
            toks[0].start,
            toks[-1].end,
            # a road is never a group's ("a farm with a barn, by a lane")
            parent=None if self.vocab.entries[sense.type].kind in WAY_KINDS else self.members_of,
            group=sense.type in self.vocab.groups,
            paragraph=self.focus if self.members_of is None else None,
        )
        self.req.entities.append(entity)
        self.of_type.setdefault(entity.type, []).append(entity)
        return entity.id

    def entity(self, eid: str) -> Entity:
        return self.req.entities[int(eid[1:]) - 1]

    def kind_of(self, eid: str) -> str:
        """The catalog kind of a thing named: object, group, path or junction."""
        return self.vocab.entries[self.entity(eid).type].kind

    def matching(self, sense: NounSense, parent: str | None = _ANYWHERE) -> list[str]:
        """The things the noun may name: those of ``parent`` (a group, or None for the
        top level) when given; else the focus group's own if it has any, else the top
        level's if there are any, else all."""
        out = []
        for e in self.of_type.get(sense.type, ()):  # a city names 1,500 things
            if sense.exact and sense.style is not None and e.style not in (None, sense.style):
                continue
            out.append(e)
        if parent != _ANYWHERE:
            out = [e for e in out if e.parent == parent]
        else:
            for owner in (self.focus, None):
                own = [e for e in out if e.parent == owner]
                if own:
                    out = own
                    break
        # "the bookshelf" is the plain one before "the low bookshelf"
        return [e.id for e in sorted(out, key=lambda e: e.style != sense.style)]

    def refer(
        self,
        sense: NounSense,
        det: str,
        ordinal: int | None,
        count: int | None,
        colour: str | None,
        toks: list[Token],
        scope: str | None = _ANYWHERE,
    ) -> list[str]:
        found = self.matching(sense, scope)
        owners = {self.entity(e).parent for e in found}
        ranked = self.ranks.setdefault((sense.type, owners.pop() if len(owners) == 1 else None), [])
        if ordinal is not None:
            # a style's noun counts its own ("the second low bookshelf"), the plain noun
            # every one of the type ("the third bookshelf", low ones included)
            found_set, ranked_set = set(found), set(ranked)
            counted = [e for e in ranked if e in found_set]
            unranked = [e for e in found if e not in ranked_set]
            while len(counted) < ordinal:
                more = unranked.pop(0) if unranked else self.create(sense, colour, toks)
                ranked.append(more)
                counted.append(more)
            chosen = [counted[ordinal - 1]]
            self.ordinal_used.setdefault(sense.type, set()).add(chosen[0])
        elif det == "other":
            named = self.ordinal_used.setdefault(sense.type, set())
            rest = [e for e in found if e not in named and e not in self.in_sets]
            rest = rest or [e for e in found if e not in named] or found[-1:]
            chosen = rest[:1] if rest else [self.create(sense, colour, toks)]
            named.add(chosen[0])
        elif det == "of" and count is not None:
            # "two of the bookshelves": those named on their own first, then the rest
            order = [e for e in ranked if e in found] + [e for e in found if e not in ranked]
            while len(order) < count:
                order.append(self.create(sense, colour, toks))
            chosen = order[:count]
            self.in_sets.update(chosen)
            ranked.extend(e for e in chosen if e not in ranked)  # the set takes the next places
        elif det == "others" and count is not None:
            # "eight other homes": the next ones not named before, as the describer
            # counts them ("the thirty-fifth home" after 34 named in sets)
            order = [e for e in found if e not in ranked and e not in self.in_sets]
            while len(order) < count:
                order.append(self.create(sense, colour, toks))
            chosen = order[:count]
            self.in_sets.update(chosen)
            ranked.extend(chosen)
        elif sense.plural or det in ("both", "each", "every", "all"):
            want = count or (2 if det == "both" else max(len(found), 2 if sense.plural else 1))
            while len(found) < want:
                found.append(self.create(sense, colour, toks))
            chosen = found if count is None else found[:want]
        else:
            chosen = found[:1] or [self.create(sense, colour, toks)]
        if len(chosen) == 1 and chosen[0] not in ranked:
            ranked.append(chosen[0])
        for eid in chosen:
            e = self.entity(eid)
            if sense.exact and sense.style is not None and e.style is None:
                e.style = sense.style
        return chosen

    # -- noun phrases --------------------------------------------------------------

    def noun_phrase(self, toks: list[Token], i: int, subject: list[str], obj: bool = False):
        """(kind, value, tokens taken) for the noun phrase at i, or None. kind is
        "things" (entity ids), "place" (a Place), "opening" (door/window sides), "room",
        "size", "absent" or "it"."""
        j = i
        det = ""
        count: int | None = None
        ordinal: int | None = None
        m = self.match(toks, j, NUMBERS)
        low = toks[j].low
        if low in ("no", "without"):
            k = j + 1
            if k < len(toks) and toks[k].low in ("a", "an", "any"):
                k += 1
            hit = self.match(toks, k, self.vocab.nouns) if k < len(toks) else None
            if hit:
                return "absent", self.vocab.nouns[hit[0]].type, k + hit[1] - i
            return None
        if low in ("it", "them"):
            return "it", low, 1
        if low == "each" and j + 1 < len(toks) and toks[j + 1].low == "other":
            return "each other", subject, 2
        if low in (
            "the",
            "this",
            "that",
            "these",
            "those",
            "both",
            "each",
            "every",
            "all",
            "another",
            "other",
        ):
            det = low
            j += 1
            if low in ("both", "all") and j < len(toks) and toks[j].low == "the":
                j += 1
            if j < len(toks) and toks[j].low == "other":
                det, j = "other", j + 1
        elif toks[j].low.replace(".", "", 1).isdigit() and not self._size_at(toks, j):
            det, count, j = "a", int(float(toks[j].low)), j + 1
        elif m:
            det, count, j = "a", NUMBERS[m[0]], j + m[1]
        if count is not None and det == "a" and j < len(toks) and toks[j].low == "other":
            det, j = "others", j + 1  # "eight other homes": ones not named yet
        if (
            count is not None
            and j + 1 < len(toks)
            and toks[j].low == "of"
            and toks[j + 1].low in ("the", "these", "those")
        ):  # "two of the bookshelves"
            det, j = "of", j + 2
        if (
            j < len(toks)
            and det in ("the", "these", "those", "")
            and self.match(toks, j, NUMBERS)
            and not self.match(toks, j, ORDINALS)  # "the one hundred and first home"
        ):
            m2 = self.match(toks, j, NUMBERS)
            assert m2 is not None
            count, j = NUMBERS[m2[0]], j + m2[1]
        if det == "another" and j < len(toks) and toks[j].low == "more":
            j += 1
        if j < len(toks) and toks[j].low == "more":
            j += 1
        nth = self.match(toks, j, ORDINALS) if j < len(toks) else None
        if nth is not None:  # "the second", "the one hundred and fifth"
            ordinal, j = ORDINALS[nth[0]], j + nth[1]
            det = det or "the"
        if j >= len(toks):
            return None
        # A room part or an opening.
        place = self._place(toks, j)
        if place is not None:
            kind, value, n = place
            # a relation's object without its article ("desk under window") is the one
            definite = det in ("the", "this", "that") or (obj and det == "")
            if kind == "opening" and definite and ordinal is None:
                return "place", Place(value[0], None), j + n - i
            if kind == "opening":
                return "opening", (value[0], count or 1), j + n - i
            if kind == "place" and ordinal is not None and value.kind == "window":
                value = Place("window", ordinal)
            if kind == "place" and det in ("each", "every", "all") and value.number is None:
                value = Place(value.kind, 0)  # one against each wall, in each corner: _apply
            return kind, value, j + n - i
        # A room.
        size = self._size_at(toks, j)
        if size is not None:
            dims, n = size
            rest = self._room_word(toks, j + n)
            if rest is not None:
                return "room", (rest[0], dims, 1.0), j + n + rest[1] - i
            return "size", dims, j + n - i
        room = self._room_word(toks, j)
        thing = self.match(toks, j, self.vocab.nouns)
        if room is not None and (thing is None or thing[1] < room[1]):  # "an office chair"
            return "room", (room[0], None, room[2]), j + room[1] - i
        # A thing.
        colour = None
        hit = self.match(toks, j, self.vocab.nouns)
        if hit is None and toks[j].low in COLOUR_TERMS:
            colour = toks[j].low
            hit = self.match(toks, j + 1, self.vocab.nouns) if j + 1 < len(toks) else None
            if hit is not None:
                j += 1
        if hit is None and j > i:
            hit = adjective_noun(self, toks, j)
            if hit is not None:
                j += 1
        if hit is None:
            return None
        sense = self.vocab.nouns[hit[0]]
        if hit[0] in self.vocab.shared:  # "shop": the city's group or its building
            words = [t.low for t in toks[j + hit[1] : j + hit[1] + 2]]
            shared = shared_sense(self, hit[0], sense, words, ordinal, det)
            sense, ordinal, det = shared
        taken = toks[i : j + hit[1]]
        self.each = det in ("each", "every") and ordinal is None
        if obj and det == "" and not sense.plural and self.matching(sense):
            pass  # "chair at desk": the desk named before, as "the desk"
        elif det in ("", "a", "another") and ordinal is None:
            n = count if count is not None else (2 if sense.plural else 1)
            ids = [self.create(sense, colour, taken) for _ in range(n)]
            return "things", ids, j + hit[1] - i
        scope, extra = self._owner_after(toks, j + hit[1], subject)
        ids = self.refer(sense, det, ordinal, count, colour, taken, scope)
        return "things", ids, j + hit[1] + extra - i

    def _owner_after(self, toks: list[Token], k: int, subject: list[str]):
        """Where a definite phrase's thing belongs, said after it: "of the first row of
        desks" (that group's), "on its own" (the top level's); (the group, or None for
        the top level, or _ANYWHERE when nothing is said; tokens taken)."""
        words = [t.low for t in toks[k : k + 3]]
        if words in (["on", "its", "own"], ["on", "their", "own"]):
            for t in toks[k : k + 3]:
                t.used = True
            return None, 3
        if not words or words[0] not in ("of", "at") or k + 1 >= len(toks):
            return _ANYWHERE, 0
        j = k + 1
        while j < len(toks) and (toks[j].low in ("the", "this", "that") or toks[j].low in ORDINALS):
            j += 1
        nth = self.match(toks, j, ORDINALS) if j < len(toks) else None
        j += nth[1] if nth is not None else 0  # "of the one hundred and fifth home"
        hit = self.match(toks, j, self.vocab.nouns) if j < len(toks) else None
        if hit is None or self.vocab.nouns[hit[0]].type not in self.vocab.groups:
            return _ANYWHERE, 0
        owner = self.noun_phrase(toks, k + 1, subject)
        if owner is None or owner[0] != "things" or len(owner[1]) != 1:
            return _ANYWHERE, 0
        for t in toks[k : k + 1 + owner[2]]:
            t.used = True
        return owner[1][0], 1 + owner[2]

    def _size_at(self, toks: list[Token], j: int):
        """ "4 by 3 metre", "4x3 m", "4 m by 3 m": ((w, d), tokens taken) or None."""
        units = ("m", "metre", "metres", "meter", "meters")
        k = j
        if k >= len(toks) or not toks[k].low.replace(".", "", 1).isdigit():
            return None
        w = float(toks[k].low)
        k += 1
        if k < len(toks) and toks[k].low in units:
            k += 1
        if (
            k + 1 < len(toks)
            and toks[k].low in ("by", "x")
            and toks[k + 1].low.replace(".", "", 1).isdigit()
        ):
            d = float(toks[k + 1].low)
            k += 2
            if k < len(toks) and toks[k].low in units:
                k += 1
            return (w, d), k - j
        return None

    def _room_word(self, toks: list[Token], j: int):
        factor = 1.0
        k = j
        if k < len(toks) and toks[k].low in ROOM_SIZES:
            factor = ROOM_SIZES[toks[k].low]
            k += 1
        hit = self.match(toks, k, ROOMS) if k < len(toks) else None
        if hit is None:
            return None
        return hit[0], k + hit[1] - j, factor

    def _place(self, toks: list[Token], j: int):
        low = toks[j].low
        nxt = toks[j + 1].low if j + 1 < len(toks) else ""
        if low in COMPASS_WORDS and nxt in ("wall", "side"):
            return "place", Place("wall", WALL_NUMBER[low]), 2
        parts = low.split("-")
        if len(parts) == 2 and all(p in COMPASS_WORDS for p in parts) and nxt == "corner":
            return "place", Place("corner", WALL_NUMBER[parts[0]], (parts[0], parts[1])), 2
        if (
            low in COMPASS_WORDS
            and nxt in COMPASS_WORDS
            and j + 2 < len(toks)
            and toks[j + 2].low == "corner"
        ):
            return "place", Place("corner", WALL_NUMBER[low], (low, nxt)), 3
        if low in ("wall", "walls"):
            return "place", Place("wall"), 1
        if low in ("corner", "corners"):
            by = [t.low for t in toks[j + 1 : j + 4]]
            if by[:1] in (["by"], ["near"]) and by[1:] == ["the", "door"]:
                return "place", Place("corner", by_door=True), 4
            return "place", Place("corner"), 1
        if low in ("door", "doors", "doorway", "window", "windows"):
            kind = "door" if low.startswith("door") else "window"
            return "opening", (kind,), 1
        return None
