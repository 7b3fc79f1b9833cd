"""The ``scenewright`` command: generate scenes and datasets, check rules, inspect scenes.

Each subcommand is a small function ``run_<name>(args) -> exit code``: it parses, makes
one call into the library (``scenewright.api``, ``scenewright.scene_folder``, the
stages) and reports. The commands come in families, each module with its commands'
parsers and help: ``scene_commands`` (generate, layout, describe, render, export),
``dataset_commands`` (dataset), ``learning_commands`` (fit, relations, learn),
``example_commands`` (validate, match, augment, vary), ``evaluation_commands``
(evaluate), ``completion_commands``
(complete, plans), ``info_commands`` (expand, schema, list); ``options`` holds what
their parsers share, ``common`` what they share at run time. Parsing and error
reporting live here once.

Exit codes: 0 done; 1 generation failed (e.g. a layout that could not satisfy every
relation: its files are still written, marked ``ok: false``); 2 bad input (options,
missing or unreadable files, an output directory that cannot be written, bad rules, a
bad scene.json, an output that cannot be written). Errors print as one line
``scenewright: error: ...`` (a rules error as its located excerpt) and no traceback
unless ``--debug`` is given; running out of memory says so, and in which stage.
"""

from __future__ import annotations

import argparse
import atexit
import errno
import os
import sys
import threading
import traceback

from scenewright.core import VERSION
from scenewright.core.collector import collect_less
from scenewright.core.errors import ScenewrightError

from . import (
    completion_commands,
    compose_commands,
    dataset_commands,
    evaluation_commands,
    example_commands,
    info_commands,
    learning_commands,
    scene_commands,
)
from .common import PROG
from .options import CommandLineParser, common_options

#: The command families, in the order ``--help`` lists their commands.
FAMILIES = (
    scene_commands,
    dataset_commands,
    example_commands,
    evaluation_commands,
    info_commands,
    learning_commands,
    completion_commands,
    compose_commands,
)


def build_parser() -> CommandLineParser:
    parser = CommandLineParser(
        prog=PROG,
        description="Procedural 3D scenes from a graph grammar, laid out by MCMC and described in English.",
        epilog="examples:\n  scenewright generate village --seed 7 -o out/\n  scenewright list\n"
        "  scenewright COMMAND --help",
        formatter_class=argparse.RawDescriptionHelpFormatter,
        parents=[common_options(suppress=False)],
    )
    parser.add_argument("--version", action="version", version=f"{PROG} {VERSION}")
    commands = parser.add_subparsers(dest="command", metavar="COMMAND", required=True)

    for family in FAMILIES:
        family.add_commands(commands)
    return parser


def run() -> None:
    """The ``scenewright`` console command: ``main`` on the process's arguments, then
    ``exit_now`` with its exit code."""
    set_process_defaults()
    collect_less()
    try:
        code = main()
    except SystemExit as done:  # argparse's --help, --version and usage errors
        if not isinstance(done.code, int | None):
            raise
        code = done.code or 0
    exit_now(code)


def set_process_defaults() -> None:
    """What the console command sets in its environment before anything imports numpy.

    OpenBLAS (numpy's and scipy's) runs on one thread unless the user set
    ``OPENBLAS_NUM_THREADS``: the matrices here are small (frames, footprints, a few
    hundred points), so a pool of threads speeds nothing, yet starting the two pools
    costs a cold ``generate`` about a seventh of its CPU time; a dataset uses every core
    by its worker processes, which inherit the setting."""
    os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")


def exit_now(code: int) -> None:
    """End the process with ``code`` once what it registered to run at exit has run
    (multiprocessing's children, temporary folders, logging) and the standard streams
    are flushed, skipping the interpreter's teardown: freeing every object and module of
    a run that imported numpy, scipy and OpenGL is about a tenth of a cold ``generate``'s
    CPU time. Every output file is closed by then (they are written whole, then renamed).
    With a thread still running, or no ``atexit._run_exitfuncs`` (not CPython), the
    process exits the ordinary way, which waits for the thread."""
    run_exit_functions = getattr(atexit, "_run_exitfuncs", None)
    if threading.active_count() > 1 or run_exit_functions is None:
        sys.exit(code)
    run_exit_functions()
    for stream in (sys.stdout, sys.stderr):
        try:
            stream.flush()
        except (OSError, ValueError):  # a reader gone (a broken pipe), or a closed stream
            pass
    os._exit(code)


def main(argv: list[str] | None = None) -> int:
    """Run the command line; return the exit code (the console script exits with it).
    An error line never repeats a long argument in full (``shortened``)."""
    words = list(sys.argv[1:] if argv is None else argv)
    stderr = sys.stderr
    sys.stderr = _Shortening(stderr, words)
    try:
        return _main(argv)
    finally:
        sys.stderr = stderr


#: Arguments longer than this are shown shortened in error lines: far longer than the
#: paths users name (the location of an error is kept whole), short of a pasted file.
LONG_ARGUMENT = 1000


def shortened(text: str, words: list[str]) -> str:
    """``text`` with each argument of ``words`` longer than ``LONG_ARGUMENT`` characters
    shown as its first 60 and how long it is, so the cause of an error stays readable."""
    for word in sorted({w for w in words if len(w) > LONG_ARGUMENT}, key=len, reverse=True):
        for shown in (repr(word), ascii(word), word):
            if shown in text:
                text = text.replace(shown, f"{shown[:60]}... ({len(word)} characters)")
    return text


class _Shortening:
    """stderr, with the long arguments of the command line shortened in what is written."""

    def __init__(self, stream, words: list[str]):
        self._stream, self._words = stream, words

    def write(self, text: str) -> int:
        self._stream.write(shortened(text, self._words))
        return len(text)

    def __getattr__(self, name: str):
        return getattr(self._stream, name)


def _main(argv: list[str] | None) -> int:
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
        return 2 if error.errno == errno.ENAMETOOLONG else 1  # a name the user gave
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
    "scenewright.render.plan_image": "drawing the plan",
    "scenewright.core.schema_check": "reading the scene.json",
    "scenewright.dataset": "making the dataset",
    "scenewright.completion": "reading the plans",
    "scenewright.completion.model_builder": "building the plan model",
    "scenewright.completion.complete": "completing the room",
    "scenewright.completion.request": "completing the room",
    "scenewright.completion.contents": "completing the room",
    "scenewright.completion.furnishing": "completing the room",
    "scenewright.completion.starting_poses": "completing the room",
    "scenewright.completion.explanation": "completing the room",
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
