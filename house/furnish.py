"""Furnishing a house: each room laid out on its own by its room type's rule set.

Once the plan is fixed the rooms do not interact (a wall stands between any two), so
each is expanded and laid out alone, as a room scene of its rule set would be, with the
room's own walls, doors and windows in place of the rule set's room. Room k draws from
its own stream (child k of the scene's ``room`` stream), so a room's furniture depends
on nothing but the seed and its place in the plan, and the rooms may be laid out in
any order or in parallel (``workers``) with the same result.

A room is tried up to ``ROOM_TRIES`` times (a fresh layout seed each time, as a
dataset's retry does, and a fresh expansion every ``LAYOUTS_PER_GRAPH`` tries, since
the first one may hold more than the room takes) until its layout is ok and a person
can walk between all its doors (``door_paths``); the best try is kept otherwise and
its problems say why.
"""

from __future__ import annotations

import math
from concurrent.futures import ProcessPoolExecutor
from dataclasses import replace

import numpy as np
from scipy import ndimage

from scenewright.core.geometry import points_in_polygon, points_segments_distance
from scenewright.core.house import House, HouseRoom
from scenewright.core.scene import Scene, assemble_scene
from scenewright.core.seeds import MAX_SEED, retry_seed, stream
from scenewright.generator import expand, load_rules
from scenewright.generator.layout import layout_scene
from scenewright.generator.layout.params import LayoutParams
from scenewright.generator.rules import Rules

#: Layouts tried per room before its best is kept, and how many of them lay out one
#: expansion before the room's rule set is expanded again (retry streams from REEXPAND on).
ROOM_TRIES = 12
LAYOUTS_PER_GRAPH = 1
REEXPAND = 100
#: One try's layout: fewer restarts than a room scene's own (a try that fails costs
#: less; the next try's fresh expansion does more for a room that is hard to furnish).
ROOM_LAYOUT = LayoutParams(restarts=1)
#: Half the narrowest way a person walks between a room's doors (m), the grid it is found on,
#: and the height below which a thing is stepped over (a rug).
WAY_HALF = 0.3
WAY_CELL = 0.1
STEP_OVER = 0.05


def room_seed(seed: int, index: int) -> int:
    """The seed room ``index`` of the house with ``seed`` is furnished with."""
    return int(stream(seed, "room", index).integers(0, MAX_SEED))


def furnish(house: House, seed: int, *, workers: int = 1) -> list[Scene]:
    """One laid-out room scene per room of ``house``, in the house's room order."""
    jobs = [(room, room_seed(seed, k)) for k, room in enumerate(house.rooms)]
    if workers > 1 and len(jobs) > 1:
        with ProcessPoolExecutor(max_workers=min(workers, len(jobs))) as pool:
            return list(pool.map(_furnish_job, jobs))
    loaded: dict[str, Rules] = {}  # rooms of one type share their rule set, read once
    scenes = []
    for room, room_seed_ in jobs:
        if room.rules not in loaded:
            loaded[room.rules] = load_rules(room.rules)
        scenes.append(furnish_room(room, room_seed_, loaded[room.rules]))
    return scenes


def _furnish_job(job: tuple[HouseRoom, int]) -> Scene:
    return furnish_room(*job)


def furnish_room(room: HouseRoom, seed: int, rules: Rules | None = None) -> Scene:
    """The room laid out with its rule set (``rules``, read from ``room.rules`` when not
    given): the first of ``ROOM_TRIES`` tries that is ok with every door reachable from
    every other, or else the try with the fewest problems."""
    if rules is None:
        rules = load_rules(room.rules)
    rules = replace(
        rules,
        params=replace(rules.params, room=room.room, extent=room.room.extent, name=room.type),
    )
    best: Scene | None = None
    for attempt in range(ROOM_TRIES):
        if attempt % LAYOUTS_PER_GRAPH == 0:
            # after a graph's layouts fail, a fresh expansion: it may ask less of the room
            graph = expand(rules, retry_seed(seed, REEXPAND + attempt) if attempt else seed)
        layout = layout_scene(graph, retry_seed(seed, attempt), params=ROOM_LAYOUT)
        scene = assemble_scene(graph, layout, rules=room.rules, seed=seed)
        blocked = door_paths(scene)
        if blocked:
            scene.layout.ok = False
            scene.layout.problems = [*scene.layout.problems, blocked]
        if scene.layout.ok:
            return scene
        if best is None or len(scene.layout.problems) < len(best.layout.problems):
            best = scene
    assert best is not None
    return best


def door_paths(scene: Scene) -> str | None:
    """Why a person cannot walk between every two doors of the scene's room (a way at least
    ``2 * WAY_HALF`` wide around the furniture), or None when they can."""
    room = scene.room
    assert room is not None
    doors = room.doors
    if not doors:
        return None
    xs = [p[0] for p in room.corners]
    zs = [p[1] for p in room.corners]
    gx, gz = np.meshgrid(
        np.arange(min(xs) + WAY_CELL / 2, max(xs), WAY_CELL),
        np.arange(min(zs) + WAY_CELL / 2, max(zs), WAY_CELL),
    )
    free = points_in_polygon(room.corners, gx, gz)
    free &= (
        points_segments_distance(gx, gz, [(w.start, w.end) for w in room.walls]) >= WAY_HALF - 1e-9
    )
    for obj in scene.placed_objects():
        if obj.position[1] > 0.01 or obj.size[1] < STEP_OVER:
            continue  # on something else, or flat enough to walk over
        c, s = math.cos(obj.yaw), math.sin(obj.yaw)
        dx, dz = gx - obj.position[0], gz - obj.position[2]
        local_x = dx * c - dz * s
        local_z = dx * s + dz * c
        free &= ~(
            (np.abs(local_x) < obj.size[0] / 2 + WAY_HALF)
            & (np.abs(local_z) < obj.size[2] / 2 + WAY_HALF)
        )
    labels, _count = ndimage.label(free)
    reached: list[set[int]] = []
    for door in doors:
        (ax, az), (bx, bz) = room.opening_ends(door)
        near = points_segments_distance(gx, gz, [((ax, az), (bx, bz))]) <= WAY_HALF + 2 * WAY_CELL
        found = set(np.unique(labels[near & free]).tolist()) - {0}
        if not found:
            return f"{door.id}: no free way leads from it into the room"
        reached.append(found)
    common = set.intersection(*reached)
    if not common:
        return "its doors are not joined by a free way 0.6 m wide"
    return None
