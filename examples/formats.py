"""Which reader reads a file (``FORMATS``, a registry), and loading one or more examples.

A file is read whole (a regular file of at most ``MAX_EXAMPLE_BYTES``) and its format
found from its content: ``glTF`` magic bytes for GLB, a JSON object with the keys
``format`` and ``rules`` for a scenewright scene.json, any other JSON for the
hand-written format. A folder holding
a ``scene.json`` (what ``scenewright generate`` writes) stands for that file; any other
folder for the examples in it (``folder_examples``: its ``.json`` and ``.glb`` files
and its sub-folders holding a scene.json, in name order), so a set of examples can be
named by its folder. A folder ``scenewright dataset`` wrote (its ``dataset.json`` beside
a ``scenes`` folder) stands for the scenes in that folder. An example's name is its
file's stem, or its folder's name for a ``scene.json``.
"""

from __future__ import annotations

import codecs
import os
from collections.abc import Callable, Iterable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from scenewright.core.files import UnusableFile, load_json, read_regular_file
from scenewright.core.limits import MAX_SCENE_JSON_BYTES
from scenewright.core.scene import Scene

from .example import Example, ExampleError
from .glb import read_glb
from .handwritten import read_handwritten
from .scene_json import read_scene_json

#: The largest example file read (a GLB with its meshes, or JSON).
MAX_EXAMPLE_BYTES = max(MAX_SCENE_JSON_BYTES, 256 * 1024 * 1024)


@dataclass(frozen=True)
class ExampleFormat:
    """One format: its name, whether some bytes are in it, and its reader
    ``read(path, content, name) -> Scene`` (text for JSON formats, bytes for binary)."""

    name: str
    recognises: Callable[[bytes], bool]
    read: Callable[[str, Any, str], Scene]  # the content: bytes if ``binary``, else str
    binary: bool = False


def _json_object(data: bytes) -> dict | None:
    """The JSON object ``data`` holds, or None when it holds none (not UTF-8, not JSON,
    nested too deep, or another kind of value): the readers then say why."""
    if data.startswith(codecs.BOM_UTF8):
        data = data[len(codecs.BOM_UTF8) :]
    if not data.lstrip().startswith(b"{"):
        return None
    try:
        # NaN is kept here (as None) so a scene.json holding one is still told a scene.json,
        # whose own check then names where it is.
        document = load_json(data.decode("utf-8"), parse_constant=lambda constant: None)
    except (UnicodeDecodeError, ValueError):
        return None
    return document if isinstance(document, dict) else None


def _is_scene_json(data: bytes) -> bool:
    # A scene.json is a JSON object with the "format" and "rules" keys scenewright writes
    # (told by its structure, not by the words appearing somewhere in the text).
    document = _json_object(data)
    return document is not None and "rules" in document and "format" in document


#: Tried in order; the first that recognises a file reads it.
FORMATS: tuple[ExampleFormat, ...] = (
    ExampleFormat("glb", lambda data: data[:4] == b"glTF", read_glb, binary=True),
    ExampleFormat("scene.json", _is_scene_json, read_scene_json),
    ExampleFormat("example.json", lambda data: True, read_handwritten),
)


def example_file(path: str | os.PathLike[str]) -> Path:
    """The file an example path names: itself, or the scene.json of a folder holding one."""
    target = Path(path)
    return (
        target / "scene.json" if target.is_dir() and (target / "scene.json").is_file() else target
    )


def load_example(path: str | os.PathLike[str], name: str | None = None) -> Example:
    """The example in ``path`` (a file, or a folder holding a scene.json)."""
    target = example_file(path)
    shown = str(path)
    try:
        data = read_regular_file(target, MAX_EXAMPLE_BYTES, "an example file")
    except UnusableFile as problem:
        raise ExampleError(shown, "", f"cannot read: it {problem}") from None
    except OSError as error:
        raise ExampleError(shown, "", f"cannot read: {error.strerror or error}") from None
    if not data:
        raise ExampleError(shown, "", "is empty")
    if (
        data.startswith(codecs.BOM_UTF8) and data[:4] != b"glTF"
    ):  # Windows editors write one; JSON has none
        data = data[len(codecs.BOM_UTF8) :]
    default_name = (
        target.parent.name if target.name == "scene.json" and target.parent.name else target.stem
    )
    name = name or default_name or "example"
    for example_format in FORMATS:
        if example_format.recognises(data):
            if example_format.binary:
                content: object = data
            else:
                try:
                    content = data.decode("utf-8")
                except UnicodeDecodeError as error:
                    raise ExampleError(shown, "", f"not UTF-8 text (byte {error.start})") from None
            scene = example_format.read(str(target), content, name)
            return Example(name=name, path=str(target), format=example_format.name, scene=scene)
    raise ExampleError(
        shown, "", "not a format examples are read from"
    )  # pragma: no cover (the last one takes all)


#: The file endings of examples a folder of examples is read for.
EXAMPLE_SUFFIXES = (".json", ".glb")


#: What ``scenewright dataset`` writes into its folder: its settings, and the folder of
#: its scenes' scene.json files.
DATASET_SETTINGS, DATASET_SCENES = "dataset.json", "scenes"


def folder_examples(folder: Path) -> list[Path]:
    """The examples a folder without a scene.json stands for (module docstring)."""
    if (folder / DATASET_SETTINGS).is_file() and (folder / DATASET_SCENES).is_dir():
        return folder_examples(folder / DATASET_SCENES)  # a dataset: its scenes
    found = sorted(
        entry
        for entry in folder.iterdir()
        if (entry.is_file() and entry.suffix.lower() in EXAMPLE_SUFFIXES)
        or (entry.is_dir() and (entry / "scene.json").is_file())
    )
    if not found:
        raise ExampleError(
            str(folder), "", "holds no examples (.json or .glb files, or folders with a scene.json)"
        )
    return found


def example_paths(paths: Iterable[str | os.PathLike[str]]) -> list[str | os.PathLike[str]]:
    """``paths`` with each folder of examples (one without a scene.json) replaced by
    the examples in it (``folder_examples``)."""
    expanded: list[str | os.PathLike[str]] = []
    for path in paths:
        folder = Path(path)
        expanded += (
            folder_examples(folder)
            if folder.is_dir() and not (folder / "scene.json").is_file()
            else [path]
        )
    return expanded


def _example_bytes(path: str | os.PathLike[str]) -> bytes | None:
    """The bytes of the file an example path names, or None when it cannot be read
    (its reader then says why)."""
    try:
        return read_regular_file(example_file(path), MAX_EXAMPLE_BYTES, "an example file")
    except (UnusableFile, OSError):
        return None


def is_handwritten_example(path: str | os.PathLike[str]) -> bool:
    """Whether the file ``path`` is JSON for the hand-written reader rather than a
    scene.json: it lists ``objects`` and names no ``rules`` (every scene.json does; the
    hand-written format has no such key). False when it cannot be read."""
    data = _example_bytes(path)
    document = _json_object(data) if data is not None else None
    return document is not None and "objects" in document and "rules" not in document


def is_scene_json_file(path: str | os.PathLike[str]) -> bool:
    """Whether ``path`` (a file, or a folder holding a scene.json) is a scenewright
    scene.json, by the same test the readers use; False when it cannot be read."""
    data = _example_bytes(path)
    return data is not None and _is_scene_json(data)


def load_examples(paths: Iterable[str | os.PathLike[str]]) -> list[Example]:
    """The examples of ``paths`` in order (a folder of examples: each in name order),
    their names made unique (``bedroom``, ``bedroom-2``, ...). A file named twice (a
    folder and a file in it: ``dining/ dining/*.json``) is refused: counted twice, it
    would weigh double in every statistic learned from the examples."""
    examples: list[Example] = []
    taken: set[str] = set()
    read: dict[Path, str] = {}
    for path in example_paths(paths):
        target = example_file(path)
        try:
            key = target.resolve()
        except OSError:
            key = target
        if key in read:
            also = "" if read[key] == str(path) else f" (also as {read[key]})"
            raise ExampleError(str(path), "", f"is named twice{also}: an example counts once")
        read[key] = str(path)
        example = load_example(path)
        name, count = example.name, 1
        while name in taken:
            count += 1
            name = f"{example.name}-{count}"
        taken.add(name)
        example.name = name
        examples.append(example)
    if not examples:
        raise ExampleError("examples", "", "no example files given")
    return examples
