"""Pinned and warm-started layouts: which boxes and paths stay put, and where chains start.

``layout_scene(..., pinned=, pinned_paths=, start=)`` hands its arguments to
``compile_pins``, which checks them against the compiled problem and returns ``Pins``:
per box and per path a flag the mover reads in O(1), and the poses and points the
initial placement puts first.

Rules (also in docs/layout.md):

- A pinned object or junction keeps its pose bit for bit (x, y, z and yaw as given).
  No move proposes it. Whatever rests on it and is not pinned itself may still move on
  its top (it is *anchored*).
- A pinned object cannot stay put on a support that moves, so the supports beneath a
  pinned object must be pinned too (``InputError`` otherwise). A pinned path keeps every
  control point; a pinned path that starts at a junction needs that junction pinned too,
  at its first point. A free path whose junction is pinned keeps starting there.
- Rigid moves of several boxes (a group, a cluster of related items) carry only the free
  boxes: pinned boxes and what rests on them stay behind. Moves that place or turn a
  group as a whole (data-driven) are refused for a group that holds a pinned or anchored
  box; its free members still move on their own. A junction with a pinned path never
  moves (it is pinned). Free roads and junctions are brought to the pinned things that
  must be next to them (the initial placement's candidate fans, and ``Placer.pull``).
- ``start`` gives poses (and path points) every chain starts from instead of the
  constructive placement; those boxes may move. Boxes and paths ``start`` leaves out are
  placed constructively around the given ones. A start pose's y is not used: heights
  follow the supports. A started path that starts at a junction begins at the
  junction's position (a junction with no pose of its own goes to the path's first
  point). An id both pinned and started is pinned.
- An id that is not an object, junction or path of the graph, a group id, a pose that is
  not a finite ``Pose`` or points of the wrong shape are a one-line ``InputError``.

``scene_layout(scene)`` and ``pins_from_scene(scene, problem, ids)`` read the same
from a laid-out ``Scene`` (the ``scenewright layout`` command): a group pins all its
members, a path its junction, an object the objects beneath it.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from difflib import get_close_matches

import numpy as np

from scenewright.core.errors import InputError
from scenewright.core.poses import Pose

from .problem import Problem

#: How far (metres) a pinned path's first point may be from its pinned junction.
JUNCTION_TOLERANCE = 1e-3


@dataclass
class Pins:
    """What stays put and where chains start, by box and path index."""

    box: list[bool]  # pinned: never moved
    anchored: list[bool]  # not pinned, but resting (perhaps through others) on a pinned box
    path: list[bool]  # pinned path: no control point moves
    poses: dict[int, Pose] = field(default_factory=dict)  # pinned boxes
    points: dict[int, list[list[float]]] = field(default_factory=dict)  # pinned paths
    start_poses: dict[int, Pose] = field(default_factory=dict)  # warm-started boxes (not pinned)
    start_points: dict[int, list[list[float]]] = field(default_factory=dict)  # warm-started paths

    @classmethod
    def none(cls, problem: Problem) -> Pins:
        return cls([False] * problem.n_boxes, [False] * problem.n_boxes, [False] * problem.n_paths)

    @property
    def preset(self) -> bool:
        """Whether anything is pinned or started (else the layout is the plain one)."""
        return bool(self.poses or self.points or self.start_poses or self.start_points)

    def fixed(self, box: int) -> bool:
        """Pinned, or resting on a pinned box: rigid multi-box moves leave it behind."""
        return self.box[box] or self.anchored[box]

    def preset_boxes(self) -> dict[int, Pose]:
        """Boxes placed before the constructive placement: pinned, then started."""
        return {**self.start_poses, **self.poses}

    def set_heights(self, problem: Problem, state) -> None:
        """Pinned boxes at their own y; what rests on them on top of them (``State.y``)."""
        if not self.poses:
            return
        for box in range(problem.n_boxes):
            if self.box[box]:
                state.y[box] = self.poses[box].y
            elif self.anchored[box]:
                y = 0.0
                for below in problem.beneath(box):
                    if self.box[below]:
                        y += self.poses[below].y + problem.height[below]
                        break
                    y += problem.height[below]
                state.y[box] = y

    def preset_points(self, path: int) -> list[list[float]] | None:
        if path in self.points:
            return self.points[path]
        return self.start_points.get(path)


def compile_pins(
    problem: Problem,
    pinned: Mapping[str, Pose] | None = None,
    pinned_paths: Mapping[str, object] | None = None,
    start: Mapping[str, object] | None = None,
) -> Pins:
    """Check ``pinned``, ``pinned_paths`` and ``start`` against the problem; ``InputError`` if wrong."""
    pins = Pins.none(problem)
    box_index = {box_id: box for box, box_id in enumerate(problem.ids)}
    path_index = {path_id: path for path, path_id in enumerate(problem.path_ids)}
    for box_id, pose in (pinned or {}).items():
        if box_id not in box_index:
            _refuse(problem, "pinned", box_id, box_index)
        pins.poses[box_index[box_id]] = check_pose("pinned", box_id, pose)
    for path_id, points in (pinned_paths or {}).items():
        if path_id not in path_index:
            _refuse(problem, "pinned_paths", path_id, path_index)
        path = path_index[path_id]
        pins.points[path] = check_points(
            "pinned_paths", path_id, points, problem.path_segments[path] + 1
        )
    for entry_id, value in (start or {}).items():
        if entry_id in box_index:
            box = box_index[entry_id]
            pose = check_pose("start", entry_id, value)
            if box not in pins.poses:
                pins.start_poses[box] = pose
        elif entry_id in path_index:
            path = path_index[entry_id]
            points = check_points("start", entry_id, value, problem.path_segments[path] + 1)
            if path not in pins.points:
                pins.start_points[path] = points
        else:
            _refuse(problem, "start", entry_id, [*box_index, *path_index])

    for box in pins.poses:
        pins.box[box] = True
    for box in pins.poses:
        for below in problem.beneath(box):
            if not pins.box[below]:
                raise InputError(
                    f"pinned: {problem.ids[box]} rests on {problem.ids[below]}, which is not pinned; "
                    f"pin {problem.ids[below]} too (a pinned object cannot stay put on a support that moves)"
                )
    for path in pins.points:
        pins.path[path] = True
    for path, points in pins.points.items():
        parent = problem.path_parent[path]
        if parent >= 0 and not pins.path[parent]:
            raise InputError(
                f"pinned_paths: {problem.path_ids[path]} branches from {problem.path_ids[parent]}, "
                f"which is not pinned; pin {problem.path_ids[parent]} too"
            )
        junction = problem.path_start[path]
        if junction < 0:
            continue
        if junction not in pins.poses:
            raise InputError(
                f"pinned_paths: {problem.path_ids[path]} starts at {problem.ids[junction]}, which is not pinned; "
                f"pin {problem.ids[junction]} too"
            )
        pose = pins.poses[junction]
        if math.hypot(points[0][0] - pose.x, points[0][1] - pose.z) > JUNCTION_TOLERANCE:
            raise InputError(
                f"pinned_paths: {problem.path_ids[path]} starts at ({points[0][0]:g}, {points[0][1]:g}) but "
                f"{problem.ids[junction]} is pinned at ({pose.x:g}, {pose.z:g})"
            )
    for box in range(problem.n_boxes):
        pins.anchored[box] = not pins.box[box] and any(
            pins.box[below] for below in problem.beneath(box)
        )
    return pins


def _refuse(problem: Problem, what: str, entry_id: object, known: Iterable[str]) -> None:
    """Raise the one-line ``InputError`` for an id ``what`` cannot take."""
    if what == "pinned" and entry_id in problem.path_ids:
        raise InputError(f"pinned: {entry_id} is a path; give its control points in pinned_paths")
    if what == "pinned_paths" and entry_id in problem.ids:
        raise InputError(f"pinned_paths: {entry_id} is not a path; give its Pose in pinned")
    if entry_id in problem.group_ids:
        members = problem.group_members[problem.group_ids.index(entry_id)]
        listed = ", ".join(problem.ids[b] for b in members) or "it has none"
        raise InputError(f"{what}: {entry_id} is a group; give its members instead ({listed})")
    close = get_close_matches(str(entry_id), list(known), n=1)
    hint = f"; did you mean {close[0]!r}?" if close else ""
    raise InputError(f"{what}: unknown id {entry_id!r} (no such node in the scene graph){hint}")


def check_pose(what: str, entry_id: str, pose: object) -> Pose:
    if not isinstance(pose, Pose):
        raise InputError(f"{what}: {entry_id}: expected a Pose, got {type(pose).__name__}")
    values = (pose.x, pose.y, pose.z, pose.yaw)
    if not all(
        isinstance(v, (int, float, np.floating, np.integer)) and math.isfinite(v) for v in values
    ):
        raise InputError(f"{what}: {entry_id}: the pose must be finite numbers, got {pose}")
    return pose


def check_points(what: str, path_id: str, points: object, count: int | None) -> list[list[float]]:
    """Control points as a list of [x, z] floats (the values given, unchanged)."""
    try:
        array = np.asarray(points, dtype=float)
    except (TypeError, ValueError):
        raise InputError(f"{what}: {path_id}: expected control points [[x, z], ...]") from None
    if array.ndim != 2 or array.shape[1] != 2 or len(array) < 2:
        raise InputError(
            f"{what}: {path_id}: expected control points [[x, z], ...], got shape {array.shape}"
        )
    if count is not None and len(array) != count:
        raise InputError(
            f"{what}: {path_id}: expected {count} control points (its segments + 1), got {len(array)}"
        )
    if not np.isfinite(array).all():
        raise InputError(f"{what}: {path_id}: control points must be finite numbers")
    return [[float(x), float(z)] for x, z in array]


# -- from a laid-out Scene -------------------------------------------------------------


def scene_layout(scene) -> tuple[dict[str, Pose], dict[str, list[list[float]]]]:
    """The poses of a Scene's objects and junctions and its paths' points (groups left out)."""
    poses = {
        o.id: Pose(float(o.position[0]), float(o.position[1]), float(o.position[2]), float(o.yaw))
        for o in scene.objects
        if o.kind != "group"
    }
    paths = {p.id: [[float(x), float(z)] for x, z in p.points] for p in scene.paths}
    return poses, paths


@dataclass
class ScenePins:
    """What ``pins_from_scene`` pins: poses, path points, and the ids it added on its own."""

    poses: dict[str, Pose]
    paths: dict[str, list[list[float]]]
    added: list[str]  # pinned because a named id needs them (members, supports, junctions, roads)


def pins_from_scene(
    scene, problem: Problem, ids: Iterable[str], *, what: str = "--pin"
) -> ScenePins:
    """Pin these ids of a laid-out Scene at their current poses (``problem`` is its graph's).

    An object or junction pins itself, a path its control points and the junction it
    starts at (a branch also the road it starts on, and so on), a group every object in it; any object pinned brings the objects beneath
    it (they must stay for it to stay). Unknown ids are an ``InputError``.
    """
    poses, points = scene_layout(scene)
    box_index = {box_id: box for box, box_id in enumerate(problem.ids)}
    path_index = {path_id: path for path, path_id in enumerate(problem.path_ids)}
    group_index = {group_id: g for g, group_id in enumerate(problem.group_ids)}
    named: list[str] = []
    boxes: list[int] = []
    paths: list[int] = []
    for entry_id in ids:
        if entry_id in named:
            continue
        named.append(entry_id)
        if entry_id in box_index:
            boxes.append(box_index[entry_id])
        elif entry_id in path_index:
            path = path_index[entry_id]
            while path >= 0:  # a branch brings the road it starts on, and so on
                paths.append(path)
                if problem.path_start[path] >= 0:
                    boxes.append(problem.path_start[path])
                path = problem.path_parent[path]
        elif entry_id in group_index:
            boxes.extend(problem.group_members[group_index[entry_id]])
        else:
            known = list(box_index) + list(path_index) + list(group_index)
            close = get_close_matches(entry_id, known, n=1)
            hint = f"; did you mean {close[0]!r}?" if close else ""
            raise InputError(
                f"{what}: unknown id {entry_id!r} (not an object, group, junction or path of the scene){hint}"
            )
    for box in list(boxes):
        boxes.extend(problem.beneath(box))
    chosen_boxes = sorted(set(boxes))
    chosen_paths = sorted(set(paths))
    missing = [problem.ids[b] for b in chosen_boxes if problem.ids[b] not in poses]
    missing += [problem.path_ids[p] for p in chosen_paths if problem.path_ids[p] not in points]
    if missing:
        raise InputError(f"{what}: the scene has no pose for {', '.join(missing)}")
    return ScenePins(
        poses={problem.ids[b]: poses[problem.ids[b]] for b in chosen_boxes},
        paths={problem.path_ids[p]: points[problem.path_ids[p]] for p in chosen_paths},
        added=[problem.ids[b] for b in chosen_boxes if problem.ids[b] not in named]
        + [problem.path_ids[p] for p in chosen_paths if problem.path_ids[p] not in named],
    )
