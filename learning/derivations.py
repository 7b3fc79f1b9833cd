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
"""

from __future__ import annotations

from collections import Counter
from dataclasses import dataclass

import numpy as np

from scenewright.core.errors import InputError
from scenewright.core.room import ROOM_KINDS
from scenewright.core.scene_graph import SceneGraph
from scenewright.generator.expand import Draws, expand_with
from scenewright.generator.rules import Rules
from scenewright.generator.rules_errors import ExpansionError

#: Replays one example may take before the search gives up.
MAX_REPLAYS = 20_000


class AmbiguousExample(InputError):
    """An example with more possible derivations than the search may try."""


@dataclass(frozen=True)
class Signature:
    """What a derivation must reproduce of an example: three multisets (``Counter``s)."""

    objects: Counter
    parents: Counter
    relations: Counter

    def within(self, other: Signature) -> bool:
        """Whether this scene could still grow into ``other``: an expansion only adds
        objects and relations, so none of its multisets may exceed ``other``'s."""
        return all(
            mine <= theirs  # Counter inclusion
            for mine, theirs in ((self.objects, other.objects), (self.parents, other.parents),
                                 (self.relations, other.relations))
        )  # fmt: skip


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
    wanted = signature(example)
    found: list[list[dict]] = []
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
            if signature(draws.graph).within(wanted):
                # pushed last-first, so that option 0 is tried first: the search order is fixed
                pending.extend(script + [option] for option in reversed(range(undecided.options)))
            continue
        except ExpansionError:
            continue
        if signature(graph) == wanted:
            found.append(graph.derivation)
    return found
