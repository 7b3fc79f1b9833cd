"""The dataset job against hostile or unlucky use: absurd and changing -n, a killed main
process, two runs on one directory, too many workers, Ctrl-C at any moment, and a dask
cluster that is misnamed, empty or lost. Whatever can hang is run in a subprocess with
a time limit; the rest uses the cheap stand-in scene of ``test_dataset``.

Dask cases needing a real scheduler to kill are in ``test_dataset_hardening_dask``.
"""

from __future__ import annotations

import fcntl
import json
import os
import signal
import subprocess
import sys
import time
from collections import Counter
from pathlib import Path

import pytest
from render_fixtures import run_without_opengl
from test_dataset import LIGHT_FORK_SERVER, dataset_bytes, fake_scene, metadata_rows, spec_of

import scenewright.dataset.run
from scenewright.cli import main
from scenewright.core.errors import GenerationError, InputError
from scenewright.dataset.run import available_cpus, run_dataset
from scenewright.dataset.spec import (
    LOCK_FILE,
    METADATA_FILE,
    RECORDS_DIR,
    SETTINGS_FILE,
    DatasetSpec,
    SceneProduct,
)

TESTS = Path(__file__).parent
INTERRUPTED = "scenewright: interrupted (rerunning a dataset command resumes it)"


def pid_scene(spec: DatasetSpec, index: int) -> SceneProduct:
    """The stand-in scene, recording which process made it."""
    time.sleep(0.05)  # long enough for every worker of the pool to get some
    product = fake_scene(spec, index)
    product.stats["pid"] = os.getpid()
    return product


def dying_scene(spec: DatasetSpec, index: int) -> SceneProduct:
    """A worker that dies outright (as one killed by the kernel for lack of memory)."""
    if index == 2:
        os._exit(9)
    return fake_scene(spec, index)


def cli_command(*argv: str, before: str = "") -> list[str]:
    """The scenewright command in a fresh interpreter; it prints "ready" as the dataset
    run begins, inside the command, so a test can interrupt it from its first moment
    (Ctrl-C during the interpreter's start and the imports is outside the command, and
    so was the moment between a "ready" printed before ``main`` and ``main`` itself)."""
    script = (
        # Ctrl-C as on a terminal: a shell that runs the tests as a background job starts
        # its children with SIGINT ignored, and Python then leaves it ignored.
        "import signal; signal.signal(signal.SIGINT, signal.default_int_handler)\n"
        f"import sys; sys.path.insert(0, {str(TESTS)!r})\n"
        "import scenewright.cli, scenewright.dataset.run\n"
        f"{before}\n"
        "run = scenewright.dataset.run.run_dataset\n"
        "def announced(*args, **kwargs):\n"
        "    print('ready', flush=True)\n"
        "    return run(*args, **kwargs)\n"
        "scenewright.dataset.run.run_dataset = announced\n"
        "sys.exit(scenewright.cli.main(sys.argv[1:]))\n"
    )
    return [sys.executable, "-c", script, *argv]


def fake_job(directory: Path, count: int, workers: int = 2) -> list[str]:
    """``run_dataset`` on the stand-in scene, in a fresh interpreter."""
    script = (
        # Ctrl-C as on a terminal: a shell that runs the tests as a background job starts
        # its children with SIGINT ignored, and Python then leaves it ignored.
        "import signal; signal.signal(signal.SIGINT, signal.default_int_handler)\n"
        f"import sys; sys.path.insert(0, {str(TESTS)!r})\n"
        "from test_dataset import fake_scene, spec_of\n"
        "import scenewright.dataset.run\n"
        "from scenewright.dataset.run import run_dataset\n"
        f"{LIGHT_FORK_SERVER}\n"
        "if __name__ == '__main__':\n"
        f"    run_dataset(spec_of({count}), {str(directory)!r}, workers={workers}, producer=fake_scene,\n"
        "                progress=False)\n"
    )
    return [sys.executable, "-c", script]


def group_members(group: int) -> list[int]:
    """Live (not zombie) processes of a process group, from /proc."""
    members = []
    for entry in Path("/proc").iterdir():
        if not entry.name.isdigit():
            continue
        try:
            stat = (entry / "stat").read_text()
        except OSError:
            continue
        state, _parent, process_group = stat[stat.rindex(")") + 2 :].split()[:3]
        if int(process_group) == group and state != "Z":
            members.append(int(entry.name))
    return members


def wait_for(condition, seconds: float, what: str) -> None:
    deadline = time.monotonic() + seconds
    while not condition():
        assert time.monotonic() < deadline, f"timed out after {seconds} s waiting for {what}"
        time.sleep(0.05)


def records(root: Path) -> int:
    return len(list((root / RECORDS_DIR).glob("*.json"))) if (root / RECORDS_DIR).is_dir() else 0


def interrupt_group(job: subprocess.Popen) -> None:
    os.killpg(job.pid, signal.SIGKILL)
    job.wait()


# -- 1. -n: absurd, shrinking, growing; start-up independent of N ----------------------


def test_rerun_reads_each_record_once_to_start_and_once_to_publish(tmp_path, monkeypatch):
    """Start-up scans the records folder once (it used to scan it once per index: a
    rerun of 2000 finished scenes took 100 s)."""
    run_dataset(spec_of(60), tmp_path, workers=1, producer=fake_scene, progress=False)
    reads: Counter = Counter()
    real = scenewright.dataset.run.read_record

    def counted(path: Path):
        reads[path.name] += 1
        return real(path)

    monkeypatch.setattr(scenewright.dataset.run, "read_record", counted)
    report = run_dataset(spec_of(60), tmp_path, workers=1, producer=fake_scene, progress=False)
    assert (report.made, report.skipped) == (0, 60)
    assert len(reads) == 60 and max(reads.values()) == 2


@pytest.mark.slow
def test_an_absurd_count_starts_at_once_and_a_smaller_one_is_accepted_afterwards(tmp_path):
    """`dataset desk -n 1000000000000` used to print nothing and never start (a list of N
    items, each a scan of the records), and the count it stored refused any smaller -n."""
    root = tmp_path / "huge"
    job = subprocess.Popen(
        cli_command(
            "dataset",
            "desk",
            "-n",
            "1000000000000",
            "-o",
            str(root),
            "--size",
            "32x32",
            "--workers",
            "1",
        ),
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        start_new_session=True,
    )
    try:
        assert job.stdout.readline() == b"ready\n"
        wait_for(lambda: records(root) >= 1 or job.poll() is not None, 90, "the first scene")
        assert job.poll() is None
        os.killpg(job.pid, signal.SIGINT)
        # A bound on a hang, not a timing: alone it exits within seconds, but with two
        # other processes busy on the two cores it has taken over 30 s.
        _, err = job.communicate(timeout=120)
    finally:
        if job.returncode is None:
            interrupt_group(job)
    assert job.returncode == 130 and err.decode().splitlines()[-1] == INTERRUPTED
    assert "count" not in json.loads((root / SETTINGS_FILE).read_text())
    made = records(root)

    rerun = subprocess.run(
        [
            sys.executable,
            "-m",
            "scenewright.cli",
            "dataset",
            "desk",
            "-n",
            "1",
            "-o",
            str(root),
            "--size",
            "32x32",
        ],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert rerun.returncode == 0, rerun.stderr
    assert (
        "1 scene in metadata.jsonl" in rerun.stdout
        and "ran 0 now, 1 were already done" in rerun.stdout
    )
    if made > 1:
        assert (
            f"{made - 1} finished scenes with index 1 or above stay on disk, not listed"
            in rerun.stdout
        )
    assert len(metadata_rows(root)) == 1


@pytest.mark.slow
def test_a_missing_opengl_backend_in_the_workers_is_one_line_not_a_dead_pool(tmp_path):
    """The workers start their renderer before their first scene; when it cannot start,
    the error comes back through that scene as one line, instead of breaking the pool
    ("a worker process died") with the initializer's traceback."""
    env = dict(os.environ, PYOPENGL_PLATFORM="no-such-platform")
    done = subprocess.run(
        [
            sys.executable,
            "-m",
            "scenewright.cli",
            "dataset",
            "desk",
            "-n",
            "2",
            "-o",
            str(tmp_path / "d"),
            "--size",
            "32x32",
            "--workers",
            "2",
        ],
        env=env,
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert done.returncode == 1 and "Traceback" not in done.stderr, done.stderr
    last = done.stderr.strip().splitlines()[-1]
    assert last.startswith(
        "scenewright: error: offscreen OpenGL backend PYOPENGL_PLATFORM='no-such-platform'"
    )
    assert "died" not in done.stderr


def test_the_fork_servers_preload_survives_a_missing_opengl_backend():
    """The fork server imports ``worker_preload`` before any worker exists and dies of
    any error but ImportError: a backend that cannot load must leave the import whole,
    for the worker to report (the test above), with the parser built all the same."""
    code = (
        "import scenewright.dataset.worker_preload\n"
        "from scenewright.generator.rules_lark import _parser\n"
        "print(_parser.cache_info().currsize)\n"
    )
    done = run_without_opengl(code)
    assert done.returncode == 0 and "Traceback" not in done.stderr, done.stderr
    assert done.stdout.strip() == "1"
    assert "scenewright.dataset.worker_preload" in scenewright.dataset.run.WORKER_MODULES


@pytest.mark.slow
def test_shrinking_lists_only_scenes_below_n_and_growing_back_makes_nothing(tmp_path):
    grown = tmp_path / "grown"
    run_dataset(spec_of(9), grown, workers=1, producer=fake_scene, progress=False)
    shrunk = run_dataset(spec_of(5), grown, workers=1, producer=fake_scene, progress=False)
    assert (shrunk.made, shrunk.skipped, shrunk.beyond) == (0, 5, 4)
    assert [row["scene_id"] for row in metadata_rows(grown)] == [
        "000000",
        "000001",
        "000002",
        "000004",
    ]
    stats = json.loads((grown / "stats.json").read_text())
    assert (stats["scenes"], stats["written"], stats["failed"]) == (5, 4, 1)
    assert (grown / "images/000008.png").is_file() and (
        grown / RECORDS_DIR / "000008.json"
    ).is_file()
    run_dataset(spec_of(5), tmp_path / "direct5", workers=1, producer=fake_scene, progress=False)
    assert (grown / METADATA_FILE).read_bytes() == (
        tmp_path / "direct5" / METADATA_FILE
    ).read_bytes()

    again = run_dataset(spec_of(9), grown, workers=1, producer=fake_scene, progress=False)
    assert (again.made, again.skipped, again.beyond) == (0, 9, 0)
    run_dataset(spec_of(9), tmp_path / "direct9", workers=1, producer=fake_scene, progress=False)
    assert dataset_bytes(grown) == dataset_bytes(tmp_path / "direct9")


def test_a_shrunk_dataset_loads_only_its_listed_scenes(tmp_path):
    datasets = pytest.importorskip("datasets")
    run_dataset(spec_of(9), tmp_path / "d", workers=1, producer=fake_scene, progress=False)
    run_dataset(spec_of(5), tmp_path / "d", workers=1, producer=fake_scene, progress=False)
    loaded = datasets.load_dataset(
        "imagefolder",
        data_dir=str(tmp_path / "d"),
        split="train",
        cache_dir=str(tmp_path / "cache"),
    )
    assert loaded["scene_id"] == ["000000", "000001", "000002", "000004"]


# -- 6. kill -9 of the main process leaves nothing behind -------------------------------


def assert_nothing_outlives_a_killed_main(job: subprocess.Popen, root: Path, scenes: int) -> None:
    try:
        wait_for(
            lambda: records(root) >= scenes or job.poll() is not None, 90, "the run to get going"
        )
        assert job.poll() is None
        assert len(group_members(job.pid)) >= 4  # this process, fork server, tracker, workers
        os.kill(job.pid, signal.SIGKILL)  # the main process only, as `kill -9 PID` does
        # Returns once every process holding the job's stdout and stderr has exited.
        job.communicate(timeout=15)
        wait_for(lambda: not group_members(job.pid), 5, "the job's processes to exit")
    finally:
        if group_members(job.pid):
            os.killpg(job.pid, signal.SIGKILL)
        job.wait()


@pytest.mark.slow
def test_kill_minus_nine_of_the_main_process_ends_its_workers_and_fork_server(tmp_path):
    root = tmp_path / "killed"
    job = subprocess.Popen(
        fake_job(root, 200),
        env={**os.environ, "FAKE_SCENE_DELAY": "0.2"},
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        start_new_session=True,
    )
    assert_nothing_outlives_a_killed_main(job, root, 3)
    report = run_dataset(spec_of(20), root, workers=2, producer=fake_scene, progress=False)
    assert report.skipped >= 3 and len(metadata_rows(root)) == 17  # resumes as before


@pytest.mark.slow
def test_kill_minus_nine_of_the_command_ends_its_rendering_workers(tmp_path):
    root = tmp_path / "desk"
    job = subprocess.Popen(
        [sys.executable, "-m", "scenewright.cli", "dataset", "desk", "-n", "200", "-o", str(root)]
        + ["--size", "32x32", "--workers", "2", "-q"],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        start_new_session=True,
    )
    assert_nothing_outlives_a_killed_main(job, root, 2)


# -- 8. one run per directory ------------------------------------------------------------


def test_a_directory_in_use_is_refused_and_its_temporary_files_are_left_alone(tmp_path, capsys):
    run_dataset(spec_of(3), tmp_path, workers=1, producer=fake_scene, progress=False)
    in_flight = tmp_path / "images" / ".000003.png.x1y2z3.partial"  # what a running run is writing
    with open(tmp_path / LOCK_FILE, "r+") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        lock.write("4242\n")
        lock.flush()
        in_flight.write_bytes(b"half a PNG")
        with pytest.raises(
            InputError, match=r"is in use by another scenewright dataset run \(pid 4242\)"
        ):
            run_dataset(spec_of(8), tmp_path, workers=1, producer=fake_scene, progress=False)
        assert in_flight.read_bytes() == b"half a PNG"
        assert main(["dataset", "desk", "-n", "2", "-o", str(tmp_path)]) == 2
        assert capsys.readouterr().err.splitlines() == [
            f"scenewright: error: {tmp_path} is in use by another scenewright dataset run (pid 4242)"
        ]
    # Unlocked: the leftover is a killed run's and is cleared; the lock file with a dead
    # pid in it does not block.
    report = run_dataset(spec_of(8), tmp_path, workers=1, producer=fake_scene, progress=False)
    assert (report.skipped, report.made) == (3, 5) and not in_flight.exists()
    assert (tmp_path / LOCK_FILE).read_text() == ""  # emptied when the run ends


@pytest.mark.slow
def test_a_second_run_during_the_first_exits_2_and_the_first_finishes(tmp_path):
    root = tmp_path / "shared"
    gate = tmp_path / "go on"  # the first run makes two scenes, then waits for it
    first = subprocess.Popen(
        fake_job(root, 30),
        env={**os.environ, "FAKE_SCENE_GATE": str(gate)},
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        start_new_session=True,
    )
    try:
        wait_for(
            lambda: records(root) >= 2 or first.poll() is not None, 60, "the first run to get going"
        )
        with pytest.raises(
            InputError, match=rf"in use by another scenewright dataset run \(pid {first.pid}\)"
        ):
            run_dataset(spec_of(30), root, workers=1, producer=fake_scene, progress=False)
        gate.touch()
        _, err = first.communicate(timeout=60)
    finally:
        if first.returncode is None:
            interrupt_group(first)
    assert first.returncode == 0, err.decode()
    run_dataset(spec_of(30), tmp_path / "clean", workers=1, producer=fake_scene, progress=False)
    assert dataset_bytes(root) == dataset_bytes(tmp_path / "clean")


# -- 12. --workers is capped ---------------------------------------------------------------


def test_workers_are_capped_at_the_cpus_and_the_pending_scenes(tmp_path):
    cpus = available_cpus()
    report = run_dataset(spec_of(12), tmp_path, workers=1000, producer=pid_scene, progress=False)
    assert report.workers == min(cpus, 12)
    pids = {
        json.loads(p.read_text())["stats"]["pid"] for p in (tmp_path / RECORDS_DIR).glob("*.json")
    }
    assert 1 <= len(pids) <= min(cpus, 12)
    (tmp_path / RECORDS_DIR / "000005.json").unlink()
    assert (
        run_dataset(spec_of(12), tmp_path, workers=1000, producer=pid_scene, progress=False).workers
        == 1
    )


def test_too_many_workers_is_a_note_not_an_error(tmp_path, monkeypatch, capsys):
    real = scenewright.dataset.run.run_dataset
    used = {}

    def fake_run(*args, **kwargs):
        report = real(*args, **{**kwargs, "producer": fake_scene})
        used["workers"] = report.workers
        return report

    monkeypatch.setattr(scenewright.dataset.run, "run_dataset", fake_run)
    monkeypatch.setattr(scenewright.dataset.run, "available_cpus", lambda: 1)
    # --no-coco: fake_scene makes no COCO annotations
    assert (
        main(["dataset", "desk", "-n", "3", "-o", str(tmp_path), "--workers", "1000", "--no-coco"])
        == 0
    )
    err = capsys.readouterr().err.splitlines()
    assert (
        err[0]
        == "scenewright: note: --workers 1000 is more than the CPUs this process may use (1); using 1"
    )
    assert used["workers"] == 1


def test_a_worker_that_dies_is_reported_as_such(tmp_path):
    with pytest.raises(GenerationError, match="a worker process died"):
        run_dataset(spec_of(8), tmp_path, workers=2, producer=dying_scene, progress=False)
    assert not (tmp_path / METADATA_FILE).exists()


# -- 13. Ctrl-C at any moment: one line, exit 130 ----------------------------------------


@pytest.mark.slow
@pytest.mark.parametrize("delay", [0.0, 0.5, 1.0, 2.5])
def test_ctrl_c_at_any_moment_prints_one_line_and_leaves_no_process(tmp_path, delay):
    """Ctrl-C on a terminal signals the whole process group. While the fork server was
    importing the pipeline (the first seconds) it printed its own traceback; a worker
    did too."""
    job = subprocess.Popen(
        cli_command(
            "dataset",
            "desk",
            "-n",
            # Enough scenes that the job is still running at the last delay: 40 took
            # under 2.5 s once the dataset made about 16 scenes a second.
            "2000",
            "-o",
            str(tmp_path),
            "--size",
            "32x32",
            "--workers",
            "2",
            "-q",
        ),
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        start_new_session=True,
    )
    try:
        assert job.stdout.readline() == b"ready\n"
        time.sleep(delay)
        os.killpg(job.pid, signal.SIGINT)
        _, err = job.communicate(timeout=60)
    finally:
        if job.returncode is None:
            interrupt_group(job)
    assert err.decode().splitlines() == [INTERRUPTED] and job.returncode == 130
    wait_for(lambda: not group_members(job.pid), 10, "the job's processes to exit")


# -- 13. dask: a bad address or a scheduler without workers ------------------------------


@pytest.mark.parametrize("address", ["foo", "http://127.0.0.1:8786", "tcp://[::1"])
def test_a_malformed_scheduler_address_is_one_line_at_once(tmp_path, address):
    pytest.importorskip("distributed")
    started = time.monotonic()
    result = subprocess.run(
        [sys.executable, "-m", "scenewright.cli", "dataset", "desk", "-n", "2", "-o", str(tmp_path)]
        + ["--scheduler", address],
        capture_output=True,
        text=True,
        timeout=60,
    )
    lines = result.stderr.splitlines()
    assert result.returncode == 2 and len(lines) == 1, result.stderr
    assert lines[0].startswith(
        f"scenewright: error: --scheduler {address!r} is not a dask scheduler address "
    )
    assert time.monotonic() - started < 15  # closing a half-made client used to wait 20 s


def test_a_scheduler_without_workers_is_reported_after_the_timeout(tmp_path, capsys):
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(n_workers=0, processes=False, dashboard_address=None) as cluster:
        with pytest.raises(InputError, match=r"has no workers \(waited 0.5 s\).*--worker-timeout"):
            run_dataset(
                spec_of(2),
                tmp_path / "api",
                scheduler=cluster.scheduler_address,
                worker_timeout=0.5,
                producer=fake_scene,
                progress=False,
            )
        argv = [
            "dataset",
            "desk",
            "-n",
            "2",
            "-o",
            str(tmp_path / "cli"),
            "--worker-timeout",
            "0.5",
        ]
        assert main([*argv, "--scheduler", cluster.scheduler_address]) == 2
    address = cluster.scheduler_address
    assert capsys.readouterr().err.splitlines() == [
        f"the dask scheduler at {address} has no workers yet; waiting up to 0.5 s for one",
        f"scenewright: error: the dask scheduler at {address} has no workers (waited 0.5 s); "
        f"start some with 'dask worker {address}', or wait longer with --worker-timeout",
    ]
