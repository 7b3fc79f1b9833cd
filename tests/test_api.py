"""The Python API: generate() end to end, reproducibility, the Scene conveniences, and
the README's Python example (executed as it stands)."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

import scenewright
from scenewright.api import (
    build_scene,
    generate,
    render_scene,
    reproducible_json,
    summary_line,
    timings_of,
)
from scenewright.core.errors import InputError
from scenewright.core.scene import Scene

README = Path(__file__).parents[1] / "README.md"


def test_readme_python_example_runs(tmp_path, monkeypatch, capsys):
    blocks = re.findall(r"```python\n(.*?)```", README.read_text(), flags=re.DOTALL)
    assert blocks, "README.md has no python example"
    monkeypatch.chdir(tmp_path)
    for block in blocks:
        exec(compile(block, str(README), "exec"), {"__name__": "readme"})
    assert (tmp_path / "village.glb").read_bytes()[:4] == b"glTF"
    assert "(240, 320, 3)" in capsys.readouterr().out


def test_generate_fills_description_and_timings():
    scene = generate("village", seed=3, style="short", variant=1)
    assert isinstance(scene, Scene) and scene.placed_objects()
    assert scene.description.style == "short" and scene.description.variant == 1
    assert scene.description.text == scenewright.describe(scene, style="short", variant=1).text
    assert set(scene.timings) == {"expand", "layout", "describe"}
    assert scene.render is None
    assert summary_line(scene).startswith("ok: " if scene.layout.ok else "LAYOUT FAILED: ")


def test_same_rules_and_seed_give_identical_scene_json():
    first, second = generate("village", seed=11), generate("village", seed=11)
    assert reproducible_json(first) == reproducible_json(second)
    assert reproducible_json(first) != reproducible_json(generate("village", seed=12))
    assert first.timings and '"timings"' not in reproducible_json(first)
    assert '"seconds"' not in reproducible_json(first)
    assert set(timings_of(first)) == {"expand", "layout", "describe"}


def test_rules_by_name_path_or_loaded_give_the_same_scene(tmp_path):
    by_name = reproducible_json(build_scene("desk", 5))
    assert reproducible_json(build_scene(scenewright.load_rules("desk"), 5)) == by_name
    copy = tmp_path / "desk.rules"
    copy.write_text(Path(scenewright.load_rules("desk").path).read_text())
    from_path = build_scene(copy, 5)
    assert from_path.rules == str(copy)
    assert reproducible_json(from_path).replace(f'"{copy}"', '"desk"') == by_name


def test_render_and_export_a_generated_scene(tmp_path):
    scene = generate("desk", seed=2)
    before = reproducible_json(scene)
    rendered, images = render_scene(scene, size=(64, 48))
    assert images.colour.shape == (48, 64, 3)
    assert rendered.render["camera"] and "render" in rendered.timings
    assert (
        reproducible_json(scene) == before and scene.render is None
    )  # a new scene, the old one unchanged
    text = rendered.to_json()
    assert '"camera"' in text and Scene.from_json(text).to_json() == text
    assert scenewright.render_image(scene, 32, 24).colour.shape == (24, 32, 3)
    scenewright.export(scene, tmp_path / "desk.glb")
    assert (tmp_path / "desk.glb").stat().st_size > 0


def test_bad_style_view_and_rules_are_input_errors(tmp_path):
    with pytest.raises(InputError, match="unknown style 'long'"):
        generate("desk", style="long")
    with pytest.raises(InputError, match="unknown view"):
        scenewright.render_image(generate("desk"), view="side")
    with pytest.raises(InputError):
        generate(tmp_path / "missing.rules")


def test_the_apis_styles_and_views_are_the_describers_and_renderers():
    from scenewright.api import STYLES, VIEWS
    from scenewright.describer import STYLES as DESCRIBER_STYLES
    from scenewright.render.camera import VIEWS as CAMERA_VIEWS

    assert STYLES == DESCRIBER_STYLES and VIEWS == CAMERA_VIEWS


STALL = Path(__file__).parent / "rules" / "stall" / "stall.rules"


def test_a_rule_set_describes_its_scenes_with_its_own_templates():
    scene = generate(STALL, seed=1)
    assert scene.templates == str(STALL.parent.resolve() / "templates")
    # templates/inventory.j2 beside the rules replaces the package's overview sentence
    assert scene.description.text.startswith("At this stall the scene offers ")
    again = Scene.from_json(reproducible_json(scene))
    assert (
        again.templates == scene.templates
        and scenewright.describe(again).text == scene.description.text
    )
    from scenewright.describer.templates import PACKAGE_TEMPLATES

    assert scenewright.describe(scene, templates=PACKAGE_TEMPLATES).text.startswith(
        "The scene consists of "
    )


def test_templates_given_to_generate_replace_the_rule_sets_own(tmp_path):
    (tmp_path / "caption.j2").write_text("A tiny {{ setting }} with {{ items | join_list }}.")
    scene = generate(STALL, seed=1, style="short", templates=tmp_path)
    assert scene.templates == str(tmp_path.resolve())
    assert scene.description.text.startswith("A tiny stall with ")
    # the rule set's inventory.j2 is not read: the package's stands in for it
    assert scenewright.describe(scene).text.startswith("The scene consists of ")
    with pytest.raises(InputError, match="templates folder .* does not exist"):
        generate(STALL, templates=tmp_path / "missing")
    (tmp_path / "caption.j2").write_text("A {{ setting ")
    with pytest.raises(InputError, match=r"caption\.j2:1: unexpected end of template"):
        generate(STALL, templates=tmp_path)
