"""The ``scenewright`` command: generate scenes and datasets, check rules, inspect scenes.

Each subcommand is a small function ``run_<name>(args) -> exit code`` over the
pipeline functions of ``scenewright.api``; parsing and error reporting live here once.

Exit codes: 0 done; 1 generation failed (e.g. a layout that could not satisfy every
relation: its files are still written, marked ``ok: false``); 2 bad input (options,
missing or unreadable files, an output directory that cannot be written, bad rules, a
bad scene.json, an output that cannot be written). Errors print as one line
``scenewright: error: ...`` (a rules error as its located excerpt) and no traceback
unless ``--debug`` is given; running out of memory says so, and in which stage.
"""

from __future__ import annotations

import argparse
import json
import os
import re
import sys
import textwrap
import traceback
from collections.abc import Callable
from pathlib import Path

from scenewright import __version__
from scenewright.api import DATASET_RETRIES, STYLES, VIEWS
from scenewright.core.errors import InputError, ScenewrightError

PROG = "scenewright"
#: Files ``generate`` writes; stale ones from an earlier run into the same directory
#: (say a preview, before --no-render) are removed so the directory shows one scene.
GENERATE_OUTPUTS = (
    "scene.json",
    "timings.json",
    "description.txt",
    "preview.png",
    "preview_depth.png",
    "preview_seg.png",
    "preview_ids.json",
    "scene.glb",
    "plan.png",
)
#: ``complete`` writes generate's files and, with --explain, its layout mask.
COMPLETE_OUTPUTS = GENERATE_OUTPUTS + ("mask.png",)


class CommandLineParser(argparse.ArgumentParser):
    """argparse with one-line errors that exit 2 through ``main``'s error handling."""

    def error(self, message: str):  # type: ignore[override]
        raise InputError(f"{message} (see '{self.prog} --help')")


# -- option types ---------------------------------------------------------------------


def image_size(text: str) -> tuple[int, int]:
    """``WxH`` in pixels, e.g. ``640x480`` (ASCII digits only)."""
    match = re.fullmatch(r"([0-9]{1,9})[xX]([0-9]{1,9})", text)
    if match is None:
        raise argparse.ArgumentTypeError(
            f"expected WIDTHxHEIGHT such as 640x480, not {_clipped(text)}"
        )
    size = (int(match[1]), int(match[2]))
    if not all(8 <= side <= 8192 for side in size):
        raise argparse.ArgumentTypeError(f"each side must be 8..8192 pixels, not {_clipped(text)}")
    return size


def whole_number(text: str) -> int:
    """An optionally negative whole number in ASCII digits (``int`` would also take
    full-width digits, underscores and spaces)."""
    if re.fullmatch(r"-?[0-9]{1,30}", text) is None:
        raise argparse.ArgumentTypeError(f"expected a whole number, not {_clipped(text)}")
    return int(text)


def _clipped(text: str, limit: int = 40) -> str:
    """An argument as it may be shown in an error: quoted, escaped, and not too long."""
    shown = ascii(text)
    return shown if len(shown) <= limit else shown[: limit - 4] + "...'"


def count_at_least(minimum: int) -> Callable[[str], int]:
    def parse(text: str) -> int:
        value = whole_number(text)
        if value < minimum:
            raise argparse.ArgumentTypeError(f"must be at least {minimum}, not {value}")
        return value

    parse.__name__ = "number"
    return parse


def camera_range(name: str) -> Callable[[str], tuple[float, float]]:
    """An option's ``A`` or ``LOW:HIGH`` (``render.views.parse_range`` for ``name``)."""

    def parse(text: str) -> tuple[float, float]:
        from scenewright.render.views import parse_range

        try:
            return parse_range(text, name)
        except InputError as error:
            raise argparse.ArgumentTypeError(str(error)) from None

    parse.__name__ = f"{name} range"
    return parse


def camera_settings(text: str):
    """``generate --camera``'s ``KEY=VALUE,...`` (``render.views.parse_camera``)."""
    from scenewright.render.views import parse_camera

    try:
        return parse_camera(text)
    except InputError as error:
        raise argparse.ArgumentTypeError(str(error)) from None


def seed_value(text: str) -> int:
    value = whole_number(text)
    if not 0 <= value < 2**63:
        raise argparse.ArgumentTypeError(f"must be between 0 and 2**63-1, not {value}")
    return value


def prior_value(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"must be a number, not {_clipped(text)}") from None
    if not 0 < value <= 1000:
        raise argparse.ArgumentTypeError(f"must be above 0 and at most 1000, not {value:g}")
    return value


# -- shared helpers -------------------------------------------------------------------


def say(args: argparse.Namespace, text: str) -> None:
    """Print progress and summaries to stdout unless ``--quiet``."""
    if not args.quiet:
        print(text, flush=True)


def note_progress(args: argparse.Namespace, text: str) -> None:
    """Print a line on how long work goes to stderr unless ``--quiet``: stdout keeps the
    summary alone."""
    if not args.quiet:
        print(text, file=sys.stderr, flush=True)


def output_directory(path: str) -> Path:
    """``path`` created if needed and checked writable, else ``InputError``."""
    directory = Path(path)
    if directory.exists() and not directory.is_dir():
        raise InputError(f"cannot write to {directory}: it is a file, not a directory")
    try:
        directory.mkdir(parents=True, exist_ok=True)
        probe = directory / f".{PROG}-write-test.partial"
        probe.write_bytes(b"")
        probe.unlink()
    except OSError as error:
        raise InputError(f"cannot write to {directory}: {error.strerror or error}") from error
    return directory


def output_file(path: str, default_name: str) -> Path:
    """The file ``-o PATH`` names: PATH, or ``default_name`` inside it when PATH is an
    existing directory or ends in '/'. Its folder is created and checked writable."""
    target = Path(path)
    if path.endswith(("/", os.sep)) or target.is_dir():
        target = target / default_name
    output_directory(str(target.parent))
    return target


class SceneFileError(InputError):
    """A scene.json that cannot be read, is not JSON, or does not pass ``schema_check``;
    ``problems`` lists each problem as a line (one when the file could not be read)."""

    def __init__(self, path: str, reason: str, problems: list[str] | None = None):
        super().__init__(f"{path}: {reason}")
        self.path, self.reason = path, reason
        self.problems = problems or [reason]


def read_scene_data(path: str, *, check_files: bool = False) -> dict:
    """The checked document of a scene.json file (``schema_check``; with ``check_files``
    the files it names must exist too); ``SceneFileError`` if bad."""
    from scenewright.core.files import UnusableFile, read_regular_file
    from scenewright.core.limits import MAX_SCENE_JSON_BYTES
    from scenewright.schema_check import SceneSchemaError, parse_scene_json, validate_scene_dict

    try:
        text = read_regular_file(path, MAX_SCENE_JSON_BYTES, "a scene.json").decode("utf-8")
        data = parse_scene_json(text)
        validate_scene_dict(data, check_files=check_files)
    except UnusableFile as problem:
        raise SceneFileError(path, f"cannot read: it {problem}") from None
    except OSError as error:
        raise SceneFileError(path, f"cannot read: {error.strerror or error}") from None
    except UnicodeDecodeError:
        raise SceneFileError(path, "not UTF-8 text") from None
    except SceneSchemaError as error:
        lines = [f"scene.json {where}: {message}" for where, message in error.problems]
        raise SceneFileError(path, str(error), lines) from None
    except ValueError as error:
        raise SceneFileError(path, f"not JSON: {error}") from None
    return data


def read_scene(path: str):
    """A Scene from a scene.json file, checked (``read_scene_data``)."""
    from scenewright.core.scene import Scene

    return Scene.from_dict(read_scene_data(path))


# -- subcommands ----------------------------------------------------------------------


def run_generate(args: argparse.Namespace) -> int:
    from scenewright.api import generate, render_scene
    from scenewright.atomic import check_output_directory
    from scenewright.generator import load_rules

    check_output_directory(
        args.output, GENERATE_OUTPUTS
    )  # before any work: it is replaced as a whole
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
    images = None
    if args.render:
        scene, images = render_scene(scene, size=args.size, view=args.view, camera=args.camera)
    elif args.camera is not None:
        raise InputError(
            "--camera places the preview's camera; it needs the preview (leave out --no-render)"
        )
    return write_scene_outputs(args, scene, images)


def write_scene_outputs(
    args: argparse.Namespace, scene, images, outputs=GENERATE_OUTPUTS, extra: dict | None = None
) -> int:
    """Write what ``generate`` writes for a finished scene (all files appear together or
    not at all) and report the layout's verdict: exit 0 when ok, 1 when not. ``extra``
    (file name -> function writing it to a path) adds files; ``outputs`` names every
    file the command may write (stale ones not written this time are removed)."""
    from scenewright.api import export, reproducible_json, summary_line, timed, timings_of
    from scenewright.atomic import staged_outputs, write_atomic, writing
    from scenewright.render.offscreen import save_render
    from scenewright.render.plan import draw_plan

    directory = args.output.rstrip("/") or "/"
    with staged_outputs(args.output, outputs) as stage:
        write_atomic(stage / "description.txt", scene.description.text + "\n")
        for name, write in (extra or {}).items():
            with writing(stage / name):
                write(stage / name)
        if images is not None:
            save_render(images, stage, stem="preview")
        with timed(scene.timings, "export"):
            export(scene, stage / "scene.glb")
        with writing(stage / "plan.png"):
            draw_plan(scene, stage / "plan.png")
        write_atomic(stage / "scene.json", reproducible_json(scene))
        write_atomic(stage / "timings.json", json.dumps(timings_of(scene), indent=1) + "\n")
        written = sorted(p.name for p in stage.iterdir())
    say(args, f"wrote {directory}/: {', '.join(written)}")
    say(args, summary_line(scene))
    if scene.layout.ok:
        return 0
    problems = "; ".join(scene.layout.problems) or "see layout in scene.json"
    print(
        f"{PROG}: error: the layout did not satisfy every constraint (files kept): {problems}",
        file=sys.stderr,
    )
    return 1


def run_layout(args: argparse.Namespace) -> int:
    """Lay a scene.json out again, keeping the pinned ids where they are; write as generate does."""
    from scenewright.api import checked_templates, describe_scene, render_scene, timed
    from scenewright.atomic import check_output_directory
    from scenewright.core.scene import assemble_scene
    from scenewright.generator.layout import layout_scene
    from scenewright.generator.layout.pinning import pins_from_scene, scene_layout
    from scenewright.generator.layout.problem import compile_problem

    check_output_directory(args.output, GENERATE_OUTPUTS)
    old = read_scene(args.scene)
    templates = checked_templates(args.templates)
    try:
        graph = old.graph()
        problem = compile_problem(graph)
    except InputError as error:
        raise SceneFileError(args.scene, str(error)) from error
    except (KeyError, ValueError, TypeError) as error:
        raise SceneFileError(args.scene, f"not a valid scene graph: {error}") from error
    ids = [part.strip() for text in args.pin for part in text.split(",") if part.strip()]
    pins = pins_from_scene(old, problem, ids)
    start = None
    if args.warm:
        poses, points = scene_layout(old)
        start = {**poses, **points}
    timings: dict[str, float] = {}
    context = None
    if args.context is not None:
        from scenewright.generator.layout.learned_term import read_context

        context = read_context(args.context)
    with timed(timings, "layout"):
        layout = layout_scene(
            graph,
            args.seed,
            pinned=pins.poses,
            pinned_paths=pins.paths,
            start=start,
            context=context,
        )
    scene = assemble_scene(graph, layout, rules=old.rules, seed=args.seed)
    scene.derivation = list(old.derivation)
    if templates is not None:
        scene.templates = templates
    scene.timings.update(timings)
    scene = describe_scene(scene, style=args.style, variant=args.variant, words=args.words)
    images = None
    if args.render:
        scene, images = render_scene(scene, size=args.size, view=args.view)
    if ids:
        named = list(dict.fromkeys(ids))
        also = f" (with {', '.join(pins.added)})" if pins.added else ""
        say(args, f"pinned: {', '.join(named)}{also}")
    return write_scene_outputs(args, scene, images)


def seconds_value(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a number of seconds, not {text!r}") from None
    if not 0 < value < float("inf"):
        raise argparse.ArgumentTypeError(f"must be a positive number of seconds, not {text!r}")
    return value


def scheduler_address(text: str) -> str:
    if not text.strip():
        raise argparse.ArgumentTypeError(
            "expected a scheduler address such as tcp://host:8786, not an empty string"
        )
    return text.strip()


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


def chosen_context(args: argparse.Namespace, rules):
    """The learned context ``--context`` names, else the one beside the rules, as (file,
    context); None with ``--no-context`` or when there is none. Says which it uses."""
    from scenewright.api import rules_context

    if args.context is not None and args.no_context:
        raise InputError("--context and --no-context contradict each other; give one")
    context = None if args.no_context else rules_context(rules, args.context)
    if context is not None:
        say(args, f"context: {context[0]} ({len(context[1].pairs)} pair kinds)")
    return context


def run_dataset(args: argparse.Namespace) -> int:
    from scenewright.dataset import available_cpus, dataset_spec
    from scenewright.dataset import run_dataset as run
    from scenewright.dataset_scene import with_picture_captions
    from scenewright.generator import load_rules

    if not args.images and (args.depth or args.segmentation):
        raise InputError(
            "--depth and --segmentation are images: they cannot be made with --no-images"
        )
    cameras = dataset_cameras(args)
    rules = load_rules(args.rules)
    context = chosen_context(args, rules)
    spec = dataset_spec(
        rules,
        args.count,
        context=context[0] if context is not None else None,
        base_seed=args.seed,
        captions=args.captions,
        templates=args.templates,
        size=args.size,
        view=args.view,
        depth=args.depth,
        segmentation=args.segmentation,
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


def run_validate(args: argparse.Namespace) -> int:
    from scenewright.examples.formats import is_handwritten_example
    from scenewright.generator import check_rules, shipped_rule_sets

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
    print(f"{name}: ok ({kind} example: {objects} object{'s' * (objects != 1)} in {room})")
    return True


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


def emit(args: argparse.Namespace, text: str) -> int:
    """Write ``text`` to ``--output`` (atomically) or, without one, to stdout; exit code 0."""
    from scenewright.atomic import write_atomic

    if args.output:
        write_atomic(args.output, text)
        say(args, f"wrote {args.output}")
    else:
        sys.stdout.write(text)
    return 0


def run_expand(args: argparse.Namespace) -> int:
    from scenewright.generator import expand, graph_to_dot, load_rules

    graph = expand(load_rules(args.rules, allow=args.allow_outside), args.seed)
    text = (
        graph_to_dot(graph)
        if args.format == "dot"
        else json.dumps(graph.to_dict(), indent=1) + "\n"
    )
    return emit(args, text)


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
    result = render_image(scene, *args.size, view=args.view)
    written = save_render(result, target.parent, stem=target.stem)
    say(args, "wrote " + ", ".join(str(p) for p in written.values()))
    return 0


def run_export(args: argparse.Namespace) -> int:
    from scenewright.api import export

    scene = read_scene(args.scene)
    target = output_file(args.output, "scene.glb")
    export(scene, target)
    say(args, f"wrote {target}")
    return 0


def run_schema(args: argparse.Namespace) -> int:
    from scenewright.schema_check import load_schema

    print(json.dumps(load_schema(), indent=2, ensure_ascii=False))
    return 0


def run_fit(args: argparse.Namespace) -> int:
    from scenewright.atomic import write_atomic
    from scenewright.examples.formats import example_paths
    from scenewright.learning.fit import fit_rule_set, parse_what

    what = parse_what(args.what)
    examples = [(str(path), read_fit_example(path)) for path in example_paths(args.examples)]
    output = output_file(args.output, "fitted.rules")
    report = output_file(args.report, "fit.json") if args.report else None
    fit, context, written = fit_rule_set(
        args.rules,
        examples,
        output,
        report=report,
        allow=args.allow_outside,
        prior=args.prior,
        write=write_atomic,
        what=what,
        seed=args.seed,
        rounds=args.rounds,
        layouts=args.layouts,
    )
    unidentified = fit.unidentified
    if "weights" in what:
        say(
            args,
            f"fitted {len(fit.parameters)} parameters from {fit.examples} example"
            f"{'s' if fit.examples != 1 else ''}"
            + (
                f"; {len(unidentified)} no example drew kept their numbers: "
                + ", ".join(f"{p.kind} {p.name}" for p in unidentified)
                if unidentified
                else ""
            ),
        )
    if context is not None:
        say(
            args,
            f"fitted a context of {len(context.context.pairs)} pair kind"
            f"{'s' * (len(context.context.pairs) != 1)} from {len(examples)} examples "
            f"(divergence {context.divergence[0]:.3f} at the start, {context.divergence[context.kept]:.3f} kept)",
        )
    say(args, "wrote " + ", ".join(str(path) for path in written))
    return 0


def read_fit_example(path: str | os.PathLike):
    """A scene.json document (checked; its derivation, when kept, is what is fitted), or
    the Scene of an example read from geometry alone (the hand-written format, GLB)."""
    from scenewright.examples import load_example
    from scenewright.examples.formats import is_scene_json_file

    if is_scene_json_file(path):
        folder = Path(path)
        return read_scene_data(str(folder / "scene.json" if folder.is_dir() else folder))
    return load_example(path).scene


def run_relations(args: argparse.Namespace) -> int:
    from scenewright.examples import load_examples
    from scenewright.learning.relations import find_relations

    examples = load_examples(args.examples)
    result = find_relations(
        [e.scene for e in examples], test=args.test, seed=args.seed, prune=args.prune
    )
    sys.stdout.write(json.dumps(result.to_dict(), indent=1) + "\n" if args.json else result.table())
    return 0


def run_learn(args: argparse.Namespace) -> int:
    from scenewright.atomic import write_atomic
    from scenewright.examples import load_examples
    from scenewright.learning.context import context_path
    from scenewright.learning.learn import CONTEXT_REPLAYS, learn_rule_set

    examples = load_examples(args.examples)
    output = output_file(args.output, "induced.rules")
    report = output_file(args.report, "learn.json") if args.report else None
    learned = learn_rule_set(
        examples,
        output,
        report=report,
        seed=args.seed,
        test=args.test,
        check=args.check,
        context=args.context,
        rounds=args.rounds,
        layouts=args.layouts,
        write=write_atomic,
        progress=lambda message: note_progress(args, message),
    )
    induction = learned.induction
    related = sum(pair.related for pair in induction.relations.pairs)
    say(
        args,
        f"induced {len(induction.catalog)} types, {len(induction.groups)} group"
        f"{'s' * (len(induction.groups) != 1)} and {len(induction.written_pairs())} relations from "
        f"{induction.scenes} examples ({related} related type pairs by the {induction.relations.test} test)",
    )
    if learned.check is not None:
        say(args, learned.check.summary())
    context = learned.context
    if context is not None:
        left_out = "".join(
            f"; {len(names)} example{'s' * (len(names) != 1)} {why} left out ({', '.join(names)})"
            for names, why in (
                (context.left_out, "no derivation of the induced rules makes"),
                (context.ambiguous, "the induced rules make in too many ways to search"),
            )
            if names
        )
        if context.unsearched:
            left_out += (
                f"; {len(context.unsearched)} not searched (the searches before them spent the "
                f"{CONTEXT_REPLAYS} replays all share)"
            )
        if context.fit is not None:
            pairs = context.fit.context.pairs
            say(
                args,
                f"fitted a context of {len(pairs)} pair kind{'s' * (len(pairs) != 1)} from {context.used} "
                f"examples (divergence {context.fit.divergence[0]:.3f} at the start, "
                f"{context.fit.divergence[context.fit.kept]:.3f} kept){left_out}",
            )
        else:
            say(args, f"no context learned: {context.why_not}{left_out}")
    sidecar = context_path(output)
    if sidecar not in learned.written and sidecar.exists():
        say(
            args,
            f"note: {sidecar} beside the rules is not from this run; generate will use it (--no-context "
            "leaves it out)",
        )
    say(args, "wrote " + ", ".join(str(path) for path in learned.written))
    return 0


def fraction(text: str) -> float:
    """A number from 0 to 1."""
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(
            f"expected a number from 0 to 1, not {_clipped(text)}"
        ) from None
    if not 0.0 <= value <= 1.0:
        raise argparse.ArgumentTypeError(f"must be from 0 to 1, not {_clipped(text)}")
    return value


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
    from scenewright.atomic import write_atomic
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
    from scenewright.atomic import check_output_directory
    from scenewright.examples import load_examples
    from scenewright.variation.synthesis import vary
    from scenewright.variation.write import FOLDERS, summary, write_variants

    check_output_directory(args.output, FOLDERS)  # before any work: it is replaced as a whole
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


def run_list(args: argparse.Namespace) -> int:
    from scenewright.api import load_rules
    from scenewright.core.shapes import SHAPES
    from scenewright.generator import shipped_rule_sets

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
    return 0


def created_types(rules) -> set[str]:
    """The names the subjects of ``rules``' statements give (types and groups made, and
    names bound before)."""
    from scenewright.generator import rules_ast as ast

    return {
        statement.subject.name
        for production in rules.productions.values()
        for statement in ast.production_statements(production)
        if isinstance(statement.subject, ast.Reference)
    }


def run_plans_build(args: argparse.Namespace) -> int:
    """Read a plan set, build its model and write it (atomically)."""
    from scenewright.atomic import write_atomic
    from scenewright.completion.model import build_model, model_json
    from scenewright.completion.plan import load_plans

    plans = load_plans(args.plans)
    model = build_model(plans)
    target = output_file(args.output, "model.json")
    write_atomic(target, model_json(model))
    counts = ", ".join(f"{entry['plans']} {name}" for name, entry in model["types"].items())
    say(
        args,
        f"wrote {target}: {len(plans)} plans ({counts}), {len(model['categories'])} categories",
    )
    return 0


def run_plans_graph(args: argparse.Namespace) -> int:
    """Print (or write) one room type's object relation graph."""
    from scenewright.completion import shipped_plans_dir
    from scenewright.completion.model import build_model, graph_dot, read_model, relation_graph
    from scenewright.completion.plan import load_plans

    model = (
        read_model(args.model)
        if args.model
        else build_model(load_plans(args.plans or shipped_plans_dir()))
    )
    graph = relation_graph(model, args.type)
    text = graph_dot(graph) if args.format == "dot" else json.dumps(graph, indent=1) + "\n"
    return emit(args, text)


def run_plans_draw(args: argparse.Namespace) -> int:
    """Draw plans of a set (all, or the ids named) on one sheet."""
    from scenewright.atomic import atomic_stream, writing
    from scenewright.completion import shipped_plans_dir
    from scenewright.completion.drawing import MAX_PANELS, draw_plans
    from scenewright.completion.plan import load_plans

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
    from scenewright.completion.plan import load_plans

    table = leave_one_out(load_plans(args.plans or shipped_plans_dir()), args.requested)
    sys.stdout.write(report(table, args.requested))
    return 0


def run_complete(args: argparse.Namespace) -> int:
    """Complete an empty room from a few categories; write as generate does."""
    from scenewright.api import checked_templates, describe_scene, render_scene
    from scenewright.atomic import check_output_directory
    from scenewright.completion.complete import (
        complete,
        draw_explanation,
        parse_request,
        summary_of,
    )
    from scenewright.generator import indoor_catalog

    check_output_directory(
        args.output, COMPLETE_OUTPUTS
    )  # before any work: it is replaced as a whole
    catalog = indoor_catalog()
    keep = None
    if args.scene is not None:
        from scenewright.completion.complete import existing_request, parse_categories

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
        request = parse_request(args.room, args.door, args.window, args.categories, catalog)
    templates = checked_templates(args.templates)
    scene = complete(request, args.seed, plans=args.plans, catalog=catalog, keep=keep)
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
    scene = describe_scene(
        scene, style=args.style, variant=args.variant, templates=templates, words=args.words
    )
    images = None
    if args.render:
        scene, images = render_scene(scene, size=args.size, view=args.view)
    extra = {"mask.png": lambda path: draw_explanation(scene, path)} if args.explain else None
    return write_scene_outputs(args, scene, images, COMPLETE_OUTPUTS, extra)


# -- the parser -----------------------------------------------------------------------

EXAMPLES = {
    "generate": """\
examples:
  scenewright generate village --seed 7 -o out/
  scenewright generate my_town.rules --seed 3 --style short --size 1024x768 -o town/
  scenewright generate desk --no-render -o desk/
  scenewright generate market.rules --templates my_words/ -o market/

writes scene.json (reproducible: no wall-clock times), timings.json, description.txt,
preview.png (+ preview_depth.png, preview_seg.png, preview_ids.json), scene.glb and
plan.png (a top-down debug plan). All files appear together or not at all. When the
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
    "dataset": f"""\
examples:
  scenewright dataset village -n 1000 -o data/village --captions 3 --size 512x512
  scenewright dataset desk -n 200 -o data/desk --seed 42 --workers 2 --depth --segmentation
  scenewright dataset village -n 100000 -o data/village --scheduler tcp://head:8786
  scenewright dataset classroom -n 500 -o data/classroom --frame camera --min-visible 0.5 --min-size 24
  scenewright dataset my_town.rules -n 500 -o data/town --retries 6 --include-failed
  scenewright dataset bedroom -n 500 -o data/bedroom --no-images
  scenewright dataset fitted/dining.rules -n 1000 -o data/dining   # with fitted/dining.context.json

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
    "validate": """\
examples:
  scenewright validate village
  scenewright validate my.rules out/scene.json
  scenewright validate my_rooms/study.json my_rooms/kitchen.glb    # example scenes, as learn reads them

Prints "FILE: ok" or every diagnostic (file:line:column with the line and a caret).
Exit 2 when any file has an error; warnings alone exit 0.""",
    "expand": """\
examples:
  scenewright expand village --seed 7
  scenewright expand village --seed 7 --format dot -o village.dot && dot -Tsvg village.dot""",
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

writes the colour image and, beside it, STEM_depth.png (16-bit millimetres),
STEM_seg.png (16-bit instance ids) and STEM_ids.json (id -> object). When PNG is an
existing directory or ends in '/', the files are preview.png etc. inside it.""",
    "export": """\
examples:
  scenewright export out/scene.json -o out/scene.glb
  scenewright export out/scene.json -o exports/

When GLB is an existing directory or ends in '/', the file is scene.glb inside it.""",
    "schema": """\
examples:
  scenewright schema > scene.schema.json""",
    "fit": """\
examples:
  scenewright dataset study -n 500 -o data/study --size 64x64
  scenewright fit study data/study/scenes/*.json -o fitted/study.rules --report fitted/fit.json
  scenewright fit my.rules liked/*.json -o my_fitted.rules
  scenewright fit bedroom my_rooms/ -o my_bedroom.rules   # hand-written examples or GLB, a folder of them
  scenewright fit bedroom my_rooms/ -o my_bedroom.rules --what weights,context   # and spatial priors

Re-estimates the rule set's numbers from what the example scenes drew: alternative
weights, optional probabilities, count distributions (a range becomes a weighted range
'2..4 {0.2 0.5 0.3}') and style weights. Each is the posterior mean under a Dirichlet
prior of --prior pseudo-draws per option; the report gives every parameter with its
draws, estimate, standard error and the value written before. A parameter no example
drew keeps its number and is listed as unidentified. The output is the input with only
its numbers changed; files it includes are written beside it at the same relative paths.
Examples are scene.json files of this rule set. Those made by scenewright keep their
derivation (the draws fit counts); for one without, fit searches for the derivations
that could have made it and fits by expectation-maximisation (docs/learning.md).
Hand-written examples and GLB files (their types named as in the rules) are fitted the
same way, the derivations told apart by which of their relations the geometry holds;
for --what context their objects are related as their derivation relates them.""",
    "relations": """\
examples:
  scenewright dataset bedroom -n 500 -o data/bedroom --no-images
  scenewright relations data/bedroom/scenes/*.json
  scenewright relations rooms/*.json room.glb --json
  scenewright relations data/bedroom/scenes/*.json --test angle --seed 3

finds which pairs of object types stand in a pattern relative to each other in the
example scenes (scene.json or its folder, the hand-written example format, GLB). The
default test compares where a b stands in an a's frame (position and turn) within a
scene with an a and a b of two different scenes, whose placements are independent
(energy distance, 199 permutations, related at p <= 0.01); --test angle is the test of
complete spatial randomness by angles of Zhang et al. (related at d >= 1.628);
--test cooccurrence calls a pair related when most scenes hold both. Of a triangle of
related types a pair that holds only through the third type is reported as indirect
(a lamp on a nightstand by a bed relates to the bed through the nightstand): one
resting on another, else for the default test a pair whose poses are no tighter than
their composition through the third type (of such, the least direct in the
coordinates that hold its relation, or of those about as direct the one standing
farthest apart; roads close triangles too), else the weakest pair; a third type in
fewer than 3 of 4 of a pair's scenes carries nothing; --no-prune keeps them. A type
resting on another in half the scenes holding both or more (measured from the boxes)
is related to it whatever the p-value, from 5 scenes. A pair the room fixes side by
side in most scenes (a stove beside a sink under the one window), which no test of
poses can contrast, is related as "fixed". In scenes with
groups (a home, a market stand) each type is tested in each kind of group it stands in
(a bush in a home, a bush in a park), and a type pair takes the verdict of its most
related pair of such roles ("in groups"); a triangle of parts of one kind of group is
judged within each group. Prints a table of every pair of types that share a scene,
or with --json the same fields (a, b, related, statistic, p_value, pairs, scenes,
strength, tested, fixed, pruned, groups). The same examples and seed
print the same result. See docs/learning.md.""",
    "learn": """\
examples:
  scenewright learn examples/sets/desks/*.json -o desks.rules --report learn.json
  scenewright learn data/bedroom/scenes/*.json -o bedroom_learned.rules --seed 3 --check 0
  scenewright learn examples/sets/bedrooms -o bedrooms.rules   # a folder; writes bedrooms.context.json too
  scenewright learn examples/sets/desks/*.json -o desks.rules --no-context   # the rules alone
  scenewright validate desks.rules && scenewright generate desks.rules --seed 1 -o out/
  (examples/sets/ is in the repository: run these from its root, or name your own files)

induces a rule set from example scenes alone (scene.json or its folder, the
hand-written example format, GLB; a folder of such files): a catalog of the types seen (median sizes, styles
weighted by how often each was seen), the type pairs related by --test (and what rests
on what, measured from the boxes) grouped around an anchor object, each member placed
relative to its parent by the labels that hold at the density-peak clusters of its
relative poses (several clusters: weighted alternatives), and how often and how many
of each were seen ('0.85? 1..3 {6 4 1}'). The file is checked like 'validate' does,
then --check N scenes (50) are generated from it and compared with the examples: each
type's count per scene, the share of scenes holding each related pair, the share of
objects for which the written placement holds. Unless --no-context, a context (spatial
priors, as 'fit --what context' learns them) is fitted to the same examples against the
induced rules and written beside them as NAME.context.json; when no related pair occurs
in two examples, the rules are written without one and a line says why. --report gives
every type pair (test statistic, p-value, the labels chosen and their clusters), the
catalog, the groups, that comparison and the context's fit. The same examples and seed
give the same files. See docs/learning.md.""",
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
    "complete": """\
examples:
  scenewright complete --room 5x4 --door S:0.8:0.9 --window N:2.5:1.4 --with bed,bookshelf --seed 1 -o bedroom/
  scenewright complete --room 6x5 --door W:1:0.9 --with dining_table --with chair=6 --no-render -o dining/
  scenewright complete --room "0,0 6,0 6,3 3,3 3,5 0,5" --door 1:1:0.9 --with desk -o office/
  scenewright complete bedroom/scene.json --add piano -o bedroom2/   # what is there stays put

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
    "list": """\
examples:
  scenewright list
  scenewright list --shapes

--shapes prints each procedural shape a catalog entry may name ("shape NAME") with its
footprint convention: what its front (local +Z) shows and where a person uses it from.""",
}


def common_options(suppress: bool) -> argparse.ArgumentParser:
    """--debug and --quiet, accepted before or after the subcommand."""
    default = argparse.SUPPRESS if suppress else False
    options = argparse.ArgumentParser(add_help=False)
    options.add_argument(
        "--debug", action="store_true", default=default, help="show tracebacks of errors"
    )
    options.add_argument(
        "-q", "--quiet", action="store_true", default=default, help="print only errors"
    )
    return options


def build_parser() -> CommandLineParser:
    parser = CommandLineParser(
        prog=PROG,
        description="Procedural 3D scenes from a graph grammar, laid out by MCMC and described in English.",
        epilog="examples:\n  scenewright generate village --seed 7 -o out/\n  scenewright list\n"
        "  scenewright COMMAND --help",
        formatter_class=argparse.RawDescriptionHelpFormatter,
        parents=[common_options(suppress=False)],
    )
    parser.add_argument("--version", action="version", version=f"{PROG} {__version__}")
    commands = parser.add_subparsers(dest="command", metavar="COMMAND", required=True)

    def command(name: str, summary: str, handler) -> CommandLineParser:
        sub = commands.add_parser(
            name,
            help=summary,
            description=summary,
            epilog=EXAMPLES[name],
            formatter_class=argparse.RawDescriptionHelpFormatter,
            parents=[common_options(suppress=True)],
        )
        sub.set_defaults(handler=handler)
        return sub

    def style_options(sub: argparse.ArgumentParser) -> None:
        sub.add_argument("--style", choices=STYLES, default="full", help="description style")
        sub.add_argument(
            "--words",
            type=count_at_least(1),
            default=None,
            metavar="N",
            help="a word budget: the most detailed style (full, summary, short) whose text has at most N "
            "words (short when none has), instead of --style",
        )
        sub.add_argument(
            "--variant", type=count_at_least(0), default=0, help="paraphrase variant (0 canonical)"
        )
        templates_option(sub)

    def templates_option(sub: argparse.ArgumentParser) -> None:
        sub.add_argument(
            "--templates",
            metavar="DIR",
            help="folder of description templates (*.j2) to use instead of the rule set's own",
        )

    def allow_option(sub: argparse.ArgumentParser) -> None:
        sub.add_argument(
            "--allow-outside",
            action="append",
            default=[],
            metavar="PATH",
            help="let the rule set also read PATH (a folder, with all below it, or a file) outside its own "
            "folder (repeatable; see docs/security.md)",
        )

    def context_options(sub: argparse.ArgumentParser) -> None:
        sub.add_argument(
            "--context",
            metavar="JSON",
            help="a learned context (scenewright fit --what context); by default NAME.context.json beside a "
            "NAME.rules file is used when it exists",
        )
        sub.add_argument(
            "--no-context", action="store_true", help="ignore NAME.context.json beside the rules"
        )

    def view_options(sub: argparse.ArgumentParser, size: str) -> None:
        sub.add_argument(
            "--size",
            type=image_size,
            default=image_size(size),
            metavar="WxH",
            help=f"image size ({size})",
        )
        sub.add_argument("--view", choices=VIEWS, default="perspective", help="camera")

    generate = command(
        "generate", "generate one scene with its description, images and files", run_generate
    )
    generate.add_argument(
        "rules", help="shipped rule set name (see 'list') or path to a .rules file"
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

    dataset = command(
        "dataset", "generate N scenes as a Hugging Face imagefolder dataset", run_dataset
    )
    dataset.add_argument("rules", help="shipped rule set name or path to a .rules file")
    dataset.add_argument(
        "-n", "--count", type=count_at_least(1), required=True, metavar="N", help="number of scenes"
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
        type=count_at_least(1),
        metavar="K",
        help="worker processes (default and maximum: one per CPU this process may use, and at most one per "
        "scene left to make; a larger K is lowered with a note; ignored with --scheduler)",
    )
    dataset.add_argument(
        "--captions",
        type=count_at_least(1),
        default=1,
        metavar="K",
        help="short captions per scene (1)",
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
        type=count_at_least(1),
        default=None,
        metavar="N",
        help="the text column: the most detailed description (full, summary, short) of at most N words, "
        "for large scenes (default: the full description; scene.json keeps it either way)",
    )
    dataset.add_argument(
        "--depth", action="store_true", help="also write depth/ (16-bit millimetres)"
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
        type=count_at_least(1),
        default=1,
        metavar="N",
        help="images per scene, each its own row, their cameras drawn from the ranges below (1)",
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
        type=count_at_least(1),
        metavar="K",
        help="...up to K draws in all, keeping the view that showed the most (8)",
    )
    dataset.add_argument(
        "--retries",
        type=count_at_least(0),
        default=DATASET_RETRIES,
        metavar="K",
        help=f"lay a scene whose layout failed out again up to K times, with derived layout seeds and the same "
        f"objects ({DATASET_RETRIES}: with 30%% of layouts failing, 0.8%% of scenes still fail)",
    )

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

    expand = command("expand", "print the scene graph that the grammar expands to", run_expand)
    expand.add_argument("rules", help="shipped rule set name or path to a .rules file")
    expand.add_argument("--seed", type=seed_value, default=0, help="random seed (0)")
    expand.add_argument(
        "--format", choices=("json", "dot"), default="json", help="output format (json)"
    )
    expand.add_argument("-o", "--output", metavar="FILE", help="write to FILE instead of stdout")
    allow_option(expand)

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

    export = command("export", "export a scene.json as binary glTF", run_export)
    export.add_argument("scene", metavar="SCENE_JSON")
    export.add_argument(
        "-o",
        "--output",
        default="scene.glb",
        metavar="GLB",
        help="output file (scene.glb), or a directory",
    )

    fit = command("fit", "re-estimate a rule set's weights from example scenes", run_fit)
    fit.add_argument("rules", help="shipped rule set name or path to a .rules file")
    fit.add_argument(
        "examples",
        nargs="+",
        metavar="EXAMPLE",
        help="example scenes of the rule set (scene.json, the hand-written format, GLB, or a folder of them)",
    )
    fit.add_argument(
        "-o", "--output", required=True, metavar="RULES", help="the fitted rules file to write"
    )
    fit.add_argument(
        "--report", metavar="JSON", help="also write every parameter with its standard error here"
    )
    fit.add_argument(
        "--prior",
        type=prior_value,
        default=0.5,
        metavar="A",
        help="Dirichlet pseudo-draws per option (0.5: Jeffreys' prior; more pulls rarely drawn parameters "
        "towards uniform)",
    )
    fit.add_argument(
        "--what",
        default="weights",
        metavar="WHAT[,WHAT]",
        help="what to fit: weights (the rules' numbers, the default), context (spatial priors learned from the "
        "examples' layouts, written beside the rules as NAME.context.json), or weights,context",
    )
    fit.add_argument(
        "--seed", type=seed_value, default=0, help="seed of the context fit's layouts (0)"
    )
    fit.add_argument(
        "--rounds",
        type=count_at_least(0),
        default=2,
        metavar="N",
        help="context: rounds of iterative scaling (2)",
    )
    fit.add_argument(
        "--layouts",
        type=count_at_least(1),
        default=40,
        metavar="N",
        help="context: scenes laid out per round (40)",
    )
    allow_option(fit)

    relations = command(
        "relations",
        "find which object type pairs are spatially related in example scenes",
        run_relations,
    )
    relations.add_argument(
        "examples",
        nargs="+",
        metavar="EXAMPLE",
        help="example scenes (scene.json or its folder, .json, .glb)",
    )
    relations.add_argument("--json", action="store_true", help="print the result as JSON")
    relations.add_argument(
        "--test",
        choices=("permutation", "angle", "cooccurrence"),
        default="permutation",
        help="permutation (default: within- vs across-scene poses), angle (complete spatial randomness by "
        "angles) or cooccurrence (a baseline)",
    )
    relations.add_argument(
        "--seed", type=seed_value, default=0, help="seed of the tests' random draws (0)"
    )
    relations.add_argument(
        "--no-prune",
        dest="prune",
        action="store_false",
        help="keep indirect relations (a pair of a triangle that holds through the third type)",
    )

    learn = command("learn", "induce a rule set from example scenes alone", run_learn)
    learn.add_argument(
        "examples",
        nargs="+",
        metavar="EXAMPLE",
        help="example scenes (scene.json or its folder, .json, .glb)",
    )
    learn.add_argument(
        "-o", "--output", required=True, metavar="RULES", help="the rules file to write"
    )
    learn.add_argument(
        "--report",
        metavar="JSON",
        help="also write the pairs, catalog, groups, the check and the context's fit here",
    )
    learn.add_argument(
        "--seed",
        type=seed_value,
        default=0,
        help="seed of the relation test, the check scenes and the context fit (0)",
    )
    learn.add_argument(
        "--test",
        choices=("permutation", "angle", "cooccurrence"),
        default="permutation",
        help="which test finds the related type pairs (permutation; see 'relations --help')",
    )
    learn.add_argument(
        "--check",
        type=count_at_least(0),
        default=50,
        metavar="N",
        help="scenes to generate from the induced rules and compare with the examples (50; 0: none)",
    )
    learn.add_argument(
        "--no-context",
        dest="context",
        action="store_false",
        help="write no context: by default spatial priors are learned from the examples' layouts against the "
        "induced rules and written beside them as NAME.context.json, which generate uses",
    )
    learn.add_argument(
        "--rounds",
        type=count_at_least(0),
        default=2,
        metavar="N",
        help="context: rounds of iterative scaling (2)",
    )
    learn.add_argument(
        "--layouts",
        type=count_at_least(1),
        default=40,
        metavar="N",
        help="context: scenes laid out per round (40)",
    )

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
            epilog=EXAMPLES["plans"],
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
        type=count_at_least(1),
        default=10,
        metavar="N",
        help="variants to make (10)",
    )
    vary_command.add_argument("--seed", type=seed_value, default=0, help="random seed (0)")
    vary_command.add_argument(
        "-o", "--output", required=True, metavar="DIR", help="output directory"
    )
    vary_command.add_argument(
        "--operations",
        type=count_at_least(1),
        default=3,
        metavar="K",
        help="at most K operations per variant (3)",
    )
    vary_command.add_argument(
        "--no-render", dest="render", action="store_false", help="skip the preview images"
    )
    view_options(vary_command, "640x480")
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
        "--room", metavar="WxD|CORNERS", help="room size (5x4) or corners x,z x,z ..."
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
    complete.add_argument("--seed", type=seed_value, default=0, help="layout seed (0)")
    complete.add_argument("-o", "--output", required=True, metavar="DIR", help="output directory")
    style_options(complete)
    complete.add_argument(
        "--no-render", dest="render", action="store_false", help="skip the preview images"
    )
    view_options(complete, "640x480")

    command("schema", "print the scene.json JSON Schema", run_schema)
    listing = command(
        "list", "list the shipped rule sets and their object types, or the shapes", run_list
    )
    listing.add_argument(
        "--shapes",
        action="store_true",
        help="list the procedural shapes and the side each one faces instead",
    )
    return parser


def main(argv: list[str] | None = None) -> int:
    """Run the command line; return the exit code (the console script exits with it)."""
    debug = "--debug" in (sys.argv[1:] if argv is None else argv)
    args = None
    try:
        args = build_parser().parse_args(argv)
        return args.handler(args)
    except ScenewrightError as error:
        if debug:
            traceback.print_exc()
        located = getattr(error, "diagnostics", None)
        print(str(error) if located else f"{PROG}: error: {error}", file=sys.stderr)
        return error.exit_code
    except KeyboardInterrupt:
        words = sys.argv[1:] if argv is None else argv
        command = (
            args.command
            if args is not None
            else next((w for w in words if not w.startswith("-")), None)
        )
        resumes = " (rerunning a dataset command resumes it)" if command == "dataset" else ""
        print(f"{PROG}: interrupted{resumes}", file=sys.stderr)
        return 130
    except BrokenPipeError:
        # The reader stopped early (``scenewright list --shapes | head``): nothing is
        # wrong. Point stdout at /dev/null so Python's flush at exit cannot fail again.
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return 0
    except MemoryError as error:
        if debug:
            traceback.print_exc()
        print(
            f"{PROG}: error: out of memory while {activity(error)} (docs/limits.md lists the bounds on "
            "input; this machine has less memory than the input needs)",
            file=sys.stderr,
        )
        return 1
    except OSError as error:  # the system refused something (a device, a file): not a bug
        if debug:
            traceback.print_exc()
        where = f"{error.filename}: " if error.filename is not None else ""
        print(f"{PROG}: error: {where}{error.strerror or error}", file=sys.stderr)
        return 1
    except Exception as error:  # a bug, not the user's fault: say so in one line
        if debug:
            traceback.print_exc()
        print(
            f"{PROG}: error: {type(error).__name__}: {error} (rerun with --debug for the traceback)",
            file=sys.stderr,
        )
        return 1


#: What the code of each module does, to say in which stage memory ran out (the
#: innermost module of the traceback that is listed here, by its longest prefix).
ACTIVITIES = {
    "scenewright.generator": "reading the rules",
    "scenewright.generator.expand": "expanding the grammar",
    "scenewright.generator.layout": "laying the scene out",
    "scenewright.describer": "describing the scene",
    "scenewright.learning": "learning from the examples",
    "scenewright.render": "building meshes",
    "scenewright.render.offscreen": "rendering",
    "scenewright.render.plan": "drawing the plan",
    "scenewright.schema_check": "reading the scene.json",
    "scenewright.dataset": "making the dataset",
    "scenewright.completion": "reading the plans",
    "scenewright.completion.model": "building the plan model",
    "scenewright.completion.complete": "completing the room",
}


def activity(error: BaseException) -> str:
    """What the program was doing where ``error`` was raised, in words."""
    doing = "running"
    trace = error.__traceback__
    while trace is not None:
        module = trace.tb_frame.f_globals.get("__name__", "")
        known = [
            prefix for prefix in ACTIVITIES if module == prefix or module.startswith(prefix + ".")
        ]
        if known:
            doing = ACTIVITIES[max(known, key=len)]
        trace = trace.tb_next
    return doing


if __name__ == "__main__":
    sys.exit(main())
