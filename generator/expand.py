"""Grammar expansion: a checked rule set and a seed in, a ``SceneGraph`` out.

Expansion starts at the ``start`` nonterminal and runs depth-first in statement
order. Every random choice (an alternative, a count in a range, an optional
statement, a style, ``some TYPE``) is drawn from the expansion's own child stream of
the scene's seed (``core.seeds``), in that fixed order, so the same rules and seed
always give the same graph. Each draw is recorded, in order, with the nodes it made,
in the graph's ``derivation`` (format: ``generator.derivation``); recording draws
nothing. Expansion is bounded: deeper than ``max_depth`` nested calls, more than
``max_nodes`` nodes or too many steps raises ``ExpansionError`` naming the chain of
productions that got there, so a runaway rule set fails fast instead of hanging.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import NoReturn

import numpy as np

from scenewright.core.relations import RELATIONS
from scenewright.core.room import ROOM_KINDS, ROOM_NODE
from scenewright.core.scene_graph import SceneGraph
from scenewright.core.seeds import SeedLike, stage_stream

from . import rules_ast as ast
from .catalog import CatalogEntry, SourceLocation, Style
from .derivation import choice
from .rules import Rules
from .rules_errors import ExpansionError

#: Steps (repetitions of statements, calls) allowed per allowed node, on top of a fixed
#: allowance: enough for any sensible rule set, small enough that a rule set which calls
#: productions that create nothing, many times over, stops within a second.
_STEPS_PER_NODE = 50
_BASE_STEPS = 10_000

#: A chain longer than this is shown as its first and last few productions.
_CHAIN_HEAD, _CHAIN_TAIL = 4, 2


def expand(rules: Rules, seed: SeedLike) -> SceneGraph:
    """Expand ``rules`` from its start symbol into a scene graph, deterministically.

    ``seed``: the scene's seed (an int), a Generator to draw from, or None (fresh entropy).
    """
    return expand_with(rules, RandomDraws(stage_stream(seed, "expansion")))


def expand_with(rules: Rules, draws: Draws) -> SceneGraph:
    """Expand ``rules`` answering each draw with ``draws``: the seeded stream (``expand``)
    or another answerer, such as one that replays or enumerates derivations."""
    expansion = _Expansion(rules, draws)
    draws.watch(expansion.graph)
    start = rules.productions[rules.start]
    expansion.call(start, arguments=[], parent=None, location=start.location)
    return expansion.graph


class Draws:
    """What answers the random draws of an expansion, one method per kind of draw."""

    def watch(self, graph: SceneGraph) -> None:
        """Called once, before the first draw, with the graph the expansion builds."""

    def optional(self, probability: float) -> bool:
        """Whether a statement written with ``probability`` is carried out."""
        raise NotImplementedError

    def count(self, low: int, high: int, weights: tuple[float, ...] | None) -> int:
        """A count from ``low`` to ``high``: uniform, or by ``weights`` (one per count)."""
        raise NotImplementedError

    def pick(self, probabilities: np.ndarray) -> int:
        """An alternative's or style's index, drawn with ``probabilities`` (they sum to 1)."""
        raise NotImplementedError

    def some(self, candidates: int) -> int:
        """Which of ``candidates`` nodes ``some TYPE`` means (uniform)."""
        raise NotImplementedError


class RandomDraws(Draws):
    """Draws from a seeded stream, in the fixed order expansion makes them."""

    def __init__(self, rng: np.random.Generator):
        self.rng = rng

    def optional(self, probability: float) -> bool:
        return bool(self.rng.random() < probability)

    def count(self, low: int, high: int, weights: tuple[float, ...] | None) -> int:
        if weights is None:
            return int(self.rng.integers(low, high + 1))
        shares = np.asarray(weights, dtype=float)
        return low + int(self.rng.choice(len(shares), p=shares / shares.sum()))

    def pick(self, probabilities: np.ndarray) -> int:
        return int(self.rng.choice(len(probabilities), p=probabilities))

    def some(self, candidates: int) -> int:
        return int(self.rng.integers(candidates))


@dataclass
class _Expansion:
    """The state of one expansion: the graph so far and where in the rules we are."""

    rules: Rules
    draws: Draws
    graph: SceneGraph = field(init=False)
    #: Node ids of each type, in creation order (for ``some``, ``each`` and ``#N``).
    by_type: dict[str, list[str]] = field(default_factory=dict)
    #: Every node id in creation order (the nodes a choice made are a slice of it).
    made: list[str] = field(default_factory=list)
    #: The nonterminals being expanded, outermost first.
    chain: list[str] = field(default_factory=list)
    steps: int = 0
    max_steps: int = field(init=False)

    def __post_init__(self) -> None:
        self.graph = SceneGraph(params=self.rules.params)
        for (
            node
        ) in self.graph.nodes():  # a room's walls, doors and windows are there from the start
            if node.kind in ROOM_KINDS and node.kind != ROOM_NODE:
                self.by_type.setdefault(node.type, []).append(node.id)
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
            self.fail(
                location, f"expansion deeper than max_depth {self.rules.max_depth}", production.name
            )
        self.chain.append(production.name)
        weights = [alt.weight if alt.weight is not None else 1.0 for alt in production.alternatives]
        index, drawn = self.pick(weights, "alternative", production.location)
        # the checks made every call pass exactly as many arguments as there are parameters
        scope = {
            param.name: nodes for param, nodes in zip(production.params, arguments, strict=True)
        }
        first = len(self.made)
        created: list[str] = []
        for statement in production.alternatives[index].statements:
            created.extend(self.run(statement, scope, parent))
        if drawn is not None:
            drawn["nodes"] = self.made[first:]
        self.chain.pop()
        return created[:1]

    # -- statements -------------------------------------------------------------

    def run(
        self, statement: ast.Statement, scope: dict[str, list[str]], parent: str | None
    ) -> list[str]:
        """Carry out one statement; return the nodes it created at this level.

        ``scope`` (bound names -> node ids) gains the statement's ``as`` binding.
        """
        first = len(self.made)
        optional: dict | None = None
        if statement.probability is not None:
            taken = self.draws.optional(statement.probability)
            optional = self.note(
                "optional", statement.probability_location, taken, probability=statement.probability
            )
            if not taken:
                if statement.binding:
                    scope[statement.binding] = []  # later statements see it, bound to nothing
                return []
        repetitions, counted = self.count(statement.count)
        created: list[str] = []
        subjects_of_all_repetitions: list[str] = []
        for _ in range(repetitions):
            self.step(statement.location)
            subjects, creates = self.subjects(statement.subject, scope, parent)
            for subject in subjects:
                for relation in statement.relations:
                    for target in self.targets(relation, scope, subject):
                        self.graph.add_relation(
                            subject, target, relation.label, some=relation.target.kind == "some"
                        )
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
        for drawn in (optional, counted):
            if drawn is not None:
                drawn["nodes"] = self.made[first:]
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
        if len(self.made) >= self.rules.max_nodes:  # the room's own nodes do not count
            self.fail(location, f"more than max_nodes {self.rules.max_nodes} nodes")
        style: Style | None = None
        drawn: dict | None = None
        if entry.styles:
            weights = [s.weight for s in entry.styles]
            index, drawn = self.pick(weights, "style", entry.location, type=entry.name)
            style = entry.styles[index]
        node = self.graph.add_node(entry, style=style, parent=parent, rule=self.chain[-1])
        self.by_type.setdefault(entry.name, []).append(node)
        self.made.append(node)
        if drawn is not None:
            drawn["nodes"] = [node]
        return node

    # -- references -------------------------------------------------------------

    def targets(
        self, relation: ast.Relation, scope: dict[str, list[str]], subject: str
    ) -> list[str]:
        """The targets of one relation from ``subject``. A label by the room (a wall
        label, ``AwayFromWall``) to ``some wall`` or ``some window`` targets the room
        node: the layout chooses the wall or window that fits (and records it), so no
        draw is made here."""
        target = relation.target
        if (
            target.kind == "some"
            and target.name in ROOM_KINDS
            and RELATIONS[relation.label].by_room
        ):
            return [ROOM_NODE]
        return self.resolve(target, scope, exclude=subject)

    def noun(self, type_name: str) -> str:
        """A type's noun for messages (a room's parts are no catalog entries)."""
        return self.rules.catalog[type_name].noun if type_name in self.rules.catalog else type_name

    def resolve(
        self, reference: ast.Reference, scope: dict[str, list[str]], exclude: str | None = None
    ) -> list[str]:
        """The nodes a reference means now; ``exclude`` (the subject) is never its own target."""
        if reference.kind == "name":
            return [node for node in scope[reference.name] if node != exclude]
        existing = self.by_type.get(reference.name, [])
        if reference.kind == "nth":
            if reference.index > len(existing):
                noun = self.noun(reference.name)
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
            noun = self.noun(reference.name)
            self.fail(
                reference.location,
                f"'some {reference.name}' finds no {noun} in the scene at this point",
            )
        index = self.draws.some(len(candidates))
        picked = [candidates[index]]
        self.note(
            "some", reference.location, index, picked, options=len(candidates), type=reference.name
        )
        return picked

    # -- draws and bounds -------------------------------------------------------

    def pick(
        self,
        weights: list[float],
        kind: str,
        location: SourceLocation | None,
        type: str | None = None,
    ) -> tuple[int, dict | None]:
        """An index drawn with probability proportional to ``weights``, and its record
        (None when there was nothing to draw: a single option)."""
        if len(weights) == 1:
            return 0, None
        probabilities = np.asarray(weights, dtype=float)
        index = self.draws.pick(probabilities / probabilities.sum())
        return index, self.note(kind, location, index, options=len(weights), type=type)

    def count(self, count: ast.Count | None) -> tuple[int, dict | None]:
        """How many times a statement runs, and the record of the draw (None when fixed)."""
        if count is None:
            return 1, None
        low, high = int(count.low), int(count.high)
        if low == high:
            return low, None
        drawn = self.draws.count(low, high, count.weights)
        return drawn, self.note("count", count.location, drawn, low=low, high=high)

    def note(
        self,
        kind: str,
        location: SourceLocation | None,
        value: int | bool,
        nodes: list[str] | None = None,
        *,
        options: int | None = None,
        low: int | None = None,
        high: int | None = None,
        probability: float | None = None,
        type: str | None = None,
    ) -> dict:
        """Append a record of a draw to the derivation (``choice``'s details); its nodes
        may be filled in later."""
        record = choice(
            kind,
            self.chain[-1],
            location,
            value,
            nodes,
            options=options,
            low=low,
            high=high,
            probability=probability,
            type=type,
        )
        self.graph.derivation.append(record)
        return record

    def step(self, location: SourceLocation) -> None:
        self.steps += 1
        if self.steps > self.max_steps:
            self.fail(location, f"expansion took more than {self.max_steps} steps")

    def fail(
        self, location: SourceLocation, message: str, next_call: str | None = None
    ) -> NoReturn:
        chain = self.chain + ([next_call] if next_call else [])
        if len(chain) > _CHAIN_HEAD + _CHAIN_TAIL + 1:
            chain = chain[:_CHAIN_HEAD] + ["..."] + chain[-_CHAIN_TAIL:]
        shown = " -> ".join(chain)
        raise ExpansionError(
            self.rules.sources.diagnostic(location, f"{message} (expanding {shown})")
        )
