"""Diversity: does sampling with learned context terms keep the examples' spread?

The dining-table comparison of Dema and Sari-Sarraf (Entropy 2014, section 5.2): one table
and six chairs in one arrangement, jittered into ``--examples`` example scenes (each
chair's offset by a Gaussian of ``--jitter`` metres per axis, its turn by one of 0.1 rad,
the table's place and turn too; seeded). ``fit_context`` learns the context from them,
then ``--scenes`` new scenes of the same rules are laid out three ways:

- ``temperature 1``: the learned terms (and the relations of their pairs) sampled at
  temperature 1, the rest annealed (the default with a context);
- ``annealed``: the same energy, everything annealed (the optimiser's way);
- ``no context``: the rules alone, as ``generate`` lays them out without a context.

Per chair *slot* (the arrangement's six places; in each scene the chairs are matched
to the slots by the smallest total distance, as two chairs of one relation are
interchangeable) the spread is the root mean square distance of the chair's position
in the table's frame from the slot's mean position; the table prints each slot's
generated spread over the examples' and the mean of these ratios (target: within
[0.8, 1.25] at temperature 1, below 0.8 when annealed), and the layout time per scene
of each way (target: temperature 1 at most 2x no context; the ways are laid out in turn
scene by scene, so that the machine's load weighs on each alike), with the mean steps per
layout and the *divergence*: per learned pair kind the total variation distance of the
generated scenes' relative-pose shares from the examples' (as ``fit`` measures it:
blurred by 3 bins, position and yaw averaged), the mean over kinds.

``--template-init`` lays out temperature 1 twice, its constructive placement from the
rules' relations (``rules init``) and from the learned templates (``templates``,
``LayoutParams.template_init``), to compare steps, time, ok and the figures above
(and leaves ``annealed`` out).
``--rules R --from DIR`` takes another rule set and its examples (a fitted
``--context FILE`` instead of fitting one, if given): the new scenes are expanded from
R with seeds 0.., and only the dining set prints slot spreads. The examples are DIR's
scene.json files, or else every example in it (hand-written, GLB) read from geometry
alone and related as its derivation of R relates it, as ``fit`` and ``learn`` do
(``learning.context.measured_example_layout``).

    .venv/bin/python benchmarks/bench_diversity.py
    .venv/bin/python benchmarks/bench_diversity.py --template-init
    .venv/bin/python benchmarks/bench_diversity.py --template-init --rules R --from DIR --context R.context.json
    .venv/bin/python benchmarks/bench_diversity.py --rules bedrooms.rules --from examples/sets/bedrooms --context bedrooms.context.json
    .venv/bin/python benchmarks/bench_diversity.py --examples 30 --scenes 60 --seed 1
    .venv/bin/python benchmarks/bench_diversity.py --write-examples dining_examples   # the examples only
"""

from __future__ import annotations

import argparse
import json
import math
import sys
import time
from dataclasses import replace
from pathlib import Path

import numpy as np
from scipy.optimize import linear_sum_assignment

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from scenewright.api import build_scene  # noqa: E402
from scenewright.examples import load_examples  # noqa: E402
from scenewright.examples.formats import is_scene_json_file  # noqa: E402
from scenewright.generator import expand, load_rules  # noqa: E402
from scenewright.generator.layout import LayoutParams, layout_scene  # noqa: E402
from scenewright.generator.layout.learned_term import read_context  # noqa: E402
from scenewright.learning.context import (  # noqa: E402
    UPDATE_SMOOTH,
    counts,
    example_layout,
    fit_example_layouts,
    graph_pair_poses,
    measured_example_layout,
    share_distance,
    shares,
)
from scenewright.learning.derivations import measured_derivation_graphs  # noqa: E402
from scenewright.learning.induce import renamed_scenes

RULES = Path(__file__).resolve().parents[1] / "examples" / "sets" / "dining" / "dining.rules"

#: The arrangement in the table's frame (x along its left, z along its forward), per
#: side label: the chairs' places and the yaw that faces the table.
SLOTS = {
    "NextToFront": ([(-0.4, 0.8), (0.4, 0.8)], math.pi),
    "NextToBehind": ([(-0.4, -0.8), (0.4, -0.8)], 0.0),
    "NextToLeft": ([(1.15, 0.0)], -math.pi / 2.0),
    "NextToRight": ([(-1.15, 0.0)], math.pi / 2.0),
}


def side_of(scene: dict) -> dict[str, str]:
    """Chair id -> its NextTo label."""
    return {r["source"]: r["label"] for r in scene["relations"] if r["label"] in SLOTS}


def jittered_examples(rules: Path, count: int, jitter: float, seed: int) -> list[tuple[str, dict]]:
    """``count`` example scene.json documents: a scene of the rules with its objects moved
    to the jittered arrangement (the derivation and relations kept)."""
    rng = np.random.default_rng(seed)
    template = build_scene(load_rules(rules), 0).to_dict()
    sides = side_of(template)
    examples = []
    for k in range(count):
        scene = {**template, "objects": [dict(o) for o in template["objects"]]}
        tx, tz, tyaw = rng.normal(0.0, 0.3), rng.normal(0.0, 0.3), rng.normal(0.0, 0.2)
        c, s = math.cos(tyaw), math.sin(tyaw)
        used: dict[str, int] = {}
        for obj in scene["objects"]:
            if obj["type"] == "table":
                obj["position"] = [tx, 0.0, tz]
                obj["yaw"] = tyaw
            elif obj["id"] in sides:
                side = sides[obj["id"]]
                places, yaw = SLOTS[side]
                lx, lz = places[used.get(side, 0)]
                used[side] = used.get(side, 0) + 1
                lx, lz = lx + rng.normal(0.0, jitter), lz + rng.normal(0.0, jitter)
                obj["position"] = [tx + lx * c + lz * s, 0.0, tz - lx * s + lz * c]
                obj["yaw"] = math.atan2(
                    math.sin(tyaw + yaw + rng.normal(0.0, 0.1)), math.cos(tyaw + yaw)
                )
        examples.append((f"example_{k:02d}", scene))
    return examples


def chair_positions(objects: list[tuple[str, float, float, float]]) -> np.ndarray:
    """(6, 2) chair positions in the table's frame, matched to the arrangement's slots.
    ``objects``: (type, x, z, yaw)."""
    table = next(o for o in objects if o[0] == "table")
    c, s = math.cos(table[3]), math.sin(table[3])
    local = []
    for kind, x, z, _ in objects:
        if kind == "chair":
            dx, dz = x - table[1], z - table[2]
            local.append((dx * c - dz * s, dx * s + dz * c))
    slots = np.array([place for places, _ in SLOTS.values() for place in places])
    local = np.array(local)
    cost = np.linalg.norm(slots[:, None, :] - local[None, :, :], axis=2)
    rows, cols = linear_sum_assignment(cost)
    return local[cols[np.argsort(rows)]]


def spreads(positions: np.ndarray) -> np.ndarray:
    """(6,) RMS distance of each slot's chair from its mean; ``positions`` (n, 6, 2)."""
    centred = positions - positions.mean(axis=0, keepdims=True)
    return np.sqrt((centred**2).sum(axis=2).mean(axis=0))


def sample(rules: Path, count: int, ways: dict, slots: bool) -> dict[str, dict]:
    """Lay out ``count`` scenes of the rules (seeds 0..count-1) each way of ``ways``
    (name -> (context, params)), the ways in turn scene by scene, so that a change in the
    machine's load while it runs weighs on every way alike. Per way: the chair positions
    (count, 6, 2) when ``slots`` (the dining set), related pairs' relative poses per
    kind, CPU seconds and steps per layout, and how many were ok."""
    loaded = load_rules(rules)
    made = {
        name: {"positions": [], "poses": {}, "seconds": 0.0, "steps": 0, "ok": 0} for name in ways
    }
    for seed in range(count):
        graph = expand(loaded, seed)
        for name, (context, params) in ways.items():
            way = made[name]
            start = time.process_time()
            result = layout_scene(graph, seed, params=params, context=context)
            way["seconds"] += time.process_time() - start
            way["steps"] += result.steps
            way["ok"] += result.ok
            if slots:
                objects = [(graph.node(i).type, p.x, p.z, p.yaw) for i, p in result.poses.items()]
                way["positions"].append(chair_positions(objects))
            for kind, pose in graph_pair_poses(
                graph, {i: (p.x, p.z, p.yaw) for i, p in result.poses.items()}
            ):
                way["poses"].setdefault(kind, []).append(pose)
    for way in made.values():
        way["positions"] = np.array(way["positions"])
        way["seconds"] /= count
        way["steps"] /= count
    return made


def measured_layouts(rules: Path, folder: Path) -> list:
    """The examples in ``folder`` read from geometry alone, each related as its
    derivation of ``rules`` relates it (those no derivation makes are left out, as
    ``learn`` leaves them out)."""
    loaded = load_rules(rules)
    found = load_examples([folder])
    laid = []
    for example, scene in zip(found, renamed_scenes(found)[0], strict=False):
        graphs = measured_derivation_graphs(loaded, scene, example.name)
        if graphs:
            laid.append(measured_example_layout(example.name, scene, graphs))
    return laid


def divergence(context, observed: dict, generated: dict) -> float:
    """Mean over the context's pair kinds of the distance of generated from observed
    shares (``learning.context.share_distance`` at UPDATE_SMOOTH); poses per kind."""
    distances = []
    for table in context.pairs:
        target = shares(*counts(table, observed.get(table.kind, [])), UPDATE_SMOOTH)
        made = shares(*counts(table, generated.get(table.kind, [])), UPDATE_SMOOTH)
        distances.append(share_distance(made, target))
    return float(np.mean(distances))


def main() -> int:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("--balance", action="store_true", help="fit the visual-balance term too")
    parser.add_argument("--examples", type=int, default=30)
    parser.add_argument("--scenes", type=int, default=60)
    parser.add_argument("--jitter", type=float, default=0.08, help="metres per axis (0.08)")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--rounds", type=int, default=2)
    parser.add_argument("--layouts", type=int, default=40, help="layouts per round of the fit (40)")
    parser.add_argument(
        "--write-examples", metavar="DIR", help="only write the examples as DIR/example_NN.json"
    )
    parser.add_argument(
        "--template-init", action="store_true", help="compare the initial placement from templates"
    )
    parser.add_argument("--rules", type=Path, default=RULES, help="another rule set (with --from)")
    parser.add_argument(
        "--from", dest="source", type=Path, metavar="DIR", help="scene.json examples of --rules"
    )
    parser.add_argument(
        "--context", type=Path, metavar="FILE", help="a fitted context instead of fitting one"
    )
    args = parser.parse_args()

    rules = args.rules
    slots = args.source is None
    if slots:
        examples = jittered_examples(rules, args.examples, args.jitter, args.seed)
    elif all(is_scene_json_file(p) for p in args.source.glob("*.json")):
        examples = [
            (p.stem, json.loads(p.read_text(encoding="utf-8")))
            for p in sorted(args.source.glob("*.json"))
        ]
    else:
        examples = []  # read from geometry alone (measured_layouts)
    laid = (
        [example_layout(name, scene) for name, scene in examples]
        if examples
        else measured_layouts(rules, args.source)
    )
    if args.write_examples:
        folder = Path(args.write_examples)
        folder.mkdir(parents=True, exist_ok=True)
        for name, scene in examples:
            (folder / f"{name}.json").write_text(
                json.dumps(scene, indent=1) + "\n", encoding="utf-8"
            )
        print(f"wrote {len(examples)} examples to {folder}/")
        return 0
    observed: dict = {}
    for example in laid:
        for kind, pose in example.poses:
            observed.setdefault(kind, []).append(pose)
    if args.context is not None:
        context = read_context(str(args.context))
        print(f"context: {args.context}, {len(context.pairs)} pair kinds; {len(laid)} examples")
    else:
        start = time.process_time()
        fitted = fit_example_layouts(
            laid,
            seed=args.seed,
            rounds=args.rounds,
            layouts=args.layouts,
            balance=args.balance,
        )
        context = fitted.context
        print(
            f"fit: {len(laid)} examples, {len(context.pairs)} pair kinds, "
            f"divergence per round {' '.join(f'{d:.3f}' for d in fitted.divergence)}, kept round {fitted.kept}; "
            f"{time.process_time() - start:.1f} CPU s"
        )
    if (
        args.template_init
    ):  # the comparison of the two starts (annealed left out: it is not sampling)
        ways = {
            "rules init": (context, replace(LayoutParams(), template_init=False)),
            "templates": (context, replace(LayoutParams(), template_init=True)),
        }
    else:
        ways = {
            "temperature 1": (context, LayoutParams()),
            "annealed": (context, replace(LayoutParams(), tempered=False)),
        }
    ways["no context"] = (None, LayoutParams())
    reference = None
    if slots:
        reference = spreads(
            np.array(
                [
                    chair_positions(
                        [
                            (o["type"], o["position"][0], o["position"][2], o["yaw"])
                            for o in scene["objects"]
                        ]
                    )
                    for _, scene in examples
                ]
            )
        )
        print(f"\n{'':14s} " + " ".join(f"slot {k + 1}" for k in range(6)) + "   mean", end="")
    else:
        print(f"\n{'':14s}", end="")
    print("   s/layout  steps  ok      divergence")
    if slots:
        print(f"{'examples (m)':14s} " + " ".join(f"{v:6.3f}" for v in reference))
    times = {}
    for name, made in sample(rules, args.scenes, ways, slots).items():
        times[name] = made["seconds"]
        line = f"{name:14s} "
        if slots:
            ratio = spreads(made["positions"]) / reference
            line += " ".join(f"{v:6.2f}" for v in ratio) + f"  {ratio.mean():5.2f} "
        line += f"  {made['seconds']:8.4f}  {made['steps']:5.0f}  {made['ok']}/{args.scenes}   "
        print(line + f"{divergence(context, observed, made['poses']):.3f}")
    first = next(iter(ways))
    print(f"\nlayout time, {first} / no context: {times[first] / times['no context']:.2f}x")
    if args.template_init:
        print(
            f"layout time, templates / rules init: {times['templates'] / times['rules init']:.2f}x"
        )
    return 0


if __name__ == "__main__":
    sys.exit(main())
