"""The pipeline in one call: rules -> scene graph -> layout -> Scene -> text -> images.

``generate`` is what the README shows and what the CLI and the dataset job build on;
the smaller functions here are its steps. ``layout_again`` lays a scene out anew around
pinned objects and ``complete_room`` furnishes a room from a plan set, each described;
``scene_folder.write_scene`` writes any of them as ``scenewright generate`` does. Stages return values; the steps here join
them into a new Scene (``dataclasses.replace``), never change the one they were given,
and add their wall time to the new scene's ``timings`` (seconds, keys ``expand``,
``layout``, ``describe``, ``render``, ``export``).

Seeds: one int per scene, validated here (``check_seed``); each stage draws from its own
child stream of it (``scenewright.core.seeds``).

Reproducibility: the same rules, seed and scenewright version give the same scene. Wall
clock times are the one thing that differs between runs, so ``reproducible_json`` leaves
them out of scene.json and callers store them beside it (``timings.json``).

Stage modules (and numpy, networkx) are imported inside the functions: ``import
scenewright`` and ``scenewright --help`` stay fast and never start OpenGL.
"""

from __future__ import annotations

import os
from dataclasses import replace
from pathlib import Path
from typing import TYPE_CHECKING, Any

from scenewright.core.errors import InputError
from scenewright.core.relations import RELATIONS
from scenewright.core.timing import timed

if TYPE_CHECKING:
    from collections.abc import Mapping

    from scenewright.completion.complete import Request
    from scenewright.composer.compose import Report as ComposeReport
    from scenewright.core.scene import Scene
    from scenewright.describer import Description
    from scenewright.generator.layout.learned_term import LearnedContext
    from scenewright.generator.rules import CatalogEntry, Rules
    from scenewright.render.offscreen import Renderer, RenderResult
    from scenewright.render.views import CameraRanges

#: The description styles and camera views, here as well as in the describer and the
#: renderer so that checking an option does not import those (a test keeps them equal).
STYLES = ("full", "summary", "short")
VIEWS = ("perspective", "top")
DEFAULT_SIZE = (640, 480)
#: A dataset's layout retries per scene (``DatasetSpec.retries``, ``dataset --retries``):
#: with a share p of layouts failing, a scene stays failed with probability p**4, 0.8 %
#: at p = 0.3 and 0.01 % at p = 0.1. A rule set failing more often than that needs its
#: rules fixed rather than more attempts; a retry costs one more layout of that scene.
DATASET_RETRIES = 3


def load_rules(source: str | os.PathLike[str] | Rules) -> Rules:
    """A loaded rule set from a shipped name (``"village"``), a path, or Rules as they are."""
    from scenewright.generator import load_rules as load

    if isinstance(source, (str, os.PathLike)):
        return load(source)
    return source


def rules_label(rules: Rules) -> str:
    """How scene.json names the rule set: the shipped name, or the file's path."""
    from importlib.resources import files

    from scenewright.generator import shipped_rule_sets

    if rules.name in shipped_rule_sets():
        shipped = Path(str(files("scenewright.grammar_rules").joinpath(f"{rules.name}.rules")))
        if shipped.resolve() == Path(rules.path).resolve():
            return rules.name
    return str(rules.path)


def build_scene(
    rules: str | os.PathLike[str] | Rules,
    seed: int,
    *,
    templates: str | os.PathLike[str] | None = None,
    layout_seed: int | None = None,
    context: LearnedContext | str | os.PathLike[str] | None = None,
) -> Scene:
    """Expand the grammar with ``seed`` and lay the graph out: a Scene without text or images.

    ``context``: a learned context the layout samples with, or the path of a context
    file (``NAME.context.json``, as ``fit --what context`` writes it).

    ``templates``, a folder of description templates, replaces the rule set's own in
    ``scene.templates`` (as an absolute path), so every description of the scene uses it.
    ``layout_seed`` (default ``seed``) names the layout's streams alone: the same graph
    laid out again, as a dataset's retry of a failed layout does (``core.seeds.retry_seed``).
    """
    from scenewright.core.scene import assemble_scene
    from scenewright.core.seeds import check_seed
    from scenewright.generator import expand
    from scenewright.generator.layout import layout_scene

    seed = check_seed(seed)
    layout_seed = seed if layout_seed is None else check_seed(layout_seed, "layout seed")
    loaded = load_rules(rules)
    if isinstance(context, (str, os.PathLike)):
        from scenewright.generator.layout.learned_term import read_context

        where = os.fspath(context)
        context = read_context(where)
        context.check_rules(loaded.path, where)
    timings: dict[str, float] = {}
    with timed(timings, "expand"):
        graph = expand(loaded, seed)
    with timed(timings, "layout"):
        layout = layout_scene(graph, layout_seed, context=context)
    scene = assemble_scene(graph, layout, rules=rules_label(loaded), seed=seed)
    if templates is not None:
        scene.templates = str(Path(templates).resolve())
    scene.timings.update(timings)
    return scene


def describe(
    scene: Scene,
    style: str = "full",
    variant: int = 0,
    templates: str | os.PathLike[str] | None = None,
    words: int | None = None,
) -> Description:
    """An English description of ``scene`` (a ``Description``); the scene is unchanged.

    ``templates``: a folder of description templates for this description only; by
    default the scene's own (``scene.templates``, from its rule set), if any.
    ``words``: a word budget that chooses the style instead (``describer.describe``).
    """
    from scenewright.describer import describe as describe_stage

    check_choice("style", style, STYLES)
    if scene.house is not None:  # a house: an overview, then each room as rooms are described
        from scenewright.house.describe import describe_house

        return describe_house(scene, style=style if words is None else "full", variant=variant)
    return describe_stage(
        scene, style=style, variant=variant, templates=templates or scene.templates, words=words
    )


def describe_scene(
    scene: Scene,
    *,
    style: str = "full",
    variant: int = 0,
    templates: str | os.PathLike[str] | None = None,
    words: int | None = None,
) -> Scene:
    """``scene`` with its description (``describe``) and the time it took."""
    timings = dict(scene.timings)
    with timed(timings, "describe"):
        description = describe(
            scene, style=style, variant=variant, templates=templates, words=words
        )
    return replace(scene, description=description.record(), timings=timings)


def render_image(
    scene: Scene,
    width: int = DEFAULT_SIZE[0],
    height: int = DEFAULT_SIZE[1],
    view: str = "perspective",
    renderer: Renderer | None = None,
    *,
    camera: CameraRanges | None = None,
    camera_view: int = 0,
    normals: bool = False,
) -> RenderResult:
    """Render ``scene`` offscreen: colour, depth, segmentation, per-object metadata
    (``RenderResult.metadata`` is what scene.json stores under ``render``) and 3D ground
    truth (``RenderResult.ground_truth``); ``normals``: the surface normals image too.

    Pass a ``renderer`` to reuse one OpenGL context over many scenes (the image then has
    the renderer's size); otherwise one is made for this call and closed after it.

    ``camera``: draw a perspective camera from these ranges (``render.views``) with the
    scene's ``camera`` stream ``camera_view`` (``core.seeds``) instead of the automatic
    one; a target the scene lacks is an ``InputError``, as is ``view="top"`` with it.
    """
    from scenewright.render.offscreen import Renderer

    check_choice("view", view, VIEWS)
    if camera is not None and view != "perspective":
        raise InputError("a drawn camera (--camera) is a perspective one; leave out --view top")
    if renderer is not None:
        return _render_with(renderer, scene, view, camera, camera_view, normals)
    with Renderer(width, height) as own:
        return _render_with(own, scene, view, camera, camera_view, normals)


def _render_with(
    renderer: Renderer,
    scene: Scene,
    view: str,
    camera: CameraRanges | None,
    camera_view: int,
    normals: bool,
) -> RenderResult:
    if camera is None:
        return renderer.render(scene, view=view, normals=normals)
    from scenewright.core.seeds import stream
    from scenewright.render.views import aimed_view

    rng = stream(scene.seed, "camera", camera_view)
    return aimed_view(renderer, scene, camera, rng, require_target=True, normals=normals)


def render_scene(
    scene: Scene,
    *,
    size: tuple[int, int] = DEFAULT_SIZE,
    view: str = "perspective",
    renderer: Renderer | None = None,
    camera: CameraRanges | None = None,
    camera_view: int = 0,
    normals: bool = False,
) -> tuple[Scene, RenderResult]:
    """``scene`` with its render metadata and the time it took, and the images
    (``camera``, ``camera_view``, ``normals``: as ``render_image``)."""
    from scenewright.render.offscreen import render_metadata

    timings = dict(scene.timings)
    with timed(timings, "render"):
        result = render_image(
            scene,
            *size,
            view=view,
            renderer=renderer,
            camera=camera,
            camera_view=camera_view,
            normals=normals,
        )
    return replace(scene, render=render_metadata(result), timings=timings), result


def export(
    scene: Scene,
    path: str | os.PathLike[str],
    *,
    ground: bool = True,
    camera: bool = True,
    light: bool = True,
    cutaway: bool = False,
) -> Path:
    """Write the scene as a binary glTF file (one named node per object, materials,
    normals; with its ground or floor, the preview's camera and sun unless told
    otherwise; ``cutaway`` leaves out the walls the preview cuts away), or, for a path
    ending in .usda, .usdc or .usd, as a USD stage of the same content."""
    from scenewright.render.export import export_glb
    from scenewright.render.usd_export import USD_SUFFIXES, export_usd

    write = export_usd if Path(path).suffix.lower() in USD_SUFFIXES else export_glb
    write(scene, path, ground=ground, camera=camera, light=light, cutaway=cutaway)
    return Path(path)


def generate(
    rules: str | os.PathLike[str] | Rules,
    seed: int = 0,
    *,
    style: str = "full",
    variant: int = 0,
    templates: str | os.PathLike[str] | None = None,
    words: int | None = None,
    context: LearnedContext | str | os.PathLike[str] | None = None,
) -> Scene:
    """Generate one scene: expand, lay out and describe it (``words``: a word budget, see ``describe``).

    ``rules`` is a shipped rule-set name, a path to a ``.rules`` file, or loaded Rules;
    ``seed`` a whole number from 0 to 2**63 - 1. The returned Scene has ``description``
    filled and ``timings`` per stage; ``render_image(scene)`` draws it and ``export(scene,
    path)`` writes its GLB. A layout that could not satisfy everything is returned as
    it is, with ``scene.layout.ok`` false and ``scene.layout.problems`` saying why.

    ``templates`` is a folder of description templates that replaces the rule set's
    own (the scene block's ``templates``); the scene records it in ``scene.templates``
    so that describing the scene again uses it too.

    ``context`` is a learned context (``scenewright fit --what context``), or the path
    of its file: the layout then samples its pairs at temperature 1. The CLI's
    ``generate`` uses the one beside a rules file by default; this function only the
    one it is given (``rules_context`` finds the one beside a rules file).
    """
    check_choice("style", style, STYLES)
    if is_house_plan(rules):
        return generate_house(rules, seed, style=style, variant=variant)  # type: ignore[arg-type]
    scene = build_scene(rules, seed, templates=checked_templates(templates), context=context)
    return describe_scene(scene, style=style, variant=variant, words=words)


def is_house_plan(source: object) -> bool:
    """Whether ``source`` names a house: a plan file (``plan NAME { ... }``, shipped or a
    path) or a given floor plan (``.json``)."""
    if not isinstance(source, (str, os.PathLike)):
        return False
    from scenewright.house import is_plan_file
    from scenewright.house.given_plan import is_given_plan

    return is_given_plan(source) or is_plan_file(source)


def generate_house(
    plan: str | os.PathLike[str],
    seed: int = 0,
    *,
    style: str = "full",
    variant: int = 0,
    workers: int = 1,
) -> Scene:
    """A house of several rooms: the floor plan ``plan`` (a plan file's name or path, or a
    given plan as ``.json``) drawn with ``seed``, each room furnished by its room type's
    rule set (``workers`` processes lay rooms out side by side, with the same result), then
    described. ``scene.house`` holds the plan; objects are named ``ROOM/OBJECT``."""
    from scenewright.house import house_scene_from
    from scenewright.house.describe import describe_house

    check_choice("style", style, STYLES)
    timings: dict[str, float] = {}
    with timed(timings, "layout"):
        scene = house_scene_from(plan, seed, workers=workers, label=plan_label(plan))
    with timed(timings, "describe"):
        description = describe_house(scene, style=style, variant=variant)
    return replace(scene, description=description.record(), timings=timings)


def plan_label(plan: str | os.PathLike[str]) -> str:
    """How scene.json names a house's plan: the shipped plan's name, or the file's path."""
    from scenewright.house import shipped_plans

    label = os.fspath(plan)
    return label if label in shipped_plans() else str(Path(label).resolve())


def plan_file(plan: str | os.PathLike[str]) -> Path:
    """The file a house plan is read from (a shipped plan's, or the path given)."""
    from scenewright.house.plan_language import plan_path

    return plan_path(plan) or Path(os.fspath(plan))


def compose(
    text: str,
    seed: int = 0,
    *,
    catalog: str | os.PathLike[str] | Rules | None = None,
    style: str = "full",
    variant: int = 0,
    words: int | None = None,
    templates: str | os.PathLike[str] | None = None,
    rules_label: str | None = None,
) -> tuple[Scene, ComposeReport]:
    """A scene from English (docs/compose.md): the things ``text`` names, with the
    relations it states, in the room it describes, laid out with ``seed`` and described.

    ``catalog``: a rule set (shipped name, path or Rules) whose object types may be
    named besides the shipped indoor catalog's (outdoors: the outdoor catalog's). Returns the Scene and a report: the
    character spans used, every word or phrase not used (``report.messages()``), the
    rule set written (``report.rules``) and the statements the layout could not satisfy
    (``report.conflicts()``). ``style``, ``variant``, ``words``, ``templates``: as in
    ``generate``. ``rules_label``: how scene.json names the rule set
    (``"composed"``, or the file the rule set is kept in).
    """
    from scenewright.composer.compose import RULES_LABEL, lay_out, plan, report_of
    from scenewright.composer.outdoor import catalog_for

    check_choice("style", style, STYLES)
    templates = checked_templates(templates)  # before any work
    allow: tuple[str, ...] = ()
    own = None
    if catalog is not None:
        own = load_rules(catalog)
        allow = (str(Path(own.path).parent),)
    entries, prefer, ground = catalog_for(text, own)
    request, rules = plan(text, entries, prefer, ground)
    scene, unsatisfied, crowded = lay_out(
        rules, request, seed, label=rules_label or RULES_LABEL, allow=allow
    )
    report = report_of(text, request, rules)
    report.unsatisfied = unsatisfied
    report.crowded = crowded
    if templates is not None:
        scene.templates = templates
    return describe_scene(scene, style=style, variant=variant, words=words), report


def complete_room(
    request: Request,
    seed: int,
    *,
    plans: str | os.PathLike[str] | None = None,
    catalog: Mapping[str, CatalogEntry] | None = None,
    keep: Scene | None = None,
    templates: str | os.PathLike[str] | None = None,
    style: str = "full",
    variant: int = 0,
    words: int | None = None,
) -> Scene:
    """A room furnished from a plan set (``completion.complete``: ``request``, ``seed``,
    ``plans``, ``catalog``, ``keep``) and described (``templates``, ``style``,
    ``variant``, ``words``: as in ``describe``); ``scene.completion`` records what was
    chosen and why."""
    from scenewright.completion.complete import complete

    templates = checked_templates(templates)
    scene = complete(request, seed, plans=plans, catalog=catalog, keep=keep)
    return describe_scene(scene, style=style, variant=variant, templates=templates, words=words)


class SceneGraphError(InputError):
    """A scene (read from a scene.json) whose graph cannot be laid out again."""


def layout_again(
    scene: Scene,
    seed: int,
    *,
    pin: list[str] | tuple[str, ...] = (),
    warm: bool = False,
    context: LearnedContext | str | os.PathLike[str] | None = None,
    templates: str | os.PathLike[str] | None = None,
    style: str = "full",
    variant: int = 0,
    words: int | None = None,
) -> tuple[Scene, list[str]]:
    """``scene`` laid out again with the layout seed ``seed`` and described, keeping the
    ids in ``pin`` exactly where they stand (a group pins its members, a path its
    control points and first junction, an object what stands on it); with ``warm`` the
    rest starts from its poses in ``scene``. ``context``: as in ``build_scene``;
    ``templates``, ``style``, ``variant``, ``words``: as in ``generate``. Returns the new
    scene (its rules and derivation those of ``scene``, its seed ``seed``) and the ids
    pinned along with those named. ``SceneGraphError`` when the scene's graph cannot be
    laid out."""
    from scenewright.core.scene import assemble_scene
    from scenewright.core.seeds import check_seed
    from scenewright.generator.layout import layout_scene
    from scenewright.generator.layout.pinning import pins_from_scene, scene_layout
    from scenewright.generator.layout.problem import compile_problem

    seed = check_seed(seed, "layout seed")
    templates = checked_templates(templates)
    if scene.house is not None:
        return _house_layout_again(scene, seed, pin, warm=warm, style=style, variant=variant)
    try:
        graph = scene.graph()
        problem = compile_problem(graph)
    except InputError as error:
        raise SceneGraphError(str(error)) from error
    except (KeyError, ValueError, TypeError) as error:
        raise SceneGraphError(f"not a valid scene graph: {error}") from error
    pins = pins_from_scene(scene, problem, list(pin))
    start = None
    if warm:
        poses, points = scene_layout(scene)
        start = {**poses, **points}
    if isinstance(context, (str, os.PathLike)):
        from scenewright.generator.layout.learned_term import read_context

        where = os.fspath(context)
        context = read_context(where)
        rules_file = shipped_rules_file(scene.rules) or scene.rules
        context.check_rules(rules_file if Path(rules_file).is_file() else None, where)
    timings: dict[str, float] = {}
    with timed(timings, "layout"):
        layout = layout_scene(
            graph,
            seed,
            pinned=pins.poses,
            pinned_paths=pins.paths,
            start=start,
            context=context,
        )
    laid_out = assemble_scene(graph, layout, rules=scene.rules, seed=seed)
    laid_out.derivation = list(scene.derivation)
    if templates is not None:
        laid_out.templates = templates
    laid_out.timings.update(timings)
    described = describe_scene(laid_out, style=style, variant=variant, words=words)
    return described, list(pins.added)


def _house_layout_again(
    scene: Scene, seed: int, pin, *, warm: bool, style: str, variant: int
) -> tuple[Scene, list[str]]:
    """``layout_again`` for a house: each room laid out again on its own (room k with the
    seed the house furnishes room k with, ``house.furnish.room_seed``), keeping the pinned
    ids of that room (``ROOM/OBJECT``); the plan stays as it is."""
    from scenewright.core.house import in_room, room_of
    from scenewright.house.assemble import house_scene, room_scene
    from scenewright.house.furnish import room_seed

    house = scene.house
    assert house is not None
    room_ids = [room.id for room in house.rooms]
    for name in pin:
        if room_of(name) not in room_ids:
            raise SceneGraphError(
                f"--pin {name}: a house's objects are named ROOM/OBJECT "
                f"(rooms: {', '.join(room_ids)})"
            )
    rooms, added = [], []
    for k, house_room in enumerate(house.rooms):
        local = room_scene(scene, house_room.id)
        prefix = house_room.id + "/"
        pins = [name.removeprefix(prefix) for name in pin if room_of(name) == house_room.id]
        again, more = layout_again(local, room_seed(seed, k), pin=pins, warm=warm)
        rooms.append(again)
        added += [in_room(house_room.id, name) for name in more]
    laid_out = house_scene(house, rooms, rules=scene.rules, seed=seed, name=scene.name)
    return describe_scene(laid_out, style=style, variant=variant), added


def rules_context(
    rules: Rules, path: str | os.PathLike[str] | None = None
) -> tuple[str, LearnedContext] | None:
    """The learned context at ``path``, or else the one beside a rules file
    (``NAME.context.json`` beside ``NAME.rules``, as ``fit --what context`` writes it),
    with the file it came from; None when there is none. ``InputError`` for a file that
    is not a context."""
    from scenewright.generator.layout.learned_term import context_path, read_context

    if path is None:
        beside = context_path(rules.path)
        if rules_label(rules) == rules.name or not beside.is_file():
            return None
        path = beside
    context = read_context(str(path))
    context.check_rules(rules.path, str(path))
    return str(path), context


def shipped_rules_file(name: str) -> str | None:
    """The file of the shipped rule set ``name``, or None when no rule set has that name."""
    from importlib.resources import files

    from scenewright.generator import shipped_rule_sets

    if name not in shipped_rule_sets():
        return None
    return str(files("scenewright.grammar_rules").joinpath(f"{name}.rules"))


def checked_templates(templates: str | os.PathLike[str] | None) -> str | None:
    """A templates folder given by the user, as an absolute path once its templates
    compile (``TemplateError`` if not); None stays None."""
    if templates is None:
        return None
    from scenewright.describer.templates import check_templates

    return check_templates(templates)


def reproducible_json(scene: Scene) -> str:
    """scene.json text without wall-clock times: identical bytes for the same rules + seed."""
    return scene.to_json(reproducible=True)


def timings_of(scene: Scene) -> dict[str, float]:
    """Seconds per stage, which ``reproducible_json`` leaves out, for ``timings.json``.

    (The layout's own ``layout.seconds``, also left out, is within microseconds of
    ``layout`` here.)
    """
    return {stage: round(seconds, 6) for stage, seconds in scene.timings.items()}


def summary_line(scene: Scene) -> str:
    """One line for people: objects, relations satisfied, energy, time."""
    objects = len(scene.placed_objects())
    stated = [
        r
        for r in scene.relations
        if r.label in RELATIONS and RELATIONS[r.label].family != "structural"
    ]
    satisfied = sum(r.satisfied for r in stated)
    seconds = sum(scene.timings.values())
    verdict = "ok" if scene.layout.ok else "LAYOUT FAILED"
    return (
        f"{verdict}: {_count(objects, 'object')}, {_count(len(scene.paths), 'path')}, relations satisfied "
        f"{satisfied}/{len(stated)}, energy {scene.layout.energy:.3g}, {seconds:.2f} s"
    )


def _count(count: int, noun: str) -> str:
    return f"{count} {noun}" if count == 1 else f"{count} {noun}s"


def check_choice(what: str, value: Any, allowed: tuple[str, ...]) -> None:
    if value not in allowed:
        raise InputError(f"unknown {what} {value!r}; choose one of {', '.join(allowed)}")
