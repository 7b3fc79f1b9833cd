"""Completion benchmark: how often ``complete`` lays a room out ok, and what the layout
mask's energy part buys.

    .venv/bin/python benchmarks/bench_complete.py                  # both parts below
    .venv/bin/python benchmarks/bench_complete.py --table          # six fixed requests, seeds 0..9
    .venv/bin/python benchmarks/bench_complete.py --random 50      # 50 random rooms, seed 0 each
    .venv/bin/python benchmarks/bench_complete.py --random 50 --first-seed 1000  # 50 other rooms, seed 1000
    .venv/bin/python benchmarks/bench_complete.py --without-mask-term   # the mask chooses the starts only
    .venv/bin/python benchmarks/bench_complete.py --composite 20   # 20 large two-type requests, split and not

``--table`` runs the six requests of the completion table in docs/notes/measurements.md
(room, door, window, requested categories) for layout seeds 0..9 and prints per request:
ok, layout CPU seconds per scene (median), and the *mask cover* on seeds 0..4: the mean,
over the laid-out floor pieces (those not standing on another, flat ones aside), of the
layout mask read at 5 x 5 points of each footprint (``layout_mask.mask_at``); and the
same over the categories of the large pieces the mask term is for (``complete.masked``:
what the plans show against a wall or free).

``--random N`` draws N rooms from a fixed stream (sides 3.0-6.5 x 3.0-5.5 m, a door on
one wall and a window on another, one of the four home types' main piece requested,
with a second category half the time) and completes each with layout seed 0. It
prints: ok (share of rooms laid out with no problem), blocked doors (rooms where a
piece stands in a door's swing), reachability (of the pieces someone must reach, the
share reachable from the door), categories added per room (mean, beyond the request),
CPU seconds per room (the whole ``complete`` call, the plan model built once
beforehand: median, mean, and the slowest room's with its request), the mask cover as
above, and how many rooms Equation 2 gave several types.

``--composite N`` draws N large rooms from another fixed stream (sides 6-9 m, a door
and a window on two walls, two requested categories that belong to different home
types: bed + sofa, desk + dining table, ...) and completes each with layout seed 0
twice: split by virtual walls (``complete``'s default) and not split (``split=False``:
the room whole, the first type's mask, the old behaviour) as the baseline. It prints
for each: ok, rooms of more than one type, and over those the share of floor pieces
whose centre lies in the region they belong to (``complete.region_boxes``; for the
baseline the regions the split would have made, with the baseline's own categories),
the mean share of their footprints inside it, and CPU seconds per room.

Prints figures only; nothing is asserted. One process, one core.
"""

from __future__ import annotations

import argparse
import dataclasses
import statistics
import time

import numpy as np

from scenewright.completion import CATEGORY_METHODS, MASK_METHODS, shipped_plans_dir
from scenewright.completion.complete import complete, region_boxes
from scenewright.completion.contents import category_owners, choose_contents
from scenewright.completion.explanation import recorded_mask_values
from scenewright.completion.floor_plan import load_plans
from scenewright.completion.model_builder import build_model
from scenewright.completion.regions import footprint_share, split_room
from scenewright.completion.request import parse_request
from scenewright.completion.stances import stands_by_room
from scenewright.generator import indoor_catalog
from scenewright.generator import layout as layout_module

#: The docs' table: room, door, window, requested.
TABLE = (
    ("5x4", "S:0.8:0.9", "N:2.5:1.4", "bed,bookshelf"),
    ("3x3", "S:0.6:0.8", "N:1.5:1.0", "bed"),
    ("4x3.6", "S:3.2:0.85", "E:1.8:1.3", "desk"),
    ("5x4", "S:0.8:0.9", "E:2:1.2", "sofa"),
    ("4.5x4", "W:1:0.9", "N:2.2:1.4", "dining_table"),
    ("7x6", "S:1:0.9", "N:3:1.4", "bed,bookshelf"),
)
#: Random requests: a type's main piece, and the second categories one may come with.
MAIN = {
    "bed": ("bookshelf", "desk", "wardrobe"),
    "sofa": ("bookshelf", "armchair", "tv_stand"),
    "desk": ("bookshelf", "filing_cabinet", "armchair"),
    "dining_table": ("dresser", "bookshelf"),
}
#: Pieces at most this tall lie flat (a rug) and are left out of the cover.
FLAT = 0.02
SAMPLES = 5
STREAM_SEED = 2024


def large_categories(model, names) -> set[str]:
    """Of ``names``, the categories the plans show against a wall or free in the middle
    (``stances.stands_by_room``): those whose pieces the mask term is for when nothing
    ties them to another piece (``complete.masked``)."""
    return {name for name in names if stands_by_room(model, name)}


def mask_cover(scene, only=None) -> float:
    """Mean mask value at 5 x 5 points of each floor piece's footprint (``only``: those categories)."""
    grid = (np.arange(SAMPLES) + 0.5) / SAMPLES - 0.5
    values = []
    for obj in scene.placed_objects():
        if (
            obj.position[1] > 0.01
            or obj.size[1] <= FLAT
            or (only is not None and obj.type not in only)
        ):
            continue
        width, depth = obj.size[0], obj.size[2]
        local = np.array([(a * width, b * depth) for a in grid for b in grid])
        c, s = np.cos(obj.yaw), np.sin(obj.yaw)
        x, z = obj.position[0], obj.position[2]
        points = np.column_stack(
            [x + local[:, 0] * c + local[:, 1] * s, z - local[:, 0] * s + local[:, 1] * c]
        )
        values.append(float(np.mean(recorded_mask_values(scene.completion, scene.room, points))))
    return float(np.mean(values)) if values else float("nan")


class LayoutClock:
    """CPU seconds spent in ``layout_scene`` (``complete`` imports it when called, so
    wrapping the module's attribute times its calls)."""

    def __init__(self) -> None:
        self.seconds = 0.0
        self._original = layout_module.layout_scene

        def timed(*args, **kwargs):
            started = time.process_time()
            try:
                return self._original(*args, **kwargs)
            finally:
                self.seconds += time.process_time() - started

        layout_module.layout_scene = timed


CLOCK: LayoutClock | None = None
#: ``--categories`` and ``--mask``: the steps every request is completed with (None: the default).
METHODS: dict[str, str] = {}


def run(request, seed, model, catalog, mask_term, split=True):
    """The completed scene, the CPU seconds of the whole call and of its layout."""
    global CLOCK
    CLOCK = CLOCK or LayoutClock()
    before = CLOCK.seconds
    started = time.process_time()
    request = dataclasses.replace(request, **METHODS)
    scene = complete(request, seed, model=model, catalog=catalog, mask_term=mask_term, split=split)
    return scene, time.process_time() - started, CLOCK.seconds - before


def table(model, catalog, seeds: int, mask_term: bool) -> None:
    known = set(catalog)
    print(
        "| room | door; window | requested | ok | layout CPU s (median) | mask cover: floor pieces / large pieces (seeds 0-4) |"
    )
    print("|---|---|---|---|---|---|")
    for room, door, window, requested in TABLE:
        request = parse_request(room, [door], [window], [requested], known)
        oks, seconds, cover, cover_large = 0, [], [], []
        for seed in range(seeds):
            scene, _, layout_seconds = run(request, seed, model, catalog, mask_term)
            oks += scene.layout.ok
            seconds.append(layout_seconds)
            if seed < 5:
                cover.append(mask_cover(scene))
                cover_large.append(mask_cover(scene, large_categories(model, catalog)))
        print(
            f"| {room.replace('x', ' x ')} | {door}; {window} | {requested.replace(',', ', ')} | {oks}/{seeds} "
            f"| {statistics.median(seconds):.2f} | {np.mean(cover):.3f} / {np.mean(cover_large):.3f} |"
        )


def random_rooms(count: int, known, first_seed: int = 0) -> list:
    """``count`` requests drawn from a fixed stream (module docstring); another
    ``first_seed`` draws other rooms."""
    rng = np.random.default_rng(STREAM_SEED + first_seed)
    requests = []
    walls = ("N", "E", "S", "W")
    while len(requests) < count:
        width, depth = (
            round(float(rng.uniform(3.0, 6.5)), 1),
            round(float(rng.uniform(3.0, 5.5)), 1),
        )
        door_wall, window_wall = rng.choice(4, size=2, replace=False)
        door_length = width if walls[door_wall] in "NS" else depth
        window_length = width if walls[window_wall] in "NS" else depth
        door_width = round(float(rng.uniform(0.8, 0.95)), 2)
        window_width = round(float(rng.uniform(1.0, min(1.8, window_length - 0.6))), 2)
        door = f"{walls[door_wall]}:{rng.uniform(0.5 + door_width / 2, door_length - 0.5 - door_width / 2):.2f}:{door_width}"
        window = f"{walls[window_wall]}:{rng.uniform(0.3 + window_width / 2, window_length - 0.3 - window_width / 2):.2f}:{window_width}"
        main = list(MAIN)[int(rng.integers(len(MAIN)))]
        wanted = [main] + ([str(rng.choice(MAIN[main]))] if rng.random() < 0.5 else [])
        requests.append((f"{width}x{depth}", door, window, ",".join(wanted)))
    return [
        (spec, parse_request(spec[0], [spec[1]], [spec[2]], [spec[3]], known)) for spec in requests
    ]


def random_table(model, catalog, count: int, mask_term: bool, first_seed: int = 0) -> None:
    oks = blocked = reach_needed = unreachable = added = 0
    seconds, cover, cover_large, split = [], [], [], 0
    slowest = (0.0, None)
    for spec, request in random_rooms(count, set(catalog), first_seed):
        scene, cpu, _ = run(request, first_seed, model, catalog, mask_term)
        seconds.append(cpu)
        slowest = max(slowest, (cpu, spec))
        split += len(scene.completion["types"]) > 1
        oks += scene.layout.ok
        problems = scene.layout.problems
        blocked += any("stands in the swing of" in p for p in problems)
        reach_needed += sum(1 for o in scene.placed_objects() if o.access and o.position[1] <= 0.01)
        unreachable += sum(1 for p in problems if "cannot be reached" in p)
        added += sum(
            n for name, n in scene.completion["counts"].items() if name not in request.requested
        )
        cover.append(mask_cover(scene))
        cover_large.append(mask_cover(scene, large_categories(model, catalog)))
    print(
        f"{count} random rooms (layout seed {first_seed}), mask term {'on' if mask_term else 'off'}:"
    )
    print(
        f"  ok {oks}/{count} ({100 * oks / count:.0f} %); blocked doors {blocked}; "
        f"reachable {reach_needed - unreachable}/{reach_needed} ({100 * (reach_needed - unreachable) / max(reach_needed, 1):.1f} %); "
        f"categories added per room {added / count:.1f}; CPU s per room median {statistics.median(seconds):.2f}, "
        f"mean {statistics.mean(seconds):.2f}, max {slowest[0]:.2f} ({' '.join(slowest[1])}); "
        f"mask cover {np.nanmean(cover):.3f} / large {np.nanmean(cover_large):.3f}; rooms of several types {split}"
    )


#: Composite requests: two categories that belong to different home types.
PAIRS = (
    ("bed", "sofa"),
    ("desk", "dining_table"),
    ("bed", "desk"),
    ("sofa", "dining_table"),
    ("bed", "dining_table"),
    ("sofa", "desk"),
)
COMPOSITE_SEED = 2025


def composite_rooms(count: int, known) -> list:
    """``count`` large two-type requests drawn from a fixed stream (module docstring)."""
    rng = np.random.default_rng(COMPOSITE_SEED)
    walls = ("N", "E", "S", "W")
    requests = []
    for k in range(count):
        width, depth = (
            round(float(rng.uniform(6.0, 9.0)), 1),
            round(float(rng.uniform(6.0, 9.0)), 1),
        )
        door_wall, window_wall = rng.choice(4, size=2, replace=False)
        door_length = width if walls[door_wall] in "NS" else depth
        window_length = width if walls[window_wall] in "NS" else depth
        door = f"{walls[door_wall]}:{rng.uniform(0.6, door_length - 0.6):.2f}:0.9"
        window = f"{walls[window_wall]}:{rng.uniform(1.0, window_length - 1.0):.2f}:1.4"
        wanted = ",".join(PAIRS[k % len(PAIRS)])
        requests.append((f"{width}x{depth}", door, window, wanted))
    return [
        (spec, parse_request(spec[0], [spec[1]], [spec[2]], [spec[3]], known)) for spec in requests
    ]


def region_figures(scene, model, request) -> tuple[list[bool], list[float]] | None:
    """Per floor piece of a room of several types: whether its centre lies in the region
    it belongs to, and the share of its footprint there; None for a room of one type."""
    record = scene.completion
    if len(record["types"]) < 2:
        return None
    if "regions" in record:
        regions = split_room(model, scene.room, tuple(record["types"]))
        boxes = [entry["pieces"] for entry in record["regions"]]
    else:  # the baseline: the regions the split would make, its own categories' owners
        contents = choose_contents(model, request, split=False)
        regions = split_room(model, scene.room, contents.types)
        index = {region.room_type: k for k, region in enumerate(regions)}
        owners = category_owners(
            model, contents.types, contents.owners, contents.explorations, contents.counts
        )
        types = {o.id: o.type for o in scene.placed_objects()}
        relations = [(r.source, r.target, r.label) for r in scene.relations]
        boxes = region_boxes(
            types,
            relations,
            {name: index[t] for name, t in owners.items()},
            len(regions),
            large_categories(model, set(types.values())),
        )
    objects = {o.id: o for o in scene.placed_objects()}
    inside, shares = [], []
    for region, ids in zip(regions, boxes, strict=False):
        for box in ids:
            obj = objects.get(box)
            if obj is None:
                continue
            inside.append(bool(region.contains([[obj.position[0], obj.position[2]]])[0]))
            shares.append(
                footprint_share(
                    region, obj.position[0], obj.position[2], obj.size[0], obj.size[2], obj.yaw
                )
            )
    return inside, shares


def composite_table(model, catalog, count: int) -> None:
    rooms = composite_rooms(count, set(catalog))
    for split in (True, False):
        oks = several = 0
        seconds, inside, shares = [], [], []
        for _spec, request in rooms:
            scene, cpu, _ = run(request, 0, model, catalog, True, split)
            seconds.append(cpu)
            oks += scene.layout.ok
            figures = region_figures(scene, model, request)
            if figures is not None:
                several += 1
                inside += figures[0]
                shares += figures[1]
        print(
            f"{count} large two-type rooms (layout seed 0), {'split by virtual walls' if split else 'not split (baseline)'}:"
        )
        print(
            f"  ok {oks}/{count} ({100 * oks / count:.0f} %); rooms of several types {several}; pieces with their "
            f"centre in their region {sum(inside)}/{len(inside)} ({100 * sum(inside) / max(len(inside), 1):.0f} %); "
            f"footprint share inside {np.mean(shares):.3f}; CPU s per room median {statistics.median(seconds):.2f}, "
            f"mean {statistics.mean(seconds):.2f}"
        )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--table", action="store_true", help="the docs' six requests only")
    parser.add_argument("--random", type=int, default=None, metavar="N", help="N random rooms only")
    parser.add_argument(
        "--seeds", type=int, default=10, help="layout seeds per request of --table (10)"
    )
    parser.add_argument(
        "--first-seed",
        type=int,
        default=0,
        help="--random: the rooms' stream and the layout seed (0; 1000 and up for held-out rooms)",
    )
    parser.add_argument(
        "--without-mask-term", action="store_true", help="the mask chooses the starting poses only"
    )
    parser.add_argument(
        "--composite",
        type=int,
        default=None,
        metavar="N",
        help="N large two-type rooms only, split by virtual walls and not",
    )
    parser.add_argument(
        "--categories",
        choices=CATEGORY_METHODS,
        help=f"how the categories are chosen (default {CATEGORY_METHODS[0]})",
    )
    parser.add_argument(
        "--mask", choices=MASK_METHODS, help=f"how the mask is chosen (default {MASK_METHODS[0]})"
    )
    args = parser.parse_args()
    METHODS.update({k: getattr(args, k) for k in ("categories", "mask") if getattr(args, k)})
    model = build_model(load_plans(shipped_plans_dir()))
    catalog = indoor_catalog()
    mask_term = not args.without_mask_term
    if args.composite is not None:
        composite_table(model, catalog, args.composite)
        return
    both = not args.table and args.random is None
    if args.table or both:
        table(model, catalog, args.seeds, mask_term)
    if args.random is not None or both:
        random_table(model, catalog, args.random or 50, mask_term, args.first_seed)


if __name__ == "__main__":
    main()
