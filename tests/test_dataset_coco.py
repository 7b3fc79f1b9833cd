"""A dataset's COCO instances file on the real pipeline: read back by pycocotools, every
mask equal to the segmentation's, ids stable, the same bytes after a resume."""

from __future__ import annotations

import json
import shutil

import numpy as np
import pytest
from PIL import Image
from test_dataset import dataset_bytes

from scenewright.api import load_rules
from scenewright.dataset.coco import COCO_FILE, coco_categories
from scenewright.dataset.run import run_dataset
from scenewright.dataset.spec import METADATA_FILE, RECORDS_DIR, dataset_spec

pycocotools_coco = pytest.importorskip("pycocotools.coco")


def bedroom_spec(count: int):
    return dataset_spec("bedroom", count, size=(64, 64), segmentation=True)


@pytest.fixture(scope="module")
def bedroom(tmp_path_factory):
    """Three bedrooms at 64x64 with their segmentation, by one worker (a window shows)."""
    root = tmp_path_factory.mktemp("coco") / "bedroom"
    run_dataset(bedroom_spec(3), root, workers=1, progress=False)
    return root


def rows_of(root) -> list[dict]:
    return [json.loads(line) for line in (root / METADATA_FILE).read_text().splitlines()]


def test_pycocotools_reads_every_mask_back_as_the_segmentation(bedroom):
    coco = pycocotools_coco.COCO(str(bedroom / COCO_FILE))
    rows = rows_of(bedroom)
    assert sorted(coco.getImgIds()) == [int(row["scene_id"]) + 1 for row in rows]
    names = {category["id"]: category["name"] for category in coco.loadCats(coco.getCatIds())}
    seen_categories = set()
    for row in rows:
        image_id = int(row["scene_id"]) + 1
        image = coco.loadImgs(image_id)[0]
        assert (image["file_name"], image["width"], image["height"]) == (row["file_name"], 64, 64)
        segmentation = np.asarray(Image.open(bedroom / row["segmentation_file_name"]))
        ids_file = bedroom / "segmentation" / f"{row['scene_id']}_ids.json"
        index_of = {
            entity: int(index) for index, entity in json.loads(ids_file.read_text()).items()
        }
        scene = json.loads((bedroom / "scenes" / f"{row['scene_id']}.json").read_text())
        types = {o["id"]: o["type"] for o in scene["objects"]}
        types |= {opening["id"]: opening["kind"] for opening in scene["room"]["openings"]}
        annotations = coco.loadAnns(coco.getAnnIds(imgIds=[image_id]))
        # every entity with a pixel is annotated, once
        assert sorted(a["entity_id"] for a in annotations) == sorted(
            entity for entity, index in index_of.items() if (segmentation == index).any()
        )
        for annotation in annotations:
            expected = segmentation == index_of[annotation["entity_id"]]
            assert np.array_equal(coco.annToMask(annotation), expected.astype(np.uint8))
            rows_hit, columns_hit = np.nonzero(expected)
            x0, y0 = columns_hit.min(), rows_hit.min()
            assert annotation["bbox"] == [
                x0,
                y0,
                columns_hit.max() + 1 - x0,
                rows_hit.max() + 1 - y0,
            ]
            assert annotation["area"] == expected.sum() and annotation["iscrowd"] == 0
            assert names[annotation["category_id"]] == types[annotation["entity_id"]]
            seen_categories.add(names[annotation["category_id"]])
    assert {"bed", "wardrobe", "window"} <= seen_categories


def test_categories_are_the_catalog_types_sorted_with_stable_ids(bedroom):
    categories = json.loads((bedroom / COCO_FILE).read_text())["categories"]
    assert categories == coco_categories(load_rules("bedroom"))
    names = [category["name"] for category in categories]
    assert names == sorted(names) and [category["id"] for category in categories] == list(
        range(1, len(names) + 1)
    )
    assert {"bed", "nightstand", "door", "window"} <= set(names) and "Bedroom" not in names
    # desk.rules has walls without openings: no door or window category
    assert not {"door", "window"} & {
        category["name"] for category in coco_categories(load_rules("desk"))
    }
    annotation_ids = [a["id"] for a in json.loads((bedroom / COCO_FILE).read_text())["annotations"]]
    assert annotation_ids == list(range(1, len(annotation_ids) + 1))


@pytest.mark.slow
def test_resumed_and_grown_datasets_write_the_same_file(bedroom, tmp_path):
    # Interrupted after scene 0 and 2 were stored, before the file was written.
    resumed = tmp_path / "resumed"
    shutil.copytree(bedroom, resumed)
    for stale in (
        resumed / COCO_FILE,
        resumed / METADATA_FILE,
        resumed / RECORDS_DIR / "000001.json",
    ):
        stale.unlink()
    report = run_dataset(bedroom_spec(3), resumed, workers=1, progress=False)
    assert (report.made, report.skipped) == (1, 2)
    assert (resumed / COCO_FILE).read_bytes() == (bedroom / COCO_FILE).read_bytes()
    assert dataset_bytes(resumed) == dataset_bytes(bedroom)
    # Made 2 scenes first, then grown to 3: the first two keep their image and annotation ids.
    grown = tmp_path / "grown"
    run_dataset(bedroom_spec(2), grown, workers=1, progress=False)
    two = json.loads((grown / COCO_FILE).read_text())
    run_dataset(bedroom_spec(3), grown, workers=1, progress=False)
    assert (grown / COCO_FILE).read_bytes() == (bedroom / COCO_FILE).read_bytes()
    three = json.loads((grown / COCO_FILE).read_text())
    assert three["annotations"][: len(two["annotations"])] == two["annotations"]


def test_no_coco_writes_no_file_and_old_datasets_resume_with_it(bedroom, tmp_path, capsys):
    from scenewright.cli import main

    argv = ["dataset", "desk", "-n", "1", "-o", str(tmp_path / "off"), "--size", "32x32", "--quiet"]
    assert main([*argv, "--no-coco"]) == 0
    assert not (tmp_path / "off" / "annotations").exists()
    assert json.loads((tmp_path / "off" / "dataset.json").read_text())["coco"] is False
    # A dataset.json from before COCO output existed has no "coco": it meant none.
    settings = json.loads((tmp_path / "off" / "dataset.json").read_text())
    del settings["coco"]
    (tmp_path / "off" / "dataset.json").write_text(json.dumps(settings))
    assert main(argv) == 2
    assert "other settings (coco False -> True)" in capsys.readouterr().err
    assert main([*argv, "--no-coco"]) == 0
