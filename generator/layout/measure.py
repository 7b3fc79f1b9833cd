"""Measure a layout that is already there (an imported scene) without sampling.

``measure_layout(graph, poses, paths)`` puts every object and junction at its given pose
and every path at its given points, and returns the ``LayoutResult`` the sampler would
report for that state: each relation with its value, verdict and chosen direction, the
problems (in a room its own too: a box across a wall, in a door's swing, in a space kept
free, out of reach), ``ok``, the energy and its parts, and ``steps`` 0. The poses are
used as given, y included (heights are not recomputed from the supports), so a scene
built by ``layout_scene`` measures to the verdicts its layout reported.
"""

from __future__ import annotations

import time
from collections.abc import Mapping, Sequence

import numpy as np

from scenewright.core.errors import InputError
from scenewright.core.poses import LayoutResult, Pose
from scenewright.core.scene_graph import SceneGraph

from .energy import Energy
from .mask_term import FloorMask, compile_mask
from .params import LayoutParams
from .pinning import check_points, check_pose
from .problem import compile_problem
from .report import assess
from .state import State


def measure_layout(
    graph: SceneGraph,
    poses: Mapping[str, Pose],
    paths: Mapping[str, object],
    params: LayoutParams | None = None,
    mask: FloorMask | Sequence[FloorMask] | None = None,
) -> LayoutResult:
    """The verdict on ``graph`` laid out at ``poses`` (id -> Pose for every object and
    junction) and ``paths`` (id -> [[x, z], ...] for every path); nothing is moved.

    Poses given for groups are ignored (a group's place is its members'). A missing
    object, junction or path, an id that is not in the graph, or a malformed pose or
    point list is an ``InputError``. ``mask`` (``mask_term.FloorMask`` or several) adds the
    energy's ``mask`` part, as ``layout_scene`` does; the verdict does not read it.
    """
    params = params or LayoutParams()
    started = time.perf_counter()
    problem = compile_problem(graph)
    if mask is not None:
        problem.mask = compile_mask(mask, problem.ids)
    groups = set(problem.group_ids)
    box_ids, path_ids = set(problem.ids), set(problem.path_ids)
    for entry_id in poses:
        if entry_id not in box_ids and entry_id not in groups:
            what = (
                "a path (give its points in paths)"
                if entry_id in path_ids
                else "not in the scene graph"
            )
            raise InputError(f"poses: {entry_id!r} is {what}")
    for entry_id in paths:
        if entry_id not in path_ids:
            raise InputError(f"paths: {entry_id!r} is not a path of the scene graph")
    missing = [box_id for box_id in problem.ids if box_id not in poses]
    missing += [path_id for path_id in problem.path_ids if path_id not in paths]
    if missing:
        raise InputError(f"no pose or points given for {', '.join(missing)}")

    state = State(problem)
    for box, box_id in enumerate(problem.ids):
        pose = check_pose("poses", box_id, poses[box_id])
        state.set_pose(box, pose.x, pose.z, pose.yaw)
        state.y[box] = pose.y
    for path, path_id in enumerate(problem.path_ids):
        state.points[path] = check_points("paths", path_id, paths[path_id], None)
    energy = Energy(problem, state, params)
    energy.activate(list(range(problem.n_boxes)))
    relations, problems = assess(energy)
    parts = energy.full()
    return LayoutResult(
        poses={
            box_id: Pose(state.x[b], state.y[b], state.z[b], state.yaw[b])
            for b, box_id in enumerate(problem.ids)
        },
        paths={
            path_id: np.array(state.points[p], dtype=float)
            for p, path_id in enumerate(problem.path_ids)
        },
        relations=relations,
        energy=float(sum(parts.values())),
        parts=parts,
        steps=0,
        acceptance=0.0,
        seconds=time.perf_counter() - started,
        ok=not problems,
        problems=list(problems),
    )
