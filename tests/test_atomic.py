"""Outputs appear whole or not at all: one file (``write_atomic``) and the set of files
``generate`` writes (``staged_outputs``), even when the process is killed with SIGKILL;
what a killed run leaves behind is cleared by the next; a write that fails (a full
disk) names the path and exits cleanly.
"""

from __future__ import annotations

import errno
import filecmp
import json
import os
import random
import select
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from scenewright.cli import main
from scenewright.core import atomic
from scenewright.core.atomic import (
    OutputError,
    check_output_directory,
    remove_dead_partials,
    staged_outputs,
    write_atomic,
)

OUTPUTS = ("a.txt", "b.txt", "c.txt")


def dead_pid() -> int:
    """The id of a process that has finished (and been waited for)."""
    process = subprocess.Popen([sys.executable, "-c", "pass"])
    process.wait()
    return process.pid


def publish(directory: Path, files: dict[str, str]) -> None:
    with staged_outputs(directory, OUTPUTS) as stage:
        for name, text in files.items():
            (stage / name).write_text(text)


def listing(directory: Path) -> dict[str, str]:
    return {p.name: p.read_text() for p in sorted(directory.iterdir())}


# -- staged_outputs --------------------------------------------------------------------


def test_a_directory_of_outputs_is_replaced_as_a_whole(tmp_path):
    out = tmp_path / "out"
    publish(out, {"a.txt": "1", "b.txt": "1", "c.txt": "1"})
    (out / "notes.md").write_text("mine")  # not an output: kept
    os.symlink("notes.md", out / "link.md")
    publish(out, {"a.txt": "2", "b.txt": "2"})  # c.txt is stale now: gone
    assert listing(out) == {"a.txt": "2", "b.txt": "2", "link.md": "mine", "notes.md": "mine"}
    assert os.readlink(out / "link.md") == "notes.md"
    assert [p.name for p in tmp_path.iterdir()] == ["out"]  # no partial beside it


def test_a_failing_block_leaves_the_directory_as_it_was(tmp_path):
    out = tmp_path / "out"
    publish(out, {"a.txt": "1"})
    with pytest.raises(RuntimeError):
        with staged_outputs(out, OUTPUTS) as stage:
            (stage / "a.txt").write_text("2")
            raise RuntimeError("a stage failed")
    assert listing(out) == {"a.txt": "1"}
    assert [p.name for p in tmp_path.iterdir()] == ["out"]


def test_without_rename_exchange_the_old_directory_is_set_aside_then_removed(tmp_path, monkeypatch):
    monkeypatch.setattr(atomic, "_exchange", lambda first, second: False)  # NFS, or no renameat2
    out = tmp_path / "out"
    publish(out, {"a.txt": "1"})
    publish(out, {"a.txt": "2"})
    assert listing(out) == {"a.txt": "2"}
    assert [p.name for p in tmp_path.iterdir()] == ["out"]


def test_partials_of_dead_runs_are_removed_and_live_ones_kept(tmp_path):
    out = tmp_path / "out"
    publish(out, {"a.txt": "1"})
    dead, alive = dead_pid(), os.getppid()
    leftovers = [
        tmp_path / f".out.{dead}-abcdefgh.partial",  # a stage of a killed run
        out / f".a.txt.{dead}-abcdefgh.partial",  # a file a killed write_atomic left
    ]
    leftovers[0].mkdir()
    (leftovers[0] / "a.txt").write_text("half")
    leftovers[1].write_text("half")
    live = tmp_path / f".out.{alive}-abcdefgh.partial"  # another run, still going
    live.mkdir()
    other = tmp_path / f".elsewhere.{dead}-abcdefgh.partial"  # not this directory's
    other.mkdir()
    assert remove_dead_partials(out) == 2
    assert not any(path.exists() for path in leftovers)
    assert live.exists() and other.exists()


def test_a_directory_a_killed_run_had_set_aside_comes_back(tmp_path):
    aside = tmp_path / f".out.{dead_pid()}-aside.partial"
    aside.mkdir()
    (aside / "a.txt").write_text("old")
    (aside / "notes.md").write_text("mine")
    publish(tmp_path / "out", {"b.txt": "new"})
    # Put back, then replaced as usual: its own file kept, its stale output gone.
    assert listing(tmp_path / "out") == {"b.txt": "new", "notes.md": "mine"}
    assert [p.name for p in tmp_path.iterdir()] == ["out"]


@pytest.mark.parametrize(
    "make, words",
    [
        (lambda out: (out / "sub").mkdir(), "it holds sub, which the output does not replace"),
        (lambda out: os.mkfifo(out / "pipe"), "it holds pipe, which the output does not replace"),
    ],
)
def test_a_directory_holding_what_cannot_be_taken_along_is_refused(tmp_path, make, words):
    out = tmp_path / "out"
    out.mkdir()
    make(out)
    with pytest.raises(OutputError, match=words):
        check_output_directory(out, OUTPUTS)


def test_the_current_directory_is_refused(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    with pytest.raises(
        OutputError, match=r"cannot write to \.: it is \(or holds\) the current directory"
    ):
        check_output_directory(".", OUTPUTS)
    assert main(["generate", "desk", "--no-render", "-o", str(tmp_path.parent)]) == 2
    assert "it is (or holds) the current directory" in capsys.readouterr().err


# -- write failures (item 10: disk full) -------------------------------------------------


class FullDisk:
    """A file whose every write fails as on a full disk."""

    def __init__(self, descriptor: int):
        os.close(descriptor)

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        return False

    def write(self, data):
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))


def fill_the_disk(monkeypatch) -> None:
    """Make every file opened for writing through ``os.fdopen`` (``write_atomic``) a ``FullDisk``."""
    opened = os.fdopen

    def fdopen(descriptor, mode="r", *args, **kwargs):
        return FullDisk(descriptor) if "w" in mode else opened(descriptor, mode, *args, **kwargs)

    monkeypatch.setattr(os, "fdopen", fdopen)


def test_a_full_disk_in_write_atomic_names_the_file(tmp_path, monkeypatch):
    fill_the_disk(monkeypatch)
    with pytest.raises(OutputError) as caught:
        write_atomic(tmp_path / "x.glb", b"data")
    assert str(caught.value) == f"cannot write {tmp_path / 'x.glb'}: No space left on device"
    assert list(tmp_path.iterdir()) == []


def test_a_full_disk_while_generating_names_the_output_and_exits_2(tmp_path, monkeypatch, capsys):
    """Before: "scenewright: error: OSError: [Errno 28] No space left on device (rerun
    with --debug for the traceback)", exit 1, no path."""
    out = tmp_path / "out"
    assert main(["generate", "desk", "--no-render", "-o", str(out), "-q"]) == 0
    before = {p.name: p.read_bytes() for p in out.iterdir()}
    fill_the_disk(monkeypatch)  # every output but the plan is written with write_atomic
    assert main(["generate", "desk", "--seed", "2", "--no-render", "-o", str(out)]) == 2
    err = capsys.readouterr().err
    assert (
        err
        == f"scenewright: error: cannot write {out / 'description.txt'}: No space left on device\n"
    )
    assert {p.name: p.read_bytes() for p in out.iterdir()} == before
    assert [p.name for p in tmp_path.iterdir()] == ["out"]


def test_a_full_disk_under_a_library_write_names_the_file(tmp_path, monkeypatch, capsys):
    """The plan is saved by Pillow, whose failed write() names no file."""
    from PIL import Image

    def full(self, *args, **kwargs):
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))

    monkeypatch.setattr(Image.Image, "save", full)
    out = tmp_path / "out"
    assert main(["generate", "desk", "--no-render", "-o", str(out)]) == 2
    assert (
        capsys.readouterr().err
        == f"scenewright: error: cannot write {out / 'plan.png'}: No space left on device\n"
    )


def test_export_to_a_full_disk_names_the_file(tmp_path, monkeypatch, capsys):
    assert main(["generate", "desk", "--no-render", "-o", str(tmp_path / "out"), "-q"]) == 0
    fill_the_disk(monkeypatch)
    assert (
        main(["export", str(tmp_path / "out" / "scene.json"), "-o", str(tmp_path / "x.glb")]) == 2
    )
    assert (
        capsys.readouterr().err
        == f"scenewright: error: cannot write {tmp_path / 'x.glb'}: No space left on device\n"
    )


# -- generate under SIGKILL (item 7) ----------------------------------------------------

#: The server: imports what ``generate`` runs once, then, for each request (a JSON line:
#: the arguments, and whether rename-exchange is missing), forks a child that runs
#: ``main`` with every rename, link and removal slowed, so that kills land in the middle
#: of publishing too. It answers the child's pid at once; on the next line from the test
#: (sent once the test has killed the child, or to wait for it) it reaps the child and
#: answers its exit code (negative: the signal that ended it). Until then the child is
#: not reaped, so the pid the test kills cannot name another process. Forking saves each
#: run the half second a fresh interpreter spends importing.
SERVER = """
import json, os, shutil, sys, time
import scenewright.api, scenewright.generator, scenewright.render.export, scenewright.render.plan_image
import scenewright.describer, scenewright.generator.layout
from scenewright.core import atomic
from scenewright.cli import exit_now, main

def slowed(function):
    def slow(*args, **kwargs):
        time.sleep(0.01)
        result = function(*args, **kwargs)
        time.sleep(0.01)
        return result
    return slow

def child(argv, no_exchange, log):
    code = 1
    try:
        output = os.open(log, os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o644)
        os.dup2(output, 1)
        os.dup2(output, 2)
        for module, name in ((os, "replace"), (os, "rename"), (os, "link"), (shutil, "rmtree"), (atomic, "_exchange")):
            setattr(module, name, slowed(getattr(module, name)))
        if no_exchange:
            atomic._exchange = slowed(lambda first, second: False)
        code = main(argv)
        exit_now(code)  # as the console command ends
    finally:
        os._exit(code)  # never back into the server's loop

print("ready", flush=True)
while request := sys.stdin.readline():
    pid = os.fork()
    if pid == 0:
        child(**json.loads(request))
    print(pid, flush=True)
    sys.stdin.readline()
    _, status = os.waitpid(pid, 0)
    print(os.waitstatus_to_exitcode(status), flush=True)
"""


class Server:
    """The test's end of ``SERVER``; the children's output goes to ``log``."""

    def __init__(self, folder: Path):
        self.log = folder / "child.log"
        self.process = subprocess.Popen(
            [sys.executable, "-c", SERVER], stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True
        )
        assert self.answer(timeout=120) == "ready"

    def answer(self, timeout: float) -> str:
        # One line at a time is ever in the pipe, so nothing waits in the reader's buffer.
        ready, _, _ = select.select([self.process.stdout], [], [], timeout)
        assert ready, f"no answer from the server in {timeout} s"
        line = self.process.stdout.readline()
        assert line, "the server ended"
        return line.strip()

    def tell(self, line: str) -> None:
        self.process.stdin.write(line + "\n")
        self.process.stdin.flush()

    def close(self) -> None:
        self.process.stdin.close()
        assert self.process.wait(timeout=60) == 0
        self.process.stdout.close()


@pytest.fixture(scope="module")
def server(tmp_path_factory):
    started = Server(tmp_path_factory.mktemp("server"))
    yield started
    started.close()


def generate(
    server: Server,
    out: Path,
    seed: int,
    *extra: str,
    kill_after: float | None = None,
    exchange: bool = True,
) -> None:
    argv = ["generate", "desk", "--seed", str(seed), "--no-render", "-o", str(out), "-q"]
    request = {"argv": [*argv, *extra], "no_exchange": not exchange, "log": str(server.log)}
    server.tell(json.dumps(request))
    pid = int(server.answer(timeout=60))
    if kill_after is not None:
        time.sleep(kill_after)
        os.kill(pid, signal.SIGKILL)  # not reaped yet: the pid is still the child's
    server.tell("reap")
    code = int(server.answer(timeout=120))  # reaped: its id no longer names a live process
    if kill_after is None:
        assert code == 0, server.log.read_text()
    else:  # killed, or it had finished before the kill
        assert code in (-signal.SIGKILL, 0), server.log.read_text()


def which_run(out: Path, references: dict[str, Path]) -> str:
    """The reference run whose files ``out`` holds, every one, byte for byte (timings aside)."""
    if not out.is_dir():
        return "no directory"
    names = sorted(
        p.name
        for p in out.iterdir()
        if p.name != "timings.json" and not p.name.endswith(".partial")
    )
    for label, reference in references.items():
        wanted = sorted(p.name for p in reference.iterdir() if p.name != "timings.json")
        if names == wanted and all(
            filecmp.cmp(out / n, reference / n, shallow=False) for n in names
        ):
            return label
    return f"a mixture: {names}"


def partials(folder: Path) -> list[str]:
    found = [p for p in folder.iterdir() if p.name.endswith(".partial")]
    found += (
        [p for p in (folder / "out").iterdir() if p.name.endswith(".partial")]
        if (folder / "out").is_dir()
        else []
    )
    return sorted(p.name for p in found)


@pytest.fixture(scope="module")
def references(tmp_path_factory, server) -> dict[str, Path]:
    """The files of two uninterrupted runs."""
    folder = tmp_path_factory.mktemp("references")
    generate(server, folder / "ref1", 1, "--size", "32x32")  # with previews when OpenGL is there
    generate(server, folder / "ref2", 2)
    return {"seed 1": folder / "ref1", "seed 2": folder / "ref2"}


@pytest.mark.slow
@pytest.mark.parametrize("exchange", [True, False], ids=["rename-exchange", "rename-aside"])
def test_generate_is_all_or_nothing_under_sigkill(tmp_path, server, references, exchange):
    """Before: 8 of 22 kills left a .scenewright-*.partial that no later run removed, and
    with slowed renames 5 of 10 left scene.json of seed 2 beside previews of seed 1.

    After each kill the directory holds every file of one run (with rename-exchange at
    once; renaming aside, after the next run's first step has put back a directory set
    aside), and the next run leaves no partial behind.
    """
    work = tmp_path / "work"
    # How long an uninterrupted run takes that replaces the files of another, as the
    # runs killed below do (publishing over a directory takes longer than into none).
    work.mkdir()
    shutil.copytree(references["seed 1"], work / "out")
    started = time.monotonic()
    generate(server, work / "out", 2, exchange=exchange)
    duration = time.monotonic() - started
    assert which_run(work / "out", references) == "seed 2"
    shutil.rmtree(work)
    rng = random.Random(7)
    # One kill in each of as many equal parts of the run's last four fifths, then four
    # more in its last fifth, where the outputs are published.
    spread = 6 if exchange else 4
    kills = [duration * (0.2 + 0.8 * (part + rng.random()) / spread) for part in range(spread)]
    kills += [rng.uniform(0.8 * duration, duration) for _ in range(4)]
    for kill_after in kills:
        work.mkdir()
        shutil.copytree(references["seed 1"], work / "out")
        generate(server, work / "out", 2, kill_after=kill_after, exchange=exchange)
        if exchange:
            assert which_run(work / "out", references) in references
        remove_dead_partials(work / "out")  # what the next run does first
        assert which_run(work / "out", references) in references
        assert partials(work) == []
        shutil.rmtree(work)
    work.mkdir()
    shutil.copytree(references["seed 1"], work / "out")
    generate(server, work / "out", 2, kill_after=0.6 * duration, exchange=exchange)
    generate(server, work / "out", 2, exchange=exchange)
    assert which_run(work / "out", references) == "seed 2"
    assert partials(work) == []
