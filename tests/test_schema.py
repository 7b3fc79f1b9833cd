"""scene.json validates against the shipped schema; broken documents are located."""

import copy
import json

import jsonschema
import pytest
from render_fixtures import market_scene, renderer_or_skip

from scenewright.core.errors import InputError
from scenewright.core.scene import Relation, SceneDescription
from scenewright.core.schema_check import SceneSchemaError, load_schema, validate_scene_dict
from scenewright.render.offscreen import render_metadata


def scene_dict() -> dict:
    scene = market_scene()
    scene.relations = [Relation("sign_1", "table_1", "NextToRight", -0.01, True, None)]
    scene.description = SceneDescription(
        "A table.", [("sign_1", "NextToRight", "table_1")], "full", 0
    )
    return json.loads(scene.to_json())


def test_schema_is_valid_draft_2020_12_and_documents_every_key():
    schema = load_schema()
    jsonschema.Draft202012Validator.check_schema(schema)
    scene_keys = set(scene_dict())
    assert scene_keys <= set(schema["properties"])
    for name in ("object", "path", "relation", "layout"):
        part = schema["$defs"][name]
        assert all(
            "description" in spec or "$ref" in spec for spec in part["properties"].values()
        ), name


def test_a_scene_validates_as_written_and_reproducibly():
    validate_scene_dict(scene_dict())
    validate_scene_dict({**scene_dict(), "templates": "/rules/stall/templates"})
    validate_scene_dict(json.loads(market_scene().to_json(reproducible=True)))


def test_a_rendered_scene_validates():
    renderer = renderer_or_skip(64, 48)
    with renderer:
        scene = market_scene()
        scene.render = render_metadata(renderer.render(scene, "top"))
    validate_scene_dict(json.loads(scene.to_json()))


@pytest.mark.parametrize(
    "break_it, path",
    [
        (lambda d: d["objects"][1].update(position=[1.0, 2.0]), "$.objects[1].position"),
        (lambda d: d["objects"][0].update(kind="thing"), "$.objects[0].kind"),
        (lambda d: d["paths"][0].update(points=[[0.0, 1.0]]), "$.paths[0].points"),
        (lambda d: d["relations"][0].pop("satisfied"), "$.relations[0]"),
        (lambda d: d.update(seed="seven"), "$.seed"),
        (lambda d: d.pop("objects"), "$"),
        (lambda d: d.update(description={"facts": []}), "$.description"),
        (lambda d: d.update(templates=["words"]), "$.templates"),
    ],
)
def test_broken_documents_are_refused_with_their_location(break_it, path):
    data = copy.deepcopy(scene_dict())
    break_it(data)
    with pytest.raises(SceneSchemaError) as caught:
        validate_scene_dict(data)
    assert isinstance(caught.value, InputError)
    assert caught.value.path == path
    assert "\n" not in str(caught.value) and str(caught.value).startswith(f"scene.json {path}: ")


@pytest.mark.parametrize("rules", ["desk", "bedroom"])
def test_generated_scenes_validate(rules):
    from scenewright.api import build_scene  # expansion and layout, no description

    validate_scene_dict(json.loads(build_scene(rules, seed=1).to_json()))
