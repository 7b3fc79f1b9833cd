"""The scene commands: ``generate`` a scene, lay one out again (``layout``),
``describe``, ``render`` and ``export`` a scene.json."""

from __future__ import annotations

import argparse
from functools import partial

from scenewright.core.errors import InputError

from .common import (
    SceneFileError,
    chosen_context,
    output_file,
    read_scene,
    report_scene,
    say,
)
from .options import (
    add_command,
    allow_option,
    camera_settings,
    context_options,
    seed_value,
    style_options,
    view_options,
)

HELP = {
    "generate": """\
examples:
  scenewright generate village --seed 7 -o out/
  scenewright generate my_town.rules --seed 3 --style short --size 1024x768 -o town/
  scenewright generate desk --no-render -o desk/
  scenewright generate city --seed 1 --words 800 -o city/   # 1,100-2,200 objects, a summary text
  scenewright generate market.rules --templates my_words/ -o market/
  scenewright generate apartment --seed 3 -o flat/        # a house: a floor plan, each room furnished
  scenewright generate my_plan.json -o mine/              # furnish a floor plan of your own

writes scene.json (reproducible: no wall-clock times), timings.json, description.txt,
preview.png (+ preview_depth.png/.npy/.json, preview_seg.png, preview_ids.json,
preview_3d.json: see 'scenewright render --help'), scene.glb (with the ground, the
preview's camera and its sun: see 'scenewright export --help') and plan.png (a
top-down debug plan). All files appear together or not at all. When the
layout could not satisfy every relation the files are still written (scene.json says
"ok": false) and the exit code is 1.""",
    "layout": """\
examples:
  scenewright generate village --seed 7 -o out/
  scenewright layout out/scene.json --pin tower_1,market_stand_1 --seed 2 -o out2/
  scenewright layout out/scene.json --pin road_1 --pin windmill_1 --warm --no-render -o out3/
  scenewright layout dining/scene.json --pin table_1 --context fitted/dining.context.json -o out4/

lays the scene of SCENE_JSON out again with the layout seed N, keeping the pinned ids
exactly where they are (x, y, z and yaw unchanged) and placing everything else around
them. A group pins all its members, a path its control points and the junction it
starts at, an object also the objects beneath it. Unpinned things start from a fresh
placement, or with --warm from their poses in SCENE_JSON. --context samples the layout
with a learned context, as generate does with the one beside its rules.

writes the same files as generate, with a new description; scene.json keeps the rules,
objects and relations and records --seed as its "seed". The same input file, pins and
seed give the same scene.json. When the layout could not satisfy every relation the
files are still written ("ok": false) and the exit code is 1.""",
    "describe": """\
examples:
  scenewright describe out/scene.json
  scenewright describe out/scene.json --style short --variant 2
  scenewright describe out/scene.json --templates my_templates/

uses the description templates the scene was generated with (scene.json's "templates",
from the rule set or generate --templates) unless --templates names another folder.""",
    "render": """\
examples:
  scenewright render out/scene.json -o out/preview.png
  scenewright render out/scene.json -o top.png --view top --size 1024x1024

writes the colour image and, beside it, STEM_depth.png (16-bit, in the unit that
STEM_depth.json gives: millimetres unless the scene is deeper than 65.5 m),
STEM_depth.npy (float32 metres), STEM_seg.png (16-bit instance ids), STEM_ids.json
(id -> object), STEM_3d.json (K, the extrinsics in the OpenCV and OpenGL conventions,
each object's pose and 3D box in the camera frame) and, with --normals,
STEM_normals.png. When PNG is an existing directory or ends in '/', the files are
preview.png etc. inside it.""",
    "export": """\
examples:
  scenewright export out/scene.json -o out/scene.glb
  scenewright export out/scene.json -o exports/
  scenewright export out/scene.json -o game.glb --cutaway --no-camera --no-light
  scenewright export out/scene.json -o out/scene.usda

A name ending in .usda (text), .usdc or .usd (binary) writes a USD stage of the same
content: Y up, metres, UsdPreviewSurface materials.

The GLB has a PBR material per colour and normals, so a viewer (Blender, Godot,
three.js) shows the preview's colours lit; what rests on something is its child node.
It holds the ground (a room's floor), the preview's camera and its sun unless
--no-ground, --no-camera, --no-light leave them out; in a room, walls the preview cuts
away are marked "cutaway": true in their extras, and --cutaway leaves them out.
When GLB is an existing directory or ends in '/', the file is scene.glb inside it.""",
}


def add_commands(commands) -> None:
    """Add the commands generate, layout, describe, render, export to ``commands`` (argparse's subparsers)."""
    command = partial(add_command, commands, HELP)

    generate = command(
        "generate", "generate one scene with its description, images and files", run_generate
    )
    generate.add_argument(
        "rules",
        help="shipped rule set or house plan name (see 'list'), a path to a .rules file, "
        "or a floor plan as .json (a house whose rooms are furnished)",
    )
    generate.add_argument("--seed", type=seed_value, default=0, help="random seed (0)")
    generate.add_argument(
        "-o", "--output", default="out", metavar="DIR", help="output directory (out)"
    )
    style_options(generate)
    generate.add_argument(
        "--no-render", dest="render", action="store_false", help="skip the preview images"
    )
    view_options(generate, "640x480")
    generate.add_argument(
        "--camera",
        type=camera_settings,
        metavar="KEY=VALUE,...",
        help="place the preview's camera: azimuth (degrees from south towards east), elevation (degrees), "
        "distance (times the framing distance), target (an id or type); a number may be a range LOW:HIGH, drawn "
        "from the seed (e.g. azimuth=30,elevation=45,distance=1.2)",
    )
    context_options(generate)
    allow_option(generate)
    generate.add_argument(
        "--workers",
        type=int,
        default=1,
        metavar="N",
        help="a house: lay out its rooms in N processes (the same scene whatever N; default 1)",
    )

    layout = command(
        "layout", "lay a scene.json out again, keeping pinned objects where they are", run_layout
    )
    layout.add_argument("scene", metavar="SCENE_JSON")
    layout.add_argument(
        "--pin",
        action="append",
        default=[],
        metavar="ID[,ID...]",
        help="objects, groups, junctions or paths that keep their poses (repeatable)",
    )
    layout.add_argument("--seed", type=seed_value, default=0, help="layout seed (0)")
    layout.add_argument(
        "--warm", action="store_true", help="start unpinned objects from their old poses"
    )
    layout.add_argument(
        "--context",
        metavar="JSON",
        help="a learned context to sample the layout with (scenewright fit --what context); none by default",
    )
    layout.add_argument("-o", "--output", required=True, metavar="DIR", help="output directory")
    style_options(layout)
    layout.add_argument(
        "--no-render", dest="render", action="store_false", help="skip the preview images"
    )
    view_options(layout, "640x480")

    describe = command("describe", "print the English description of a scene.json", run_describe)
    describe.add_argument("scene", metavar="SCENE_JSON")
    style_options(describe)

    render = command("render", "render a scene.json offscreen", run_render)
    render.add_argument("scene", metavar="SCENE_JSON")
    render.add_argument(
        "-o",
        "--output",
        default="preview.png",
        metavar="PNG",
        help="colour image (preview.png), or a directory to write preview.png etc. into",
    )
    view_options(render, "640x480")
    render.add_argument(
        "--normals",
        action="store_true",
        help="also write STEM_normals.png (surface normals in the camera frame)",
    )

    export = command("export", "export a scene.json as binary glTF or USD", run_export)
    export.add_argument("scene", metavar="SCENE_JSON")
    export.add_argument(
        "-o",
        "--output",
        default="scene.glb",
        metavar="GLB",
        help="output file (scene.glb; .usda/.usdc/.usd for USD), or a directory",
    )
    export.add_argument(
        "--no-ground", dest="ground", action="store_false", help="leave out the ground / floor"
    )
    export.add_argument(
        "--no-camera", dest="camera", action="store_false", help="leave out the preview's camera"
    )
    export.add_argument(
        "--no-light", dest="light", action="store_false", help="leave out the sun light"
    )
    export.add_argument(
        "--cutaway",
        action="store_true",
        help="leave out the walls (and their doors and windows) the preview cuts away",
    )


def run_generate(args: argparse.Namespace) -> int:
    from scenewright.api import generate, generate_house, is_house_plan
    from scenewright.generator import load_rules
    from scenewright.scene_folder import check_scene_folder, write_scene

    check_scene_folder(args.output)  # before any work: it is replaced as a whole
    if args.camera is not None and not args.render:
        raise InputError(
            "--camera places the preview's camera; it needs the preview (leave out --no-render)"
        )
    if is_house_plan(args.rules):
        scene = generate_house(
            args.rules, args.seed, style=args.style, variant=args.variant, workers=args.workers
        )
        written = write_scene(
            scene,
            args.output,
            render=args.render,
            size=args.size,
            view=args.view,
            camera=args.camera,
        )
        return report_scene(args, written)
    rules = load_rules(args.rules, allow=args.allow_outside)
    context = chosen_context(args, rules)
    scene = generate(
        rules,
        args.seed,
        style=args.style,
        variant=args.variant,
        templates=args.templates,
        words=args.words,
        context=context[1] if context is not None else None,
    )
    written = write_scene(
        scene, args.output, render=args.render, size=args.size, view=args.view, camera=args.camera
    )
    return report_scene(args, written)


def run_layout(args: argparse.Namespace) -> int:
    """Lay a scene.json out again, keeping the pinned ids where they are; write as generate does."""
    from scenewright.api import SceneGraphError, layout_again
    from scenewright.scene_folder import check_scene_folder, write_scene

    check_scene_folder(args.output)
    old = read_scene(args.scene)
    ids = [part.strip() for text in args.pin for part in text.split(",") if part.strip()]
    try:
        scene, added = layout_again(
            old,
            args.seed,
            pin=ids,
            warm=args.warm,
            context=args.context,
            templates=args.templates,
            style=args.style,
            variant=args.variant,
            words=args.words,
        )
    except SceneGraphError as error:
        raise SceneFileError(args.scene, str(error)) from error
    if ids:
        named = list(dict.fromkeys(ids))
        also = f" (with {', '.join(added)})" if added else ""
        say(args, f"pinned: {', '.join(named)}{also}")
    written = write_scene(scene, args.output, render=args.render, size=args.size, view=args.view)
    return report_scene(args, written)


def run_describe(args: argparse.Namespace) -> int:
    from scenewright.api import describe

    scene = read_scene(args.scene)
    print(
        describe(
            scene,
            style=args.style,
            variant=args.variant,
            templates=args.templates,
            words=args.words,
        ).text
    )
    return 0


def run_render(args: argparse.Namespace) -> int:
    from scenewright.api import render_image
    from scenewright.render.offscreen import save_render

    scene = read_scene(args.scene)
    target = output_file(args.output, "preview.png")
    result = render_image(scene, *args.size, view=args.view, normals=args.normals)
    written = save_render(result, target.parent, stem=target.stem)
    say(args, "wrote " + ", ".join(str(p) for p in written.values()))
    return 0


def run_export(args: argparse.Namespace) -> int:
    from scenewright.api import export

    scene = read_scene(args.scene)
    target = output_file(args.output, "scene.glb")
    export(
        scene,
        target,
        ground=args.ground,
        camera=args.camera,
        light=args.light,
        cutaway=args.cutaway,
    )
    say(args, f"wrote {target}")
    return 0
