"""Accessory placement, leave-one-out: do the completed rooms put what stands on or at a
piece where the held-out plan has it?

    .venv/bin/python benchmarks/bench_accessories.py              # every shipped plan, seed 0
    .venv/bin/python benchmarks/bench_accessories.py --only bedroom --seeds 2

For each plan: the plan model is built from the other plans; the plan's empty room is
completed (``complete``, default steps, layout seed 0..seeds-1) holding exactly the
plan's categories and counts (all requested, none added), so every piece the designer
drew is there to be placed. The *accessories* are the pieces of the categories the whole
plan set shows standing on or at a larger piece (``accessories.learn_accessories``: a
lamp, a night table, a chair, an office chair, a desk lamp, a laptop, a television, a
refrigerator); each has an anchor (``accessories.anchor_of``: the piece it stands on,
or the nearest larger floor piece within 0.3 m). The completed scene's pieces get their
anchors the same way (what stands on what from the scene's support relations).

A plan's accessory is *matched* when the scene has an accessory of its category at an
anchor of its anchor's category whose offset in the anchor's frame is within 0.3 m of
the plan's and whose yaw relative to the anchor is within 30 degrees of it; each scene
piece matches one plan piece at most (the assignment of least total offset,
``scipy.optimize.linear_sum_assignment``, per category and anchor category). Printed: per
room type and in all, the plans' accessories, the share matched, the share whose pair
the scene has at all (its category at an anchor of the same category, anywhere), and the
layouts ok; then per pair the plans' pieces and the share matched.

Prints figures only; nothing is asserted. One process, one core.
"""

from __future__ import annotations

import argparse
import dataclasses
import math
from collections import Counter, defaultdict

import numpy as np
from scipy.optimize import linear_sum_assignment

from scenewright.completion import complete as complete_module
from scenewright.completion import shipped_plans_dir
from scenewright.completion.accessories import anchor_of, learn_accessories, relative_pose
from scenewright.completion.floor_plan import Furniture, load_plans
from scenewright.completion.model_builder import build_model
from scenewright.completion.request import Request
from scenewright.core.errors import InputError
from scenewright.core.relations import RELATIONS
from scenewright.generator import indoor_catalog

#: A plan's accessory is matched within these of its offset (metres) and relative yaw.
OFFSET = 0.3
YAW = math.radians(30.0)


def accessory_poses(pieces, catalog, categories) -> dict[tuple[str, str], list[dict]]:
    """(category, anchor category) -> the relative poses of the ``pieces`` of the
    accessory ``categories`` that have an anchor."""
    out: dict[tuple[str, str], list[dict]] = defaultdict(list)
    for piece in pieces:
        if piece.category not in categories:
            continue
        found = anchor_of(piece, pieces, catalog)
        if found is not None:
            anchor, on = found
            out[piece.category, anchor.category].append(relative_pose(piece, anchor, on))
    return out


def scene_pieces(scene) -> list[Furniture]:
    """The scene's objects as plan pieces: footprint, yaw and what each stands on."""
    support = {
        r.source: r.target
        for r in scene.relations
        if r.label in RELATIONS and RELATIONS[r.label].support
    }
    return [
        Furniture(
            id=obj.id,
            category=obj.type,
            center=(float(obj.position[0]), float(obj.position[2])),
            size=(float(obj.size[0]), float(obj.size[2])),
            yaw=float(obj.yaw),
            on=support.get(obj.id),
        )
        for obj in scene.placed_objects()
    ]


def matched(truth: list[dict], found: list[dict]) -> int:
    """How many of the plan's poses ``truth`` a pose of ``found`` matches (module docstring)."""
    if not truth or not found:
        return 0
    cost = np.zeros((len(truth), len(found)))
    hits = np.zeros_like(cost, dtype=bool)
    for i, a in enumerate(truth):
        for j, b in enumerate(found):
            distance = math.dist(a["offset"], b["offset"])
            turn = abs(math.remainder(a["yaw"] - b["yaw"], 2.0 * math.pi))
            hits[i, j] = distance <= OFFSET and turn <= YAW
            cost[i, j] = distance + (0.0 if hits[i, j] else 100.0)
    rows, cols = linear_sum_assignment(cost)
    return int(hits[rows, cols].sum())


def complete_as_drawn(plan, model, catalog, seed: int):
    """The plan's empty room completed with exactly its categories and counts."""
    counts = dict(sorted(Counter(piece.category for piece in plan.furniture).items()))
    request = Request(room=plan.room, requested=counts)
    choose = complete_module.choose_contents

    def exactly(model_, request_, **kwargs):
        # One region: the plan's pieces, however Equation 2 reads the room.
        chosen = choose(model_, request_, **{**kwargs, "split": False})
        return dataclasses.replace(chosen, counts=dict(counts))

    complete_module.choose_contents = exactly
    try:
        return complete_module.complete(request, seed, model=model, catalog=catalog)
    finally:
        complete_module.choose_contents = choose


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--seeds", type=int, default=1, help="layout seeds per plan (1)")
    parser.add_argument("--only", default=None, help="only plans of this room type")
    args = parser.parse_args()
    catalog = indoor_catalog()
    plans = sorted(load_plans(shipped_plans_dir()), key=lambda plan: plan.id)
    categories = set(learn_accessories(plans, catalog))
    rows: dict[str, Counter] = defaultdict(Counter)
    pairs: dict[tuple[str, str], Counter] = defaultdict(Counter)
    for plan in plans:
        if args.only and plan.type != args.only:
            continue
        model = build_model([other for other in plans if other.id != plan.id])
        truth = accessory_poses(plan.furniture, catalog, categories)
        for seed in range(args.seeds):
            try:
                scene = complete_as_drawn(plan, model, catalog, seed)
            except InputError:  # more of a category than the other plans hold together
                rows["all"]["refused"] += 1
                continue
            found = accessory_poses(scene_pieces(scene), catalog, categories)
            for key in (plan.type, "all"):
                rows[key]["layouts"] += 1
                rows[key]["ok"] += scene.layout.ok
            for pair, poses in truth.items():
                hits = matched(poses, found.get(pair, []))
                present = min(len(poses), len(found.get(pair, [])))
                for key in (plan.type, "all"):
                    rows[key]["pieces"] += len(poses)
                    rows[key]["matched"] += hits
                    rows[key]["present"] += present
                pairs[pair]["pieces"] += len(poses)
                pairs[pair]["matched"] += hits
    print(
        f"Accessories placed as the held-out plan has them (within {OFFSET} m and "
        f"{math.degrees(YAW):.0f} degrees of its anchor), {args.seeds} seed(s) a plan:"
    )
    print(
        "| room type | accessories | matched | at an anchor of the plan's category | layouts ok |"
    )
    print("|---|---|---|---|---|")
    for key in sorted(rows, key=lambda k: (k == "all", k)):
        row = rows[key]
        pieces = max(row["pieces"], 1)
        print(
            f"| {key} | {row['pieces']} | {row['matched'] / pieces:.3f} | "
            f"{row['present'] / pieces:.3f} | {row['ok']}/{row['layouts']} |"
        )
    if rows["all"]["refused"]:
        print(
            f"(refused: {rows['all']['refused']} plans hold more of a category than the others together)"
        )
    print()
    print("| accessory on or at | pieces | matched |")
    print("|---|---|---|")
    for (name, anchor), row in sorted(
        pairs.items(), key=lambda item: (-item[1]["pieces"], item[0])
    ):
        print(f"| {name} at {anchor} | {row['pieces']} | {row['matched'] / row['pieces']:.3f} |")


if __name__ == "__main__":
    main()
