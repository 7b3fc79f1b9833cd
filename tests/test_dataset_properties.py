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

from scenewright.atomic import remove_partials, write_atomic
from scenewright.cli import image_size
from scenewright.dataset import RECORDS_DIR, finished_indices, scene_stem, write_metadata


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
    states=st.lists(st.sampled_from(["done", "torn", "missing", "skipped"]), min_size=12, max_size=12),
    order=st.permutations(range(12)),
)
def test_only_whole_records_count_and_metadata_follows_the_index(count, states, order):
    """Records written in any order, some torn or absent: exactly the whole ones are
    finished, and metadata lists the written rows by index."""
    with tempfile.TemporaryDirectory() as directory:
        root = Path(directory)
        (root / RECORDS_DIR).mkdir()
        records = {}
        for index in order:
            state = states[index]
            record = {
                "index": index,
                "ok": state != "skipped",
                "row": None if state == "skipped" else {"i": index},
            }
            path = root / RECORDS_DIR / f"{scene_stem(index)}.json"
            if state == "torn":  # what a non-atomic writer could leave behind
                path.write_text(json.dumps(record)[:7])
            elif state != "missing":
                write_atomic(path, json.dumps(record))
                records[index] = record
        expected = {i for i in range(count) if states[i] in ("done", "skipped")}
        assert finished_indices(root, count) == expected
        rows = write_metadata(root, [records[i] for i in sorted(records)])
        lines = (root / "metadata.jsonl").read_text().splitlines()
        assert rows == len(lines) == sum(state == "done" for state in states)
        assert [json.loads(line)["i"] for line in lines] == sorted(
            i for i, s in enumerate(states) if s == "done"
        )


@given(width=st.integers(8, 8192), height=st.integers(8, 8192))
def test_size_option_round_trips(width, height):
    assert image_size(f"{width}x{height}") == (width, height)
    assert image_size(f"{width}X{height}") == (width, height)


@pytest.mark.parametrize("text", ["640", "x480", "640x", "0x480", "640x99999", "-640x480", "6.4x480", "axb"])
def test_size_option_refuses(text):
    with pytest.raises(argparse.ArgumentTypeError):
        image_size(text)
