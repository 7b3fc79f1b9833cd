"""The derivations of a rule set that could have made an example scene.

An example without its derivation (a scene.json whose derivation was dropped, a scene
made by hand) may have come from more than one derivation: a desk made by either
alternative of ``Workplace``, two books from one range or from two. Fitting weights to
such examples (expectation-maximisation, ``weights.fit_weights``) needs every
derivation that makes a scene *like* the example, where like means the same
``signature``: the multiset of its objects' (type, style), of (type, parent's type), and
of its relations' (subject type, label, target type), a room's parts standing by their
kind (``wall``, ``window``, ``room``). Which node ``some TYPE`` picks changes none of
these, so those draws are answered with the first candidate and not enumerated.

``derivations_of`` searches depth first over the draws. Each prefix of answers is
replayed from the start (an expansion is small and cheap to restart); a prefix whose
partial scene already has more objects of a type than the example is cut off, as is
one the expansion refuses (too many nodes, ``some`` with no candidate). The search
stops with ``AmbiguousExample`` after ``MAX_REPLAYS`` replays. Searches for many
examples in a row can share a ``ReplayBudget``, which stops them with ``BudgetSpent``
once it is spent: where the rules leave most examples ambiguous (chairs that could
belong to any of several tables), each one otherwise costs the full ``MAX_REPLAYS``.

An example read from geometry alone (the hand-written format, GLB) has no relation
labels but what rests on what. Its signature (``resting_signature`` of its graph) is
the multiset of its objects' (type, style) and of (type, the type it rests on), as its
support-family relations and a derivation's say. Every derivation of that signature
is then scored by the geometry (``geometric_agreement``): for each of its relation
statements (subject type, label, target), whether the example holds it, measured by the
layout's own predicates between objects of those types (a wall's, a window's or the
room's labels against the example's room); the derivations that state the most that
holds are kept. So of "a nightstand to the left of the bed" and "to the right", the
one where the example's nightstand stands is kept; where the geometry cannot tell
(two derivations state equally much that holds), both are, and EM shares the example
between them. A statement the example cannot show (a window label in a room the
hand-written format gave no windows, a wall label without a room) counts as holding
for every derivation, so it decides nothing.

A learned context needs more than the derivation: which of the example's objects each
of its nodes stands for, so that its relation edges say which objects are related
(``assign_objects``: per type, the assignment that holds the most of the derivation's
relations between objects). Of several best derivations, ``closest_derivation`` takes
the one the example comes nearest to holding.
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass

import numpy as np
from scipy.optimize import linear_sum_assignment

from scenewright.core.errors import InputError
from scenewright.core.poses import Pose
from scenewright.core.relations import RELATIONS, Relation
from scenewright.core.room import ROOM_KINDS, ROOM_NODE
from scenewright.core.scene import Scene
from scenewright.core.scene_graph import SceneGraph, SceneParams
from scenewright.examples.example import scene_supports
from scenewright.generator.catalog import CatalogEntry
from scenewright.generator.expand import Draws, expand_with
from scenewright.generator.layout import measure_layout
from scenewright.generator.rules import Rules
from scenewright.generator.rules_errors import ExpansionError

from .errors import AmbiguousExample, BudgetSpent

#: A relation statement of a signature: (subject type, label, target type or room kind).
Statement = tuple[str, str, str]
#: Replays one example may take before the search gives up.
MAX_REPLAYS = 20_000


@dataclass
class ReplayBudget:
    """Replays that several searches share: each replay of each takes one."""

    left: int

    def take(self, name: str) -> None:
        """One replay for the search of the example ``name``; ``BudgetSpent`` when none
        is left."""
        if self.left <= 0:
            raise BudgetSpent(
                f"{name}: the searches of the examples before it spent the replays they share"
            )
        self.left -= 1


@dataclass(frozen=True)
class Signature:
    """What a derivation must reproduce of an example: three multisets (``Counter``s)."""

    objects: Counter
    parents: Counter
    relations: Counter | None  # None: not compared (an example measured from geometry)

    def within(self, other: Signature) -> bool:
        """Whether this scene could still grow into ``other`` (an example's): an expansion
        only adds objects and relations, so none of its multisets may exceed ``other``'s.
        An example object without a style stands for its type in any style
        (``objects_fit``)."""
        pairs = [(self.parents, other.parents)]
        if self.relations is not None and other.relations is not None:
            pairs.append((self.relations, other.relations))
        return objects_fit(self.objects, other.objects, exact=False) and all(
            mine <= theirs for mine, theirs in pairs
        )  # Counter inclusion

    def like(self, other: Signature) -> bool:
        """The same signature as ``other`` (an example's; relations compared only when
        both have them, a style the example leaves out matching any)."""
        both = self.relations is not None and other.relations is not None
        return (
            objects_fit(self.objects, other.objects, exact=True)
            and self.parents == other.parents
            and (not both or self.relations == other.relations)
        )


def objects_fit(made: Counter, example: Counter, *, exact: bool) -> bool:
    """Whether the (type, style) multiset ``made`` (an expansion's) fits within
    ``example``'s (with ``exact``, is it), where an example object of style None (the
    example gave none) stands for an object of its type in any style: the styles the
    example names are matched first, the objects left over take its unstyled ones."""
    if all(style is not None for _, style in example) or not made:
        return made == example if exact else made <= example
    free: Counter = Counter()
    for (type_name, style), count in example.items():
        if style is None:
            free[type_name] += count
    for (type_name, style), count in made.items():
        named = 0 if style is None else example.get((type_name, style), 0)
        free[type_name] -= max(0, count - named)
        if free[type_name] < 0:
            return False
    if not exact:
        return True
    types: Counter = Counter()
    for (type_name, _), count in example.items():
        types[type_name] += count
    for (type_name, _), count in made.items():
        types[type_name] -= count
    return not any(types.values())


def resting_signature(graph: SceneGraph) -> Signature:
    """The signature by what rests on what: (type, style) of the objects and (type, the
    type its support-family relation rests it on); relations not compared."""
    nodes = {node.id: node for node in graph.nodes()}
    things = [node for node in nodes.values() if node.kind not in ROOM_KINDS]
    rests_on = {
        edge.source: nodes[edge.target].type
        for edge in graph.edges()
        if RELATIONS[edge.label].support
    }
    return Signature(
        Counter((node.type, node.style) for node in things),
        Counter((node.type, rests_on.get(node.id)) for node in things),
        None,
    )


def measured_relations(
    scene: Scene, wanted: Iterable[tuple[str, str, str | None]]
) -> dict[tuple[str, str, str | None], Relation]:
    """The layout's verdict (``core.relations.Relation``: ``value``, ``satisfied``) on each
    of ``wanted``, (subject object id, label, other object id or None for the room) in the
    example ``scene``, measured by the layout's own predicates at the example's poses and
    sizes, all in one ``measure_layout``."""
    objects = scene.placed_objects()
    graph = SceneGraph(
        params=SceneParams(
            extent=tuple(scene.extent), ground="floor" if scene.room else "grass", room=scene.room
        )
    )
    node_of, poses = {}, {}
    for obj in objects:
        node_of[obj.id] = graph.add_node(
            CatalogEntry(obj.type, "object", obj.noun or obj.type, size=tuple(obj.size))
        )
        poses[node_of[obj.id]] = Pose(*(float(v) for v in obj.position), float(obj.yaw))
    object_of = {
        node: object_id for object_id, node in node_of.items()
    }  # anything else is the room's
    added = set()
    for subject, label, other in wanted:
        edge = (node_of[subject], ROOM_NODE if other is None else node_of[other], label)
        if edge not in added:
            added.add(edge)
            graph.add_relation(*edge)
    return {
        (object_of[relation.source], relation.label, object_of.get(relation.target)): relation
        for relation in measure_layout(graph, poses, {}).relations
    }


def holding_statements(scene: Scene, statements: set[Statement]) -> Counter:
    """Statement -> how many objects of its subject type the example ``scene`` holds it
    for (with some other object of the target type, or against its room), for every
    statement of ``statements`` that is not a support (those are in the signature)."""
    objects = scene.placed_objects()
    type_of = {obj.id: obj.type for obj in objects}
    wanted = []
    for subject_type, label, target in statements:
        if RELATIONS[label].support or _unmeasurable(label, scene):
            continue
        for subject in (o.id for o in objects if o.type == subject_type):
            if target in ROOM_KINDS:
                wanted.append((subject, label, None))
            else:
                wanted.extend(
                    (subject, label, o.id) for o in objects if o.type == target and o.id != subject
                )
    held = {
        (subject, label, ROOM_NODE if other is None else type_of[other])
        for (subject, label, other), relation in measured_relations(scene, wanted).items()
        if relation.satisfied
    }
    held_by_type = Counter((type_of[subject], label, role) for subject, label, role in held)
    return Counter(
        {
            (subject_type, label, target): len(objects)
            if _unmeasurable(label, scene)  # may hold for every one: tells nothing
            else held_by_type[(subject_type, label, ROOM_NODE if target in ROOM_KINDS else target)]
            for subject_type, label, target in statements
        }
    )


def _unmeasurable(label: str, scene: Scene) -> bool:
    """Whether the example cannot show whether ``label`` holds: a label by the room (a
    wall label, ``AwayFromWall``) without a room, or a window label in a room without
    windows (the hand-written format states no openings), so that the statement neither
    wins nor loses a derivation."""
    spec = RELATIONS[label]
    if not spec.by_room:
        return False
    if scene.room is None:
        return True
    return spec.wall in ("under_window", "beside_window") and not any(
        o.kind == "window" for o in scene.room.openings
    )


def geometric_agreement(derivation_graph: SceneGraph, holding: Counter) -> int:
    """How many of the derivation's relation statements the example holds: per
    statement, the least of how often the derivation states it and how many of the
    example's objects hold it (``holding_statements``)."""
    stated = signature(derivation_graph).relations
    return sum(min(count, holding[statement]) for statement, count in stated.items())


def signature(graph: SceneGraph) -> Signature:
    """The signature of a scene graph (an example's, or one an expansion made)."""
    nodes = {node.id: node for node in graph.nodes()}

    def role(node_id: str) -> str:
        node = nodes[node_id]
        return node.kind if node.kind in ROOM_KINDS else node.type

    things = [node for node in nodes.values() if node.kind not in ROOM_KINDS]
    return Signature(
        Counter((node.type, node.style) for node in things),
        Counter((node.type, nodes[node.parent].type if node.parent else None) for node in things),
        Counter((role(edge.source), edge.label, role(edge.target)) for edge in graph.edges()),
    )


class _Undecided(Exception):
    """The replay reached a draw its script does not answer; ``options`` to try."""

    def __init__(self, options: int):
        super().__init__(options)
        self.options = options


class _Scripted(Draws):
    """Answers draws from a script of option indices; raises ``_Undecided`` past its end."""

    def __init__(self, script: list[int]):
        self.script = script
        self.position = 0
        self.graph: SceneGraph | None = None

    def watch(self, graph: SceneGraph) -> None:
        self.graph = graph

    def _next(self, options: int) -> int:
        if self.position == len(self.script):
            raise _Undecided(options)
        self.position += 1
        return self.script[self.position - 1]

    def optional(self, probability: float) -> bool:
        return bool(self._next(2))

    def count(self, low: int, high: int, weights: tuple[float, ...] | None) -> int:
        return low + self._next(high - low + 1)

    def pick(self, probabilities: np.ndarray) -> int:
        return self._next(len(probabilities))

    def some(self, candidates: int) -> int:
        return 0


def derivations_of(rules: Rules, example: SceneGraph, name: str = "example") -> list[list[dict]]:
    """Every derivation of ``rules`` whose scene has ``example``'s signature, as lists of
    derivation records (``generator.derivation``), in the order the search finds them.

    Raises ``AmbiguousExample`` when the search takes more than ``MAX_REPLAYS`` replays.
    """
    return [graph.derivation for graph in _search(rules, signature(example), signature, name)]


def measured_derivations_of(
    rules: Rules, example: Scene, name: str = "example"
) -> list[list[dict]]:
    """The derivations of ``rules`` that make an example read from geometry alone
    (``measured_derivation_graphs``), as lists of derivation records."""
    return [graph.derivation for graph in measured_derivation_graphs(rules, example, name)]


def measured_derivation_graphs(
    rules: Rules, example: Scene, name: str = "example", budget: ReplayBudget | None = None
) -> list[SceneGraph]:
    """The scene graphs of the derivations of ``rules`` that make an example read from
    geometry alone: those of its resting signature that state the most relations the
    example holds (module docstring), in the order the search finds them.

    The search first keeps to derivations every statement of which the example holds
    (partial ones pruned as soon as they state one it does not, which makes it fast);
    only when none is found does it take every derivation of the resting signature and
    keep the best-agreeing ones. ``budget``: replays shared with other searches."""
    holding = _HoldingCache(example)
    wanted = resting_signature(example.graph())
    graphs = _search(rules, wanted, resting_signature, name, holding.holds_all, budget)
    if not graphs:
        graphs = _search(rules, wanted, resting_signature, name, budget=budget)
    if not graphs:
        return []
    agreement = [
        geometric_agreement(graph, holding.counts(signature(graph).relations)) for graph in graphs
    ]
    best = max(agreement)
    return [graph for graph, score in zip(graphs, agreement, strict=False) if score == best]


#: How much the assignment of derivation nodes to example objects weighs how far a
#: relation is from holding (its log factor, squashed to [0, 1)) against whether it holds
#: (1 per relation): a tie-break between assignments holding as many relations.
NEAR_MISS = 1e-3


def closest_derivation(
    graphs: Sequence[SceneGraph], example: Scene
) -> tuple[SceneGraph, dict[str, str]]:
    """Of the scene graphs of an example's best derivations (``measured_derivation_graphs``,
    which state equally much that the example holds), the one whose relations the
    example's objects come nearest to holding, with its assignment (``assign_objects``):
    the least assignment cost, near misses included; the first on a tie. (A nightstand
    that is quite next to neither side of the bed leaves "left of it" and "right of it"
    tied in the search; the side it is nearer wins here.)"""
    best: tuple[float, SceneGraph, dict[str, str]] | None = None
    for graph in graphs:
        chosen, cost = _assignment(graph, example)
        if best is None or cost < best[0] - 1e-12:
            best = (cost, graph, chosen)
    assert best is not None, "no derivation to choose from"
    return best[1], best[2]


def assign_objects(graph: SceneGraph, example: Scene) -> dict[str, str]:
    """Which object of ``example`` (an example read from geometry alone) each object node
    of ``graph`` (the scene graph of one of its derivations, ``measured_derivation_graphs``)
    stands for: node id -> object id, one to one.

    A node is assigned an object of its type and style. Of all such assignments the one
    sought holds the most of the graph's relation edges between objects: a support edge
    holds when the example rests the one object on the other; any other edge when the
    layout's predicate holds between the two objects at the example's poses
    (``measured_relations``); a node resting on nothing gets an object resting on
    nothing. Ties go to the assignment whose broken relations miss by least
    (``NEAR_MISS``). It is found block by block, a block being the nodes of one (type,
    style) with its objects (linear assignment, ``scipy.optimize.linear_sum_assignment``):
    first in the order the graph made the blocks, each against the blocks assigned
    before it; then again against all the others, keeping a block's new assignment only
    when the whole holds more, until none changes. Deterministic."""
    return _assignment(graph, example)[0]


def _assignment(graph: SceneGraph, example: Scene) -> tuple[dict[str, str], float]:
    """``assign_objects``' assignment and its cost: relations broken, plus ``NEAR_MISS``
    times how far each misses."""
    objects = example.placed_objects()
    nodes = [node for node in graph.nodes() if node.kind == "object"]
    # A type of which the example leaves some style out is one block, whatever the styles.
    unstyled = {obj.type for obj in objects if obj.style is None}

    def block(type_name: str, style: str | None) -> tuple[str, str | None]:
        return (type_name, None if type_name in unstyled else style)

    blocks: dict[tuple[str, str | None], tuple[list[str], list[str]]] = {}
    for node in nodes:
        blocks.setdefault(block(node.type, node.style), ([], []))[0].append(node.id)
    for obj in objects:
        if block(obj.type, obj.style) not in blocks:
            raise InputError(
                f"the derivation has no {obj.type} (style {obj.style}) for example object {obj.id!r}"
            )
        blocks[block(obj.type, obj.style)][1].append(obj.id)
    for (type_name, _), (block_nodes, block_objects) in blocks.items():
        if len(block_nodes) != len(block_objects):
            raise InputError(
                f"the derivation makes {len(block_nodes)} {type_name}, the example has {len(block_objects)}"
            )
    node_ids = {node.id for node in nodes}
    edges = [edge for edge in graph.edges() if edge.source in node_ids and edge.target in node_ids]
    rests_on = scene_supports(example)
    type_of = {obj.id: obj.type for obj in objects}
    wanted = [
        (a, edge.label, b)
        for edge in edges
        if not RELATIONS[edge.label].support
        for a in type_of
        if type_of[a] == graph.node(edge.source).type
        for b in type_of
        if type_of[b] == graph.node(edge.target).type and b != a
    ]
    verdicts = measured_relations(example, wanted)
    supported = {edge.source for edge in edges if RELATIONS[edge.label].support}

    def edge_cost(source: str, label: str, target: str) -> float:
        if RELATIONS[label].support:
            return 0.0 if rests_on.get(source) == target else 1.0
        verdict = verdicts[(source, label, target)]
        miss = -float(verdict.value or 0.0)
        return (0.0 if verdict.satisfied else 1.0) + NEAR_MISS * miss / (1.0 + miss)

    def node_cost(node: str, obj: str, chosen: dict[str, str]) -> float:
        cost = 0.0 if (node in supported) == (obj in rests_on) else 1.0
        for edge in edges:
            if edge.source == node and edge.target in chosen:
                cost += edge_cost(obj, edge.label, chosen[edge.target])
            elif edge.target == node and edge.source in chosen:
                cost += edge_cost(chosen[edge.source], edge.label, obj)
        return cost

    def total(chosen: dict[str, str]) -> float:
        unary = sum((node in supported) != (obj in rests_on) for node, obj in chosen.items())
        return unary + sum(edge_cost(chosen[e.source], e.label, chosen[e.target]) for e in edges)

    def assigned(
        block_nodes: list[str], block_objects: list[str], chosen: dict[str, str]
    ) -> dict[str, str]:
        others = {node: obj for node, obj in chosen.items() if node not in block_nodes}
        costs = np.array(
            [[node_cost(node, obj, others) for obj in block_objects] for node in block_nodes]
        )
        rows, columns = linear_sum_assignment(costs)
        return {block_nodes[r]: block_objects[c] for r, c in zip(rows, columns, strict=False)}

    chosen: dict[str, str] = {}
    for block_nodes, block_objects in blocks.values():
        chosen.update(assigned(block_nodes, block_objects, chosen))
    best = total(chosen)
    for _ in range(len(blocks)):
        improved = False
        for block_nodes, block_objects in blocks.values():
            trial = {**chosen, **assigned(block_nodes, block_objects, chosen)}
            score = total(trial)
            if score < best - 1e-12:
                chosen, best, improved = trial, score, True
        if not improved:
            break
    return chosen, best


class _HoldingCache:
    """``holding_statements`` of one example, measured once per statement."""

    def __init__(self, example: Scene):
        self.example = example
        self.known: Counter = Counter()
        self.measured: set[Statement] = set()

    def counts(self, statements: Iterable[Statement]) -> Counter:
        new = set(statements) - self.measured
        if new:
            self.known.update(holding_statements(self.example, new))
            self.measured |= new
        return self.known

    def holds_all(self, graph: SceneGraph) -> bool:
        """Whether the example holds every relation statement of ``graph`` as often as
        it states it (supports aside: the signature has them)."""
        stated = signature(graph).relations
        known = self.counts(stated)
        return all(
            RELATIONS[label].support or count <= known[(subject, label, target)]
            for (subject, label, target), count in stated.items()
        )


def _search(
    rules: Rules,
    wanted: Signature,
    sign: Callable[[SceneGraph], Signature],
    name: str,
    fits: Callable[[SceneGraph], bool] | None = None,
    budget: ReplayBudget | None = None,
) -> list[SceneGraph]:
    """The expansions of ``rules`` whose ``sign`` is ``wanted`` (module docstring) and,
    when given, that ``fits`` (which must also hold of every partial expansion on the way);
    each replay also taken from ``budget`` when given."""
    found: list[SceneGraph] = []
    pending: list[list[int]] = [[]]
    replays = 0
    while pending:
        script = pending.pop()
        replays += 1
        if budget is not None:
            budget.take(name)
        if replays > MAX_REPLAYS:
            raise AmbiguousExample(
                f"{name}: more than {MAX_REPLAYS} partial derivations could lead to this scene; "
                "fit it from a scene.json that keeps its derivation"
            )
        draws = _Scripted(script)
        try:
            graph = expand_with(rules, draws)
        except _Undecided as undecided:
            if sign(draws.graph).within(wanted) and (fits is None or fits(draws.graph)):
                # pushed last-first, so that option 0 is tried first: the search order is fixed
                pending.extend(script + [option] for option in reversed(range(undecided.options)))
            continue
        except ExpansionError:
            continue
        if sign(graph).like(wanted) and (fits is None or fits(graph)):
            found.append(graph)
    return found
