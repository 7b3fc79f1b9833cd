"""Which type pairs ``scenewright relations`` finds, against the pairs the grammar relates.

    .venv/bin/python benchmarks/bench_relations.py                       # every shipped rule set, 500 scenes
    .venv/bin/python benchmarks/bench_relations.py desk kitchen --scenes 200
    .venv/bin/python benchmarks/bench_relations.py classroom --scenes 100 --workers 2
    .venv/bin/python benchmarks/bench_relations.py --generate-only        # fill the scene cache, nothing else
    .venv/bin/python benchmarks/bench_relations.py --jitter               # one planted relation, growing jitter
    .venv/bin/python benchmarks/bench_relations.py benchmarks/relation_rules/*.rules   # rule sets the tests were not tuned on
    .venv/bin/python benchmarks/bench_relations.py village --floor 0.3   # another nearest-neighbour tightness floor

For each rule set: lay out scenes 0..N-1 with ``api.build_scene`` (expansion and
layout, no description, no render) and keep their scene.json in a cache folder
(``--cache``, default a folder in the system's temp directory, keyed by a digest of the
rules files and of the generator's and core's sources, so a changed rule set or layout
is generated afresh); scenes whose layout failed are left out, as a dataset leaves them
out. The truth is every unordered pair of object types that some relation statement
of the grammar links in these scenes (the relation edges of their scene graphs between
two objects, Implicit ones included; edges to walls, windows, the room, groups and
paths relate no two object types, and neither does a pair the grammar relates only
through a group: a blacksmith's group next to a tower). Not every true pair can be
seen in the poses: a relation whose anchor the room pins (a counter next to a sink
that stands under a fixed window) puts its objects in the same place in every scene,
so no test of where things stand relative to each other, within against across
scenes, can tell it from the room's own pattern. So each true pair is also tested by
an *oracle*, the permutation test's energy test told which objects the grammar linked
(``oracle_verdicts``: one linked edge per scene, the source in its target's frame,
against the source of the other scene's edge, on random pairs of scenes): the pair is
*shown by the geometry* when p <= 0.01 and the linked poses are the tighter
(tightness > 0), and not shown when fewer than 20 scenes link it. Recall is printed
against all true pairs and against the shown ones; precision always against all of
them: the oracle only says which misses no test of poses could avoid at this many
scenes. Then each test of ``learning.relation_finding`` (the
permutation test, the angle test, co-occurrence) is run on the cached scene.json files
as ``scenewright relations`` reads them, and its precision and recall against the
truth are printed with the pairs it missed (with their p-value and strength, or
pruned) and the ones it made up. ``--jitter`` shows instead what the permutation and
the angle test make of one planted relation as its jitter grows. With more than one
rule set, a last table gives every set's precision and recall per test.

Prints figures only; nothing is asserted.
"""

from __future__ import annotations

import argparse
import hashlib
import math
import multiprocessing
import tempfile
import time
from collections import Counter, defaultdict
from pathlib import Path

import numpy as np

from scenewright import __version__
from scenewright.api import build_scene, load_rules, reproducible_json
from scenewright.core.scene import Scene
from scenewright.examples import load_examples
from scenewright.generator.rules import shipped_rule_sets

PACKAGE_ROOT = Path(__file__).resolve().parent.parent
#: Sources whose change changes the scenes a seed makes (the cache key covers them).
GENERATING_SOURCES = ("generator", "core")


def cache_folder(root: Path, name: str) -> Path:
    """The folder of ``name``'s cached scenes: keyed by the rules files, the generating
    code and the version, so any change to them starts a new folder."""
    rules = load_rules(name)
    digest = hashlib.sha256(__version__.encode())
    files = sorted(Path(rules.path).parent.rglob("*.rules"))
    for folder in GENERATING_SOURCES:
        files += sorted((PACKAGE_ROOT / folder).rglob("*.py"))
    for path in files:
        digest.update(path.name.encode())
        digest.update(path.read_bytes())
    return root / f"{Path(name).stem}-{digest.hexdigest()[:16]}"


def _make_scene(job: tuple[str, int, str]) -> tuple[int, bool, float]:
    """Lay out scene ``seed`` of rule set ``name`` into ``folder/SEED.json`` (a failed
    layout into ``SEED.failed.json``); return the seed, whether it is ok, CPU seconds."""
    name, seed, folder = job
    started = time.process_time()
    scene = build_scene(name, seed)
    suffix = ".json" if scene.layout.ok else ".failed.json"
    target = Path(folder) / f"{seed:06d}{suffix}"
    partial = target.with_suffix(".partial")
    partial.write_text(reproducible_json(scene))
    partial.replace(target)
    return seed, scene.layout.ok, time.process_time() - started


def generated_scenes(
    name: str, count: int, cache: Path, workers: int
) -> tuple[list[Path], int, float]:
    """The scene.json files of seeds 0..count-1 of ``name`` whose layout is ok (made
    where the cache lacks them); also the number of failed layouts and the CPU seconds
    spent making scenes now."""
    folder = cache_folder(cache, name)
    folder.mkdir(parents=True, exist_ok=True)
    missing = [
        (name, seed, str(folder))
        for seed in range(count)
        if not (folder / f"{seed:06d}.json").exists()
        and not (folder / f"{seed:06d}.failed.json").exists()
    ]
    spent = 0.0
    if missing:
        with multiprocessing.get_context("forkserver").Pool(workers) as pool:
            for _, _, seconds in pool.imap_unordered(_make_scene, missing, chunksize=4):
                spent += seconds
    ok = [
        folder / f"{seed:06d}.json"
        for seed in range(count)
        if (folder / f"{seed:06d}.json").exists()
    ]
    return ok, count - len(ok), spent


def true_pairs(scenes: list[Scene]) -> Counter:
    """Unordered object type pairs some relation edge links, with the number of scenes
    holding such an edge."""
    return Counter({pair: len(links) for pair, links in linked_objects(scenes).items()})


def linked_objects(scenes: list[Scene]) -> dict[tuple[str, str], dict[int, list[tuple[str, str]]]]:
    """Per unordered type pair some relation edge links: per scene index, the (source,
    target) object ids of those edges."""
    links: dict = defaultdict(lambda: defaultdict(list))
    for index, scene in enumerate(scenes):
        types = {o.id: o.type for o in scene.placed_objects()}
        for r in scene.relations:
            if r.source in types and r.target in types:
                edges = links[tuple(sorted((types[r.source], types[r.target])))][index]
                if (
                    r.source,
                    r.target,
                ) not in edges:  # one edge per object pair, however many labels
                    edges.append((r.source, r.target))
    return links


def oracle_verdicts(
    scenes: list[Scene], seed: int
) -> dict[tuple[str, str], tuple[bool, float | None, float | None]]:
    """Per true pair: whether the geometry shows it to a test told which objects the
    grammar linked, with that test's p-value and tightness (None, None: in fewer than
    ``PAIR_SCENES`` scenes). The test is the permutation test's (random pairs of scenes,
    energy distance, ``PERMUTATIONS`` flip patterns), on one linked edge per scene: the
    source's pose in its target's frame, against the source of the paired scene's edge
    in the target's frame; the pair shows when p <= ``ALPHA`` and the within-scene poses
    are tighter (tightness > 0)."""
    import numpy as np

    from scenewright.learning.relation_poses import pair_stream, relative_poses
    from scenewright.learning.relation_statistics import flip_test
    from scenewright.learning.relation_thresholds import ALPHA, PAIR_SCENES, PERMUTATIONS

    verdicts = {}
    for (a, b), per_scene in linked_objects(scenes).items():
        rng = pair_stream(seed, a, b)
        indices = sorted(per_scene)
        if len(indices) < PAIR_SCENES:
            verdicts[(a, b)] = (False, None, None)
            continue
        objects = [{o.id: o for o in scenes[index].placed_objects()} for index in indices]
        # One edge per scene, of the pair's usual direction (source type, target type).
        directions = Counter(
            (objects[k][s].type, objects[k][t].type)
            for k, i in enumerate(indices)
            for s, t in per_scene[i]
        )
        usual = directions.most_common(1)[0][0]
        edges = []
        for k, index in enumerate(indices):
            options = [
                (s, t)
                for s, t in per_scene[index]
                if (objects[k][s].type, objects[k][t].type) == usual
            ]
            if options:
                source, target = options[int(rng.integers(len(options)))]
                edges.append((objects[k][source], objects[k][target]))
        order = rng.permutation(len(edges))
        pairs = len(order) // 2
        ones, twos = order[:pairs], order[pairs : 2 * pairs]  # scene pair k: ones[k], twos[k]
        targets = _poses([edges[k][1] for k in np.concatenate([ones, twos])])
        sources = _poses([edges[k][0] for k in np.concatenate([ones, twos])])
        swapped = np.concatenate([sources[pairs:], sources[:pairs]])  # the other scene's source
        within = relative_poses(targets, sources[:, None])[:, 0]
        across = relative_poses(targets, swapped[:, None])[:, 0]
        _, p_value, tightness = flip_test(within, across, PERMUTATIONS, rng)
        verdicts[(a, b)] = (p_value <= ALPHA and tightness > 0, p_value, tightness)
    return verdicts


def _poses(objects: list) -> np.ndarray:
    """(x, z, yaw) of each object -> (n, 3)."""

    return np.array([(o.position[0], o.position[2], o.yaw) for o in objects])


def scored(found: set, truth: set) -> tuple[float, float]:
    hits = len(found & truth)
    precision = hits / len(found) if found else float("nan")
    recall = hits / len(truth) if truth else float("nan")
    return precision, recall


def evaluate(
    name: str, paths: list[Path], failed: int, seed: int
) -> dict[str, tuple[float, float]]:
    """Print how each test fares on the scenes ``paths``; return per test its precision
    and recall."""
    from scenewright.learning.relation_finding import find_relations
    from scenewright.learning.relation_tests import TESTS

    started = time.process_time()
    examples = load_examples(paths)
    loading = time.process_time() - started
    truth_counts = true_pairs([e.scene for e in examples])
    truth = set(truth_counts)
    oracle = oracle_verdicts([e.scene for e in examples], seed)
    visible = {pair for pair, (shows, _, _) in oracle.items() if shows}
    print(
        f"{name}: {len(paths)} scenes ({failed} failed layouts left out), {len(truth)} true pairs, "
        f"{len(visible)} of them shown by the geometry; reading {loading:.1f} CPU s"
    )
    hidden = sorted(truth - visible)
    if hidden:
        print(
            "  not shown even to a test told the linked objects: "
            + ", ".join(f"{a}-{b} ({_oracle_figures(oracle[(a, b)])})" for a, b in hidden)
        )
    scores = {}
    for test in TESTS:
        started = time.process_time()
        result = find_relations([e.scene for e in examples], test=test, seed=seed)
        seconds = time.process_time() - started
        found = {(pair.a, pair.b) for pair in result.pairs if pair.related}
        precision, recall = scored(found, truth)
        scores[test] = (precision, recall)
        _, shown_recall = scored(found, visible)
        pruned = sum(pair.pruned for pair in result.pairs)
        print(
            f"  {test:12s} precision {precision:.2f}  recall {recall:.2f}  recall of the shown {shown_recall:.2f}  "
            f"({len(found & truth)} of {len(found)} found are true; {pruned} pruned as indirect; "
            f"{len(result.pairs)} pairs tested; {seconds:.1f} CPU s)"
        )
        missed = sorted(truth - found)
        extra = sorted(found - truth)
        verdicts = {(pair.a, pair.b): pair for pair in result.pairs}
        if missed:
            print(
                "    missed: "
                + ", ".join(
                    f"{a}-{b} ({truth_counts[(a, b)]} scenes{_figures(verdicts.get((a, b)))})"
                    for a, b in missed
                )
            )
        if extra:
            print("    not in the grammar: " + ", ".join(f"{a}-{b}" for a, b in extra))
    return scores


def summary(scores: dict[str, dict[str, tuple[float, float]]]) -> str:
    """A table of every rule set's precision and recall per test ("-" where there is no
    true pair, or nothing found)."""
    tests = list(next(iter(scores.values())))
    width = max(len(name) for name in scores) + 2
    lines = [
        " " * width + "".join(f"{test:>22s}" for test in tests),
        " " * width + "".join(f"{'precision  recall':>22s}" for _ in tests),
    ]
    for name, per_test in scores.items():
        cells = "".join(
            f"{'-' if math.isnan(p) else f'{p:.2f}':>13s}{'-' if math.isnan(r) else f'{r:.2f}':>9s}"
            for p, r in per_test.values()
        )
        lines.append(f"{name:<{width}s}{cells}")
    return "\n".join(lines)


def _oracle_figures(verdict: tuple[bool, float | None, float | None]) -> str:
    """The told test's p-value and tightness of a pair the geometry does not show."""
    _, p_value, tightness = verdict
    return "too few scenes" if p_value is None else f"p {p_value:.3g}, tightness {tightness:.2f}"


def _figures(pair) -> str:
    """How a missed pair fared: pruned, or its p-value and strength."""
    if pair is None or not pair.tested:
        return ", untested"
    if pair.pruned:
        return ", pruned"
    p_value = "" if pair.p_value is None else f", p {pair.p_value:.3g}"
    return f"{p_value}, strength {pair.strength:.2f}"


def jitter_sweep(count: int, seed: int) -> None:
    """A chair 0.9 m in front of a table and turned to face it, placed with Gaussian
    jitter of each size, in ``count`` scenes of 8 x 8 m: what each test makes of it."""
    import numpy as np

    from scenewright.core.scene import SceneObject
    from scenewright.learning.relation_finding import find_relations

    def scene(placed):
        objects = [
            SceneObject(
                id=f"{kind}{k}",
                type=kind,
                kind="object",
                noun=kind,
                plural=None,
                parent=None,
                style=None,
                position=[x, 0.0, z],
                yaw=yaw,
                size=[0.5, 0.8, 0.5],
                order=k,
            )
            for k, (kind, x, z, yaw) in enumerate(placed)
        ]
        return Scene(
            rules="jitter", seed=0, extent=[8.0, 8.0], objects=objects, paths=[], relations=[]
        )

    print(
        f"a chair 0.9 m in front of a table, facing it, in {count} scenes; jitter = sd of the chair's offset "
        "(m) and turn (rad)"
    )
    for jitter in (0.0, 0.001, 0.01, 0.05, 0.2):
        rng = np.random.default_rng(seed)
        scenes = []
        for _ in range(count):
            x, z, yaw = rng.uniform(-3, 3), rng.uniform(-3, 3), rng.uniform(-math.pi, math.pi)
            lx, lz = rng.normal(0, jitter), 0.9 + rng.normal(0, jitter)
            chair = (
                x + lx * math.cos(yaw) + lz * math.sin(yaw),
                z - lx * math.sin(yaw) + lz * math.cos(yaw),
                yaw + math.pi + rng.normal(0, jitter),
            )
            scenes.append(scene([("table", x, z, yaw), ("chair", *chair)]))
        cells = []
        for test in ("permutation", "angle"):
            (pair,) = find_relations(scenes, test=test, seed=seed).pairs
            cells.append(
                f"{test} {'related' if pair.related else 'not related':11s} statistic {pair.statistic:6.3f} "
                f"p {pair.p_value:.3g}"
            )
        print(f"  jitter {jitter:5.3f}: " + "; ".join(cells))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument(
        "rules", nargs="*", help="shipped rule sets or .rules files (default: every shipped set)"
    )
    parser.add_argument("--scenes", type=int, default=500, help="scenes per rule set (500)")
    parser.add_argument("--workers", type=int, default=2, help="processes laying scenes out (2)")
    parser.add_argument("--seed", type=int, default=0, help="seed of the tests' streams (0)")
    parser.add_argument(
        "--cache",
        type=Path,
        default=Path(tempfile.gettempdir()) / "scenewright-bench-relations",
        help="folder of cached scene.json files",
    )
    parser.add_argument("--generate-only", action="store_true", help="fill the cache and stop")
    parser.add_argument(
        "--floor",
        type=float,
        default=None,
        help="the permutation test's nearest-neighbour tightness floor (default: the module's MIN_LOCAL_TIGHTNESS)",
    )
    parser.add_argument(
        "--jitter",
        action="store_true",
        help="instead: one planted relation under growing jitter, both tests",
    )
    args = parser.parse_args()
    if args.floor is not None:
        from scenewright.learning import relation_tests

        relation_tests.MIN_LOCAL_TIGHTNESS = args.floor
    if args.jitter:
        jitter_sweep(args.scenes, args.seed)
        return
    scores = {}
    for name in args.rules or shipped_rule_sets():
        paths, failed, spent = generated_scenes(name, args.scenes, args.cache, args.workers)
        if spent:
            print(
                f"{name}: laid out {args.scenes} scenes' missing ones in {spent:.0f} CPU s",
                flush=True,
            )
        if not args.generate_only:
            scores[Path(name).stem] = evaluate(Path(name).stem, paths, failed, args.seed)
    if len(scores) > 1:
        print(
            f"\nprecision and recall against the grammar's pairs, {args.scenes} scenes each, seed {args.seed}:"
        )
        print(summary(scores))


if __name__ == "__main__":
    main()
