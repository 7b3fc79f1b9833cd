"""Plausibility benchmark: ok rates off the development seeds, seats at their tables,
nightstands by their beds, and SceneEval's four metrics per shipped rule set.

    .venv/bin/python benchmarks/bench_plausible.py                          # every shipped set, seeds 1000..1049
    .venv/bin/python benchmarks/bench_plausible.py --first 1000 --count 500  # the issue's full range
    .venv/bin/python benchmarks/bench_plausible.py --first 0 --count 50      # the development seeds
    .venv/bin/python benchmarks/bench_plausible.py study bedroom --count 200

Each scene is generated once (``build_scene``: the grammar expanded and laid out with
the seed) and then measured; per rule set it prints:

- ok: layouts with no problem at all (every relation holds, nothing overlaps by more
  than 1 cm, nothing crosses a wall, no door swing, kept space or way blocked);
- seats: of the seats at a table or desk (``Seated*`` relations), the share whose
  nearest side is within 0.35 m of the table and that face it within 10 degrees, and
  the median gap; nightstands: the share within 0.15 m of their bed;
- SceneEval (``scenewright.generator.scene_metrics``, rooms only): the mean share of
  objects in a collision beyond 1 cm and out of bounds beyond 1 cm, the mean
  navigability, the doors blocked and the windows blocked (of all doors and windows);
- seconds per scene (wall clock: the layout may run in a worker process).

Layouts take about 0.5-3 CPU seconds a room; the full 500 seeds of every set take
hours on one core, so the default is the first 50 of the range and the figures say
which seeds they cover. Prints figures only; nothing is asserted.
"""

from __future__ import annotations

import argparse
import math
import statistics
import time

from scenewright.api import build_scene
from scenewright.core.geometry import make_rect, rect_distance
from scenewright.core.relations import RELATIONS, SEAT_REACH, SEAT_SQUARE_TOLERANCE
from scenewright.core.scene import Scene, SceneObject
from scenewright.generator import load_rules
from scenewright.generator.rules import shipped_rule_sets
from scenewright.generator.scene_metrics import evaluate_scene, summarise

NIGHTSTAND_REACH = 0.15


def _rect(obj: SceneObject):
    return make_rect(obj.position[0], obj.position[2], obj.size[0], obj.size[2], obj.yaw)


def seat_figures(scene: Scene) -> tuple[list[tuple[float, float]], list[float]]:
    """Per seat relation (gap in metres, degrees off facing its side) and per nightstand
    its gap to the bed it stands beside."""
    by_id = {o.id: o for o in scene.objects}
    seats, nightstands = [], []
    for relation in scene.relations:
        if relation.label not in RELATIONS or relation.target not in by_id:
            continue
        spec = RELATIONS[relation.label]
        a, b = by_id.get(relation.source), by_id[relation.target]
        if a is None:
            continue
        gap = rect_distance(_rect(a), _rect(b))
        if spec.seat:
            # the side A stands at: B's local direction nearest the direction B -> A
            dx, dz = a.position[0] - b.position[0], a.position[2] - b.position[2]
            c, s = math.cos(b.yaw), math.sin(b.yaw)
            sides = spec.direction_vectors(c, s).values()
            wx, wz = max(sides, key=lambda v: v[0] * dx + v[1] * dz)
            forward = (math.sin(a.yaw), math.cos(a.yaw))
            dot = max(-1.0, min(1.0, -(forward[0] * wx + forward[1] * wz)))
            seats.append((gap, math.degrees(math.acos(dot))))
        elif a.type == "nightstand" and b.type == "bed" and spec.family == "next_to":
            nightstands.append(gap)
    return seats, nightstands


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("rules", nargs="*", help="rule sets (default: every shipped one)")
    parser.add_argument("--first", type=int, default=1000, help="first seed (1000)")
    parser.add_argument("--count", type=int, default=50, help="seeds per rule set (50)")
    args = parser.parse_args()
    names = args.rules or sorted(shipped_rule_sets())
    last = args.first + args.count - 1
    print(f"seeds {args.first}..{last}")
    header = (
        f"{'rules':<12} {'ok':>9} {'seats ok':>9} {'gap med':>8} {'nights':>7} "
        f"{'coll':>6} {'oob':>6} {'nav':>7} {'doors':>9} {'windows':>9} {'s':>6}"
    )
    print(header)
    for name in names:
        indoor = load_rules(name).params.room is not None
        ok, seats, nightstands, metrics, seconds, failed = 0, [], [], [], [], []
        for seed in range(args.first, last + 1):
            start = time.perf_counter()
            scene = build_scene(name, seed)
            seconds.append(time.perf_counter() - start)
            ok += scene.layout.ok
            if not scene.layout.ok:
                failed.append((seed, scene.layout.problems[:1]))
            found_seats, found_nightstands = seat_figures(scene)
            seats += found_seats
            nightstands += found_nightstands
            if indoor:
                metrics.append(evaluate_scene(scene, f"{name} {seed}"))
        good = sum(
            g <= SEAT_REACH + 1e-6 and off <= math.degrees(SEAT_SQUARE_TOLERANCE) + 1e-6
            for g, off in seats
        )
        near = sum(g <= NIGHTSTAND_REACH + 1e-6 for g in nightstands)
        row = f"{name:<12} {ok:>4}/{args.count:<4}"
        row += f" {f'{100 * good / len(seats):.1f}%' if seats else '-':>9}"
        row += f" {f'{statistics.median(g for g, _ in seats):.2f}' if seats else '-':>8}"
        row += f" {f'{100 * near / len(nightstands):.0f}%' if nightstands else '-':>7}"
        if metrics:
            summary = summarise(metrics)
            row += (
                f" {100 * summary.collision_rate:>5.1f}% {100 * summary.out_of_bounds_rate:>5.1f}%"
            )
            row += f" {100 * (summary.navigability or 0.0):>6.1f}%"
            row += f" {summary.blocked_doors:>3}/{summary.doors:<5} {summary.blocked_windows:>3}/{summary.windows:<5}"
        else:
            row += f" {'-':>6} {'-':>6} {'-':>7} {'-':>9} {'-':>9}"
        row += f" {statistics.mean(seconds):>6.2f}"
        print(row, flush=True)
        for seed, problems in failed:
            print(f"    not ok: seed {seed}: {problems[0] if problems else ''}")


if __name__ == "__main__":
    main()
