"""Description lengths: words of the full text and of the summary level, per rule set.

    .venv/bin/python benchmarks/bench_description_length.py town village bedroom --seeds 10
    .venv/bin/python benchmarks/bench_description_length.py village --styles full

Lays out each seed (``layout_scene``), describes it in each style and prints, per rule
set and style, the median, smallest and largest word count over the seeds, and for the
summary the sentences that claim a count. Nothing is asserted.
"""

from __future__ import annotations

import argparse
import statistics

from scenewright.core.scene import assemble_scene
from scenewright.describer import describe
from scenewright.generator import expand, load_rules
from scenewright.generator.layout import layout_scene


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("rule_sets", nargs="+")
    parser.add_argument("--seeds", type=int, default=10, help="seeds 0..N-1")
    parser.add_argument("--styles", nargs="+", default=["full", "summary"])
    args = parser.parse_args()
    for name in args.rule_sets:
        rules = load_rules(name)
        counts: dict[str, list[int]] = {style: [] for style in args.styles}
        claims = 0
        for seed in range(args.seeds):
            graph = expand(rules, seed)
            scene = assemble_scene(graph, layout_scene(graph, seed), rules=name, seed=seed)
            for style in args.styles:
                description = describe(scene, style=style)
                counts[style].append(len(description.text.split()))
                claims += (
                    sum(bool(s.claims) for s in description.sentences) if style == "summary" else 0
                )
        for style, found in counts.items():
            print(
                f"{name:10s} {style:8s} words: median {statistics.median(found):6.0f}  "
                f"min {min(found):5d}  max {max(found):5d}  per seed {found}"
            )
        if "summary" in counts:
            print(
                f"{name:10s} summary sentences claiming a count: {claims} over {args.seeds} seeds"
            )


if __name__ == "__main__":
    main()
