"""The Augmented Graph: matched objects merged into nodes, every object in one node."""

from __future__ import annotations

import json
import math

import numpy as np

from scenewright.examples import Example
from scenewright.examples.example import ObjectRecord, example_scene
from scenewright.variation import augment
from scenewright.variation.perturb import perturbed_copy


def box(object_id, kind, x, z, yaw_degrees, size, y=0.0):
    return ObjectRecord(object_id, kind, size, (x, y, z), math.radians(yaw_degrees))


ROOM = [
    box("bed", "bed", 0.0, 0.0, 0.0, (1.6, 0.5, 2.0)),
    box("stand", "nightstand", 1.05, -0.75, 0.0, (0.5, 0.55, 0.5)),
    box("lamp", "lamp", 1.05, -0.75, 0.0, (0.2, 0.4, 0.2), y=0.55),
    box("desk", "desk", 2.8, 2.5, -90.0, (1.2, 0.75, 0.6)),
    box("chair", "chair", 2.05, 2.5, 90.0, (0.45, 0.9, 0.45)),
    box("wardrobe", "wardrobe", -2.5, 2.0, 90.0, (1.2, 2.0, 0.6)),
]


def examples():
    base = example_scene(ROOM, name="a", source="a", extent=(8.0, 8.0), room=None)
    found = [Example("a", "a.json", "example.json", base)]
    for seed, name in ((3, "b"), (5, "c")):
        copy, _ = perturbed_copy(base, np.random.default_rng(seed), remove=0, add=1)
        found.append(Example(name, f"{name}.json", "example.json", copy))
    return found


def test_every_object_is_in_exactly_one_node_and_roles_merge():
    given = examples()
    graph = augment(given)
    members = [m for node in graph.nodes for m in node.members]
    assert len(members) == len(set(members)) == sum(len(e.scene.objects) for e in given)
    assert set(graph.node_of) == set(members)
    # The disguised copies' beds (renamed, moved) join the first example's bed.
    bed = graph.node(graph.node_of[(0, "bed")])
    assert len(bed.members) == 3 and {e for e, _ in bed.members} == {0, 1, 2}
    chair = graph.node(graph.node_of[(0, "chair")])
    assert len(chair.members) == 3
    # The added boxes have nodes of their own.
    assert all(len(graph.node(graph.node_of[(e, "added_0")]).members) == 1 for e in (1, 2))
    # The lamps rest on the nightstand's node, each a node of its own.
    lamp = graph.node(graph.node_of[(0, "lamp")])
    assert lamp.supporter == graph.node_of[(0, "stand")]
    # Edges unite the members' relations: chair and desk face each other.
    assert "F" in graph.edges[(chair.id, graph.node_of[(0, "desk")])]


def test_augmented_graph_is_deterministic_and_printable():
    first, second = augment(examples()), augment(examples())
    assert json.dumps(first.to_dict()) == json.dumps(second.to_dict())
    dot = first.to_dot()
    assert dot.startswith("digraph augmented {") and dot.count("->") == len(
        first.to_dict()["edges"]
    )
