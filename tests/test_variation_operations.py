"""Replace, grow and transfer, the compatibility filter, pinning and determinism."""

from __future__ import annotations

import math
from dataclasses import replace
from types import SimpleNamespace

import numpy as np
import pytest

from scenewright.api import build_scene
from scenewright.core.frames import to_local
from scenewright.examples import Example
from scenewright.examples.example import ObjectRecord, example_scene
from scenewright.variation import augment, structure_graph
from scenewright.variation.operations import grow_node, replace_object, transfer_items
from scenewright.variation.synthesis import apply_change, start_variant, vary


def box(object_id, kind, x, z, yaw_degrees, size, y=0.0):
    return ObjectRecord(object_id, kind, size, (x, y, z), math.radians(yaw_degrees))


def example(name, records):
    return Example(
        name,
        f"{name}.json",
        "example.json",
        example_scene(records, name=name, source=name, extent=(7.0, 7.0), room=None),
    )


# Two studies: a desk with a chair in front; the first has a lamp on the desk and a
# shelf, the second a bigger table with two books and a cabinet touching its left side.
FIRST = example(
    "first",
    [
        box("desk", "desk", 0.0, 0.0, 0.0, (1.4, 0.75, 0.7)),
        box("chair", "chair", 0.0, 0.8, 180.0, (0.5, 0.9, 0.5)),
        box("lamp", "lamp", 0.4, -0.1, 0.0, (0.2, 0.4, 0.2), y=0.75),
        box("shelf", "shelf", -2.5, -2.0, 0.0, (0.9, 1.8, 0.35)),
    ],
)
SECOND = example(
    "second",
    [
        box("table", "table", 0.5, 0.5, 0.0, (1.6, 0.74, 0.8)),
        box("seat", "stool", 0.5, 1.35, 180.0, (0.5, 0.85, 0.5)),
        box("book_a", "book", 0.0, 0.4, 0.0, (0.2, 0.05, 0.3), y=0.74),
        box("book_b", "book", 0.9, 0.6, 90.0, (0.2, 0.05, 0.3), y=0.74),
        box("cabinet", "cabinet", 1.6, 0.5, 0.0, (0.6, 0.7, 0.6)),
    ],
)


@pytest.fixture(scope="module")
def graph():
    return augment([FIRST, SECOND])


def test_roles_merge(graph):
    assert graph.node_of[(0, "desk")] == graph.node_of[(1, "table")]
    assert graph.node_of[(0, "chair")] == graph.node_of[(1, "seat")]


def test_replace_anchors_on_the_face_towards_the_chair(graph):
    variant = start_variant(0, FIRST)
    change = replace_object(variant, graph, "desk", (1, "table"))
    new = change.added[0][0]
    assert new.type == "table" and new.yaw == pytest.approx(0.0)
    # The desk's front (towards the chair, +Z) stays where it was; the table grows backwards.
    assert new.position[2] + new.size[2] / 2 == pytest.approx(0.0 + 0.35)
    assert new.position[0] == pytest.approx(0.0)
    # The paper's scale: the ratio term over the scene's diagonal (a 7 x 7 m extent).
    assert change.compatibility == pytest.approx(
        math.exp((1 - (1 + 0.2 / 3.0) * (1 + 0.01 / 1.49) * (1 + 0.1 / 1.5)) / math.hypot(7, 7))
    )
    # The lamp rides along onto the table's top, its place scaled.
    lamp = next(obj for obj, _ in change.added if obj.type == "lamp")
    assert lamp.position[1] == pytest.approx(0.74)
    lx, _ = to_local(new.position[0], new.position[2], new.yaw, lamp.position[0], lamp.position[2])
    assert lx == pytest.approx(0.4 * 1.6 / 1.4)


def test_grow_keeps_the_gap_to_the_neighbour_face(graph):
    variant = start_variant(0, FIRST)
    node = graph.node_of[(1, "cabinet")]
    change = grow_node(variant, graph, node, (1, "cabinet"))
    cabinet = change.added[0][0]
    # In the second study the cabinet touches the table's +X side (gap 0); the desk is
    # narrower, so it comes in to touch the desk's side.
    assert cabinet.position[0] - cabinet.size[0] / 2 == pytest.approx(0.7)
    assert change.record["next_to"] == "desk"


def test_transfer_onto_a_top_and_refused_where_nothing_can_stand(graph):
    variant = start_variant(0, FIRST)
    change = transfer_items(variant, graph, "desk", (1, "table"))
    assert change.removed == ["lamp"]
    books = [obj for obj, _ in change.added]
    assert [b.type for b in books] == ["book", "book"] and all(
        b.position[1] == pytest.approx(0.75) for b in books
    )
    assert (
        len({b.id for b in books}) == 2 and len(set(change.record["items"])) == 2
    )  # two books, two ids
    assert all(r.target == "desk" for r in change.relations)
    # A top 2.1 m up, or one narrower than a book, cannot carry them.
    tall = example("tall", [box("desk", "desk", 0.0, 0.0, 0.0, (1.4, 2.1, 0.7))])
    assert transfer_items(start_variant(0, tall), graph, "desk", (1, "table")) is None
    narrow = example("narrow", [box("desk", "desk", 0.0, 0.0, 0.0, (0.15, 0.75, 0.15))])
    assert transfer_items(start_variant(0, narrow), graph, "desk", (1, "table")) is None


def test_applied_change_pins_everything_untouched(graph):
    variant = start_variant(0, FIRST)
    change = replace_object(variant, graph, "desk", (1, "table"))
    done = apply_change(variant, graph, change, np.random.default_rng(0))
    assert done is not None and done.scene.layout.ok
    before = variant.objects()
    for object_id in ("chair", "shelf"):
        after = done.objects()[object_id]
        assert after.position == before[object_id].position and after.yaw == before[object_id].yaw
    assert done.origin["table_1"] == (1, "table") and "desk" not in done.objects()
    assert done.operations[0]["operation"] == "replace" and done.compatibility == pytest.approx(
        change.compatibility
    )


def test_regrown_object_returns_to_its_place():
    # The first study without its shelf, and with it: growing the shelf back into the
    # first from the second puts it where it was.
    full = example(
        "full",
        [
            box("desk", "desk", 0.0, 0.0, 0.0, (1.4, 0.75, 0.7)),
            box("chair", "chair", 0.0, 0.8, 180.0, (0.5, 0.9, 0.5)),
            box("shelf", "shelf", -1.2, 0.0, 0.0, (0.9, 1.8, 0.35)),
        ],
    )
    cut = example(
        "cut",
        [
            r
            for r in [
                box("desk", "desk", 0.0, 0.0, 0.0, (1.4, 0.75, 0.7)),
                box("chair", "chair", 0.0, 0.8, 180.0, (0.5, 0.9, 0.5)),
            ]
        ],
    )
    graph = augment([cut, full])
    node = graph.node_of[(1, "shelf")]
    variant = start_variant(0, cut)
    done = apply_change(
        variant, graph, grow_node(variant, graph, node, (1, "shelf")), np.random.default_rng(1)
    )
    shelf = done.objects()["shelf_1"]
    assert math.hypot(shelf.position[0] + 1.2, shelf.position[2]) <= 0.2
    assert abs(math.remainder(shelf.yaw, 2 * math.pi)) <= math.radians(15)


@pytest.mark.parametrize(
    "rules, seed, object_id", [("living_room", 2, "bookshelf_1"), ("kitchen", 1, "dining_table_1")]
)
def test_regrown_object_among_alike_ones_returns_to_its_place(rules, seed, object_id):
    # Two identical bookshelves with the same relations; a table among alike chairs.
    # With the object deleted, the cut room matches the full one as well with the alike
    # objects swapped as not; the place tie-break keeps each on its own, so the deleted
    # one is grown back where it was (without it: its twin took its node, and nothing
    # was grown; the table was put by the wrong chair, turned about 160 degrees).
    scene = build_scene(rules, seed)
    graph = structure_graph(scene)
    gone = {object_id, *(graph.ids[j] for j in graph.carried(graph.index(object_id)))}
    cut = replace(
        scene,
        objects=[o for o in scene.objects if o.id not in gone],
        relations=[r for r in scene.relations if r.source not in gone and r.target not in gone],
    )
    examples = [
        Example("cut", "cut", "scene.json", cut),
        Example("full", "full", "scene.json", scene),
    ]
    ag = augment(examples)
    variant = start_variant(0, examples[0])
    change = grow_node(variant, ag, ag.node_of[(1, object_id)], (1, object_id))
    done = apply_change(variant, ag, change, np.random.default_rng(seed))
    grown, original = done.objects()[change.added[0][0].id], scene.object(object_id)
    assert (
        math.hypot(
            grown.position[0] - original.position[0], grown.position[2] - original.position[2]
        )
        <= 0.2
    )
    assert abs(math.remainder(grown.yaw - original.yaw, 2 * math.pi)) <= math.radians(15)


def test_a_regrown_desk_brings_a_lamp_beside_its_laptop_on_its_own_top():
    # The lamp stands on the desk 2 cm below the laptop's top, beside it: it rests on
    # the desk, not on the laptop (before, height alone put it on the laptop, and no
    # layout could hold that).
    desk = [
        box("desk", "desk", 0.0, 0.0, 0.0, (1.2, 0.75, 0.6)),
        box("laptop", "laptop", 0.0, 0.0, 0.0, (0.34, 0.02, 0.24), y=0.75),
        box("lamp", "lamp", -0.45, 0.15, 0.0, (0.2, 0.45, 0.2), y=0.75),
    ]
    chair = box("chair", "chair", 0.0, 0.7, 180.0, (0.5, 0.9, 0.5))
    full, cut = example("full", [*desk, chair]), example("cut", [chair])
    graph = augment([cut, full])
    variant = start_variant(0, cut)
    change = grow_node(variant, graph, graph.node_of[(1, "desk")], (1, "desk"))
    rests_on = {r.source: r.target for r in change.relations if r.label == "OnTopOf"}
    assert rests_on == {"laptop_1": "desk_1", "lamp_1": "desk_1"}
    done = apply_change(variant, graph, change, np.random.default_rng(0))
    assert done is not None and done.scene.layout.ok


def test_low_compatibility_operations_are_not_applied():
    # The only member to swap in is a very different box: similarity far below 0.8.
    small = example("small", [box("crate", "crate", 0.0, 0.0, 0.0, (0.3, 0.3, 0.3))])
    big = example("big", [box("hall", "hall", 0.0, 0.0, 0.0, (3.0, 2.5, 3.0))])
    graph = augment([small, big], threshold=0.0)  # merge them anyway
    assert graph.node_of[(0, "crate")] == graph.node_of[(1, "hall")]
    assert replace_object(start_variant(0, small), graph, "crate", (1, "hall")).compatibility < 0.8
    assert vary([small, big], 3, seed=0, ag=graph, attempts=4) == []


def test_vary_is_deterministic():
    first = vary([FIRST, SECOND], 3, seed=7, attempts=6)
    second = vary([FIRST, SECOND], 3, seed=7, attempts=6)
    assert first and [r.scene.to_json(reproducible=True) for r in first] == [
        r.scene.to_json(reproducible=True) for r in second
    ]
    assert [r.synthesis() for r in first] == [r.synthesis() for r in second]
    assert all(r.scene.layout.ok for r in first)
    assert [r.compatibility for r in first] == sorted(
        (r.compatibility for r in first), reverse=True
    )


def test_a_change_no_layout_holds_is_not_laid_out_again(monkeypatch):
    # Every layout fails: each variant starts from an example, so the same first change
    # on the same example comes up in several attempts; it is laid out only once.
    import scenewright.generator.layout as layout

    laid: list[str] = []

    def failing(graph, seed, *, pinned=None, pinned_paths=None, start=None, **options):
        laid.append(
            repr(sorted({**pinned, **start}.items())) + repr(sorted(map(repr, graph.edges())))
        )
        return SimpleNamespace(ok=False)

    monkeypatch.setattr(layout, "layout_scene", failing)
    monkeypatch.setattr(
        layout, "measure_layout", lambda graph, poses, paths: SimpleNamespace(ok=False)
    )
    assert vary([FIRST, SECOND], 3, seed=7, attempts=8) == []
    assert len(laid) > 2 and len(set(laid)) == len(laid)


def room_example(name: str, objects: list[dict]) -> Example:
    import json
    import tempfile
    from pathlib import Path

    from scenewright.examples import load_example

    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / f"{name}.json"
        path.write_text(
            json.dumps({"room": {"width": 4.0, "depth": 3.5, "height": 2.6}, "objects": objects})
        )
        return load_example(path)


@pytest.mark.parametrize(
    "first, second",
    [
        ((0.45, 0.9, 0.5), (0.6, 1.1, 0.6)),  # a chair and an office chair
        ((0.8, 2.0, 0.35), (0.8, 1.0, 0.35)),  # a tall and a low bookshelf
        ((1.6, 0.55, 2.1), (1.0, 0.5, 2.0)),  # a double and a single bed
    ],
)
def test_like_pieces_are_compatible_enough_to_replace_each_other_in_a_room(first, second):
    from scenewright.variation.operations import _similarity
    from scenewright.variation.synthesis import KEEP

    scene = room_example(
        "r", [{"id": "t", "type": "table", "size": [1, 0.7, 1], "position": [0, 0]}]
    ).scene
    one = SimpleNamespace(size=first)
    other = SimpleNamespace(size=second)
    assert _similarity(one, other, scene) > KEEP
    bed, chair = SimpleNamespace(size=(1.6, 0.55, 2.1)), SimpleNamespace(size=(0.45, 0.9, 0.5))
    assert _similarity(bed, chair, scene) < KEEP  # unlike pieces are still refused


def test_an_object_grown_from_a_corner_of_a_hand_written_room_brings_its_corner():
    from scenewright.variation.operations import measured_walls

    example = room_example(
        "corner",
        [
            {
                "id": "chair",
                "type": "armchair",
                "size": [0.85, 0.95, 0.85],
                "position": [-1.575, -1.325],
                "yaw": 0,
            },
            {
                "id": "lamp",
                "type": "floor_lamp",
                "size": [0.35, 1.6, 0.35],
                "position": [-0.9, -1.575],
                "yaw": 0,
            },
            {
                "id": "table",
                "type": "side_table",
                "size": [0.45, 0.55, 0.45],
                "position": [0.5, 0.3],
                "yaw": 0,
            },
        ],
    ).scene
    assert measured_walls(example, "chair") == ["InCorner"]
    assert measured_walls(example, "lamp") == ["AgainstWall"]
    assert measured_walls(example, "table") == []
