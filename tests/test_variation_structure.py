"""Structure graphs: the relation set measured from hand-built configurations."""

from __future__ import annotations

import math

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from scenewright.examples.example import ObjectRecord, example_scene
from scenewright.variation import structure_graph
from scenewright.variation.structure import wrap


def graph_of(*records):
    return structure_graph(
        example_scene(list(records), name="t", source="t", extent=(10.0, 10.0), room=None)
    )


def box(object_id, x, z, yaw_degrees=0.0, size=(1.0, 1.0, 1.0), y=0.0, kind=None):
    return ObjectRecord(object_id, kind or object_id, size, (x, y, z), math.radians(yaw_degrees))


def relations(graph, a, b):
    return set(graph.relation_set(graph.index(a), graph.index(b)))


def test_vertical_contact_left_and_right_have_opposite_contact_angles():
    # A bed facing south (+Z); its own left is +X. Nightstands touching it on either side.
    bed = box("bed", 0.0, 0.0, size=(1.6, 0.5, 2.0))
    left = box("left", 1.05, -0.75, size=(0.5, 0.5, 0.5))
    right = box("right", -1.05, -0.75, size=(0.5, 0.5, 0.5))
    graph = graph_of(bed, left, right)
    assert {"V", "A"} <= relations(graph, "bed", "left") and "C" not in relations(
        graph, "bed", "left"
    )
    on_left = graph.edges[(graph.index("bed"), graph.index("left"))].contact_angles
    on_right = graph.edges[(graph.index("bed"), graph.index("right"))].contact_angles
    assert on_left == pytest.approx((math.pi / 2, math.pi / 2)) and on_right == pytest.approx(
        (-math.pi / 2, -math.pi / 2)
    )
    # Seen from the nightstand, the normal points back at the bed: turned by pi.
    back = graph.edges[(graph.index("left"), graph.index("bed"))].contact_angles
    assert [wrap(b - a) for a, b in zip(reversed(on_left), back, strict=False)] == pytest.approx(
        [math.pi, math.pi]
    )
    # The two nightstands are 1.6 m apart, far for their 0.35 m half diagonals.
    assert relations(graph, "left", "right") == set()


def test_facing_is_directed():
    desk = box("desk", 0.0, 0.0, size=(1.4, 0.75, 0.7))  # faces +Z
    chair = box("chair", 0.0, 0.8, 180.0, size=(0.5, 0.9, 0.5))  # in front of it, facing it
    graph = graph_of(desk, chair)
    assert {"F", "C"} <= relations(graph, "chair", "desk")
    assert "F" in relations(graph, "desk", "chair")
    edge = graph.edges[(graph.index("chair"), graph.index("desk"))]
    assert edge.gap == pytest.approx(0.8 - 0.35 - 0.25)
    assert abs(edge.facing_angle) == pytest.approx(math.pi)
    turned = graph_of(desk, box("chair", 0.0, 0.8, 0.0, size=(0.5, 0.9, 0.5)))  # back to the desk
    assert "F" not in relations(turned, "chair", "desk") and "F" in relations(
        turned, "desk", "chair"
    )


def test_alignment_needs_parallel_flush_sides():
    first = box("a", 0.0, 0.0, size=(1.0, 2.0, 0.6))
    flush = box("b", 1.3, 0.0, size=(1.0, 2.0, 0.6))
    assert "A" in relations(graph_of(first, flush), "a", "b")
    assert "A" not in relations(graph_of(first, box("b", 1.3, 0.2, size=(1.0, 2.0, 0.6))), "a", "b")
    assert "A" not in relations(
        graph_of(first, box("b", 1.3, 0.0, 20.0, size=(1.0, 2.0, 0.6))), "a", "b"
    )
    # Turned by 90 degrees but flush still counts: the boxes are parallel.
    assert "A" in relations(
        graph_of(first, box("b", 1.3, 0.0, 90.0, size=(0.6, 2.0, 1.0))), "a", "b"
    )


def test_close_records_the_gap_and_far_objects_have_no_edge():
    graph = graph_of(box("a", 0.0, 0.0), box("b", 1.3, 0.0))
    assert relations(graph, "a", "b") >= {"C"}
    assert graph.edges[(0, 1)].gap == pytest.approx(0.3)
    far = graph_of(box("a", 0.0, 0.0), box("b", 3.0, 0.0))
    assert far.edges == {}


def test_supported_objects_leave_the_layout_subgraph():
    desk = box("desk", 0.0, 0.0, size=(1.4, 0.75, 0.7))
    lamp = box("lamp", 0.4, 0.0, y=0.75, size=(0.2, 0.4, 0.2))
    bulb = box("bulb", 0.4, 0.0, y=1.15, size=(0.1, 0.1, 0.1))
    chair = box("chair", 0.0, 0.8, 180.0, size=(0.5, 0.9, 0.5))
    graph = graph_of(desk, lamp, bulb, chair)
    assert relations(graph, "desk", "lamp") == {"S"} and relations(graph, "lamp", "desk") == {"s"}
    assert [graph.ids[i] for i in graph.layout_nodes()] == ["desk", "chair"]
    assert [graph.ids[i] for i in graph.carried(graph.index("desk"))] == ["lamp", "bulb"]
    # A supported object is in no layout relation, even with the chair right beside the lamp.
    assert relations(graph, "lamp", "chair") == set()


@settings(max_examples=30, deadline=None)
@given(
    st.lists(
        st.tuples(
            st.floats(-3, 3),
            st.floats(-3, 3),
            st.floats(-180, 180),
            st.floats(0.2, 2.0),
            st.floats(0.2, 2.0),
        ),
        min_size=2,
        max_size=6,
    )
)
def test_every_edge_is_stored_both_ways_consistently(boxes):
    records = [
        box(f"o{k}", x, z, yaw, size=(w, 1.0, d)) for k, (x, z, yaw, w, d) in enumerate(boxes)
    ]
    graph = graph_of(*records)
    for (i, j), edge in graph.edges.items():
        back = graph.edges[(j, i)]
        assert back.gap == pytest.approx(edge.gap, abs=1e-9)
        assert wrap(back.facing_angle + edge.facing_angle) == pytest.approx(0.0, abs=1e-9)
        assert edge.relations - {"F"} == back.relations - {"F"}
        if edge.gap > 1e-6:  # separated: one separating axis, seen from either side
            for a, b in zip(reversed(edge.contact_angles), back.contact_angles, strict=False):
                assert abs(wrap(b - a - math.pi)) == pytest.approx(0.0, abs=1e-6)


def test_graded_memberships_fall_off_smoothly_around_each_threshold():
    from scenewright.variation.structure import CONTACT, fade

    assert fade(0.0, CONTACT, CONTACT) == 1.0 and fade(2 * CONTACT, CONTACT, CONTACT) == 0.0
    assert fade(CONTACT, CONTACT, CONTACT) == pytest.approx(0.5)
    values = [fade(gap / 100.0, CONTACT, CONTACT) for gap in range(11)]
    assert values == sorted(values, reverse=True)

    def grades(gap):
        graph = graph_of(box("a", 0.0, 0.0), box("b", 1.0 + gap, 0.0))  # 1 m cubes side by side
        return dict(zip("VAFC", graph.edges[(0, 1)].grades, strict=False)), relations(
            graph, "a", "b"
        )

    touching, crisp = grades(0.0)
    assert touching["V"] == 1.0 and touching["C"] == 0.0 and crisp == {"V", "A"}
    at_threshold, crisp = grades(CONTACT - 1e-9)
    assert (
        at_threshold["V"] == pytest.approx(0.5)
        and at_threshold["C"] == pytest.approx(0.5)
        and "V" in crisp
    )


def test_a_pair_just_beyond_near_is_in_the_fringe_not_an_edge():
    # 1 m cubes: near up to a gap of their half diagonal, 0.707 m; just beyond it no
    # relation holds, but near's fall-off still gives a graded membership.
    graph = graph_of(box("a", 0.0, 0.0), box("b", 1.72, 0.0))
    assert relations(graph, "a", "b") == set() and (0, 1) not in graph.edges
    grades = dict(zip("VAFC", graph.fringe[(0, 1)].grades, strict=False))
    assert 0.0 < grades["C"] < 0.5 and grades["V"] == 0.0
    far = graph_of(box("a", 0.0, 0.0), box("b", 3.0, 0.0))
    assert far.edges == {} and far.fringe == {}
