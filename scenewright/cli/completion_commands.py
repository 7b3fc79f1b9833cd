"""The completion commands (``scenewright.completion``): ``complete`` a room
from a few categories, and ``plans``: build, graph, evaluate and draw a plan set."""

from __future__ import annotations

import argparse
import json
import sys
from dataclasses import replace
from functools import partial

from scenewright.completion import CATEGORY_METHODS, MASK_METHODS
from scenewright.core.errors import InputError
from scenewright.scene_folder import COMPLETE_FILES

from .common import (
    emit,
    output_file,
    read_scene,
    report_scene,
    say,
)
from .options import (
    CommandLineParser,
    add_command,
    common_options,
    seed_value,
    style_options,
    view_options,
)

HELP = {
    "plans": """\
examples:
  scenewright plans build completion/plans -o model.json
  scenewright plans graph --type bedroom --format dot | dot -Tsvg > bedroom.svg
  scenewright plans graph --type study --format json --model model.json
  scenewright plans evaluate --requested 2
  scenewright plans draw --only bedroom_01,study_06 --masks -o plans.png
  (completion/plans is in the repository: run 'plans build' from its root, or name your own folder)

build reads every plan (*.json, in sub-folders too) of a plan set, checks each (one
line naming the file and JSON path for the first problem, exit 2) and writes the plan
model: per room type P(category | type), co-occurrence weighted by the activity prior,
the most instances per plan, the mean room area; per plan its room feature and 10 x 10
layout mask; the mask clusters. The same plans give the same bytes. graph prints a
type's object relation graph (edges with weight > 0) from --model, --plans, or the
shipped plan set. evaluate holds each plan out in turn and prints, per type, how often
the model finds its room type, the precision, recall and F1 of the categories it adds,
how far the number it adds is from the plan's, and its layout mask's IoU with the
plan's, each as ours / a simple baseline, then over all plans which side is better and
by how much, and the plans whose type either side got wrong (about a minute of CPU for
the shipped set). draw puts plans on one PNG sheet (with --masks, each beside
its layout mask). See docs/completion.md.""",
    "complete": """\
examples:
  scenewright complete --room 5x4 --door S:0.8:0.9 --window N:2.5:1.4 --with bed,bookshelf --seed 1 -o bedroom/
  scenewright complete --room 6x5 --door W:1:0.9 --with dining_table --with chair=6 --no-render -o dining/
  scenewright complete --room "0,0 6,0 6,3 3,3 3,5 0,5" --door 1:1:0.9 --with desk -o office/
  scenewright complete bedroom/scene.json --add piano -o bedroom2/   # what is there stays put
  scenewright complete flat/scene.json --in living_room_1 --add piano -o flat2/   # one room of a house

completes an empty room from the categories asked for (--with NAME[=COUNT], names of
the indoor catalog, repeatable), from a set of furnished floor plans (--plans, default
the shipped set): the room's type(s) by area (Equation 2 of Fu et al. 2017), the other
categories by their relation graph (Algorithm 1), starting places along the walls from
the layout mask of the most similar plans (Equation 4), then the MCMC layout. --room is
W x D or the corners x,z in order; a door is WALL:OFFSET:WIDTH[:HEIGHT], a window
WALL:OFFSET:WIDTH[:SILL[:HEIGHT]] (sill 0.9, height 1.2 by default), WALL one of N, E,
S, W or a wall number, OFFSET the centre's metres from the wall's start as in a rules
file (walls run clockwise seen from above: the north wall from its west end, the east
from its north end, the south from its east end, the west from its south end).

writes the same files as generate; scene.json's "completion" records the types, each
chosen category with its P(category | type) and relation weight, the reference plans
and the mask with its plans' weights. The same request and seed give the same
scene.json. When the layout could not satisfy every relation the files are still
written ("ok": false) and the exit code is 1. --explain adds mask.png: the layout mask
drawn on the room with the laid-out pieces over it. See docs/completion.md.""",
}


def add_commands(commands) -> None:
    """Add the commands plans, complete to ``commands`` (argparse's subparsers)."""
    command = partial(add_command, commands, HELP)

    plans = command(
        "plans",
        "furnished floor plans: build their model, show a relation graph, evaluate, draw",
        None,
    )
    plan_actions = plans.add_subparsers(dest="plans_command", metavar="ACTION", required=True)

    def plan_action(name: str, summary: str, handler) -> CommandLineParser:
        action = plan_actions.add_parser(
            name,
            help=summary,
            description=summary,
            epilog=HELP["plans"],
            formatter_class=argparse.RawDescriptionHelpFormatter,
            parents=[common_options(suppress=True)],
        )
        action.set_defaults(handler=handler)
        return action

    def plan_set(action: argparse.ArgumentParser) -> None:
        action.add_argument(
            "plans", metavar="PLANS_DIR", nargs="?", help="a plan set (default: the shipped one)"
        )

    build = plan_action("build", "check a plan set and write its model", run_plans_build)
    build.add_argument(
        "plans",
        metavar="PLANS_DIR",
        help="folder of plan files (the shipped set: completion/plans)",
    )
    build.add_argument(
        "-o",
        "--output",
        required=True,
        metavar="FILE",
        help="model file (or a directory for model.json)",
    )
    graph = plan_action("graph", "print a room type's object relation graph", run_plans_graph)
    graph.add_argument(
        "--type", required=True, help="room type (bedroom, living_room, study, dining_room, ...)"
    )
    graph.add_argument(
        "--format", choices=("dot", "json"), default="dot", help="output format (dot)"
    )
    source = graph.add_mutually_exclusive_group()
    source.add_argument("--model", metavar="FILE", help="a model written by 'plans build'")
    source.add_argument(
        "--plans", metavar="PLANS_DIR", help="a plan set (default: the shipped one)"
    )
    graph.add_argument("-o", "--output", metavar="FILE", help="write to FILE instead of stdout")
    evaluate = plan_action(
        "evaluate",
        "leave-one-out: predictions for each held-out plan against baselines",
        run_plans_evaluate,
    )
    plan_set(evaluate)
    evaluate.add_argument(
        "--requested",
        type=int,
        choices=(1, 2),
        default=1,
        help="how many of each plan's categories (those taking the most floor) make the request (1)",
    )
    draw = plan_action(
        "draw", "draw plans (and their layout masks) on one PNG sheet", run_plans_draw
    )
    plan_set(draw)
    draw.add_argument(
        "--only",
        action="append",
        default=[],
        metavar="ID[,ID...]",
        help="the plans to draw (repeatable)",
    )
    draw.add_argument("--masks", action="store_true", help="draw each plan's layout mask beside it")
    draw.add_argument(
        "-o",
        "--output",
        required=True,
        metavar="PNG",
        help="image file (or a directory for plans.png)",
    )

    complete = command(
        "complete",
        "furnish an empty room from a few objects, learned from floor plans",
        run_complete,
    )
    complete.add_argument(
        "scene",
        nargs="?",
        metavar="SCENE_JSON",
        help="a furnished room (scene.json) to add to: what it holds stays where it is",
    )
    complete.add_argument(
        "--add",
        action="append",
        default=[],
        metavar="NAME[=N][,...]",
        help="with SCENE_JSON: categories to add (repeatable)",
    )
    complete.add_argument(
        "--in",
        dest="in_room",
        metavar="ROOM",
        help="with a house's SCENE_JSON: the room to add to (bedroom_2); the rest stays as it is",
    )
    complete.add_argument(
        "--room",
        metavar="WxD|CORNERS",
        help="room size (5x4) or corners x,z x,z ... (at most 100 m a side, 64 corners)",
    )
    complete.add_argument(
        "--door",
        action="append",
        default=[],
        metavar="WALL:OFFSET:WIDTH[:HEIGHT]",
        help="a door (repeatable)",
    )
    complete.add_argument(
        "--window",
        action="append",
        default=[],
        metavar="WALL:OFFSET:WIDTH[:SILL[:HEIGHT]]",
        help="a window (repeatable)",
    )
    complete.add_argument(
        "--with",
        dest="categories",
        action="append",
        default=[],
        metavar="NAME[=N][,...]",
        help="categories the room must hold (repeatable)",
    )
    complete.add_argument(
        "--explain",
        action="store_true",
        help="also write mask.png: the layout mask on the room, with the pieces laid out",
    )
    complete.add_argument(
        "--plans", metavar="PLANS_DIR", help="a plan set (default: the shipped one)"
    )
    complete.add_argument(
        "--categories",
        dest="category_method",
        choices=CATEGORY_METHODS,
        default=CATEGORY_METHODS[0],
        help="how the added categories are chosen: co-occurrence with the request at the "
        "type's usual number (default), or the paper's Algorithm 1",
    )
    complete.add_argument(
        "--mask",
        dest="mask_method",
        choices=MASK_METHODS,
        default=MASK_METHODS[0],
        help="where the large pieces are pulled: the type's mean layout mask (default), or "
        "the paper's Equation 4 (the masks of the plans most like the room)",
    )
    complete.add_argument("--seed", type=seed_value, default=0, help="layout seed (0)")
    complete.add_argument("-o", "--output", required=True, metavar="DIR", help="output directory")
    style_options(complete)
    complete.add_argument(
        "--no-render", dest="render", action="store_false", help="skip the preview images"
    )
    view_options(complete, "640x480")


def run_plans_build(args: argparse.Namespace) -> int:
    """Read a plan set, build its model and write it (atomically)."""
    from scenewright.completion.floor_plan import load_plans
    from scenewright.completion.model_builder import build_model, model_json
    from scenewright.core.atomic import write_atomic

    plans = load_plans(args.plans)
    model = build_model(plans)
    target = output_file(args.output, "model.json")
    write_atomic(target, model_json(model))
    counts = ", ".join(f"{entry.plans} {name}" for name, entry in model.types.items())
    say(
        args,
        f"wrote {target}: {len(plans)} plans ({counts}), {len(model.categories)} categories",
    )
    return 0


def run_plans_graph(args: argparse.Namespace) -> int:
    """Print (or write) one room type's object relation graph."""
    from scenewright.completion.floor_plan import load_plans
    from scenewright.completion.model_builder import (
        build_model,
        graph_dot,
        read_model,
        relation_graph,
        shipped_model,
    )

    if args.model:
        model = read_model(args.model)
    else:
        model = build_model(load_plans(args.plans)) if args.plans else shipped_model()
    graph = relation_graph(model, args.type)
    text = graph_dot(graph) if args.format == "dot" else json.dumps(graph, indent=1) + "\n"
    return emit(args, text)


def run_plans_draw(args: argparse.Namespace) -> int:
    """Draw plans of a set (all, or the ids named) on one sheet."""
    from scenewright.completion import shipped_plans_dir
    from scenewright.completion.drawing import MAX_PANELS, draw_plans
    from scenewright.completion.floor_plan import load_plans
    from scenewright.core.atomic import atomic_stream, writing

    plans = load_plans(args.plans or shipped_plans_dir())
    if args.only:
        wanted = [part.strip() for text in args.only for part in text.split(",") if part.strip()]
        by_id = {plan.id: plan for plan in plans}
        missing = [name for name in wanted if name not in by_id]
        if missing:
            raise InputError(f"no plan {missing[0]!r} in the plan set")
        plans = [by_id[name] for name in dict.fromkeys(wanted)]
    if len(plans) > MAX_PANELS:
        raise InputError(
            f"{len(plans)} plans are more than one sheet holds ({MAX_PANELS}); name some with --only"
        )
    target = output_file(args.output, "plans.png")
    with atomic_stream(target, binary=True) as stream, writing(target):
        draw_plans(plans, stream, masks=args.masks)
    say(args, f"wrote {target} ({len(plans)} plans)")
    return 0


def run_plans_evaluate(args: argparse.Namespace) -> int:
    """Leave-one-out over a plan set: the model's predictions against simple baselines."""
    from scenewright.completion import shipped_plans_dir
    from scenewright.completion.evaluation import leave_one_out, report
    from scenewright.completion.floor_plan import load_plans

    table = leave_one_out(load_plans(args.plans or shipped_plans_dir()), args.requested)
    sys.stdout.write(report(table, args.requested))
    return 0


def run_complete(args: argparse.Namespace) -> int:
    """Complete an empty room from a few categories; write as generate does."""
    from scenewright.api import complete_room
    from scenewright.completion.explanation import draw_explanation, summary_of
    from scenewright.completion.request import parse_request
    from scenewright.generator import indoor_catalog
    from scenewright.scene_folder import check_scene_folder, write_scene

    check_scene_folder(args.output, COMPLETE_FILES)  # before any work: it is replaced as a whole
    catalog = indoor_catalog()
    keep = house = None
    if args.scene is not None:
        from scenewright.completion.request import existing_request, parse_categories

        stated = [
            name
            for name, given in (
                ("--room", args.room),
                ("--door", args.door),
                ("--window", args.window),
                ("--with", args.categories),
            )
            if given
        ]
        if stated:
            raise InputError(
                f"{stated[0]} describes an empty room; a scene.json brings its own (name what to add with --add)"
            )
        if not args.add:
            raise InputError(
                "completing a scene.json needs --add NAME[=N][,...]: what to add to it"
            )
        keep = read_scene(args.scene)
        house, keep = _room_to_complete(keep, args)
        request = existing_request(keep, parse_categories(args.add, catalog), catalog)
    else:
        if args.add:
            raise InputError(
                "--add adds to a scene.json (scenewright complete out/scene.json --add piano); "
                "for an empty room name its categories with --with"
            )
        if args.room is None or not args.categories:
            raise InputError(
                "an empty room needs --room and --with (or give a scene.json to complete)"
            )
        if args.in_room is not None:
            raise InputError("--in names a room of a house: give the house's scene.json")
        request = parse_request(args.room, args.door, args.window, args.categories, catalog)
    request = replace(request, categories=args.category_method, mask=args.mask_method)
    scene = complete_room(
        request,
        args.seed,
        plans=args.plans,
        catalog=catalog,
        keep=keep,
        templates=args.templates,
        style=args.style,
        variant=args.variant,
        words=args.words,
    )
    say(args, summary_of(scene.completion))
    if keep is not None:
        kept, new = (
            len(keep.placed_objects()),
            len(scene.placed_objects()) - len(keep.placed_objects()),
        )
        say(
            args,
            f"kept {kept} piece{'s' * (kept != 1)} where {'they' if kept != 1 else 'it'} stood; placed {new} new "
            f"(what --add asked for, and what the line above says the plans added)",
        )
    if house is not None:
        scene = _house_with(house, args.in_room, scene, args)
    written = write_scene(
        scene,
        args.output,
        render=args.render,
        size=args.size,
        view=args.view,
        extra=(
            (lambda rendered: {"mask.png": lambda path: draw_explanation(rendered, path)})
            if args.explain
            else None
        ),
        outputs=COMPLETE_FILES,
    )
    return report_scene(args, written)


def _room_to_complete(scene, args):
    """(the house, the room of it --in names) for a house's scene.json; (None, the scene)
    for a room's."""
    if scene.house is None:
        if args.in_room is not None:
            raise InputError(f"--in {args.in_room}: {args.scene} is a room, not a house")
        return None, scene
    from scenewright.house.assemble import room_scene

    rooms = [room.id for room in scene.house.rooms]
    if args.in_room not in rooms:
        what = "which room to complete" if args.in_room is None else f"no room {args.in_room!r}"
        raise InputError(f"{args.scene} is a house: --in names {what} (rooms: {', '.join(rooms)})")
    if args.explain:
        raise InputError("--explain draws one room's mask; it is not made for a house")
    return scene, room_scene(scene, args.in_room)


def _house_with(house, room_id: str, completed, args):
    """The house with room ``room_id`` replaced by its ``completed`` scene, described."""
    from dataclasses import replace

    from scenewright.api import describe_scene
    from scenewright.house.assemble import house_scene, room_scene

    rooms = [
        completed if room.id == room_id else room_scene(house, room.id)
        for room in house.house.rooms
    ]
    joined = house_scene(house.house, rooms, rules=house.rules, seed=house.seed, name=house.name)
    joined = replace(joined, completion=completed.completion)
    return describe_scene(joined, style=args.style, variant=args.variant)
