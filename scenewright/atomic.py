"""Files that appear whole or not at all: write to a temporary name, then rename.

``os.replace`` within one directory is atomic on POSIX, so a reader (or a run that is
restarted after being killed) sees either the old file or the complete new one, never
a torn one. Temporary files are hidden and end in ``.partial``; ``remove_partials``
clears what a killed run left behind. Files are not fsynced: this guards against a
killed process, not against losing power.
"""

from __future__ import annotations

import os
import shutil
import tempfile
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import IO

PARTIAL_SUFFIX = ".partial"


def write_atomic(path: str | os.PathLike[str], data: bytes | str) -> Path:
    """Write ``data`` (text is UTF-8 encoded) to ``path`` atomically; return the path."""
    with atomic_stream(path, binary=True) as stream:
        stream.write(data.encode("utf-8") if isinstance(data, str) else data)
    return Path(path)


@contextmanager
def atomic_stream(path: str | os.PathLike[str], *, binary: bool = False) -> Iterator[IO]:
    """A file to write ``path`` through, piece by piece; it replaces ``path`` only when the
    block ends without an error (text mode is UTF-8)."""
    target = Path(path)
    handle, temporary = tempfile.mkstemp(prefix=f".{target.name}.", suffix=PARTIAL_SUFFIX, dir=target.parent)
    # mkstemp makes the file private (0600); give it the mode open() would have.
    os.chmod(temporary, 0o666 & ~_UMASK)
    try:
        with os.fdopen(handle, "wb") if binary else os.fdopen(handle, "w", encoding="utf-8") as stream:
            yield stream
        os.replace(temporary, target)
    except BaseException:
        Path(temporary).unlink(missing_ok=True)
        raise


def _read_umask() -> int:
    mask = os.umask(0)  # the only way to read it is to set it: do so once, at import
    os.umask(mask)
    return mask


_UMASK = _read_umask()


def remove_partials(directory: str | os.PathLike[str]) -> int:
    """Delete what a killed writer left under ``directory`` (temp files, scratch dirs)."""
    leftovers = sorted(Path(directory).rglob(f".*{PARTIAL_SUFFIX}"))
    for leftover in leftovers:
        if leftover.is_dir():
            shutil.rmtree(leftover, ignore_errors=True)
        else:
            leftover.unlink(missing_ok=True)
    return len(leftovers)


@contextmanager
def staged_outputs(directory: str | os.PathLike[str]) -> Iterator[Path]:
    """A hidden scratch directory inside ``directory`` whose files are published together.

    Write every output into the yielded directory. When the block succeeds each file is
    moved into ``directory`` with ``os.replace``; when it raises, the scratch directory
    is deleted and ``directory`` is left as it was.
    """
    final = Path(directory)
    scratch = Path(tempfile.mkdtemp(prefix=".scenewright-", suffix=PARTIAL_SUFFIX, dir=final))
    try:
        yield scratch
        for staged in sorted(scratch.iterdir()):
            os.replace(staged, final / staged.name)
    finally:
        shutil.rmtree(scratch, ignore_errors=True)
