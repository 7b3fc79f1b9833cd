"""Town benchmark: layout time and quality on the large shipped rule set (``town``).

    .venv/bin/python benchmarks/bench_town.py                   # seeds 0..19
    .venv/bin/python benchmarks/bench_town.py --seeds 50
    .venv/bin/python benchmarks/bench_town.py --decompose off   # one chain over the whole scene

Prints, over the seeds: objects per scene, the median and 90th percentile of layout CPU
seconds (this process's ``time.process_time``, which does not grow when other work
shares the machine; one core), the share of ``ok`` layouts, how many overlaps the
layouts reported in all, and the problems by kind; then the targets. Nothing is asserted.
"""

from __future__ import annotations

import argparse
import statistics
import time
from collections import Counter

from scenewright.generator import expand, load_rules
from scenewright.generator.layout import LayoutParams, layout_scene

#: What a town layout is meant to reach (seeds 0..19): median CPU seconds, share ok, overlaps.
TARGET_MEDIAN_SECONDS = 3.0
TARGET_OK = 0.95


def percentile(values: list[float], share: float) -> float:
    ordered = sorted(values)
    return ordered[int(share * (len(ordered) - 1))]


def problem_kind(problem: str) -> str:
    for word in ("overlaps", "is not", "outside", "leaves", "long", "turns", "apart"):
        if word in problem:
            return word
    return "other"


def bench(rules_name: str, seeds: int, params: LayoutParams, verbose: bool) -> None:
    rules = load_rules(rules_name)
    cpu, counts, oks, kinds = [], [], 0, Counter()
    for seed in range(seeds):
        graph = expand(rules, seed)
        counts.append(len(graph.nodes("object")))
        started = time.process_time()
        result = layout_scene(graph, seed, params=params)
        cpu.append(time.process_time() - started)
        oks += result.ok
        kinds.update(problem_kind(problem) for problem in result.problems)
        if verbose:
            print(
                f"  seed {seed:3d}: {counts[-1]:3d} objects  {cpu[-1]:7.2f} s  ok {result.ok}  {result.problems[:3]}"
            )
    median, p90, share = statistics.median(cpu), percentile(cpu, 0.9), oks / seeds
    print(
        f"{rules_name}: seeds 0..{seeds - 1}, {min(counts)}..{max(counts)} objects per scene (mean {statistics.mean(counts):.0f})"
    )
    print(
        f"  layout cpu seconds: median {median:.2f}  p90 {p90:.2f}  max {max(cpu):.2f}  mean {statistics.mean(cpu):.2f}"
    )
    print(f"  ok {100 * share:.0f} %   overlaps {kinds['overlaps']}")
    if kinds:
        print("  problems by kind:", dict(kinds.most_common()))
    print(
        f"  targets: median <= {TARGET_MEDIAN_SECONDS:.0f} s {'met' if median <= TARGET_MEDIAN_SECONDS else 'MISSED'}, "
        f"ok >= {100 * TARGET_OK:.0f} % {'met' if share >= TARGET_OK else 'MISSED'}, "
        f"0 overlaps {'met' if kinds['overlaps'] == 0 else 'MISSED'}"
    )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument(
        "--seeds", type=int, default=20, help="lay out seeds 0..SEEDS-1 (default 20)"
    )
    parser.add_argument("--rules", default="town", help="rule set (default town)")
    parser.add_argument("--verbose", action="store_true", help="one line per seed")
    parser.add_argument(
        "--decompose",
        choices=("auto", "off"),
        default="auto",
        help="auto: group decomposition where its rule says (default); off: one chain over the whole scene",
    )
    parser.add_argument(
        "--workers", type=int, default=1, help="processes laying out the groups' frames (default 1)"
    )
    args = parser.parse_args()
    params = LayoutParams(decompose=args.decompose == "auto", workers=args.workers)
    bench(args.rules, args.seeds, params, args.verbose)


if __name__ == "__main__":
    main()
