"""scene.json files written by scenewright, read as they are (checked by the shipped
scene.json schema), with a measured support added for any object that rests on
another without a support relation saying so."""

from __future__ import annotations

from dataclasses import replace

from scenewright.core.relations import RELATIONS, Relation
from scenewright.core.scene import Scene
from scenewright.core.schema_check import SceneSchemaError, validate_scene_dict

from .example import SUPPORT_LABEL, ExampleError
from .handwritten import parse_json
from .stacking import infer_supports


def read_scene_json(path: str, text: str, name: str) -> Scene:
    """The Scene of a scene.json ``text`` (``path`` names it in errors)."""
    data = parse_json(path, text)
    try:
        validate_scene_dict(data)
    except SceneSchemaError as error:
        raise ExampleError(path, error.path, error.problems[0][1]) from None
    try:
        scene = Scene.from_dict(data)
    except (
        KeyError,
        TypeError,
        ValueError,
    ) as error:  # what the schema lets through and the model refuses
        raise ExampleError(
            path, "", f"not a usable scene.json: {type(error).__name__}: {error}"
        ) from None
    supported = {
        r.source for r in scene.relations if r.label in RELATIONS and RELATIONS[r.label].support
    }
    measured = [
        Relation(upper, lower, SUPPORT_LABEL, 0.0, True)
        for upper, lower in infer_supports(scene.placed_objects()).items()
        if upper not in supported
    ]
    return replace(scene, relations=scene.relations + measured) if measured else scene
