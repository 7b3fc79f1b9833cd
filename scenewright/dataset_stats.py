"""A dataset's statistics: stats.json and a stats.png overview, built from the records.

Counts (scenes, written, failed, the most frequent layout problems), object type and
relation label frequencies (with how often each relation held), caption and text
lengths in words, and seconds per pipeline stage. Frequencies cover every scene that
was generated, failed ones included, so a failing rule shows up. Times are wall clock,
so stats.json, unlike the rest of the dataset, differs between runs.
"""

from __future__ import annotations

import io
import json
import re
from collections import Counter
from pathlib import Path

import numpy as np

from scenewright.atomic import write_atomic

STATS_JSON = "stats.json"
STATS_PNG = "stats.png"


class StatsCollector:
    """Adds up per-scene records one at a time (a dataset's records need not fit in memory)."""

    def __init__(self) -> None:
        self.scenes = self.written = self.failed = 0
        self.objects: Counter = Counter()
        self.relations: dict[str, list[int]] = {}
        self.problems: Counter = Counter()
        self.text_words: list[int] = []
        self.caption_words: list[int] = []
        self.stage_seconds: dict[str, list[float]] = {}

    def add(self, record: dict) -> None:
        self.scenes += 1
        self.written += record["row"] is not None
        self.failed += not record["ok"]
        stats = record["stats"]
        self.objects.update(stats.get("objects", {}))
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

    def summary(self, *, made: int, seconds: float) -> dict:
        """The stats.json dictionary; ``made`` and ``seconds`` describe this run only."""
        by_count = sorted(self.relations.items(), key=lambda item: (-item[1][0], item[0]))
        return {
            "scenes": self.scenes,
            "written": self.written,
            "failed": self.failed,
            "failure_rate": round(self.failed / self.scenes, 4) if self.scenes else 0.0,
            "problems": dict(self.problems.most_common(20)),
            "objects": dict(sorted(self.objects.items(), key=lambda item: (-item[1], item[0]))),
            "relations": {label: {"total": total, "satisfied": held} for label, (total, held) in by_count},
            "words": {
                "text": distribution(self.text_words, bins=12),
                "caption": distribution(self.caption_words, bins=12),
            },
            "seconds_per_stage": {
                stage: distribution(values, digits=4) for stage, values in self.stage_seconds.items()
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
        summary["histogram"] = {"edges": [round(float(e), digits) for e in edges], "counts": counts.tolist()}
    return summary


def write_stats(root: Path, stats: dict) -> None:
    """Write stats.json and the stats.png overview into the dataset directory."""
    write_atomic(root / STATS_JSON, json.dumps(stats, indent=1, ensure_ascii=False) + "\n")
    write_atomic(root / STATS_PNG, stats_figure(stats))


def stats_figure(stats: dict) -> bytes:
    """A 2x2 PNG: object frequencies, relations held, text lengths, seconds per stage."""
    import matplotlib  # only here: a dataset run needs it once, at the end

    matplotlib.use("Agg")
    from matplotlib.figure import Figure

    figure = Figure(figsize=(12, 9), dpi=80, layout="constrained")
    axes = figure.subplots(2, 2)
    figure.suptitle(f"{stats['scenes']} scenes, {stats['written']} written, {stats['failed']} failed layouts")

    top_objects = list(stats["objects"].items())[:20]
    bars(axes[0, 0], [name for name, _ in top_objects], [n for _, n in top_objects], "objects (top 20 types)")

    labels = list(stats["relations"])
    totals = [stats["relations"][label]["total"] for label in labels]
    held = [stats["relations"][label]["satisfied"] for label in labels]
    bars(axes[0, 1], labels, totals, "relations: total (light) and satisfied (dark)", alpha=0.35)
    axes[0, 1].barh(labels, held, color="tab:blue")

    lengths = axes[1, 0]
    described = {name: summary for name, summary in stats["words"].items() if summary["count"]}
    for name, summary in described.items():
        histogram = summary["histogram"]
        label = f"{name} (median {summary['median']:g})"
        lengths.stairs(histogram["counts"], histogram["edges"], fill=True, alpha=0.6, label=label)
    lengths.set_title("length in words (full text, short captions)")
    lengths.set_xlabel("words")
    lengths.set_ylabel("texts")
    if described:
        lengths.legend()

    stages = stats["seconds_per_stage"]
    bars(axes[1, 1], list(stages), [stages[s]["mean"] for s in stages], "mean seconds per scene and stage")

    buffer = io.BytesIO()
    figure.savefig(buffer, format="png")
    return buffer.getvalue()


def bars(axis, names: list[str], values: list[float], title: str, alpha: float = 1.0) -> None:
    axis.barh(names, values, color="tab:blue", alpha=alpha)
    axis.invert_yaxis()
    axis.set_title(title)
    axis.tick_params(axis="y", labelsize=8)
