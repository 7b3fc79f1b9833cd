"""Datasets beyond one machine: the same job on a dask.distributed cluster.

``cluster_executor(address)`` connects to a running scheduler and returns a standard
``concurrent.futures.Executor`` over it (dask's own ``ClientExecutor``), so the dataset
loop is the same code for a local process pool and for a cluster. Every worker needs
scenewright installed (``pip install 'scenewright[dask]'``); each keeps its rules and
renderer per thread (``dataset_scene.worker_context``), and returns encoded
files to this process, which alone writes the dataset directory.
"""

from __future__ import annotations

import concurrent.futures as cf

from scenewright.core.errors import InputError

#: How long to wait for the scheduler before saying it cannot be reached.
CONNECT_TIMEOUT = "10s"


class ClusterExecutor(cf.Executor):
    """A dask client's executor that also closes the client when it is shut down."""

    def __init__(self, client) -> None:
        self._client = client
        # pure=False: every call is real work; two scenes never share a task key.
        self._executor = client.get_executor(pure=False)

    def submit(self, fn, /, *args, **kwargs) -> cf.Future:
        return self._executor.submit(fn, *args, **kwargs)

    def slots(self) -> int:
        """Scenes the cluster works on at once: its worker threads (at least one)."""
        return max(1, sum(self._client.nthreads().values()))

    def shutdown(self, wait: bool = True, *, cancel_futures: bool = False) -> None:
        self._executor.shutdown(wait=wait)
        self._client.close()


def cluster_executor(address: str) -> ClusterExecutor:
    """An executor on the dask.distributed scheduler at ``address`` (``tcp://host:8786``)."""
    try:
        from distributed import Client
    except ImportError as error:
        raise InputError("--scheduler needs dask.distributed: pip install 'scenewright[dask]'") from error
    try:
        # CONNECT_TIMEOUT is read here, at call time, so tests can shorten it.
        client = Client(address, timeout=CONNECT_TIMEOUT, set_as_default=False)
    except (OSError, TimeoutError, ValueError) as error:
        raise InputError(f"cannot reach the dask scheduler at {address}: {error}") from error
    return ClusterExecutor(client)
