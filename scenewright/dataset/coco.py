"""A dataset's COCO instances file, ``annotations/instances.json``, from the rendered
segmentation.

Every image of ``metadata.jsonl`` (one per row) is a COCO image, and every entity with
at least one pixel in that image's segmentation is an annotation of it: objects,
junctions, paths, and a room's doors and windows. Visibility thresholds play no part
(they decide what a caption names; COCO annotates every instance that shows), and
groups have no pixels of their own. Categories are the rule set's catalog types that
are drawn (objects, paths, junctions: not groups), plus ``door`` and ``window`` when
the rule set's room has one, sorted by name and numbered from 1, so a rule set's ids do not
depend on which scenes were made.

A worker computes the annotations of its scene's views (``view_annotations``: box,
area and run-length encoded mask, with category *names*) and they travel in the
scene's record. At the end of every run, resumed or not, ``coco_writer`` rebuilds the
file from the records in index order, as ``metadata.jsonl`` is: so a run killed and
resumed writes the same bytes as one that was not, whatever the number of workers.
Image ids are ``dataset.image_number(index, view, views) + 1`` (stable when N grows or shrinks);
annotation ids count from 1 in file order.
"""

from __future__ import annotations

import json
import shutil
import tempfile
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from scenewright.core import VERSION
from scenewright.core.atomic import atomic_stream
from scenewright.dataset.spec import DatasetSpec, image_number

if TYPE_CHECKING:
    from scenewright.core.scene import Scene
    from scenewright.generator.rules import Rules
    from scenewright.render.offscreen import RenderResult

COCO_DIR = "annotations"
COCO_FILE = f"{COCO_DIR}/instances.json"


def coco_categories(rules: Rules) -> list[dict]:
    """The COCO categories of a rule set: ``{"id", "name", "supercategory"}`` per drawn
    catalog type (the supercategory is its kind: object, path, junction), and door and
    window (supercategory opening) when the rule set's room has one."""
    kinds = {entry.name: entry.kind for entry in rules.catalog if entry.kind != "group"}
    if rules.params.room is not None:
        kinds.update({opening.kind: "opening" for opening in rules.params.room.openings})
    return [
        {"id": k, "name": name, "supercategory": kinds[name]}
        for k, name in enumerate(sorted(kinds), start=1)
    ]


def view_annotations(result: RenderResult, scene: Scene) -> list[dict]:
    """The annotations of one rendered view, in segmentation index order: per entity
    with pixels, its ``entity_id``, ``category`` (type name; a door's or window's kind),
    ``bbox`` [x, y, width, height], ``area`` (pixels) and ``segmentation`` (COCO RLE
    with ``counts`` as a string)."""
    from pycocotools import mask as mask_utils

    types = {o.id: o.type for o in scene.objects} | {p.id: p.type for p in scene.paths}
    if scene.room is not None:
        types |= {opening.id: opening.kind for opening in scene.room.openings}
    pixels = np.bincount(result.segmentation.ravel(), minlength=len(result.ids) + 1)
    # pycocotools reads masks column by column: compare in that order once, no copies per entity.
    by_column = np.asfortranarray(result.segmentation)
    annotations = []
    for index, entity_id in enumerate(result.ids, start=1):
        if not pixels[index]:
            continue
        rle = mask_utils.encode((by_column == index).view(np.uint8))
        x0, y0, x1, y1 = result.boxes[entity_id]
        annotations.append(
            {
                "entity_id": entity_id,
                "category": types[entity_id],
                "bbox": [x0, y0, x1 - x0, y1 - y0],
                "area": int(pixels[index]),
                "segmentation": {
                    "size": [int(n) for n in rle["size"]],
                    "counts": rle["counts"].decode("ascii"),
                },
            }
        )
    return annotations


@contextmanager
def coco_writer(
    root: Path, spec: DatasetSpec, categories: list[dict]
) -> Iterator[Callable[[dict], None]]:
    """Write ``root/annotations/instances.json`` (atomically) from the records passed to
    the function this yields, in index order; the file appears when the block ends
    without an error. Images are written as they come and annotations to a spool file
    (unnamed, so a killed run leaves nothing), copied in after them: neither list is
    held in memory."""
    ids = {category["name"]: category["id"] for category in categories}
    width, height = spec.size
    views = spec.views
    (root / COCO_DIR).mkdir(exist_ok=True)
    with (
        atomic_stream(root / COCO_FILE) as out,
        tempfile.TemporaryFile("w+", encoding="utf-8", dir=root / COCO_DIR) as spool,
    ):
        info = {
            "description": f"scenewright dataset of the {spec.rules} rules",
            "version": VERSION,
        }
        out.write(
            f'{{"info": {json.dumps(info, ensure_ascii=False)},\n"licenses": [],\n"categories": [\n'
        )
        out.write(",\n".join(json.dumps(category, ensure_ascii=False) for category in categories))
        out.write('\n],\n"images": [')
        written = {"images": 0, "annotations": 0}

        def add(record: dict) -> None:
            rows = [record["row"], *record.get("views", [])] if record["row"] is not None else []
            if rows and "coco" not in record:
                raise RuntimeError(
                    f"the record of scene {record['index']} holds no COCO annotations"
                )
            for view, (row, annotations) in enumerate(
                zip(rows, record.get("coco", []), strict=True)
            ):
                image_id = image_number(record["index"], view, views) + 1
                image = {
                    "id": image_id,
                    "file_name": row["file_name"],
                    "width": width,
                    "height": height,
                    "scene_id": row["scene_id"],
                    "view": view,
                }
                out.write(
                    ("\n" if not written["images"] else ",\n")
                    + json.dumps(image, ensure_ascii=False)
                )
                written["images"] += 1
                for annotation in annotations:
                    written["annotations"] += 1
                    entry = {
                        "id": written["annotations"],
                        "image_id": image_id,
                        "category_id": ids[annotation["category"]],
                        "bbox": annotation["bbox"],
                        "area": annotation["area"],
                        "iscrowd": 0,
                        "segmentation": annotation["segmentation"],
                        "entity_id": annotation["entity_id"],
                    }
                    separator = "\n" if written["annotations"] == 1 else ",\n"
                    spool.write(separator + json.dumps(entry, ensure_ascii=False))

        yield add
        out.write('\n],\n"annotations": [')
        spool.seek(0)
        shutil.copyfileobj(spool, out)
        out.write("\n]}\n")


def coco_sink(root: Path, spec: DatasetSpec):
    """``coco_writer`` for ``spec``'s rule set (loaded here: the categories are its
    catalog's), or None when the spec turns COCO output off."""
    if not spec.coco:
        return None
    from scenewright.api import load_rules

    return coco_writer(root, spec, coco_categories(load_rules(spec.rules)))
