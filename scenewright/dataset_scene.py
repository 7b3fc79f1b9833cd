"""One dataset scene, made inside a worker process: generate, caption, render, encode.

A worker keeps a ``WorkerContext`` for its whole life: the parsed rules and one
``Renderer`` (one OpenGL context), made once by ``worker_context`` (the process pool's
initializer, or lazily on a dask worker). An OpenGL context is current in one thread
only, so a worker process running several threads (a dask worker with ``--nthreads``
above 1) gets one context per thread. ``produce_scene`` turns a scene index into a
``SceneProduct``: the encoded files and the scene's record. It writes nothing into the
dataset directory; the parent process does (``dataset.store_product``).
"""

from __future__ import annotations

import threading
from collections import Counter
from dataclasses import dataclass
from typing import TYPE_CHECKING

from scenewright.api import build_scene, describe, describe_scene, render_scene, reproducible_json, timed, timings_of
from scenewright.dataset import DatasetSpec, SceneProduct, scene_seed, scene_stem
from scenewright.core.errors import ScenewrightError
from scenewright.core.scene import Scene

if TYPE_CHECKING:
    from scenewright.generator.rules import Rules
    from scenewright.render.offscreen import Renderer


@dataclass
class WorkerContext:
    """What a worker builds once and reuses for every scene it makes."""

    settings: dict
    rules: Rules
    renderer: Renderer


_per_thread = threading.local()


def worker_context(spec: DatasetSpec) -> WorkerContext:
    """This thread's rules and renderer for ``spec``, made on first use."""
    context: WorkerContext | None = getattr(_per_thread, "context", None)
    if context is None or context.settings != spec.settings():
        from scenewright.api import load_rules
        from scenewright.render.offscreen import Renderer

        if context is not None:
            context.renderer.close()
        context = WorkerContext(spec.settings(), load_rules(spec.rules), Renderer(*spec.size))
        _per_thread.context = context
    return context


def produce_scene(spec: DatasetSpec, index: int) -> SceneProduct:
    """Make scene ``index`` of ``spec``: its files (images, scene.json) and its record."""
    from scenewright.render.offscreen import encode_render

    context = worker_context(spec)
    seed = scene_seed(spec.base_seed, index)
    stem = scene_stem(index)
    try:
        scene = build_scene(context.rules, seed, templates=spec.templates)
    except ScenewrightError as error:  # e.g. an expansion that hit the rules' bounds
        return SceneProduct(index, seed, False, {}, None, {"problems": [str(error)]})
    if not scene.layout.ok and not spec.include_failed:
        failed = {f"failed/{stem}.json": reproducible_json(scene).encode()}
        return SceneProduct(index, seed, False, failed, None, scene_stats(scene, []))

    scene = describe_scene(scene, style="full")
    with timed(scene.timings, "describe"):
        captions = [describe(scene, style="short", variant=k).text for k in range(spec.captions)]
    scene, result = render_scene(scene, size=spec.size, view=spec.view, renderer=context.renderer)
    images = {kind: data for kind, (_, data) in encode_render(result).items()}

    files = {f"images/{stem}.png": images["colour"]}
    row: dict = {"file_name": f"images/{stem}.png"}
    if spec.depth:
        files[f"depth/{stem}.png"] = images["depth"]
        row["depth_file_name"] = f"depth/{stem}.png"
    if spec.segmentation:
        files[f"segmentation/{stem}.png"] = images["segmentation"]
        files[f"segmentation/{stem}_ids.json"] = images["ids"]
        row["segmentation_file_name"] = f"segmentation/{stem}.png"
    files[f"scenes/{stem}.json"] = reproducible_json(scene).encode()
    full_text = scene.description["text"]
    row.update(caption=captions[0], text=full_text)
    row.update({f"caption_{k}": caption for k, caption in enumerate(captions[1:], start=1)})
    row.update(scene_id=stem, seed=seed, rules=spec.rules, ok=scene.layout.ok)
    return SceneProduct(index, seed, scene.layout.ok, files, row, scene_stats(scene, [full_text, *captions]))


def scene_stats(scene: Scene, texts: list[str]) -> dict:
    """What stats.json aggregates over scenes: objects, relations, text lengths, times."""
    relations: dict[str, list[int]] = {}
    for relation in scene.relations:
        counts = relations.setdefault(relation.label, [0, 0])
        counts[0] += 1
        counts[1] += relation.satisfied
    return {
        "objects": dict(Counter(o.type for o in scene.placed_objects())),
        "relations": relations,
        "words": {"text": len(texts[0].split()), "captions": [len(t.split()) for t in texts[1:]]}
        if texts
        else {},
        "seconds": timings_of(scene),
        "problems": list(scene.layout.problems),
    }
