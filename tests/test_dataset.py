"""The dataset machinery (seeding, atomic writes, resume, pool, dask errors, stats) on a cheap
stand-in for the pipeline, so these tests exercise the job itself in a few seconds.

``fake_scene`` is a module-level function so worker processes can import it by name.
"""

from __future__ import annotations

import io
import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

from scenewright.core.errors import InputError
from scenewright.dataset.run import ProgressLines, progress_bar, run_dataset
from scenewright.dataset.spec import (
    METADATA_FILE,
    RECORDS_DIR,
    DatasetSpec,
    SceneProduct,
    scene_seed,
    scene_stem,
)

TESTS = Path(__file__).parent
#: For a job in a fresh interpreter that makes ``fake_scene``s: its fork server skips
#: preloading the pipeline, which the stand-in scene does not use (about a second of CPU
#: time in each such job). Tests of the real command keep it.
LIGHT_FORK_SERVER = "scenewright.dataset.run.WORKER_MODULES = []"


def fake_scene(spec: DatasetSpec, index: int) -> SceneProduct:
    """A deterministic stand-in scene: noise image, caption, every seventh layout 'fails'."""
    delay = float(os.environ.get("FAKE_SCENE_DELAY", "0"))
    if delay:
        time.sleep(delay)
    gate = os.environ.get("FAKE_SCENE_GATE")
    if gate and index >= 2:  # the first two scenes, then the rest once the file exists
        while not os.path.exists(gate):
            time.sleep(0.01)
    seed = scene_seed(spec.base_seed, index)
    ok = index % 7 != 3
    stem = scene_stem(index)
    stats = {
        "objects": {"table": 1 + seed % 3},
        "relations": {"NextTo": [2, 1 + ok]},
        "problems": [],
    }
    if not ok:
        stats["problems"] = [f"sign_{index} is not next to table_1 (distance {seed % 10} m)"]
        if not spec.include_failed:
            return SceneProduct(index, seed, False, {f"failed/{stem}.json": b"{}\n"}, None, stats)
    pixels = np.random.default_rng(seed).integers(
        0, 256, size=(spec.size[1], spec.size[0], 3), dtype=np.uint8
    )
    buffer = io.BytesIO()
    Image.fromarray(pixels).save(buffer, format="PNG")
    captions = [f"scene {index} caption {k}" for k in range(spec.captions)]
    row = {
        "file_name": f"images/{stem}.png",
        "caption": captions[0],
        "text": f"The scene {index} in full.",
    }
    row.update({f"caption_{k}": c for k, c in enumerate(captions[1:], start=1)})
    row.update(scene_id=stem, seed=seed, rules=spec.rules, ok=ok)
    stats["words"] = {"text": 5, "captions": [len(c.split()) for c in captions]}
    stats["seconds"] = {"layout": 0.01 * (index + 1)}
    files = {
        f"images/{stem}.png": buffer.getvalue(),
        f"scenes/{stem}.json": json.dumps({"seed": seed}).encode(),
    }
    return SceneProduct(index, seed, ok, files, row, stats)


def crashing_scene(spec: DatasetSpec, index: int) -> SceneProduct:
    if index == 5:
        raise RuntimeError("boom")
    return fake_scene(spec, index)


def failing_scene(spec: DatasetSpec, index: int) -> SceneProduct:
    """Every layout fails."""
    stats = {
        "objects": {"box": 2},
        "relations": {"NextToNorth": [1, 0]},
        "problems": ["box_2 is not north of box_1 (90° off)"],
    }
    return SceneProduct(index, scene_seed(spec.base_seed, index), False, {}, None, stats)


def spec_of(count: int = 8, **settings) -> DatasetSpec:
    """A spec for ``fake_scene``, which makes no COCO annotations (nor has real rules to take
    categories from)."""
    return DatasetSpec(
        rules="fake", rules_digest="0" * 8, count=count, size=(16, 12), coco=False, **settings
    )


def dataset_bytes(root: Path) -> dict[str, bytes]:
    """Every published file of a dataset except stats (records and stats hold timings)."""
    return {
        str(p.relative_to(root)): p.read_bytes()
        for p in sorted(root.rglob("*"))
        if p.is_file() and not p.name.startswith("stats.") and RECORDS_DIR not in p.parts
    }


def metadata_rows(root: Path) -> list[dict]:
    return [json.loads(line) for line in (root / METADATA_FILE).read_text().splitlines()]


def test_scene_seed_is_derived_from_base_and_index_only():
    assert scene_seed(5, 3) == int(np.random.SeedSequence([5, 3]).generate_state(1)[0])
    assert scene_seed(5, 3) == scene_seed(5, 3)
    assert len({scene_seed(0, i) for i in range(1000)}) == 1000
    assert scene_seed(0, 1) != scene_seed(1, 0)


def test_imagefolder_layout_ordered_metadata_and_failures_left_out(tmp_path):
    report = run_dataset(
        spec_of(8, captions=3), tmp_path, workers=1, producer=fake_scene, progress=False
    )
    rows = metadata_rows(tmp_path)
    assert [r["scene_id"] for r in rows] == [
        "000000",
        "000001",
        "000002",
        "000004",
        "000005",
        "000006",
        "000007",
    ]
    assert all((tmp_path / r["file_name"]).is_file() for r in rows)
    assert rows[0]["caption_2"] == "scene 0 caption 2" and rows[0]["seed"] == scene_seed(0, 0)
    assert (
        not (tmp_path / "images/000003.png").exists() and (tmp_path / "failed/000003.json").exists()
    )
    assert (report.count, report.made, report.written, report.failed) == (8, 8, 7, 1)
    stats = json.loads((tmp_path / "stats.json").read_text())
    assert (stats["scenes"], stats["failed"]) == (8, 1)
    assert stats["relations"]["NextTo"] == {"total": 16, "satisfied": 15}
    assert stats["problems"] == {"sign is not next to table (distance # m)": 1}
    assert (tmp_path / "stats.png").read_bytes()[:4] == b"\x89PNG"


def test_include_failed_writes_failed_scenes_flagged(tmp_path):
    run_dataset(
        spec_of(8, include_failed=True), tmp_path, workers=1, producer=fake_scene, progress=False
    )
    rows = metadata_rows(tmp_path)
    assert len(rows) == 8
    assert [r["scene_id"] for r in rows if not r["ok"]] == ["000003"]


def test_same_bytes_for_one_and_two_workers(tmp_path):
    run_dataset(spec_of(10), tmp_path / "one", workers=1, producer=fake_scene, progress=False)
    run_dataset(spec_of(10), tmp_path / "two", workers=2, producer=fake_scene, progress=False)
    assert dataset_bytes(tmp_path / "one") == dataset_bytes(tmp_path / "two")


def test_rerun_skips_finished_scenes_and_count_may_grow(tmp_path):
    run_dataset(spec_of(4), tmp_path / "grown", workers=1, producer=fake_scene, progress=False)
    report = run_dataset(
        spec_of(9), tmp_path / "grown", workers=1, producer=fake_scene, progress=False
    )
    assert (report.skipped, report.made) == (4, 5)
    run_dataset(spec_of(9), tmp_path / "direct", workers=1, producer=fake_scene, progress=False)
    assert dataset_bytes(tmp_path / "grown") == dataset_bytes(tmp_path / "direct")


@pytest.mark.slow
def test_resume_after_kill_minus_nine(tmp_path):
    """Kill a running job (and its workers) with SIGKILL mid-run; the rerun completes it
    with no gaps, duplicates, leftovers or corrupt files, byte-identical to a clean run."""
    killed = tmp_path / "killed"
    script = (
        f"import sys; sys.path.insert(0, {str(TESTS)!r})\n"
        "from test_dataset import fake_scene, spec_of\n"
        "import scenewright.dataset.run\n"
        "from scenewright.dataset.run import run_dataset\n"
        f"{LIGHT_FORK_SERVER}\n"
        f"run_dataset(spec_of(12), {str(killed)!r}, workers=2, producer=fake_scene, progress=False)\n"
    )
    env = {**os.environ, "FAKE_SCENE_DELAY": "0.15"}
    job = subprocess.Popen([sys.executable, "-c", script], env=env, start_new_session=True)
    try:
        deadline = time.monotonic() + 30
        while len(list((killed / RECORDS_DIR).glob("*.json"))) < 4:
            assert time.monotonic() < deadline and job.poll() is None, "the job did not get going"
            time.sleep(0.02)
    finally:
        os.killpg(job.pid, signal.SIGKILL)
        job.wait()
    done_before = len(list((killed / RECORDS_DIR).glob("*.json")))
    assert 4 <= done_before < 12
    assert not (killed / METADATA_FILE).exists()

    report = run_dataset(spec_of(12), killed, workers=2, producer=fake_scene, progress=False)
    assert report.skipped == done_before and report.made == 12 - done_before
    run_dataset(spec_of(12), tmp_path / "clean", workers=1, producer=fake_scene, progress=False)
    assert dataset_bytes(killed) == dataset_bytes(tmp_path / "clean")
    assert not list(killed.rglob("*.partial"))
    ids = [r["scene_id"] for r in metadata_rows(killed)]
    assert ids == sorted(set(ids)) and len(ids) == 10  # 3 and 10 are failed layouts


def test_unreachable_scheduler_is_bad_input(tmp_path, monkeypatch):
    pytest.importorskip("distributed")
    monkeypatch.setattr("scenewright.dataset.cluster.CONNECT_TIMEOUT", 0.2)
    with pytest.raises(InputError, match="cannot reach the dask scheduler"):
        run_dataset(
            spec_of(2), tmp_path, scheduler="tcp://127.0.0.1:9", producer=fake_scene, progress=False
        )


def test_huggingface_imagefolder_reads_it(tmp_path):
    datasets = pytest.importorskip("datasets")
    run_dataset(
        spec_of(8, captions=2), tmp_path / "hf", workers=1, producer=fake_scene, progress=False
    )
    loaded = datasets.load_dataset(
        "imagefolder",
        data_dir=str(tmp_path / "hf"),
        split="train",
        cache_dir=str(tmp_path / "cache"),
    )
    assert loaded.num_rows == 7
    assert {"image", "caption", "caption_1", "text", "scene_id", "seed", "ok"} <= set(
        loaded.column_names
    )
    assert loaded[0]["image"].size == (16, 12)
    assert loaded[0]["caption_1"] == "scene 0 caption 1"


def test_refuses_other_settings_and_foreign_directories(tmp_path):
    run_dataset(spec_of(4), tmp_path / "d", workers=1, producer=fake_scene, progress=False)
    with pytest.raises(InputError, match="other settings .*base_seed 0 -> 1"):
        run_dataset(
            spec_of(4, base_seed=1), tmp_path / "d", workers=1, producer=fake_scene, progress=False
        )
    (tmp_path / "other").mkdir()
    (tmp_path / "other" / "notes.txt").write_text("mine")
    with pytest.raises(InputError, match="not empty"):
        run_dataset(spec_of(4), tmp_path / "other", workers=1, producer=fake_scene, progress=False)
    (tmp_path / "file").write_text("")
    with pytest.raises(InputError, match="cannot write the dataset"):
        run_dataset(
            spec_of(4), tmp_path / "file" / "sub", workers=1, producer=fake_scene, progress=False
        )


def test_a_worker_error_stops_the_run_and_keeps_finished_scenes(tmp_path):
    with pytest.raises(RuntimeError, match="boom"):
        run_dataset(spec_of(8), tmp_path, workers=1, producer=crashing_scene, progress=False)
    assert (tmp_path / RECORDS_DIR / "000004.json").exists()
    assert not (tmp_path / METADATA_FILE).exists()
    report = run_dataset(spec_of(8), tmp_path, workers=1, producer=fake_scene, progress=False)
    assert report.skipped >= 5 and len(metadata_rows(tmp_path)) == 7


def test_every_layout_failing_is_reported_and_the_command_exits_1(tmp_path, monkeypatch, capsys):
    import scenewright.dataset.run
    from scenewright.cli import main

    real = scenewright.dataset.run.run_dataset
    monkeypatch.setattr(
        scenewright.dataset.run,
        "run_dataset",
        lambda *a, **k: real(*a, **{**k, "producer": failing_scene}),
    )
    assert main(["dataset", "desk", "-n", "3", "-o", str(tmp_path), "--workers", "1"]) == 1
    captured = capsys.readouterr()
    assert "every scene's layout failed" in captured.err
    assert "most frequent layout problems: box is not north of box (#° off) (3x)" in captured.out
    assert (tmp_path / METADATA_FILE).read_text() == ""
    stats = json.loads((tmp_path / "stats.json").read_text())
    assert (stats["written"], stats["failed"], stats["problems"]) == (
        0,
        3,
        {"box is not north of box (#° off)": 3},
    )
    assert (tmp_path / "stats.png").stat().st_size > 0


def test_progress_in_a_log_is_a_plain_line_per_interval(tmp_path, capsys):
    # Under pytest stderr is not a terminal, as in a log file: a quick run prints one
    # line at the end, not a redraw per scene.
    run_dataset(spec_of(8), tmp_path, workers=1, producer=fake_scene)
    lines = capsys.readouterr().err.splitlines()
    assert len(lines) == 1 and "\r" not in lines[0]
    assert lines[0].startswith("scenes: 8/8 (100%) [") and lines[0].endswith(", failed=1]")

    now = [0.0]
    log = io.StringIO()
    progress = ProgressLines(100, "scenes", log, interval=30.0, clock=lambda: now[0])
    for second in range(1, 91):  # a scene a second
        now[0] = float(second)
        progress.set_postfix(failed=second // 10)
        progress.update(1)
    progress.close()
    assert log.getvalue().splitlines() == [
        "scenes: 30/100 (30%) [00:30<01:10,  1.00scene/s, failed=3]",
        "scenes: 60/100 (60%) [01:00<00:40,  1.00scene/s, failed=6]",
        "scenes: 90/100 (90%) [01:30<00:10,  1.00scene/s, failed=9]",
    ]
    now[0] = 95.0
    progress.update(5)  # the run ends between two lines: close says where it ended
    progress.close()
    assert (
        log.getvalue().splitlines()[-1]
        == "scenes: 95/100 (95%) [01:35<00:05,  1.00scene/s, failed=9]"
    )


def test_progress_on_a_terminal_is_a_bar_and_silent_when_disabled():
    class Terminal(io.StringIO):
        def isatty(self) -> bool:
            return True

    bar = progress_bar(10, True, 4, Terminal())
    assert not isinstance(bar, ProgressLines) and bar.desc == "scenes (4 already done)"
    bar.close()
    log = io.StringIO()
    silent = progress_bar(10, False, 0, log)
    silent.update(10)
    silent.close()
    assert log.getvalue() == ""
