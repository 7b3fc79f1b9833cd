"""What each relation family does in the layout, one module per family, in one table.

A relation label's family (``scenewright.core.relations``) says which geometry it asks
for. Everything the layout does by family is the family's ``LayoutFamily`` entry here:
its energy and measures (Table 1 of the paper), the threshold that decides whether it
holds and the words for when it does not (``evaluate``, ``satisfied``, ``complaint``),
how the problem's compiler checks its ends, how a placement puts A where it holds (and B, for a
data-driven move of the target), what a placement by another relation snaps onto, how
the initial placement orders and anchors items by it. The compiler, the placement
(``placement.Placer``), the moves and the initial placement look the entry up instead
of asking for a family by name, so a new family is a module here and a line in
``LAYOUT_FAMILIES``.
"""

from __future__ import annotations

from scenewright.core.relations import FAMILIES

from ..params import LayoutParams
from ..relation_terms import Measure
from ..state import State
from ..terms import RelationTerm
from . import alignment, clearance, facing, next_to, support, wall
from .entry import LayoutFamily

#: One entry per geometric family of the relation registry (in the order
#: ``Placer.place_by`` tries snapping families in). ``structural`` relations
#: become path starts when the problem is compiled and are never placed.
LAYOUT_FAMILIES: dict[str, LayoutFamily] = {
    "next_to": next_to.FAMILY,
    "facing": facing.FAMILY,
    "support": support.FAMILY,
    "wall": wall.FAMILY,
    "alignment": alignment.FAMILY,
    "clearance": clearance.FAMILY,
}

_missing = set(FAMILIES) - set(LAYOUT_FAMILIES) - {"structural"}
if _missing:  # a registry family the layout cannot score or place: refuse at start-up
    raise ImportError(f"the layout implements no relation family {', '.join(sorted(_missing))}")


def placing(terms: list[RelationTerm]) -> list[RelationTerm]:
    """Those of ``terms`` (one item's relations) that place it: of families that place,
    one that places only alone (``LayoutFamily.places_alone``) where no other does."""
    found = [t for t in terms if LAYOUT_FAMILIES[t.spec.family].places]
    others = [t for t in found if not LAYOUT_FAMILIES[t.spec.family].places_alone]
    return others or found


def evaluate(term: RelationTerm, state: State, params: LayoutParams) -> Measure:
    """The energy (>= 0) of one relation edge and its geometric measures."""
    return LAYOUT_FAMILIES[term.spec.family].measure(term, state, params)


def satisfied(term: RelationTerm, measure: Measure, params: LayoutParams) -> bool:
    """Whether the relation holds geometrically (the thresholds of ``report``)."""
    return LAYOUT_FAMILIES[term.spec.family].holds(term, measure, params)


def complaint(term: RelationTerm, measure: Measure, params: LayoutParams) -> str:
    """What is wrong with a relation that does not hold, in words."""
    return LAYOUT_FAMILIES[term.spec.family].complaint(term, measure, params)
