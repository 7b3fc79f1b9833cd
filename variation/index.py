"""The index of ``vary``'s output: which variant is which, and which are new.

``scenewright.scene_folder.write_variants`` writes each variant as a scene folder
(``variant_001/``, ``variant_002/``, ... in rank order, best first) and index.json,
built here: per variant its K, operations, layout verdict and whether it is new (its
multiset of (type, style) or its relation set differs from every example's). ``summary`` is the
line the command prints, with how many operations of each kind the variants took.
"""

from __future__ import annotations

import os
from collections import Counter
from pathlib import Path

from scenewright.examples import Example

from .structure import structure_graph
from .synthesis import Result

#: The operations, in the order the summary counts them.
OPERATION_KINDS = ("replace", "grow", "transfer")
#: The names the output directory is made of (replaced as a whole).
FOLDERS = frozenset([f"variant_{k:03d}" for k in range(1, 10000)] + ["index.json"])


def fingerprint(scene) -> tuple:
    """((type, style) multiset, relation set) of a scene: what makes a variant new. The
    style counts, so a tall bookshelf put for a low one (a replacement) makes a new
    room, as it looks one."""
    graph = structure_graph(scene)
    kinds = Counter(zip(graph.types, (style or "" for style in graph.styles), strict=True))
    types = tuple(sorted(kinds.items()))
    relations = frozenset(
        (graph.types[i], graph.types[j], frozenset(edge.relations))
        for (i, j), edge in graph.edges.items()
        if edge.relations
    )
    return types, relations


def is_new(result: Result, examples: list[Example]) -> bool:
    types, relations = fingerprint(result.scene)
    return all(types != t or relations != r for t, r in (fingerprint(e.scene) for e in examples))


def new_index(examples: list[Example], seed: int) -> dict:
    """index.json before its variants: the seed and the examples."""
    return {
        "seed": seed,
        "examples": [{"name": e.name, "path": e.path} for e in examples],
        "variants": [],
    }


def variant_entry(result: Result, examples: list[Example], folder: str, scene) -> dict:
    """index.json's record of one variant, written to ``folder`` as ``scene``."""
    return {
        "folder": folder,
        "base": result.base,
        "compatibility": round(result.compatibility, 6),
        "operations": [op["operation"] for op in result.operations],
        "ok": scene.layout.ok,
        "objects": len(scene.placed_objects()),
        "new": is_new(result, examples),
    }


def summary(index: dict, directory: str | os.PathLike[str]) -> str:
    variants = index["variants"]
    ok = sum(v["ok"] for v in variants)
    new = sum(v["new"] for v in variants)
    best = (
        f", K from {variants[-1]['compatibility']:.2f} to {variants[0]['compatibility']:.2f}"
        if variants
        else ""
    )
    used = Counter(op for v in variants for op in v["operations"])
    mix = ", ".join(f"{used[kind]} {kind}" for kind in OPERATION_KINDS)
    return (
        f"wrote {Path(directory)}/: {len(variants)} variants ({ok} ok, {new} new){best}; "
        f"operations: {mix}; index.json lists them"
    )
