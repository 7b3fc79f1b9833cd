"""compose --complete: the composed room, then what the completion model adds to a room of
its kind, with what the text asked for kept where it stands."""

from __future__ import annotations

import json

import pytest

from scenewright.cli import main

TEXT = "a bedroom with a double bed against the north wall and a wardrobe"


@pytest.mark.slow
def test_complete_adds_around_what_the_text_asked_for(tmp_path):
    plain, full = tmp_path / "plain", tmp_path / "full"
    assert main(["compose", TEXT, "--seed", "1", "--no-render", "-o", str(plain)]) == 0
    assert main(["compose", TEXT, "--seed", "1", "--no-render", "--complete", "-o", str(full)]) in (
        0,
        1,
    )
    before = json.loads((plain / "scene.json").read_text())
    after = json.loads((full / "scene.json").read_text())
    poses = {o["id"]: o["position"] for o in after["objects"]}
    for obj in before["objects"]:
        assert poses[obj["id"]] == obj["position"]  # kept where it stood
    assert len(after["objects"]) > len(before["objects"])
    assert after["completion"]["counts"]["bed"] == 1


@pytest.mark.slow
def test_a_kept_lamp_is_not_lifted_onto_a_support_the_completion_adds(tmp_path):
    out = tmp_path / "lamps"
    code = main(["compose", "a room with two lamps", "--complete", "--no-render", "-o", str(out)])
    assert code in (0, 1)
    scene = json.loads((out / "scene.json").read_text())
    lamps = [o for o in scene["objects"] if o["id"] in ("lamp_1", "lamp_2")]
    assert len(lamps) == 2 and all(lamp["position"][1] == 0.0 for lamp in lamps)
