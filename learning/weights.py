"""A rule set's random parameters estimated from example scenes' derivations.

Every random parameter of a rule set is a categorical distribution over its options
(``generator.derivation.ChoiceCounts``): which alternative of a production, which count
of a range ``2..4``, whether an optional statement ``0.6?`` is carried out, which style
of a catalog type. A scene made by scenewright keeps its derivation, one record per
draw, so how often each option was drawn is observed, and the estimate is closed form:
the posterior mean under a symmetric Dirichlet prior of ``PRIOR`` pseudo-draws per
option,

    p_k = (n_k + a) / (N + K a),    se_k = sqrt(p_k (1 - p_k) / (N + K a + 1)),

with n_k the draws of option k, N their sum, K the options and a the prior (se_k is the
posterior standard deviation). The prior keeps every option possible (an alternative
weight must be positive) and matters only for parameters drawn a handful of times. A
parameter never drawn in any example (its production never reached) is *unidentified*:
the examples say nothing about it, and it keeps the value the rules had.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from dataclasses import dataclass

import numpy as np

from scenewright.generator.derivation import Site, all_statements, choice_counts, site_of
from scenewright.generator.rules import Rules

#: Dirichlet pseudo-draws per option (Jeffreys' prior for a categorical distribution).
PRIOR = 0.5

#: The kinds of parameter, in the order the report lists them.
KINDS = ("alternative", "count", "optional", "style")


@dataclass(frozen=True)
class Parameter:
    """One random parameter: its options, how often each was drawn, the estimate.

    ``name`` is the production (alternative, and the production holding a count or an
    optional statement) or the catalog type (style); ``site`` is where the parameter is
    written (the production for alternatives, the range, the probability, the entry for
    styles). ``options`` label the options: alternatives ``"1"``, ``"2"``, ... in the
    order written, counts the numbers, optional ``"skipped"`` and ``"carried out"``,
    styles their names. ``written`` is the distribution the rules had.
    """

    kind: str
    name: str
    site: Site
    options: tuple[str, ...]
    draws: tuple[int, ...]
    estimate: tuple[float, ...]
    standard_error: tuple[float, ...]
    written: tuple[float, ...]

    @property
    def identified(self) -> bool:
        """Whether any example drew this parameter at all."""
        return sum(self.draws) > 0

    @property
    def key(self) -> tuple[str, str, Site]:
        return self.kind, self.name, self.site

    def to_dict(self) -> dict:
        return {
            "kind": self.kind,
            "name": self.name,
            "at": str(self.site),
            "identified": self.identified,
            "options": list(self.options),
            "draws": list(self.draws),
            "estimate": [round(value, 6) for value in self.estimate],
            "standard_error": [round(value, 6) for value in self.standard_error],
            "written": [round(value, 6) for value in self.written],
        }


@dataclass(frozen=True)
class WeightFit:
    """Every random parameter of a rule set, estimated from ``examples`` derivations."""

    parameters: tuple[Parameter, ...]
    examples: int
    prior: float

    @property
    def unidentified(self) -> list[Parameter]:
        return [parameter for parameter in self.parameters if not parameter.identified]

    def to_dict(self) -> dict:
        return {
            "examples": self.examples,
            "prior": self.prior,
            "parameters": [parameter.to_dict() for parameter in self.parameters],
            "unidentified": [f"{p.kind} {p.name} at {p.site}" for p in self.unidentified],
        }


def posterior(draws: Sequence[int], prior: float = PRIOR) -> tuple[np.ndarray, np.ndarray]:
    """The Dirichlet posterior mean and standard deviation of a categorical distribution.

    ``draws``: (K,) counts of each option. Returns two (K,) arrays.
    """
    counts = np.asarray(draws, dtype=float)
    total = counts.sum() + prior * len(counts)
    mean = (counts + prior) / total
    return mean, np.sqrt(mean * (1.0 - mean) / (total + 1.0))


def fit_weights(rules: Rules, derivations: Iterable[list[dict]], prior: float = PRIOR) -> WeightFit:
    """Estimate every random parameter of ``rules`` from example derivations.

    Raises ``ValueError`` for a record that is not a draw of these rules.
    """
    derivations = list(derivations)
    tally = choice_counts(rules, *derivations)
    parameters: list[Parameter] = []

    def add(kind: str, name: str, site: Site, options, draws, written) -> None:
        mean, error = posterior(draws, prior)
        written = np.asarray(written, dtype=float)
        parameters.append(Parameter(
            kind, name, site, tuple(str(option) for option in options), tuple(int(d) for d in draws),
            tuple(float(v) for v in mean), tuple(float(v) for v in error),
            tuple(float(v) for v in written / written.sum()),
        ))  # fmt: skip

    statements = _statements_by_site(rules)
    for name, draws in tally.alternatives.items():
        production = rules.productions[name]
        weights = [1.0 if a.weight is None else a.weight for a in production.alternatives]
        add("alternative", name, site_of(production.location), range(1, len(draws) + 1), draws, weights)
    for site, draws in tally.counts.items():
        rule, statement = statements[site]
        count = statement.count
        weights = count.weights if count.weights is not None else [1.0] * len(draws)
        add("count", rule, site, list(draws), list(draws.values()), weights)
    for site, draws in tally.optional.items():
        rule, statement = statements[site]
        p = statement.probability
        add("optional", rule, site, ("skipped", "carried out"), (draws[False], draws[True]), (1.0 - p, p))
    for type_name, draws in tally.styles.items():
        entry = rules.catalog[type_name]
        weights = [style.weight for style in entry.styles]
        add("style", type_name, site_of(entry.location), list(draws), list(draws.values()), weights)
    parameters.sort(key=lambda p: (KINDS.index(p.kind), p.site))
    return WeightFit(tuple(parameters), len(derivations), prior)


def _statements_by_site(rules: Rules) -> dict[Site, tuple[str, object]]:
    """The production and statement of each count range and optional probability."""
    found: dict[Site, tuple[str, object]] = {}
    for production in rules.productions.values():
        for alternative in production.alternatives:
            for statement in all_statements(alternative.statements):
                if statement.count is not None:
                    found[site_of(statement.count.location)] = (production.name, statement)
                if statement.probability is not None:
                    found[site_of(statement.probability_location)] = (production.name, statement)
    return found
