"""The ``dataset`` command: N scenes as a Hugging Face imagefolder dataset
(``scenewright.dataset``)."""

from __future__ import annotations

import argparse
import sys
from functools import partial

from scenewright.api import DATASET_RETRIES
from scenewright.core.errors import InputError

from .common import (
    PROG,
    chosen_context,
    say,
)
from .options import (
    MAX_CAPTIONS,
    MAX_DATASET_SCENES,
    MAX_RETRIES,
    MAX_VIEW_TRIES,
    MAX_VIEWS,
    MAX_WORDS,
    MAX_WORKERS,
    add_command,
    camera_range,
    context_options,
    count_at_least,
    fraction,
    scheduler_address,
    seconds_value,
    seed_value,
    templates_option,
    view_options,
)

HELP = {
    "dataset": f"""\
examples:
  scenewright dataset village -n 1000 -o data/village --captions 3 --size 512x512
  scenewright dataset desk -n 200 -o data/desk --seed 42 --workers 2 --depth --segmentation
  scenewright dataset village -n 100000 -o data/village --scheduler tcp://head:8786
  scenewright dataset classroom -n 500 -o data/classroom --frame camera --min-visible 0.5 --min-size 24
  scenewright dataset my_town.rules -n 500 -o data/town --retries 6 --include-failed
  scenewright dataset bedroom -n 500 -o data/bedroom --no-images
  scenewright dataset fitted/dining.rules -n 1000 -o data/dining   # with fitted/dining.context.json
  scenewright dataset --prompts rooms.txt -n 500 -o data/requests --no-images

Scene i uses the seed SeedSequence([SEED, i]).generate_state(1)[0], so the output is the
same bytes whatever the number of workers. Rerunning the same command resumes an
interrupted run; rerunning with another -n grows the dataset or shrinks what
metadata.jsonl and the statistics list (scenes at N and above stay on disk). One run at
a time may use DIR (a second one exits 2). The directory loads with
datasets.load_dataset("imagefolder", data_dir=DIR). With --no-images nothing is rendered:
each scene is scenes/STEM.json and its description texts/STEM.txt, and its row names
both (scene_file_name, text_file_name) and holds the text (no captions of a picture).

A scene whose layout fails is laid out again (--retries K, default {DATASET_RETRIES}) with the layout
seed retry_seed(seed, k) and the same objects, so failures do not favour small scenes;
each row records its layout_seed and attempts, and stats.json the retries by scene size.

exit codes:
  0    all N scenes made, every layout ok
  1    some scenes failed: a layout failed after every retry (in failed/, or with
       --include-failed in metadata.jsonl as ok=false), or the rules could not make a
       scene for its seed (an expansion error, printed with its file:line:col); the
       other scenes are written. Also: the work failed (a lost dask scheduler, a worker
       that died; rerun to resume)
  2    bad input (options, rules, DIR made with other settings or in use, an
       unreachable scheduler or one without workers)
  130  interrupted (Ctrl-C; rerun to resume)""",
}


def add_commands(commands) -> None:
    """Add the command dataset to ``commands`` (argparse's subparsers)."""
    command = partial(add_command, commands, HELP)

    dataset = command(
        "dataset", "generate N scenes as a Hugging Face imagefolder dataset", run_dataset
    )
    dataset.add_argument(
        "rules",
        nargs="?",
        help="shipped rule set name or path to a .rules file (with --prompts: optional, the rule set "
        "whose catalog the prompts may name besides the shipped indoor one)",
    )
    dataset.add_argument(
        "--prompts",
        metavar="FILE",
        help="compose each scene from one request in English drawn from FILE (one a line, # a comment) "
        "with the scene's seed, as `compose` does; the rows record the prompt and its used and unused spans",
    )
    dataset.add_argument(
        "-n",
        "--count",
        type=count_at_least(1, MAX_DATASET_SCENES),
        required=True,
        metavar="N",
        help="number of scenes",
    )
    dataset.add_argument(
        "-o",
        "--output",
        required=True,
        metavar="DIR",
        help="dataset directory (resumed if it exists)",
    )
    dataset.add_argument("--seed", type=seed_value, default=0, help="base seed (0)")
    context_options(dataset)
    dataset.add_argument(
        "--workers",
        type=count_at_least(1, MAX_WORKERS),
        metavar="K",
        help="worker processes (default and maximum: one per CPU this process may use, and at most one per "
        "scene left to make; a larger K is lowered with a note; ignored with --scheduler)",
    )
    dataset.add_argument(
        "--captions",
        type=count_at_least(1, MAX_CAPTIONS),
        default=1,
        metavar="K",
        help="short captions per scene (1; at most 100)",
    )
    templates_option(dataset)
    view_options(dataset, "512x512")
    dataset.add_argument(
        "--no-images",
        dest="images",
        action="store_false",
        help="no render: write each scene's scene.json and its description (texts/) only, for fast example corpora",
    )
    dataset.add_argument(
        "--text-words",
        type=count_at_least(1, MAX_WORDS),
        default=None,
        metavar="N",
        help="the text column: the most detailed description (full, summary, short) of at most N words, "
        "for large scenes (default: the full description; scene.json keeps it either way)",
    )
    dataset.add_argument(
        "--depth",
        action="store_true",
        help="also write depth/: a 16-bit PNG (its unit in the row's depth_scale) and float32 "
        "metres (.npy) per image",
    )
    dataset.add_argument(
        "--normals",
        action="store_true",
        help="also write normals/ (surface normals in the camera frame, RGB)",
    )
    dataset.add_argument(
        "--boxes-3d",
        action="store_true",
        help="add the objects_3d column: each object's pose and 3D box in the camera frame",
    )
    dataset.add_argument(
        "--segmentation", action="store_true", help="also write segmentation/ (16-bit ids)"
    )
    dataset.add_argument(
        "--scheduler",
        type=scheduler_address,
        metavar="ADDRESS",
        help="run on a dask.distributed scheduler (tcp://host:8786)",
    )
    dataset.add_argument(
        "--worker-timeout",
        type=seconds_value,
        metavar="S",
        help="with --scheduler: give up after S seconds without a dask worker, at the start or mid-run (60)",
    )
    dataset.add_argument(
        "--include-failed",
        action="store_true",
        help="keep scenes whose layout failed, flagged ok=false",
    )
    dataset.add_argument(
        "--frame",
        choices=("scene", "camera"),
        default="scene",
        help="side words of the captions: the scene's (north of, B's own left) or the picture's "
        "('to the left of the tent in the picture') (scene)",
    )
    dataset.add_argument(
        "--min-visible",
        type=float,
        default=0.25,
        metavar="F",
        help="captions name only what shows at least this fraction of itself in the picture (0.25)",
    )
    dataset.add_argument(
        "--min-size",
        type=int,
        metavar="PX",
        help="...and whose pixel box is at least this long on its longer side (16, or a sixteenth of the "
        "image's shorter side when that is less)",
    )
    dataset.add_argument(
        "--no-grounding",
        dest="grounding",
        action="store_false",
        help="leave out the rows' grounding column (spans of the captions and text, ids, pixel boxes) and "
        "refexps column (referring expressions with their programs)",
    )
    dataset.add_argument(
        "--no-questions",
        dest="questions",
        action="store_false",
        help="leave out the rows' questions column (CLEVR-style questions with programs and answers) and "
        "questions.json",
    )
    dataset.add_argument(
        "--no-coco",
        dest="coco",
        action="store_false",
        help="leave out annotations/instances.json (COCO instances of every image, from the segmentation)",
    )
    dataset.add_argument(
        "--views",
        type=count_at_least(1, MAX_VIEWS),
        default=1,
        metavar="N",
        help="images per scene, each its own row, their cameras drawn from the ranges below (1; at most 100)",
    )
    for name, meaning in (
        ("azimuth", "in degrees from south towards east, e.g. 0:360 (the automatic view's)"),
        ("elevation", "in degrees above the horizon, within 0:89 (35)"),
        ("distance", "as a factor of the one that frames the target, within 0.1:10 (1)"),
    ):
        dataset.add_argument(
            f"--{name}",
            type=camera_range(name),
            metavar="X|LOW:HIGH",
            help=f"the cameras' {name} {meaning}",
        )
    dataset.add_argument(
        "--target",
        metavar="ID|TYPE",
        help="aim the cameras at this entity (or the first of this type); a scene without it is framed whole",
    )
    dataset.add_argument(
        "--target-visible",
        type=fraction,
        metavar="F",
        help="draw a view again while its target shows less than this visible fraction (0.5)...",
    )
    dataset.add_argument(
        "--view-tries",
        type=count_at_least(1, MAX_VIEW_TRIES),
        metavar="K",
        help="...up to K draws in all, keeping the view that showed the most (8)",
    )
    dataset.add_argument(
        "--retries",
        type=count_at_least(0, MAX_RETRIES),
        default=DATASET_RETRIES,
        metavar="K",
        help=f"lay a scene whose layout failed out again up to K times, with derived layout seeds and the same "
        f"objects ({DATASET_RETRIES}: with 30%% of layouts failing, 0.8%% of scenes still fail)",
    )


def dataset_cameras(args: argparse.Namespace):
    """The ``CameraRanges`` of ``dataset``'s camera options, or None when none is given
    (the automatic camera); ``InputError`` for several views that could not differ."""
    from scenewright.render.views import MIN_TARGET_VISIBLE, VIEW_TRIES, CameraRanges

    given = [
        args.azimuth,
        args.elevation,
        args.distance,
        args.target,
        args.target_visible,
        args.view_tries,
    ]
    if args.views == 1 and all(value is None for value in given):
        return None
    if args.view != "perspective":
        raise InputError(
            "camera options (--views, --azimuth, ...) draw perspective cameras; leave out --view top"
        )
    ranges = CameraRanges(
        azimuth=args.azimuth,
        elevation=args.elevation,
        distance=args.distance,
        target=args.target,
        min_visible=MIN_TARGET_VISIBLE if args.target_visible is None else args.target_visible,
        tries=VIEW_TRIES if args.view_tries is None else args.view_tries,
    )
    if args.views > 1 and not ranges.varies():
        raise InputError(
            f"--views {args.views} would draw {args.views} identical views; give --azimuth, --elevation or "
            "--distance a range LOW:HIGH"
        )
    return ranges


def run_dataset(args: argparse.Namespace) -> int:
    from scenewright.api import is_house_plan
    from scenewright.dataset.produce import with_picture_captions
    from scenewright.dataset.run import available_cpus
    from scenewright.dataset.run import run_dataset as run
    from scenewright.dataset.spec import dataset_spec
    from scenewright.generator import load_rules

    if not args.images and (args.depth or args.segmentation or args.normals or args.boxes_3d):
        raise InputError(
            "--depth, --segmentation, --normals and --boxes-3d are of images: "
            "they cannot be made with --no-images"
        )
    cameras = dataset_cameras(args)
    if args.rules is None and args.prompts is None:
        raise InputError("give a rule set, or --prompts FILE to compose the scenes from")
    house = args.rules is not None and is_house_plan(args.rules)
    rules = load_rules(args.rules) if args.rules is not None and not house else None
    if house and (args.context is not None or args.prompts is not None):
        raise InputError("--context and --prompts are for a rule set's scenes, not a house plan's")
    if args.prompts is not None and (args.context is not None or args.no_context):
        raise InputError(
            "--context and --no-context are for a rule set's scenes; "
            "scenes composed from --prompts are laid out without a learned context"
        )
    context = chosen_context(args, rules) if args.prompts is None and not house else None
    spec = dataset_spec(
        args.rules if house else rules,
        args.count,
        prompts=args.prompts,
        context=context[0] if context is not None else None,
        base_seed=args.seed,
        captions=args.captions,
        templates=args.templates,
        size=args.size,
        view=args.view,
        depth=args.depth,
        segmentation=args.segmentation,
        normals=args.normals,
        boxes_3d=args.boxes_3d,
        include_failed=args.include_failed,
        retries=args.retries,
        images=args.images,
        coco=args.coco,
        views=args.views,
        camera=cameras,
        text_words=args.text_words,
    )
    spec = with_picture_captions(
        spec,
        grounding=args.grounding,
        questions=args.questions,
        frame=args.frame,
        min_visible=args.min_visible,
        min_size=args.min_size,
    )
    cpus = available_cpus()
    if args.workers and args.workers > cpus and not args.scheduler and not args.quiet:
        print(
            f"{PROG}: note: --workers {args.workers} is more than the CPUs this process may use ({cpus}); "
            f"using {cpus}",
            file=sys.stderr,
        )
    report = run(
        spec,
        args.output,
        workers=args.workers,
        scheduler=args.scheduler,
        progress=not args.quiet,
        worker_timeout=args.worker_timeout,
    )
    notes, errors = report.summary(spec)
    for line in notes:
        say(args, line)
    for line in errors:
        print(f"{PROG}: error: {line}", file=sys.stderr)
    return 1 if report.failed else 0
