"""``scenewright fit``: a rule set and example scenes in, the fitted rule set and its report out.

``fit_rule_set`` reads each example's derivation (scene.json files made by scenewright
keep it), estimates the rule set's parameters (``weights.fit_weights``), writes the
rules with their new numbers (``rewrite``) and the report, each file whole or not at
all, and checks that what it wrote loads as a rule set.
"""

from __future__ import annotations

import json
import os
from collections.abc import Callable, Iterable, Sequence
from pathlib import Path

from scenewright.core.errors import InputError
from scenewright.generator import load_rules
from scenewright.generator.rules import parse_rules_tree

from .rewrite import fitted_files, rewrite_rules
from .weights import PRIOR, WeightFit, fit_weights


class ExampleError(InputError):
    """An example scene that cannot be learned from, named with its file."""


def example_derivation(path: str, scene: dict) -> list[dict]:
    """The derivation an example scene keeps; ``ExampleError`` if it keeps none."""
    derivation = scene.get("derivation")
    if not derivation and scene.get("objects"):
        raise ExampleError(
            f"{path}: the scene keeps no derivation (the record of its grammar draws that fit counts); "
            "fit reads scene.json files made by scenewright generate, layout or dataset"
        )
    return derivation or []


def fit_rule_set(
    rules_source: str | os.PathLike,
    examples: Sequence[tuple[str, dict]],
    output: Path,
    *,
    report: Path | None = None,
    allow: Iterable[str | os.PathLike] = (),
    prior: float = PRIOR,
    write: Callable[[Path, str], object],
) -> tuple[WeightFit, list[Path]]:
    """Fit ``rules_source`` to ``examples`` ((file name, scene.json document) pairs) and
    write the fitted rules to ``output`` (with its included files beside it) and the
    report to ``report``. ``write(path, text)`` writes one file atomically.

    Returns the fit and the files written. Raises ``ExampleError`` for an example that is
    not a derivation of these rules, ``FitOutputError`` when the output cannot be placed.
    """
    rules = load_rules(rules_source, allow=allow)
    derivations = []
    for path, scene in examples:
        derivation = example_derivation(path, scene)
        try:
            fit_weights(rules, [derivation], prior)
        except ValueError as error:
            raise ExampleError(f"{path}: not a scene of {rules.name}.rules ({error})") from None
        derivations.append(derivation)
    fit = fit_weights(rules, derivations, prior)
    tree = parse_rules_tree(rules_source, allow=allow)
    placed = fitted_files(tree, rewrite_rules(tree, fit), output)
    for path, text in placed:
        path.parent.mkdir(parents=True, exist_ok=True)
        write(path, text)
    load_rules(output, allow=allow)  # the fitted file must load: only numbers changed, within their ranges
    written = [path for path, _ in placed]
    if report is not None:
        document = {"rules": os.fspath(rules_source), "output": os.fspath(output), **fit.to_dict()}
        write(report, json.dumps(document, indent=2) + "\n")
        written.append(report)
    return fit, written
