"""The example-scene commands: ``validate`` rules, scene.json files and example
scenes; ``match`` two examples, ``augment`` several into one graph, ``vary`` them into
new scenes (``scenewright.variation``)."""

from __future__ import annotations

import argparse
import json
import sys
from functools import partial
from pathlib import Path

from .common import (
    PROG,
    SceneFileError,
    output_file,
    read_scene_data,
    say,
)
from .options import (
    MAX_OPERATIONS,
    MAX_VARIANTS,
    add_command,
    allow_option,
    count_at_least,
    fraction,
    seed_value,
    view_options,
)

HELP = {
    "validate": """\
examples:
  scenewright validate village
  scenewright validate my.rules out/scene.json
  scenewright validate my_rooms/study.json my_rooms/kitchen.glb    # example scenes, as learn reads them

Prints "FILE: ok" or every diagnostic (file:line:column with the line and a caret).
Exit 2 when any file has an error; warnings alone exit 0.""",
    "match": """\
examples:
  scenewright match rooms/a/scene.json rooms/b/scene.json
  scenewright match my_study.json study.glb --json
  scenewright match a.json b.json --threshold 0.8 --type-prior 0.3

matches the standing objects of two example scenes (scene.json, the hand-written
example format, or GLB: docs/examples.md) by their role in the layout: box sizes and
the relations between objects (facing, touching, aligned, close), not their type names
(--type-prior lets equal names count a little). Prints each pair with its confidence;
pairs below --threshold are withdrawn. Objects standing on others are not matched
(they travel with what carries them). See docs/variation.md.""",
    "augment": """\
examples:
  scenewright augment rooms/a rooms/b rooms/c -o ag.json
  scenewright augment a.json b.glb --format dot -o ag.dot && dot -Tsvg ag.dot > ag.svg

merges the example scenes into one Augmented Graph: each node a set of objects matched
across the examples (by 'scenewright match'), each edge the union of its members'
relations (S support, F facing, V touching, A aligned, C close). Every input object is
in exactly one node; objects standing on others are nodes resting on their supporter's.
Without -o the graph is printed. See docs/variation.md.""",
    "vary": """\
examples:
  scenewright vary rooms/a rooms/b rooms/c -n 30 --seed 1 -o variants/
  scenewright vary my_room.json room.glb -n 10 --no-render -o out/

makes N new scenes from the examples (scene.json, hand-written .json or .glb) by
replacing an object by one matched to it in another example, growing an object one
example has next to its matched neighbour, or moving what stands on a table onto its
counterpart; each operation is laid out again with everything it did not touch pinned,
and only compatible ones are kept. Writes DIR/variant_001/ ... (best first), each like
'generate' writes a scene, with scene.json's "synthesis" record naming every
operation, its compatibility and each object's source; and DIR/index.json. Same
examples and seed: same output. Exit 1 when fewer than N distinct variants could be
made (those made are written). See docs/variation.md.""",
}


def add_commands(commands) -> None:
    """Add the commands validate, match, augment, vary to ``commands`` (argparse's subparsers)."""
    command = partial(add_command, commands, HELP)

    validate = command(
        "validate", "check rules files (and scene.json files and example scenes)", run_validate
    )
    validate.add_argument(
        "files",
        nargs="+",
        metavar="FILE",
        help=".rules files, shipped rule set names, scene .json files, or example scenes (hand-written .json, .glb)",
    )
    allow_option(validate)

    match = command(
        "match", "match the objects of two example scenes by their role in the layout", run_match
    )
    match.add_argument(
        "first",
        metavar="A",
        help="example scene: scene.json (or its folder), hand-written .json, or .glb",
    )
    match.add_argument("second", metavar="B", help="the other example scene")
    match.add_argument("--json", action="store_true", help="print the matching as JSON")
    match.add_argument(
        "--threshold",
        type=fraction,
        default=0.6,
        metavar="C",
        help="confidence below which a pair is withdrawn (0.6)",
    )
    match.add_argument(
        "--type-prior",
        type=fraction,
        default=0.0,
        metavar="P",
        help="how much different type names lower a pair's box similarity (0: names ignored)",
    )

    augment = command("augment", "merge example scenes into one Augmented Graph", run_augment)
    augment.add_argument(
        "examples",
        nargs="+",
        metavar="EXAMPLE",
        help="example scenes (scene.json or its folder, .json, .glb)",
    )
    augment.add_argument("-o", "--output", metavar="FILE", help="write to FILE instead of stdout")
    augment.add_argument(
        "--format", choices=("json", "dot"), default="json", help="output format (json)"
    )
    augment.add_argument(
        "--threshold",
        type=fraction,
        default=0.6,
        metavar="C",
        help="matching confidence to merge two objects (0.6)",
    )

    vary_command = command(
        "vary", "make new scenes by reshuffling objects of example scenes", run_vary
    )
    vary_command.add_argument(
        "examples",
        nargs="+",
        metavar="EXAMPLE",
        help="example scenes, two or more (scene.json or its folder, .json, .glb)",
    )
    vary_command.add_argument(
        "-n",
        "--count",
        type=count_at_least(1, MAX_VARIANTS),
        default=10,
        metavar="N",
        help="variants to make (10; at most 10000)",
    )
    vary_command.add_argument("--seed", type=seed_value, default=0, help="random seed (0)")
    vary_command.add_argument(
        "-o", "--output", required=True, metavar="DIR", help="output directory"
    )
    vary_command.add_argument(
        "--operations",
        type=count_at_least(1, MAX_OPERATIONS),
        default=3,
        metavar="K",
        help="at most K operations per variant (3)",
    )
    vary_command.add_argument(
        "--no-render", dest="render", action="store_false", help="skip the preview images"
    )
    view_options(vary_command, "640x480")


def run_validate(args: argparse.Namespace) -> int:
    from scenewright.examples.formats import is_handwritten_example
    from scenewright.generator import check_rules, shipped_rule_sets
    from scenewright.house import is_plan_file

    shipped = shipped_rule_sets()
    any_error = False
    for name in args.files:
        if not Path(name).is_file() and name not in shipped:
            print(f"{name}: error: no such file (nor a shipped rule set: {', '.join(shipped)})")
            any_error = True
        elif name.lower().endswith(".glb") or (
            name.endswith(".json") and is_handwritten_example(name)
        ):
            any_error |= not validate_example_file(name)
        elif name.endswith(".json"):
            any_error |= not validate_scene_file(name)
        elif is_plan_file(name):
            any_error |= not validate_plan_file(name)
        else:
            diagnostics = check_rules(name, allow=args.allow_outside)
            for diagnostic in diagnostics:
                print(diagnostic)
            errors = sum(d.severity == "error" for d in diagnostics)
            warnings = len(diagnostics) - errors
            any_error |= errors > 0
            if not errors:
                print(
                    f"{name}: ok"
                    + (f" ({warnings} warning{'s' * (warnings != 1)})" if warnings else "")
                )
    return 2 if any_error else 0


def validate_plan_file(name: str) -> bool:
    """Print ``NAME: ok`` or the located mistakes of a house plan (``plan NAME { ... }``);
    return whether it is ok."""
    from scenewright.generator.rules_errors import RulesError
    from scenewright.house import read_plan

    try:
        read_plan(name)
    except RulesError as error:
        for diagnostic in error.diagnostics:
            print(diagnostic)
        return False
    print(f"{name}: ok")
    return True


def validate_example_file(name: str) -> bool:
    """Print ``NAME: ok`` (with what it holds) or its problem, for a hand-written example
    or a GLB (``examples``, the reader learn, fit and vary use); return whether it is ok."""
    from scenewright.examples import ExampleError, load_example

    try:
        example = load_example(name)
    except ExampleError as error:
        print(
            f"{error.path}: error: "
            + (f"{error.where}: {error.reason}" if error.where else error.reason)
        )
        return False
    objects = len(example.objects())
    kind = {"glb": "GLB", "example.json": "hand-written"}.get(example.format, example.format)
    room = "a room" if example.scene.room is not None else "open ground"
    warnings = overlap_warnings(name, example.scene)
    noted = f", {len(warnings)} warning{'s' * (len(warnings) != 1)}" if warnings else ""
    for line in warnings:
        print(line)
    print(f"{name}: ok ({kind} example: {objects} object{'s' * (objects != 1)} in {room}{noted})")
    return True


def overlap_warnings(name: str, scene) -> list[str]:
    """A warning per pair of objects that run into each other, and per object through a
    wall or out of the scene, by more than the layout's tolerance (1 cm, as its ``ok``):
    a model learns from an example what a layout may do."""
    from scenewright.generator.layout.report import OVERLAP_TOLERANCE
    from scenewright.generator.scene_metrics import evaluate_scene

    metrics = evaluate_scene(scene, name, OVERLAP_TOLERANCE)
    lines = [
        f"{name}: warning: {a} runs {100 * depth:.0f} cm into {b}"
        for a, b, depth in metrics.collisions
    ]
    where = "through the wall" if scene.room is not None else "out of the scene"
    lines += [
        f"{name}: warning: {ident} stands {100 * excess:.0f} cm {where}"
        for ident, excess in metrics.out_of_bounds
    ]
    return lines


def validate_scene_file(name: str) -> bool:
    """Print ``NAME: ok`` or each problem of a scene.json (and of the files it names) on
    a line of its own; return whether it is ok."""
    try:
        read_scene_data(name, check_files=True)
    except SceneFileError as error:
        for problem in error.problems:
            print(f"{name}: error: {problem}")
        return False
    print(f"{name}: ok")
    return True


def run_match(args: argparse.Namespace) -> int:
    from scenewright.examples import load_examples
    from scenewright.variation import match_graphs, structure_graph

    first, second = load_examples([args.first, args.second])
    matching = match_graphs(
        structure_graph(first.scene),
        structure_graph(second.scene),
        threshold=args.threshold,
        type_prior=args.type_prior,
    )
    if args.json:
        print(json.dumps({"a": first.path, "b": second.path, **matching.to_dict()}, indent=1))
        return 0
    print(
        f"{first.name} -> {second.name}: {len(matching.pairs)} matched, {len(matching.withdrawn)} withdrawn, "
        f"energy {matching.energy:.3f}"
    )
    print("\n".join(matching.lines()))
    return 0


def run_augment(args: argparse.Namespace) -> int:
    from scenewright.core.atomic import write_atomic
    from scenewright.examples import load_examples
    from scenewright.variation import augment

    graph = augment(load_examples(args.examples), threshold=args.threshold)
    text = graph.to_dot() if args.format == "dot" else json.dumps(graph.to_dict(), indent=1) + "\n"
    if args.output:
        target = output_file(args.output, "ag.dot" if args.format == "dot" else "ag.json")
        write_atomic(target, text)
        merged = sum(len(node.members) > 1 for node in graph.nodes)
        say(
            args,
            f"wrote {target}: {len(graph.nodes)} nodes ({merged} merged from several examples), "
            f"{len(graph.to_dict()['edges'])} edges",
        )
    else:
        sys.stdout.write(text)
    return 0


def run_vary(args: argparse.Namespace) -> int:
    from scenewright.examples import load_examples
    from scenewright.scene_folder import check_scene_folder, write_variants
    from scenewright.variation.index import FOLDERS, summary
    from scenewright.variation.synthesis import vary

    check_scene_folder(args.output, FOLDERS)  # before any work: it is replaced as a whole
    examples = load_examples(args.examples)
    results = vary(examples, args.count, args.seed, max_operations=args.operations)
    index = write_variants(
        results,
        examples,
        args.output,
        args.seed,
        render=args.render,
        size=args.size,
        view=args.view,
    )
    say(args, summary(index, args.output))
    if len(results) < args.count:
        print(
            f"{PROG}: error: made {len(results)} distinct variants of the {args.count} asked for (files kept)",
            file=sys.stderr,
        )
        return 1
    return 0
