"""What a dataset is, shared by every part of the dataset job: its spec (``DatasetSpec``,
checked and made by ``dataset_spec``), the names of its files, the numbering of its
scenes and images, and what a worker returns for one scene (``SceneProduct``).

Every other module of the package imports this one and it imports none of them.
"""

from __future__ import annotations

import hashlib
import json
import os
from collections.abc import Callable
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from scenewright.api import DATASET_RETRIES
from scenewright.core.errors import InputError

if TYPE_CHECKING:
    from scenewright.render.views import CameraRanges

#: The settings that must not change when a run is resumed into the same directory.
SETTINGS_FILE = "dataset.json"
RECORDS_DIR = ".records"
METADATA_FILE = "metadata.jsonl"
#: Locked (``flock``) by the run using the directory, so a second run is refused; the
#: kernel releases the lock when that run ends in any way, ``kill -9`` included.
LOCK_FILE = ".lock"


def image_number(index: int, view: int, views: int) -> int:
    """Image ``view`` of scene ``index`` counted over the dataset's images (0-based), with
    ``views`` images a scene: unchanged when the dataset grows or shrinks."""
    return index * views + view


def scene_seed(base_seed: int, index: int) -> int:
    """The seed of scene ``index`` in a dataset with ``base_seed`` (a 32-bit integer)."""
    return int(np.random.SeedSequence([base_seed, index]).generate_state(1)[0])


def scene_stem(index: int) -> str:
    return f"{index:06d}"


@dataclass(frozen=True)
class DatasetSpec:
    """What to make. Everything here except ``count`` is fixed for a dataset directory.

    ``count`` (N) is how many scenes, indices 0..N-1, metadata.jsonl and the statistics
    cover; a rerun may raise it (more scenes are made) or lower it (scenes at N and
    above stay on disk but are no longer listed).

    ``rules`` is how the user named the rule set (shipped name or path) and
    ``rules_digest`` a hash of its text, so a resumed run cannot silently mix rule
    versions. ``captions`` is the number of short captions per scene (variants 0..K-1).
    ``retries`` is how many more times a failed layout is tried, with the layout seeds
    ``core.seeds.retry_seed(seed, 1..retries)``, the scene's graph unchanged.
    ``templates`` is the absolute path of a description templates folder that replaces
    the rule set's own, or None. ``coco``: write ``annotations/instances.json``
    (``coco``). ``views``: images per scene, each its own row; ``camera``: the
    ranges their cameras are drawn from (``render.views``), None for the automatic one.
    ``text_words``: the ``text`` column is the most detailed description (full, summary,
    short) of at most this many words (``describe(words=...)``), None: the full one;
    scene.json keeps the full description either way. ``context``: the absolute path of
    the learned context every layout samples with (``scenewright fit --what context``),
    None for none; ``context_digest`` a hash of its text, so a resumed run cannot mix
    contexts. ``depth``: each image's depth as a 16-bit PNG (its unit in the row's
    ``depth_scale``) and as float32 metres (``.npy``); ``normals``: a surface normals
    image per view; ``boxes_3d``: the row's ``objects_3d`` column (each entity's pose
    and 3D box in the camera frame, ``render.ground_truth``). ``prompts``: the absolute
    path of a prompts file (one request in English a line): each scene composes one of
    them, drawn with the scene's ``prompt`` stream (``composer``), and ``rules`` is then
    the rule set whose catalog the prompts may name besides the shipped indoor one
    (``""`` for none); ``prompts_digest`` a hash of the file's text.
    """

    rules: str
    rules_digest: str
    count: int
    base_seed: int = 0
    captions: int = 1
    templates: str | None = None
    size: tuple[int, int] = (512, 512)
    view: str = "perspective"
    depth: bool = False
    segmentation: bool = False
    include_failed: bool = False
    retries: int = DATASET_RETRIES
    #: False: no render, no images and no picture captions; a scene is its scene.json
    #: and its description (``texts/STEM.txt``), for fast example corpora.
    images: bool = True
    coco: bool = True
    views: int = 1
    camera: CameraRanges | None = None
    text_words: int | None = None
    context: str | None = None
    context_digest: str | None = None
    normals: bool = False
    boxes_3d: bool = False
    prompts: str | None = None
    prompts_digest: str | None = None

    def settings(self) -> dict:
        """The fixed part, as stored in ``dataset.json`` (tuples as lists, as JSON reads
        them back). The ground truth options added later (``normals``, ``boxes_3d``) are
        stored only when on, so a dataset made before them resumes as it was."""
        data = json.loads(json.dumps(asdict(self)))
        del data["count"]
        for name in LATER_OPTIONS:
            if not data[name]:
                del data[name]
        return data


#: Options stored in ``dataset.json`` only when on (``DatasetSpec.settings``).
LATER_OPTIONS = ("normals", "boxes_3d", "prompts", "prompts_digest")

#: The most prompts a prompts file may hold, and the longest prompt (characters).
MAX_PROMPTS = 100_000
MAX_PROMPT_CHARS = 2_000


def dataset_spec(
    rules,
    count: int,
    *,
    templates: str | os.PathLike[str] | None = None,
    context: str | os.PathLike[str] | None = None,
    prompts: str | os.PathLike[str] | None = None,
    **settings,
) -> DatasetSpec:
    """The spec for ``count`` scenes of a rule set (name, path or loaded Rules), or of
    the requests in a ``prompts`` file (``rules`` then the rule set whose catalog they
    may name, or None for the shipped indoor catalog alone).

    Loads (and so checks) the rules and the description templates the scenes will use
    (``templates``, else the rule set's own), names the rules as scene.json does, and
    hashes their text. ``context`` is a learned context file to lay every scene out
    with (read, so checked, and hashed; ``api.rules_context`` finds the one beside the
    rules). ``prompts`` is read (``read_prompts``) and hashed. ``settings`` are the
    other ``DatasetSpec`` fields; without images there is no COCO file, and several
    views or camera ranges are an ``InputError``.
    """
    from scenewright.api import (
        checked_templates,
        is_house_plan,
        load_rules,
        plan_file,
        plan_label,
        rules_context,
        rules_label,
    )

    if not settings.get("images", True):
        if settings.get("views", 1) > 1 or settings.get("camera") is not None:
            raise InputError(
                "--views and the camera options are for images: they cannot be used with --no-images"
            )
        settings["coco"] = False  # no picture, nothing to annotate
    if prompts is not None:
        if context is not None:
            raise InputError(
                "--context is for a rule set's scenes; scenes composed from prompts are laid out without one"
            )
        read_prompts(prompts)
        # each composed scene names its own types (a second look is TYPE_2): no one
        # list of COCO categories covers them
        settings.update(
            prompts=str(Path(prompts).resolve()), prompts_digest=file_digest(prompts), coco=False
        )
        if rules is None:
            return DatasetSpec(
                rules="",
                rules_digest="",
                count=count,
                templates=checked_templates(templates),
                **settings,
            )
    if is_house_plan(rules):
        if templates is not None or context is not None:
            raise InputError(
                "--templates and --context are for a rule set's scenes; "
                "a house's rooms are described and laid out by their own rule sets"
            )
        # rooms of several rule sets: no one catalog gives the COCO categories
        settings["coco"] = False
        return DatasetSpec(
            rules=plan_label(rules),
            rules_digest=file_digest(plan_file(rules)),
            count=count,
            templates=None,
            **settings,
        )
    loaded = load_rules(rules)
    if templates is None:
        checked_templates(loaded.params.templates)  # a broken one stops the run before any work
    else:
        templates = checked_templates(templates)
    digest = file_digest(loaded.path)
    if context is not None:
        path, _ = rules_context(loaded, context)  # an InputError for a file that is not a context
        settings.update(context=str(Path(path).resolve()), context_digest=file_digest(path))
    return DatasetSpec(
        rules=rules_label(loaded), rules_digest=digest, count=count, templates=templates, **settings
    )


def read_prompts(path: str | os.PathLike[str]) -> tuple[str, ...]:
    """The prompts of a prompts file: its lines that are not blank and do not start with
    ``#``, stripped. An ``InputError`` for a file that cannot be read as UTF-8, that
    holds no prompt, more than ``MAX_PROMPTS`` or one longer than ``MAX_PROMPT_CHARS``."""
    try:
        text = Path(path).read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as error:
        reason = getattr(error, "strerror", None) or "not UTF-8 text"
        raise InputError(f"{path}: cannot read the prompts: {reason}") from None
    prompts = []
    for number, line in enumerate(text.splitlines(), start=1):
        line = line.strip()
        if not line or line.startswith("#"):
            continue
        if len(line) > MAX_PROMPT_CHARS:
            raise InputError(
                f"{path}:{number}: a prompt of {len(line)} characters; at most {MAX_PROMPT_CHARS}"
            )
        prompts.append(line)
        if len(prompts) > MAX_PROMPTS:
            raise InputError(f"{path}: more than {MAX_PROMPTS} prompts")
    if not prompts:
        raise InputError(f"{path}: no prompt in it (one request a line; # starts a comment)")
    return tuple(prompts)


def file_digest(path: str | os.PathLike[str]) -> str:
    """The SHA-256 of a file's bytes, in hex."""
    return hashlib.sha256(Path(path).read_bytes()).hexdigest()


@dataclass
class SceneProduct:
    """What a worker returns for one scene: files to write and the scene's record.

    ``files`` maps paths relative to the dataset directory to their bytes. ``row`` is
    the scene's metadata.jsonl row, or None when the scene is left out (failed layout
    without ``include_failed``). ``stats`` feeds stats.json (see ``stats``).
    ``views``: the rows of the scene's further views (1, 2, ...), after ``row``, that of
    view 0. ``coco``: the COCO annotations of each row's image (``coco``), or
    None without COCO output.
    """

    index: int
    seed: int
    ok: bool
    files: dict[str, bytes]
    row: dict | None
    stats: dict = field(default_factory=dict)
    views: list[dict] = field(default_factory=list)
    coco: list[list[dict]] | None = None

    def record(self) -> dict:
        record = {
            "index": self.index,
            "seed": self.seed,
            "ok": self.ok,
            "files": sorted(self.files),
            "row": self.row,
            "stats": self.stats,
        }
        if self.views:
            record["views"] = self.views
        if self.coco is not None:
            record["coco"] = self.coco
        return record


#: Computes one scene in a worker process: ``produce(spec, index) -> SceneProduct``.
Producer = Callable[[DatasetSpec, int], SceneProduct]
