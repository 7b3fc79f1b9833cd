"""A dataset run: N scenes from one rule set, written in the Hugging Face ``imagefolder`` layout.

Seeds. Scene ``i`` of a dataset with base seed ``b`` uses the seed
``SeedSequence([b, i]).generate_state(1)[0]`` (``scene_seed``): it depends on nothing
but ``(b, i)``, so any scene can be regenerated alone, the bytes on disk do not depend
on the number of workers or on the order in which scenes finish, and a dataset can grow
or shrink by its count: scene ``i`` is the same whatever N it was made under.

On disk (``DIR``)::

    dataset.json           the settings; a rerun must use the same ones (N is not one)
    metadata.jsonl         one row per image of a written scene with index < N, ordered by index
    images/000000.png      the preview (000000_0.png, 000000_1.png, ... with several views)
    scenes/000000.json     scene.json (no wall-clock times: reproducible)
    texts/000000.txt       the full description, instead of images/ (``images`` off)
    depth/, segmentation/  optional ground truth (16-bit PNGs)
    failed/000003.json     scene.json of a scene whose every layout failed (not in metadata)
    stats.json, stats.png  counts, frequencies, caption lengths, time per stage
    questions.json         every row's questions, CLEVR's layout (``questions``)
    annotations/instances.json  COCO instances of every image (``coco``)
    .records/000000.json   one record per finished scene: the commit marker for resume
    .lock                  locked (flock) by the run using the directory, which writes its
                           pid there while it runs

A scene whose layout fails is laid out again, up to ``DatasetSpec.retries`` times, with
the layout seeds ``core.seeds.retry_seed(seed, k)`` and the same scene graph, so the
dataset keeps the rule set's mix of scene sizes (``produce.laid_out_scene``).

Every file is written atomically; a scene counts as done only once its record exists,
and the record is written after the scene's files. A run that is killed therefore
resumes where it stopped: finished scenes are skipped, a half-finished one is made
again (with the same bytes), and ``metadata.jsonl`` and the statistics are rebuilt
from the records at the end. Start-up reads the records folder once and walks the
indices still to make lazily, so it costs the same whatever N is.

Work runs on a process pool (one machine, ``WorkerPool``) or on a dask.distributed
cluster (several, ``cluster``); workers compute and encode, and only this
process writes to ``DIR``, so a cluster's workers need no shared filesystem.
"""

from __future__ import annotations

import concurrent.futures as cf
import fcntl
import hashlib
import json
import multiprocessing
import os
import signal
import sys
import threading
import time
from collections.abc import Callable, Iterator
from concurrent.futures.process import BrokenProcessPool
from contextlib import contextmanager, nullcontext
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, TextIO

from scenewright.core.atomic import atomic_stream, remove_partials, write_atomic
from scenewright.core.collector import collect_less
from scenewright.core.errors import GenerationError, InputError, ScenewrightError
from scenewright.core.files import load_json
from scenewright.dataset.coco import coco_sink
from scenewright.dataset.spec import (
    LOCK_FILE,
    METADATA_FILE,
    RECORDS_DIR,
    SETTINGS_FILE,
    DatasetSpec,
    Producer,
    SceneProduct,
    scene_stem,
)
from scenewright.dataset.stats import StatsCollector, write_stats

if TYPE_CHECKING:
    pass

#: What a worker imports; a fork server imports it once for all its workers
#: (``worker_preload`` loads pyrender and builds the rules parser there too).
WORKER_MODULES = [
    "scenewright.generator.layout",
    "scenewright.describer",
    "scenewright.dataset.produce",
    "scenewright.dataset.worker_preload",
]
#: When stderr is not a terminal (a log file, a batch job), progress is a plain line at
#: most this often (seconds) and one at the end, not a bar redrawn after every scene.
LOG_INTERVAL = 30.0
#: When no scene has finished for this long (seconds), the run asks its executor whether
#: it can still make progress (a dask cluster may have lost its scheduler or workers).
IDLE_CHECK = 5.0
#: What a setting stored by a version that did not have it meant (a dataset made before
#: retries existed retried nothing, one made before COCO output wrote none, one made
#: before datasets without images had images), so such a dataset can be resumed with that value.
SETTINGS_BEFORE = {
    "retries": 0,
    "images": True,
    "coco": False,
    "views": 1,
    "camera": None,
    "text_words": None,
    "context": None,
    "context_digest": None,
}


def available_cpus() -> int:
    """The CPUs this process may run on (its affinity, not the machine's count): the
    default and the most local worker processes a run starts."""
    if hasattr(os, "process_cpu_count"):  # Python 3.13+
        return os.process_cpu_count() or 1
    if hasattr(os, "sched_getaffinity"):
        return len(os.sched_getaffinity(0))
    return os.cpu_count() or 1


def pool_size(requested: int | None, pending: int) -> int:
    """Worker processes for ``pending`` scenes: ``requested`` (default: one per CPU), at
    most one per CPU (more only compete for the same cores, each holding its own
    pipeline and OpenGL context) and at most one per pending scene."""
    cpus = available_cpus()
    return max(1, min(requested or cpus, cpus, pending))


@dataclass
class RunReport:
    """What a run did: how many scenes exist, how many this run made, how long it took.

    ``beyond`` counts finished scenes with an index of ``count`` or more (from a run with a
    larger N): they stay on disk, unlisted. ``workers`` is the number of scenes made at
    once (pool processes or cluster threads; 0 when nothing was left to make).
    """

    directory: Path
    count: int
    made: int
    skipped: int
    written: int
    failed: int
    seconds: float
    stats: dict = field(default_factory=dict)
    beyond: int = 0
    workers: int = 0

    @property
    def scenes_per_minute(self) -> float:
        return 60.0 * self.made / self.seconds if self.seconds > 0 else 0.0

    def summary(self, spec: DatasetSpec) -> tuple[list[str], list[str]]:
        """What the command says of the run: lines for people (progress, figures) and
        error lines, one per kind of failure (a layout that failed after every retry,
        the errors of scenes the rules could not make)."""
        stats = self.stats
        failed_layouts = stats["failed_layouts"]
        kept = "included, ok=false" if spec.include_failed else "left out"
        images = f" ({self.written * spec.views} images)" if spec.views > 1 else ""
        notes = [
            f"{self.directory}: {self.written} scene{'s' * (self.written != 1)}{images} in metadata.jsonl; {failed_layouts} "
            f"of {self.count} layouts failed after {spec.retries} retries ({kept}); ran {self.made} now, {self.skipped} "
            "were already done"
        ]
        retries = stats["retries"]
        if retries["scenes_retried"]:
            notes.append(
                f"{retries['scenes_retried']} scenes needed a layout retry ({retries['retries']} retries; by scene "
                "size in stats.json)"
            )
        if self.beyond:
            notes.append(
                f"{self.beyond} finished scenes with index {self.count} or above stay on disk, not listed"
            )
        if failed_layouts:
            notes.append(f"most frequent layout problems: {counted(stats['problems'])}")
        if self.made:
            notes.append(
                f"{self.seconds:.1f} s, {self.scenes_per_minute:.1f} scenes/min; statistics in stats.json, stats.png"
            )
        errors = [
            f"the {stage} failed for {error['scenes']} of {self.count} scenes (not made): {counted(error['messages'])}"
            for stage, error in stats["errors"].items()
        ]
        if failed_layouts:
            which = f"{failed_layouts} of {self.count} layouts"
            if failed_layouts == self.count:
                which = "every scene's layout"
            errors.append(f"{which} failed after {spec.retries} retries ({kept})")
        if self.written == 0 and self.count > 0:
            errors.append("nothing usable was written")
        return notes, errors


def counted(kinds: dict[str, int], shown: int = 3) -> str:
    """The first ``shown`` of a {kind: count} dict as "kind (3x); other (1x)"."""
    return "; ".join(f"{kind} ({n}x)" for kind, n in list(kinds.items())[:shown])


@contextmanager
def open_dataset(spec: DatasetSpec, directory: str | os.PathLike[str]) -> Iterator[Path]:
    """Create or reopen a dataset directory and hold its lock for the block.

    Refuses a directory that holds other files but no dataset, one made with other
    settings, and one another run is using. Under the lock it removes what a killed run
    left half-written (no other run can be writing it) and stores the settings.
    """
    root = Path(directory)
    try:
        root.mkdir(parents=True, exist_ok=True)
        settings_path = root / SETTINGS_FILE
        if not settings_path.exists() and any(entry.name != LOCK_FILE for entry in root.iterdir()):
            raise InputError(
                f"{root} is not empty and holds no scenewright dataset; choose a new directory"
            )
        lock = lock_directory(root)
    except OSError as error:
        raise InputError(
            f"cannot write the dataset to {root}: {error.strerror or error}"
        ) from error
    try:
        try:
            if settings_path.exists():
                check_same_settings(spec, read_settings(settings_path), root)
            write_atomic(settings_path, json.dumps(spec.settings(), indent=1) + "\n")
            for sub in ("images" if spec.images else "texts", "scenes", RECORDS_DIR):
                (root / sub).mkdir(exist_ok=True)
            remove_partials(root)
        except OSError as error:
            raise InputError(
                f"cannot write the dataset to {root}: {error.strerror or error}"
            ) from error
        yield root
    finally:
        unlock_directory(lock)


def lock_directory(root: Path) -> int:
    """Take the directory's lock (``LOCK_FILE``) for this run and write this process's
    pid into it; return the descriptor, whose closing releases the lock. Refuses with
    the holder's pid when another run has it. The lock is ``flock``: the kernel drops it
    when its holder ends, however, so a killed run never leaves the directory locked."""
    descriptor = os.open(root / LOCK_FILE, os.O_RDWR | os.O_CREAT | os.O_CLOEXEC, 0o666)
    try:
        fcntl.flock(descriptor, fcntl.LOCK_EX | fcntl.LOCK_NB)
    except BlockingIOError:
        holder = os.pread(descriptor, 32, 0).decode("ascii", "replace").strip() or "unknown"
        os.close(descriptor)
        raise InputError(
            f"{root} is in use by another scenewright dataset run (pid {holder})"
        ) from None
    os.ftruncate(descriptor, 0)
    os.pwrite(descriptor, f"{os.getpid()}\n".encode(), 0)
    return descriptor


def unlock_directory(descriptor: int) -> None:
    """Empty the lock file (a finished dataset's files stay the same bytes whoever made
    them) and release the lock."""
    try:
        os.ftruncate(descriptor, 0)
    finally:
        os.close(descriptor)


def read_settings(path: Path) -> dict:
    """The settings a dataset folder's ``dataset.json`` holds; ``InputError`` naming the
    file when it is not a JSON object of at most 1 MiB (it is a few hundred bytes)."""
    from scenewright.core.files import UnusableFile, read_regular_file

    try:
        document = load_json(read_regular_file(path, 2**20, "a dataset.json").decode("utf-8"))
    except UnusableFile as problem:
        raise InputError(f"{path}: cannot read: it {problem}") from None
    except UnicodeDecodeError:
        raise InputError(f"{path}: not UTF-8 text; it is not a dataset's settings") from None
    except ValueError as error:
        raise InputError(f"{path}: not JSON ({error}); it is not a dataset's settings") from None
    if not isinstance(document, dict):
        raise InputError(
            f"{path}: not a dataset's settings (a JSON object), but a JSON {type(document).__name__}"
        )
    return document


def check_same_settings(spec: DatasetSpec, stored: dict, root: Path) -> None:
    """Refuse a rerun whose settings differ from the stored ones (``count`` is not a
    setting; a ``count`` that datasets made before it could change is ignored). A
    setting missing on either side has its default: its ``SETTINGS_BEFORE`` value, or
    for the caption settings, which are stored only when not the defaults, those."""
    from scenewright.dataset.produce import CAPTION_DEFAULTS

    defaults = {**CAPTION_DEFAULTS, **SETTINGS_BEFORE}
    stored, current = {**defaults, **stored}, {**defaults, **spec.settings()}
    keys = [key for key in dict.fromkeys([*current, *stored]) if key != "count"]
    differing = [key for key in keys if stored.get(key) != current.get(key)]
    if differing:
        details = ", ".join(
            f"{key} {stored.get(key)!r} -> {current.get(key)!r}" for key in differing
        )
        raise InputError(
            f"{root} holds a dataset made with other settings ({details}); use a new directory"
        )


def finished_indices(root: Path) -> set[int]:
    """The indices whose record exists and reads back (those scenes are done), from one
    pass over the records folder: the cost follows the records on disk, not N."""
    done: set[int] = set()
    with os.scandir(root / RECORDS_DIR) as entries:
        for entry in entries:
            stem, _, suffix = entry.name.partition(".")
            if suffix == "json" and stem.isdigit() and scene_stem(int(stem)) == stem:
                record = read_record(Path(entry.path))
                if record is not None and intact(root, record):
                    done.add(int(stem))
    return done


#: The record's key giving each of the scene's files its digest (relative path -> the
#: sha256 of its bytes); ``files`` lists the names.
FILES_KEY = "digests"


def intact(root: Path, record: dict) -> bool:
    """Whether every file a scene's record lists is there, with the bytes it was written
    with where the record has their digest (a record written before digests were kept
    has none); a scene that fails is made again."""
    names = record.get("files", [])
    digests = record.get(FILES_KEY, {})
    if not isinstance(names, list) or not isinstance(digests, dict):
        return False
    for relative in names:
        if (
            not isinstance(relative, str)
            or ".." in Path(relative).parts
            or Path(relative).is_absolute()
        ):
            return False  # a record never names a file outside the dataset
        try:
            data = (root / relative).read_bytes()
        except OSError:
            return False
        digest = digests.get(relative)
        if digest is not None and hashlib.sha256(data).hexdigest() != digest:
            return False
    return True


def pending_indices(count: int, done: set[int]) -> Iterator[int]:
    """The indices below ``count`` not in ``done``, in order, one at a time (never a list
    of N items: N may be far larger than what fits in memory)."""
    return (index for index in range(count) if index not in done)


def read_record(path: Path) -> dict | None:
    try:
        record = load_json(path.read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None
    return record if isinstance(record, dict) else None


def store_product(root: Path, product: SceneProduct) -> None:
    """Write a scene's files, then its record (the marker that the scene is done), which
    lists each file with its digest (``FILES_KEY``) so a resumed run can tell a file
    that went missing or was cut short (``intact``)."""
    digests = {}
    for relative, payload in sorted(product.files.items()):
        target = root / relative
        target.parent.mkdir(parents=True, exist_ok=True)
        data = payload.encode("utf-8") if isinstance(payload, str) else payload
        write_atomic(target, data)
        digests[str(relative)] = hashlib.sha256(data).hexdigest()
    record = json.dumps({**product.record(), FILES_KEY: digests}, ensure_ascii=False) + "\n"
    write_atomic(root / RECORDS_DIR / f"{scene_stem(product.index)}.json", record)


def publish_metadata(root: Path, count: int, coco=None) -> StatsCollector:
    """Rebuild metadata.jsonl from the records, in index order, one record at a time
    (a scene's rows: its views in order); return the records' statistics. Every record
    must exist (the run has finished). ``coco``: a ``coco.coco_writer`` to pass
    every record to as well, or None."""
    collector = StatsCollector()
    with atomic_stream(root / METADATA_FILE) as metadata, coco or nullcontext(None) as add_coco:
        for index in range(count):
            record = read_record(root / RECORDS_DIR / f"{scene_stem(index)}.json")
            if record is None:
                raise RuntimeError(f"scene {index} has no record after the run; rerun to finish it")
            collector.add(record)
            if record["row"] is not None:
                for row in [record["row"], *record.get("views", [])]:
                    metadata.write(json.dumps(row, ensure_ascii=False) + "\n")
            if add_coco is not None:
                add_coco(record)
    return collector


@contextmanager
def interrupts_deferred() -> Iterator[None]:
    """Hold Ctrl-C (SIGINT) back until the block ends, then deliver it.

    Wraps the calls that may start a pool worker: interrupted halfway, that start would
    leave a worker that fails on its own, with a traceback of its own, after the clean
    one-line report. Signals are handled in the main thread only; elsewhere (an API
    caller's thread) this does nothing, as it does when SIGINT's handler was installed
    by something other than Python (it could not be put back).
    """
    if (
        threading.current_thread() is not threading.main_thread()
        or signal.getsignal(signal.SIGINT) is None
    ):
        yield  # not the main thread, or a handler Python did not install: leave it alone
        return
    caught: list[int] = []
    previous = signal.signal(signal.SIGINT, lambda number, frame: caught.append(number))
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, previous)
        if caught:
            signal.raise_signal(signal.SIGINT)


def start_fork_server() -> None:
    """Start the fork server with SIGINT blocked. It inherits the blocked signal, and so
    does every worker forked from it: Ctrl-C on a terminal, sent to the whole process
    group, reaches only this process, which then stops the pool, instead of printing a
    KeyboardInterrupt traceback from the server's imports or from a worker. A signal
    that arrives meanwhile is delivered here when the block ends.

    The resource tracker starts first, on its own: starting it unblocks SIGINT in this
    thread (CPython blocks and then unblocks it around that start), which would undo the
    block if it happened inside ``forkserver.ensure_running``."""
    from multiprocessing import forkserver, resource_tracker

    resource_tracker.ensure_running()
    previous = signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGINT})
    try:
        forkserver.ensure_running()
    finally:
        signal.pthread_sigmask(signal.SIG_SETMASK, previous)


def start_worker(lifeline, spec: DatasetSpec | None) -> None:
    """A pool worker's initializer: leave Ctrl-C to the parent, exit as soon as the parent
    closes or loses the lifeline, and with ``spec``, warm up (rules parsed, renderer
    started) once for the worker's life.

    SIGINT is also ignored here for a fork server that ``start_fork_server`` did not
    start (one an API caller's process started earlier)."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    threading.Thread(
        target=exit_when_closed, args=(lifeline,), name="lifeline", daemon=True
    ).start()
    # The pool has a worker per core: a software OpenGL's own rasteriser threads would
    # only contend with the other workers (same images, more scenes a minute: the
    # figures are in docs/notes/measurements.md). Set before the worker's renderer
    # exists; a value the user gave is kept.
    os.environ.setdefault("LP_NUM_THREADS", "0")
    collect_less()
    if spec is not None:
        from scenewright.dataset.produce import worker_context

        try:
            worker_context(spec)
        except ScenewrightError:
            # Raised again by the worker's first scene, whose future carries it to the
            # parent as one line; raised here, it would only break the pool.
            pass


def exit_when_closed(lifeline) -> None:
    """Wait on the lifeline; nothing is ever sent, so it wakes only at end-of-file, when
    its one write end is closed: by ``WorkerPool.stop`` or by the kernel as the parent
    dies (even by SIGKILL). Then end this worker at once, whatever it was doing."""
    lifeline.poll(None)
    os._exit(1)


class WorkerPool(cf.ProcessPoolExecutor):
    """The process pool on this machine, whose workers never outlive this process.

    Workers start with ``forkserver`` (``spawn`` where it is missing): each creates its
    own OpenGL context, and a context must not be inherited through ``fork``. Each worker
    holds the read end of a pipe, the lifeline, whose only write end stays here, and a
    thread waiting on it (``start_worker``). When this process dies, even by ``kill
    -9``, the kernel closes the write end and every worker exits; the fork server then
    sees its last client gone and exits, and the resource tracker after it, so nothing
    is left running or holding the caller's stdout and stderr. Leaving the pool's
    ``with`` block with an error (Ctrl-C included) closes the lifeline first, so the
    workers stop at once rather than after their current scene.
    """

    def __init__(self, workers: int, warm_up: DatasetSpec | None) -> None:
        methods = multiprocessing.get_all_start_methods()
        context = multiprocessing.get_context("forkserver" if "forkserver" in methods else "spawn")
        if context.get_start_method() == "forkserver":
            # Import the pipeline once in the fork server rather than in every worker (the
            # imports take seconds); no OpenGL context exists yet at that point.
            context.set_forkserver_preload(WORKER_MODULES)
            start_fork_server()
        self._lifeline_read, self._lifeline = context.Pipe(duplex=False)
        super().__init__(
            max_workers=workers,
            mp_context=context,
            initializer=start_worker,
            initargs=(self._lifeline_read, warm_up),
        )
        self.workers = workers

    def slots(self) -> int:
        return self.workers

    def check(self) -> None:
        """Nothing to check while waiting: a worker that dies breaks the pool, and the
        pool reports that itself through the futures (``failure``)."""

    def failure(self, future: cf.Future) -> BaseException | None:
        """The error a finished future stands for, or None if it holds a scene."""
        error = future.exception()
        if isinstance(error, BrokenProcessPool):
            lost = GenerationError(
                "a worker process died (killed, or out of memory?); the scenes that finished are stored: "
                "rerun the same command to resume"
            )
            lost.__cause__ = error
            return lost
        return error

    def stop(self) -> None:
        """End every worker now (they exit as soon as the lifeline closes)."""
        self._lifeline.close()

    def __exit__(self, exc_type, exc_value, traceback) -> bool:
        if exc_type is not None:
            self.stop()
        with interrupts_deferred():
            self.shutdown(wait=True)
        self.stop()
        self._lifeline_read.close()
        return False


def make_executor(
    workers: int | None,
    pending: int,
    scheduler: str | None,
    producer: Producer,
    spec: DatasetSpec,
    worker_timeout: float | None,
    note: Callable[[str], None] | None,
):
    """Where the scenes are computed: a ``WorkerPool`` of ``pool_size(workers, pending)``
    processes, or with a dask.distributed ``scheduler`` address a
    ``cluster.ClusterExecutor`` (which tells ``note`` when it waits for a
    worker). Both are ``concurrent.futures`` executors that also offer ``slots()``
    (scenes made at once), ``check()`` (raise when no progress is possible) and
    ``failure(future)`` (the error a finished future stands for)."""
    if scheduler:
        from scenewright.dataset.cluster import WORKER_TIMEOUT, cluster_executor

        timeout = WORKER_TIMEOUT if worker_timeout is None else worker_timeout
        return cluster_executor(scheduler, timeout, note)
    from scenewright.dataset.produce import produce_scene

    return WorkerPool(pool_size(workers, pending), spec if producer is produce_scene else None)


def run_dataset(
    spec: DatasetSpec,
    directory: str | os.PathLike[str],
    *,
    workers: int | None = None,
    scheduler: str | None = None,
    producer: Producer | None = None,
    progress: bool = True,
    worker_timeout: float | None = None,
) -> RunReport:
    """Make (or finish) the dataset ``spec`` in ``directory``; return what was done.

    ``workers`` sizes the local process pool (default and maximum: one per CPU this
    process may use, and no more than the scenes left to make); with a dask
    ``scheduler`` address the cluster's workers are used instead, and
    ``worker_timeout`` is how long (seconds) the cluster may have no workers before the
    run gives up (``cluster.WORKER_TIMEOUT`` by default). ``producer`` computes
    one scene in a worker (default: the real pipeline, ``produce.produce_scene``);
    tests inject a cheap one. Holds the directory's lock throughout.
    """
    from scenewright.dataset.produce import produce_scene
    from scenewright.dataset.questions import publish_questions

    producer = producer or produce_scene
    with open_dataset(spec, directory) as root:
        done = finished_indices(root)
        skipped = sum(1 for index in done if index < spec.count)
        pending = spec.count - skipped
        started = time.perf_counter()
        made = failed_now = slots = 0
        if pending:
            note = progress_note if progress else None
            with make_executor(
                workers, pending, scheduler, producer, spec, worker_timeout, note
            ) as executor:
                slots = executor.slots()
                bar = progress_bar(pending, progress, skipped)
                try:
                    todo = pending_indices(spec.count, done)
                    for product in completed_products(
                        executor, producer, spec, todo, window=4 * slots
                    ):
                        store_product(root, product)
                        made += 1
                        failed_now += not product.ok
                        bar.set_postfix(failed=failed_now, refresh=False)
                        bar.update(1)
                finally:
                    bar.close()
        seconds = time.perf_counter() - started
        collector = publish_metadata(root, spec.count, coco_sink(root, spec))
        publish_questions(root, spec)
        stats = collector.summary(made=made, seconds=seconds)
        write_stats(root, stats)
    return RunReport(
        directory=root,
        count=spec.count,
        made=made,
        skipped=skipped,
        written=collector.written,
        failed=collector.failed,
        seconds=seconds,
        stats=stats,
        beyond=len(done) - skipped,
        workers=slots,
    )


def completed_products(
    executor, producer: Producer, spec: DatasetSpec, todo: Iterator[int], *, window: int
) -> Iterator[SceneProduct]:
    """Run ``producer`` over the indices ``todo`` yields, at most ``window`` at a time;
    yield the products as they finish.

    The window bounds memory (each product carries encoded images) and lets ``todo`` be
    consumed lazily. While nothing finishes for ``IDLE_CHECK`` seconds the executor is
    asked whether it can still make progress. The first error is raised here; the work
    still pending is the executor's to drop as its ``with`` block ends with that error
    (the pool stops its workers, the cluster cancels its tasks).
    """
    pending: set[cf.Future] = set()
    while True:
        with interrupts_deferred():
            for index in todo:
                pending.add(executor.submit(producer, spec, index))
                if len(pending) >= window:
                    break
        if not pending:
            return
        finished, pending = cf.wait(pending, timeout=IDLE_CHECK, return_when=cf.FIRST_COMPLETED)
        if not finished:
            executor.check()
            continue
        # Store every scene that did finish before reporting one that failed.
        outcomes = [(future, executor.failure(future)) for future in finished]
        for future, error in outcomes:
            if error is None:
                yield future.result()
        failures = [error for _, error in outcomes if error is not None]
        if failures:
            raise failures[0]


def progress_note(text: str) -> None:
    """A line about the run's progress that is not a count (waiting for a dask worker)."""
    print(text, file=sys.stderr, flush=True)


def progress_bar(total: int, enabled: bool, already: int, stream: TextIO | None = None):
    """Progress with rate and ETA on ``stream`` (stderr): a tqdm bar on a terminal,
    ``ProgressLines`` otherwise, a silent stand-in when disabled."""
    from tqdm import tqdm

    stream = stream or sys.stderr
    description = f"scenes ({already} already done)" if already else "scenes"
    if enabled and not stream.isatty():
        return ProgressLines(total, description, stream)
    return tqdm(
        total=total,
        unit="scene",
        desc=description,
        disable=not enabled,
        dynamic_ncols=True,
        file=stream,
    )


class ProgressLines:
    """Progress for a log: the bar's text (count, percentage, elapsed, ETA, rate,
    failures) as a plain line at most every ``interval`` seconds and at ``close`` (unless
    the last line already says it),
    so a long run leaves a readable line per interval rather than a redraw per scene.
    Offers the part of tqdm's interface ``run_dataset`` uses."""

    FORMAT = "{desc}: {n_fmt}/{total_fmt} ({percentage:.0f}%) [{elapsed}<{remaining}, {rate_fmt}{postfix}]"

    def __init__(
        self,
        total: int,
        description: str,
        stream: TextIO,
        *,
        interval: float = LOG_INTERVAL,
        clock=time.monotonic,
    ):
        self.total, self.description, self.stream = total, description, stream
        self.interval, self.clock = interval, clock
        self.count = 0
        self.shown: int | None = None  # the count the last line showed
        self.postfix = ""
        self.started = self.printed = clock()

    def set_postfix(self, *, refresh: bool = False, **values) -> None:
        self.postfix = ", ".join(f"{key}={value}" for key, value in values.items())

    def update(self, n: int = 1) -> None:
        self.count += n
        if self.clock() - self.printed >= self.interval:
            self._print()

    def close(self) -> None:
        if self.shown != self.count:
            self._print()

    def _print(self) -> None:
        from tqdm import tqdm

        self.printed, self.shown = self.clock(), self.count
        line = tqdm.format_meter(
            self.count,
            self.total,
            self.printed - self.started,
            prefix=self.description,
            unit="scene",
            postfix=self.postfix,
            bar_format=self.FORMAT,
        )
        print(line, file=self.stream, flush=True)
