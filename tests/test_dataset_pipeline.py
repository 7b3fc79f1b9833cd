"""The dataset job on the real pipeline (rules, layout, describer, OpenGL renderer in
worker processes, or on a local dask cluster), kept small: a few desk scenes at 64x64."""

from __future__ import annotations

import json
from importlib import resources

import jsonschema
import numpy as np
import pytest
from PIL import Image
from test_dataset import dataset_bytes

from scenewright.api import generate, render_image
from scenewright.cli import main
from scenewright.dataset.run import run_dataset
from scenewright.dataset.spec import METADATA_FILE, dataset_spec, scene_seed


@pytest.fixture(scope="module")
def one_worker(tmp_path_factory):
    """A 4-scene desk dataset with every optional column, made by one worker.

    This process renders first: a worker forked from a process holding an OpenGL
    context hangs (tried), so the pool must not inherit one (it uses forkserver).
    """
    render_image(generate("desk", seed=1), 32, 32)
    root = tmp_path_factory.mktemp("desk") / "one"
    spec = dataset_spec(
        "desk",
        4,
        captions=2,
        size=(64, 64),
        depth=True,
        segmentation=True,
        normals=True,
        boxes_3d=True,
    )
    run_dataset(spec, root, workers=1, progress=False)  # the API: any error shows in full
    return root


def test_two_workers_write_the_same_bytes(one_worker, tmp_path):
    argv = ["dataset", "desk", "-n", "4", "-o", str(tmp_path), "--size", "64x64", "--captions", "2"]
    options = ["--depth", "--segmentation", "--normals", "--boxes-3d", "--quiet"]
    assert main([*argv, "--workers", "2", *options]) == 0
    assert dataset_bytes(tmp_path) == dataset_bytes(one_worker)


def test_rows_carry_captions_seeds_and_ground_truth(one_worker):
    rows = [json.loads(line) for line in (one_worker / METADATA_FILE).read_text().splitlines()]
    assert [r["seed"] for r in rows] == [scene_seed(0, i) for i in range(4)]
    schema = json.loads(
        resources.files("scenewright.dataset")
        .joinpath("schema/metadata_row.schema.json")
        .read_text()
    )
    for row in rows:
        assert row["rules"] == "desk" and row["ok"] is True
        assert (
            row["text"].startswith("The scene consists of") and row["caption"] != row["caption_1"]
        )
        for column in (
            "file_name",
            "depth_file_name",
            "depth_metres_path",
            "segmentation_file_name",
            "normals_file_name",
        ):
            assert (one_worker / row[column]).is_file()
        metres = np.load(one_worker / row["depth_metres_path"])
        png = np.asarray(Image.open(one_worker / row["depth_file_name"]))
        assert metres.dtype == np.float32 and metres.shape == (64, 64)
        assert np.abs(png * row["depth_scale"] - metres).max() <= row["depth_scale"] / 2 + 1e-4
        assert np.array(row["camera"]["K"]).shape == (3, 3)
        assert {"world_to_camera_opencv", "world_to_camera_opengl"} <= set(row["camera"])
        jsonschema.validate(row, schema)
        tables = [entry for entry in row["objects_3d"] if entry["id"].startswith("table")]
        assert len(tables) == 1 and len(tables[0]["corners"]) == 8
        scene = json.loads((one_worker / "scenes" / f"{row['scene_id']}.json").read_text())
        assert scene["seed"] == row["seed"] and scene["description"]["text"] == row["text"]
    stats = json.loads((one_worker / "stats.json").read_text())
    assert stats["scenes"] == 4 and stats["objects"]["table"] == 4
    assert set(stats["seconds_per_stage"]) >= {"expand", "layout", "describe", "render"}


def test_loads_as_imagefolder_with_ground_truth_columns(one_worker, tmp_path):
    datasets = pytest.importorskip("datasets")
    loaded = datasets.load_dataset(
        "imagefolder", data_dir=str(one_worker), split="train", cache_dir=str(tmp_path)
    )
    assert loaded.num_rows == 4
    assert {"image", "depth", "segmentation", "caption", "caption_1", "text"} <= set(
        loaded.column_names
    )
    assert loaded[0]["image"].size == (64, 64) and loaded[0]["depth"].size == (64, 64)


def test_dataset_command_reports_and_bad_rules_exit_2(capsys, one_worker, tmp_path):
    argv = [
        "dataset",
        "desk",
        "-n",
        "4",
        "-o",
        str(one_worker),
        "--size",
        "64x64",
        "--captions",
        "2",
        "--depth",
        "--normals",
        "--boxes-3d",
    ]
    assert main([*argv, "--segmentation"]) == 0
    out = capsys.readouterr().out
    assert (
        "4 scenes in metadata.jsonl; 0 of 4 layouts failed" in out and "4 were already done" in out
    )
    assert main([*argv]) == 2
    assert "other settings (segmentation True -> False)" in capsys.readouterr().err
    bad = tmp_path / "bad.rules"
    bad.write_text("scene {\n")
    assert main(["dataset", str(bad), "-n", "2", "-o", str(tmp_path / "x")]) == 2
    assert capsys.readouterr().err.startswith(f"{bad}:1:")
    assert not (tmp_path / "x").exists()


@pytest.mark.slow
def test_dask_workers_render_the_same_bytes_as_the_pool(one_worker, tmp_path):
    distributed = pytest.importorskip("distributed")
    argv = ["dataset", "desk", "-n", "4", "-o", str(tmp_path), "--size", "64x64", "--captions", "2"]
    # Two threads per worker process: each thread must get its own OpenGL context.
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=2, processes=True, dashboard_address=None
    ) as cluster:
        options = ["--depth", "--segmentation", "--normals", "--boxes-3d", "-q"]
        assert main([*argv, "--scheduler", cluster.scheduler_address, *options]) == 0
    assert dataset_bytes(tmp_path) == dataset_bytes(one_worker)
