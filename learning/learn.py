"""``scenewright learn``: example scenes in; an induced rule set, checked, and its report out.

``learn_rule_set`` induces the rules (``induce``), checks that the text passes the
static checks (as ``scenewright validate`` does) and loads, then makes ``check`` scenes
from it (expansion and layout, no text or images; scene k with the seed drawn from
the ``learn`` stream k of ``seed``) and compares them with the examples:

- per type, the distribution of its count per scene, examples against generated
  scenes, as a total variation distance (0: the same; 1: disjoint);
- per written relation (a tree edge parent -> child), the share of scenes holding both
  types, and the share of child objects for which one of the written placement labels
  holds relative to its parent (measured as the induction measured the examples), in
  both;
- how many of the generated layouts are ok, and, where fewer than ``CHECK_OK_SHARE``
  are, a warning naming the statement the layouts that were not ok broke most often.

With ``context`` it also learns a context from the same examples against the induced
rules (``learned_context``: each example related as one of its best derivations of
those rules relates it, as ``fit --what context`` does for examples read from geometry
alone), to be written beside the rules as ``NAME.context.json``; examples no derivation
makes, or too many to search, are left out of it, the searches of all the examples
share ``CONTEXT_REPLAYS`` replays (those after are not searched), and when no related
pair occurs in enough examples (``context.NoRelatedPairs``) the rules are written
without one and the reason kept.

Nothing is written until all of that has succeeded; then the rules file, the context
and the report, each whole (``write``).
"""

from __future__ import annotations

import json
import os
from collections import Counter
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np

from scenewright.core.atomic import scratch_directory
from scenewright.core.relations import RELATIONS
from scenewright.core.scene import Scene
from scenewright.core.seeds import check_seed, stream
from scenewright.examples import Example, scene_supports
from scenewright.generator import check_rules, load_rules
from scenewright.generator.layout.learned_term import context_path
from scenewright.generator.rules import Rules

from .context import (
    LAYOUTS,
    ROUNDS,
    ContextFit,
    fit_example_layouts,
    measured_example_layout,
)
from .derivations import ReplayBudget, measured_derivation_graphs
from .errors import AmbiguousExample, BudgetSpent, InducedRulesError, NoRelatedPairs
from .induce import edge_instances, induce, renamed_scenes
from .induction import Induction, Member
from .rules_text import rules_text

#: Scenes generated from the induced rules to compare with the examples.
CHECK_SCENES = 50
#: Below this share of the check's layouts ok, ``learn`` warns on its first line.
CHECK_OK_SHARE = 0.95
#: Replays the derivation searches of all the examples share when ``learn`` fits a
#: context (``derivations.ReplayBudget``): five examples' worth of
#: ``derivations.MAX_REPLAYS``, well above what the shipped example sets take (design
#: notes, docs/notes/design.md, "Learning a rule set"); rules that leave every example
#: ambiguous (chairs that could be any table's) would otherwise take 20,000 replays an
#: example.
CONTEXT_REPLAYS = 100_000


def check_seed_of(seed: int, index: int) -> int:
    """The seed of check scene ``index``: a 31-bit draw from the ``learn`` stream ``index``."""
    return int(stream(seed, "learn", index).integers(0, 2**31))


def count_distribution(scenes: Sequence[Scene], type_name: str) -> dict[int, float]:
    """count -> share of ``scenes`` holding that many objects of ``type_name``."""
    counted = Counter(sum(o.type == type_name for o in scene.placed_objects()) for scene in scenes)
    return {k: counted[k] / len(scenes) for k in sorted(counted)}


def total_variation(first: dict[int, float], second: dict[int, float]) -> float:
    """Half the L1 distance of two distributions over counts."""
    return 0.5 * sum(abs(first.get(k, 0.0) - second.get(k, 0.0)) for k in set(first) | set(second))


def label_share(scenes: Sequence[Scene], member: Member, induction: Induction) -> float | None:
    """The share of ``member``'s objects in ``scenes`` (with a parent) for which one of
    its written placement labels holds relative to the parent; None without any."""
    instances = edge_instances(
        scenes,
        [scene_supports(s) for s in scenes],
        member.parent,
        member.type,
        resting_only=member.carried,
    )
    placement = {p.labels[0] for p in member.placements if p.labels}
    if len(instances.poses) == 0 or not placement:
        return None
    held = np.zeros(len(instances.poses), dtype=bool)
    for rests in (True, False):
        chosen, holds = instances.holds(rests)
        for label in placement & set(holds):
            held[chosen] |= holds[label]
    return float(held.mean())


def _share_holding_both(scenes: Sequence[Scene], first: str, second: str) -> float:
    return float(np.mean([{first, second} <= {o.type for o in s.placed_objects()} for s in scenes]))


@dataclass(frozen=True)
class Check:
    """The comparison of ``scenes`` generated scenes with the examples (module docstring)."""

    scenes: int
    layouts_ok: int
    types: list[dict]
    pairs: list[dict]
    #: Per statement of the rules (child type, label, what it is related to), in how many
    #: of the layouts that were not ok it was broken: most first.
    faults: list[dict] = field(default_factory=list)

    def warning(self) -> str | None:
        """A line saying that fewer than ``CHECK_OK_SHARE`` of the check's layouts were
        ok, naming the statement broken in most of the others; None when enough were."""
        if self.scenes == 0 or self.layouts_ok >= CHECK_OK_SHARE * self.scenes:
            return None
        text = (
            f"warning: only {self.layouts_ok} of {self.scenes} scenes of the learned rules laid "
            f"out ok (under {CHECK_OK_SHARE:.0%})"
        )
        if self.faults:
            worst = self.faults[0]
            text += (
                f"; the rule most at fault: {worst['statement']} (broken in {worst['layouts']} of "
                f"the {self.scenes - self.layouts_ok} that were not ok)"
            )
        return text

    @property
    def mean_total_variation(self) -> float:
        return float(np.mean([row["total_variation"] for row in self.types])) if self.types else 0.0

    def to_dict(self) -> dict:
        return {
            "scenes": self.scenes,
            "layouts_ok": self.layouts_ok,
            "mean_total_variation": round(self.mean_total_variation, 4),
            "types": self.types,
            "pairs": self.pairs,
            "faults": self.faults,
            "warning": self.warning(),
        }

    def summary(self) -> str:
        differences = [abs(p["examples_both"] - p["generated_both"]) for p in self.pairs]
        held = [
            (p["examples_label_holds"], p["generated_label_holds"])
            for p in self.pairs
            if p["examples_label_holds"] is not None and p["generated_label_holds"] is not None
        ]
        text = (
            f"{self.scenes} scenes generated from it ({self.layouts_ok} laid out ok): per-type counts "
            f"{self.mean_total_variation:.3f} mean total variation from the examples"
        )
        if differences:
            text += f"; pairs present together {np.mean(differences):.3f} apart on average"
        if held:
            text += (
                f"; placement labels hold for {np.mean([g for _, g in held]):.0%} of related objects "
                f"({np.mean([e for e, _ in held]):.0%} in the examples)"
            )
        return text


#: Makes the scene of a rule set for a seed, laid out, without text or images (the
#: application's ``build_scene``): what the check generates.
SceneBuilder = Callable[[Rules, int], Scene]


def compare(
    induction: Induction,
    examples: Sequence[Scene],
    rules: Rules,
    count: int,
    seed: int,
    build_scene: SceneBuilder,
) -> Check:
    """Generate ``count`` scenes from ``rules`` with ``build_scene`` and compare them with
    ``examples`` (the examples' scenes with the induced type names)."""
    generated = [build_scene(rules, check_seed_of(seed, k)) for k in range(count)]
    types = []
    for type_name in induction.catalog:
        seen, made = (
            count_distribution(examples, type_name),
            count_distribution(generated, type_name),
        )
        types.append(
            {
                "type": type_name,
                "examples": {str(k): round(v, 4) for k, v in seen.items()},
                "generated": {str(k): round(v, 4) for k, v in made.items()},
                "total_variation": round(total_variation(seen, made), 4),
            }
        )
    pairs = []
    for (first, second), member in sorted(induction.written_pairs().items()):
        seen_held, made_held = (
            label_share(examples, member, induction),
            label_share(generated, member, induction),
        )
        pairs.append(
            {
                "parent": member.parent,
                "child": member.type,
                "labels": sorted({p.labels[0] for p in member.placements if p.labels}),
                "examples_both": round(_share_holding_both(examples, first, second), 4),
                "generated_both": round(_share_holding_both(generated, first, second), 4),
                "examples_label_holds": None if seen_held is None else round(seen_held, 4),
                "generated_label_holds": None if made_held is None else round(made_held, 4),
            }
        )
    return Check(
        count, sum(scene.layout.ok for scene in generated), types, pairs, layout_faults(generated)
    )


def layout_faults(scenes: Sequence[Scene]) -> list[dict]:
    """Per statement (``child LABEL parent`` by type, a wall label by ``wall``): in how
    many of ``scenes`` whose layout was not ok it was broken, most first."""
    broken: Counter = Counter()
    for scene in scenes:
        if scene.layout.ok:
            continue
        types = {o.id: o.type for o in scene.placed_objects()}
        broken.update(
            {
                f"{types[r.source]} {r.label} {types.get(r.target, 'wall' if RELATIONS[r.label].wall else r.target)}"
                for r in scene.relations
                if r.satisfied is False and r.source in types
            }
        )
    return [
        {"statement": statement, "layouts": count}
        for statement, count in sorted(broken.items(), key=lambda item: (-item[1], item[0]))
    ]


@dataclass(frozen=True)
class InducedContext:
    """The context ``learn`` fitted (None when it learned none, ``why_not`` saying why)
    and the examples left out of it: ``left_out``, no derivation of the induced rules
    makes them; ``ambiguous``, the rules might make them in more ways than one search
    may try (``derivations.MAX_REPLAYS``); ``unsearched``, the searches before them
    spent the replays all share (``CONTEXT_REPLAYS``)."""

    fit: ContextFit | None
    why_not: str | None
    used: int
    left_out: list[str]
    ambiguous: list[str]
    unsearched: list[str]

    def to_dict(self, path: Path | None) -> dict:
        document = {
            "file": os.fspath(path) if self.fit is not None and path is not None else None,
            "examples": self.used,
            "left_out": self.left_out,
            "ambiguous": self.ambiguous,
            "unsearched": self.unsearched,
        }
        if self.fit is not None:
            document.update(self.fit.context.fit or {})
        else:
            document["why_not"] = self.why_not
        return document


def learned_context(
    rules: Rules,
    names: Sequence[str],
    scenes: Sequence[Scene],
    *,
    seed: int,
    rounds: int = ROUNDS,
    layouts: int = LAYOUTS,
    balance: bool = False,
    replays: int = CONTEXT_REPLAYS,
    progress: Callable[[str], object] = lambda message: None,
) -> InducedContext:
    """A context fitted to ``scenes`` (named ``names``) against ``rules``, each scene
    related as one of its best derivations relates it (``measured_example_layout``);
    scenes no derivation makes, or with too many to search, are left out, and once the
    searches have spent ``replays`` the rest are not searched. ``progress`` hears how
    the searches go, about ten times."""
    laid, left_out, ambiguous, unsearched = [], [], [], []
    budget = ReplayBudget(replays)
    every = max(1, len(scenes) // 10)
    for index, (name, scene) in enumerate(zip(names, scenes, strict=False)):
        try:
            graphs = measured_derivation_graphs(rules, scene, name, budget)
        except BudgetSpent:
            unsearched = list(names[index:])
            progress(
                f"context: the derivation searches spent their {replays} replays; "
                f"{len(unsearched)} of {len(scenes)} examples not searched"
            )
            break
        except AmbiguousExample:
            ambiguous.append(name)
            continue
        if graphs:
            laid.append(measured_example_layout(name, scene, graphs))
        else:
            left_out.append(name)
        if (index + 1) % every == 0 or index + 1 == len(scenes):
            progress(
                f"context: searched the derivations of {index + 1} of {len(scenes)} examples ({len(laid)} made "
                "by the induced rules)"
            )
    if not laid and (ambiguous or unsearched):
        why = "the induced rules make the examples in too many ways to search for one of them"
        return InducedContext(None, why, 0, left_out, ambiguous, unsearched)
    try:
        fit = fit_example_layouts(laid, seed=seed, rounds=rounds, layouts=layouts, balance=balance)
    except NoRelatedPairs as error:
        return InducedContext(None, str(error), len(laid), left_out, ambiguous, unsearched)
    if fit.rules_alone_better:  # a context that makes scenes worse is not written
        why = f"the rules alone come as near the examples held out ({fit.held_out_summary()})"
        return InducedContext(None, why, len(laid), left_out, ambiguous, unsearched)
    return InducedContext(fit, None, len(laid), left_out, ambiguous, unsearched)


def resting_as_written(scene: Scene, induction: Induction) -> Scene:
    """``scene`` (an example, with the induced type names) with what rests on what as the
    induced rules can make it, for the context's derivation search: an object resting
    on one its type is not written to rest on (a book on a book, where the rules put
    books on the side table) rests instead on the first thing below it that it is
    written to rest on, or, when there is none (a footstool on a rug, where the rules
    stand footstools by the armchair), on the floor. Poses stay as they are."""
    written = {
        (member.type, member.parent)
        for member in induction.written_pairs().values()
        if member.carried
        or any(p.labels and RELATIONS[p.labels[0]].support for p in member.placements)
    }
    types = {o.id: o.type for o in scene.placed_objects()}
    below = {r.source: r.target for r in scene.relations if RELATIONS[r.label].support}
    relations, changed = [], False
    for relation in scene.relations:
        kept = (
            not RELATIONS[relation.label].support
            or relation.source not in types
            or (types[relation.source], types.get(relation.target)) in written
        )
        if kept:
            relations.append(relation)
            continue
        changed = True
        mover, target, seen = types[relation.source], below.get(relation.target), set()
        while (
            target is not None and target not in seen and (mover, types.get(target)) not in written
        ):
            seen.add(target)
            target = below.get(target)
        if target is not None and (mover, types.get(target)) in written:
            relations.append(replace(relation, target=target))
    return replace(scene, relations=relations) if changed else scene


@dataclass(frozen=True)
class Learned:
    """What ``learn_rule_set`` made: the induction, its rules text, the check (None
    when no scenes were generated), the context (None when not asked for) and the
    files written."""

    induction: Induction
    text: str
    check: Check | None
    context: InducedContext | None
    written: list[Path]


def learn_rule_set(
    examples: Sequence[Example],
    output: Path,
    *,
    report: Path | None = None,
    seed: int = 0,
    test: str = "permutation",
    check: int = CHECK_SCENES,
    context: bool = True,
    rounds: int = ROUNDS,
    layouts: int = LAYOUTS,
    balance: bool = False,
    write: Callable[[Path, str], object],
    build_scene: SceneBuilder,
    progress: Callable[[str], object] = lambda message: None,
) -> Learned:
    """Induce a rule set from ``examples``, check it (module docstring) and write it to
    ``output``, with ``context`` its context beside it (``context_path``; ``rounds`` and
    ``layouts`` are the context fit's) and the report to ``report``; ``write(path, text)``
    writes one file whole; ``build_scene(rules, seed)`` makes a check scene; ``progress`` hears which stage is under way."""
    seed = check_seed(seed)
    name = output.stem if output.suffix == ".rules" else output.name
    induction = induce(examples, name=name, seed=seed, test=test)
    text = rules_text(induction)
    with scratch_directory("learn") as folder:
        trial = folder / f"{name}.rules"

        def checked(text: str) -> tuple[Rules, Check | None]:
            """The rules of ``text``, past the static checks, and their check scenes'."""
            trial.write_text(text, encoding="utf-8")
            errors = [d for d in check_rules(trial) if d.is_error]
            if errors:
                raise InducedRulesError(
                    "the induced rules do not pass the checks:\n"
                    + "\n".join(str(d) for d in errors)
                )
            rules = load_rules(trial)
            if check > 0:
                progress(f"checking the induced rules on {check} generated scenes")
            found = (
                compare(induction, scenes, rules, check, seed, build_scene) if check > 0 else None
            )
            return rules, found

        scenes, _ = renamed_scenes(examples)
        rules, result = checked(text)
        names = [example.name for example in examples]
        fitted = None
        if context:
            progress(f"fitting a context: searching the derivations of {len(scenes)} examples")
            fitted = learned_context(
                rules,
                names,
                [resting_as_written(scene, induction) for scene in scenes],
                seed=seed,
                rounds=rounds,
                layouts=layouts,
                balance=balance,
                progress=progress,
            )
    written = []
    write(output, text)
    written.append(output)
    sidecar = context_path(output)
    if fitted is not None and fitted.fit is not None:
        files = [Path(example.path).read_bytes() for example in examples]
        write(sidecar, fitted.fit.context.for_rules(text, files).to_json())
        written.append(sidecar)
    if report is not None:
        document = {
            "output": os.fspath(output),
            **induction.to_dict(),
            "check": result.to_dict() if result else None,
            "context": fitted.to_dict(sidecar) if fitted is not None else None,
        }
        write(report, json.dumps(document, indent=1, ensure_ascii=False) + "\n")
        written.append(report)
    return Learned(induction, text, result, fitted, written)
