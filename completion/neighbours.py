"""How a piece stands to the windows and to the pieces around it, learned from the
plans next to ``stances`` (which says how it stands to the walls): the tests each plan
piece is measured by, and how ``furnishing`` reads the learned shares. Per category
the model keeps (``plan_model.CategoryStance``):

- ``window``: the share of its pieces (of those whose plan has a window) that stand
  *under a window*: the back touches a wall (``stances.touched_walls``) and the centre
  lies within the span of a window in that wall (a desk under the window);
- ``close``: per category the share of its pieces away from the walls that stand
  *close before* a piece of it: before it (``stances.before_of``) with at most
  ``CLOSE_GAP`` between the two footprints (a coffee table 0.45 m before its sofa; a
  dining table a metre or more from a sideboard stands free in the room, not before it);
- ``facing``: per category the share of its pieces that *face* a piece of it: the
  first piece the ray along the piece's forward axis from its centre crosses, within
  ``FACING_REACH`` of its front, looking past what stands before it (a sofa faces the
  television stand across the coffee table before it, an armchair the coffee table);
- ``beside``: per category the share of its pieces that stand *beside* a piece of it:
  the centre off that piece's left or right side, not wholly before or behind it, the
  footprints within ``BESIDE_GAP`` (an armchair beside the coffee table).

``facing`` and ``beside`` are over the pieces whose plan has a piece of that category
besides them, neither flat nor an accessory; ``close`` over those away from the walls.
``stances`` learns the shares with these tests and reads them: a category is placed
by one when more than ``stances.MOST`` of its pieces stood so (``stances.under_window``,
``facing_target``, ``beside_target``, ``stance`` for close before), with no rule
written per category.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

from scenewright.core.frames import to_local
from scenewright.core.geometry import rect_distance

if TYPE_CHECKING:
    from scenewright.completion.floor_plan import Furniture
    from scenewright.core.room import Room, Wall

#: Metres between two footprints within which one stands close before the other.
CLOSE_GAP = 0.6
#: Metres beyond a piece's front within which what its forward ray crosses is what it faces.
FACING_REACH = 4.0
#: Metres between two footprints within which one stands beside the other.
BESIDE_GAP = 1.0
#: A share over fewer pieces than this is no evidence (the one armchair in a dining room
#: faced its table): the shares above keep only categories seen with at least this many.
LEAST = 5


# -- the tests a plan piece is measured by ------------------------------------------------


def is_under_window(piece: Furniture, room: Room, back: Wall | None) -> bool:
    """Whether ``piece``, whose back touches the wall ``back`` (None: no wall), stands
    under a window of ``room`` (module docstring)."""
    if back is None:
        return False
    u, _ = back.to_wall(*piece.center)
    return any(
        window.wall == back.id and window.span[0] <= u <= window.span[1] for window in room.windows
    )


def gap_before(piece: Furniture, other: Furniture) -> float:
    """Metres between ``other``'s front side and the near side of ``piece``, which stands
    before it (``stances.before_of``)."""
    _, lz = to_local(*other.center, other.yaw, *piece.center)
    return lz - other.size[1] / 2.0 - piece.size[1] / 2.0


def faced(
    piece: Furniture, others: Sequence[Furniture], before: dict[str, str]
) -> Furniture | None:
    """The piece of ``others`` that ``piece`` faces (module docstring), or None;
    ``before``: per piece id the id of the piece it stands before, which ``piece``
    looks past."""
    best = None
    for other in others:
        if before.get(other.id) == piece.id:
            continue
        corners = [to_local(*piece.center, piece.yaw, *corner) for corner in other.corners]
        xs = [x for x, _ in corners]
        zs = [z for _, z in corners]
        # The forward ray (x = 0, z > 0) crosses the footprint: its corners on both sides.
        if not (min(xs) <= 0.0 <= max(xs)) or max(zs) <= 0.0:
            continue
        ahead = max(min(zs), 0.0) - piece.size[1] / 2.0
        if ahead <= FACING_REACH and (best is None or (ahead, other.id) < best[0]):
            best = ((ahead, other.id), other)
    return best[1] if best is not None else None


def is_beside(piece: Furniture, other: Furniture) -> bool:
    """Whether ``piece`` stands beside ``other`` (module docstring)."""
    lx, lz = to_local(*other.center, other.yaw, *piece.center)
    if abs(lx) <= other.size[0] / 2.0 or abs(lz) > (other.size[1] + piece.size[1]) / 2.0:
        return False
    return rect_distance(piece.rect, other.rect) <= BESIDE_GAP
