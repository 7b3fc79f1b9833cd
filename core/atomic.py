"""Outputs that appear whole or not at all: one file, or a directory of files together.

``write_atomic`` / ``atomic_stream`` write one file under a temporary name beside it
and ``os.replace`` it into place, so a reader (or a run restarted after being killed)
sees the old file or the complete new one, never a torn one.

``staged_outputs`` publishes a directory of outputs as one: the new directory is made
beside the old one and swapped in with a single rename (Linux ``renameat2`` with
``RENAME_EXCHANGE``; a plain rename when there is no old one), so whenever the process
stops, even by ``kill -9``, the directory holds the old set of files or the new set,
never a mixture. Files in it that the run does not write are kept (hard-linked into the
new directory); a folder or a device in it is refused, as is the current directory,
since the directory is replaced as a whole. Where the filesystem cannot exchange two
names (NFS), the old directory is renamed aside first and the new one renamed in; a
kill between the two leaves the old one aside, and the next run puts it back.

Temporary names are hidden, end in ``.partial`` and carry the id of the process that
made them (``.NAME.PID-XXXXXXXX.partial``). ``staged_outputs`` first removes the
partials beside and inside its directory whose process is no longer running;
``remove_partials`` removes every partial under a directory (a dataset directory, which
one run owns).

``staged_files`` publishes files in different places (a rules file, its context, a
report) as a set: each is written beside its target under a partial name, and only when
every one is written are they renamed into place, one after another; when a rename (or
a check the caller runs after them) fails, the files already replaced are put back.
``scratch_directory`` is a private working folder (in the temporary folder) that is
removed on every exit; one a killed run left is removed by the next. A write that fails (a full disk, a read-only folder) raises
``OutputError`` naming the path (``writing`` names it for a library's writes). Files are not fsynced: this guards against a killed
process, not against losing power.
"""

from __future__ import annotations

import ctypes
import errno
import functools
import json
import os
import re
import shutil
import stat
import sys
import tempfile
from collections.abc import Collection, Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import IO

from scenewright.core.errors import InputError

PARTIAL_SUFFIX = ".partial"
#: ``.NAME.PID-RANDOM.partial``: what a process of id PID is making in place of NAME.
_PARTIAL_NAME = re.compile(r"^\.(?P<name>.+)\.(?P<pid>\d+)-(?P<tag>[^.]*)\.partial$")
#: The tag of an old directory renamed aside where names cannot be exchanged.
_ASIDE = "aside"
#: The name in ``.NAME.PID-journal.partial``: the renames a process's staged set is making.
_JOURNAL = "staged-set"
_AT_FDCWD = -100
_RENAME_EXCHANGE = 2


class OutputError(InputError):
    """An output that cannot be written (a full disk, a read-only or unsuitable folder):
    exit code 2. ``path`` is the file or directory (``directory``: written into), ``reason`` why."""

    def __init__(self, path: str | os.PathLike[str], reason: str, *, directory: bool = False):
        self.path, self.reason = os.fspath(path), reason
        super().__init__(f"cannot write {'to ' * directory}{self.path}: {reason}")


def write_atomic(path: str | os.PathLike[str], data: bytes | str) -> Path:
    """Write ``data`` (text is UTF-8 encoded) to ``path`` atomically; return the path."""
    with atomic_stream(path, binary=True) as stream:
        stream.write(data.encode("utf-8") if isinstance(data, str) else data)
    return Path(path)


@contextmanager
def atomic_stream(path: str | os.PathLike[str], *, binary: bool = False) -> Iterator[IO]:
    """A file to write ``path`` through, piece by piece; it replaces ``path`` only when the
    block ends without an error (text mode is UTF-8). A write that fails raises
    ``OutputError`` naming ``path``."""
    target = Path(path)
    temporary = None
    try:
        handle, temporary = tempfile.mkstemp(
            prefix=_partial_prefix(target.name), suffix=PARTIAL_SUFFIX, dir=target.parent
        )
        # mkstemp makes the file private (0600); give it the mode open() would have.
        os.chmod(temporary, 0o666 & ~_UMASK)
        with (
            os.fdopen(handle, "wb")
            if binary
            else os.fdopen(handle, "w", encoding="utf-8") as stream
        ):
            yield stream
        os.replace(temporary, target)
    except OSError as error:
        if temporary is None:  # the temporary file could not be made
            raise OutputError(target, error.strerror or str(error)) from error
        Path(temporary).unlink(missing_ok=True)
        if error.filename not in (None, temporary):
            raise  # not the writing of this file: some other file the block used
        raise OutputError(target, error.strerror or str(error)) from error
    except BaseException:
        if temporary is not None:
            Path(temporary).unlink(missing_ok=True)
        raise


@contextmanager
def writing(path: str | os.PathLike[str]) -> Iterator[None]:
    """A block that writes ``path`` through a library (matplotlib, PIL): a failed write
    there names no file, so it is raised as ``OutputError`` naming ``path``."""
    try:
        yield
    except OSError as error:
        if error.filename is not None:
            raise
        raise OutputError(path, error.strerror or str(error)) from error


def _read_umask() -> int:
    mask = os.umask(0)  # the only way to read it is to set it: do so once, at import
    os.umask(mask)
    return mask


_UMASK = _read_umask()


def remove_partials(directory: str | os.PathLike[str]) -> int:
    """Delete every partial under ``directory`` (temporary files, scratch directories):
    for a directory one run owns, which it clears when it starts."""
    leftovers = sorted(Path(directory).rglob(f".*{PARTIAL_SUFFIX}"))
    for leftover in leftovers:
        _remove(leftover)
    return len(leftovers)


def check_output_directory(directory: str | os.PathLike[str], replaces: Collection[str]) -> Path:
    """The real path of ``directory`` if ``staged_outputs`` may replace it, else
    ``OutputError`` saying why: it is a file, a mount point or the current directory
    (or holds it), or it holds a folder or a device among the files it keeps."""
    final = Path(directory).resolve()
    here = Path.cwd().resolve()
    if final == here or final in here.parents:
        reason = (
            "it is (or holds) the current directory, and the output replaces its directory as a whole; "
            "give the output a folder of its own"
        )
        raise OutputError(directory, reason, directory=True)
    if not final.exists():
        return final
    if not final.is_dir():
        raise OutputError(directory, "it is a file, not a directory", directory=True)
    if os.path.ismount(final):
        reason = (
            "it is a mount point, and the output replaces its directory as a whole by swapping in a new "
            "one beside it; write into a folder inside it"
        )
        raise OutputError(directory, reason, directory=True)
    foreign = sorted(entry.name for entry in _kept(final, replaces) if not _linkable(entry))
    if foreign:
        listed = ", ".join(foreign[:3]) + (
            f" and {len(foreign) - 3} more" if len(foreign) > 3 else ""
        )
        reason = (
            f"it holds {listed}, which the output does not replace and which a new directory cannot take "
            "along (not a plain file); give the output a folder of its own"
        )
        raise OutputError(directory, reason, directory=True)
    return final


@contextmanager
def staged_outputs(directory: str | os.PathLike[str], replaces: Collection[str]) -> Iterator[Path]:
    """A new directory to write the outputs into, which replaces ``directory`` as one.

    ``replaces``: the names of the outputs. When the block succeeds, the files of
    ``directory`` not among them are linked into the new directory and the two are
    swapped; the old one is then deleted. Of the outputs, those the block did not
    write are gone afterwards (a stale preview, say). ``directory`` is made at once if
    it does not exist; when the block raises, it is left as it was (and so made empty).
    ``check_output_directory``'s refusals apply.
    """
    final = check_output_directory(directory, replaces)
    try:
        final.parent.mkdir(parents=True, exist_ok=True)
        remove_dead_partials(final)  # first: it may put back the directory a killed run set aside
        final.mkdir(exist_ok=True)
        stage = Path(
            tempfile.mkdtemp(
                prefix=_partial_prefix(final.name), suffix=PARTIAL_SUFFIX, dir=final.parent
            )
        )
        os.chmod(stage, 0o777 & ~_UMASK)
    except OSError as error:
        reason = f"cannot make a folder beside it in {final.parent} ({error.strerror or error})"
        raise OutputError(directory, reason, directory=True) from error
    try:
        yield stage
        if final.exists():
            check_output_directory(directory, replaces)  # nothing unsuitable appeared meanwhile
            for entry in _kept(final, replaces):
                if not (stage / entry.name).exists():
                    _take_along(entry, stage / entry.name)
        _publish(stage, final)
    except OutputError as error:  # an output written with write_atomic: name it where it was going
        _remove(stage)
        shown = _shown_path(error.path, stage, directory)
        if shown is None:
            raise
        raise OutputError(shown, error.reason) from error
    except OSError as error:
        _remove(stage)
        if error.filename is not None and not _shown_path(error.filename, stage, directory):
            raise  # not a write of an output: some other file the block used
        raise OutputError(
            _shown_path(error.filename, stage, directory) or directory, error.strerror or str(error)
        ) from error
    except BaseException:
        _remove(stage)
        raise


class StagedFiles:
    """The files of one ``staged_files`` block: ``write`` stages one, ``commit`` puts
    every staged one in place (see ``staged_files``)."""

    def __init__(self) -> None:
        self._pending: dict[Path, Path] = {}  # target -> its staged partial
        self._replaced: list[tuple[Path, Path | None]] = []  # target -> its old copy, or None
        self._made: list[Path] = []  # folders made for targets, deepest last
        self._journal: Path | None = None  # the renames under way (``commit``)

    def write(self, path: str | os.PathLike[str], data: bytes | str) -> Path:
        """Stage ``data`` (text is UTF-8) for ``path``; ``path`` is not touched yet."""
        target = Path(path)
        if target.is_dir():
            raise OutputError(target, "it is a directory")
        missing = [p for p in (target.parent, *target.parent.parents) if not p.exists()]
        for folder in reversed(missing):
            try:
                folder.mkdir()
            except OSError as error:
                raise OutputError(folder, error.strerror or str(error), directory=True) from error
            self._made.append(folder)
        finish_killed_sets(target.parent)  # before its staged files count as dead partials
        remove_dead_partials(target)
        try:
            handle, partial = tempfile.mkstemp(
                prefix=_partial_prefix(target.name), suffix=PARTIAL_SUFFIX, dir=target.parent
            )
        except OSError as error:
            raise OutputError(target, error.strerror or str(error)) from error
        staged = Path(partial)
        previous = self._pending.pop(target, None)
        if previous is not None:
            previous.unlink(missing_ok=True)
        self._pending[target] = staged
        try:
            os.chmod(staged, 0o666 & ~_UMASK)
            with os.fdopen(handle, "wb") as stream:
                stream.write(data.encode("utf-8") if isinstance(data, str) else data)
        except OSError as error:
            raise OutputError(target, error.strerror or str(error)) from error
        return target

    def commit(self) -> None:
        """Put every staged file in place; on a failure, put back the ones replaced."""
        for target in self._pending:
            if target.is_dir():  # made meanwhile
                raise OutputError(target, "it is a directory")
        if not self._pending:
            return
        # Every file is staged whole: a run killed during the renames leaves this journal,
        # and the next staged write into its folder finishes them (``finish_killed_sets``).
        self._journal = _journal_path(next(iter(self._pending)).parent)
        write_atomic(
            self._journal,
            json.dumps([[os.fspath(s), os.fspath(t)] for t, s in self._pending.items()]),
        )
        while self._pending:
            target, staged = next(iter(self._pending.items()))
            old = None
            try:
                if os.path.lexists(target):  # kept under a second name, to put back on failure
                    old = target.parent / f"{_partial_prefix(target.name)}old{PARTIAL_SUFFIX}"
                    _remove(old)
                    try:
                        os.link(target, old, follow_symlinks=False)
                    except OSError:  # a filesystem without hard links: a copy will do
                        shutil.copy2(target, old, follow_symlinks=False)
                os.replace(staged, target)
            except OSError as error:
                if old is not None:
                    old.unlink(missing_ok=True)
                raise OutputError(target, error.strerror or str(error)) from error
            del self._pending[target]
            self._replaced.append((target, old))
        self._journal.unlink(missing_ok=True)

    def roll_back(self) -> None:
        """Remove what is staged, put back the files replaced, remove the folders made."""
        if self._journal is not None:
            self._journal.unlink(missing_ok=True)
        for staged in self._pending.values():
            staged.unlink(missing_ok=True)
        self._pending.clear()
        for target, old in reversed(self._replaced):
            try:
                if old is not None:
                    os.replace(old, target)
                else:
                    target.unlink(missing_ok=True)
            except OSError:
                pass  # best effort: the error that led here is the one to report
        self._replaced.clear()
        for folder in reversed(self._made):
            try:
                folder.rmdir()
            except OSError:
                pass  # something else was put there meanwhile: keep it
        self._made.clear()

    def finish(self) -> None:
        """Drop the old copies of the replaced files."""
        for _, old in self._replaced:
            if old is not None:
                old.unlink(missing_ok=True)
        self._replaced.clear()


@contextmanager
def staged_files() -> Iterator[StagedFiles]:
    """A set of files written together or not at all: write each with the block's
    ``write(path, data)``; when the block ends without an error they are put in place
    (``commit``, which the block may also call itself, to check the files in place);
    when the block or a rename fails, every file is as it was before the block. A kill
    before the renames leaves partials beside the targets, which the next write of the
    same names removes: the old set stays. A kill during the renames leaves a journal of
    them, and the next staged write into the first file's folder finishes them: the new
    set is put in place whole."""
    staged = StagedFiles()
    try:
        yield staged
        staged.commit()
    except BaseException:
        staged.roll_back()
        raise
    staged.finish()


@contextmanager
def scratch_directory(name: str) -> Iterator[Path]:
    """A private folder in the temporary folder, removed when the block ends however it
    ends; the folders of this ``name`` that a killed process left are removed first."""
    base = Path(tempfile.gettempdir())
    for entry in base.glob(f".scenewright-{name}.*{PARTIAL_SUFFIX}"):
        match = _PARTIAL_NAME.match(entry.name)
        if match is not None and not _alive(int(match["pid"])):
            _remove(entry)
    folder = Path(
        tempfile.mkdtemp(prefix=_partial_prefix(f"scenewright-{name}"), suffix=PARTIAL_SUFFIX)
    )
    try:
        yield folder
    finally:
        _remove(folder)


def finish_killed_sets(folder: str | os.PathLike[str]) -> int:
    """Finish the renames of the staged sets whose process was killed while making them
    in ``folder`` (their journals): each file still staged goes to its target. Return how
    many were put in place."""
    count = 0
    directory = Path(folder)
    if not directory.is_dir():
        return 0
    for entry in sorted(directory.glob(f".{_JOURNAL}.*-journal{PARTIAL_SUFFIX}")):
        match = _PARTIAL_NAME.match(entry.name)
        if match is None or _alive(int(match["pid"])):
            continue
        try:
            pairs = json.loads(entry.read_text())
        except (OSError, ValueError):
            pairs = []  # cut short while written: no rename had begun
        for staged, target in pairs:
            if os.path.lexists(staged):
                try:
                    os.replace(staged, target)
                    count += 1
                except OSError:
                    pass  # left as a partial, which the next write removes
            remove_dead_partials(target)  # the old copies kept to put back on a failure
        entry.unlink(missing_ok=True)
    return count


def _journal_path(folder: Path) -> Path:
    return folder / f".{_JOURNAL}.{os.getpid()}-journal{PARTIAL_SUFFIX}"


def remove_dead_partials(path: str | os.PathLike[str]) -> int:
    """Remove the partials of ``path`` (beside it) and inside it (if a directory) whose
    process is no longer running; put back a directory a killed run had renamed aside.
    Return how many were removed or put back."""
    final = Path(path)
    count = 0
    for folder, wanted in ((final.parent, final.name), (final, None)):
        if not folder.is_dir():
            continue
        # Only the partials are sorted: the folder beside an output may hold thousands of
        # other entries (a shared /tmp).
        for entry in sorted(e for e in folder.iterdir() if _PARTIAL_NAME.match(e.name)):
            match = _PARTIAL_NAME.match(entry.name)
            assert match is not None
            if (wanted is not None and match["name"] != wanted) or _alive(int(match["pid"])):
                continue
            if match["tag"] == _ASIDE and not os.path.lexists(final):
                os.rename(
                    entry, final
                )  # killed between the two renames: the old directory comes back
            else:
                _remove(entry)
            count += 1
    return count


def _publish(stage: Path, final: Path) -> None:
    """Put ``stage`` where ``final`` is, in one step where the filesystem allows."""
    try:
        os.rename(stage, final)  # there was no directory, or an empty one: replaced at once
        return
    except OSError as error:
        if error.errno not in (errno.ENOTEMPTY, errno.EEXIST):
            raise
    if _exchange(stage, final):
        _remove(stage)  # it now holds the old directory
        return
    aside = final.parent / f"{_partial_prefix(final.name)}{_ASIDE}{PARTIAL_SUFFIX}"
    _remove(aside)  # left by an earlier process that had this one's id
    os.rename(final, aside)
    os.rename(stage, final)
    _remove(aside)


def _exchange(first: Path, second: Path) -> bool:
    """Swap two paths in one step (``renameat2(..., RENAME_EXCHANGE)``); False where the
    system or the filesystem cannot."""
    renameat2 = _renameat2()
    if renameat2 is None:
        return False
    if (
        renameat2(_AT_FDCWD, os.fsencode(first), _AT_FDCWD, os.fsencode(second), _RENAME_EXCHANGE)
        == 0
    ):
        return True
    code = ctypes.get_errno()
    if code in (errno.EINVAL, errno.ENOSYS, errno.EOPNOTSUPP):
        return False
    raise OSError(code, os.strerror(code), str(second))


@functools.cache
def _renameat2():
    """libc's ``renameat2`` (Linux, glibc 2.28 or later), or None."""
    if not sys.platform.startswith("linux"):
        return None
    try:
        function = ctypes.CDLL(None, use_errno=True).renameat2
    except (OSError, AttributeError):
        return None
    function.argtypes = (
        ctypes.c_int,
        ctypes.c_char_p,
        ctypes.c_int,
        ctypes.c_char_p,
        ctypes.c_uint,
    )
    function.restype = ctypes.c_int
    return function


def _kept(final: Path, replaces: Collection[str]) -> list[os.DirEntry]:
    """The entries of ``final`` a new directory must take along: not outputs, not partials."""
    with os.scandir(final) as entries:
        return [
            e for e in entries if e.name not in replaces and not e.name.endswith(PARTIAL_SUFFIX)
        ]


def _linkable(entry: os.DirEntry) -> bool:
    """A regular file or a symbolic link, which a hard link can take along."""
    mode = entry.stat(follow_symlinks=False).st_mode
    return stat.S_ISREG(mode) or stat.S_ISLNK(mode)


def _take_along(entry: os.DirEntry, target: Path) -> None:
    try:
        os.link(entry.path, target, follow_symlinks=False)
    except OSError:  # a filesystem without hard links, or protected ones: a copy will do
        shutil.copy2(entry.path, target, follow_symlinks=False)


def _alive(pid: int) -> bool:
    if pid == os.getpid():
        return True
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True  # someone else's process
    except (OverflowError, ValueError):
        return False  # not a process id at all
    return True


def _partial_prefix(name: str) -> str:
    return f".{name}.{os.getpid()}-"


def _remove(path: Path) -> None:
    if path.is_dir() and not path.is_symlink():
        shutil.rmtree(path, ignore_errors=True)
    else:
        path.unlink(missing_ok=True)


def _shown_path(written, stage: Path, directory: str | os.PathLike[str]) -> str | None:
    """Where a write into ``stage`` was going, as the user named it (``out/scene.glb``),
    or None when ``written`` lies outside ``stage``."""
    if written is None:
        return None
    path = Path(os.fsdecode(written))
    if path == stage or path.is_relative_to(stage):
        return os.path.join(os.fspath(directory), os.fspath(path.relative_to(stage)))
    return None
