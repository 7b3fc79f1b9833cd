"""The words for each relation label and the describer's other fixed phrases.

Every relation label of Table 1 that the text may state (all but ``Implicit*`` and
``PathConnectedTo``) has one or more verb phrases, written in the third person singular
with the object to follow ("is next to", "faces away from"); the first is canonical,
the others are synonyms for paraphrase variants. Direction words are B's: "A is to the
left of B" means A is on B's own left (B's local +X), "in front of B" on B's forward
side.
"""

from __future__ import annotations

from scenewright.generator.relations import (
    COMPASS_DIRECTIONS,
    LABELS,
    PATH_LABELS,
    SIDE_DIRECTIONS,
    is_implicit,
)

from .variation import Choices

#: Labels the text may state: geometric ones that hold. ``Implicit*`` labels constrain the
#: layout only; ``PathConnectedTo`` is told as the road network ("roads meeting at ...").
DESCRIBED_LABELS: frozenset[str] = frozenset(
    label for label in LABELS if not is_implicit(label) and label not in PATH_LABELS
)

#: Labels whose statement says the same read either way round ("A is next to B" is "B is
#: next to A"); the describer states such a pair once.
SYMMETRIC_LABELS: frozenset[str] = frozenset(
    {"NextTo", "FacingSameDirection", "FacingOrthogonalDirection"}
)

_NEXT_TO = ("is next to", "is beside")
_COMPASS = {d: (f"is {d} of", f"is on the {d} side of") for d in COMPASS_DIRECTIONS}
_SIDE = {d: (f"is to the {d} of",) for d in SIDE_DIRECTIONS}

_WORDING: dict[str, tuple[str, ...]] = {
    "NextTo": _NEXT_TO,
    "NextToNorth": _COMPASS["north"],
    "NextToEast": _COMPASS["east"],
    "NextToSouth": _COMPASS["south"],
    "NextToWest": _COMPASS["west"],
    "NextToLeft": _SIDE["left"],
    "NextToRight": _SIDE["right"],
    "NextToFront": ("is in front of",),
    "NextToBehind": ("is behind",),
    "OnTopOf": ("is on top of", "is on"),
    "OnTopOfMiddle": ("is in the middle of", "stands in the middle of"),
    "OnTopOfEdge": ("is on the edge of", "stands on the edge of"),
    "OnTopOfFrontEdge": ("is at the front edge of", "stands at the front edge of"),
    # IsPartOf* rests A on B like OnTopOf*, but A belongs to B (a sign on a stall).
    "IsPartOf": ("is part of", "forms part of"),
    "IsPartOfMiddle": ("is attached to the middle of",),
    "IsPartOfEdge": ("is attached to the edge of",),
    "IsPartOfFrontEdge": ("is attached to the front edge of",),
    "FacingTowards": ("faces", "is turned towards"),
    "FacingAwayFrom": ("faces away from", "is turned away from"),
    "FacingSameDirection": ("faces the same way as", "faces the same direction as"),
    "FacingOrthogonalDirection": ("stands at a right angle to", "is at a right angle to"),
}


def relation_wordings(label: str, chosen: str | None = None) -> tuple[str, ...]:
    """The verb phrases that state ``label`` (canonical first).

    ``NextToChooseDirection`` / ``NextToChooseSide`` are worded from the direction the
    layout chose; without a valid one they fall back to plain "next to", which holds
    for every next-to label.
    """
    if label == "NextToChooseDirection":
        return _COMPASS.get(chosen or "", _NEXT_TO)
    if label == "NextToChooseSide":
        return _SIDE.get(chosen or "", _NEXT_TO)
    if label not in _WORDING:
        raise KeyError(f"relation label {label!r} has no wording")
    return _WORDING[label]


#: Labels that say where A is ("is on top of", "is north of"): "is" + a place phrase
#: may be inverted ("On top of it is a pot."), unlike "is part of" or "faces".
_PLACE_LABELS = frozenset(
    {label for label in _WORDING if label.startswith(("NextTo", "OnTopOf"))}
    | {"NextToChooseDirection", "NextToChooseSide"}
)


def place_phrases(label: str, chosen: str | None = None) -> tuple[str, ...]:
    """The place phrases ("on top of", "north of") that say where A is, or () for other labels.

    A place phrase can follow a noun ("a sign to the right of a table") or lead an
    inverted sentence ("On top of this table are two books.").
    """
    if label not in _PLACE_LABELS:
        return ()
    return tuple(w[len("is "):] for w in relation_wordings(label, chosen) if w.startswith("is "))


#: How a whole is said to be made of its parts ("The mill consists of ...").
COMPOSITION_VERBS = ("consists of", "is made up of", "has")

#: How a caption joins the setting to what it holds ("A village with ...").
CAPTION_LINKS = ("with", "containing")


class Lexicon:
    """Word choice for one description: canonical words, or seeded synonyms for a variant."""

    def __init__(self, choices: Choices) -> None:
        self._choices = choices

    def relation(self, label: str, chosen: str | None = None) -> str:
        return self._choices.pick(relation_wordings(label, chosen))

    def place(self, label: str, chosen: str | None = None) -> str:
        """A place phrase for a place label (see ``place_phrases``)."""
        return self._choices.pick(place_phrases(label, chosen))

    def composition(self) -> str:
        return self._choices.pick(COMPOSITION_VERBS)

    def caption_link(self) -> str:
        return self._choices.pick(CAPTION_LINKS)
