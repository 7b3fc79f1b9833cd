"""The README's rules tutorial is real: its rule set loads, and generates the text shown."""

from __future__ import annotations

import re
from pathlib import Path

from scenewright.api import build_scene, describe
from scenewright.generator import check_rules, load_rules

README = (Path(__file__).parents[1] / "README.md").read_text()


def tutorial_rules(tmp_path: Path) -> Path:
    blocks = re.findall(r"```rules\n(.*?)```", README, flags=re.DOTALL)
    assert len(blocks) == 1, "README should have exactly one rules tutorial block"
    path = tmp_path / "market.rules"
    path.write_text(blocks[0])
    return path


def shown_description() -> str:
    shown = README.split("$ cat out/description.txt\n", 1)[1].split("```", 1)[0]
    return " ".join(shown.split())


def test_tutorial_rules_have_no_diagnostics(tmp_path):
    assert check_rules(tutorial_rules(tmp_path)) == []


def test_tutorial_generates_the_description_shown(tmp_path):
    scene = build_scene(load_rules(tutorial_rules(tmp_path)), 3)
    assert scene.layout.ok
    assert describe(scene).text == shown_description()
