"""Datasets: N scenes from one rule set, written in the Hugging Face ``imagefolder`` layout.

Seeds. Scene ``i`` of a dataset with base seed ``b`` uses the seed
``SeedSequence([b, i]).generate_state(1)[0]`` (``scene_seed``): it depends on nothing
but ``(b, i)``, so any scene can be regenerated alone and the bytes on disk do not
depend on the number of workers or on the order in which scenes finish.

On disk (``DIR``)::

    dataset.json           the settings; a rerun must use the same ones (count may grow)
    metadata.jsonl         one row per written scene, ordered by index
    images/000000.png      the preview
    scenes/000000.json     scene.json (no wall-clock times: reproducible)
    depth/, segmentation/  optional ground truth (16-bit PNGs)
    failed/000003.json     scene.json of a scene whose layout failed (not in metadata)
    stats.json, stats.png  counts, frequencies, caption lengths, time per stage
    .records/000000.json   one record per finished scene: the commit marker for resume

Every file is written atomically; a scene counts as done only once its record exists,
and the record is written after the scene's files. A run that is killed therefore
resumes where it stopped: finished scenes are skipped, a half-finished one is made
again (with the same bytes), and ``metadata.jsonl`` and the statistics are rebuilt
from the records at the end.

Work runs on a process pool (one machine) or on a dask.distributed cluster (several);
workers compute and encode, and only this process writes to ``DIR``, so a cluster's
workers need no shared filesystem.
"""

from __future__ import annotations

import concurrent.futures as cf
import hashlib
import json
import multiprocessing
import os
import sys
import time
from collections.abc import Callable, Iterator
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import TextIO

import numpy as np

from scenewright.atomic import atomic_stream, remove_partials, write_atomic
from scenewright.dataset_stats import StatsCollector, write_stats
from scenewright.core.errors import InputError

#: The settings that must not change when a run is resumed into the same directory.
SETTINGS_FILE = "dataset.json"
RECORDS_DIR = ".records"
METADATA_FILE = "metadata.jsonl"
#: What a worker imports; a fork server imports it once for all its workers.
WORKER_MODULES = ["scenewright.generator.layout", "scenewright.describer", "scenewright.dataset_scene"]
#: When stderr is not a terminal (a log file, a batch job), progress is a plain line at
#: most this often (seconds) and one at the end, not a bar redrawn after every scene.
LOG_INTERVAL = 30.0


def scene_seed(base_seed: int, index: int) -> int:
    """The seed of scene ``index`` in a dataset with ``base_seed`` (a 32-bit integer)."""
    return int(np.random.SeedSequence([base_seed, index]).generate_state(1)[0])


def default_workers() -> int:
    """One worker per core this process may run on (its CPU affinity, not the machine's)."""
    if hasattr(os, "sched_getaffinity"):
        return len(os.sched_getaffinity(0))
    return os.cpu_count() or 1


def scene_stem(index: int) -> str:
    return f"{index:06d}"


@dataclass(frozen=True)
class DatasetSpec:
    """What to make. Everything here except ``count`` is fixed for a dataset directory.

    ``rules`` is how the user named the rule set (shipped name or path) and
    ``rules_digest`` a hash of its text, so a resumed run cannot silently mix rule
    versions. ``captions`` is the number of short captions per scene (variants 0..K-1).
    ``templates`` is the absolute path of a description templates folder that replaces
    the rule set's own, or None.
    """

    rules: str
    rules_digest: str
    count: int
    base_seed: int = 0
    captions: int = 1
    templates: str | None = None
    size: tuple[int, int] = (512, 512)
    view: str = "perspective"
    depth: bool = False
    segmentation: bool = False
    include_failed: bool = False

    def settings(self) -> dict:
        """The fixed part, as stored in ``dataset.json``."""
        data = asdict(self)
        data["size"] = list(self.size)
        del data["count"]
        return data


def dataset_spec(
    rules, count: int, *, templates: str | os.PathLike[str] | None = None, **settings
) -> DatasetSpec:
    """The spec for ``count`` scenes of a rule set (name, path or loaded Rules).

    Loads (and so checks) the rules and the description templates the scenes will use
    (``templates``, else the rule set's own), names the rules as scene.json does, and
    hashes their text. ``settings`` are the other ``DatasetSpec`` fields.
    """
    from scenewright.api import checked_templates, load_rules, rules_label

    loaded = load_rules(rules)
    if templates is None:
        checked_templates(loaded.params.templates)  # a broken one stops the run before any work
    else:
        templates = checked_templates(templates)
    digest = hashlib.sha256(Path(loaded.path).read_bytes()).hexdigest()
    return DatasetSpec(
        rules=rules_label(loaded), rules_digest=digest, count=count, templates=templates, **settings
    )


@dataclass
class SceneProduct:
    """What a worker returns for one scene: files to write and the scene's record.

    ``files`` maps paths relative to the dataset directory to their bytes. ``row`` is
    the scene's metadata.jsonl row, or None when the scene is left out (failed layout
    without ``include_failed``). ``stats`` feeds stats.json (see ``dataset_stats``).
    """

    index: int
    seed: int
    ok: bool
    files: dict[str, bytes]
    row: dict | None
    stats: dict = field(default_factory=dict)

    def record(self) -> dict:
        return {
            "index": self.index,
            "seed": self.seed,
            "ok": self.ok,
            "files": sorted(self.files),
            "row": self.row,
            "stats": self.stats,
        }


#: Computes one scene in a worker process: ``produce(spec, index) -> SceneProduct``.
Producer = Callable[[DatasetSpec, int], SceneProduct]


@dataclass
class RunReport:
    """What a run did: how many scenes exist, how many this run made, how long it took."""

    directory: Path
    count: int
    made: int
    skipped: int
    written: int
    failed: int
    seconds: float
    stats: dict = field(default_factory=dict)

    @property
    def scenes_per_minute(self) -> float:
        return 60.0 * self.made / self.seconds if self.seconds > 0 else 0.0


def prepare_directory(spec: DatasetSpec, directory: str | os.PathLike[str]) -> Path:
    """Create or reopen a dataset directory; refuse one made with other settings."""
    root = Path(directory)
    settings_path = root / SETTINGS_FILE
    try:
        root.mkdir(parents=True, exist_ok=True)
        if settings_path.exists():
            check_same_settings(spec, json.loads(settings_path.read_text()), root)
        elif any(root.iterdir()):
            raise InputError(f"{root} is not empty and holds no scenewright dataset; choose a new directory")
        for sub in ("images", "scenes", RECORDS_DIR):
            (root / sub).mkdir(exist_ok=True)
        remove_partials(root)
        write_atomic(settings_path, json.dumps({**spec.settings(), "count": spec.count}, indent=1) + "\n")
    except OSError as error:
        raise InputError(f"cannot write the dataset to {root}: {error.strerror or error}") from error
    return root


def check_same_settings(spec: DatasetSpec, stored: dict, root: Path) -> None:
    differing = [key for key, value in spec.settings().items() if stored.get(key) != value]
    if differing:
        details = ", ".join(f"{key} {stored.get(key)!r} -> {spec.settings()[key]!r}" for key in differing)
        raise InputError(f"{root} holds a dataset made with other settings ({details}); use a new directory")
    if spec.count < int(stored.get("count", 0)):
        raise InputError(
            f"{root} already holds a dataset of {stored['count']} scenes; a rerun may keep or raise -n, not lower it"
        )


def finished_indices(root: Path, count: int) -> set[int]:
    """Indices whose record exists and reads back: those scenes are done."""
    done: set[int] = set()
    for path in (root / RECORDS_DIR).glob("*.json"):
        if path.stem.isdigit() and int(path.stem) < count and read_record(path) is not None:
            done.add(int(path.stem))
    return done


def read_record(path: Path) -> dict | None:
    try:
        return json.loads(path.read_text())
    except (OSError, ValueError):
        return None


def store_product(root: Path, product: SceneProduct) -> None:
    """Write a scene's files, then its record (the marker that the scene is done)."""
    for relative, payload in sorted(product.files.items()):
        target = root / relative
        target.parent.mkdir(parents=True, exist_ok=True)
        write_atomic(target, payload)
    record = json.dumps(product.record(), ensure_ascii=False) + "\n"
    write_atomic(root / RECORDS_DIR / f"{scene_stem(product.index)}.json", record)


def publish_metadata(root: Path, count: int) -> StatsCollector:
    """Rebuild metadata.jsonl from the records, in index order, one record at a time;
    return the records' statistics. Every record must exist (the run has finished)."""
    collector = StatsCollector()
    with atomic_stream(root / METADATA_FILE) as metadata:
        for index in range(count):
            record = read_record(root / RECORDS_DIR / f"{scene_stem(index)}.json")
            if record is None:
                raise RuntimeError(f"scene {index} has no record after the run; rerun to finish it")
            collector.add(record)
            if record["row"] is not None:
                metadata.write(json.dumps(record["row"], ensure_ascii=False) + "\n")
    return collector


def make_executor(
    workers: int, scheduler: str | None, producer: Producer, spec: DatasetSpec
) -> tuple[cf.Executor, int]:
    """A process pool on this machine, or an executor on a dask.distributed scheduler,
    with the number of scenes it works on at once (``workers``, or the cluster's threads).

    Pool workers start with ``forkserver`` (``spawn`` where it is missing): each creates
    its own OpenGL context, and a context must not be inherited through ``fork``. Each
    worker warms up once (rules parsed, renderer started) and keeps that for its life.
    """
    if scheduler:
        from scenewright.dataset_cluster import cluster_executor

        executor = cluster_executor(scheduler)
        return executor, executor.slots()
    from scenewright.dataset_scene import produce_scene, worker_context

    methods = multiprocessing.get_all_start_methods()
    context = multiprocessing.get_context("forkserver" if "forkserver" in methods else "spawn")
    if context.get_start_method() == "forkserver":
        # Import the pipeline once in the fork server rather than in every worker (the
        # imports take seconds); no OpenGL context exists yet at that point.
        context.set_forkserver_preload(WORKER_MODULES)
    warm_up = worker_context if producer is produce_scene else None
    pool = cf.ProcessPoolExecutor(
        max_workers=workers, mp_context=context, initializer=warm_up, initargs=(spec,)
    )
    return pool, workers


def run_dataset(
    spec: DatasetSpec,
    directory: str | os.PathLike[str],
    *,
    workers: int | None = None,
    scheduler: str | None = None,
    producer: Producer | None = None,
    progress: bool = True,
) -> RunReport:
    """Make (or finish) the dataset ``spec`` in ``directory``; return what was done.

    ``workers`` sizes the local process pool (default: one per core); with a dask
    ``scheduler`` address the cluster's workers are used instead. ``producer`` computes
    one scene in a worker (default: the real pipeline, ``dataset_scene.produce_scene``);
    tests inject a cheap one.
    """
    from scenewright.dataset_scene import produce_scene

    producer = producer or produce_scene
    workers = workers or default_workers()
    root = prepare_directory(spec, directory)
    todo = [i for i in range(spec.count) if i not in finished_indices(root, spec.count)]
    started = time.perf_counter()
    made = failed_now = 0
    if todo:
        executor, slots = make_executor(workers, scheduler, producer, spec)
        with executor:
            bar = progress_bar(len(todo), progress, spec.count - len(todo))
            for product in completed_products(executor, producer, spec, todo, window=4 * slots):
                store_product(root, product)
                made += 1
                failed_now += not product.ok
                bar.set_postfix(failed=failed_now, refresh=False)
                bar.update(1)
            bar.close()
    seconds = time.perf_counter() - started
    collector = publish_metadata(root, spec.count)
    stats = collector.summary(made=made, seconds=seconds)
    write_stats(root, stats)
    return RunReport(
        directory=root,
        count=spec.count,
        made=made,
        skipped=spec.count - len(todo),
        written=collector.written,
        failed=collector.failed,
        seconds=seconds,
        stats=stats,
    )


def completed_products(
    executor: cf.Executor, producer: Producer, spec: DatasetSpec, todo: list[int], *, window: int
) -> Iterator[SceneProduct]:
    """Run ``producer`` over ``todo``, at most ``window`` at a time; yield as they finish.

    The window bounds memory (each product carries encoded images). The first error
    stops the run: pending work is cancelled and the error is raised here.
    """
    pending: set[cf.Future] = set()
    queue = iter(todo)
    try:
        while True:
            for index in queue:
                pending.add(executor.submit(producer, spec, index))
                if len(pending) >= window:
                    break
            if not pending:
                return
            finished, pending = cf.wait(pending, return_when=cf.FIRST_COMPLETED)
            # Store every scene that did finish before reporting one that failed.
            failures = [future.exception() for future in finished if future.exception() is not None]
            for future in finished:
                if future.exception() is None:
                    yield future.result()
            if failures:
                raise failures[0]
    finally:
        for future in pending:
            future.cancel()


def progress_bar(total: int, enabled: bool, already: int, stream: TextIO | None = None):
    """Progress with rate and ETA on ``stream`` (stderr): a tqdm bar on a terminal,
    ``ProgressLines`` otherwise, a silent stand-in when disabled."""
    from tqdm import tqdm

    stream = stream or sys.stderr
    description = f"scenes ({already} already done)" if already else "scenes"
    if enabled and not stream.isatty():
        return ProgressLines(total, description, stream)
    return tqdm(total=total, unit="scene", desc=description, disable=not enabled, dynamic_ncols=True, file=stream)


class ProgressLines:
    """Progress for a log: the bar's text (count, percentage, elapsed, ETA, rate,
    failures) as a plain line at most every ``interval`` seconds and at ``close`` (unless
    the last line already says it),
    so a long run leaves a readable line per interval rather than a redraw per scene.
    Offers the part of tqdm's interface ``run_dataset`` uses."""

    FORMAT = "{desc}: {n_fmt}/{total_fmt} ({percentage:.0f}%) [{elapsed}<{remaining}, {rate_fmt}{postfix}]"

    def __init__(
        self, total: int, description: str, stream: TextIO, *, interval: float = LOG_INTERVAL, clock=time.monotonic
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
            self.count, self.total, self.printed - self.started, prefix=self.description, unit="scene",
            postfix=self.postfix, bar_format=self.FORMAT,
        )  # fmt: skip
        print(line, file=self.stream, flush=True)
