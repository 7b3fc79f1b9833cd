"""Grammar expansion: a checked rule set and a seed in, a ``SceneGraph`` out.

Expansion starts at the ``start`` nonterminal and runs depth-first in statement
order. Every random choice (an alternative, a count in a range, an optional
statement, a style, ``some TYPE``) is drawn from one ``numpy.random.Generator``
seeded with the seed, in that fixed order, so the same rules and seed always give the
same graph. Expansion is bounded: deeper than ``max_depth`` nested calls, more than
``max_nodes`` nodes or too many steps raises ``ExpansionError`` naming the chain of
productions that got there, so a runaway rule set fails fast instead of hanging.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import NoReturn

import numpy as np

from . import rules_ast as ast
from .catalog import CatalogEntry, SourceLocation, Style
from .rules import Rules
from .rules_errors import ExpansionError
from .scene_graph import SceneGraph

#: Steps (repetitions of statements, calls) allowed per allowed node, on top of a fixed
#: allowance: enough for any sensible rule set, small enough that a rule set which calls
#: productions that create nothing, many times over, stops within a second.
_STEPS_PER_NODE = 50
_BASE_STEPS = 10_000

#: A chain longer than this is shown as its first and last few productions.
_CHAIN_HEAD, _CHAIN_TAIL = 4, 2


def expand(rules: Rules, seed: int) -> SceneGraph:
    """Expand ``rules`` from its start symbol into a scene graph, deterministically."""
    expansion = _Expansion(rules, np.random.default_rng(seed))
    start = rules.productions[rules.start]
    expansion.call(start, arguments=[], parent=None, location=start.location)
    return expansion.graph


@dataclass
class _Expansion:
    """The state of one expansion: the graph so far and where in the rules we are."""

    rules: Rules
    rng: np.random.Generator
    graph: SceneGraph = field(init=False)
    #: Node ids of each type, in creation order (for ``some``, ``each`` and ``#N``).
    by_type: dict[str, list[str]] = field(default_factory=dict)
    #: The nonterminals being expanded, outermost first.
    chain: list[str] = field(default_factory=list)
    steps: int = 0
    max_steps: int = field(init=False)

    def __post_init__(self) -> None:
        self.graph = SceneGraph(params=self.rules.params)
        self.max_steps = _BASE_STEPS + _STEPS_PER_NODE * self.rules.max_nodes

    # -- productions ------------------------------------------------------------

    def call(
        self,
        production: ast.Production,
        arguments: list[list[str]],
        parent: str | None,
        location: SourceLocation,
    ) -> list[str]:
        """Expand one production; return its head (the first node it creates), if any."""
        self.step(location)
        if len(self.chain) >= self.rules.max_depth:
            self.fail(location, f"expansion deeper than max_depth {self.rules.max_depth}", production.name)
        weights = [alt.weight if alt.weight is not None else 1.0 for alt in production.alternatives]
        alternative = production.alternatives[self.pick(weights)]
        # the checks made every call pass exactly as many arguments as there are parameters
        scope = {param.name: nodes for param, nodes in zip(production.params, arguments, strict=True)}
        self.chain.append(production.name)
        created: list[str] = []
        for statement in alternative.statements:
            created.extend(self.run(statement, scope, parent))
        self.chain.pop()
        return created[:1]

    # -- statements -------------------------------------------------------------

    def run(self, statement: ast.Statement, scope: dict[str, list[str]], parent: str | None) -> list[str]:
        """Carry out one statement; return the nodes it created at this level.

        ``scope`` (bound names -> node ids) gains the statement's ``as`` binding.
        """
        if statement.probability is not None and self.rng.random() >= statement.probability:
            if statement.binding:
                scope[statement.binding] = []  # later statements see it, bound to nothing
            return []
        created: list[str] = []
        subjects_of_all_repetitions: list[str] = []
        for _ in range(self.count(statement.count)):
            self.step(statement.location)
            subjects, creates = self.subjects(statement.subject, scope, parent)
            for subject in subjects:
                for relation in statement.relations:
                    for target in self.resolve(relation.target, scope, exclude=subject):
                        self.graph.add_relation(subject, target, relation.label)
            if statement.block is not None:
                for group in subjects:
                    inner = dict(scope)
                    if statement.binding:
                        inner[statement.binding] = [group]  # inside its block: this group
                    for nested in statement.block:
                        self.run(nested, inner, group)
            subjects_of_all_repetitions.extend(subjects)
            if creates:
                created.extend(subjects)
        if statement.binding:
            scope[statement.binding] = subjects_of_all_repetitions
        return created

    def subjects(
        self, subject: ast.Reference | ast.Call, scope: dict[str, list[str]], parent: str | None
    ) -> tuple[list[str], bool]:
        """The subject nodes of one repetition, and whether they were created by it."""
        if isinstance(subject, ast.Call):
            arguments = [self.resolve(argument, scope) for argument in subject.arguments]
            production = self.rules.productions[subject.nonterminal]
            return self.call(production, arguments, parent, subject.location), True
        if subject.kind == "name" and subject.name not in scope:
            return [self.create(self.rules.catalog[subject.name], parent, subject.location)], True
        return self.resolve(subject, scope), False

    def create(self, entry: CatalogEntry, parent: str | None, location: SourceLocation) -> str:
        if len(self.graph) >= self.rules.max_nodes:
            self.fail(location, f"more than max_nodes {self.rules.max_nodes} nodes")
        style: Style | None = None
        if entry.styles:
            style = entry.styles[self.pick([s.weight for s in entry.styles])]
        node = self.graph.add_node(entry, style=style, parent=parent, rule=self.chain[-1])
        self.by_type.setdefault(entry.name, []).append(node)
        return node

    # -- references -------------------------------------------------------------

    def resolve(
        self, reference: ast.Reference, scope: dict[str, list[str]], exclude: str | None = None
    ) -> list[str]:
        """The nodes a reference means now; ``exclude`` (the subject) is never its own target."""
        if reference.kind == "name":
            return [node for node in scope[reference.name] if node != exclude]
        existing = self.by_type.get(reference.name, [])
        if reference.kind == "nth":
            if reference.index > len(existing):
                noun = self.rules.catalog[reference.name].noun
                self.fail(
                    reference.location,
                    f"'{reference.name} #{reference.index}' refers to {noun} number {reference.index}, "
                    f"but only {len(existing)} exist at this point",
                )
            node = existing[reference.index - 1]
            return [] if node == exclude else [node]
        candidates = [node for node in existing if node != exclude]
        if reference.kind == "each":
            return candidates
        if not candidates:
            noun = self.rules.catalog[reference.name].noun
            self.fail(reference.location, f"'some {reference.name}' finds no {noun} in the scene at this point")
        return [candidates[int(self.rng.integers(len(candidates)))]]

    # -- draws and bounds -------------------------------------------------------

    def pick(self, weights: list[float]) -> int:
        """An index drawn with probability proportional to ``weights``."""
        if len(weights) == 1:
            return 0
        probabilities = np.asarray(weights, dtype=float)
        return int(self.rng.choice(len(weights), p=probabilities / probabilities.sum()))

    def count(self, count: ast.Count | None) -> int:
        if count is None:
            return 1
        low, high = int(count.low), int(count.high)
        return low if low == high else int(self.rng.integers(low, high + 1))

    def step(self, location: SourceLocation) -> None:
        self.steps += 1
        if self.steps > self.max_steps:
            self.fail(location, f"expansion took more than {self.max_steps} steps")

    def fail(self, location: SourceLocation, message: str, next_call: str | None = None) -> NoReturn:
        chain = self.chain + ([next_call] if next_call else [])
        if len(chain) > _CHAIN_HEAD + _CHAIN_TAIL + 1:
            chain = chain[:_CHAIN_HEAD] + ["..."] + chain[-_CHAIN_TAIL:]
        shown = " -> ".join(chain)
        raise ExpansionError(self.rules.sources.diagnostic(location, f"{message} (expanding {shown})"))
