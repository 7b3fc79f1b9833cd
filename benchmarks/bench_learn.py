"""How close ``scenewright learn`` comes to a rule set it never saw, from its scenes alone.

    .venv/bin/python benchmarks/bench_learn.py desk --scenes 40
    .venv/bin/python benchmarks/bench_learn.py desk study kitchen --scenes 100 --check 50
    .venv/bin/python benchmarks/bench_learn.py --examples examples/sets/desks/*.json

For each shipped rule set: lay out scenes 0..N-1 (cached as ``bench_relations`` caches
them; failed layouts left out), learn a rule set from their scene.json files as
``scenewright learn`` does (``learn_rule_set``, its check generating ``--check``
scenes), and print

- the relations written against the grammar's (every pair of object types some
  relation statement links in those scenes): precision and recall, and for each true
  pair the labels the grammar used next to the labels learned;
- the check of ``learn`` (learned rules against the examples: mean total variation of
  per-type counts, mean difference of the share of scenes holding each related pair,
  the share of related objects whose written placement holds) beside the same
  comparison of the true rule set against the examples (``--check`` fresh scenes of
  it): the floor that sampling alone gives.

With ``--examples`` it learns from the files given (no truth to score against) and
prints the check beside nothing. Prints figures only; nothing is asserted.
"""

from __future__ import annotations

import argparse
import sys
import tempfile
import time
from collections import defaultdict
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_relations import generated_scenes  # noqa: E402  (the shared scene cache)

from scenewright.api import build_scene, load_rules  # noqa: E402
from scenewright.core.relations import RELATIONS  # noqa: E402
from scenewright.examples import load_examples  # noqa: E402
from scenewright.learning.learn import Check, compare, learn_rule_set  # noqa: E402


def grammar_labels(scenes) -> dict[tuple[str, str], set[str]]:
    """(a, b) sorted type pair -> the labels of relation edges between objects of the
    two types in ``scenes`` (written ``child LABEL parent``, Implicit forms by their base)."""
    found: dict[tuple[str, str], set[str]] = defaultdict(set)
    for scene in scenes:
        types = {o.id: o.type for o in scene.placed_objects()}
        for relation in scene.relations:
            if relation.source in types and relation.target in types:
                pair = tuple(sorted((types[relation.source], types[relation.target])))
                found[pair].add(RELATIONS[relation.label].base)
    return found


def check_line(check: Check) -> str:
    pairs = (
        np.mean([abs(p["examples_both"] - p["generated_both"]) for p in check.pairs])
        if check.pairs
        else 0.0
    )
    held = [
        p["generated_label_holds"] for p in check.pairs if p["generated_label_holds"] is not None
    ]
    holds = f"{np.mean(held):.0%}" if held else "-"
    return (
        f"counts {check.mean_total_variation:.3f}, pairs {pairs:.3f}, placements hold {holds}, "
        f"{check.layouts_ok}/{check.scenes} layouts ok"
    )


def learn_from(examples, check: int, seed: int):
    with tempfile.TemporaryDirectory() as folder:
        started = time.process_time()
        learned = learn_rule_set(
            examples,
            Path(folder) / "learned.rules",
            seed=seed,
            check=0,
            write=lambda p, t: None,
            build_scene=build_scene,
        )
        seconds = time.process_time() - started
        rules = Path(folder) / "learned.rules"
        rules.write_text(learned.text)
        scenes = [e.scene for e in examples]
        from scenewright.learning.induce import renamed_scenes

        renamed, _ = renamed_scenes(examples)
        result = (
            compare(learned.induction, renamed, load_rules(rules), check, seed, build_scene)
            if check
            else None
        )
    return learned, result, seconds, scenes


def evaluate(name: str, count: int, check: int, seed: int, cache: Path, workers: int) -> None:
    paths, failed, _ = generated_scenes(name, count, cache, workers)
    examples = load_examples(paths)
    learned, result, seconds, scenes = learn_from(examples, check, seed)
    induction = learned.induction
    truth = grammar_labels(scenes)
    written = induction.written_pairs()
    hits = set(written) & set(truth)
    precision = len(hits) / len(written) if written else float("nan")
    recall = len(hits) / len(truth) if truth else float("nan")
    print(
        f"{name}: {len(paths)} examples ({failed} failed layouts left out); learned in {seconds:.1f} CPU s: "
        f"{len(induction.catalog)} types, {len(induction.groups)} groups, {len(written)} relations written; "
        f"against the grammar's {len(truth)} pairs: precision {precision:.2f}, recall {recall:.2f}"
    )
    for pair in sorted(set(truth) | set(written)):
        member = written.get(pair)
        learned_labels = (
            " | ".join("+".join(p.labels) for p in member.placements) if member else "-"
        )
        print(
            f"    {pair[0]}-{pair[1]}: grammar {'+'.join(sorted(truth.get(pair, ()))) or '-'}; learned {learned_labels}"
        )
    if result is not None:
        floor = compare(
            induction, [e.scene for e in examples], load_rules(name), check, seed + 1, build_scene
        )
        print(f"  learned rules vs examples: {check_line(result)}")
        print(f"  {name}.rules  vs examples: {check_line(floor)}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("rules", nargs="*", help="shipped rule sets")
    parser.add_argument("--scenes", type=int, default=40, help="example scenes per rule set (40)")
    parser.add_argument("--check", type=int, default=50, help="scenes generated to compare (50)")
    parser.add_argument("--seed", type=int, default=0, help="seed of learn (0)")
    parser.add_argument("--workers", type=int, default=2, help="processes laying scenes out (2)")
    parser.add_argument(
        "--cache", type=Path, default=Path(tempfile.gettempdir()) / "scenewright-bench-relations"
    )
    parser.add_argument("--examples", nargs="+", type=Path, help="learn from these files instead")
    args = parser.parse_args()
    if args.examples:
        examples = load_examples(args.examples)
        learned, result, seconds, _ = learn_from(examples, args.check, args.seed)
        print(
            f"{len(examples)} examples: learned in {seconds:.1f} CPU s; {len(learned.induction.written_pairs())} "
            f"relations written"
        )
        if result is not None:
            print(f"  learned rules vs examples: {check_line(result)}")
    for name in args.rules:
        evaluate(name, args.scenes, args.check, args.seed, args.cache, args.workers)


if __name__ == "__main__":
    main()
