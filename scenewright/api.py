"""The pipeline in one call: rules -> scene graph -> layout -> Scene -> text -> images.

``generate`` is what the README shows and what the CLI and the dataset job build on;
the smaller functions here are its steps, each timing itself into ``scene.timings``
(seconds, keys ``expand``, ``layout``, ``describe``, ``render``, ``export``).

Reproducibility: the same rules, seed and scenewright version give the same scene. Wall
clock times are the one thing that differs between runs, so ``reproducible_json`` leaves
them out of scene.json and callers store them beside it (``timings.json``).

Stage modules are imported inside the functions: ``import scenewright`` and
``scenewright --help`` stay fast and never start OpenGL.
"""

from __future__ import annotations

import os
import time
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import TYPE_CHECKING, Any

from scenewright.errors import InputError
from scenewright.scene import Scene, assemble_scene

if TYPE_CHECKING:
    from scenewright.describer import Description
    from scenewright.generator.rules import Rules
    from scenewright.render.offscreen import Renderer, RenderResult

#: The description styles and camera views, here as well as in the describer and the
#: renderer so that checking an option does not import those (a test keeps them equal).
STYLES = ("full", "short")
VIEWS = ("perspective", "top")
DEFAULT_SIZE = (640, 480)


def load_rules(source: str | os.PathLike[str] | Rules) -> Rules:
    """A loaded rule set from a shipped name (``"village"``), a path, or Rules as they are."""
    from scenewright.generator import load_rules as load

    if isinstance(source, (str, os.PathLike)):
        return load(source)
    return source


@contextmanager
def timed(timings: dict[str, float], stage: str) -> Iterator[None]:
    """Add the wall time of the ``with`` block to ``timings[stage]``."""
    start = time.perf_counter()
    try:
        yield
    finally:
        timings[stage] = timings.get(stage, 0.0) + time.perf_counter() - start


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
    rules: str | os.PathLike[str] | Rules, seed: int, *, templates: str | os.PathLike[str] | None = None
) -> Scene:
    """Expand the grammar with ``seed`` and lay the graph out: a Scene without text or images.

    ``templates``, a folder of description templates, replaces the rule set's own in
    ``scene.templates`` (as an absolute path), so every description of the scene uses it.
    """
    from scenewright.generator import expand
    from scenewright.generator.layout import layout_scene

    loaded = load_rules(rules)
    timings: dict[str, float] = {}
    with timed(timings, "expand"):
        graph = expand(loaded, seed)
    with timed(timings, "layout"):
        layout = layout_scene(graph, seed)
    scene = assemble_scene(graph, layout, rules=rules_label(loaded), seed=seed)
    if templates is not None:
        scene.templates = str(Path(templates).resolve())
    scene.timings.update(timings)
    return scene


def describe_scene(
    scene: Scene,
    *,
    style: str = "full",
    variant: int = 0,
    templates: str | os.PathLike[str] | None = None,
) -> Description:
    """Describe ``scene``, store the description in it, and return it.

    ``templates``: a folder of description templates for this description only; by
    default the scene's own (``scene.templates``, from its rule set), if any.
    """
    with timed(scene.timings, "describe"):
        description = scene.describe(style=style, variant=variant, templates=templates)
    scene.description = description.to_dict()
    return description


def render_scene(
    scene: Scene,
    *,
    size: tuple[int, int] = DEFAULT_SIZE,
    view: str = "perspective",
    renderer: Renderer | None = None,
) -> RenderResult:
    """Render ``scene`` offscreen, store the render metadata in it, and return the images.

    Pass a ``renderer`` to reuse one OpenGL context over many scenes (the image then has
    the renderer's size, not ``size``); otherwise one is made for this call and closed
    after it.
    """
    from scenewright.render.offscreen import Renderer, render_metadata

    with timed(scene.timings, "render"):
        if renderer is None:
            with Renderer(*size) as own:
                result = own.render(scene, view=view)
        else:
            result = renderer.render(scene, view=view)
    scene.render = render_metadata(result)
    scene.images = result
    return result


def export_scene(scene: Scene, path: str | os.PathLike[str]) -> Path:
    """Write the scene as a binary glTF file (one named node per object)."""
    from scenewright.render.export import export_glb

    with timed(scene.timings, "export"):
        export_glb(scene, path)
    return Path(path)


def generate(
    rules: str | os.PathLike[str] | Rules,
    seed: int = 0,
    *,
    style: str = "full",
    variant: int = 0,
    templates: str | os.PathLike[str] | None = None,
    render: bool = False,
    size: tuple[int, int] = DEFAULT_SIZE,
    view: str = "perspective",
) -> Scene:
    """Generate one scene: expand, lay out, describe and (when ``render``) render it.

    ``rules`` is a shipped rule-set name, a path to a ``.rules`` file, or loaded Rules.
    The returned Scene has ``description`` filled, ``timings`` per stage, and with
    ``render=True`` its ``render`` metadata plus the pixels in ``scene.images``. A
    layout that could not satisfy everything is returned as it is, with
    ``scene.layout.ok`` false and ``scene.layout.problems`` saying why.

    ``templates`` is a folder of description templates that replaces the rule set's
    own (the scene block's ``templates``); the scene records it in ``scene.templates``
    so that describing the scene again uses it too.
    """
    check_choice("style", style, STYLES)
    check_choice("view", view, VIEWS)
    scene = build_scene(rules, seed, templates=checked_templates(templates))
    describe_scene(scene, style=style, variant=variant)
    if render:
        render_scene(scene, size=size, view=view)
    return scene


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
    stated = [r for r in scene.relations if r.label != "PathConnectedTo"]
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
