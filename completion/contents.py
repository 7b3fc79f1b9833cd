"""What a completed room holds (step 2 of ``complete``): the room's type(s) (Equation 2,
``selection.choose_types``), per type its categories (Algorithm 1,
``selection.explore_categories``) with the room's area shared among the types by their
mean areas, and the layout mask of the first type (Equation 4,
``layout_mask.amalgamated_mask``). A rectangular room of several types is split by
virtual walls (``regions``): each type's categories and mask come from its own region.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, cast

from scenewright.completion.plan_model import PlanModel

from .request import Request

if TYPE_CHECKING:  # for the annotation only: choose_contents imports it when it runs
    from .layout_mask import LayoutMask, RegionMasks


@dataclass(frozen=True)
class Contents:
    """The room's types, per type Algorithm 1's answer, the merged counts (category ->
    number, requested first) and the layout mask: the first type's ``LayoutMask`` over
    the whole room, or, for a room split by virtual walls (``regions``, one per type),
    a ``layout_mask.RegionMasks``."""

    types: tuple[str, ...]
    owners: dict[str, str]
    explorations: dict
    counts: dict[str, int]
    mask: LayoutMask | RegionMasks
    regions: tuple = ()

    def region_masks(self) -> RegionMasks:
        """The masks of a room split by virtual walls (``regions`` not empty)."""
        assert self.regions, "a room of one region has a single LayoutMask"
        return cast("RegionMasks", self.mask)

    def room_mask(self) -> LayoutMask:
        """The mask of a room of one region (``regions`` empty)."""
        assert not self.regions, "a room split by virtual walls has RegionMasks"
        return cast("LayoutMask", self.mask)


def choose_contents(model: PlanModel, request: Request, *, split: bool = True) -> Contents:
    """Equation 2, then per type the categories (``request.categories``: co-occurrence
    at the type's usual number, or Algorithm 1), then the layout mask
    (``request.mask``: the type's mean mask, or Equation 4). One type, or a room
    that is not split (``split`` False, or not a rectangle): the room's area is shared
    among the types by their mean areas, and the mask is the first (largest) type's
    over the whole room. Several types in a rectangle: the room is split by virtual
    walls (``regions.split_room``) and each type's categories and mask are those of
    its own region, as a room of its own."""
    from scenewright.completion.features import room_parts
    from scenewright.completion.layout_mask import RegionMasks, choose_mask
    from scenewright.completion.regions import split_room
    from scenewright.completion.selection import check_counts, choose_categories, choose_types

    explore_categories = choose_categories(request.categories)
    amalgamated_mask = choose_mask(request.mask)

    room = request.room
    choice = choose_types(
        model, request.requested, room.area
    )  # first: it names a category no plan has
    check_counts(model, request.requested)
    regions = split_room(model, room, choice.types) if split else ()
    region_of = {region.room_type: k for k, region in enumerate(regions)}
    total = sum(model.types[t].mean_area for t in choice.types)
    explorations = {}
    counts: dict[str, int] = dict(sorted(request.requested.items()))
    for room_type in choice.types:
        owned = {
            name: n for name, n in request.requested.items() if choice.owners[name] == room_type
        }
        if regions:
            part = regions[region_of[room_type]].room
            share, parts = part.area, room_parts(part, model.types[room_type].mean_area)
        else:
            share = room.area * model.types[room_type].mean_area / total
            parts = room_parts(room, model.types[room_type].mean_area)
        exploration = explore_categories(model, room_type, owned, share, parts)
        explorations[room_type] = exploration
        for name, n in exploration.counts.items():
            if name not in request.requested:
                counts[name] = max(counts.get(name, 0), n)
    if not regions:
        mask = amalgamated_mask(model, choice.types[0], room, counts)
        return Contents(choice.types, choice.owners, explorations, counts, mask)
    owners = category_owners(model, choice.types, choice.owners, explorations, counts)
    masks = tuple(
        amalgamated_mask(
            model,
            region.room_type,
            region.room,
            {name: n for name, n in counts.items() if owners[name] == region.room_type},
        )
        for region in regions
    )
    mask = RegionMasks(regions, masks, {name: region_of[owner] for name, owner in owners.items()})
    return Contents(choice.types, choice.owners, explorations, counts, mask, regions)


def category_owners(
    model: PlanModel, types, requested_owners: dict, explorations: dict, counts
) -> dict[str, str]:
    """Category -> the type (region) it belongs to: a requested one its Equation 2
    owner (``requested_owners``); an added one the type, of those whose Algorithm 1
    chose it, that has it most often (the paper's rule for requested categories,
    ``max P(o | s)``); ties: the earlier of ``types``."""
    owners = {}
    for name in counts:
        if name in requested_owners:
            owners[name] = requested_owners[name]
            continue
        choosers = [t for t in types if name in explorations[t].counts] or list(types)
        owners[name] = max(
            choosers,
            key=lambda t: (
                model.types[t].probability(name),
                -list(types).index(t),
            ),
        )
    return owners
