"""Writing variants: one folder per variant, as ``scenewright generate`` writes a scene,
and an index.

``write_variants(results, examples, directory, seed, render=...)`` fills ``directory``
(replaced as a whole, ``scenewright.atomic.staged_outputs``: all folders appear
together or not at all) with ``variant_001/``, ``variant_002/``, ... in rank order (best
K first), each holding scene.json (with a ``synthesis`` record: the base example, the
operations with their compatibilities, K, and each object's source example and id),
description.txt, scene.glb, plan.png and, when rendering, the previews; and index.json
listing every variant with its K, operations, layout verdict and whether it is new
(its type multiset or its relation set differs from every example's).
"""

from __future__ import annotations

import json
import os
from collections import Counter
from pathlib import Path

from scenewright.examples import Example

from .structure import structure_graph
from .synthesis import Result

#: The names the output directory is made of (replaced as a whole).
FOLDERS = frozenset([f"variant_{k:03d}" for k in range(1, 10000)] + ["index.json"])


def fingerprint(scene) -> tuple:
    """(type multiset, relation set) of a scene: what makes a variant new."""
    graph = structure_graph(scene)
    types = tuple(sorted(Counter(graph.types).items()))
    relations = frozenset(
        (graph.types[i], graph.types[j], frozenset(edge.relations))
        for (i, j), edge in graph.edges.items()
        if edge.relations
    )
    return types, relations


def is_new(result: Result, examples: list[Example]) -> bool:
    types, relations = fingerprint(result.scene)
    return all(types != t or relations != r for t, r in (fingerprint(e.scene) for e in examples))


def write_variants(
    results: list[Result],
    examples: list[Example],
    directory: str | os.PathLike[str],
    seed: int,
    *,
    render: bool = False,
    size: tuple[int, int] = (640, 480),
    view: str = "perspective",
) -> dict:
    """Write the variants and index.json; return the index."""
    from scenewright.api import describe_scene, export, render_scene, reproducible_json
    from scenewright.atomic import staged_outputs, write_atomic, writing
    from scenewright.render.offscreen import save_render
    from scenewright.render.plan import draw_plan

    index = {
        "seed": seed,
        "examples": [{"name": e.name, "path": e.path} for e in examples],
        "variants": [],
    }
    with staged_outputs(directory, FOLDERS) as stage:
        for rank, result in enumerate(results, start=1):
            folder = stage / f"variant_{rank:03d}"
            folder.mkdir()
            scene = describe_scene(result.scene)
            if render:
                scene, images = render_scene(scene, size=size, view=view)
                save_render(images, folder, stem="preview")
            export(scene, folder / "scene.glb")
            with writing(folder / "plan.png"):
                draw_plan(scene, folder / "plan.png")
            data = json.loads(reproducible_json(scene))
            data["synthesis"] = result.synthesis()
            write_atomic(
                folder / "scene.json", json.dumps(data, indent=1, ensure_ascii=False) + "\n"
            )
            write_atomic(folder / "description.txt", scene.description.text + "\n")
            index["variants"].append(
                {
                    "folder": folder.name,
                    "base": result.base,
                    "compatibility": round(result.compatibility, 6),
                    "operations": [op["operation"] for op in result.operations],
                    "ok": scene.layout.ok,
                    "objects": len(scene.placed_objects()),
                    "new": is_new(result, examples),
                }
            )
        write_atomic(stage / "index.json", json.dumps(index, indent=1) + "\n")
    return index


def summary(index: dict, directory: str | os.PathLike[str]) -> str:
    variants = index["variants"]
    ok = sum(v["ok"] for v in variants)
    new = sum(v["new"] for v in variants)
    best = (
        f", K from {variants[-1]['compatibility']:.2f} to {variants[0]['compatibility']:.2f}"
        if variants
        else ""
    )
    return f"wrote {Path(directory)}/: {len(variants)} variants ({ok} ok, {new} new){best}; index.json lists them"
