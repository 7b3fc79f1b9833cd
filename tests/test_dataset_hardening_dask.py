"""A dask cluster that goes away under a running dataset: its workers, then its scheduler.

Each case ran into 32 lines of tracebacks ending in an empty ``CancelledError``, or into
a silent wait for workers that never came; now each ends in one line and exit 1, with
the finished scenes stored. The scheduler and workers are ``dask`` commands in their own
process groups, so the test can kill them; the dataset command runs in a subprocess
with a time limit.
"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest
from test_dataset_hardening import cli_command, group_members, records, wait_for

pytestmark = pytest.mark.slow
DASK = Path(sys.executable).parent / "dask"


@pytest.fixture
def scheduler(tmp_path):
    """A dask scheduler on a free port: (its process, its address)."""
    pytest.importorskip("distributed")
    if not DASK.exists():
        pytest.skip("the dask command is not installed")
    scheduler_file = tmp_path / "scheduler.json"
    process = subprocess.Popen(
        [str(DASK), "scheduler", "--host", "127.0.0.1", "--port", "0", "--dashboard-address", ":0"]
        + ["--scheduler-file", str(scheduler_file)],
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
        start_new_session=True,
    )
    try:
        wait_for(
            lambda: scheduler_file.exists() and scheduler_file.stat().st_size > 0,
            60,
            "the scheduler",
        )
        yield process, json.loads(scheduler_file.read_text())["address"]
    finally:
        if group_members(process.pid):
            os.killpg(process.pid, signal.SIGKILL)
        process.wait()


def start_worker(address: str) -> subprocess.Popen:
    """A dask worker, returned once the scheduler has it: the commands under test wait
    only half a second for workers, and a worker still importing on a busy machine would
    read as none at all."""
    from distributed import Client

    worker = subprocess.Popen(
        [str(DASK), "worker", address, "--nworkers", "1", "--nthreads", "1", "--no-dashboard"],
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
        start_new_session=True,
    )
    with Client(address, timeout=60) as client:
        client.wait_for_workers(1, timeout=120)
    return worker


def kill_group(process: subprocess.Popen) -> None:
    if group_members(process.pid):
        os.killpg(process.pid, signal.SIGKILL)
    process.wait()


def run_until_scenes_then(
    root: Path, address: str, scenes: int, action
) -> subprocess.CompletedProcess:
    """Run a desk dataset on the cluster until ``scenes`` are stored, do ``action``, and
    return how the command ended (it must end within a minute)."""
    job = subprocess.Popen(
        cli_command(
            "dataset",
            "desk",
            "-n",
            "500",
            "-o",
            str(root),
            "--size",
            "32x32",
            "--scheduler",
            address,
            "--worker-timeout",
            "0.5",
            "-q",
            before="scenewright.dataset.run.IDLE_CHECK = 0.1",
        ),
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        start_new_session=True,
    )
    try:
        wait_for(
            lambda: records(root) >= scenes or job.poll() is not None,
            120,
            "scenes from the cluster",
        )
        assert job.poll() is None, job.stderr.read()
        action()
        out, err = job.communicate(timeout=60)
    finally:
        kill_group(job)
    return subprocess.CompletedProcess(job.args, job.returncode, out, err)


def test_losing_every_worker_then_the_scheduler_ends_in_one_line_each(tmp_path, scheduler):
    process, address = scheduler
    worker = start_worker(address)
    try:
        ended = run_until_scenes_then(tmp_path / "a", address, 2, lambda: kill_group(worker))
    finally:
        kill_group(worker)
    assert ended.returncode == 1, ended.stderr
    assert ended.stderr.splitlines() == [
        f"scenewright: error: the dask cluster at {address} has had no workers for 0.5 s; the scenes that "
        "finished are stored: start workers and rerun the same command to resume (--worker-timeout waits longer)"
    ]

    worker = start_worker(address)
    try:
        started = time.monotonic()
        ended = run_until_scenes_then(tmp_path / "b", address, 2, lambda: kill_group(process))
        assert time.monotonic() - started < 120
    finally:
        kill_group(worker)
    assert ended.returncode == 1, ended.stderr
    assert ended.stderr.splitlines() == [
        f"scenewright: error: lost the connection to the dask scheduler at {address}; the scenes that "
        "finished are stored: rerun the same command to resume"
    ]
    assert records(tmp_path / "b") >= 2
