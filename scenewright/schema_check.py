"""Check a scene.json document against the shipped JSON Schema.

The schema (``scenewright/schema/scene.schema.json``, package data) documents every
key ``Scene.to_dict()`` writes; tools reading scene.json can use it too.
``validate_scene_dict`` raises ``SceneSchemaError`` (an ``InputError``) naming the JSON
path of the problem, e.g. ``$.objects[2].position``.
"""

from __future__ import annotations

import json
from functools import lru_cache
from importlib import resources
from typing import Any

import jsonschema
from jsonschema.exceptions import best_match

from scenewright.core.errors import InputError

SCHEMA_FILE = "scene.schema.json"


class SceneSchemaError(InputError):
    """A scene.json document that does not follow the schema; ``path`` locates it."""

    def __init__(self, path: str, message: str):
        super().__init__(f"scene.json {path}: {message}")
        self.path = path


def load_schema() -> dict[str, Any]:
    """The scene.json JSON Schema (draft 2020-12) as a dict (a fresh copy each call)."""
    return json.loads(_schema_text())


def validate_scene_dict(data: Any) -> None:
    """Raise ``SceneSchemaError`` for the most relevant problem in ``data``, if any."""
    error = best_match(_validator().iter_errors(data))
    if error is not None:
        raise SceneSchemaError(json_path(error.absolute_path), _one_line(error.message))


def json_path(parts) -> str:
    """``$.objects[2].size`` style text for a sequence of keys and indices."""
    text = "$"
    for part in parts:
        text += f"[{part}]" if isinstance(part, int) else f".{part}"
    return text


@lru_cache(maxsize=1)
def _schema_text() -> str:
    return resources.files("scenewright").joinpath("schema", SCHEMA_FILE).read_text(encoding="utf-8")


@lru_cache(maxsize=1)
def _validator() -> jsonschema.Draft202012Validator:
    schema = load_schema()
    jsonschema.Draft202012Validator.check_schema(schema)
    return jsonschema.Draft202012Validator(schema)


def _one_line(message: str, limit: int = 200) -> str:
    """Error messages quote the offending value, which may be long or span lines."""
    flat = " ".join(message.split())
    return flat if len(flat) <= limit else flat[: limit - 3] + "..."
