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
stops with ``AmbiguousExample`` after ``MAX_REPLAYS`` replays.

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
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Callable, Iterable
from dataclasses import dataclass

import numpy as np

from scenewright.core.errors import InputError
from scenewright.core.poses import Pose
from scenewright.core.relations import RELATIONS
from scenewright.core.room import ROOM_KINDS, ROOM_NODE
from scenewright.core.scene import Scene
from scenewright.core.scene_graph import SceneGraph, SceneParams
from scenewright.generator.catalog import CatalogEntry
from scenewright.generator.layout import measure_layout
from scenewright.generator.expand import Draws, expand_with
from scenewright.generator.rules import Rules
from scenewright.generator.rules_errors import ExpansionError

#: A relation statement of a signature: (subject type, label, target type or room kind).
Statement = tuple[str, str, str]
#: Replays one example may take before the search gives up.
MAX_REPLAYS = 20_000


class AmbiguousExample(InputError):
    """An example with more possible derivations than the search may try."""


@dataclass(frozen=True)
class Signature:
    """What a derivation must reproduce of an example: three multisets (``Counter``s)."""

    objects: Counter
    parents: Counter
    relations: Counter | None  # None: not compared (an example measured from geometry)

    def within(self, other: Signature) -> bool:
        """Whether this scene could still grow into ``other``: an expansion only adds
        objects and relations, so none of its multisets may exceed ``other``'s."""
        pairs = [(self.objects, other.objects), (self.parents, other.parents)]
        if self.relations is not None and other.relations is not None:
            pairs.append((self.relations, other.relations))
        return all(mine <= theirs for mine, theirs in pairs)  # Counter inclusion

    def like(self, other: Signature) -> bool:
        """The same signature (relations compared only when both have them)."""
        both = self.relations is not None and other.relations is not None
        return self.objects == other.objects and self.parents == other.parents and (not both or self.relations == other.relations)


def resting_signature(graph: SceneGraph) -> Signature:
    """The signature by what rests on what: (type, style) of the objects and (type, the
    type its support-family relation rests it on); relations not compared."""
    nodes = {node.id: node for node in graph.nodes()}
    things = [node for node in nodes.values() if node.kind not in ROOM_KINDS]
    rests_on = {edge.source: nodes[edge.target].type for edge in graph.edges() if RELATIONS[edge.label].support}
    return Signature(
        Counter((node.type, node.style) for node in things),
        Counter((node.type, rests_on.get(node.id)) for node in things),
        None,
    )


def holding_statements(scene: Scene, statements: set[Statement]) -> Counter:
    """Statement -> how many objects of its subject type the example ``scene`` holds it
    for (with some other object of the target type, or against its room), for every
    statement of ``statements`` that is not a support (those are in the signature)."""
    objects = scene.placed_objects()
    graph = SceneGraph(params=SceneParams(extent=tuple(scene.extent), ground="floor" if scene.room else "grass",
                                          room=scene.room))  # fmt: skip
    node_of, poses = {}, {}
    for obj in objects:
        node_of[obj.id] = graph.add_node(CatalogEntry(obj.type, "object", obj.noun or obj.type, size=tuple(obj.size)))
        poses[node_of[obj.id]] = Pose(*(float(v) for v in obj.position), float(obj.yaw))
    type_of = {node_of[obj.id]: obj.type for obj in objects}
    measured = set()
    for subject_type, label, target in statements:
        if RELATIONS[label].support or _unmeasurable(label, scene):
            continue
        for subject in (node_of[o.id] for o in objects if o.type == subject_type):
            if target in ROOM_KINDS:
                others = [ROOM_NODE]
            else:
                others = [node_of[o.id] for o in objects if o.type == target and node_of[o.id] != subject]
            for other in others:
                if (subject, label, other) not in measured:
                    measured.add((subject, label, other))
                    graph.add_relation(subject, other, label)
    held = {
        (relation.source, relation.label, type_of.get(relation.target, ROOM_NODE))
        for relation in measure_layout(graph, poses, {}).relations if relation.satisfied
    }  # fmt: skip
    held_by_type = Counter((type_of[subject], label, role) for subject, label, role in held)
    return Counter({
        (subject_type, label, target): len(objects) if _unmeasurable(label, scene)  # may hold for every one: tells nothing
        else held_by_type[(subject_type, label, ROOM_NODE if target in ROOM_KINDS else target)]
        for subject_type, label, target in statements
    })  # fmt: skip


def _unmeasurable(label: str, scene: Scene) -> bool:
    """Whether the example cannot show whether ``label`` holds: a wall label without a
    room, or a window label in a room without windows (the hand-written format states
    no openings), so that the statement neither wins nor loses a derivation."""
    wall = RELATIONS[label].wall
    if wall is None:
        return False
    if scene.room is None:
        return True
    return wall in ("under_window", "beside_window") and not any(o.kind == "window" for o in scene.room.openings)


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


def measured_derivations_of(rules: Rules, example: Scene, name: str = "example") -> list[list[dict]]:
    """The derivations of ``rules`` that make an example read from geometry alone: those
    of its resting signature that state the most relations the example holds (module
    docstring), in the order the search finds them.

    The search first keeps to derivations every statement of which the example holds
    (partial ones pruned as soon as they state one it does not, which makes it fast);
    only when none is found does it take every derivation of the resting signature and
    keep the best-agreeing ones."""
    holding = _HoldingCache(example)
    wanted = resting_signature(example.graph())
    graphs = _search(rules, wanted, resting_signature, name, holding.holds_all)
    if not graphs:
        graphs = _search(rules, wanted, resting_signature, name)
    if not graphs:
        return []
    agreement = [geometric_agreement(graph, holding.counts(signature(graph).relations)) for graph in graphs]
    best = max(agreement)
    return [graph.derivation for graph, score in zip(graphs, agreement) if score == best]


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
        return all(RELATIONS[label].support or count <= known[(subject, label, target)]
                   for (subject, label, target), count in stated.items())  # fmt: skip


def _search(
    rules: Rules, wanted: Signature, sign: Callable[[SceneGraph], Signature], name: str,
    fits: Callable[[SceneGraph], bool] | None = None,
) -> list[SceneGraph]:  # fmt: skip
    """The expansions of ``rules`` whose ``sign`` is ``wanted`` (module docstring) and,
    when given, that ``fits`` (which must also hold of every partial expansion on the way)."""
    found: list[SceneGraph] = []
    pending: list[list[int]] = [[]]
    replays = 0
    while pending:
        script = pending.pop()
        replays += 1
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
