"""Datasets beyond one machine: the same job on a dask.distributed cluster.

``cluster_executor(address)`` connects to a running scheduler and returns a standard
``concurrent.futures.Executor`` over it (dask's own ``ClientExecutor``), so the dataset
loop is the same code for a local process pool and for a cluster. Every worker needs
scenewright installed (``pip install 'scenewright[dask]'``); each keeps its rules and
renderer per thread (``produce.worker_context``), and returns encoded
files to this process, which alone writes the dataset directory.

Each way a cluster can fail ends in one line: an address that is not one or a scheduler
that cannot be reached (``InputError``, exit 2), a scheduler with no workers
(``InputError`` after ``worker_timeout`` seconds), a scheduler lost or left without
workers mid-run (``GenerationError``, exit 1; the finished scenes are stored). dask's
and tornado's own log records about the same trouble are silenced while the executor
is open (``quiet_dask_logs``).
"""

from __future__ import annotations

import asyncio
import concurrent.futures as cf
import logging
import time
from collections.abc import Callable

from scenewright.core.errors import GenerationError, InputError

#: Seconds to wait for the scheduler before saying it cannot be reached.
CONNECT_TIMEOUT = 10.0
#: Seconds a run waits while the cluster has no workers (at the start or mid-run) before
#: giving up; ``scenewright dataset --worker-timeout`` changes it.
WORKER_TIMEOUT = 60.0
#: Seconds closing the client may take when the scheduler is gone.
CLOSE_TIMEOUT = 5.0
#: The loggers whose records duplicate the one-line error (tracebacks of a lost
#: connection, reconnection attempts); silenced while a run uses the cluster.
DASK_LOGGERS = ("distributed", "tornado")


class ClusterExecutor(cf.Executor):
    """A dask client's executor that closes the client when it is shut down, and tells a
    lost scheduler or a cluster without workers from a scene's own error."""

    def __init__(
        self, client, address: str, worker_timeout: float, restore_logs: Callable[[], None]
    ) -> None:
        self._client = client
        self._address = address
        self._worker_timeout = worker_timeout
        self._restore_logs = restore_logs
        self._no_workers_since: float | None = None
        # pure=False: every call is real work; two scenes never share a task key.
        self._executor = client.get_executor(pure=False)

    def submit(self, fn, /, *args, **kwargs) -> cf.Future:
        return self._executor.submit(fn, *args, **kwargs)

    def slots(self) -> int:
        """Scenes the cluster works on at once: its worker threads (at least one)."""
        return max(1, sum(self._client.nthreads().values()))

    def check(self) -> None:
        """Raise when the run cannot go on: the scheduler is gone, or it has had no
        workers for ``worker_timeout`` seconds (tasks would wait for one forever)."""
        try:
            workers = len(self._client.nthreads())
        except Exception as error:  # any failure to ask means the scheduler is gone
            raise self.lost() from error
        if workers:
            self._no_workers_since = None
            return
        now = time.monotonic()
        self._no_workers_since = self._no_workers_since or now
        if now - self._no_workers_since >= self._worker_timeout:
            raise GenerationError(
                f"the dask cluster at {self._address} has had no workers for {self._worker_timeout:g} s; "
                "the scenes that finished are stored: start workers and rerun the same command to resume "
                "(--worker-timeout waits longer)"
            )

    def failure(self, future: cf.Future) -> BaseException | None:
        """The error a finished future stands for, or None if it holds a scene. dask
        cancels every task when the client loses the scheduler."""
        if future.cancelled():
            return self.lost()
        return future.exception()

    def lost(self) -> GenerationError:
        return GenerationError(
            f"lost the connection to the dask scheduler at {self._address}; the scenes that finished are "
            "stored: rerun the same command to resume"
        )

    def shutdown(self, wait: bool = True, *, cancel_futures: bool = False) -> None:
        """Close the executor and the client; without ``wait`` (or with
        ``cancel_futures``), cancel the tasks still on the cluster rather than wait."""
        try:
            self._executor.shutdown(wait=wait and not cancel_futures)
            self._client.close(timeout=CLOSE_TIMEOUT)
        except Exception:  # the scheduler is gone: nothing is left to close there
            pass
        finally:
            self._restore_logs()

    def __exit__(self, exc_type, exc_value, traceback) -> bool:
        # After an error (Ctrl-C included) the remaining tasks are cancelled, not awaited.
        self.shutdown(wait=exc_type is None)
        return False


def quiet_dask_logs() -> Callable[[], None]:
    """Silence ``DASK_LOGGERS`` and every logger below them; return what undoes it."""
    names = [
        name
        for name in [*DASK_LOGGERS, *logging.root.manager.loggerDict]
        if any(name == root or name.startswith(root + ".") for root in DASK_LOGGERS)
    ]
    levels = {name: logging.getLogger(name).level for name in names}
    for name in names:
        logging.getLogger(name).setLevel(logging.CRITICAL + 1)

    def restore() -> None:
        for name, level in levels.items():
            logging.getLogger(name).setLevel(level)

    return restore


def cluster_executor(
    address: str, worker_timeout: float = WORKER_TIMEOUT, note: Callable[[str], None] | None = None
) -> ClusterExecutor:
    """An executor on the dask.distributed scheduler at ``address`` (``tcp://host:8786``)
    that has at least one worker, waiting up to ``worker_timeout`` seconds for one (and
    saying so to ``note`` when the scheduler has none yet)."""
    try:
        from distributed import Client
    except ImportError as error:
        raise InputError(
            "--scheduler needs dask.distributed: pip install 'scenewright[dask]'"
        ) from error
    check_address(address)
    restore_logs = quiet_dask_logs()
    try:
        try:
            # CONNECT_TIMEOUT is read here, at call time, so tests can shorten it.
            client = Client(address, timeout=CONNECT_TIMEOUT, set_as_default=False)
        except (OSError, TimeoutError, asyncio.TimeoutError) as error:
            raise InputError(f"cannot reach the dask scheduler at {address}: {error}") from error
        if note is not None and not client.nthreads():
            note(
                f"the dask scheduler at {address} has no workers yet; waiting up to {worker_timeout:g} s for one"
            )
        try:
            client.wait_for_workers(1, timeout=worker_timeout)
        except (TimeoutError, asyncio.TimeoutError):  # one class from Python 3.11 on
            client.close(timeout=CLOSE_TIMEOUT)
            raise InputError(
                f"the dask scheduler at {address} has no workers (waited {worker_timeout:g} s); start some with "
                f"'dask worker {address}', or wait longer with --worker-timeout"
            ) from None
    except BaseException:
        restore_logs()
        raise
    return ClusterExecutor(client, address, worker_timeout, restore_logs)


def check_address(address: str) -> None:
    """Refuse an address dask cannot connect to: an unknown scheme, a transport this
    installation lacks (ucx), a host or port that does not parse. Checked before a
    Client exists: a Client that fails on such an address is left half-made, and closing
    it at exit waits 20 s and prints a traceback."""
    from distributed.comm.addressing import parse_address
    from distributed.comm.registry import Backend, get_backend

    try:
        scheme, location = parse_address(address)
        backend = get_backend(scheme)
        backend.get_connector()
        if (
            type(backend).get_address_host_port is not Backend.get_address_host_port
        ):  # host:port schemes
            backend.get_address_host_port(location)
    except (ValueError, TypeError, ImportError) as error:
        raise InputError(
            f"--scheduler {address!r} is not a dask scheduler address this installation can use ({error})"
        ) from None
