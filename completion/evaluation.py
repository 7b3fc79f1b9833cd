"""Leave-one-out over a plan set: how well the model predicts a held-out plan, against
simple baselines.

For each plan: build the model from all the other plans, take the plan's empty room and
its ``requested`` largest categories (by the floor they take; ties by name) as the
request, and compare what the model says with what the designer drew:

- **room type**: ``choose_types`` (Equation 2) is right when it gives exactly the
  plan's type (wrong when no other plan has a requested category). Baseline: the type
  whose plans have the requested categories most often (the largest product of
  ``P(o | s)``), ignoring the room.
- **categories**: Algorithm 1 run for the plan's true type; precision, recall and F1 of
  the categories it adds against the ones the plan has beyond the request. Baseline
  (co-occurrence only): as many categories as Algorithm 1 added, those most often seen
  with the requested ones (the sum of ``P(o, o_req | s)``), ignoring the room.
- **how many categories**: the absolute difference between the number Algorithm 1 adds
  and the number the plan has beyond the request. Baseline: the mean of that number
  over the type's other plans, rounded, whatever the room. A second baseline for the
  categories themselves, F1 only: the type's usual categories, those at least half its
  other plans have (``P(o | s) >= 0.5``), whatever the room and the request.
- **layout mask**: Equation 4's mask (with the plan's own furniture floor area as the
  occupancy, so this measures the layout alone) against the plan's true mask, both in
  the empty room's door-aware frame; soft IoU ``sum(min) / sum(max)``. Baseline: the
  type's mean mask over the other plans.

Every figure is the mean over plans (and per type); ``report`` sets ours beside each
baseline, with the leave-one-out spread of the difference (``spread``: the standard error
of the mean per-plan difference): a step beats its baseline only by more than that.
A third answer for the categories (F1 only) is ``complete``'s default,
``selection.usual_categories``: co-occurrence at the usual number of categories of
the K plans most like the room (compared on F1 and on the number's error).
"""

from __future__ import annotations

from collections import Counter
from typing import Any

import numpy as np

from scenewright.completion.features import canonical_frame, occupancy_mask, room_parts
from scenewright.completion.layout_mask import amalgamated_mask
from scenewright.completion.model_builder import build_model, floor_pieces
from scenewright.completion.plan_model import PlanModel
from scenewright.completion.selection import choose_types, explore_categories, usual_categories
from scenewright.core.errors import InputError

#: Each measure: its name, the key of ours and of the baseline's figure, what each is,
#: and whether more is better.
COMPARISONS = (
    (
        "room type",
        "type",
        "type_baseline",
        "Equation 2",
        "the type whose plans have the request most often",
        True,
    ),
    (
        "precision",
        "precision",
        "precision_baseline",
        "Algorithm 1",
        "co-occurrence, as many categories",
        True,
    ),
    (
        "recall",
        "recall",
        "recall_baseline",
        "Algorithm 1",
        "co-occurrence, as many categories",
        True,
    ),
    ("F1", "f1", "f1_baseline", "Algorithm 1", "co-occurrence, as many categories", True),
    (
        "F1, co-occurrence at the nearest plans' usual number",
        "f1",
        "f1_cooccurrence",
        "Algorithm 1",
        "co-occurrence, the nearest plans' usual number (complete's default)",
        True,
    ),
    (
        "F1, usual categories",
        "f1",
        "f1_usual",
        "Algorithm 1",
        "the categories of half the type's plans or more",
        True,
    ),
    (
        "number added: error",
        "added_error",
        "added_error_baseline",
        "Algorithm 1",
        "the type's usual number",
        False,
    ),
    (
        "number added: error, usual number of the nearest plans",
        "added_error",
        "added_error_cooccurrence",
        "Algorithm 1",
        "the usual number of the K plans most like the room (complete's default)",
        False,
    ),
    ("mask IoU", "mask_iou", "mask_iou_baseline", "Equation 4", "the type's mean mask", True),
)
METRICS = tuple(dict.fromkeys(key for comparison in COMPARISONS for key in comparison[1:3]))


def request_of(plan, model: PlanModel, size: int) -> dict[str, int]:
    """The ``size`` categories of ``plan`` taking the most floor (all of its pieces of each), with their counts."""
    counts = Counter(piece.category for piece in plan.furniture)
    area = {
        name: model.categories[name].floor_area * counts[name]
        for name in counts
        if name in model.categories
    }
    chosen = sorted(area, key=lambda name: (-area[name], name))[:size]
    return {name: counts[name] for name in chosen}


def evaluate_plan(plan, model: PlanModel, requested_size: int) -> dict:
    """The metrics (``METRICS``) for one held-out ``plan`` under a model built without
    it, and ``miss``: when Equation 2 or the baseline gets its type wrong, a line saying
    what each answered (else None)."""
    requested = request_of(plan, model, requested_size)
    entry = model.types[plan.type]
    truth = {piece.category for piece in plan.furniture} - set(requested)
    try:
        predicted = choose_types(model, requested, plan.room.area).types
    except InputError:  # no other plan has a requested category
        predicted = ()
    baseline_type = max(
        sorted(model.types),
        key=lambda t: float(np.prod([model.types[t].probability(n) for n in requested])),
    )
    parts = room_parts(plan.room, entry.mean_area)
    explored = explore_categories(model, plan.type, requested, plan.room.area, parts)
    added = set(explored.categories) - set(requested)
    together = {tuple(pair.pair): pair.cooccurrence for pair in entry.pairs}
    candidates = sorted(name for name in entry.categories if name not in requested)
    score = {
        name: sum(together.get((min(name, r), max(name, r)), 0.0) for r in requested)
        for name in candidates
    }
    baseline_added = set(sorted(candidates, key=lambda name: (-score[name], name))[: len(added)])
    usual_set = usual_categories(model, plan.type, requested, plan.room.area, parts)
    cooccurrence_added = set(usual_set.categories) - set(requested)
    usual = np.mean(
        [len(set(p.counts) - set(requested)) for p in model.plans if p.type == plan.type]
    )
    common = {name for name, seen in entry.categories.items() if seen.p >= 0.5} - set(requested)
    floor = floor_pieces(plan)
    true_mask = occupancy_mask(plan.room, floor, canonical_frame(plan.room))
    counts = Counter(piece.category for piece in plan.furniture)
    layout = amalgamated_mask(
        model, plan.type, plan.room, {n: c for n, c in counts.items() if n in model.categories}
    )
    mean_mask = np.mean([np.asarray(p.mask) for p in model.plans if p.type == plan.type], axis=0)
    return {
        "type": float(predicted == (plan.type,)),
        "type_baseline": float(baseline_type == plan.type),
        "precision": _share(added & truth, added),
        "recall": _share(added & truth, truth),
        "f1": _f1(added, truth),
        "precision_baseline": _share(baseline_added & truth, baseline_added),
        "recall_baseline": _share(baseline_added & truth, truth),
        "f1_baseline": _f1(baseline_added, truth),
        "f1_usual": _f1(common, truth),
        "f1_cooccurrence": _f1(cooccurrence_added, truth),
        "added_error": float(abs(len(added) - len(truth))),
        "added_error_baseline": float(abs(int(round(float(usual))) - len(truth))),
        "added_error_cooccurrence": float(abs(len(cooccurrence_added) - len(truth))),
        "mask_iou": soft_iou(layout.mask, true_mask),
        "mask_iou_baseline": soft_iou(mean_mask, true_mask),
        "miss": None
        if predicted == (plan.type,) and baseline_type == plan.type
        else (
            f"{plan.id} ({plan.room.area:.1f} m2, {_listed(requested)}): Equation 2 "
            f"{' + '.join(predicted) or 'none'}, baseline {baseline_type}"
        ),
    }


def leave_one_out(plans, requested_size: int = 1) -> dict[str, dict]:
    """Mean metrics per type and over all plans (``"all"``, which also lists the plans
    whose type either side got wrong under ``"misses"``); every type needs two plans."""
    plans = sorted(plans, key=lambda plan: plan.id)
    rows: dict[str, list[dict[str, float]]] = {}
    for plan in plans:
        model = build_model([other for other in plans if other.id != plan.id])
        if plan.type in model.types:
            rows.setdefault(plan.type, []).append(evaluate_plan(plan, model, requested_size))
    table: dict[str, dict[str, Any]] = {
        room_type: _means(found) for room_type, found in sorted(rows.items())
    }
    everything = [row for found in rows.values() for row in found]
    table["all"] = _means(everything)
    table["all"]["spread"] = {
        f"{ours}-{base}": spread([row[ours] - row[base] for row in everything])
        for _, ours, base, *_ in COMPARISONS
    }
    table["all"]["misses"] = [
        row["miss"] for found in rows.values() for row in found if row["miss"]
    ]
    return table


def spread(differences) -> float:
    """The leave-one-out spread of a mean difference: the standard error of the mean of
    the per-plan differences (their standard deviation over the square root of their
    number; 0 for fewer than two)."""
    values = np.asarray(differences, dtype=float)
    if len(values) < 2:
        return 0.0
    return round(float(values.std(ddof=1) / np.sqrt(len(values))), 3)


def _means(rows: list[dict[str, float]]) -> dict[str, float]:
    return {
        metric: round(float(np.mean([row[metric] for row in rows])), 3) for metric in METRICS
    } | {"plans": len(rows)}


def report(table: dict[str, dict], requested_size: int) -> str:
    """``leave_one_out``'s table as text: per type each measure as ours / baseline, then
    over all plans each measure in words with which side is better and by how much."""
    plural = "category" if requested_size == 1 else "categories"
    lines = [
        f"Leave-one-out over {table['all']['plans']} plans, {requested_size} requested {plural}; "
        "each cell: ours / baseline.",
        "",
        "| room type | plans | " + " | ".join(c[0] for c in COMPARISONS) + " |",
        "|---|---|" + "---|" * len(COMPARISONS),
    ]
    for name, row in table.items():
        cells = [f"{row[ours]:.3f} / {row[base]:.3f}" for _, ours, base, *_ in COMPARISONS]
        lines.append(f"| {name} | {row['plans']} | " + " | ".join(cells) + " |")
    lines += ["", "Over all plans:"]
    for name, ours, base, what, baseline, more_is_better in COMPARISONS:
        a, b = table["all"][ours], table["all"][base]
        better = (a > b) == more_is_better
        margin = table["all"].get("spread", {}).get(f"{ours}-{base}", 0.0)
        verdict = (
            "equal"
            if a == b
            else f"{'ours' if better else 'the baseline'} better by {abs(a - b):.3f}"
        )
        if a != b:
            verdict += f" (spread {margin:.3f}: " + (
                "beyond it)" if abs(a - b) > margin else "within it)"
            )
        lines.append(f"- {name}: {what} {a:.3f}, baseline ({baseline}) {b:.3f}: {verdict}")
    misses = table["all"].get("misses", ())
    lines += [
        "",
        "Room types missed by either side:" if misses else "No room type missed by either side.",
    ]
    lines += [f"- {miss}" for miss in misses]
    return "\n".join(lines) + "\n"


def _listed(requested: dict[str, int]) -> str:
    return ", ".join(
        name if count == 1 else f"{name} x{count}" for name, count in requested.items()
    )


def _share(part: set, whole: set) -> float:
    return len(part) / len(whole) if whole else 1.0


def _f1(chosen: set, truth: set) -> float:
    """The harmonic mean of precision and recall (1 when both sets are empty, 0 when nothing is right)."""
    precision, recall = _share(chosen & truth, chosen), _share(chosen & truth, truth)
    return 2 * precision * recall / (precision + recall) if precision + recall > 0 else 0.0


def soft_iou(first: np.ndarray, second: np.ndarray) -> float:
    """Soft IoU of two masks of one shape: the sum of their minima over the sum of their
    maxima (1 when both are empty)."""
    union = np.maximum(first, second).sum()
    return float(np.minimum(first, second).sum() / union) if union > 0 else 1.0
