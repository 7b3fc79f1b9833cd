"""Where furniture should go in a room: the layout mask amalgamated from the most similar
plans (the paper's Equation 4, Section 5.3).

The room's feature ``f_r`` is worked out with the chosen categories' floor areas as its
occupancy; the ``K`` plans of the type nearest to it (Euclidean distance over the four
parts) are the references. If they fall in several mask clusters, the cluster with most
of them is used (ties: the one holding the nearest plan), and its members' masks are
averaged with weights ``(1 / D_k) / sum_j (1 / D_j)``. The paper prints the weight as
``D_k / sum_j D_j``, which would give the least similar plan the most say, against its
own text (the plans "with similar room features" guide the layout); inverse distances
are what it means. A reference at distance 0 takes the whole weight.

The mask is in the room's door-aware canonical frame (``features``): ``mask_at`` reads it
at room positions, which is how a layout uses it; ``floor_mask`` lays it over the room's
bounding box as the layout energy's ``mask`` part takes it (``generator.layout.mask_term``).
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import TYPE_CHECKING

import numpy as np

from scenewright.completion import MASK_METHODS
from scenewright.completion.features import (
    CanonicalFrame,
    canonical_frame,
    room_centre,
    room_feature,
)
from scenewright.completion.plan_model import PlanEntry, PlanModel
from scenewright.completion.selection import K

if TYPE_CHECKING:
    from scenewright.generator.layout.mask_term import FloorMask

#: Distances below this count as 0 (the same room).
SAME = 1e-9
#: A composite room's region term per piece: the cost, times the layout's ``mask_weight``,
#: of a piece standing wholly beyond its region's virtual walls (a layout mask's is at most 1).
REGION_WEIGHT = 3.0


@dataclass(frozen=True)
class LayoutMask:
    """The amalgamated ``mask`` (10, 10) in the room's canonical ``frame``, the room's
    feature, and the references used with their weights (plan id -> weight)."""

    mask: np.ndarray
    frame: CanonicalFrame
    feature: np.ndarray
    weights: dict[str, float]


def amalgamated_mask(
    model: PlanModel, room_type: str, room, counts: dict[str, int], k: int = K
) -> LayoutMask:
    """The layout mask of ``room`` holding ``counts`` (category -> number) of ``room_type``."""
    entry = model.types[room_type]
    floor = sum(model.categories[name].floor_area * n for name, n in counts.items())
    feature = room_feature(room, floor, entry.mean_area)
    plans = [plan for plan in model.plans if plan.type == room_type]
    distance = {
        plan.id: float(np.linalg.norm(np.asarray(plan.feature) - feature)) for plan in plans
    }
    nearest = sorted(plans, key=lambda plan: (distance[plan.id], plan.id))[:k]
    by_cluster: dict[int, list[PlanEntry]] = {}
    for plan in nearest:  # nearest first, so each group's first member is its nearest
        by_cluster.setdefault(plan.cluster, []).append(plan)
    group = max(by_cluster.values(), key=lambda members: (len(members), -nearest.index(members[0])))
    if distance[group[0].id] <= SAME:
        weights = {plan.id: float(distance[plan.id] <= SAME) for plan in group}
        total = sum(weights.values())
        weights = {name: value / total for name, value in weights.items()}
    else:
        inverse = {plan.id: 1.0 / distance[plan.id] for plan in group}
        total = sum(inverse.values())
        weights = {name: value / total for name, value in inverse.items()}
    mask = sum(weights[plan.id] * np.asarray(plan.mask) for plan in group)
    return LayoutMask(np.asarray(mask), canonical_frame(room), feature, weights)


def mean_mask(
    model: PlanModel, room_type: str, room, counts: dict[str, int], k: int = K
) -> LayoutMask:
    """The type's mean mask, ``complete``'s default (``--mask mean``): every plan of the
    type weighs the same, whatever the room (``counts`` and ``k`` only make the feature
    it records). The leave-one-out measured Equation 4 no better than this
    (docs/completion.md, "How well it predicts")."""
    entry = model.types[room_type]
    floor = sum(model.categories[name].floor_area * n for name, n in counts.items())
    feature = room_feature(room, floor, entry.mean_area)
    plans = sorted((plan for plan in model.plans if plan.type == room_type), key=lambda p: p.id)
    weights = {plan.id: 1.0 / len(plans) for plan in plans}
    mask = np.mean([np.asarray(plan.mask) for plan in plans], axis=0)
    return LayoutMask(np.asarray(mask), canonical_frame(room), feature, weights)


def choose_mask(method: str):
    """The mask step named ``method`` (``MASK_METHODS``): ``mean_mask`` for ``mean``,
    Equation 4 (``amalgamated_mask``) for ``equation4``."""
    if method not in MASK_METHODS:
        from scenewright.core.errors import InputError

        raise InputError(f"mask method {method!r}: choose one of {', '.join(MASK_METHODS)}")
    return mean_mask if method == "mean" else amalgamated_mask


def mask_at(layout: LayoutMask, room, points) -> np.ndarray:
    """(n,) the mask's value at room points (n, 2): the cell each falls in, in the frame."""
    width, depth = room.extent
    long_side, short_side = (depth, width) if layout.frame.transpose else (width, depth)
    local = layout.frame.apply(np.asarray(points, dtype=float) - room_centre(room))
    size = layout.mask.shape[0]
    columns = np.clip(((local[:, 0] / long_side + 0.5) * size).astype(int), 0, size - 1)
    rows = np.clip(((local[:, 1] / short_side + 0.5) * size).astype(int), 0, size - 1)
    return layout.mask[rows, columns]


def floor_mask(layout: LayoutMask, room, boxes) -> FloorMask:
    """The mask over the room's bounding box, north-west cell first (rows along z), as a
    ``FloorMask`` for the layout pieces ``boxes`` (ids). The canonical frame only turns
    and mirrors the room, so each canonical cell is one cell of this grid: it is read
    at the cells' centres with ``mask_at``."""
    from scenewright.generator.layout.mask_term import FloorMask

    corners = np.array(room.corners)
    (x0, z0), (x1, z1) = corners.min(axis=0), corners.max(axis=0)
    size = layout.mask.shape[0]
    xs = x0 + (np.arange(size) + 0.5) * (x1 - x0) / size
    zs = z0 + (np.arange(size) + 0.5) * (z1 - z0) / size
    grid_x, grid_z = np.meshgrid(xs, zs)  # (size, size): row = z
    values = mask_at(layout, room, np.column_stack([grid_x.ravel(), grid_z.ravel()])).reshape(
        size, size
    )
    return FloorMask(
        np.clip(values, 0.0, 1.0), (float(x0), float(z0), float(x1), float(z1)), tuple(boxes)
    )


@dataclass(frozen=True)
class RegionMasks:
    """The layout masks of a composite room (``regions``): per region its type's mask
    in the region's own canonical frame (``masks``, one per region, in order), and the
    region each category belongs to (``owners``: category -> region index)."""

    regions: tuple
    masks: tuple[LayoutMask, ...]
    owners: dict[str, int]

    def at(self, category: str, points) -> np.ndarray:
        """(n,) the mask of the category's region at room points (n, 2); 0 outside
        the region (the virtual walls bound it)."""
        k = self.owners[category]
        region, points = self.regions[k], np.asarray(points, dtype=float).reshape(-1, 2)
        return np.where(region.contains(points), mask_at(self.masks[k], region.room, points), 0.0)


def mask_values(mask, room, category: str, points) -> np.ndarray:
    """(n,) where a piece of ``category`` should stand, at room points (n, 2): the
    room's ``LayoutMask`` read by ``mask_at``, or a composite room's ``RegionMasks``
    read for the category's region."""
    if isinstance(mask, RegionMasks):
        return mask.at(category, points)
    return mask_at(mask, room, points)


def region_floor_masks(
    masks: RegionMasks, boxes_by_region, large, *, region_weight: float = REGION_WEIGHT
) -> list[FloorMask]:
    """The layout energy's masks for a composite room, per region: its layout mask over
    its rectangle for the region's ``large`` pieces (ids), reading 0 beyond it; and for
    every piece of the region a mask of 1 over the rectangle and 0 beyond it, weighing
    ``region_weight``, that ``confine``s them (a piece whose centre crosses a virtual
    wall is a problem of the layout's verdict). ``boxes_by_region``: per region the ids
    of the pieces that belong there."""
    from scenewright.generator.layout.mask_term import FloorMask

    out = []
    for k, (region, layout) in enumerate(zip(masks.regions, masks.masks, strict=False)):
        ids = tuple(boxes_by_region[k])
        pulled = [box for box in ids if box in large]
        if pulled:
            out.append(replace(floor_mask(layout, region.room, pulled), outside=0.0))
        if ids:
            out.append(
                FloorMask(
                    np.ones((1, 1)),
                    tuple(region.bounds),
                    ids,
                    outside=0.0,
                    weight=region_weight,
                    confine=True,
                )
            )
    return out
