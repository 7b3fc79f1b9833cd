"""Variation benchmark: regrowing deleted objects, and many variants from three examples.

    .venv/bin/python benchmarks/bench_variation.py                 # both, default sizes
    .venv/bin/python benchmarks/bench_variation.py --only regrow --seeds 6
    .venv/bin/python benchmarks/bench_variation.py --only vary --count 40
    .venv/bin/python benchmarks/bench_variation.py --only sets --count 20 --set-seeds 1 1000

Regrow: in generated scenes, each standing object that has a neighbour is deleted (with
what it carries); the Augmented Graph of the cut scene and the full one is built, and
the object grown back into the cut scene (``grow_node`` + ``apply_change``). Reported:
how often it lands within 0.2 m and 15 degrees of where it was.

Vary: three generated scenes of a rule set (seeds 1, 2, 3) as examples, ``vary`` asked
for N variants. Reported: variants made, layouts ok, overlap problems, distinct, new
(type multiset or relation set unlike every example's), operations used, CPU seconds.
Sets (``--only sets``): ``vary`` on example folders, the shipped desks and bedrooms and
the learning benchmark's reading corners, music rooms and dining rooms
(``example_sets.py``). Reported: the share of variants laid out ok, the share new, the
operations of each kind. Prints figures only; nothing is asserted.
"""

from __future__ import annotations

import argparse
import math
import time
from collections import Counter
from dataclasses import replace

import numpy as np

from scenewright.api import build_scene
from scenewright.examples import Example
from scenewright.variation import augment, structure_graph
from scenewright.variation.index import is_new
from scenewright.variation.operations import grow_node
from scenewright.variation.synthesis import Variant, apply_change, signature, start_variant, vary


def as_example(scene, name: str) -> Example:
    return Example(name, name, "scene.json", scene)


def regrow(rule_sets: list[str], seeds: int) -> None:
    print("regrowing a deleted object from the Augmented Graph:")
    for rules in rule_sets:
        close = tried = failed = 0
        for seed in range(seeds):
            scene = build_scene(rules, seed)
            graph = structure_graph(scene)
            for i in graph.layout_nodes():
                if not graph.neighbours(i, set(graph.layout_nodes())):
                    continue
                gone = {graph.ids[i], *(graph.ids[j] for j in graph.carried(i))}
                cut = replace(
                    scene,
                    objects=[o for o in scene.objects if o.id not in gone],
                    relations=[
                        r for r in scene.relations if r.source not in gone and r.target not in gone
                    ],
                )
                ag = augment([as_example(cut, "cut"), as_example(scene, "full")])
                variant = start_variant(0, as_example(cut, "cut"))
                change = grow_node(variant, ag, ag.node_of[(1, graph.ids[i])], (1, graph.ids[i]))
                tried += 1
                done = (
                    apply_change(variant, ag, change, np.random.default_rng(seed))
                    if change
                    else None
                )
                if done is None:
                    failed += 1
                    continue
                grown = done.objects()[change.added[0][0].id]
                original = scene.object(graph.ids[i])
                distance = math.hypot(
                    grown.position[0] - original.position[0],
                    grown.position[2] - original.position[2],
                )
                turn = abs(math.remainder(grown.yaw - original.yaw, 2 * math.pi))
                close += distance <= 0.2 and turn <= math.radians(15)
        print(
            f"  {rules:12s} {tried} objects: within 0.2 m and 15 deg {close / max(tried, 1):.3f}; "
            f"not regrown (no layout found, or too incompatible) {failed}"
        )


def variants(rule_sets: list[str], count: int) -> None:
    print(f"{count} variants from three examples (seeds 1, 2, 3), vary seed 1:")
    for rules in rule_sets:
        examples = [as_example(build_scene(rules, seed), f"{rules}{seed}") for seed in (1, 2, 3)]
        started = time.process_time()
        results = vary(examples, count, 1)
        seconds = time.process_time() - started
        ok = sum(r.scene.layout.ok for r in results)
        overlaps = sum(any("overlap" in p for p in r.scene.layout.problems) for r in results)
        keys = {signature(Variant(r.scene, dict(r.origin))) for r in results}
        new = sum(is_new(r, examples) for r in results)
        operations = Counter(op["operation"] for r in results for op in r.operations)
        print(
            f"  {rules:12s} made {len(results)}: ok {ok}, with overlaps {overlaps}, distinct {len(keys)}, new {new}; "
            f"K {min((r.compatibility for r in results), default=0):.2f}..{max((r.compatibility for r in results), default=0):.2f}; "
            f"operations {dict(sorted(operations.items()))}; {seconds:.1f} CPU s"
        )


def example_sets(count: int, seeds: list[int]) -> None:
    """``vary`` on example folders: the shipped desks and bedrooms, and the learning
    benchmark's own reading corners, music rooms and dining rooms (nine each, written
    with each of ``seeds``, varied with that seed)."""
    import sys
    import tempfile
    from pathlib import Path

    sys.path.insert(0, str(Path(__file__).resolve().parent))
    from example_sets import KINDS, write_set

    from scenewright.examples import load_examples

    root = Path(__file__).resolve().parents[1] / "examples" / "sets"
    print(f"{count} variants of each example set:")
    for seed in seeds:
        with tempfile.TemporaryDirectory() as folder:
            sets = [("desks", sorted((root / "desks").glob("*.json")))]
            sets.append(("bedrooms", sorted((root / "bedrooms").glob("*.json"))))
            sets += [(kind, write_set(kind, 9, seed, Path(folder) / kind)) for kind in KINDS]
            for name, paths in sets:
                examples = load_examples(paths)
                started = time.process_time()
                results = vary(examples, count, seed)
                seconds = time.process_time() - started
                ok = sum(r.scene.layout.ok for r in results)
                new = sum(is_new(r, examples) for r in results)
                operations = Counter(op["operation"] for r in results for op in r.operations)
                print(
                    f"  seed {seed} {name:9s} made {len(results)}: ok {ok / max(len(results), 1):.0%}, "
                    f"new {new / max(len(results), 1):.0%}; operations "
                    f"{', '.join(f'{operations[k]} {k}' for k in ('replace', 'grow', 'transfer'))}; "
                    f"{seconds:.1f} CPU s",
                    flush=True,
                )


OPTIONS = (
    ("--seeds", int, 4, "scenes per rule set for regrow (4)"),
    ("--count", int, 40, "variants asked for (40)"),
    (
        "--rules",
        str,
        "bedroom,living_room,study",
        "rule sets, comma-separated (bedroom,living_room,study)",
    ),
)


def main() -> None:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    for flag, kind, default, words in OPTIONS:
        parser.add_argument(flag, type=kind, default=default, help=words)
    parser.add_argument("--only", choices=("regrow", "vary", "sets"))
    parser.add_argument(
        "--set-seeds", type=int, nargs="+", default=[1, 1000], help="seeds of --only sets (1 1000)"
    )
    args = parser.parse_args()
    rule_sets = args.rules.split(",")
    if args.only == "sets":
        example_sets(args.count, args.set_seeds)
        return
    if args.only != "vary":
        regrow(rule_sets, args.seeds)
    if args.only != "regrow":
        variants(rule_sets, args.count)


if __name__ == "__main__":
    main()
