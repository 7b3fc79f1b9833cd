"""Town and city benchmark: lots along roads and fitted road networks at 300 to 3,000
objects.

    .venv/bin/python benchmarks/bench_city.py                    # the default run below
    .venv/bin/python benchmarks/bench_city.py --town-seeds 100 --city-seeds 10
    .venv/bin/python benchmarks/bench_city.py --plot docs/images/layout-scaling.png

Prints, for the shipped ``town`` and for four towns written from the docs alone,
``benchmarks/town_rules/user_town.rules`` (70 loose houses with their gardens, two
crossroads with seven roads of up to 90 m) and ``crossroads_town.rules`` (52 to 68
homes as groups and 6 to 12 cottages, three crossroads with ten roads of up to 50 m,
two lanes, a square), ``grid_town.rules`` (two ``network grid`` crossroads, seven
avenues with side streets branching square off them, 54 to 66 homes) and
``branch_town.rules`` (two organic crossroads, five roads with lanes branching off
them, 50 to 62 homes), on seeds 1000..: the share of ``ok``
layouts, how many pairs of boxes overlap by more than 1 cm, and the median and 90th
percentile of layout CPU seconds (``time.process_time``: one core, not inflated by
other work on the machine); then the same for the shipped ``city`` (1,100 to 2,200
objects); then the targets. With ``--plot``, writes a plot of layout CPU seconds
against object count over all the scenes laid out, plus synthetic village graphs of
100 to 3,000 objects (``layout.synthetic``). Nothing is asserted.
"""

from __future__ import annotations

import argparse
import math
import statistics
import time
from pathlib import Path

from scenewright.core.geometry import Rect, rect_penetration
from scenewright.generator import expand, load_rules
from scenewright.generator.layout import layout_scene
from scenewright.generator.layout.synthetic import village_graph

HERE = Path(__file__).resolve().parent
TOWNS = (
    "town",
    str(HERE / "town_rules" / "user_town.rules"),
    str(HERE / "town_rules" / "crossroads_town.rules"),
    str(HERE / "town_rules" / "grid_town.rules"),
    str(HERE / "town_rules" / "branch_town.rules"),
)

#: The issue's targets: towns of about 300 objects, cities of 1,000 to 3,000.
TOWN_OK, TOWN_MEDIAN, TOWN_P90 = 0.99, 3.0, 6.0
CITY_OK, CITY_MEDIAN = 0.95, 30.0


def percentile(values: list[float], share: float) -> float:
    ordered = sorted(values)
    return ordered[int(share * (len(ordered) - 1))]


def deep_overlaps(graph, result, depth: float = 0.01) -> int:
    """Pairs of ground boxes (objects, not stacked) overlapping by more than ``depth``
    metres (the minimum separating translation), found through a grid of 10 m cells."""
    supported = {e.source for e in graph.edges() if e.label.startswith(("OnTopOf", "IsPartOf"))}
    rects = []
    for node in graph.nodes("object"):
        if node.id in supported:
            continue
        pose = result.poses[node.id]
        rects.append(
            Rect(
                pose.x,
                pose.z,
                node.size[0] / 2,
                node.size[2] / 2,
                math.cos(pose.yaw),
                math.sin(pose.yaw),
            )
        )
    cells: dict[tuple[int, int], list[int]] = {}
    for k, rect in enumerate(rects):
        reach = math.hypot(rect.hw, rect.hd)
        for i in range(math.floor((rect.cx - reach) / 10), math.floor((rect.cx + reach) / 10) + 1):
            for j in range(
                math.floor((rect.cz - reach) / 10), math.floor((rect.cz + reach) / 10) + 1
            ):
                cells.setdefault((i, j), []).append(k)
    pairs = set()
    for members in cells.values():
        for n, a in enumerate(members):
            for b in members[n + 1 :]:
                if (a, b) not in pairs and rect_penetration(rects[a], rects[b]) > depth:
                    pairs.add((a, b))
    return len(pairs)


def run(rules_name: str, seeds: range, points: list, verbose: bool) -> dict:
    rules = load_rules(rules_name)
    cpu, counts, oks, overlaps = [], [], 0, 0
    for seed in seeds:
        graph = expand(rules, seed)
        counts.append(len(graph.nodes("object")))
        started = time.process_time()
        result = layout_scene(graph, seed)
        cpu.append(time.process_time() - started)
        oks += result.ok
        deep = deep_overlaps(graph, result)
        overlaps += deep
        points.append((counts[-1], cpu[-1], Path(rules_name).stem))
        if verbose:
            print(
                f"  {Path(rules_name).stem} seed {seed}: {counts[-1]} objects {cpu[-1]:.2f} s ok {result.ok} overlaps>1cm {deep} {result.problems[:2]}",
                flush=True,
            )
    figures = {
        "ok": oks / len(cpu),
        "median": statistics.median(cpu),
        "p90": percentile(cpu, 0.9),
        "overlaps": overlaps,
    }
    print(
        f"{Path(rules_name).stem}: seeds {seeds.start}..{seeds.stop - 1}, {min(counts)}..{max(counts)} objects "
        f"(mean {statistics.mean(counts):.0f}); ok {100 * figures['ok']:.0f} %; overlaps > 1 cm {overlaps}; "
        f"cpu s median {figures['median']:.2f} p90 {figures['p90']:.2f} max {max(cpu):.2f}",
        flush=True,
    )
    return figures


def plot(points: list, path: str, sizes: list[int]) -> None:
    for size in sizes:  # synthetic village graphs fill in the sizes the rule sets do not reach
        graph = village_graph(size, 0)
        started = time.process_time()
        layout_scene(graph, 0)
        points.append((len(graph.nodes("object")), time.process_time() - started, "synthetic"))
        print(f"  synthetic {size}: {points[-1][1]:.2f} s", flush=True)
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    figure, axes = plt.subplots(figsize=(6, 4), dpi=120)
    for label, marker in (
        ("town", "o"),
        ("user_town", "s"),
        ("crossroads_town", "D"),
        ("grid_town", "P"),
        ("branch_town", "v"),
        ("city", "^"),
        ("synthetic", "x"),
    ):
        chosen = [(n, s) for n, s, name in points if name == label]
        if chosen:
            axes.scatter(*zip(*chosen, strict=False), marker=marker, label=label, s=18)
    axes.set_xscale("log")
    axes.set_yscale("log")
    axes.set_xlabel("objects")
    axes.set_ylabel("layout CPU seconds")
    axes.set_title("Layout time against scene size")
    axes.grid(True, which="both", alpha=0.3)
    axes.legend()
    figure.tight_layout()
    figure.savefig(path)
    print(f"wrote {path}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument(
        "--town-seeds", type=int, default=20, help="towns: seeds 1000.. (default 20)"
    )
    parser.add_argument(
        "--city-seeds", type=int, default=3, help="cities: seeds 1000.. (default 3; 0: none)"
    )
    parser.add_argument("--first", type=int, default=1000, help="first seed (default 1000)")
    parser.add_argument("--plot", help="write the time-against-size plot here (PNG)")
    parser.add_argument(
        "--sizes", default="100,200,400,800,1600,3000", help="synthetic sizes for the plot"
    )
    parser.add_argument("--verbose", action="store_true", help="one line per scene")
    args = parser.parse_args()
    points: list = []
    towns = [
        run(name, range(args.first, args.first + args.town_seeds), points, args.verbose)
        for name in (TOWNS if args.town_seeds else ())  # --town-seeds 0: the city only
    ]
    city = (
        run("city", range(args.first, args.first + args.city_seeds), points, args.verbose)
        if args.city_seeds
        else None
    )
    for name, figures in zip((Path(town).stem for town in TOWNS), towns, strict=False):
        print(
            f"targets {name}: ok >= 99 % {'met' if figures['ok'] >= TOWN_OK else 'MISSED'}, "
            f"0 overlaps > 1 cm {'met' if figures['overlaps'] == 0 else 'MISSED'}, "
            f"median <= 3 s {'met' if figures['median'] <= TOWN_MEDIAN else 'MISSED'}, "
            f"p90 <= 6 s {'met' if figures['p90'] <= TOWN_P90 else 'MISSED'}"
        )
    if city is not None:
        print(
            f"targets city: ok >= 95 % {'met' if city['ok'] >= CITY_OK else 'MISSED'}, "
            f"median <= 30 s {'met' if city['median'] <= CITY_MEDIAN else 'MISSED'}"
        )
    if args.plot:
        plot(points, args.plot, [int(size) for size in args.sizes.split(",")])


if __name__ == "__main__":
    main()
