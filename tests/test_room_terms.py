"""The room's own energy terms: walls, square, clearance, door swing and access.

Hand-placed configurations that do and do not break each term (in a plain room, with
turned furniture, in a rotated room and in an L-shaped one), their verdicts in words,
the incremental energy against full recomputation on random moves, the reachability
grid's exact updates, and outdoors, where the terms are 0 and cost nothing.
"""

import math

import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st

from scenewright.core.geometry import Rect, corners, make_rect
from scenewright.core.poses import Pose
from scenewright.core.room import Room
from scenewright.core.scene_graph import SceneGraph, SceneParams
from scenewright.generator import expand, load_rules
from scenewright.generator.catalog import CatalogEntry
from scenewright.generator.layout import LayoutParams, layout_scene, measure_layout
from scenewright.generator.layout.energy import Energy
from scenewright.generator.layout.problem import compile_problem
from scenewright.generator.layout.reachability import CORRIDOR_HALF, QUANTUM, AccessGrid
from scenewright.generator.layout.room_terms import ACCESS_BASE, ROOM_PARTS, SQUARE_SIGMA2
from scenewright.generator.layout.room_zones import Walls
from scenewright.generator.layout.sampler import Relocator, metropolis, start_chain
from scenewright.generator.layout.state import State
from scenewright.generator.layout.synthetic import village_graph

WARDROBE = dict(size=(1.2, 2.0, 0.6), clearance=(("front", 0.8),), access=("front",))
DESK = dict(size=(1.2, 0.75, 0.6), clearance=(("front", 0.7),), access=("front",))
CHAIR = dict(size=(0.45, 0.9, 0.5))
BED = dict(size=(1.6, 0.9, 2.1), access=("any",))
RUG = dict(size=(2.0, 0.01, 1.4), access=())
CRATE = dict(size=(0.5, 1.0, 0.5), access=())


def bedroom() -> Room:
    """5 x 4 centred on the origin: a 0.9 m door in the south wall at x = 1.5 (its swing
    x 1.05..1.95, z 1.1..2.0), a window in the north wall."""
    return (
        Room.rectangle(5, 4)
        .with_opening("door", "south", 1.0, 0.9)
        .with_opening("window", "north", 2.5, 1.4, 1.2, 0.9)
    )


def rotated(angle: float = math.radians(30.0)) -> Room:
    """The 5 x 4 rectangle turned by ``angle``, with a door in its south wall (wall_3)."""
    c, s = math.cos(angle), math.sin(angle)
    corners_ = [
        (x * c - z * s, x * s + z * c)
        for x, z in ((-2.5, -2.0), (2.5, -2.0), (2.5, 2.0), (-2.5, 2.0))
    ]
    return Room.polygon(corners_).with_opening("door", "wall_3", 1.0, 0.9)


def l_shaped() -> Room:
    """6 x 5 less a 3 x 2 notch; centred, its corners are (-3, -2.5), (3, -2.5), (3, 0.5),
    (0, 0.5) (the reflex corner), (0, 2.5), (-3, 2.5). A door at x = -2 in the north wall."""
    return Room.polygon([(0, 0), (6, 0), (6, 3), (3, 3), (3, 5), (0, 5)]).with_opening(
        "door", "wall_1", 1.0, 0.9
    )


def graph_of(room: Room | None, *objects, square: bool = True) -> SceneGraph:
    """A graph with one object per (name, fields) pair; ids are name_1, name_2, ..."""
    params = (
        SceneParams(extent=room.extent, room=room, square=square)
        if room
        else SceneParams(extent=(20.0, 20.0))
    )
    graph = SceneGraph(params)
    for name, fields in objects:
        graph.add_node(CatalogEntry(name, "object", name, **fields))
    return graph


def energy_at(graph: SceneGraph, poses: dict) -> Energy:
    """The energy with every object at its pose: {id: (x, z, yaw in degrees)}."""
    problem = compile_problem(graph)
    state = State(problem)
    for box, box_id in enumerate(problem.ids):
        x, z, yaw = poses[box_id]
        state.set_pose(box, x, z, math.radians(yaw))
    energy = Energy(problem, state, LayoutParams())
    energy.activate(list(range(problem.n_boxes)))
    return energy


def measured(graph: SceneGraph, poses: dict):
    """``measure_layout`` of the objects at {id: (x, z, yaw in degrees)}."""
    return measure_layout(
        graph, {k: Pose(x, 0.0, z, math.radians(yaw)) for k, (x, z, yaw) in poses.items()}, {}
    )


def assert_cached_parts_true(energy: Energy) -> None:
    full = energy.full()
    for part in energy.part_names:
        assert energy.parts[part] == pytest.approx(full[part], abs=1e-9), part


# -- walls ------------------------------------------------------------------------------


def test_a_box_on_the_floor_costs_nothing_and_one_through_a_wall_is_reported():
    graph = graph_of(bedroom(), ("desk", DESK))
    inside = energy_at(graph, {"desk_1": (0.0, -1.7, 0.0)})
    assert inside.parts["walls"] == 0.0 and inside.parts["extent"] == 0.0
    through = measured(graph, {"desk_1": (0.0, -1.9, 0.0)})  # back 0.2 m into the north wall
    assert (
        through.parts["walls"] > 0.0 and through.parts["extent"] == 0.0
    )  # the walls replace the extent
    assert through.problems == ["desk_1 crosses the wall"] and not through.ok


def test_a_turned_box_in_a_rotated_room_is_held_by_the_rotated_walls():
    room = rotated()
    wall = room.walls[0]  # the north wall, turned by 30 degrees
    graph = graph_of(room, ("desk", dict(DESK, clearance=())))
    yaw = math.degrees(wall.facing_yaw)
    fits = wall.to_world(2.5, 0.3)  # the desk's back on the wall
    assert energy_at(graph, {"desk_1": (*fits, yaw)}).parts["walls"] == pytest.approx(0.0, abs=1e-9)
    beyond = wall.to_world(2.5, 0.1)  # 0.2 m through it
    energy = energy_at(graph, {"desk_1": (*beyond, yaw)})
    assert energy.room.wall_excess(0) == pytest.approx(0.2, abs=1e-9)
    assert energy.parts["walls"] > 0.0


def test_in_an_l_shaped_room_a_box_may_not_cross_the_inner_corner():
    graph = graph_of(l_shaped(), ("crate", dict(size=(0.566, 1.0, 0.566))))
    # Turned by 45 degrees round the reflex corner (0, 0.5): all four of its corners
    # are on the floor, yet the wall's corner pokes 0.21 m into it.
    energy = energy_at(graph, {"crate_1": (-0.05, 0.45, 45.0)})
    assert all(l_shaped().contains(x, z) for x, z in corners(energy.state.rects[0]))
    assert energy.room.wall_excess(0) == pytest.approx(0.3 / math.sqrt(2.0), abs=1e-3)
    assert measured(graph, {"crate_1": (-0.05, 0.45, 45.0)}).problems == [
        "crate_1 crosses the wall"
    ]
    clear = energy_at(graph, {"crate_1": (-1.0, 0.0, 45.0)})
    assert clear.parts["walls"] == 0.0


@settings(max_examples=40, deadline=None)
@given(
    x=st.floats(-3.5, 3.5),
    z=st.floats(-3.0, 3.0),
    yaw=st.floats(-math.pi, math.pi),
    width=st.floats(0.1, 2.0),
    depth=st.floats(0.1, 2.0),
    shape=st.sampled_from(["rectangle", "l", "rotated"]),
)
def test_the_energy_measures_wall_crossing_as_the_room_does(x, z, yaw, width, depth, shape):
    room = {"rectangle": bedroom, "l": l_shaped, "rotated": rotated}[shape]()
    rect = make_rect(x, z, width, depth, yaw)
    assert Walls(room).excess(rect) == pytest.approx(room.footprint_excess(corners(rect)), abs=1e-9)


# -- square ---------------------------------------------------------------------------------


def test_square_costs_nothing_on_the_axes_and_grows_with_the_angle_off_them():
    graph = graph_of(bedroom(), ("crate", CRATE))
    assert [
        energy_at(graph, {"crate_1": (0.0, 0.0, yaw)}).parts["square"]
        for yaw in (0.0, 90.0, -180.0)
    ] == [pytest.approx(0.0, abs=1e-12)] * 3
    fifteen = energy_at(graph, {"crate_1": (0.0, 0.0, 15.0)}).parts["square"]
    thirty = energy_at(graph, {"crate_1": (0.0, 0.0, -60.0)}).parts["square"]
    most = energy_at(graph, {"crate_1": (0.0, 0.0, 45.0)}).parts["square"]
    assert fifteen == pytest.approx(math.radians(15.0) ** 2 / (2.0 * SQUARE_SIGMA2))
    assert 0.6 < fifteen < 0.8 and 5.5 < most < 6.5 and fifteen < thirty < most


def test_square_follows_a_rotated_room_and_can_be_switched_off():
    # Turned by 30 degrees, the walls run at yaws 60 and -30 (mod 90).
    graph = graph_of(rotated(math.radians(30.0)), ("crate", CRATE))
    assert energy_at(graph, {"crate_1": (0.0, 0.0, -30.0)}).parts["square"] == pytest.approx(
        0.0, abs=1e-12
    )
    assert energy_at(graph, {"crate_1": (0.0, 0.0, 60.0)}).parts["square"] == pytest.approx(
        0.0, abs=1e-12
    )
    assert energy_at(graph, {"crate_1": (0.0, 0.0, 0.0)}).parts["square"] > 2.0
    loose = graph_of(bedroom(), ("crate", CRATE), square=False)
    assert energy_at(loose, {"crate_1": (0.0, 0.0, 30.0)}).parts["square"] == 0.0


# -- clearance ---------------------------------------------------------------------------


def wardrobe_and(other: str, fields: dict, at: tuple, *, relation: str | None = None):
    graph = graph_of(bedroom(), ("wardrobe", WARDROBE), (other, fields))
    if relation:
        graph.add_relation(f"{other}_1", "wardrobe_1", relation)
    return graph, {
        "wardrobe_1": (-1.5, -1.7, 0.0),
        f"{other}_1": at,
    }  # against the north wall, facing south


def test_a_box_in_the_space_kept_free_in_front_is_charged_and_reported():
    graph, poses = wardrobe_and("chair", CHAIR, (-1.5, -1.0, 0.0))  # 0.15 m in front of the doors
    result = measured(graph, poses)
    assert result.parts["clearance"] > 0.0
    assert result.problems == ["chair_1 stands in the space kept free in front of wardrobe_1"]
    poses["chair_1"] = (-1.5, -0.3, 0.0)  # 0.85 m in front: clear
    assert measured(graph, poses).parts["clearance"] == 0.0


def test_partners_rugs_and_what_stands_on_the_owner_may_be_in_its_space():
    graph, poses = wardrobe_and("chair", CHAIR, (-1.5, -1.0, 0.0), relation="NextToFront")
    assert measured(graph, poses).parts["clearance"] == 0.0
    graph, poses = wardrobe_and("rug", RUG, (-1.5, -0.8, 0.0))
    assert measured(graph, poses).parts["clearance"] == 0.0


def test_turned_furniture_keeps_its_space_on_its_own_side():
    # Against the west wall facing east: the front space runs east, the left one north.
    fields = dict(WARDROBE, clearance=(("front", 0.8), ("left", 0.5)))
    graph = graph_of(bedroom(), ("wardrobe", fields), ("crate", CRATE))
    west = (-2.2, 0.0, 90.0)
    east_of_it = measured(graph, {"wardrobe_1": west, "crate_1": (-1.4, 0.0, 0.0)})
    assert east_of_it.problems == ["crate_1 stands in the space kept free in front of wardrobe_1"]
    north_of_it = measured(graph, {"wardrobe_1": west, "crate_1": (-2.2, -0.9, 0.0)})
    assert north_of_it.problems == [
        "crate_1 stands in the space kept free to the left of wardrobe_1"
    ]
    south_of_it = measured(graph, {"wardrobe_1": west, "crate_1": (-2.2, 0.9, 0.0)})
    assert south_of_it.parts["clearance"] == 0.0 and south_of_it.ok


def test_a_space_kept_free_against_a_wall_is_charged():
    graph = graph_of(bedroom(), ("wardrobe", dict(WARDROBE, access=())))
    facing_wall = measured(
        graph, {"wardrobe_1": (-1.5, -1.4, 180.0)}
    )  # doors 0.3 m from the north wall
    assert facing_wall.parts["clearance"] > 0.0
    assert facing_wall.problems == ["the space kept free in front of wardrobe_1 runs into the wall"]
    assert measured(graph, {"wardrobe_1": (-1.5, -1.7, 0.0)}).parts["clearance"] == 0.0


# -- door swing ---------------------------------------------------------------------------


def test_the_door_swing_is_kept_free_of_tall_boxes_only():
    graph = graph_of(bedroom(), ("bed", BED), ("rug", dict(RUG, size=(1.0, 0.01, 0.8))))
    blocking = measured(graph, {"bed_1": (1.5, 0.8, 0.0), "rug_1": (-1.0, 0.0, 0.0)})
    assert blocking.parts["door_swing"] > 0.0 and not blocking.ok
    assert "bed_1 stands in the swing of door_1" in blocking.problems
    beside = measured(
        graph, {"bed_1": (0.1, 0.8, 0.0), "rug_1": (1.5, 1.5, 0.0)}
    )  # the rug lies in the swing
    assert beside.parts["door_swing"] == 0.0 and beside.ok, beside.problems


def test_a_door_in_a_rotated_room_swings_into_the_room():
    room = rotated()
    door = room.doors[0]
    wall = room.part(door.wall)
    graph = graph_of(room, ("crate", CRATE))
    x, z = wall.to_world(door.offset, 0.45)
    yaw = math.degrees(wall.facing_yaw)
    assert (
        "crate_1 stands in the swing of door_1"
        in measured(graph, {"crate_1": (x, z, yaw)}).problems
    )
    x, z = wall.to_world(door.offset + 1.2, 0.45)
    assert measured(graph, {"crate_1": (x, z, yaw)}).parts["door_swing"] == 0.0


# -- windows --------------------------------------------------------------------------------


def test_a_tall_box_before_a_window_pays_and_is_a_problem_unless_the_rules_put_it_there():
    # The window (north wall, x -0.7..0.7, sill 0.9): a wardrobe against it hides it, a
    # desk about as high as the sill does not, and beside it the wardrobe hides nothing.
    graph = graph_of(bedroom(), ("wardrobe", WARDROBE), ("desk", DESK))
    before = measured(graph, {"wardrobe_1": (0.0, -1.7, 0.0), "desk_1": (-1.8, -1.7, 0.0)})
    assert before.parts["windows"] > 0.0
    assert before.problems == ["wardrobe_1 stands before window_1"]
    asked = graph_of(bedroom(), ("wardrobe", WARDROBE), ("desk", DESK))
    asked.add_relation("wardrobe_1", "wall_1", "AgainstWall")  # the window's own wall, named
    there = measured(asked, {"wardrobe_1": (0.0, -1.7, 0.0), "desk_1": (-1.8, -1.7, 0.0)})
    assert there.parts["windows"] > 0.0 and there.ok, there.problems
    beside = measured(graph, {"wardrobe_1": (-1.6, -1.7, 0.0), "desk_1": (0.0, -1.7, 0.0)})
    assert beside.parts["windows"] == 0.0
    away = measured(
        graph, {"wardrobe_1": (0.0, -1.0, 0.0), "desk_1": (-1.8, -1.7, 0.0)}
    )  # 0.7 m off the wall
    assert away.parts["windows"] == 0.0


def test_against_some_wall_a_wardrobe_leaves_the_window_free():
    graph = graph_of(bedroom(), ("wardrobe", dict(WARDROBE, size=(2.0, 2.0, 0.6))))
    graph.add_relation("wardrobe_1", "room", "AgainstWall")
    before = 0
    for seed in range(12):
        result = layout_scene(graph, np.random.default_rng(seed))
        assert result.ok
        x, z = result.poses["wardrobe_1"].x, result.poses["wardrobe_1"].z
        before += z < -1.5 and abs(x) < 1.6  # its back to the north wall, across the window
    assert before == 0


# -- access ---------------------------------------------------------------------------------


def sized_barrier(gap: float, thickness: float = 0.5):
    """The barrier graph with sideboards as wide as leaves ``gap`` and ``thickness`` deep."""
    width = 2.5 - gap / 2.0
    sideboard = dict(size=(width, 1.0, thickness), access=())
    graph = graph_of(bedroom(), ("wardrobe", WARDROBE), ("left", sideboard), ("right", sideboard))
    poses = {
        "wardrobe_1": (1.6, -1.7, 0.0),  # clear of the window (x -0.7..0.7)
        "left_1": (-2.5 + width / 2.0, 0.0, 0.0),
        "right_1": (2.5 - width / 2.0, 0.0, 0.0),
    }
    return graph, poses


def test_a_way_narrower_than_a_corridor_leaves_what_is_behind_it_unreachable():
    graph, poses = sized_barrier(0.5)
    result = measured(graph, poses)
    # The wardrobe is out of reach, and the room's far half is cut off from the door.
    assert result.problems[0] == "wardrobe_1 cannot be reached from the door (no 0.6 m wide way)"
    assert len(result.problems) == 2 and "cut off from the rest" in result.problems[1]
    assert result.parts["access"] >= ACCESS_BASE
    graph, poses = sized_barrier(0.8)
    result = measured(graph, poses)
    assert result.parts["access"] == 0.0 and result.ok, result.problems


def test_unreachable_boxes_cost_more_the_farther_they_are_from_the_way_in():
    thin = measured(*sized_barrier(0.0, thickness=0.5)).parts["access"]
    thick = measured(*sized_barrier(0.0, thickness=1.2)).parts["access"]
    assert ACCESS_BASE < thin < thick


def test_an_object_boxed_in_behind_others_is_unreachable():
    dresser = dict(size=(1.0, 1.0, 0.5), access=())
    cabinet = dict(size=(2.5, 1.0, 0.5), access=())
    graph = graph_of(bedroom(), ("wardrobe", WARDROBE), ("dresser", dresser), ("cabinet", cabinet))
    poses = {
        "wardrobe_1": (-1.9, -1.7, 0.0),  # in the north-west corner, doors south
        "dresser_1": (-0.7, -1.75, 0.0),  # beside it against the north wall
        "cabinet_1": (-1.25, -0.9, 0.0),  # 0.25 m in front of both, from the west wall
    }
    result = measured(graph, poses)
    assert "wardrobe_1 cannot be reached from the door (no 0.6 m wide way)" in result.problems
    poses["cabinet_1"] = (-1.25, 1.5, 0.0)  # moved away to the south wall
    opened = measured(graph, poses)
    assert not any("cannot be reached" in p for p in opened.problems), opened.problems


def test_access_sides_count_only_the_sides_named():
    desk = dict(DESK, clearance=())
    graph = graph_of(bedroom(), ("desk", desk))
    facing_wall = measured(
        graph, {"desk_1": (0.0, -1.5, 180.0)}
    )  # its front 0.2 m from the north wall
    assert facing_wall.problems == ["desk_1 cannot be reached from the door (no 0.6 m wide way)"]
    assert measured(graph, {"desk_1": (0.0, -1.7, 0.0)}).ok
    anywhere = graph_of(bedroom(), ("desk", dict(desk, access=("any",))))
    assert measured(anywhere, {"desk_1": (0.0, -1.5, 180.0)}).ok


def test_what_nobody_needs_to_reach_and_rooms_without_doors_cost_nothing():
    closed = graph_of(Room.rectangle(5, 4), ("wardrobe", WARDROBE), ("left", CRATE))
    assert (
        measured(closed, {"wardrobe_1": (0.0, -1.7, 0.0), "left_1": (0.0, -1.0, 0.0)}).parts[
            "access"
        ]
        == 0.0
    )
    crate = graph_of(bedroom(), ("crate", CRATE), ("left", dict(size=(5.0, 1.0, 0.5), access=())))
    walled_off = measured(crate, {"crate_1": (0.0, -1.5, 0.0), "left_1": (0.0, 0.0, 0.0)})
    assert walled_off.parts["access"] == 0.0
    # The crate needs no reaching, but the north half of the room, cut off from the door,
    # is floor lost to whoever comes in (SceneEval's navigability): the verdict says so.
    assert not any("cannot be reached" in p for p in walled_off.problems)
    assert len(walled_off.problems) == 1 and "cut off from the rest" in walled_off.problems[0]
    along = measured(crate, {"crate_1": (-2.25, 1.75, 0.0), "left_1": (0.0, -1.75, 0.0)})
    assert not any("cut off" in p for p in along.problems), along.problems


def test_a_blocked_door_leaves_everything_unreachable():
    graph = graph_of(
        bedroom(), ("wardrobe", WARDROBE), ("crate", dict(size=(1.6, 1.0, 1.0), access=()))
    )
    result = measured(graph, {"wardrobe_1": (-1.5, -1.7, 0.0), "crate_1": (1.5, 1.5, 0.0)})
    assert "crate_1 stands in the swing of door_1" in result.problems
    assert "wardrobe_1 cannot be reached from the door (no 0.6 m wide way)" in result.problems


def test_reachability_in_an_l_shaped_room_goes_round_the_corner():
    graph = graph_of(
        l_shaped(), ("wardrobe", WARDROBE), ("crate", dict(size=(3.0, 1.0, 0.5), access=()))
    )
    # The wardrobe in the far leg (south-west), facing north; the door is in the north wall.
    open_way = measured(graph, {"wardrobe_1": (-1.5, 2.2, 180.0), "crate_1": (1.5, -1.0, 0.0)})
    assert open_way.parts["access"] == 0.0, open_way.problems
    # The crate across the leg's mouth (x -3..0 at z 0.5) closes the only way.
    closed = measured(graph, {"wardrobe_1": (-1.5, 2.2, 180.0), "crate_1": (-1.5, 0.6, 0.0)})
    assert "wardrobe_1 cannot be reached from the door (no 0.6 m wide way)" in closed.problems


# -- the reachability grid -------------------------------------------------------------------


def brute_cells(grid: AccessGrid, rect: Rect, inside) -> int:
    """The plane of the cells whose centres pass ``inside(lx, lz)`` (metres, in the
    footprint's frame, its centre on the raster's 1/QUANTUM of a cell), by brute force."""
    step = grid.cell / QUANTUM
    cx = grid.x0 + round((rect.cx - grid.x0) / step) * step
    cz = grid.z0 + round((rect.cz - grid.z0) / step) * step
    gx, gz = np.meshgrid(grid.xc, grid.zc)
    c, s = round(rect.c), round(rect.s)
    lx, lz = (gx - cx) * c - (gz - cz) * s, (gx - cx) * s + (gz - cz) * c
    mask = inside(lx, lz)
    mask[:, 0] = False  # the padding column a raster may not reach (it may reach the others)
    return grid.plane(mask)


@settings(max_examples=40, deadline=None)
@given(
    x=st.floats(-2.2, 2.2),
    z=st.floats(-1.7, 1.7),
    width=st.floats(0.2, 2.0),
    depth=st.floats(0.2, 1.5),
    turn=st.integers(0, 3),
    side=st.sampled_from(["front", "back", "left", "right"]),
)
@example(
    x=0.0, z=0.28125, width=1.0, depth=0.95, turn=0, side="front"
)  # cell centres on the boundaries
@example(x=0.0, z=0.375, width=1.0, depth=0.75, turn=0, side="front")
@example(x=0.0, z=0.0, width=1.0, depth=1.5, turn=0, side="front")
def test_rasters_cover_the_cells_near_the_footprint(x, z, width, depth, turn, side):
    grid = AccessGrid(bedroom())
    rect = make_rect(x, z, width, depth, turn * math.pi / 2.0)
    hw, hd = width / 2.0, depth / 2.0
    near = CORRIDOR_HALF + grid.cell

    def within(r, strict):
        def inside(lx, lz):
            d2 = np.maximum(np.abs(lx) - hw, 0.0) ** 2 + np.maximum(np.abs(lz) - hd, 0.0) ** 2
            return d2 < r * r if strict else d2 <= r * r

        return inside

    def band(slack):
        def inside(lx, lz):
            if side in ("front", "back"):
                return (np.abs(lx) <= hw + slack) & (
                    np.abs(lz - (hd if side == "front" else -hd)) <= near + slack
                )
            return (np.abs(lz) <= hd + slack) & (
                np.abs(lx - (hw if side == "left" else -hw)) <= near + slack
            )

        return inside

    # A cell centre exactly on a boundary (x = 0, width 1 on a 0.1 m grid) may fall
    # either way by rounding: the raster must hold every cell inside by a hair and no
    # cell outside by a hair.
    hair = 1e-9
    on_grid = grid.window_plane((0, grid.shape[0], 1, grid.stride))

    def between(raster, inner, outer):
        bits = raster.bits & on_grid
        assert bits & inner == inner and bits & ~outer == 0

    between(
        grid.obstacle(rect),
        brute_cells(grid, rect, within(CORRIDOR_HALF - hair, True)),
        brute_cells(grid, rect, within(CORRIDOR_HALF + hair, True)),
    )
    between(
        grid.access(rect, ("any",)),
        brute_cells(grid, rect, within(near - hair, False)),
        brute_cells(grid, rect, within(near + hair, False)),
    )
    between(
        grid.access(rect, (side,)),
        brute_cells(grid, rect, band(-hair)),
        brute_cells(grid, rect, band(hair)),
    )


@settings(max_examples=30, deadline=None)
@given(seed=st.integers(0, 10_000))
def test_growing_from_the_doors_finds_what_labelling_finds(seed):
    rng = np.random.default_rng(seed)
    grid = AccessGrid(bedroom())
    taken = 0
    for _ in range(int(rng.integers(1, 12))):
        rect = make_rect(
            rng.uniform(-2.5, 2.5),
            rng.uniform(-2, 2),
            rng.uniform(0.2, 2.0),
            rng.uniform(0.2, 1.5),
            rng.choice([0.0, math.pi / 2, rng.uniform(-3, 3)]),
        )
        taken |= grid.obstacle(rect).bits
    free = grid.static & ~taken
    assert grid.flood(grid.seeds & free, free) == grid.label(free)


@settings(max_examples=40, deadline=None)
@given(seed=st.integers(0, 10_000))
def test_a_window_whose_ring_is_one_arc_cuts_no_way(seed):
    """The incremental proof: taking such a window out of the reachable floor leaves
    every remaining cell connected to a door within what remains."""
    rng = np.random.default_rng(seed)
    grid = AccessGrid(l_shaped())
    taken = 0
    for _ in range(int(rng.integers(2, 10))):  # (some near the door, whose cells a window may hold)
        rect = make_rect(
            rng.uniform(-3, 3),
            rng.uniform(-2.5, 2.5),
            rng.uniform(0.2, 1.5),
            rng.uniform(0.2, 1.5),
            0.0,
        )
        taken |= grid.obstacle(rect).bits
    free = grid.static & ~taken
    reach = grid.label(free)
    for _ in range(10):
        rect = make_rect(
            rng.uniform(-3, 3),
            rng.uniform(-2.5, 2.5),
            rng.uniform(0.2, 1.5),
            rng.uniform(0.2, 1.5),
            0.0,
        )
        window = grid.window(rect, CORRIDOR_HALF)
        if window[0] == window[1] or window[2] == window[3]:
            continue
        left = reach & ~grid.window_plane(window)
        if grid.ring_single(reach, window) and grid.keeps_a_door(reach, window):
            assert grid.flood(grid.seeds & left, left) == left


# -- the incremental energy ------------------------------------------------------------------


def random_room_scene(seed: int) -> SceneGraph:
    """A small furnished room of a random shape, with clearances, access sides and a few
    wall and next-to relations."""
    rng = np.random.default_rng(seed)
    room = [bedroom, l_shaped, rotated][seed % 3]()
    kinds = [
        ("wardrobe", WARDROBE),
        ("desk", DESK),
        ("bed", BED),
        ("crate", CRATE),
        ("chair", CHAIR),
        ("rug", RUG),
    ]
    graph = graph_of(room)
    ids = []
    for _ in range(int(rng.integers(4, 8))):
        name, fields = kinds[int(rng.integers(len(kinds)))]
        ids.append(graph.add_node(CatalogEntry(name, "object", name, **fields)))
    for node in ids[:2]:
        graph.add_relation(node, "room", "AgainstWall")
    graph.add_relation(ids[2], ids[0], "NextToChooseSide")
    return graph


def check_moves(
    energy: Energy, mover, rng: np.random.Generator, moves: int, relocator=None, parts=ROOM_PARTS
) -> None:
    """Random moves, each delta against full recomputation (in all and for each of ``parts``)."""
    for _ in range(moves):
        if relocator is not None and rng.random() < 0.3:
            proposal = relocator.propose(list(range(energy.problem.n_boxes)))
        else:
            proposal = mover.propose(energy.relation)
        if proposal is None:
            continue
        before = energy.full()
        delta = energy.propose(*proposal)
        after = energy.full()
        assert delta == pytest.approx(sum(after.values()) - sum(before.values()), abs=1e-9)
        for part in parts:  # the parts' own deltas, one by one
            change = energy._pending.update.delta[part]
            assert change == pytest.approx(after[part] - before[part], abs=1e-9), part
        if rng.random() < 0.5:
            energy.accept()
        else:
            energy.reject()
        assert_cached_parts_true(energy)


@settings(max_examples=9, deadline=None)
@given(seed=st.integers(0, 10_000))
def test_incremental_room_terms_equal_full_recomputation_on_random_moves(seed):
    problem = compile_problem(random_room_scene(seed))
    rng = np.random.default_rng(seed)
    energy, mover = start_chain(problem, LayoutParams(), rng)
    assert_cached_parts_true(energy)
    check_moves(energy, mover, rng, 30, Relocator(problem, energy.state, mover))


@settings(max_examples=6, deadline=None)
@given(seed=st.integers(0, 10_000))
def test_incremental_room_terms_with_two_doors_and_a_chair_on_a_rug_equal_full(seed):
    # The second door is reached from the first like a box; the chair on the rug is an
    # obstacle that moves whenever the rug does.
    room = bedroom().with_opening("door", "west", 2.0, 0.9)
    graph = graph_of(
        room, ("wardrobe", WARDROBE), ("bed", BED), ("crate", CRATE), ("rug", RUG), ("chair", CHAIR)
    )
    graph.add_relation("chair_1", "rug_1", "OnTopOf")
    graph.add_relation("wardrobe_1", "room", "AgainstWall")
    problem = compile_problem(graph)
    rng = np.random.default_rng(seed)
    energy, mover = start_chain(problem, LayoutParams(), rng)
    assert energy.room.far_doors == [1] and energy.room.obstacle[problem.ids.index("chair_1")]
    assert_cached_parts_true(energy)
    check_moves(energy, mover, rng, 30, Relocator(problem, energy.state, mover))


def test_the_reachable_floor_after_every_move_of_a_classroom_is_the_labelled_one():
    """The incremental reachable floor (kept from the last one, windows taken out, or
    left whole where the moved boxes land on none of it) is, cell for cell, the free
    floor connected to the door, on a classroom's rows of desks and chairs."""
    graph = expand(load_rules("classroom"), 3)
    problem = compile_problem(graph)
    rng = np.random.default_rng(3)
    energy, mover = start_chain(problem, LayoutParams(), rng)
    room, grid = energy.room, energy.room.access_grid
    kept = 0
    for _ in range(120):
        proposal = mover.propose(energy.relation)
        if proposal is None:
            continue
        energy.propose(*proposal)
        access = energy._pending.update.room.access
        if access is not None:
            taken = [access.taken.get(box, bits) for box, bits in enumerate(room.taken)]
            used = 0
            for bits in taken:
                used |= bits
            assert access.state.reach == grid.label(grid.static & ~used)
            kept += access.state.reach == room.access.reach
        if rng.random() < 0.5:
            energy.accept()
        else:
            energy.reject()
    assert kept  # some moves left the reachable floor as it was


def test_incremental_energy_of_a_classroom_equals_full_recomputation():
    """Rows of desks facing the board and chairs facing their desks (facing relations
    that read headings only), moved at random."""
    problem = compile_problem(expand(load_rules("classroom"), 5))
    assert any(t.spec.family == "facing" and t.spec.facing == "opposite" for t in problem.relations)
    rng = np.random.default_rng(5)
    energy, mover = start_chain(problem, LayoutParams(), rng)
    check_moves(energy, mover, rng, 40, parts=("relations",) + ROOM_PARTS)


def test_deferred_access_gives_the_same_delta_and_the_same_decisions():
    """A proposal with its access part deferred: the rest minus ``access_floor`` never
    exceeds the whole change, ``complete`` gives exactly the change ``propose`` gives
    without deferring, and ``metropolis`` decides as the plain rule on the same draws."""
    problem = compile_problem(expand(load_rules("classroom"), 3))
    rng = np.random.default_rng(3)
    energy, mover = start_chain(problem, LayoutParams(), rng)
    assert energy.parts["access"] > 0.0  # chairs out of reach: moves can lower the access part
    skipped = lowered = 0
    for step in range(150):
        proposal = mover.propose(energy.relation)
        if proposal is None:
            continue
        plain = energy.propose(*proposal)
        energy.reject()
        partial = energy.propose(*proposal, defer_access=True)
        assert partial - energy.access_floor() <= plain + 1e-12
        assert energy.complete() == plain
        lowered += energy._pending.update.delta["access"] < 0.0
        energy.reject()
        temperature = 0.05 * 0.99**step
        seed = int(rng.integers(1 << 30))
        plain_draws = np.random.default_rng(seed).random
        expected = energy.propose(*proposal)
        expected = expected <= 0.0 or plain_draws() < math.exp(-expected / temperature)
        energy.reject()
        calls = []
        original = energy.room._access_changes
        energy.room._access_changes = lambda boxes, calls=calls, original=original: (
            calls.append(boxes) or original(boxes)
        )
        decided = metropolis(
            energy, proposal, temperature, np.random.default_rng(seed).random, True
        )
        energy.room._access_changes = original
        skipped += not calls and any(problem.height[b] > 0.05 for b in proposal[0])
        assert decided == expected
        if decided:
            energy.accept()
        else:
            energy.reject()
        assert_cached_parts_true(energy)
    assert skipped and lowered  # some steps decided without reachability, some made a box reachable


def test_full_recomputation_mode_gives_the_same_room_deltas():
    problem = compile_problem(random_room_scene(4))
    incremental, mover = start_chain(problem, LayoutParams(), np.random.default_rng(4))
    naive, _ = start_chain(problem, LayoutParams(incremental=False), np.random.default_rng(4))
    for _ in range(25):
        proposal = mover.propose(incremental.relation)
        if proposal is None:
            continue
        assert incremental.propose(*proposal) == pytest.approx(naive.propose(*proposal), abs=1e-9)
        incremental.accept()
        naive.accept()
    for part in ROOM_PARTS:
        assert incremental.parts[part] == pytest.approx(naive.parts[part], abs=1e-9)
    assert incremental.troubled_boxes() == naive.troubled_boxes()


def test_troubled_boxes_include_those_breaking_room_terms():
    graph = graph_of(bedroom(), ("wardrobe", WARDROBE), ("chair", CHAIR), ("bed", BED))
    energy = energy_at(
        graph,
        {"wardrobe_1": (-1.5, -1.7, 0.0), "chair_1": (-1.5, -1.0, 0.0), "bed_1": (1.5, 0.8, 0.0)},
    )
    assert energy.troubled_boxes() == [
        0,
        1,
        2,
    ]  # the wardrobe owns the space the chair takes; the bed blocks the door
    graph, poses = sized_barrier(0.5)
    energy = energy_at(graph, poses)
    assert energy.troubled_boxes() == [0, 1, 2]  # out of reach, and the two hemming it in


# -- laying out, measuring, and outdoors -----------------------------------------------------------


def test_a_laid_out_room_keeps_its_door_and_spaces_free_and_measures_the_same():
    graph = graph_of(
        bedroom(), ("wardrobe", WARDROBE), ("desk", DESK), ("chair", CHAIR), ("bed", BED)
    )
    graph.add_relation("wardrobe_1", "room", "AgainstWall")
    graph.add_relation("desk_1", "room", "UnderWindow")
    graph.add_relation("chair_1", "desk_1", "NextToFront")
    graph.add_relation("bed_1", "room", "AgainstWall")
    result = layout_scene(graph, 1)
    assert result.ok, result.problems
    assert all(result.parts[part] < 0.5 for part in ("walls", "clearance", "door_swing", "access"))
    again = measure_layout(graph, result.poses, {})
    assert (
        again.ok and again.problems == [] and again.parts == pytest.approx(result.parts, abs=1e-9)
    )


def test_a_bed_whose_free_side_is_taken_moves_with_what_stands_by_it():
    graph = graph_of(
        bedroom(),
        ("bed", dict(BED, clearance=(("left", 0.5),))),
        ("nightstand", CRATE),
        ("rug", RUG),
    )
    graph.add_relation("bed_1", "room", "InCorner")
    graph.add_relation("nightstand_1", "bed_1", "NextToRight")
    graph.add_relation("rug_1", "bed_1", "NextToFront")
    problem = compile_problem(graph)
    energy, mover = start_chain(problem, LayoutParams(), np.random.default_rng(0))
    relocator = Relocator(problem, energy.state, mover)
    assert relocator.satellites[0] == [1, 2] and relocator.satellites[1] == []

    def in_bed_frame(poses: dict, box: int) -> tuple[float, float, float]:
        (bx, bz, byaw), (x, z, yaw) = poses[0], poses[box]
        c, s = math.cos(byaw), math.sin(byaw)
        return (x - bx) * c - (z - bz) * s, (x - bx) * s + (z - bz) * c, math.cos(yaw - byaw)

    before = {box: energy.state.pose(box) for box in range(3)}
    for _ in range(5):
        boxes, paths = relocator.propose([0])
        assert set(boxes) == {0, 1, 2} and paths == {}
        for satellite in (1, 2):  # where it was relative to the bed
            assert in_bed_frame(boxes, satellite) == pytest.approx(
                in_bed_frame(before, satellite), abs=1e-9
            )


def test_outdoors_the_room_parts_are_zero_and_build_nothing():
    graph = village_graph(12, 3)
    problem = compile_problem(graph)
    energy, _ = start_chain(problem, LayoutParams(), np.random.default_rng(3))
    assert energy.room is None
    assert all(energy.full()[part] == 0.0 for part in ROOM_PARTS)
    result = layout_scene(graph, 3, params=LayoutParams(restarts=0))
    assert all(result.parts[part] == 0.0 for part in ROOM_PARTS)
    assert result.energy == pytest.approx(
        sum(v for k, v in result.parts.items() if k not in ROOM_PARTS), abs=0.0
    )
