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
    draws: tuple[float, ...]
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
            "draws": [
                round(value, 6) if value != int(value) else int(value) for value in self.draws
            ],
            "estimate": [round(value, 6) for value in self.estimate],
            "standard_error": [round(value, 6) for value in self.standard_error],
            "written": [round(value, 6) for value in self.written],
        }


@dataclass(frozen=True)
class WeightFit:
    """Every random parameter of a rule set, estimated from ``examples`` examples, of
    which ``ambiguous`` could have come from more than one derivation (fitted by
    ``iterations`` rounds of expectation-maximisation; 0 when none was ambiguous)."""

    parameters: tuple[Parameter, ...]
    examples: int
    prior: float
    ambiguous: int = 0
    iterations: int = 0

    @property
    def unidentified(self) -> list[Parameter]:
        return [parameter for parameter in self.parameters if not parameter.identified]

    def to_dict(self) -> dict:
        return {
            "examples": self.examples,
            "ambiguous_examples": self.ambiguous,
            "em_iterations": self.iterations,
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
    """Estimate every random parameter of ``rules`` from the derivations of examples
    (closed form). Raises ``ValueError`` for a record that is not a draw of these rules."""
    return fit_weights_em(rules, [[derivation] for derivation in derivations], prior)


def fit_weights_em(
    rules: Rules,
    candidates: Sequence[Sequence[list[dict]]],
    prior: float = PRIOR,
    *,
    max_iterations: int = 1000,
    tolerance: float = 1e-9,
) -> WeightFit:
    """Estimate every random parameter of ``rules`` from examples that may each have
    come from several derivations (``candidates[e]``: example e's possible derivations).

    Examples with one derivation are counted as they are. Over the others,
    expectation-maximisation: each example's draws are counted with the weights of its
    derivations under the current parameters (E), then the parameters are re-estimated
    from the expected draws with the same formula as the closed form (M), until no
    probability moves by more than ``tolerance``. This maximises the likelihood times a
    Dirichlet(1 + prior) density (the fixed point of ``p = (E[n] + a) / (E[N] + K a)``).
    It starts from the rules' numbers mixed 9:1 with uniform, so that no option starts
    at probability 0. The standard errors are those of the expected draws: they leave
    out the uncertainty of which derivation made each example.
    """
    layout = _Layout(rules)
    fixed = np.zeros(layout.columns)
    ambiguous: list[np.ndarray] = []
    for example in candidates:
        if not example:
            raise ValueError("an example with no derivation of these rules")
        matrix = np.array([layout.vector(derivation) for derivation in example])
        if len(matrix) == 1:
            fixed += matrix[0]
        else:
            ambiguous.append(matrix)
    theta = layout.normalise(0.9 * layout.written + 0.1 * layout.uniform)
    expected, iterations = fixed, 0
    while ambiguous and iterations < max_iterations:
        iterations += 1
        expected = fixed + _expected_draws(ambiguous, np.log(theta))
        updated = layout.normalise(expected + prior)
        moved = float(np.max(np.abs(updated - theta)))
        theta = updated
        if moved < tolerance:
            break
    if ambiguous:
        expected = fixed + _expected_draws(ambiguous, np.log(theta))
    return WeightFit(
        layout.parameters(expected, prior), len(candidates), prior, len(ambiguous), iterations
    )


def _expected_draws(examples: list[np.ndarray], log_theta: np.ndarray) -> np.ndarray:
    """Sum over examples of the draws of their derivations, each weighted by its
    posterior probability among the example's derivations. ``examples``: (D_e, C)
    matrices; ``log_theta``: (C,). Returns (C,)."""
    total = np.zeros(len(log_theta))
    for matrix in examples:
        log_weight = matrix @ log_theta
        weight = np.exp(log_weight - log_weight.max())
        total += (weight / weight.sum()) @ matrix
    return total


class _Layout:
    """The random parameters of a rule set laid out as columns of one vector: each
    parameter's options side by side, in the report's order."""

    def __init__(self, rules: Rules):
        self.rules = rules
        tally = choice_counts(rules)
        statements = _statements_by_site(rules)
        slots = []  # (kind, name, site, options, written weights, the tally's dict key)
        for name, draws in tally.alternatives.items():
            production = rules.productions[name]
            weights = [1.0 if a.weight is None else a.weight for a in production.alternatives]
            options = [str(index) for index in range(1, len(draws) + 1)]
            slots.append(
                ("alternative", name, site_of(production.location), options, weights, name)
            )
        for site, draws in tally.counts.items():
            rule, statement = statements[site]
            weights = statement.count.weights or [1.0] * len(draws)
            slots.append(("count", rule, site, [str(count) for count in draws], weights, site))
        for site in tally.optional:
            rule, statement = statements[site]
            p = statement.probability
            slots.append(("optional", rule, site, ["skipped", "carried out"], [1.0 - p, p], site))
        for type_name, draws in tally.styles.items():
            entry = rules.catalog[type_name]
            weights = [style.weight for style in entry.styles]
            slots.append(
                ("style", type_name, site_of(entry.location), list(draws), weights, type_name)
            )
        slots.sort(key=lambda slot: (KINDS.index(slot[0]), slot[2]))
        self.slots = slots
        self.starts = np.cumsum([0] + [len(slot[3]) for slot in slots])
        self.columns = int(self.starts[-1])
        written = [np.asarray(slot[4], dtype=float) / sum(slot[4]) for slot in slots]
        self.written = np.concatenate(written) if written else np.zeros(0)
        self.uniform = (
            np.concatenate([np.full(len(s[3]), 1.0 / len(s[3])) for s in slots])
            if slots
            else np.zeros(0)
        )

    def vector(self, derivation: list[dict]) -> np.ndarray:
        """(C,) draws of each option in one derivation."""
        tally = choice_counts(self.rules, derivation)
        tables = {
            "alternative": tally.alternatives,
            "count": tally.counts,
            "optional": tally.optional,
            "style": tally.styles,
        }
        values = []
        for kind, _, _, _, _, key in self.slots:
            drawn = tables[kind][key]
            values.extend(drawn.values() if isinstance(drawn, dict) else drawn)
        return np.asarray(values, dtype=float)

    def normalise(self, values: np.ndarray) -> np.ndarray:
        """(C,) values scaled to sum to 1 within each parameter."""
        sums = np.add.reduceat(values, self.starts[:-1]) if self.columns else values
        return values / np.repeat(sums, np.diff(self.starts))

    def parameters(self, draws: np.ndarray, prior: float) -> tuple[Parameter, ...]:
        found = []
        for (kind, name, site, options, _, _), start, end in zip(
            self.slots, self.starts[:-1], self.starts[1:], strict=False
        ):
            mean, error = posterior(draws[start:end], prior)
            found.append(
                Parameter(
                    kind,
                    name,
                    site,
                    tuple(options),
                    tuple(float(d) for d in draws[start:end]),
                    tuple(float(v) for v in mean),
                    tuple(float(v) for v in error),
                    tuple(float(v) for v in self.written[start:end]),
                )
            )
        return tuple(found)


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
