"""The relation vocabulary of scene graphs: the edge labels of Table 1 in the paper.

Every edge of a scene graph carries exactly one of these labels. The layout turns each
into an energy term; the describer words each one that holds (never an ``Implicit*``
one, which constrains the layout but is not described).
"""

from __future__ import annotations

#: Labels that place A next to B (within ``NEXT_TO_DISTANCE`` metres), with or without
#: a direction. ``NextToChooseDirection`` / ``NextToChooseSide`` leave the direction open:
#: the layout picks whichever fits and records it.
NEXT_TO_LABELS: tuple[str, ...] = (
    "NextTo",
    "NextToChooseDirection",
    "NextToChooseSide",
    "NextToNorth",
    "NextToEast",
    "NextToSouth",
    "NextToWest",
    "NextToLeft",
    "NextToRight",
    "NextToFront",
    "NextToBehind",
)

#: Labels that rest A on B's top surface. ``IsPartOf*`` has the same geometry as
#: ``OnTopOf*``; it differs only in wording (A is a part of B, e.g. a sign on a stall).
SUPPORT_LABELS: tuple[str, ...] = (
    "OnTopOf",
    "IsPartOf",
    "OnTopOfMiddle",
    "IsPartOfMiddle",
    "OnTopOfEdge",
    "IsPartOfEdge",
    "OnTopOfFrontEdge",
    "IsPartOfFrontEdge",
)

#: Labels that compare the forward vectors of A and B.
FACING_LABELS: tuple[str, ...] = (
    "FacingTowards",
    "FacingAwayFrom",
    "FacingSameDirection",
    "FacingOrthogonalDirection",
)

#: Structural: a path starts at a junction. Adds nothing to the energy.
PATH_LABELS: tuple[str, ...] = ("PathConnectedTo",)

IMPLICIT_PREFIX = "Implicit"

#: The labels that may take the ``Implicit`` prefix: every geometric one.
_IMPLICITABLE = NEXT_TO_LABELS + SUPPORT_LABELS + FACING_LABELS

#: Every label a rules file may use.
LABELS: frozenset[str] = frozenset(
    NEXT_TO_LABELS
    + SUPPORT_LABELS
    + FACING_LABELS
    + PATH_LABELS
    + tuple(IMPLICIT_PREFIX + label for label in _IMPLICITABLE)
)

#: Directions a ``Choose*`` label may resolve to, as recorded in ``chosen``.
COMPASS_DIRECTIONS = ("north", "east", "south", "west")
SIDE_DIRECTIONS = ("left", "right")


def is_implicit(label: str) -> bool:
    """True for an ``Implicit*`` label: it constrains the layout but is never described."""
    return label.startswith(IMPLICIT_PREFIX)


def base_label(label: str) -> str:
    """The label without its ``Implicit`` prefix (``ImplicitNextTo`` -> ``NextTo``)."""
    return label[len(IMPLICIT_PREFIX):] if is_implicit(label) else label


def is_support(label: str) -> bool:
    """True when the label stacks A on B (A's height follows B's top)."""
    return base_label(label) in SUPPORT_LABELS
