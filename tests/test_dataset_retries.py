"""Layout retries and rules errors in datasets, on the real pipeline with a rule set of
our own whose outcome is decided by what it expands to: one crate always fits its yard,
two never do (every layout of them fails, whatever the seed), and a pile that recurses
past ``max_depth`` is an expansion error. Kept small: a handful of scenes at 16x16."""

from __future__ import annotations

import io
import json
from contextlib import redirect_stderr, redirect_stdout
from pathlib import Path

import pytest
from hypothesis import given
from hypothesis import strategies as st
from test_dataset import dataset_bytes, spec_of

from scenewright.api import build_scene, load_rules, render_image
from scenewright.cli import main
from scenewright.core.seeds import MAX_SEED, retry_seed
from scenewright.dataset.run import check_same_settings
from scenewright.dataset.spec import METADATA_FILE, dataset_spec, scene_seed
from scenewright.dataset.stats import error_kind, retries_by_size

CRAMPED = """\
# One crate fits the yard, two never do; a pile recurses past max_depth.
scene cramped {
    extent 2.5 x 2.5
    start Yard
    max_depth 3
}
object crate { noun "crate" size 1.9 x 1 x 1.9 }
Yard -> 1: { crate } | 1: { 2 crate } | 1: { Pile }
Pile -> 1: { crate } | 99: { Pile }
"""
SCENES = 6


@pytest.fixture(scope="module")
def cramped(tmp_path_factory) -> Path:
    path = tmp_path_factory.mktemp("rules") / "cramped.rules"
    path.write_text(CRAMPED)
    return path


def outcomes(rules: Path) -> dict[int, str]:
    """What each scene of the dataset is, from the grammar alone: "ok" (one crate),
    "fails" (two crates) or "error" (the expansion error), by expanding every seed."""
    from scenewright.core.errors import ScenewrightError
    from scenewright.generator import expand

    loaded = load_rules(rules)
    kinds = {}
    for index in range(SCENES):
        try:
            graph = expand(loaded, scene_seed(0, index))
        except ScenewrightError:
            kinds[index] = "error"
            continue
        crates = sum(node.type == "crate" for node in graph.nodes())
        kinds[index] = "ok" if crates == 1 else "fails"
    return kinds


def command(rules: Path, root: Path, *extra: str) -> list[str]:
    return [
        "dataset",
        str(rules),
        "-n",
        str(SCENES),
        "-o",
        str(root),
        "--size",
        "16x16",
        "--retries",
        "1",
        *extra,
    ]


@pytest.fixture(scope="module")
def made(cramped, tmp_path_factory):
    """The dataset made by the command with one worker and one retry: its directory,
    the exit code, and what the command printed (stdout, stderr)."""
    render_image(build_scene("desk", 1), 16, 16)  # this process holds a context, as users' may
    root = tmp_path_factory.mktemp("cramped") / "one"
    out, err = io.StringIO(), io.StringIO()
    with redirect_stdout(out), redirect_stderr(err):
        code = main(command(cramped, root, "--workers", "1"))
    return root, code, out.getvalue(), err.getvalue()


def test_retry_seed_is_the_seed_first_then_independent_32_bit_seeds():
    assert retry_seed(7, 0) == 7
    later = [retry_seed(7, k) for k in range(1, 50)]
    assert later == [retry_seed(7, k) for k in range(1, 50)]  # depends on (seed, k) only
    assert len(set(later)) == len(later) and all(0 <= s < 2**32 for s in later)
    assert retry_seed(8, 1) != retry_seed(7, 1)


@given(seed=st.integers(0, MAX_SEED), attempt=st.integers(1, 1000))
def test_retry_seeds_are_valid_seeds_for_any_scene_seed(seed, attempt):
    derived = retry_seed(seed, attempt)
    assert 0 <= derived < 2**32 and derived == retry_seed(seed, attempt)


def test_a_failing_layout_is_retried_with_the_same_objects(cramped):
    from scenewright.dataset.produce import laid_out_scene, worker_context

    kinds = outcomes(cramped)
    assert set(kinds.values()) == {"ok", "fails", "error"}, "the rule set should give every outcome"
    spec = dataset_spec(cramped, 1, size=(16, 16), retries=1)
    context = worker_context(spec)
    failing = scene_seed(0, next(i for i, kind in kinds.items() if kind == "fails"))
    scene, tried = laid_out_scene(context, spec, failing)
    assert tried == {"layout_seed": retry_seed(failing, 1), "attempts": 2} and not scene.layout.ok
    first = build_scene(cramped, failing)
    assert [(o.id, o.type, o.size) for o in scene.objects] == [
        (o.id, o.type, o.size) for o in first.objects
    ]
    assert scene.seed == failing  # the scene's own seed: expansion, words and camera
    assert scene.timings["layout"] > first.timings["layout"]  # the two layouts add up

    fitting = scene_seed(0, next(i for i, kind in kinds.items() if kind == "ok"))
    scene, tried = laid_out_scene(context, spec, fitting)
    assert tried == {"layout_seed": fitting, "attempts": 1} and scene.layout.ok


def test_the_command_reports_retries_by_size_errors_with_locations_and_exits_1(made, cramped):
    root, code, out, err = made
    assert code == 1
    kinds = outcomes(cramped)
    counts = {kind: sum(k == kind for k in kinds.values()) for kind in ("ok", "fails", "error")}
    expected_error = f"{cramped}:9:30: expansion deeper than max_depth 3"
    assert (
        f"scenewright: error: the expansion failed for {counts['error']} of {SCENES} scenes (not made): "
        f"{expected_error} ({counts['error']}x)"
    ) in err
    assert f"error: {counts['fails']} of {SCENES} layouts failed after 1 retries (left out)" in err
    assert "#" not in err
    assert f"{counts['fails']} scenes needed a layout retry ({counts['fails']} retries" in out

    rows = [json.loads(line) for line in (root / METADATA_FILE).read_text().splitlines()]
    assert [int(r["scene_id"]) for r in rows] == [i for i, kind in kinds.items() if kind == "ok"]
    assert all(r["layout_seed"] == r["seed"] and r["attempts"] == 1 for r in rows)
    records = {i: json.loads((root / ".records" / f"{i:06d}.json").read_text()) for i in kinds}
    for index, kind in kinds.items():
        if kind == "fails":
            assert records[index]["stats"]["attempts"] == 2
            assert records[index]["stats"]["layout_seed"] == retry_seed(scene_seed(0, index), 1)
            assert (root / "failed" / f"{index:06d}.json").is_file()
        if kind == "error":
            assert records[index]["stats"]["error"]["stage"] == "expansion"

    stats = json.loads((root / "stats.json").read_text())
    assert (
        stats["failed_layouts"] == counts["fails"]
        and stats["failed"] == counts["fails"] + counts["error"]
    )
    assert stats["errors"] == {
        "expansion": {"scenes": counts["error"], "messages": {expected_error: counts["error"]}}
    }
    # Two crates always overlap in the yard; pushing them apart may also push one out.
    assert stats["problems"]["crate overlaps crate by # cm"] == counts["fails"]
    assert set(stats["problems"]) <= {
        "crate overlaps crate by # cm",
        "crate is outside the scene by # m",
    }
    assert stats["retries"]["by_objects"] == [
        {
            "objects": "1",
            "scenes": counts["ok"],
            "retried": 0,
            "retries": 0,
            "mean_layouts": 1.0,
            "failed_after_retries": 0,
        },
        {
            "objects": "2",
            "scenes": counts["fails"],
            "retried": counts["fails"],
            "retries": counts["fails"],
            "mean_layouts": 2.0,
            "failed_after_retries": counts["fails"],
        },
    ]


def test_two_workers_and_a_rerun_give_the_same_bytes_and_other_retries_are_refused(
    made, cramped, tmp_path, capsys
):
    root = made[0]
    assert main(command(cramped, tmp_path / "two", "--workers", "2", "-q")) == 1
    assert dataset_bytes(tmp_path / "two") == dataset_bytes(root)
    before = dataset_bytes(root)
    assert main(command(cramped, root, "-q")) == 1  # resumed: nothing to make, the same verdict
    assert dataset_bytes(root) == before
    capsys.readouterr()
    assert main([*command(cramped, root), "--retries", "2"]) == 2
    assert "other settings (retries 1 -> 2)" in capsys.readouterr().err


def test_a_dataset_made_before_retries_resumes_with_retries_0(tmp_path):
    stored = spec_of(4).settings()
    del stored["retries"]
    check_same_settings(spec_of(4, retries=0), stored, tmp_path)
    with pytest.raises(Exception, match="retries 0 -> 3"):
        check_same_settings(spec_of(4), stored, tmp_path)


def test_retries_by_size_bins_whole_numbers_of_objects():
    tries = [(10, 1, True), (12, 2, True), (17, 4, False), (40, 3, True), (41, 1, True)]
    summary = retries_by_size(tries)
    assert (summary["scenes_retried"], summary["retries"], summary["failed_after_retries"]) == (
        3,
        6,
        1,
    )
    bins = summary["by_objects"]
    assert [b["objects"] for b in bins] == ["10-13", "14-17", "38-41"]  # width ceil(32 / 8) = 4
    assert [b["scenes"] for b in bins] == [2, 1, 2] and [b["retries"] for b in bins] == [1, 3, 2]
    assert bins[0]["mean_layouts"] == 1.5 and bins[1]["failed_after_retries"] == 1
    assert sum(b["scenes"] for b in bins) == len(tries)
    assert retries_by_size([])["by_objects"] == []


def test_error_kind_drops_the_chain_and_keeps_the_location():
    message = "/data/r1_b_depth_small.rules:9:31: expansion deeper than max_depth 3 (expanding Row -> Row)"
    assert (
        error_kind(message)
        == "/data/r1_b_depth_small.rules:9:31: expansion deeper than max_depth 3"
    )
    assert (
        error_kind("r.rules:2:5: more than max_nodes 10 nodes")
        == "r.rules:2:5: more than max_nodes 10 nodes"
    )
