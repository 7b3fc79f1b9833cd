"""The commands that show what scenewright holds: ``expand`` a rule set's scene
graph, print the scene.json ``schema``, ``list`` the shipped rule sets and shapes."""

from __future__ import annotations

import argparse
import json
import textwrap
from functools import partial

from .common import (
    emit,
)
from .options import (
    add_command,
    allow_option,
    seed_value,
)

HELP = {
    "expand": """\
examples:
  scenewright expand village --seed 7
  scenewright expand village --seed 7 --format dot -o village.dot && dot -Tsvg village.dot""",
    "schema": """\
examples:
  scenewright schema > scene.schema.json""",
    "list": """\
examples:
  scenewright list
  scenewright list --shapes

--shapes prints each procedural shape a catalog entry may name ("shape NAME") with its
footprint convention: what its front (local +Z) shows and where a person uses it from.""",
}


def add_commands(commands) -> None:
    """Add the commands expand, schema, list to ``commands`` (argparse's subparsers)."""
    command = partial(add_command, commands, HELP)

    expand = command("expand", "print the scene graph that the grammar expands to", run_expand)
    expand.add_argument("rules", help="shipped rule set name or path to a .rules file")
    expand.add_argument("--seed", type=seed_value, default=0, help="random seed (0)")
    expand.add_argument(
        "--format", choices=("json", "dot"), default="json", help="output format (json)"
    )
    expand.add_argument("-o", "--output", metavar="FILE", help="write to FILE instead of stdout")
    allow_option(expand)

    command("schema", "print the scene.json JSON Schema", run_schema)
    listing = command(
        "list", "list the shipped rule sets and their object types, or the shapes", run_list
    )
    listing.add_argument(
        "--shapes",
        action="store_true",
        help="list the procedural shapes and the side each one faces instead",
    )


def run_expand(args: argparse.Namespace) -> int:
    from scenewright.generator import expand, graph_to_dot, load_rules

    graph = expand(load_rules(args.rules, allow=args.allow_outside), args.seed)
    text = (
        graph_to_dot(graph)
        if args.format == "dot"
        else json.dumps(graph.to_dict(), indent=1) + "\n"
    )
    return emit(args, text)


def run_schema(args: argparse.Namespace) -> int:
    from scenewright.core.schema_check import load_schema

    print(json.dumps(load_schema(), indent=2, ensure_ascii=False))
    return 0


def run_list(args: argparse.Namespace) -> int:
    from scenewright.api import load_rules
    from scenewright.core.shapes import SHAPES
    from scenewright.generator import shipped_rule_sets
    from scenewright.generator.rules import created_types

    if args.shapes:
        rows = [("shape", "front (local +Z; its left is +X)", "used from")]
        rows += [(shape.name, shape.front, shape.used_from) for shape in SHAPES.values()]
        name_width, front_width = (max(len(row[column]) for row in rows) for column in (0, 1))
        for name, front, used_from in rows:
            print(f"{name:<{name_width}}  {front:<{front_width}}  {used_from}")
        return 0
    for name in shipped_rule_sets():
        rules = load_rules(name)
        width, depth = rules.params.extent
        catalog = {entry.name for entry in rules.catalog if entry.kind == "object"}
        types = sorted(
            created_types(rules) & catalog
        )  # a room set's catalog is shared: it makes only some
        walls = ", walls" if rules.params.walls else ""
        print(
            f"{name}  ({width:g} x {depth:g} m{walls}; makes {len(types)} of its catalog's {len(catalog)} object types)"
        )
        print(
            textwrap.fill(
                ", ".join(types), width=88, initial_indent="    ", subsequent_indent="    "
            )
        )
    from scenewright.house import read_plan, shipped_plans

    for name in shipped_plans():
        plan = read_plan(name)
        always = sum(room.count[0] for room in plan.rooms if room.probability >= 1.0)
        most = sum(room.count[1] for room in plan.rooms)
        print(f"{name}  (house plan, {plan.noun}: {always}..{most} rooms)")
        print(
            textwrap.fill(
                ", ".join(room.type for room in plan.rooms),
                width=88,
                initial_indent="    ",
                subsequent_indent="    ",
            )
        )
    return 0
