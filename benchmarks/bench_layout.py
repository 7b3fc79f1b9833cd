"""Layout benchmark: village quality and time, scaling with scene size, naive vs incremental.

    .venv/bin/python benchmarks/bench_layout.py                 # everything below
    .venv/bin/python benchmarks/bench_layout.py --village 200   # seeds 0..199 of village.rules
    .venv/bin/python benchmarks/bench_layout.py --village 100 --restarts 0   # first chains only
    .venv/bin/python benchmarks/bench_layout.py --scaling       # 10, 30, 100, 300 objects
    .venv/bin/python benchmarks/bench_layout.py --compare       # per-step cost, full vs incremental
    .venv/bin/python benchmarks/bench_layout.py --synthetic 1000 --seeds 3   # one size, its target

Prints figures only; nothing is asserted. One process, one core. Times are given as
wall seconds (what ``LayoutResult.seconds`` records) and as this process's CPU seconds,
which do not grow when other work shares the machine.
"""

from __future__ import annotations

import argparse
import statistics
import time
from collections import Counter

import numpy as np

from scenewright.generator import expand, load_rules
from scenewright.generator.layout import LayoutParams, layout_scene
from scenewright.generator.layout.problem import compile_problem
from scenewright.generator.layout.sampler import start_chain
from scenewright.generator.layout.synthetic import village_graph


def village(seeds: int, rules_name: str, params: LayoutParams) -> None:
    rules = load_rules(rules_name)
    times, cpu, steps, counts, failures = [], [], [], [], Counter()
    ok = 0
    for seed in range(seeds):
        graph = expand(rules, seed)
        counts.append(sum(1 for n in graph.nodes() if n.kind == "object"))
        started = time.process_time()
        result = layout_scene(graph, seed, params=params)
        cpu.append(time.process_time() - started)
        times.append(result.seconds)
        steps.append(result.steps)
        ok += result.ok
        for problem in result.problems:
            failures[_kind(problem)] += 1
    print(f"{rules_name}: {seeds} seeds, {min(counts)}..{max(counts)} objects per scene")
    print(f"  ok {100 * ok / seeds:.1f} %   mean steps {statistics.mean(steps):.0f}")
    for name, values in (("wall", sorted(times)), ("cpu", sorted(cpu))):
        print(
            f"  {name:4s} seconds: mean {statistics.mean(values):.3f}  median {statistics.median(values):.3f}  "
            f"p90 {values[int(0.9 * (seeds - 1))]:.3f}  max {values[-1]:.3f}"
        )
    if failures:
        print("  problems by kind:", dict(failures.most_common()))
    cpu.sort()
    mean, p90, share = statistics.mean(cpu), cpu[int(0.9 * (seeds - 1))], ok / seeds
    print(
        f"  targets (cpu): mean <= 0.1 s {_met(mean <= 0.1)}, p90 <= 0.2 s {_met(p90 <= 0.2)}, "
        f"100 % ok {_met(share == 1.0)}"
    )


def _met(held: bool) -> str:
    return "met" if held else "MISSED"


def _kind(problem: str) -> str:
    for word in ("overlaps", "is not", "outside", "leaves", "long", "turns", "apart"):
        if word in problem:
            return word
    return "other"


def scaling() -> None:
    print("scaling (synthetic village graphs, seeds 0..4):")
    print("  objects   layout cpu s   steps   cpu us/step")
    for size in (10, 30, 100, 300):
        seconds, steps, per_step = [], [], []
        for seed in range(5):
            graph = village_graph(size, seed)
            started = time.process_time()
            result = layout_scene(graph, seed)
            seconds.append(time.process_time() - started)
            steps.append(result.steps)
            per_step.append(step_cost(graph, seed, incremental=True, steps=1000))
        print(
            f"  {size:7d}   {statistics.median(seconds):12.3f}   {statistics.median(steps):5.0f}"
            f"   {statistics.median(per_step):11.1f}"
        )


def synthetic(size: int, seeds: int) -> None:
    """Layout CPU seconds of synthetic village graphs of ``size`` objects, seeds 0..seeds-1."""
    seconds, steps, ok = [], [], 0
    for seed in range(seeds):
        graph = village_graph(size, seed)
        started = time.process_time()
        result = layout_scene(graph, seed)
        seconds.append(time.process_time() - started)
        steps.append(result.steps)
        ok += result.ok
    median = statistics.median(seconds)
    print(f"synthetic village graphs, {size} objects, seeds 0..{seeds - 1}:")
    print(
        f"  layout cpu seconds: median {median:.2f}  max {max(seconds):.2f}   steps median {statistics.median(steps):.0f}   ok {ok}/{seeds}"
    )
    if size == 1000:
        print(f"  target (cpu): median <= 3 s {_met(median <= 3.0)}")


def step_cost(graph, seed: int, *, incremental: bool, steps: int) -> float:
    """CPU microseconds per sampler step (propose + energy change + accept/reject), after the start."""
    params = LayoutParams(incremental=incremental)
    energy, mover = start_chain(compile_problem(graph), params, np.random.default_rng(seed))
    started = time.process_time()
    for _ in range(steps):
        proposal = mover.propose(energy.relation)
        if proposal is None:
            continue
        if energy.propose(*proposal) < 0.0:
            energy.accept()
        else:
            energy.reject()
    return 1e6 * (time.process_time() - started) / steps


def compare() -> None:
    print("full energy vs incremental, cpu us per step (same moves, synthetic village graphs):")
    for size in (30, 100, 300):
        graph = village_graph(size, 0)
        naive = step_cost(graph, 0, incremental=False, steps=300)
        incremental = step_cost(graph, 0, incremental=True, steps=300)
        print(
            f"  {size:4d} objects: full {naive:9.1f}   incremental {incremental:7.1f}   ratio {naive / incremental:6.1f}x"
        )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument(
        "--village", type=int, metavar="SEEDS", help="lay out this many village scenes"
    )
    parser.add_argument("--rules", default="village", help="rule set for --village")
    parser.add_argument(
        "--restarts", type=int, help="chains after the first for --village (default: LayoutParams)"
    )
    parser.add_argument("--scaling", action="store_true")
    parser.add_argument("--compare", action="store_true")
    parser.add_argument(
        "--synthetic", type=int, metavar="OBJECTS", help="lay out synthetic graphs of this size"
    )
    parser.add_argument("--seeds", type=int, default=5, help="seeds for --synthetic (default 5)")
    args = parser.parse_args()
    if args.synthetic:
        synthetic(args.synthetic, args.seeds)
    everything = not (args.village or args.scaling or args.compare or args.synthetic)
    if args.village or everything:
        params = LayoutParams() if args.restarts is None else LayoutParams(restarts=args.restarts)
        village(args.village or 200, args.rules, params)
    if args.scaling or everything:
        scaling()
    if args.compare or everything:
        compare()


if __name__ == "__main__":
    main()
