"""A dataset's statistics: stats.json and a stats.png overview, built from the records.

Counts (scenes, written, failed, the most frequent layout problems, the errors of
scenes the rules could not make), the layout retries scenes needed by their number of
objects, object type and relation label frequencies (with how often each relation
held), caption and text lengths in words, and seconds per pipeline stage (wall clock,
and the worker's CPU time, which a busy machine does not inflate as much). Frequencies
cover every scene that was generated, failed ones included, so a failing rule shows up.
Times differ between runs, so stats.json, unlike the rest of the dataset, does too.
"""

from __future__ import annotations

import json
import re
from collections import Counter
from pathlib import Path

import numpy as np

from scenewright.core.atomic import write_atomic

from .stats_sheet import stats_sheet

STATS_JSON = "stats.json"
STATS_PNG = "stats.png"
#: Scene sizes (objects per scene) are counted in at most this many bins of equal width.
SIZE_BINS = 8


class StatsCollector:
    """Adds up per-scene records one at a time (a dataset's records need not fit in memory)."""

    def __init__(self) -> None:
        self.scenes = self.written = self.failed = 0
        self.objects: Counter = Counter()
        self.relations: dict[str, list[int]] = {}
        self.problems: Counter = Counter()
        self.errors: dict[str, Counter] = {}
        self.failed_layouts = 0
        self.tries: list[
            tuple[int, int, bool]
        ] = []  # (objects, layouts tried, ok) per laid-out scene
        self.text_words: list[int] = []
        self.caption_words: list[int] = []
        self.stage_seconds: dict[str, list[float]] = {}
        self.stage_cpu: dict[str, list[float]] = {}

    def add(self, record: dict) -> None:
        self.scenes += 1
        self.written += record["row"] is not None
        self.failed += not record["ok"]
        stats = record["stats"]
        if "error" in stats:  # the rules could not make this scene: nothing else to count
            error = stats["error"]
            self.errors.setdefault(error["stage"], Counter())[error_kind(error["message"])] += 1
            return
        self.failed_layouts += not record["ok"]
        objects = stats.get("objects", {})
        self.tries.append((sum(objects.values()), stats.get("attempts", 1), record["ok"]))
        self.objects.update(objects)
        for label, (total, satisfied) in stats.get("relations", {}).items():
            counts = self.relations.setdefault(label, [0, 0])
            counts[0] += total
            counts[1] += satisfied
        self.problems.update(problem_kind(p) for p in stats.get("problems", []))
        words = stats.get("words", {})
        if words:
            self.text_words.append(words["text"])
            self.caption_words.extend(words["captions"])
        for stage, value in stats.get("seconds", {}).items():
            self.stage_seconds.setdefault(stage, []).append(value)
        for stage, value in stats.get("cpu", {}).items():
            self.stage_cpu.setdefault(stage, []).append(value)

    def summary(self, *, made: int, seconds: float) -> dict:
        """The stats.json dictionary; ``made`` and ``seconds`` describe this run only."""
        by_count = sorted(self.relations.items(), key=lambda item: (-item[1][0], item[0]))
        return {
            "scenes": self.scenes,
            "written": self.written,
            "failed": self.failed,
            "failure_rate": round(self.failed / self.scenes, 4) if self.scenes else 0.0,
            "failed_layouts": self.failed_layouts,
            "problems": dict(self.problems.most_common(20)),
            "errors": {
                stage: {"scenes": sum(kinds.values()), "messages": dict(kinds.most_common(20))}
                for stage, kinds in sorted(self.errors.items())
            },
            "retries": retries_by_size(self.tries),
            "objects": dict(sorted(self.objects.items(), key=lambda item: (-item[1], item[0]))),
            "relations": {
                label: {"total": total, "satisfied": held} for label, (total, held) in by_count
            },
            "words": {
                "text": distribution(self.text_words, bins=12),
                "caption": distribution(self.caption_words, bins=12),
            },
            "seconds_per_stage": {
                stage: distribution(values, digits=4)
                for stage, values in self.stage_seconds.items()
            },
            "cpu_seconds_per_stage": {
                stage: distribution(values, digits=4) for stage, values in self.stage_cpu.items()
            },
            "this_run": {
                "scenes_made": made,
                "seconds": round(seconds, 3),
                "scenes_per_minute": round(60.0 * made / seconds, 1) if seconds > 0 else 0.0,
            },
        }


def problem_kind(problem: str) -> str:
    """A layout problem with ids reduced to types and numbers to ``#``, so alike problems
    count together: "sign_3 is not next to table_2 (distance 3.4 m)" -> "sign is not
    next to table (distance # m)"."""
    typed = re.sub(r"_\d+\b", "", problem)
    return re.sub(r"\d+(?:\.\d+)?", "#", typed)


def error_kind(message: str) -> str:
    """An error with what varies between seeds left out, so the errors of one cause count
    together: an expansion error without the chain of productions that led to it
    ("r.rules:9:31: expansion deeper than max_depth 3 (expanding Row -> Row)" ->
    "r.rules:9:31: expansion deeper than max_depth 3"); its location stays as written."""
    return re.sub(r" \(expanding .*\)$", "", message)


def retries_by_size(tries: list[tuple[int, int, bool]]) -> dict:
    """How many layout retries scenes needed, overall and by their number of objects.

    ``tries`` holds (objects, layouts tried, ok) per laid-out scene. The sizes fall in
    at most ``SIZE_BINS`` bins of equal whole-number width from the smallest scene up;
    each bin says its scenes, those that needed a retry, the retries, the mean layouts
    per scene and the scenes still failed after the last one.
    """
    if not tries:
        return {"scenes_retried": 0, "retries": 0, "failed_after_retries": 0, "by_objects": []}
    sizes = np.array([objects for objects, _, _ in tries])
    attempts = np.array([tried for _, tried, _ in tries])
    failed = np.array([not ok for _, _, ok in tries])
    low = int(sizes.min())
    width = max(1, -(-(int(sizes.max()) - low + 1) // SIZE_BINS))  # ceiling division
    bins = (sizes - low) // width
    by_objects = []
    for k in np.unique(bins):
        inside = bins == k
        first = low + int(k) * width
        by_objects.append(
            {
                "objects": f"{first}-{first + width - 1}" if width > 1 else str(first),
                "scenes": int(inside.sum()),
                "retried": int((attempts[inside] > 1).sum()),
                "retries": int((attempts[inside] - 1).sum()),
                "mean_layouts": round(float(attempts[inside].mean()), 3),
                "failed_after_retries": int(failed[inside].sum()),
            }
        )
    return {
        "scenes_retried": int((attempts > 1).sum()),
        "retries": int((attempts - 1).sum()),
        "failed_after_retries": int(failed.sum()),
        "by_objects": by_objects,
    }


def distribution(values: list[float], digits: int = 2, bins: int = 0) -> dict:
    """Count, min, median, mean, p90, max and total; with ``bins``, a histogram too."""
    if not values:
        return {"count": 0}
    data = np.asarray(values, dtype=float)
    summary = {
        "count": int(data.size),
        "min": round(float(data.min()), digits),
        "median": round(float(np.median(data)), digits),
        "mean": round(float(data.mean()), digits),
        "p90": round(float(np.percentile(data, 90)), digits),
        "max": round(float(data.max()), digits),
        "total": round(float(data.sum()), digits),
    }
    if bins:
        counts, edges = np.histogram(data, bins=bins)
        summary["histogram"] = {
            "edges": [round(float(e), digits) for e in edges],
            "counts": counts.tolist(),
        }
    return summary


def write_stats(root: Path, stats: dict) -> None:
    """Write stats.json and the stats.png overview into the dataset directory."""
    write_atomic(root / STATS_JSON, json.dumps(stats, indent=1, ensure_ascii=False) + "\n")
    write_atomic(root / STATS_PNG, stats_sheet(stats))
