"""Why Equation 4's layout mask does no better than the type's mean mask, leave-one-out.

    .venv/bin/python benchmarks/bench_plan_masks.py

For each shipped plan held out (the model built from the others), with the plans' own
masks in their door-aware canonical frames (``features.canonical_frame``), it prints per
type and over all plans the mean soft IoU with the held-out plan's mask of:

- ``eq4``: Equation 4's mask (``layout_mask.amalgamated_mask``, the plan's furniture as
  the occupancy), as ``plans evaluate`` measures it;
- ``mean``: the type's mean mask over the other plans (``plans evaluate``'s baseline);
- ``best``: the single other plan of the type whose mask matches best, and ``best10``:
  the mean of the 10 best-matching masks. Both look at the answer; they bound what any
  choice of K = 10 reference plans could reach.

Then, over every pair of plans of a type, how well a room feature predicts how alike
two plans' masks are: the Spearman rank correlation between minus the distance in each
part of ``f_r`` (and in all four, as Equation 4 compares rooms) and the pair's mask IoU
(1 would be a perfect predictor, 0 none); and the mean IoU of the pairs whose door and
window stand on the same walls of the canonical frame against the others (the angle
between door and window, the feature's only word on the openings, does not tell a door
and window on the two short walls from a door and window on the two long ones).

Prints figures only; nothing is asserted. One process, one core.
"""

from __future__ import annotations

import itertools
from collections import Counter

import numpy as np
from scipy.stats import spearmanr

from scenewright.completion import shipped_plans_dir
from scenewright.completion.evaluation import soft_iou
from scenewright.completion.features import canonical_frame, occupancy_mask, room_centre
from scenewright.completion.floor_plan import load_plans
from scenewright.completion.layout_mask import amalgamated_mask
from scenewright.completion.model_builder import build_model, floor_pieces

PARTS = ("angle", "occupancy", "aspect", "relative size")


def sides(room, openings) -> tuple[str, ...]:
    """The walls of the canonical frame (top, bottom, left, right) the openings stand on."""
    frame = canonical_frame(room)
    width, depth = room.extent
    long_side, short_side = (depth, width) if frame.transpose else (width, depth)
    found = set()
    for opening in openings:
        x, z = frame.apply(np.asarray(opening.center) - room_centre(room))[0] / (
            long_side,
            short_side,
        )
        gaps = {"top": z + 0.5, "bottom": 0.5 - z, "left": x + 0.5, "right": 0.5 - x}
        found.add(min(sorted(gaps), key=lambda side: gaps[side]))
    return tuple(sorted(found))


def main() -> None:
    plans = sorted(load_plans(shipped_plans_dir()), key=lambda plan: plan.id)
    truth = {
        plan.id: occupancy_mask(plan.room, floor_pieces(plan), canonical_frame(plan.room))
        for plan in plans
    }
    rows: dict[str, list[tuple[float, ...]]] = {}
    for plan in plans:
        model = build_model([other for other in plans if other.id != plan.id])
        others = [other.id for other in plans if other.type == plan.type and other.id != plan.id]
        counts = Counter(piece.category for piece in plan.furniture)
        layout = amalgamated_mask(
            model,
            plan.type,
            plan.room,
            {n: c for n, c in counts.items() if n in model.categories},
        )
        alike = {other: soft_iou(truth[other], truth[plan.id]) for other in others}
        nearest = sorted(others, key=lambda other: -alike[other])[:10]
        rows.setdefault(plan.type, []).append(
            (
                soft_iou(layout.mask, truth[plan.id]),
                soft_iou(np.mean([truth[other] for other in others], axis=0), truth[plan.id]),
                alike[nearest[0]],
                soft_iou(np.mean([truth[other] for other in nearest], axis=0), truth[plan.id]),
            )
        )
    print("| room type | plans | eq4 | mean | best | best10 |")
    print("|---|---|---|---|---|---|")
    for name, found in [
        *sorted(rows.items()),
        ("all", [row for rows_of_type in rows.values() for row in rows_of_type]),
    ]:
        print(
            f"| {name} | {len(found)} | "
            + " | ".join(f"{value:.3f}" for value in np.mean(found, axis=0))
            + " |"
        )

    model = build_model(plans)
    feature = {entry.id: np.asarray(entry.feature) for entry in model.plans}
    openings = {
        plan.id: (sides(plan.room, plan.room.doors), sides(plan.room, plan.room.windows))
        for plan in plans
    }
    print()
    print(
        "| room type | pairs | "
        + " | ".join(f"rho {part}" for part in PARTS)
        + " | rho f_r | IoU same walls (pairs) | IoU other walls |"
    )
    print("|---|---|" + "---|" * (len(PARTS) + 3))
    for room_type in sorted(rows):
        ids = [plan.id for plan in plans if plan.type == room_type]
        pairs = list(itertools.combinations(ids, 2))
        iou = [soft_iou(truth[a], truth[b]) for a, b in pairs]
        rho = [
            spearmanr([-abs(feature[a][k] - feature[b][k]) for a, b in pairs], iou).correlation
            for k in range(4)
        ]
        rho.append(
            spearmanr([-np.linalg.norm(feature[a] - feature[b]) for a, b in pairs], iou).correlation
        )
        same = [
            value for (a, b), value in zip(pairs, iou, strict=False) if openings[a] == openings[b]
        ]
        other = [
            value for (a, b), value in zip(pairs, iou, strict=False) if openings[a] != openings[b]
        ]
        print(
            f"| {room_type} | {len(pairs)} | "
            + " | ".join(f"{value:+.2f}" for value in rho)
            + f" | {np.mean(same):.3f} ({len(same)}) | {np.mean(other):.3f} |"
        )


if __name__ == "__main__":
    main()
