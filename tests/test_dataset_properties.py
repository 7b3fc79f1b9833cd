"""Property tests of the pieces resume relies on: atomic writes, which records count as
finished, metadata rebuilt in index order, and the size option's parser."""

from __future__ import annotations

import argparse
import json
import tempfile
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from scenewright.cli.options import image_size
from scenewright.core.atomic import remove_partials, write_atomic
from scenewright.dataset.run import finished_indices, publish_metadata
from scenewright.dataset.spec import METADATA_FILE, RECORDS_DIR, scene_stem


@settings(max_examples=40, deadline=None)
@given(payloads=st.lists(st.binary(max_size=200) | st.text(max_size=50), min_size=1, max_size=4))
def test_atomic_write_leaves_the_last_payload_and_no_temporary(payloads):
    with tempfile.TemporaryDirectory() as directory:
        target = Path(directory) / "file.bin"
        for payload in payloads:
            write_atomic(target, payload)
        last = payloads[-1]
        assert target.read_bytes() == (last.encode() if isinstance(last, str) else last)
        assert [p.name for p in Path(directory).iterdir()] == ["file.bin"]
        assert remove_partials(directory) == 0


@settings(max_examples=40, deadline=None)
@given(
    count=st.integers(1, 12),
    states=st.lists(
        st.sampled_from(["done", "torn", "missing", "failed"]), min_size=12, max_size=12
    ),
    order=st.permutations(range(12)),
)
def test_only_whole_records_count_and_metadata_follows_the_index(count, states, order):
    """Records written in any order, some torn or absent: exactly the whole ones are
    finished; once the rest are made, metadata lists the written rows by index."""

    def record_of(index: int) -> str:
        failed = states[index] == "failed"
        stats = {"objects": {"table": 1}}
        return json.dumps(
            {
                "index": index,
                "ok": not failed,
                "row": None if failed else {"i": index},
                "stats": stats,
            }
        )

    with tempfile.TemporaryDirectory() as directory:
        root = Path(directory)
        (root / RECORDS_DIR).mkdir()
        for index in order:
            path = root / RECORDS_DIR / f"{scene_stem(index)}.json"
            if states[index] == "torn":  # what a writer that is not atomic could leave
                path.write_text(record_of(index)[:7])
            elif states[index] != "missing":
                write_atomic(path, record_of(index))
        expected = {i for i in range(count) if states[i] in ("done", "failed")}
        assert {i for i in finished_indices(root) if i < count} == expected

        for index in reversed(order):  # a rerun makes the rest, finishing in any order
            if index not in finished_indices(root):
                write_atomic(root / RECORDS_DIR / f"{scene_stem(index)}.json", record_of(index))
        collector = publish_metadata(root, 12)
        lines = (root / METADATA_FILE).read_text().splitlines()
        assert [json.loads(line)["i"] for line in lines] == [
            i for i in range(12) if states[i] != "failed"
        ]
        assert (collector.scenes, collector.written, collector.objects["table"]) == (
            12,
            len(lines),
            12,
        )


@given(width=st.integers(8, 8192), height=st.integers(8, 8192))
def test_size_option_round_trips(width, height):
    assert image_size(f"{width}x{height}") == (width, height)
    assert image_size(f"{width}X{height}") == (width, height)


@pytest.mark.parametrize(
    "text", ["640", "x480", "640x", "0x480", "640x99999", "-640x480", "6.4x480", "axb"]
)
def test_size_option_refuses(text):
    with pytest.raises(argparse.ArgumentTypeError):
        image_size(text)


def test_atomic_write_gives_the_mode_open_would(tmp_path):
    from scenewright.core.atomic import write_atomic

    target = write_atomic(tmp_path / "a.txt", "x")
    plain = tmp_path / "b.txt"
    plain.write_text("x")
    assert target.stat().st_mode & 0o777 == plain.stat().st_mode & 0o777
