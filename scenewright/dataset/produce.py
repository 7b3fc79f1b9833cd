"""One dataset scene, made inside a worker process: generate, caption, render, encode.

A worker keeps a ``WorkerContext`` for its whole life: the parsed rules and one
``Renderer`` (one OpenGL context), made once by ``worker_context`` (the process pool's
initializer, or lazily on a dask worker). An OpenGL context is current in one thread
only, so a worker process running several threads (a dask worker with ``--nthreads``
above 1) gets one context per thread. ``produce_scene`` turns a scene index into a
``SceneProduct``: the encoded files and the scene's record. It writes nothing into the
dataset directory; the parent process does (``dataset.store_product``).

A scene has ``spec.views`` pictures (``view_picture``), each with its own row, files,
captions and COCO annotations (``coco``): from the automatic camera, or from
one drawn from ``spec.camera`` with the scene's camera stream of that view
(``render.views``). The layout and the full text are made once per scene.

Captions are made after the render, of the picture (``describer.view``: only what it
shows well enough, only relations that hold in it), and with ``grounding`` every
caption's and the full text's mentions go into the row with their pixel boxes, and
referring expressions for the objects the picture shows (``describer.refexp``); with
``questions``, CLEVR-style questions about the picture with their programs and answers
(``describer.questions``). ``PictureCaptions`` is a ``DatasetSpec`` that carries how (a plain ``DatasetSpec``
means the defaults).
"""

from __future__ import annotations

import threading
from collections import Counter
from dataclasses import dataclass, field, fields, replace
from time import process_time
from typing import TYPE_CHECKING

from scenewright.api import (
    build_scene,
    compose,
    describe,
    render_scene,
    reproducible_json,
    timed,
    timings_of,
)
from scenewright.core.errors import InputError, ScenewrightError
from scenewright.core.scene import Scene
from scenewright.core.seeds import retry_seed, stream
from scenewright.dataset.spec import (
    DatasetSpec,
    SceneProduct,
    file_digest,
    read_prompts,
    scene_seed,
    scene_stem,
)
from scenewright.generator.rules_errors import ExpansionError
from scenewright.house import house_scene_from

if TYPE_CHECKING:
    from scenewright.generator.layout.learned_term import LearnedContext
    from scenewright.generator.rules import Rules
    from scenewright.render.offscreen import Renderer


@dataclass(frozen=True)
class PictureCaptions(DatasetSpec):
    """A dataset's settings with how the captions of each picture are made.

    ``grounding``: add the row's ``grounding`` and ``refexps`` columns; ``questions``: add
    its ``questions`` column (and the dataset's questions.json); ``frame``: "scene" or "camera"
    (``describer.view``); ``min_visible`` and ``min_size``: the thresholds an entity must
    pass to be named in a caption (``render.visibility.Thresholds``; ``min_size`` None:
    16 pixels, or a sixteenth of the image's shorter side when that is less).
    """

    grounding: bool = True
    questions: bool = True
    frame: str = "scene"
    min_visible: float = 0.25
    min_size: int | None = None


#: What a plain ``DatasetSpec`` gets: grounding and questions on, the scene's frame, the default thresholds.
DEFAULT_CAPTIONS = PictureCaptions(rules="", rules_digest="", count=0)

#: The caption settings' defaults by name, which a plain ``DatasetSpec`` stores none of.
CAPTION_DEFAULTS = {
    f.name: getattr(DEFAULT_CAPTIONS, f.name)
    for f in fields(PictureCaptions)
    if f.name not in DatasetSpec.__dataclass_fields__
}


def with_picture_captions(spec: DatasetSpec, **options) -> DatasetSpec:
    """``spec`` with these caption ``options`` (``PictureCaptions``' fields), checked:
    an ``InputError`` for an unknown frame or a threshold out of range. Default options
    leave ``spec`` as it is, so its ``dataset.json`` is the same as a plain spec's."""
    from scenewright.describer.view import FRAMES
    from scenewright.render.visibility import Thresholds

    settings = {f.name: getattr(spec, f.name) for f in fields(spec)} | options
    made = PictureCaptions(**settings)
    Thresholds(made.min_visible, made.min_size)
    if made.frame not in FRAMES:
        raise InputError(
            f"unknown caption frame {made.frame!r}; expected one of: {', '.join(FRAMES)}"
        )
    defaults = all(getattr(made, name) == value for name, value in CAPTION_DEFAULTS.items())
    return spec if defaults and not isinstance(spec, PictureCaptions) else made


@dataclass
class WorkerContext:
    """What a worker builds once and reuses for every scene it makes."""

    settings: dict
    rules: Rules | None  # None: scenes composed from prompts with the shipped catalogs alone
    renderer: Renderer | None  # None for a dataset without images
    context: LearnedContext | None = None  # the learned context layouts sample with
    prompts: tuple[str, ...] = ()  # a prompts dataset's requests
    house: bool = False  # the scenes are houses of a plan (spec.rules names it)


_per_thread = threading.local()


def worker_context(spec: DatasetSpec) -> WorkerContext:
    """This thread's rules and renderer for ``spec``, made on first use."""
    context: WorkerContext | None = getattr(_per_thread, "context", None)
    if context is None or context.settings != spec.settings():
        from scenewright.api import is_house_plan, load_rules
        from scenewright.render.offscreen import Renderer

        if context is not None and context.renderer is not None:
            context.renderer.close()
        renderer = Renderer(*spec.size) if spec.images else None
        house = bool(spec.rules) and is_house_plan(spec.rules)
        context = WorkerContext(
            spec.settings(),
            load_rules(spec.rules) if spec.rules and not house else None,
            renderer,
            spec_context(spec),
            spec_prompts(spec),
            house,
        )
        _per_thread.context = context
    return context


def spec_context(spec: DatasetSpec) -> LearnedContext | None:
    """The learned context ``spec`` names, read once per worker; an ``InputError`` when
    its file changed since the dataset was set up (its digest differs)."""
    if spec.context is None:
        return None
    from scenewright.generator.layout.learned_term import read_context

    if file_digest(spec.context) != spec.context_digest:
        raise InputError(
            f"{spec.context}: the learned context changed since this dataset was set up"
        )
    return read_context(spec.context)


def spec_prompts(spec: DatasetSpec) -> tuple[str, ...]:
    """The prompts ``spec`` names, read once per worker (none without); an
    ``InputError`` when their file changed since the dataset was set up."""
    if spec.prompts is None:
        return ()
    if file_digest(spec.prompts) != spec.prompts_digest:
        raise InputError(f"{spec.prompts}: the prompts changed since this dataset was set up")
    return read_prompts(spec.prompts)


def produce_scene(spec: DatasetSpec, index: int) -> SceneProduct:
    """Make scene ``index`` of ``spec``: its files (images of each view, scene.json) and
    its record."""
    context = worker_context(spec)
    seed = scene_seed(spec.base_seed, index)
    stem = scene_stem(index)
    cpu: dict[str, float] = {}  # CPU seconds per stage (scene.timings are wall clock)
    recorded: dict = {}  # what the rows record beyond the layout's tries
    try:
        with timed(cpu, "layout", process_time):
            if context.prompts:
                scene, tried, recorded = composed_scene(context, spec, seed)
            elif context.house:  # each room retries its own layout (house.furnish)
                scene = house_scene_from(spec.rules, seed, label=spec.rules)
                tried = {"layout_seed": seed, "attempts": 1}
            else:
                scene, tried = laid_out_scene(context, spec, seed)
    except ScenewrightError as error:  # the rules fail for this seed (an expansion past its bounds)
        return SceneProduct(index, seed, False, {}, None, {"error": stage_error(error)})
    if not scene.layout.ok and not spec.include_failed:
        failed = {f"failed/{stem}.json": reproducible_json(scene).encode()}
        return SceneProduct(
            index, seed, False, failed, None, {**scene_stats(scene, [], cpu), **tried}
        )

    with timed(cpu, "describe", process_time), timed(scene.timings, "describe"):
        full = describe(scene, style="full")
        text = full if spec.text_words is None else describe(scene, words=spec.text_words)
    scene = replace(scene, description=full.record())
    if not spec.images:
        return text_product(spec, index, seed, scene, text.text, tried, cpu, recorded)
    pictures, renders = [], []
    for view in range(spec.views):
        scene, picture = view_picture(
            context, spec, scene, text, ViewName(stem, view, seed, tried, recorded), cpu
        )
        pictures.append(picture)
        renders.append(scene.render)
    scene = replace(scene, render=renders[0])  # scene.json holds the first view's render
    with timed(cpu, "encode", process_time):
        files = {name: data for picture in pictures for name, data in picture.files.items()}
        files[f"scenes/{stem}.json"] = reproducible_json(scene).encode()
    rows = [picture.row for picture in pictures]
    coco = [picture.annotations for picture in pictures] if spec.coco else None
    captions = [caption for picture in pictures for caption in picture.captions]
    stats = {**scene_stats(scene, [text.text, *captions], cpu), **tried}
    return SceneProduct(
        index, seed, scene.layout.ok, files, rows[0], stats, views=rows[1:], coco=coco
    )


@dataclass(frozen=True)
class ViewName:
    """Which picture: the scene's stem, the view's number, and what its row records of
    the scene (its seed, and ``layout_seed`` and ``attempts``)."""

    stem: str
    view: int
    seed: int
    tried: dict
    recorded: dict = field(default_factory=dict)  # the prompt columns of a prompts dataset

    def image_stem(self, views: int) -> str:
        """The stem of the view's images: the scene's with one view per scene, else
        ``<stem>_<view>``."""
        return self.stem if views == 1 else f"{self.stem}_{self.view}"


@dataclass
class ViewPicture:
    """One view of a scene: its files, metadata row, captions and COCO annotations."""

    files: dict[str, bytes]
    row: dict
    captions: list[str]
    annotations: list[dict]


def view_picture(
    context: WorkerContext,
    spec: DatasetSpec,
    scene: Scene,
    text,
    name: ViewName,
    cpu: dict[str, float],
) -> tuple[Scene, ViewPicture]:
    """Render view ``name.view`` of ``scene`` (``text``: the ``Description`` of the row's
    ``text`` column, the full one or the one within ``spec.text_words``), encode it,
    caption it; return the scene with that view's render and the view's picture. The
    camera is the automatic one, or drawn from ``spec.camera`` with the scene's camera
    stream of the view (a target the scene lacks: the whole scene)."""
    from scenewright.dataset.coco import view_annotations
    from scenewright.render.offscreen import depth_unit, encode_render
    from scenewright.render.views import camera_column, resolve_target

    camera = spec.camera
    if camera is not None and resolve_target(scene, camera.target) is None:
        camera = replace(camera, target=None)
    with timed(cpu, "render", process_time):
        scene, result = render_scene(
            scene,
            size=spec.size,
            view=spec.view,
            renderer=context.renderer,
            camera=camera,
            camera_view=name.view,
            normals=spec.normals,
        )
    with timed(cpu, "encode", process_time):  # only the images asked for
        kinds = ["colour", *["depth", "depth_metres"] * spec.depth]
        kinds += [*["segmentation", "ids"] * spec.segmentation, *["normals"] * spec.normals]
        images = {kind: data for kind, (_, data) in encode_render(result, kinds=kinds).items()}
        annotations = view_annotations(result, scene) if spec.coco else []
    with timed(cpu, "describe", process_time), timed(scene.timings, "describe"):
        grounded, captions = picture_captions(spec, scene, result, text, rules=context.rules)

    image = name.image_stem(spec.views)
    files = {f"images/{image}.png": images["colour"]}
    row: dict = {"file_name": f"images/{image}.png"}
    if spec.depth:
        files[f"depth/{image}.png"] = images["depth"]
        files[f"depth/{image}.npy"] = images["depth_metres"]
        row["depth_file_name"] = f"depth/{image}.png"
        row["depth_metres_path"] = f"depth/{image}.npy"
        row["depth_scale"] = depth_unit(result.depth)
    if spec.normals:
        files[f"normals/{image}.png"] = images["normals"]
        row["normals_file_name"] = f"normals/{image}.png"
    if spec.segmentation:
        files[f"segmentation/{image}.png"] = images["segmentation"]
        files[f"segmentation/{image}_ids.json"] = images["ids"]
        row["segmentation_file_name"] = f"segmentation/{image}.png"
    row.update(caption=captions[0], text=text.text)
    row.update({f"caption_{k}": caption for k, caption in enumerate(captions[1:], start=1)})
    row["scene_id"] = name.stem
    if spec.camera is not None:
        row["view"] = name.view
    row.update(seed=name.seed, **name.tried, rules=row_rules(spec), ok=scene.layout.ok)
    row.update(name.recorded)
    row["camera"] = camera_column(result.camera)
    if spec.boxes_3d and result.ground_truth is not None:
        row["objects_3d"] = result.ground_truth["objects"]
    row.update(grounded)
    return scene, ViewPicture(files, row, captions, annotations)


def text_product(
    spec: DatasetSpec,
    index: int,
    seed: int,
    scene: Scene,
    text: str,
    tried: dict,
    cpu: dict[str, float],
    recorded: dict | None = None,
) -> SceneProduct:
    """Scene ``index`` of a dataset without images: its scene.json and its description
    (``text``: the full one, or within ``spec.text_words``), and a row naming both (no
    picture, so no captions); ``recorded``: further columns (a prompt's)."""
    stem = scene_stem(index)
    files = {
        f"scenes/{stem}.json": reproducible_json(scene).encode(),
        f"texts/{stem}.txt": (text + "\n").encode(),
    }
    row = {
        "scene_file_name": f"scenes/{stem}.json",
        "text_file_name": f"texts/{stem}.txt",
        "text": text,
        "scene_id": stem,
        "seed": seed,
        **tried,
        "rules": row_rules(spec),
        "ok": scene.layout.ok,
        **(recorded or {}),
    }
    return SceneProduct(
        index, seed, scene.layout.ok, files, row, {**scene_stats(scene, [text], cpu), **tried}
    )


def picture_captions(
    spec: DatasetSpec, scene: Scene, result, text, rules: Rules | None = None
) -> tuple[dict, list[str]]:
    """The row's ``grounding`` and ``refexps`` columns (none when grounding is turned
    off), its ``questions`` column (none when questions are turned off) and its captions
    of the rendered picture ``result``, variants 0..K-1; ``text`` is the ``Description``
    of the row's ``text`` column; ``rules``: the scene's rule set, whose nouns questions may ask about
    (``describer.questions.vocabulary_of``; None: the scene's own nouns only)."""
    from scenewright.describer.programs import PictureFacts
    from scenewright.describer.questions import picture_questions, vocabulary_of
    from scenewright.describer.refexp import referring_expressions
    from scenewright.describer.view import describe_view, grounding_records
    from scenewright.render.visibility import PictureView, Thresholds

    if scene.house is not None:
        # a house's picture shows its whole floor from above: its overview is true of it
        # (the rooms' furniture is told in the text column, room by room)
        return {}, [describe(scene, style="short").text] * spec.captions
    options = captions_options(spec)
    picture = PictureView.from_render(
        result, scene, Thresholds(options.min_visible, options.min_size)
    )
    captions = [
        describe_view(scene, picture, frame=options.frame, variant=k, templates=scene.templates)
        for k in range(spec.captions)
    ]
    texts = [c.text for c in captions]
    columns: dict = {}
    facts = PictureFacts.of(scene, picture) if options.grounding or options.questions else None
    if options.grounding:
        names = ["caption"] + [f"caption_{k}" for k in range(1, spec.captions)]
        grounding = {
            column: grounding_records(c, picture) for column, c in zip(names, captions, strict=True)
        }
        grounding["text"] = grounding_records(text, picture)
        columns.update(grounding=grounding, refexps=referring_expressions(facts))
    if options.questions:
        columns["questions"] = picture_questions(facts, vocabulary_of(rules, scene), scene.seed)
    return columns, texts


def captions_options(spec: DatasetSpec) -> PictureCaptions:
    """How the captions of ``spec``'s pictures are made (a plain ``DatasetSpec``: the defaults)."""
    return spec if isinstance(spec, PictureCaptions) else DEFAULT_CAPTIONS


def laid_out_scene(context: WorkerContext, spec: DatasetSpec, seed: int) -> tuple[Scene, dict]:
    """The scene of ``seed``, its graph laid out with the layout seeds ``retry_seed(seed,
    0..spec.retries)`` until one is ok (the last one if none is), and what its row
    records of that: ``layout_seed`` (the one kept) and ``attempts``. The graph, and so
    what the scene holds, is the same in every attempt: retrying does not favour the
    scenes that are easy to lay out. ``timings`` add up the attempts."""
    spent: Counter = Counter()
    for attempt in range(spec.retries + 1):
        layout_seed = retry_seed(seed, attempt)
        scene = build_scene(
            context.rules,
            seed,
            templates=spec.templates,
            layout_seed=layout_seed,
            context=context.context,
        )
        spent.update(scene.timings)
        if scene.layout.ok:
            break
    return replace(scene, timings=dict(spent)), {
        "layout_seed": layout_seed,
        "attempts": attempt + 1,
    }


def composed_scene(
    context: WorkerContext, spec: DatasetSpec, seed: int
) -> tuple[Scene, dict, dict]:
    """The scene of ``seed`` in a prompts dataset: one prompt drawn with the scene's
    ``prompt`` stream, composed (``api.compose``, with the rule set's catalog) with the
    scene's seed and, while its layout is not ok, with ``retry_seed(seed, 1..retries)``
    (each compose lays out up to ``composer.compose.ATTEMPTS`` times). Returns the scene,
    its ``layout_seed`` and ``attempts`` (composes tried), and the prompt's columns:
    ``prompt``, ``prompt_index`` (its place among the file's prompts, from 0),
    ``prompt_used`` (the character spans used, [start, end)) and ``prompt_unused`` (each
    word or phrase not used: its span, text and message)."""
    index = int(stream(seed, "prompt").integers(len(context.prompts)))
    prompt = context.prompts[index]
    spent: Counter = Counter()
    for attempt in range(spec.retries + 1):
        layout_seed = retry_seed(seed, attempt)
        scene, report = compose(
            prompt,
            layout_seed,
            catalog=context.rules,
            templates=spec.templates,
            rules_label=row_rules(spec),
        )
        spent.update(scene.timings)
        if scene.layout.ok:
            break
    columns = {
        "prompt": prompt,
        "prompt_index": index,
        "prompt_used": [list(span) for span in report.used],
        "prompt_unused": [
            {"start": i.start, "end": i.end, "text": i.text, "message": i.message}
            for i in report.unused
        ],
    }
    tried = {"layout_seed": layout_seed, "attempts": attempt + 1}
    return replace(scene, timings=dict(spent)), tried, columns


def row_rules(spec: DatasetSpec) -> str:
    """The row's ``rules`` column: the rule set, or ``composed`` for a prompts dataset
    (as its scene.json says; the rule set whose catalog it may name is in dataset.json)."""
    from scenewright.composer.compose import RULES_LABEL

    return RULES_LABEL if spec.prompts is not None else spec.rules


def stage_error(error: ScenewrightError) -> dict:
    """What a record says of a scene the rules could not make: the stage that failed and
    the error's first line (``file:line:col: message`` for an expansion error, without
    the quoted source line)."""
    if isinstance(error, ExpansionError):
        where = error.diagnostic
        return {"stage": "expansion", "message": f"{where.location}: {where.message}"}
    return {"stage": "layout", "message": str(error).splitlines()[0]}


def scene_stats(scene: Scene, texts: list[str], cpu: dict[str, float]) -> dict:
    """What stats.json aggregates over scenes: objects, relations, text lengths, wall
    times per stage (``seconds``) and the worker's CPU times per stage (``cpu``: all its
    threads, a software OpenGL's rasterizer included)."""
    relations: dict[str, list[int]] = {}
    for relation in scene.relations:
        counts = relations.setdefault(relation.label, [0, 0])
        counts[0] += 1
        counts[1] += relation.satisfied
    return {
        "objects": dict(Counter(o.type for o in scene.placed_objects())),
        "relations": relations,
        "words": {"text": len(texts[0].split()), "captions": [len(t.split()) for t in texts[1:]]}
        if texts
        else {},
        "seconds": timings_of(scene),
        "cpu": {stage: round(seconds, 6) for stage, seconds in cpu.items()},
        "problems": list(scene.layout.problems),
    }
