"""What every command does at run time: print progress and summaries, find the output
files and folders, read scene.json files, report a written scene."""

from __future__ import annotations

import argparse
import os
import sys
from pathlib import Path

from scenewright.core.errors import InputError

PROG = "scenewright"


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
    from scenewright.core.schema_check import (
        SceneSchemaError,
        parse_scene_json,
        validate_scene_dict,
    )

    try:
        text = read_regular_file(path, MAX_SCENE_JSON_BYTES, "a scene.json").decode("utf-8")
        if not text.strip():
            raise SceneFileError(path, "the file is empty (or only blank): there is no JSON in it")
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


def emit(args: argparse.Namespace, text: str) -> int:
    """Write ``text`` to ``--output`` (atomically) or, without one, to stdout; exit code 0."""
    from scenewright.core.atomic import write_atomic

    if args.output:
        write_atomic(args.output, text)
        say(args, f"wrote {args.output}")
    else:
        sys.stdout.write(text)
    return 0


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


def report_scene(args: argparse.Namespace, written) -> int:
    """Say what ``scene_folder.write_scene`` wrote and the layout's verdict: exit 0 when
    ok, 1 when not (the files are kept)."""
    from scenewright.api import summary_line

    scene = written.scene
    say(args, f"wrote {args.output.rstrip('/') or '/'}/: {', '.join(written.files)}")
    say(args, summary_line(scene))
    if scene.layout.ok:
        return 0
    problems = "; ".join(scene.layout.problems) or "see layout in scene.json"
    print(
        f"{PROG}: error: the layout did not satisfy every constraint (files kept): {problems}",
        file=sys.stderr,
    )
    return 1
