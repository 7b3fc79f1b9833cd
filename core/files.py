"""Reading a file that a user's input names: a regular file only, and a bounded one.

``read_regular_file`` is how rules files, description templates and mesh files are
read. It opens the file without blocking (a named pipe cannot stall it), checks on the
opened file that it is a regular file (not a directory, pipe or device such as
/dev/zero) of at most a given size, and reads no more than that. A file that fails a
check raises ``UnusableFile``, whose text completes the sentence "file 'F' ...".

``load_json`` is how every JSON file a user hands in is parsed: NaN and Infinity are
refused, and so is a document nested more than ``MAX_JSON_DEPTH`` deep (the parser's
own limit is Python's stack, and every reader after it walks the document), each as a
``ValueError`` whose text says what is wrong.
"""

from __future__ import annotations

import json
import math
import os
import stat
from typing import Any

from scenewright.core.limits import MAX_JSON_DEPTH


class UnusableFile(OSError):
    """A file that is not a regular file or is too large; the text says which ("is not a
    regular file"). An ``OSError``, like the errors of opening a file that is missing
    or unreadable, which ``read_regular_file`` lets through unchanged."""


def read_regular_file(path: str | os.PathLike[str], limit: int, holder: str) -> bytes:
    """The bytes of ``path``, which must be a regular file of at most ``limit`` bytes.

    ``holder`` says what the file is, for the message about its size ("a rules file":
    "is 5 MiB, more than the 4 MiB a rules file may hold"). The checks are made on the
    opened file, so swapping the name for another file after a check changes nothing.
    Raises ``UnusableFile``, or the ``OSError`` of opening or reading the file.
    """
    descriptor = os.open(path, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0))
    try:
        status = os.fstat(descriptor)
        if stat.S_ISDIR(status.st_mode):
            raise UnusableFile("is a directory, not a file")
        if not stat.S_ISREG(status.st_mode):
            raise UnusableFile("is not a regular file")
        if status.st_size > limit:
            raise UnusableFile(
                f"is {_mebibytes(status.st_size)}, more than the {_mebibytes(limit)} {holder} may hold"
            )
        with os.fdopen(descriptor, "rb", closefd=False) as stream:
            data = stream.read(limit + 1)
    finally:
        os.close(descriptor)
    if len(data) > limit:  # it grew after its size was read
        raise UnusableFile(f"is more than the {_mebibytes(limit)} {holder} may hold")
    return data


def _mebibytes(count: int) -> str:
    """``count`` bytes in MiB, rounded up to a tenth, so a file just over a limit reads as over it."""
    return f"{math.ceil(count * 10 / 2**20) / 10:g} MiB"


class JSONTooDeep(ValueError):
    """A JSON document nested more than ``MAX_JSON_DEPTH`` deep."""

    def __init__(self) -> None:
        super().__init__(f"nested deeper than {MAX_JSON_DEPTH} levels")


def load_json(text: str | bytes, **options: Any) -> Any:
    """The JSON document of ``text``; ``json.JSONDecodeError`` for text that is not JSON,
    ``JSONTooDeep`` for a document nested too deep, ``ValueError`` for NaN or Infinity
    (unless ``options`` give a ``parse_constant`` of their own)."""
    options.setdefault("parse_constant", _refuse_constant)
    try:
        document = json.loads(text, **options)
    except RecursionError:
        raise JSONTooDeep() from None
    pending = [(document, 0)]  # depth-first without recursion
    while pending:
        value, depth = pending.pop()
        if isinstance(value, (dict, list)):
            if depth >= MAX_JSON_DEPTH:  # the container of nesting level MAX_JSON_DEPTH + 1
                raise JSONTooDeep()
            pending.extend(
                (item, depth + 1) for item in (value.values() if isinstance(value, dict) else value)
            )
    return document


def _refuse_constant(constant: str) -> Any:
    raise ValueError(f"{constant} is not a finite number")
