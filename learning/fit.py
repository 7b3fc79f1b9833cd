"""``scenewright fit``: a rule set and example scenes in, the fitted rule set and its report out.

``fit_rule_set`` reads each example's derivation (scene.json files made by scenewright
keep it) or, for an example without one (a scene.json without it, a hand-written
example, a GLB), finds the derivations that could have made it (``derivations``), estimates the rule set's parameters (``weights.fit_weights_em``:
closed form when every example keeps its derivation), writes the
rules with their new numbers (``rewrite``) and the report, each file whole or not at
all, and checks that what it wrote loads as a rule set.

``what`` chooses what is fitted (``WHAT``): ``weights`` (the above), ``context`` (the
learned layout part, ``context``: written beside the rules as ``NAME.context.json``,
which ``generate`` picks up), or both. The context is learned from the examples' related
pairs: a scene.json's relation edges say which objects are related; an example read
from geometry alone is related as the one of its best derivations it comes nearest to
holding relates it, its objects assigned to that derivation's nodes by which of its
relations they hold (``context.measured_example_layout``). Without ``weights`` the rules are written with
their numbers as they were. The context is fitted before anything is written, so a
failure leaves no file behind.
"""

from __future__ import annotations

import json
import os
from collections.abc import Callable, Iterable, Sequence
from pathlib import Path

from scenewright.core.errors import InputError
from scenewright.core.room import ROOM_KINDS
from scenewright.core.scene import Scene
from scenewright.core.scene_graph import SceneGraph
from scenewright.examples import ExampleError
from scenewright.examples.formats import example_file
from scenewright.generator import load_rules
from scenewright.generator.derivation import choice_counts
from scenewright.generator.layout.learned_term import context_path
from scenewright.generator.rules import Rules, parse_rules_tree

from .context import (
    LAYOUTS,
    ROUNDS,
    ContextFit,
    ExampleLayout,
    example_layout,
    fit_example_layouts,
    measured_example_layout,
)
from .derivations import derivations_of, measured_derivation_graphs
from .errors import FitOutputError, NoRelatedPairs
from .rewrite import fitted_files, rewrite_rules
from .weights import PRIOR, WeightFit, fit_weights_em

#: What ``fit`` can fit, for ``--what``.
WHAT = ("weights", "context")


def parse_what(text: str) -> frozenset[str]:
    """``--what``'s comma-separated choices; ``InputError`` for an unknown or empty one."""
    chosen = [part.strip() for part in text.split(",")]
    unknown = [part for part in chosen if part not in WHAT]
    if not text.strip() or unknown:
        raise InputError(
            f"--what: unknown choice {(unknown or [text])[0]!r}; choose from {', '.join(WHAT)} (comma-separated)"
        )
    return frozenset(chosen)


def example_candidates(rules: Rules, path: str, scene: dict | Scene) -> list[list[dict]]:
    """The derivations an example scene may have come from: the one it keeps, or else
    every derivation of ``rules`` that makes a scene like it (``derivations_of``; for
    an example read from geometry alone, a ``Scene``, ``measured_candidates``).
    ``ExampleError`` if its derivation is not of these rules, or none makes it."""
    if isinstance(scene, Scene):
        return unknown_styles_undrawn(
            [graph.derivation for graph in measured_candidates(rules, path, scene)],
            {o.type for o in scene.placed_objects() if o.style is None},
        )
    derivation = scene.get("derivation")
    if derivation or not scene.get("objects"):
        try:
            choice_counts(rules, derivation or [])
        except ValueError as error:
            raise ExampleError(path, "", f"not a scene of {rules.name}.rules ({error})") from None
        return [derivation or []]
    graph = Scene.from_dict(scene).graph()
    check_styles(
        rules,
        path,
        ((n.id, n.type, n.style) for n in graph.nodes() if n.kind not in ROOM_KINDS),
    )
    found = derivations_of(rules, graph, path)
    if not found:
        types = sorted({node.type for node in graph.nodes() if node.kind not in ROOM_KINDS})
        raise ExampleError(
            path,
            "",
            f"no derivation of {rules.name}.rules makes a scene like this one "
            f"(same objects, groups and relations; its types: {', '.join(types)})",
        )
    return unknown_styles_undrawn(
        found, {n.type for n in graph.nodes() if n.kind not in ROOM_KINDS and n.style is None}
    )


def unknown_styles_undrawn(candidates: list[list[dict]], types: set[str]) -> list[list[dict]]:
    """The candidate derivations with the style draws of ``types`` (those of which the
    example leaves some object's style out) taken out, and those then alike made one:
    an example that does not say the style tells nothing about its weights, which
    then keep their number when no example says it (unidentified), rather than
    being pulled to uniform by the prior through every style's derivation."""
    if not types:
        return candidates
    kept: dict[str, list[dict]] = {}
    for derivation in candidates:
        drawn = [r for r in derivation if not (r["kind"] == "style" and r.get("type") in types)]
        kept.setdefault(json.dumps(drawn, sort_keys=True), drawn)
    return list(kept.values())


def check_styles(rules: Rules, path: str, objects: Iterable[tuple[str, str, str | None]]) -> None:
    """``ExampleError`` naming the file, the object, its type and its style when an
    example object (id, type, style) has a style its type does not have in ``rules``. An
    object without a style is of its type in a style not known, which any derivation
    may have drawn (``derivations.objects_fit``)."""
    for object_id, type_name, style in objects:
        if style is None or type_name not in rules.catalog:
            continue
        styles = [s.name for s in rules.catalog[type_name].styles]
        if style not in styles:
            has = f"its styles there: {', '.join(styles)}" if styles else "it has no styles there"
            raise ExampleError(
                path,
                "",
                f"object {object_id!r} is a {type_name} in style {style!r}, which {type_name} "
                f"in {rules.name}.rules does not have ({has}; leave the style out if it is not known)",
            )


def measured_candidates(rules: Rules, path: str, scene: Scene) -> list[SceneGraph]:
    """The scene graphs of the derivations that make an example read from geometry alone
    (``measured_derivation_graphs``); ``ExampleError`` when none does."""
    check_styles(rules, path, ((o.id, o.type, o.style) for o in scene.placed_objects()))
    found = measured_derivation_graphs(rules, scene, path)
    if not found:
        types = sorted({o.type for o in scene.placed_objects()})
        raise ExampleError(
            path,
            "",
            f"no derivation of {rules.name}.rules makes a scene like this one "
            f"(same objects, styles and what rests on what; its types: {', '.join(types)})",
        )
    return found


def example_candidates_and_layout(
    rules: Rules, path: str, scene: dict | Scene, with_layout: bool
) -> tuple[list[list[dict]], ExampleLayout | None]:
    """``example_candidates``, and when ``with_layout`` the example's layout for the
    context fit: a scene.json's own (``example_layout``), or for an example read from
    geometry alone its objects related as one of its best derivations relates them
    (``measured_example_layout``)."""
    if not isinstance(scene, Scene):
        return example_candidates(rules, path, scene), example_layout(
            path, scene
        ) if with_layout else None
    graphs = measured_candidates(rules, path, scene)
    layout = measured_example_layout(path, scene, graphs) if with_layout else None
    unstyled = {o.type for o in scene.placed_objects() if o.style is None}
    return unknown_styles_undrawn([graph.derivation for graph in graphs], unstyled), layout


def fit_rule_set(
    rules_source: str | os.PathLike,
    examples: Sequence[tuple[str, dict]],
    output: Path,
    *,
    report: Path | None = None,
    allow: Iterable[str | os.PathLike] = (),
    prior: float = PRIOR,
    write: Callable[[Path, str], object],
    commit: Callable[[], object] = lambda: None,
    what: frozenset[str] = frozenset({"weights"}),
    seed: int = 0,
    rounds: int = ROUNDS,
    layouts: int = LAYOUTS,
    balance: bool = False,
) -> tuple[WeightFit, ContextFit | None, list[Path]]:
    """Fit ``rules_source`` to ``examples`` ((file name, scene.json document) pairs, or
    (file name, Scene) for examples read from geometry alone) and
    write the fitted rules to ``output`` (with its included files beside it) and the
    report to ``report``. ``write(path, text)`` writes (or stages) one file whole;
    ``commit()`` puts the staged files in place before the fitted rules are loaded as a
    check (``core.atomic.staged_files``: a check that fails takes them back out).

    ``what``: the subset of ``WHAT`` to fit; ``seed``, ``rounds``, ``layouts`` and
    ``balance`` are the context fit's (``context.fit_context``).

    Returns the weights' fit (with ``weights`` left out: the fit that changes nothing),
    the context's fit (None without ``context``) and the files written. Raises
    ``ExampleError`` for an example that is not a derivation of these rules,
    ``FitOutputError`` when the output cannot be placed, ``context.NoRelatedPairs`` (an
    ``InputError``) when the examples hold no pair to learn a context from.
    """
    rules = load_rules(rules_source, allow=allow)
    candidates, laid = [], []
    for path, scene in examples:
        found, layout = example_candidates_and_layout(rules, path, scene, "context" in what)
        candidates.append(found)
        laid.append(layout)
    fit = fit_weights_em(rules, candidates, prior)
    context = None
    if "context" in what:
        try:
            context = fit_example_layouts(
                laid, seed=seed, rounds=rounds, layouts=layouts, balance=balance
            )
        except NoRelatedPairs as error:
            if any(isinstance(scene, Scene) for _, scene in examples):
                raise NoRelatedPairs(
                    f"{error} (the objects of an example read from geometry alone are related "
                    "as its derivation relates them)"
                ) from None
            raise
    tree = parse_rules_tree(rules_source, allow=allow)
    if "weights" not in what:
        fit = WeightFit((), fit.examples, prior)
    placed = fitted_files(tree, rewrite_rules(tree, fit), output)
    _check_named_files_reach(rules, tree, output)
    if context is not None and not context.rules_alone_better:
        fitted_text = dict(placed).get(output) or output.read_text(encoding="utf-8")
        files = [example_file(path).read_bytes() for path, _ in examples]
        placed.append(
            (context_path(output), context.context.for_rules(fitted_text, files).to_json())
        )
    for path, text in placed:
        write(path, text)
    commit()  # the files go in place together, so the check below reads them there
    load_rules(
        output, allow=allow
    )  # the fitted file must load: only numbers changed, within their ranges
    written = [path for path, _ in placed]
    if report is not None:
        document = {"rules": os.fspath(rules_source), "output": os.fspath(output), **fit.to_dict()}
        if context is not None:
            written_to = None if context.rules_alone_better else os.fspath(context_path(output))
            document["context"] = {"file": written_to, **context.context.fit}
        write(report, json.dumps(document, indent=2) + "\n")
        written.append(report)
    return fit, context, written


def _check_named_files_reach(rules: Rules, tree, output: Path) -> None:
    """Refuse, before anything is written, fitted rules that would not find the mesh
    files and templates folder the rule set names: they are named relative to the rule
    set's files, so copies written into another folder look for them there."""
    root_folder = tree.paths[tree.files[-1].path].resolve().parent
    target_folder = output.parent.resolve()
    if target_folder == root_folder:
        return
    named = [entry.mesh for entry in rules.catalog]
    named += [style.mesh for entry in rules.catalog for style in entry.styles]
    named.append(rules.params.templates)
    for path in sorted({p for p in named if p is not None}):
        source = Path(path).resolve()
        if not source.is_relative_to(root_folder):
            continue  # outside the rule set's folder: an allowed path, named as it is
        relative = source.relative_to(root_folder)
        if not (target_folder / relative).exists():
            raise FitOutputError(
                f"{output}: the rule set names {relative}, which the fitted rules would look for "
                f"as {target_folder / relative}; write the fitted rules into the rule set's folder "
                f"({root_folder}) or copy {relative} beside them first"
            )
