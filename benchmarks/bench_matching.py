"""Matching benchmark: accuracy on disguised copies, the spectral solution against the
exhaustive optimum, two different scenes of a rule set against the derivation's types,
and time.

    .venv/bin/python benchmarks/bench_matching.py              # everything, 4 seeds per rule set
    .venv/bin/python benchmarks/bench_matching.py --seeds 8
    .venv/bin/python benchmarks/bench_matching.py --only copies
    .venv/bin/python benchmarks/bench_matching.py --seeds 8 --first-seed 8   # scenes 8..15
    .venv/bin/python benchmarks/bench_matching.py --only copies --misses     # what each scene got wrong

Copies: each scene against ``perturbed_copy`` of it (every type and id renamed, 5 cm
jitter, one standing object removed, one box added, order shuffled). "Kept and right"
counts kept pairs that take an object to its copy or to the copy of an object
``interchangeable`` with it in the original (the same box and the same relations, with
the same measures: two identical chairs that stand alone; nothing in the structure
graph tells them apart, so any matching of one is as good as the other's); "assigned
right" the same before the confidence threshold; "kept, own copy" the strict count
(only an object's own copy is right). "As good as the truth" counts pairs whose
matching scores at least the true one's energy. The baseline matches by box
similarity alone (Hungarian on phi_i). The last line counts the relations between
surviving objects that the copy's moves changed (the relations are thresholds, and a
5 cm move carries a pair across one).
Exhaustive: layout subgraphs cut to 7 objects, spectral (no refinement: the better
of the two relaxations' Hungarian assignments) and refined, against the best of all
7! assignments. Time: CPU seconds of this process
(``time.process_time``), which do not grow when other work shares the machine. Prints
figures only; nothing is asserted.
"""

from __future__ import annotations

import argparse
import time
from collections import defaultdict
from dataclasses import replace

import numpy as np
from scipy.optimize import linear_sum_assignment

from scenewright.api import build_scene
from scenewright.variation.matching import (
    box_similarity,
    exhaustive_solution,
    interchangeable,
    layout_problem,
    match_graphs,
    solve,
)
from scenewright.variation.perturb import perturbed_copy
from scenewright.variation.structure import structure_graph

RULE_SETS = ("bedroom", "living_room", "kitchen", "study", "classroom", "bathroom", "desk")


def scenes_of(seeds: int, first: int = 0) -> dict[str, list]:
    return {
        rules: [build_scene(rules, seed) for seed in range(first, first + seeds)]
        for rules in RULE_SETS
    }


def copies(scenes: dict[str, list], misses: bool = False) -> None:
    print("disguised copies (types renamed, 5 cm jitter, one removed, one added):")
    print(
        f"  {'rule set':12s} objects  kept+right  assigned-right  as-good-as-truth  baseline  spurious-kept  kept,own-copy"
    )
    totals, changes = defaultdict(float), defaultdict(int)
    for rules, group in scenes.items():
        row = defaultdict(float)
        for seed, scene in enumerate(group):
            copy, truth = perturbed_copy(scene, np.random.default_rng(seed))
            first, second = structure_graph(scene), structure_graph(copy)
            loose = match_graphs(first, second, threshold=0.0)
            matching = match_graphs(first, second)
            kept = matching.mapping()
            problem, nodes_a, nodes_b = layout_problem(first, second)
            found = solve(problem)
            true = _truth_assignment(problem, first, second, nodes_a, nodes_b, truth)
            shortfall = problem.energy(true) - problem.energy(found)
            row["tie_pairs"] += 1
            row["ties"] += shortfall <= 1e-9
            if misses:
                _print_misses(scene, first, matching, truth, shortfall)
            baseline = _baseline(first, second, nodes_a, nodes_b)
            row["objects"] += sum(first.ids[i] in truth for i in nodes_a)
            row["kept"] += _right(kept, first, truth)
            row["assigned"] += _right(loose.mapping(), first, truth)
            row["baseline"] += _right(baseline, first, truth)
            row["strict"] += sum(kept.get(a) == b for a, b in truth.items())
            for key, count in _relation_changes(first, second, truth).items():
                changes[key] += count
            for pair in loose.pairs:
                if pair.a not in truth or not pair.b.startswith("thing_"):
                    row["spurious"] += 1
                    row["spurious_kept"] += pair.b in kept.values() and kept.get(pair.a) == pair.b
        for key, value in row.items():
            totals[key] += value
        _print_row(rules, row)
    _print_row("all", totals)
    print(
        f"  relations between surviving standing objects: {changes['held']}; the copy's moves made "
        f"{changes['vanished']} vanish and {changes['appeared']} appear, turned {changes['V/C']} from contact "
        f"to close or back, {changes['A']} aligned and {changes['F']} facing on or off"
    )


def _relation_changes(first, second, truth: dict[str, str]) -> dict[str, int]:
    """How the disguised copy's moves changed the relations between surviving standing
    objects: held (in the original), vanished, appeared, and V/C, A, F flipped (a
    relation held one way round and not in the copy, or the reverse)."""
    counts = defaultdict(int)
    where = {second.ids[k]: k for k in second.layout_nodes()}
    pairs = {(i, j) for i in first.layout_nodes() for j in first.layout_nodes() if i < j}
    for i, j in sorted(pairs):
        if first.ids[i] not in truth or first.ids[j] not in truth:
            continue
        k, m = where[truth[first.ids[i]]], where[truth[first.ids[j]]]
        before = first.relation_set(i, j) | first.relation_set(j, i)
        after = second.relation_set(k, m) | second.relation_set(m, k)
        counts["held"] += bool(before)
        counts["vanished"] += bool(before) and not after
        counts["appeared"] += bool(after) and not before
        if before and after:
            counts["V/C"] += ("V" in before) != ("V" in after) or ("C" in before) != ("C" in after)
            counts["A"] += ("A" in before) != ("A" in after)
            counts["F"] += first.relation_set(i, j) & {"F"} != second.relation_set(k, m) & {
                "F"
            } or (first.relation_set(j, i) & {"F"} != second.relation_set(m, k) & {"F"})
    return counts


def _print_misses(scene, first, matching, truth: dict[str, str], shortfall: float) -> None:
    """The surviving objects a scene's matching got wrong or withdrew, and how far its
    energy is below the true matching's."""
    group, original = interchangeable(first), {b: a for a, b in truth.items()}
    lines = []
    for pair in matching.pairs + matching.withdrawn:
        right = pair.b in original and group.get(original[pair.b]) == group.get(pair.a)
        if pair.a in truth and not (right and pair in matching.pairs):
            taken = original.get(pair.b, "the added box")
            state = "kept" if pair in matching.pairs else "withdrawn"
            lines.append(
                f"      {pair.a} -> copy of {taken}, confidence {pair.confidence:.2f}, {state}"
            )
    if lines or shortfall > 1e-9:
        energy = (
            f"{shortfall:.3f} below the truth's" if shortfall > 1e-9 else "at least the truth's"
        )
        print(f"    {scene.rules} seed {scene.seed}: energy {energy}")
        print("\n".join(lines))


def _print_row(name, row) -> None:
    n = max(row["objects"], 1)
    spurious = f"{row['spurious_kept']:.0f}/{row['spurious']:.0f}"
    print(
        f"  {name:12s} {row['objects']:7.0f}  {row['kept'] / n:10.3f}  {row['assigned'] / n:14.3f}  "
        f"{row['ties'] / max(row['tie_pairs'], 1):16.3f}  {row['baseline'] / n:8.3f}  {spurious:>13s}  {row['strict'] / n:13.3f}"
    )


def _right(mapping: dict[str, str], first, truth: dict[str, str]) -> int:
    """Pairs of ``mapping`` that take an object to the copy of itself or of an object
    interchangeable with it (``interchangeable``: the same box and the same relations,
    so nothing tells the two apart; the removed object may be one of them)."""
    group = interchangeable(first)
    original = {b: a for a, b in truth.items()}
    return sum(b in original and group.get(original[b]) == group.get(a) for a, b in mapping.items())


def _truth_assignment(problem, first, second, nodes_a, nodes_b, truth) -> np.ndarray:
    size = problem.size
    where_b = {second.ids[k]: position for position, k in enumerate(nodes_b)}
    assignment = -np.ones(size, dtype=int)
    for position, i in enumerate(nodes_a):
        if truth.get(first.ids[i]) in where_b:
            assignment[position] = where_b[truth[first.ids[i]]]
    free = [k for k in range(size) if k not in set(assignment.tolist())]
    for position in range(size):
        if assignment[position] < 0:
            assignment[position] = free.pop()
    return assignment


def _baseline(first, second, nodes_a, nodes_b) -> dict[str, str]:
    similarity = box_similarity(first.sizes[nodes_a], second.sizes[nodes_b])
    rows, columns = linear_sum_assignment(-similarity)
    return {
        first.ids[nodes_a[r]]: second.ids[nodes_b[c]] for r, c in zip(rows, columns, strict=False)
    }


def _cut(scene, count: int):
    """The scene with only its first ``count`` standing objects and what they carry."""
    graph = structure_graph(scene)
    keep = graph.layout_nodes()[:count]
    ids = {graph.ids[i] for i in keep} | {graph.ids[j] for i in keep for j in graph.carried(i)}
    objects = [o for o in scene.placed_objects() if o.id in ids]
    relations = [r for r in scene.relations if r.source in ids and r.target in ids]
    return replace(scene, objects=objects, relations=relations)


def exhaustive(scenes: dict[str, list], size: int = 7) -> None:
    print(f"spectral against the exhaustive optimum (layout subgraphs of at most {size} objects):")
    ratios = {"spectral": [], "refined": []}
    for _rules, group in scenes.items():
        for a in range(len(group)):
            for b in range(len(group)):
                if a == b:
                    continue
                problem, _, _ = layout_problem(
                    structure_graph(_cut(group[a], size)), structure_graph(_cut(group[b], size))
                )
                if problem.size < 2:
                    continue
                _, best = exhaustive_solution(problem)
                for name, refined in (("spectral", False), ("refined", True)):
                    ratios[name].append(problem.energy(solve(problem, refined=refined)) / best)
    for name, values in ratios.items():
        values = np.array(values)
        print(
            f"  {name:9s} pairs {len(values)}: within 95 % of the optimum in {100 * (values >= 0.95).mean():.1f} %, "
            f"mean ratio {values.mean():.3f}, worst {values.min():.3f}"
        )


def roles(scenes: dict[str, list]) -> None:
    print(
        "two different scenes of a rule set, pairs kept against the derivation (same type = same role):"
    )
    for rules, group in scenes.items():
        right = kept = possible = 0
        for a in range(len(group)):
            b = (a + 1) % len(group)
            first, second = structure_graph(group[a]), structure_graph(group[b])
            matching = match_graphs(first, second)
            kept += len(matching.pairs)
            right += sum(
                first.types[first.index(p.a)] == second.types[second.index(p.b)]
                for p in matching.pairs
            )
            types_a = [first.types[i] for i in first.layout_nodes()]
            types_b = [second.types[i] for i in second.layout_nodes()]
            possible += sum(min(types_a.count(t), types_b.count(t)) for t in set(types_a))
        print(
            f"  {rules:12s} precision {right / max(kept, 1):.3f}  recall {right / max(possible, 1):.3f}  ({kept} kept)"
        )


def timing(scenes: dict[str, list]) -> None:
    print("time to match two scenes of 20 standing objects (CPU seconds):")
    big = [
        _cut(s, 20)
        for group in scenes.values()
        for s in group
        if len(structure_graph(s).layout_nodes()) >= 20
    ]
    for seed, scene in enumerate(big[:5]):
        copy, _ = perturbed_copy(scene, np.random.default_rng(seed))
        started = time.process_time()
        first, second = structure_graph(scene), structure_graph(copy)
        built = time.process_time()
        matching = match_graphs(first, second)
        done = time.process_time()
        print(
            f"  {scene.rules} seed {scene.seed}: {len(first.layout_nodes())} x {len(second.layout_nodes())} standing "
            f"objects: structure graphs {built - started:.3f} s, matching {done - built:.3f} s "
            f"({matching.seconds:.3f} s inside match_graphs)"
        )


def main() -> None:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("--seeds", type=int, default=4, help="scenes per rule set (4)")
    parser.add_argument(
        "--first-seed", type=int, default=0, help="first scene seed (0), to measure on other scenes"
    )
    parser.add_argument("--only", choices=("copies", "exhaustive", "roles", "timing"))
    parser.add_argument(
        "--misses", action="store_true", help="copies: list each scene's wrong or withdrawn objects"
    )
    args = parser.parse_args()
    scenes = scenes_of(args.seeds, args.first_seed)
    runs = (
        ("copies", lambda s: copies(s, args.misses)),
        ("exhaustive", exhaustive),
        ("roles", roles),
        ("timing", timing),
    )
    for name, run in runs:
        if args.only in (None, name):
            run(scenes)


if __name__ == "__main__":
    main()
