"""Roads in words: the phrases that start a path at a junction or on another path, as
the describer tells a road network ("three roads meeting at an intersection", "twelve
roads meeting four at each of three intersections", "a road starting at an
intersection") and as people write it ("a lane branching off the first road").

The reader (``composer.parse``) asks ``network_phrase`` at each word where a relation
may start, gives the paths named just before it as the subjects (``trailing_paths``)
and the next noun phrase as the object, and ``connect`` writes each path's
``PathConnectedTo`` (docs/rules-language.md, Road networks). Nothing here reads text
beyond the words it is given, so the reader stays the one place that marks words used.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence

#: The catalog kinds that are ways: a relation "at" or "on" one of them is "next to".
WAY_KINDS = ("path", "junction")

#: Words that start paths at what follows: a junction ("meeting at an intersection")
#: or another path, where the new one branches off ("a lane off the first road").
NETWORK_PHRASES: tuple[tuple[str, ...], ...] = tuple(
    tuple(p.split())
    for p in (
        "meeting at",
        "meet at",
        "meets at",
        "starting at",
        "starts at",
        "start at",
        "starting from",
        "leading from",
        "leading off",
        "leading away from",
        "branching off",
        "branching from",
        "branches off",
        "branch off",
        "coming off",
        "off",
    )
)
#: "meeting four at each of three intersections": the paths shared out, four a junction.
_EACH = ("at", "each", "of")
#: Paths meeting at a junction of their own: "crossing each other", "where two roads
#: meet" (the word alone, before a comma, "and" or "with" or at the sentence's end).
_EACH_OTHER = [[verb, "each", "other"] for verb in ("meeting", "meet", "crossing", "cross")]
_ALONE = ([], [","], ["and"], ["with"])
#: The junction such paths meet at: the first of these the catalog has, else any.
JUNCTIONS = ("intersection", "crossroads")


def junction_type(entries: Mapping) -> str | None:
    """The junction type paths meet at when the text names none (``JUNCTIONS``)."""
    found = sorted(name for name, e in entries.items() if e.kind == "junction")
    return next((name for name in JUNCTIONS if name in found), found[0] if found else None)


def network_phrase(words: Sequence[str], numbers: Mapping[str, int]) -> tuple[str, int, int] | None:
    """("network", 0, tokens taken) for a phrase of ``NETWORK_PHRASES`` at the start of
    ``words`` (lower case), ("networks", N, tokens taken) for "meeting N at each of";
    ("meet", 0, tokens taken) for paths that meet at no junction named ("two roads
    crossing each other", "where two roads meet"); None for anything else. A phrase of meeting ("meeting at") is "network", which
    starts every path named just before it ("two roads and a lane meeting at ..."); any
    other ("a lane off the road") is "branch", which starts the last one named."""
    if words[:3] in _EACH_OTHER:
        return "meet", 0, 3
    if words[:1] in (["meeting"], ["meet"], ["crossing"], ["cross"]) and words[1:2] in _ALONE:
        return "meet", 0, 1
    if words[:1] in (["meeting"], ["meet"]):
        for n in (3, 2, 1):  # "meeting four at each of", "meeting twenty-one at ..."
            count = numbers.get(" ".join(words[1 : 1 + n]))
            if count and tuple(words[1 + n : 4 + n]) == _EACH:
                return "networks", count, 4 + n
    for phrase in sorted(NETWORK_PHRASES, key=len, reverse=True):
        if tuple(words[: len(phrase)]) == phrase:
            meeting = phrase[0] in ("meeting", "meet", "meets")
            return "network" if meeting else "branch", 0, len(phrase)
    return None


def trailing_paths(ids: Sequence[str], kind_of: Callable[[str], str]) -> list[str]:
    """The paths at the end of a list of things named ("a well, two roads and a lane"
    -> the two roads and the lane): what a phrase of meeting after them starts."""
    out: list[str] = []
    for eid in reversed(ids):
        if kind_of(eid) != "path":
            break
        out.append(eid)
    return out[::-1]


def connect(
    how: str,
    each: int,
    subjects: Sequence[str],
    targets: Sequence[str],
    kind_of: Callable[[str], str],
    add: Callable[[str, str, str], None],
) -> str | None:
    """Start each subject path at a target (a junction, or a path it branches off):
    all at the one target, or shared out in turn, ``each`` a target ("networks") or
    as evenly as they divide. Returns why it cannot, or None when done."""
    if not subjects:
        return "only roads, lanes and streets meet at a junction"
    if any(kind_of(t) not in WAY_KINDS for t in targets) or not targets:
        return "a road starts at a junction or on another road"
    if any(t in subjects for t in targets):
        return "a road cannot start on itself"
    share = each if how == "networks" else len(subjects) // len(targets)
    if share == 0 or share * len(targets) != len(subjects):
        return f"{len(subjects)} roads cannot be shared out among {len(targets)}"
    for k, path in enumerate(subjects):
        add(path, "PathConnectedTo", targets[k // share])
    return None


def shared_sense(reader, phrase: str, sense, after: Sequence[str], ordinal, det):
    """A noun a group shares with an object type (the city's "shop"), as the describer
    uses it: the group before "consists of" (``after``: the next words) and outside
    groups' paragraphs; inside them the object, that group's own whatever the ordinal,
    which counts both types. (sense, ordinal, determiner) as the reader is to take them."""
    group = reader.vocab.shared[phrase]
    if list(after) in (["consists", "of"], ["consist", "of"]):
        return group, ordinal, det
    if reader.members_of is None and reader.focus is None:
        return group, ordinal, det
    if ordinal is not None and reader.members_of is None:
        return sense, None, "the"
    return sense, ordinal, det
