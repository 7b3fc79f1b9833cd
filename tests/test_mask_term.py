"""The layout mask as an energy part: its value by hand, its incremental deltas against
full recomputation on random moves, the verdict that never reads it, layouts without
a mask left as they were, and the completion mask laid over the room as ``mask_at``
reads it."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from test_room_terms import BED, CRATE, WARDROBE, bedroom, check_moves, graph_of, random_room_scene

from scenewright.completion.features import CanonicalFrame
from scenewright.completion.layout_mask import LayoutMask, floor_mask, mask_at
from scenewright.core.errors import InputError
from scenewright.core.poses import Pose
from scenewright.core.room import Room
from scenewright.generator.layout import FloorMask, LayoutParams, layout_scene, measure_layout
from scenewright.generator.layout.energy import MASK_PART, PARTS
from scenewright.generator.layout.mask_term import compile_mask
from scenewright.generator.layout.problem import compile_problem
from scenewright.generator.layout.sampler import Relocator, start_chain


def half_mask(boxes=("crate_1",)) -> FloorMask:
    """Over the 5 x 4 bedroom: 1 on its west half (x < 0), 0 on its east half."""
    values = np.zeros((4, 10))
    values[:, :5] = 1.0
    return FloorMask(values, (-2.5, -2.0, 2.5, 2.0), tuple(boxes))


def measured(graph, poses, mask=None, params=None):
    return measure_layout(
        graph,
        {k: Pose(x, 0.0, z, math.radians(yaw)) for k, (x, z, yaw) in poses.items()},
        {},
        params=params,
        mask=mask,
    )


def test_a_box_costs_the_weight_times_the_share_of_its_footprint_off_the_mask():
    graph = graph_of(bedroom(), ("crate", CRATE), ("bed", BED))
    poses = {"crate_1": (-1.0, 0.0, 0.0), "bed_1": (1.2, 0.0, 0.0)}
    assert (
        measured(graph, poses, half_mask()).parts[MASK_PART] == 0.0
    )  # on the mask; the bed is not listed
    poses["crate_1"] = (1.0, -1.0, 0.0)
    assert measured(graph, poses, half_mask()).parts[MASK_PART] == pytest.approx(1.0)  # off it
    poses["crate_1"] = (
        0.0,
        -1.0,
        90.0,
    )  # across the line: samples at x -0.2, -0.1 on the mask, 0, 0.1, 0.2 off
    straddling = measured(graph, poses, half_mask(), LayoutParams(mask_weight=2.0)).parts[MASK_PART]
    assert straddling == pytest.approx(2.0 * (1.0 - 2.0 / 5.0))


def test_without_a_mask_the_layout_has_no_mask_part_and_is_unchanged():
    graph = graph_of(bedroom(), ("wardrobe", WARDROBE), ("bed", BED))
    graph.add_relation("wardrobe_1", "room", "AgainstWall")
    graph.add_relation("bed_1", "room", "AgainstWall")
    plain = layout_scene(graph, 3)
    assert MASK_PART not in plain.parts and tuple(plain.parts) == PARTS
    nothing = layout_scene(graph, 3, mask=FloorMask(np.ones((2, 2)), (-2.5, -2.0, 2.5, 2.0), ()))
    assert nothing.parts[MASK_PART] == 0.0  # a mask for no box costs nothing and changes no move
    assert nothing.poses == plain.poses and nothing.steps == plain.steps


def test_the_verdict_never_reads_the_mask():
    graph = graph_of(bedroom(), ("wardrobe", WARDROBE), ("crate", CRATE))
    for crate in (
        (-1.5, -1.0, 0.0),
        (1.5, 0.5, 0.0),
    ):  # in the wardrobe's free space, then clear of it
        poses = {"wardrobe_1": (-1.5, -1.7, 0.0), "crate_1": crate}
        plain, masked = (
            measured(graph, poses),
            measured(graph, poses, half_mask(("crate_1", "wardrobe_1"))),
        )
        assert (masked.ok, masked.problems, masked.relations) == (
            plain.ok,
            plain.problems,
            plain.relations,
        )
        assert {k: v for k, v in masked.parts.items() if k != MASK_PART} == plain.parts


def test_a_mask_pulls_its_box_to_where_it_is_high():
    graph = graph_of(bedroom(), ("crate", CRATE))
    graph.add_relation("crate_1", "room", "AgainstWall")
    plain = [layout_scene(graph, seed).poses["crate_1"].x for seed in range(4)]
    assert max(plain) > 0.0  # against any wall: some seeds put it on the east half
    for seed in range(4):
        result = layout_scene(graph, seed, mask=half_mask())
        assert (
            result.ok and result.parts[MASK_PART] == 0.0 and result.poses["crate_1"].x < -0.25
        )  # wholly west


@settings(max_examples=9, deadline=None)
@given(seed=st.integers(0, 10_000))
def test_incremental_mask_deltas_equal_full_recomputation_on_random_moves(seed):
    def one_mask(ids, rng, xs, zs):
        listed = [box_id for box_id in ids if rng.random() < 0.7]
        return FloorMask(rng.random((10, 10)), (min(xs), min(zs), max(xs), max(zs)), tuple(listed))

    check_mask_deltas(seed, one_mask)


def check_mask_deltas(seed, masks_for):
    """Random moves in a random room with the masks ``masks_for(ids, rng, xs, zs)``
    makes, each delta of the mask part against full recomputation."""
    graph = random_room_scene(seed)
    problem = compile_problem(graph)
    rng = np.random.default_rng(seed)
    room = graph.params.room
    xs, zs = [c[0] for c in room.corners], [c[1] for c in room.corners]
    problem.mask = compile_mask(masks_for(problem.ids, rng, xs, zs), problem.ids)
    energy, mover = start_chain(problem, LayoutParams(), rng)
    check_moves(energy, mover, rng, 30, Relocator(problem, energy.state, mover), parts=(MASK_PART,))


def test_a_bad_mask_is_refused_on_one_line():
    ids = ["crate_1"]
    with pytest.raises(InputError, match="'sofa_1' is not an object"):
        compile_mask(FloorMask(np.ones((2, 2)), (0, 0, 1, 1), ("sofa_1",)), ids)
    with pytest.raises(InputError, match="from 0 to 1"):
        compile_mask(FloorMask(np.full((2, 2), 1.5), (0, 0, 1, 1), ()), ids)
    with pytest.raises(InputError, match="positive size"):
        compile_mask(FloorMask(np.ones((2, 2)), (0, 0, 0, 1), ()), ids)


@settings(max_examples=12, deadline=None)
@given(
    transpose=st.booleans(), flip_x=st.booleans(), flip_z=st.booleans(), seed=st.integers(0, 1000)
)
def test_the_floor_mask_reads_what_mask_at_reads_at_every_room_point(
    transpose, flip_x, flip_z, seed
):
    rng = np.random.default_rng(seed)
    room = (
        Room.rectangle(3.0, 4.2) if transpose else Room.rectangle(4.6, 3.4)
    )  # deeper than wide: transposed
    layout = LayoutMask(
        rng.random((10, 10)), CanonicalFrame(transpose, flip_x, flip_z), np.zeros(4), {}
    )
    floor = floor_mask(layout, room, ())
    compiled = compile_mask(floor, []).grids[0]
    width, depth = room.extent
    points = (rng.random((200, 2)) - 0.5) * np.array([width, depth]) * 0.999
    cells = [
        compiled.rows[min(int((z - compiled.z0) / compiled.cell_z), 9)][
            min(int((x - compiled.x0) / compiled.cell_x), 9)
        ]
        for x, z in points
    ]
    assert cells == mask_at(layout, room, points).tolist()


@settings(max_examples=9, deadline=None)
@given(seed=st.integers(0, 10_000))
def test_incremental_deltas_with_several_weighted_confining_masks_equal_full_recomputation(seed):
    def halves(ids, rng, xs, zs):
        middle = (min(xs) + max(xs)) / 2.0
        west, east = [b for b in ids if rng.random() < 0.5], [b for b in ids if rng.random() < 0.5]
        return [  # two halves reading 0 beyond themselves; a box may be listed by both and by a confining one
            FloorMask(
                rng.random((10, 10)), (min(xs), min(zs), middle, max(zs)), tuple(west), outside=0.0
            ),
            FloorMask(
                rng.random((4, 6)),
                (middle, min(zs), max(xs), max(zs)),
                tuple(east),
                outside=0.0,
                weight=2.5,
            ),
            FloorMask(
                np.ones((1, 1)),
                (min(xs), min(zs), middle, max(zs)),
                tuple(east),
                outside=0.0,
                weight=3.0,
                confine=True,
            ),
        ]

    check_mask_deltas(seed, halves)


def test_a_mask_with_an_outside_value_costs_what_lies_beyond_it_and_confining_makes_it_a_problem():
    graph = graph_of(bedroom(), ("crate", CRATE))
    west_half = FloorMask(
        np.ones((1, 1)), (-2.5, -2.0, 0.0, 2.0), ("crate_1",), outside=0.0, weight=2.0
    )
    edge = replace_mask(west_half, outside=None)
    east = {"crate_1": (1.0, 0.0, 0.0)}
    assert measured(graph, east, edge).parts[MASK_PART] == 0.0  # the nearest edge cell reads 1
    assert measured(graph, east, west_half).parts[MASK_PART] == pytest.approx(
        2.0
    )  # wholly beyond: the weight
    assert measured(graph, east, west_half).ok  # a preference only
    confined = measured(graph, east, replace_mask(west_half, confine=True))
    assert not confined.ok and confined.problems == ["crate_1 stands outside its part of the room"]
    assert measured(graph, {"crate_1": (-1.0, 0.0, 0.0)}, replace_mask(west_half, confine=True)).ok


def test_bad_mask_weights_and_outside_values_are_refused():
    with pytest.raises(InputError, match="outside value"):
        compile_mask(FloorMask(np.ones((2, 2)), (0, 0, 1, 1), (), outside=2.0), [])
    with pytest.raises(InputError, match="weight"):
        compile_mask(
            [
                FloorMask(np.ones((2, 2)), (0, 0, 1, 1), ()),
                FloorMask(np.ones((2, 2)), (0, 0, 1, 1), (), weight=0.0),
            ],
            [],
        )


def replace_mask(mask, **changes):
    from dataclasses import replace

    return replace(mask, **changes)
