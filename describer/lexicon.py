"""The words for each relation label and the describer's other fixed phrases.

Every relation label of Table 1 that the text may state (all but ``Implicit*`` and
``PathConnectedTo``) has one or more verb phrases, written in the third person singular
with the object to follow ("is next to", "faces away from"); the first is canonical,
the others are synonyms for paraphrase variants. Direction words are B's: "A is to the
left of B" means A is on B's own left (B's local +X), "in front of B" on B's forward
side. Where the object phrase names a part of a room that the registry's words do not
expect (``InCorner``'s words name a wall, "stands in a corner by the east wall"; the
text names the corner itself), ``PLACE_WORDINGS`` has the words for that part.
"""

from __future__ import annotations

from scenewright.core.relations import RELATIONS

from .paraphrase import Choices


def is_described(label: str) -> bool:
    """Labels the text may state when they hold: not ``Implicit*``, not structural
    (``PathConnectedTo`` is told as the road network: "roads meeting at ...")."""
    return label in RELATIONS and RELATIONS[label].described


def is_symmetric(label: str) -> bool:
    """Labels whose statement says the same read either way round ("A is next to B" is
    "B is next to A"); the describer states such a pair once."""
    return RELATIONS[label].symmetric


#: The verb phrases for a relation whose object phrase names this kind of room part
#: rather than what the registry's words expect: a wall label's words name a wall or a
#: window, but ``InCorner`` is told by the corner the object stands in.
PLACE_WORDINGS: dict[str, tuple[str, ...]] = {"corner": ("stands in", "is in")}


def relation_wordings(
    label: str, chosen: str | None = None, place_kind: str | None = None
) -> tuple[str, ...]:
    """The verb phrases that state ``label`` (canonical first), from the registry.

    A label that chooses its direction (``NextToChooseDirection``) is worded from the
    direction the layout chose; without a valid one it falls back to plain "next to",
    which holds for every next-to label. ``place_kind``: the kind of room part the
    object phrase names ("corner"), when it is one (see ``PLACE_WORDINGS``).
    """
    spec = RELATIONS[label]
    if not spec.described:
        raise KeyError(f"relation label {label!r} is never stated")
    if place_kind in PLACE_WORDINGS:
        return PLACE_WORDINGS[place_kind]
    return spec.wordings_for(chosen)


def place_phrases(
    label: str, chosen: str | None = None, place_kind: str | None = None
) -> tuple[str, ...]:
    """The place phrases ("on top of", "north of") that say where A is, or () for other labels.

    A place phrase can follow a noun ("a sign to the right of a table") or lead an
    inverted sentence ("On top of this table are two books.").
    """
    if not RELATIONS[label].place:
        return ()
    return tuple(
        w[len("is ") :] for w in relation_wordings(label, chosen, place_kind) if w.startswith("is ")
    )


#: How a whole is said to be made of its parts ("The mill consists of ...").
COMPOSITION_VERBS = ("consists of", "is made up of", "has")

#: How a caption joins the setting to what it holds ("A village with ...").
CAPTION_LINKS = ("with", "containing")


class Lexicon:
    """Word choice for one description: canonical words, or seeded synonyms for a variant."""

    def __init__(self, choices: Choices) -> None:
        self._choices = choices

    def relation(self, label: str, chosen: str | None = None, place_kind: str | None = None) -> str:
        return self._choices.pick(relation_wordings(label, chosen, place_kind))

    def place(self, label: str, chosen: str | None = None) -> str:
        """A place phrase for a place label (see ``place_phrases``)."""
        return self._choices.pick(place_phrases(label, chosen))

    def composition(self) -> str:
        return self._choices.pick(COMPOSITION_VERBS)

    def caption_link(self) -> str:
        return self._choices.pick(CAPTION_LINKS)
