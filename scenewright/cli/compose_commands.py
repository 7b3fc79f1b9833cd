"""The compose command: a scene from English (docs/compose.md)."""

from __future__ import annotations

import argparse
import sys
from functools import partial

from scenewright.core.errors import InputError

from .common import PROG, report_scene, say
from .options import add_command, seed_value, style_options, view_options

HELP = {
    "compose": """\
examples:
  scenewright compose "a bedroom with a double bed against the north wall, a nightstand on each side of the bed, a wardrobe and a desk under the window" -o out/
  scenewright compose "a 4 by 3 metre study with a desk under the window and a bookshelf against the east wall" --seed 2
  scenewright compose "a kitchen with a fridge, a sink under the window and a table with four chairs around it" --rules-out kitchen.rules
  scenewright compose "a living room with a sofa against the south wall, a TV on a stand opposite the sofa and a bookshelf by the window" -o living/
  scenewright compose "a small room with a piano" --catalog my_music.rules --strict
  scenewright compose "a bedroom with a double bed against the north wall" --complete -o full/
  scenewright compose "a village with two roads meeting at a crossroads, a well next to the first road and three cottages along the second road" -o village/
  scenewright compose "$(cat village_description.txt)" --catalog village --seed 3

writes what generate writes (scene.json, description.txt, preview.png, scene.glb,
plan.png). Words or phrases it could not use are listed as LINE:COL-COL: message, with
the nearest known word; --strict makes that an error (exit 2, nothing written). A
statement the layout could not satisfy is named with the statements it shares things
with, and the exit code is 1 (the files are kept). --rules-out keeps the rule set it
composed, to edit and generate from like any other. --complete adds, around what the
text asked for (kept where it stands), what a room of that kind usually holds. A text
that names a village, town or city, a road or a junction is composed outdoors, with
the outdoor catalog (the shipped village, town and city's types).""",
}


def add_commands(commands) -> None:
    """Add the command compose to ``commands`` (argparse's subparsers)."""
    command = partial(add_command, commands, HELP)
    compose = command("compose", "compose a scene from an English description", run_compose)
    compose.add_argument(
        "text", metavar="TEXT", help="what the scene holds, in English ('-' reads stdin)"
    )
    compose.add_argument("--seed", type=seed_value, default=0, help="random seed (0)")
    compose.add_argument(
        "-o", "--output", default="out", metavar="DIR", help="output directory (out)"
    )
    compose.add_argument(
        "--strict", action="store_true", help="an unused word or phrase is an error (exit 2)"
    )
    compose.add_argument(
        "--rules-out", metavar="FILE", help="also write the composed rule set to FILE"
    )
    compose.add_argument(
        "--catalog",
        metavar="RULES",
        help="a rule set (shipped name or .rules file) whose object types may be named too",
    )
    compose.add_argument(
        "--complete",
        action="store_true",
        help="then add what a room of that kind usually holds besides (the completion model, "
        "docs/completion.md); what the text asked for stays where it is",
    )
    style_options(compose)
    compose.add_argument(
        "--no-render", dest="render", action="store_false", help="skip the preview images"
    )
    view_options(compose, "640x480")


def run_compose(args: argparse.Namespace) -> int:
    from pathlib import Path

    from scenewright.api import compose
    from scenewright.composer.compose import plan, write_rules
    from scenewright.composer.outdoor import catalog_for
    from scenewright.scene_folder import check_scene_folder, write_scene

    text = sys.stdin.read() if args.text == "-" else args.text
    check_scene_folder(args.output)
    if args.strict:  # refuse before any layout, and before anything is written
        own = None
        if args.catalog:
            from scenewright.api import load_rules

            own = load_rules(args.catalog)
        request, _ = plan(text, *catalog_for(text, own))
        if request.issues:
            from scenewright.composer.compose import report_of

            report = report_of(text, request, "")
            for line in report.messages():
                print(line, file=sys.stderr)
            raise InputError(f"{len(request.issues)} word(s) not understood (--strict)")
    label = str(Path(args.rules_out)) if args.rules_out else None
    scene, report = compose(
        text,
        args.seed,
        catalog=args.catalog,
        style=args.style,
        variant=args.variant,
        words=args.words,
        templates=args.templates,
        rules_label=label,
    )
    for line in report.messages():
        print(line, file=sys.stderr)
    if args.complete:
        scene = completed(scene, args)
    written = write_scene(scene, args.output, render=args.render, size=args.size, view=args.view)
    if args.rules_out:
        write_rules(report.rules, args.rules_out)
        say(args, f"wrote {args.rules_out}")
    for line in report.conflicts():
        print(f"{PROG}: {line}", file=sys.stderr)
    code = report_scene(args, written)
    return code if not report.unsatisfied else max(code, 1)


def completed(scene, args: argparse.Namespace):
    """The composed room with what the completion model adds to a room of its kind, the
    composed pieces kept where they stand (``complete SCENE_JSON``'s way), described."""
    from scenewright.api import complete_room
    from scenewright.completion.explanation import summary_of
    from scenewright.completion.request import existing_request
    from scenewright.generator import indoor_catalog

    if scene.room is None:
        raise InputError(
            "--complete adds what a room usually holds: the text must ask for a room "
            "(a bedroom, a kitchen, a 4 by 3 metre room, ...)"
        )
    catalog = indoor_catalog()
    request = existing_request(scene, {}, catalog)
    result = complete_room(
        request,
        args.seed,
        catalog=catalog,
        keep=scene,
        templates=args.templates,
        style=args.style,
        variant=args.variant,
        words=args.words,
    )
    say(args, summary_of(result.completion))
    return result
